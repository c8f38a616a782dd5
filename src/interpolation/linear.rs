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
//! per axis, with no division and no loop: two 32×32→64 multiplications per axis against
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
/// is k less the top word of `2k·slope + offset·2³²`, a 96-bit unsigned value, in 32-bit pieces.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
struct Axis {
    /// Low word of the biased slope Fᵢ + 2⁶³, Fᵢ = ⌊Δᵢ·2⁶³/L⌋ (an i64; Δᵢ = L saturates to
    /// 2⁶³ − 1).
    slope_low: u32,
    /// High word of the biased slope (the signed high word of Fᵢ plus 2³¹).
    slope_high: u32,
    /// The offset's middle word Gᵢ = ⌈hᵢ·2³²/L⌉ + 1 (with hᵢ below; ≤ 2³¹ + 1), weighted 2³².
    offset: u32,
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
    /// multiplications, no division, no branch — what a cycle that takes many steps calls.
    ///
    /// # Why it is the rule, exactly
    /// For Δᵢ < 0, −⌊(k·|Δᵢ| + h)/L⌋ = ⌊(k·Δᵢ + L − 1 − h)/L⌋ (write k·|Δᵢ| + h = q·L + r with
    /// 0 ≤ r < L: the right side is ⌊(−q·L + L − 1 − r)/L⌋ = −q). So with hᵢ = h = ⌊L/2⌋ for
    /// Δᵢ ≥ 0 and L − 1 − h otherwise, posᵢ(k) = ⌊Xᵢ⌋, Xᵢ = (k·Δᵢ + hᵢ)/L, for both signs.
    ///
    /// Per line, Fᵢ = ⌊Δᵢ·2⁶³/L⌋ (an i64; for Δᵢ = L, 2⁶³ − 1) and Gᵢ = ⌈hᵢ·2³²/L⌉ + 1 (hᵢ ≤ L/2,
    /// so Gᵢ ≤ 2³¹ + 1). Then Yᵢ = (2k·Fᵢ + Gᵢ·2³²)/2⁶⁴ exceeds Xᵢ by δ with
    /// 2⁻³² − 2k/2⁶⁴ < δ < 2⁻³¹: the slope's rounding loses less than 2k/2⁶⁴ < 2⁻³³
    /// (k ≤ L < 2³⁰), the offset adds at least 2⁻³² and less than 2·2⁻³². So 0 < δ < 2⁻³⁰ < 1/L
    /// (L < 2³⁰), and since Xᵢ's fraction is a multiple of 1/L, at most 1 − 1/L, ⌊Yᵢ⌋ = ⌊Xᵢ⌋.
    ///
    /// ⌊Yᵢ⌋ in unsigned 32-bit pieces: with the slope biased to F′ = Fᵢ + 2⁶³ ∈ [0, 2⁶⁴),
    /// 2k·F′ = 2k·Fᵢ + k·2⁶⁴, so ⌊Yᵢ⌋ = ⌊(2k·F′ + Gᵢ·2³²)/2⁶⁴⌋ − k. That quotient is the high
    /// word of 2k·⌊F′/2³²⌋ + Gᵢ + c, c the high word of 2k·(F′ mod 2³²) (the low words cannot
    /// carry into it; the sum is below 2⁶⁴, as for any u32·u32 + u32 + u32). On a Cortex-M4
    /// that is one `umull`, one `umaal` and a subtraction, modulo 2³² (the result is an i32).
    ///
    /// [`Self::position_by_division`] is the rule as written; the tests hold the two equal.
    #[inline]
    pub fn position_at(&self, step: u32) -> [i32; N] {
        // ≤ L < 2³⁰, so 2k < 2³¹.
        let step = step.min(self.steps);
        self.at_clamped(step)
    }

