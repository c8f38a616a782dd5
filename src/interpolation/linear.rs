//! Linear interpolation of 2–4 axes (SPEC §12.3), as the MCX514 does it: the long axis pulses on
//! every step, every other axis by an integer rule, each within half a pulse of the ideal line.
//!
//! # The rule
//! With the finish point Δ (relative, pulses) and L = max|Δᵢ| steps, axis i after k steps is at
//!
//! ```text
//! posᵢ(k) = sign(Δᵢ) · ⌊(k·|Δᵢ| + ⌊L/2⌋) / L⌋
//! ```
//!
//! that is, |k·Δᵢ/L| rounded to nearest (ties away from the start for even L, the other way for
//! odd L, where there are no ties), with the sign applied afterwards. Why it keeps the bound: with
//! q = ⌊(k·a + h)/L⌋, a = |Δᵢ| and h = ⌊L/2⌋ ≤ L/2, q·L ≤ k·a + L/2, and
//! q·L > k·a + h − L ≥ k·a − (L + 1)/2, so 2·q·L ≥ 2·k·a − L (both sides integers):
//! |2·q·L − 2·k·a| ≤ L, i.e. |q − k·a/L| ≤ ½. Since a ≤ L the quotient grows by at most one per
//! step (one pulse per axis per step, never backwards); the long axis (a = L) moves on every
//! step; at k = L, q = a + ⌊h/L⌋ = a: the finish point, exactly.
//!
//! # Evaluated without dividing
//! A cycle may take any number of steps, so the rule is evaluated at the step reached, in O(1)
//! per axis, with no division and no loop: two 32×32→64 multiply-accumulates per axis against
//! constants of the line (see [`Line::position_at`] for why that is the rule, exactly).
//! [`Line::position_by_division`] evaluates the rule as written, the yardstick the tests hold
//! the fast form to, bit for bit.
//!
//! ```
//! use profilegen::interpolation::Line;
//! // Reference 003's line: finish (−20000, 30000, −50000); Z is the long axis, 50,000 steps.
//! let line = Line::from_pulses([-20_000, 30_000, -50_000])?;
//! assert_eq!(line.steps(), 50_000);
//! assert_eq!(line.position_at(25_000), [-10_000, 15_000, -25_000]);
//! assert_eq!(line.position_at(50_000), [-20_000, 30_000, -50_000]);
//!
//! // Step by step: at most one pulse per axis per step.
//! let mut walk = line.walk();
//! assert_eq!(walk.next(), Some([0, 1, -1])); // 0.4 → 0, 0.6 → 1, 1
//! // Or many steps at once, in O(1) per axis: 19,999.6 → 20,000 and 29,999.4 → 29,999.
//! assert_eq!(walk.advance_to(49_999), [-20_000, 29_999, -49_999]);
//! assert_eq!(walk.next(), Some([-20_000, 30_000, -50_000]));
//! assert_eq!(walk.next(), None);
//! # Ok::<(), profilegen::Error>(())
//! ```

use crate::format::mcx514::FinishPoint;
use crate::Error;

/// One axis's constants for the division-free evaluation (see [`Line::position_at`]): posᵢ(k)
/// is the high word of `2k·slope + offset`, a signed 96-bit value, in 32-bit pieces.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
struct Axis {
    /// Low word of the slope Fᵢ = ⌊Δᵢ·2⁶³/L⌋ (an i64; Δᵢ = L saturates to 2⁶³ − 1).
    slope_low: u32,
    /// High word of the slope, signed.
    slope_high: i32,
    /// The offset Gᵢ = ⌈hᵢ·2⁶⁴/L⌉ + 2³² (a u64 < 2⁶⁴, with hᵢ below), whole.
    offset: u64,
}

/// A straight line from the origin to a finish point on N axes (2 ≤ N ≤ 4), in pulses: the
/// geometry of an MCX514 linear interpolation (SPEC §12.3). See the [module docs](self) for the
/// integer rule and why it stays within ±½ pulse of the ideal line.
///
/// `N` outside 2 … 4 does not compile (a constant assertion, checked when a line is built):
///
/// ```compile_fail
/// let five_axes = profilegen::interpolation::Line::from_pulses([1, 2, 3, 4, 5]);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Line<const N: usize> {
    /// Per axis, the constants of [`Self::position_at`]; first, as the per-cycle path reads them.
    axes: [Axis; N],
    /// L = max |Δᵢ|: the steps of the whole line (the long axis's pulses).
    steps: u32,
    /// The finish point Δ, pulses, relative to the start.
    finish: [i32; N],
}

impl<const N: usize> Line<N> {
    /// The MCX514 interpolates 2, 3 or 4 axes; anything else fails to compile where a line is built.
    const AXES: () = assert!(N >= 2 && N <= 4, "a linear interpolation has 2 to 4 axes");

