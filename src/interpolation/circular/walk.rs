//! A cursor on an [`Arc`]: the step count, the octant it is in and the position there.

use super::{Arc, Octant};

/// A position on an [`Arc`]: the step count, the octant of the last step, and both axes'
/// positions. It keeps the octant it is in, so a jump of any number of steps
/// ([`Self::advance_to`]) walks over the octants it crosses (at most nine, a whole circle) and
/// evaluates the circle once: O(1) however many pulses lie in between.
///
/// As an [`Iterator`], it yields both axes' positions after each of the remaining steps, and
/// ends on [`Arc::end`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct ArcWalk {
    arc: Arc,
    /// Steps taken, 0 … [`Arc::steps`].
    step: u64,
    /// The traversal piece (see `Arc::octant_of`) holding the last step (the first step at 0).
    piece: u32,
    /// The arc step at which that piece begins (≤ 0 for the start's piece).
    piece_start: i64,
    /// Both axes, pulses relative to the start.
    position: [i32; 2],
}

impl ArcWalk {
    pub(super) fn new(arc: Arc) -> Self {
        Self {
            arc,
            step: 0,
            piece: arc.first_piece,
            piece_start: -i64::from(arc.first_offset),
            position: [0, 0],
        }
    }

    /// The arc being followed.
    pub const fn arc(&self) -> &Arc {
        &self.arc
    }

    /// Steps taken so far, 0 … [`Arc::steps`].
    pub const fn step(&self) -> u64 {
        self.step
    }

    /// Whether the walk has reached the end of the arc.
    pub const fn is_finished(&self) -> bool {
        self.step == self.arc.steps
    }

    /// Both axes' positions now, pulses relative to the start.
    pub const fn current_position(&self) -> [i32; 2] {
        self.position
    }

    /// The octant of the last step (at the start, of the first step): the one the chip's status
    /// register would show.
    pub const fn octant(&self) -> Octant {
        self.arc.octant_of(self.piece)
    }

    /// Moves to `step` (forward or back; past the end means the end) and returns both axes'
    /// positions there: what a cycle that takes many steps calls.
    pub fn advance_to(&mut self, step: u64) -> [i32; 2] {
        let arc = &self.arc;
        let step = step.min(arc.steps);
        self.step = step;
        // i64: an arc has at most 4·(D + m) < 2³⁵ steps. The piece must hold step − 1, the
        // position the last step left (step 0: the start itself).
        let (target, last) = (step as i64, step.max(1) as i64 - 1);
        while last >= self.piece_start + i64::from(arc.piece_steps(self.piece)) {
            self.piece_start += i64::from(arc.piece_steps(self.piece));
            self.piece += 1;
        }
        while last < self.piece_start {
            // Never before the start's piece, which begins at or before step 0.
            self.piece -= 1;
            self.piece_start -= i64::from(arc.piece_steps(self.piece));
        }
        // 0 … the piece's steps (the end of a piece is the next one's start).
        let offset = (target - self.piece_start) as u32;
        let point = arc.point(self.piece, offset);
        // Within i32: the reach of the circle was checked when the arc was built.
        self.position = [
            point[0].wrapping_add(arc.centre[0]),
            point[1].wrapping_add(arc.centre[1]),
        ];
        self.position
    }
}

impl Iterator for ArcWalk {
    type Item = [i32; 2];

    /// One step: O(1), as [`ArcWalk::advance_to`].
    fn next(&mut self) -> Option<[i32; 2]> {
        if self.is_finished() {
            return None;
        }
        Some(self.advance_to(self.step + 1))
    }

    fn size_hint(&self) -> (usize, Option<usize>) {
        let left = usize::try_from(self.arc.steps - self.step).ok();
        (left.unwrap_or(usize::MAX), left)
    }
}

impl core::iter::FusedIterator for ArcWalk {}