    /// [`Self::position_at`] for `step` ≤ L (the caller's contract; a larger step would not
    /// stay on the finish point).
    #[inline(always)]
    fn at_clamped(&self, step: u32) -> [i32; N] {
        let twice = u64::from(step << 1);
        self.axes.map(|axis| {
            // c: the high word of 2k·(F′ mod 2³²).
            let carry = (twice * u64::from(axis.slope_low)) >> 32;
            // ≤ (2³² − 1)² + 2·(2³² − 1) < 2⁶⁴: no overflow (one `umaal`).
            let top = twice * u64::from(axis.slope_high) + u64::from(axis.offset) + carry;
            // Modulo 2³²: the biased quotient less k is the position (an i32).
            ((top >> 32) as u32).wrapping_sub(step) as i32
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
    /// [`Line::position_at`]); for an empty line, a zero slope and offset (every position is
    /// then 0). Computed once per line, in i128 (never on the per-cycle path).
    fn new(delta: i32, steps: u32) -> Self {
        let (slope, offset) = if steps == 0 {
            (0, 0)
        } else {
            let length = i128::from(steps);
            // ⌊Δ·2⁶³/L⌋ ∈ [−2⁶³, 2⁶³]; the one value past i64 (Δ = L) saturates to 2⁶³ − 1.
            let slope = (i128::from(delta) << 63).div_euclid(length);
            let slope = i64::try_from(slope).unwrap_or(i64::MAX);
            let half = i128::from(steps / 2);
            let offset_numerator = if delta < 0 { length - 1 - half } else { half };
            // ⌈hᵢ·2³²/L⌉ + 1: hᵢ ≤ L/2, so at most 2³¹ + 1, a u32.
            let offset = ((offset_numerator << 32) + length - 1) / length + 1;
            (slope, offset as u32)
        };
        // F′ = F + 2⁶³ ∈ [0, 2⁶⁴): the two's-complement bits of F with the top bit flipped.
        let biased = (slope as u64) ^ (1 << 63);
        Self {
            slope_low: biased as u32,
            slope_high: (biased >> 32) as u32,
            offset,
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
        self.line.at_clamped(self.step)
    }

    /// Moves to the step a driving position's integer part `whole` names (a floor, any i32):
    /// below 0 means the start, past the end the end. One unsigned comparison on the way every
    /// cycle within the line takes.
    #[inline]
    pub(super) fn advance_to_whole(&mut self, whole: i32) -> [i32; N] {
        // Within 0 … L the bits are the step; a negative `whole` is ≥ 2³¹ as a u32, past L.
        let step = if whole as u32 <= self.line.steps {
            whole as u32
        } else {
            clamp_outside(whole, self.line.steps)
        };
        self.step = step;
        self.line.at_clamped(step)
    }
}

/// A driving position's integer part `whole` outside 0 … `steps`, held at the nearer end.
#[cold]
fn clamp_outside(whole: i32, steps: u32) -> u32 {
    if whole < 0 {
        0
    } else {
        steps
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

#[cfg(test)]
mod tests {
    use super::Line;

    /// A driving position's integer part outside 0 … L holds the axes at the nearer end, and one
    /// inside is the step itself (the rule by division is the yardstick).
    #[test]
    fn whole_positions_outside_the_line_hold_the_nearer_end() {
        let line = Line::from_pulses([-20_000, 30_000, -50_000]).unwrap();
        let mut walk = line.walk();
        for whole in [i32::MIN, -50_001, -1] {
            assert_eq!(walk.advance_to_whole(whole), [0, 0, 0], "{whole}");
            assert_eq!(walk.step(), 0);
        }
        for whole in [50_000, 50_001, i32::MAX] {
            assert_eq!(
                walk.advance_to_whole(whole),
                [-20_000, 30_000, -50_000],
                "{whole}"
            );
            assert_eq!(walk.step(), 50_000);
        }
        for whole in [0, 1, 25_000, 49_999] {
            assert_eq!(
                walk.advance_to_whole(whole),
                line.position_by_division(whole as u32)
            );
            assert_eq!(walk.step(), whole as u32);
        }
    }
}
