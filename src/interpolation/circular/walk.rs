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
    /// Where that piece begins and ends, counted in steps from the start of the start's piece
    /// (the arc's step plus `Arc::first_offset`, so never negative).
    piece_start: u64,
    piece_end: u64,
    /// The piece's frame: outbound, and the octant's table row (see `FRAMES`).
    outbound: bool,
    long_is_x: bool,
    signs: [i32; 2],
    /// Both axes, pulses relative to the start.
    position: [i32; 2],
}

impl ArcWalk {
    pub(super) fn new(arc: Arc) -> Self {
        let mut walk = Self {
            arc,
            step: 0,
            piece: arc.first_piece,
            piece_start: 0,
            piece_end: 0,
            outbound: true,
            long_is_x: true,
            signs: [1, 1],
            position: [0, 0],
        };
        walk.enter(arc.first_piece, 0);
        walk
    }

    /// Makes `piece`, beginning at `start`, the present piece.
    fn enter(&mut self, piece: u32, start: u64) {
        let (long_is_x, signs) = self.arc.frames[(piece % 8) as usize];
        self.piece = piece;
        self.piece_start = start;
        self.piece_end = start + u64::from(self.arc.piece_steps(piece));
        self.outbound = piece % 2 == 0;
        self.long_is_x = long_is_x;
        self.signs = signs;
    }

    /// Moves to the piece holding `last` (a position counted as `piece_start`): at most the
    /// octants of one circle either way.
    #[cold]
    fn find_piece(&mut self, last: u64) {
        let (mut piece, mut start) = (self.piece, self.piece_start);
        while last >= start + u64::from(self.arc.piece_steps(piece)) {
            start += u64::from(self.arc.piece_steps(piece));
            piece += 1;
        }
        while last < start {
            // Never before the start's piece, which begins at 0.
            piece -= 1;
            start -= u64::from(self.arc.piece_steps(piece));
        }
        self.enter(piece, start);
    }

    /// The steps of the piece after the present one.
    #[inline(always)]
    fn next_steps(&self) -> u32 {
        if self.outbound {
            self.arc.inbound_steps
        } else {
            self.arc.outbound_steps
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
    // Always inlined: out of line, the two axes come back through memory and the call costs
    // about ten instructions a cycle.
    #[inline(always)]
    pub fn advance_to(&mut self, step: u64) -> [i32; 2] {
        let step = step.min(self.arc.steps);
        self.step = step;
        // Counted from the start's piece. The piece must hold the position the last step left,
        // at − 1: piece_start < at ≤ piece_end (step 0 stays in the start's piece).
        let at = step + u64::from(self.arc.first_offset);
        if at > self.piece_end {
            if at <= self.piece_end + u64::from(self.next_steps()) {
                // The common crossing: into the next piece.
                self.enter(self.piece + 1, self.piece_end);
            } else {
                self.find_piece(at - 1);
            }
        } else if at <= self.piece_start && (step != 0 || self.piece != self.arc.first_piece) {
            // Back (step 0: to the start's piece, which holds the start itself).
            self.find_piece(at - u64::from(step != 0));
        }
        // 0 … the piece's steps (the end of a piece is the next one's start): below 2³¹.
        let offset = (at - self.piece_start) as u32;
        let (long, short) = self.arc.long_and_short(self.outbound, offset);
        // Both below 2³¹ (the reach was checked when the arc was built): the casts are exact.
        let (long, short) = (long as i32, short as i32);
        let (x, y) = if self.long_is_x {
            (long, short)
        } else {
            (short, long)
        };
        // Within i32: the reach of the circle was checked when the arc was built.
        self.position = [
            (self.signs[0] * x).wrapping_add(self.arc.centre[0]),
            (self.signs[1] * y).wrapping_add(self.arc.centre[1]),
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