    /// The line to `finish`, one checked register per axis.
    pub fn new(finish: [FinishPoint; N]) -> Self {
        #[allow(clippy::let_unit_value)] // evaluating the constant is the compile-time check
        let () = Self::AXES;
        let finish = finish.map(FinishPoint::to_bits);
        let steps = finish
            .iter()
            .map(|delta| delta.unsigned_abs())
            .max()
            .unwrap_or(0);
        Self {
            axes: finish.map(|delta| Axis::new(delta, steps)),
            steps,
            finish,
        }
    }

    /// The line to a finish point given in pulses per axis.
    ///
    /// # Errors
    /// [`Error::OutOfRange`] (parameter `finish point`) for a coordinate outside
    /// ±1,073,741,823 pulses.
    pub fn from_pulses(finish: [i32; N]) -> Result<Self, Error> {
        let mut checked = [FinishPoint::MIN; N];
        for (register, pulses) in checked.iter_mut().zip(finish) {
            *register = FinishPoint::from_bits(pulses)?;
        }
        Ok(Self::new(checked))
    }

    /// The finish point, pulses per axis, relative to the start.
    pub const fn finish(&self) -> [i32; N] {
        self.finish
    }

    /// The number of steps of the whole line: L = max|Δᵢ|, the long axis's pulses (0 for a finish
    /// point at the start). The manual deceleration point is counted in these.
    pub const fn steps(&self) -> u32 {
        self.steps
    }

    /// Every axis's position after `step` steps, in pulses relative to the start; steps past the
    /// end ([`Self::steps`]) stay on the finish point. O(1): per axis two 32×32→64
    /// multiply-accumulates, no division, no branch — what a cycle that takes many steps calls.
    ///
    /// # Why it is the rule, exactly
    /// For Δᵢ < 0, −⌊(k·|Δᵢ| + h)/L⌋ = ⌊(k·Δᵢ + L − 1 − h)/L⌋ (write k·|Δᵢ| + h = q·L + r with
    /// 0 ≤ r < L: the right side is ⌊(−q·L + L − 1 − r)/L⌋ = −q). So with hᵢ = h = ⌊L/2⌋ for
    /// Δᵢ ≥ 0 and L − 1 − h otherwise, posᵢ(k) = ⌊Xᵢ⌋, Xᵢ = (k·Δᵢ + hᵢ)/L, for both signs.
    ///
    /// Per line, Fᵢ = ⌊Δᵢ·2⁶³/L⌋ (an i64; for Δᵢ = L, 2⁶³ − 1) and Gᵢ = ⌈hᵢ·2⁶⁴/L⌉ + 2³² (a
    /// u64: hᵢ ≤ L/2). Then Yᵢ = (2k·Fᵢ + Gᵢ)/2⁶⁴ exceeds Xᵢ by δ with
    /// 2⁻³² − 2k/2⁶⁴ < δ < 2⁻³² + 2⁻⁶⁴: the slope's rounding loses less than 2k/2⁶⁴ < 2⁻³³
    /// (k ≤ L < 2³⁰), the offset adds 2⁻³² and less than 2⁻⁶⁴ more. So 0 < δ < 1/L (L < 2³⁰),
    /// and since Xᵢ's fraction is a multiple of 1/L, at most 1 − 1/L, ⌊Yᵢ⌋ = ⌊Xᵢ⌋.
    ///
    /// ⌊Yᵢ⌋ in 32-bit pieces (2k < 2³¹): P = Gᵢ + 2k·(Fᵢ mod 2³²), unsigned, below 2⁶⁴
    /// (Gᵢ ≤ 2⁶³ + 2³² + 1 and the product < 2⁶³ − 2³³); then ⌊Yᵢ⌋ is the high word of the
    /// signed ⌊P/2³²⌋ + 2k·⌊Fᵢ/2³²⌋ (the low word of P cannot carry into it). On a Cortex-M4
    /// that is one `umlal` and one `smlal`.
    ///
    /// [`Self::position_by_division`] is the rule as written; the tests hold the two equal.
    #[inline]
    pub fn position_at(&self, step: u32) -> [i32; N] {
        // ≤ L < 2³⁰, so 2k < 2³¹ fits both u32 and i32.
        let twice = step.min(self.steps) << 1;
        self.axes.map(|axis| {
            // u64, no overflow (see above): the offset plus the slope's low word times 2k.
            let partial = axis.offset + u64::from(twice) * u64::from(axis.slope_low);
            // i64: ⌊P/2³²⌋ < 2³² plus |2k·⌊F/2³²⌋| < 2⁶², exact. Its high word is the position.
            let whole =
                (partial >> 32) as i64 + i64::from(twice as i32) * i64::from(axis.slope_high);
            (whole >> 32) as i32
        })
    }

