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
    /// The last step a driving position can name: min(L, 2³¹ − 1) (an I32F32's integer part is
    /// an i32).
    last_whole: u32,
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
            // At most 2³¹ − 1: the cast is exact.
            last_whole: arc.steps.min(i32::MAX as u64) as u32,
            position: [0, 0],
        };
        walk.enter(arc.first_piece, 0);
        walk
    }

    /// Makes `piece`, beginning at `start`, the present piece. Only the piece and its bounds are
    /// kept (its frame is read from the arc's table where it is used): entering the next piece,
    /// once an octant, is then a few instructions, and the worst cycle is one that does.
    #[inline(always)]
    fn enter(&mut self, piece: u32, start: u64) {
        self.piece = piece;
        self.piece_start = start;
        self.piece_end = start + u64::from(self.arc.piece_steps(piece));
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
        if self.piece % 2 == 0 {
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
        self.jump(step.min(self.arc.steps))
    }

    /// Moves to the step a driving position's integer part `whole` names (a floor, any i32):
    /// below 0 means the start, past the end the end. As [`Self::advance_to`], with the clamp
    /// one 32-bit comparison on the way every cycle within the arc takes.
    #[inline(always)]
    pub fn advance_to_whole(&mut self, whole: i32) -> [i32; 2] {
        // Within 0 … min(L, 2³¹ − 1) the bits are the step; a negative `whole` is ≥ 2³¹ as a
        // u32, past it. Past it otherwise only when L < 2³¹ − 1: the end.
        let step = if whole as u32 <= self.last_whole {
            whole as u32
        } else {
            clamp_outside(whole, self.last_whole)
        };
        self.jump(u64::from(step))
    }

    /// [`Self::advance_to`] for `step` ≤ L (the caller's contract).
    #[inline(always)]
    fn jump(&mut self, step: u64) -> [i32; 2] {
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
        let (long, short) = self.arc.long_and_short(self.piece % 2 == 0, offset);
        let [long_x, short_x, long_y, short_y] = self.arc.frames[(self.piece % 8) as usize];
        // Both below 2³¹ (the reach was checked when the arc was built): the casts are exact.
        let (long, short) = (long as i32, short as i32);
        // Within i32: the reach of the circle was checked when the arc was built (one of each
        // pair of coefficients is 0, the other ±1).
        self.position = [
            self.arc.centre[0]
                .wrapping_add(long_x.wrapping_mul(long))
                .wrapping_add(short_x.wrapping_mul(short)),
            self.arc.centre[1]
                .wrapping_add(long_y.wrapping_mul(long))
                .wrapping_add(short_y.wrapping_mul(short)),
        ];
        self.position
    }
}

/// A driving position's integer part `whole` outside 0 … `last`, held at the nearer end.
#[cold]
fn clamp_outside(whole: i32, last: u32) -> u32 {
    if whole < 0 {
        0
    } else {
        last
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
