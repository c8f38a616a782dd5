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
//! Two ways to evaluate it, which agree exactly: [`Line::position_at`] and [`Walk::advance_to`]
//! divide once per axis (O(1) however far the step), and [`Walk`]'s iterator adds |Δᵢ| to a
//! remainder per step, Bresenham's way, with no division.
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
    /// The finish point Δ, pulses, relative to the start.
    finish: [i32; N],
    /// |Δᵢ|, pulses; at most 2³⁰ − 1 (the finish point's range).
    magnitude: [u32; N],
    /// L = max |Δᵢ|: the steps of the whole line (the long axis's pulses).
    steps: u32,
    /// ⌊L/2⌋: the offset that turns the floor of the division into round-to-nearest.
    half: u32,
}

impl<const N: usize> Line<N> {
    /// The MCX514 interpolates 2, 3 or 4 axes; anything else fails to compile where a line is built.
    const AXES: () = assert!(N >= 2 && N <= 4, "a linear interpolation has 2 to 4 axes");

    /// The line to `finish`, one checked register per axis.
    pub fn new(finish: [FinishPoint; N]) -> Self {
        #[allow(clippy::let_unit_value)] // evaluating the constant is the compile-time check
        let () = Self::AXES;
        let finish = finish.map(FinishPoint::to_bits);
        let magnitude = finish.map(i32::unsigned_abs);
        let steps = magnitude.iter().copied().max().unwrap_or(0);
        Self {
            finish,
            magnitude,
            steps,
            half: steps / 2,
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

    /// Every axis's position after `step` steps, in pulses relative to the start: O(1) per axis,
    /// one division. Steps past the end ([`Self::steps`]) stay on the finish point.
    pub fn position_at(&self, step: u32) -> [i32; N] {
        let mut walk = self.walk();
        walk.advance_to(step)
    }

    /// A cursor at step 0 that follows the line one step at a time (as an iterator) or many at
    /// once ([`Walk::advance_to`]).
    pub fn walk(&self) -> Walk<N> {
        Walk {
            line: *self,
            step: 0,
            quotient: [0; N],
            // At k = 0 the numerator is ⌊L/2⌋ < L (or 0 when L = 0): quotient 0, remainder h.
            remainder: [self.half; N],
        }
    }
}

/// A position on a [`Line`]: the step count and, per axis, the quotient and remainder of
/// `k·|Δᵢ| + ⌊L/2⌋` divided by L, so the next step needs one addition and one comparison per axis.
///
/// As an [`Iterator`], it yields every axis's position after each of the remaining steps, and
/// ends on the finish point.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Walk<const N: usize> {
    line: Line<N>,
    /// Steps taken, 0 … L.
    step: u32,
    /// |posᵢ| = ⌊(k·|Δᵢ| + ⌊L/2⌋) / L⌋.
    quotient: [u32; N],
    /// (k·|Δᵢ| + ⌊L/2⌋) mod L, always < L (or 0 when L = 0).
    remainder: [u32; N],
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
        let mut position = [0; N];
        for ((out, &quotient), &finish) in position
            .iter_mut()
            .zip(&self.quotient)
            .zip(&self.line.finish)
        {
            // quotient ≤ |Δᵢ| ≤ 2³⁰ − 1: the cast to i32 is exact.
            let magnitude = quotient as i32;
            *out = if finish < 0 { -magnitude } else { magnitude };
        }
        position
    }

    /// Moves to `step` (forward or back; past the end means the end) and returns every axis's
    /// position there: one division per axis, however many steps lie in between — what a cycle
    /// that takes many steps calls.
    pub fn advance_to(&mut self, step: u32) -> [i32; N] {
        let line = &self.line;
        let step = step.min(line.steps);
        self.step = step;
        if line.steps == 0 {
            // A finish point at the start: nothing moves, and there is nothing to divide by.
            return self.current_position();
        }
        let steps = u64::from(line.steps);
        for ((quotient, remainder), &magnitude) in self
            .quotient
            .iter_mut()
            .zip(&mut self.remainder)
            .zip(&line.magnitude)
        {
            // u64: k ≤ 2³⁰ − 1 and |Δᵢ| ≤ 2³⁰ − 1, so k·|Δᵢ| + ⌊L/2⌋ < 2⁶¹. The division is the
            // floor of the rule; the quotient is ≤ |Δᵢ| and the remainder < L, both fit u32.
            let numerator = u64::from(step) * u64::from(magnitude) + u64::from(line.half);
            *quotient = (numerator / steps) as u32;
            *remainder = (numerator % steps) as u32;
        }
        self.current_position()
    }
}

impl<const N: usize> Iterator for Walk<N> {
    type Item = [i32; N];

    /// One step: each axis adds |Δᵢ| to its remainder and pulses when it reaches L (at most once,
    /// since |Δᵢ| ≤ L). No division.
    fn next(&mut self) -> Option<[i32; N]> {
        if self.is_finished() {
            return None;
        }
        self.step += 1;
        let steps = self.line.steps;
        for ((quotient, remainder), &magnitude) in self
            .quotient
            .iter_mut()
            .zip(&mut self.remainder)
            .zip(&self.line.magnitude)
        {
            // u32: remainder < L ≤ 2³⁰ − 1 and |Δᵢ| ≤ 2³⁰ − 1, so the sum is < 2³¹.
            let sum = *remainder + magnitude;
            if sum >= steps {
                *remainder = sum - steps;
                *quotient += 1;
            } else {
                *remainder = sum;
            }
        }
        Some(self.current_position())
    }

    fn size_hint(&self) -> (usize, Option<usize>) {
        let left = (self.line.steps - self.step) as usize;
        (left, Some(left))
    }
}

impl<const N: usize> ExactSizeIterator for Walk<N> {}

impl<const N: usize> core::iter::FusedIterator for Walk<N> {}