    /// Every axis's position after `step` steps by the rule's own division,
    /// sign(Δᵢ)·⌊(k·|Δᵢ| + ⌊L/2⌋)/L⌋ (one u64 division per axis): the yardstick that
    /// [`Self::position_at`] is tested against, bit for bit.
    pub fn position_by_division(&self, step: u32) -> [i32; N] {
        let steps = self.steps;
        let step = step.min(steps);
        self.finish.map(|delta| {
            if steps == 0 {
                return 0;
            }
            // u64: k ≤ 2³⁰ − 1 and |Δᵢ| ≤ 2³⁰ − 1, so k·|Δᵢ| + ⌊L/2⌋ < 2⁶¹; the quotient is
            // ≤ |Δᵢ| < 2³⁰, so the cast is exact.
            let numerator =
                u64::from(step) * u64::from(delta.unsigned_abs()) + u64::from(steps / 2);
            let magnitude = (numerator / u64::from(steps)) as i32;
            if delta < 0 {
                -magnitude
            } else {
                magnitude
            }
        })
    }

    /// A cursor at step 0 that follows the line one step at a time (as an iterator) or many at
    /// once ([`Walk::advance_to`]).
    pub fn walk(&self) -> Walk<N> {
        Walk {
            line: *self,
            step: 0,
        }
    }
}

impl Axis {
    /// The constants of an axis with finish `delta` on a line of `steps` (see
    /// [`Line::position_at`]); all zero for an empty line (every position is then 0). Computed
    /// once per line, in i128 (never on the per-cycle path).
    fn new(delta: i32, steps: u32) -> Self {
        if steps == 0 {
            return Self {
                slope_low: 0,
                slope_high: 0,
                offset: 0,
            };
        }
        let length = i128::from(steps);
        // ⌊Δ·2⁶³/L⌋ ∈ [−2⁶³, 2⁶³]; the one value past i64 (Δ = L) saturates to 2⁶³ − 1.
        let slope = (i128::from(delta) << 63).div_euclid(length);
        let slope = i64::try_from(slope).unwrap_or(i64::MAX);
        let half = i128::from(steps / 2);
        let offset_numerator = if delta < 0 { length - 1 - half } else { half };
        // ⌈hᵢ·2⁶⁴/L⌉ + 2³²: hᵢ ≤ L/2, so at most 2⁶³ + 2³² + 1, a u64.
        let offset = ((offset_numerator << 64) + length - 1) / length + (1 << 32);
        Self {
            // The two's-complement pieces of the slope: low word unsigned, high word signed.
            slope_low: slope as u32,
            slope_high: (slope >> 32) as i32,
            offset: offset as u64,
        }
    }
}

/// A cursor on a [`Line`]: the step count, and every axis's position there computed on demand
/// ([`Line::position_at`]), so a jump of any length costs the same.
///
/// As an [`Iterator`], it yields every axis's position after each of the remaining steps, and
/// ends on the finish point.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Walk<const N: usize> {
    line: Line<N>,
    /// Steps taken, 0 … L.
    step: u32,
}

impl<const N: usize> Walk<N> {
    /// The line being followed.
    pub const fn line(&self) -> &Line<N> {
        &self.line
    }

    /// Steps taken so far, 0 … [`Line::steps`].
    pub const fn step(&self) -> u32 {
        self.step
    }

    /// Whether the walk has reached the finish point.
    pub const fn is_finished(&self) -> bool {
        self.step == self.line.steps
    }

    /// Every axis's position now, pulses relative to the start (named apart from
    /// [`Iterator::position`], which a `Walk` also has).
    pub fn current_position(&self) -> [i32; N] {
        self.line.position_at(self.step)
    }

    /// Moves to `step` (forward or back; past the end means the end) and returns every axis's
    /// position there: O(1) per axis however many steps lie in between, no division
    /// ([`Line::position_at`]).
    #[inline]
    pub fn advance_to(&mut self, step: u32) -> [i32; N] {
        self.step = step.min(self.line.steps);
        self.line.position_at(self.step)
    }
}

impl<const N: usize> Iterator for Walk<N> {
    type Item = [i32; N];

    /// One step: at most one pulse per axis (SPEC §12.3).
    fn next(&mut self) -> Option<[i32; N]> {
        if self.is_finished() {
            return None;
        }
        Some(self.advance_to(self.step + 1))
    }

    fn size_hint(&self) -> (usize, Option<usize>) {
        let left = (self.line.steps - self.step) as usize;
        (left, Some(left))
    }
}

impl<const N: usize> ExactSizeIterator for Walk<N> {}

impl<const N: usize> core::iter::FusedIterator for Walk<N> {}
