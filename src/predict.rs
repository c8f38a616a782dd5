//! Prediction (SPEC §15): the state after any number of cycles, the cycle on which the move
//! completes, and the first cycle on which the position reaches a point — without stepping.
//!
//! Every generator whose future is fixed by the commands it has lays that future out as a few
//! *segments* (at most [`MAX_SEGMENTS`]): runs of cycles on which the velocity after `k` of the
//! segment's steps is the polynomial
//!
//! ```text
//! v(k) = c0 + c1·k + c2·k(k+1)/2          (k = 1 … the segment's cycles)
//! ```
//!
//! — a run of constant velocity change (trapezoid, velocity contouring: `c2 = 0`) or of constant
//! jerk (S-curve: `c0`, `c1` the velocity and acceleration before the run, `c2` the jerk). The
//! position is the sum of the velocities, `c0·k + c1·k(k+1)/2 + c2·k(k+1)(k+2)/6`, and the
//! acceleration the difference of two (SPEC §5), so a state is one closed form away: a binary
//! search for the segment, then the sums, in 128-bit integers. Those are exactly the sums the
//! generator's additions make, so the result is bit-identical to stepping.
//!
//! Widths: within a segment the true velocity stays below 2^48 (the registers' bound) and the
//! true displacement below 2^112 (2^64 cycles at 2^48), so every value fits an `i128`; the
//! intermediate products (a cycle count cubed can pass 2^128 where its coefficient is zero or
//! tiny) are taken modulo 2^128, which leaves the exact result exact. The position wraps at 32
//! integer bits like the chip's register: the low 64 bits of the displacement.

use fixed::types::I32F32;

use crate::bisect::last_true;
use crate::State;

/// At most this many segments in a prediction: an S-curve's runs (45, its end marker included),
/// the run under way, and one for a pending abrupt stop.
pub const MAX_SEGMENTS: usize = 48;

/// One segment: `cycles` steps whose velocities follow `v(k) = c0 + c1·k + c2·k(k+1)/2`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
struct Segment {
    /// Steps from the prediction's origin to the segment's first.
    start: u64,
    /// Its steps; `u64::MAX` for the last, which lasts for ever (at a constant velocity).
    cycles: u64,
    /// The state before its first step.
    before: State,
    /// The displacement from the origin before its first step, 2^-32 counts, not wrapped.
    displacement: i128,
    /// The displacement after its last step (±`i128::MAX` for ever in motion).
    end: i128,
    c0: i128,
    c1: i128,
    c2: i128,
}

/// `k(k+1)/2` and `k(k+1)(k+2)/6` modulo 2^128: each division is exact on the factor it divides
/// before any product can wrap.
fn sums(k: u64) -> (i128, i128) {
    let k = u128::from(k);
    let (mut x, mut y, mut z) = (k, k + 1, k + 2);
    let triangle = if x % 2 == 0 { (x / 2) * y } else { x * (y / 2) };
    // One of three consecutive numbers is a multiple of 3, one of the first two is even.
    match k % 3 {
        0 => x /= 3,
        1 => z /= 3,
        _ => y /= 3,
    }
    if x % 2 == 0 {
        x /= 2;
    } else {
        y /= 2;
    }
    let tetrahedron = x.wrapping_mul(y).wrapping_mul(z);
    (triangle as i128, tetrahedron as i128)
}

impl Segment {
    /// The velocity after `k` steps (k ≥ 0; `v(0) = c0`).
    fn velocity(&self, k: u64) -> i128 {
        let (triangle, _) = sums(k);
        self.c0
            .wrapping_add(self.c1.wrapping_mul(i128::from(k)))
            .wrapping_add(self.c2.wrapping_mul(triangle))
    }

    /// The displacement after `k` steps of the segment, from the origin.
    fn displacement_after(&self, k: u64) -> i128 {
        let (triangle, tetrahedron) = sums(k);
        self.displacement
            .wrapping_add(self.c0.wrapping_mul(i128::from(k)))
            .wrapping_add(self.c1.wrapping_mul(triangle))
            .wrapping_add(self.c2.wrapping_mul(tetrahedron))
    }

    /// The state after `k` steps of the segment (`k ≤ cycles`).
    fn state_after(&self, k: u64) -> State {
        if k == 0 {
            return self.before;
        }
        let velocity = self.velocity(k);
        // The first step's acceleration is against the velocity before the segment, which the
        // polynomial's v(0) need not be (a trapezoid's run starts where it likes).
        let previous = if k == 1 {
            i128::from(self.before.velocity.to_bits())
        } else {
            self.velocity(k - 1)
        };
        let moved = self.displacement_after(k).wrapping_sub(self.displacement);
        // The low 64 bits: the position register wraps at 32 integer bits.
        let position = self.before.position.to_bits().wrapping_add(moved as i64);
        State {
            position: I32F32::from_bits(position),
            velocity: I32F32::from_bits(velocity as i64),
            acceleration: I32F32::from_bits(velocity.wrapping_sub(previous) as i64),
        }
    }
}

/// The future of a generator, from its present state, as long as it gets no further command:
/// [`Self::state_at`] any cycle, [`Self::completion`], [`Self::first_cycle_at`] a position.
///
/// Built by `predict()` on a generator ([`crate::SCurve::predict`],
/// [`crate::Trapezoidal::predict`], [`crate::VelocityContouring::predict`]) in a bounded number of
/// integer operations (one closed form per segment); every question after that is a binary
/// search. No floating point; seconds and physical units through
/// [`CycleTime`](crate::format::CycleTime). It holds its segments in place (no allocation):
/// about 6 KB, so on a microcontroller build it where the stack has room, or keep one.
#[derive(Debug, Clone)]
pub struct Prediction {
    segments: [Segment; MAX_SEGMENTS],
    len: usize,
    /// Every velocity of the future has this sign or is zero (+1, −1; 0 when all are zero), or
    /// `None` when it reverses.
    direction: Option<i128>,
}

/// One piece of a future as a generator lays it out: `cycles` steps with velocities
/// `c0 + c1·k + c2·k(k+1)/2`, I32F32 bits; the last piece's `cycles` is ignored (for ever).
#[derive(Debug, Clone, Copy)]
pub(crate) struct Piece {
    pub cycles: u64,
    pub c0: i64,
    pub c1: i64,
    pub c2: i64,
    /// `c0` and `c1` are the velocity and acceleration of the state before the piece (a run of
    /// constant jerk that continues from where the last left off).
    pub continues: bool,
}

impl Piece {
    /// A constant velocity for `cycles` steps (for ever, as the last piece).
    pub const fn constant(velocity: i64, cycles: u64) -> Self {
        Self::run(velocity, 0, cycles)
    }

    /// A run of constant `jerk` for `cycles` steps, from the state the pieces before lead to.
    pub const fn jerk_run(jerk: i64, cycles: u64) -> Self {
        Self {
            cycles,
            c0: 0,
            c1: 0,
            c2: jerk,
            continues: true,
        }
    }

    /// A run of velocities `next, next + increment, …` (a trapezoid's run).
    pub const fn run(next: i64, increment: i64, cycles: u64) -> Self {
        Self {
            cycles,
            c0: next.wrapping_sub(increment),
            c1: increment,
            c2: 0,
            continues: false,
        }
    }
}

impl Prediction {
    /// The future from `origin` along `pieces` (empty pieces skipped; the last lasts for ever
    /// and must have a constant velocity, `c1 = c2 = 0`); `None` if there are more than
    /// [`MAX_SEGMENTS`].
    pub(crate) fn new(origin: State, pieces: &[Piece]) -> Option<Self> {
        let mut prediction = Self {
            segments: [Segment::default(); MAX_SEGMENTS],
            len: 0,
            direction: Some(0),
        };
        let (mut before, mut displacement, mut start) = (origin, 0i128, 0u64);
        let count = pieces.len();
        for (index, piece) in pieces.iter().enumerate() {
            let last = index + 1 == count;
            if piece.cycles == 0 && !last {
                continue;
            }
            let (c0, c1) = if piece.continues {
                (before.velocity.to_bits(), before.acceleration.to_bits())
            } else {
                (piece.c0, piece.c1)
            };
            let slot = prediction.segments.get_mut(prediction.len)?;
            *slot = Segment {
                start,
                cycles: if last { u64::MAX } else { piece.cycles },
                before,
                displacement,
                end: 0,
                c0: i128::from(c0),
                c1: i128::from(c1),
                c2: i128::from(piece.c2),
            };
            let segment = *slot;
            prediction.len += 1;
            // The velocities' signs: a linear run is monotone between its ends; a run with a
            // jerk is an S-curve's, whose velocity keeps the move's sign (its planner checks
            // 0 ≤ v along the direction on every cycle).
            let ends = if last {
                [segment.velocity(0), segment.velocity(0)]
            } else {
                [segment.velocity(1), segment.velocity(piece.cycles)]
            };
            for velocity in ends {
                prediction.direction = match (prediction.direction, velocity.signum()) {
                    (Some(sign), 0) => Some(sign),
                    (Some(0), sign) => Some(sign),
                    (Some(sign), other) if sign == other => Some(sign),
                    _ => None,
                };
            }
            if last {
                let end = match segment.c0.signum() {
                    0 => displacement,
                    1 => i128::MAX,
                    _ => -i128::MAX,
                };
                prediction.segments[prediction.len - 1].end = end;
                break;
            }
            before = segment.state_after(piece.cycles);
            displacement = segment.displacement_after(piece.cycles);
            prediction.segments[prediction.len - 1].end = displacement;
            start = start.checked_add(piece.cycles)?;
        }
        Some(prediction)
    }

    /// The future of a generator whose next step leads from `origin` to where `later` starts
    /// (its origin): that one step, then `later`, one cycle on. `None` past [`MAX_SEGMENTS`].
    pub(crate) fn after_step(origin: State, later: &Self) -> Option<Self> {
        let next = later.segments().first()?.before;
        let moved = i128::from(
            next.position
                .to_bits()
                .wrapping_sub(origin.position.to_bits()),
        );
        let step = Segment {
            start: 0,
            cycles: 1,
            before: origin,
            displacement: 0,
            end: moved,
            c0: i128::from(next.velocity.to_bits()),
            c1: 0,
            c2: 0,
        };
        let mut prediction = Self {
            segments: [Segment::default(); MAX_SEGMENTS],
            len: later.len + 1,
            direction: match (later.direction, moved.signum()) {
                (Some(sign), 0) => Some(sign),
                (Some(0), sign) => Some(sign),
                (Some(sign), other) if sign == other => Some(sign),
                _ => None,
            },
        };
        *prediction.segments.first_mut()? = step;
        for (slot, segment) in prediction
            .segments
            .get_mut(1..later.len + 1)?
            .iter_mut()
            .zip(later.segments())
        {
            *slot = Segment {
                start: segment.start.checked_add(1)?,
                displacement: segment.displacement + moved,
                end: if segment.end.abs() == i128::MAX {
                    segment.end
                } else {
                    segment.end + moved
                },
                ..*segment
            };
        }
        Some(prediction)
    }

    fn segments(&self) -> &[Segment] {
        &self.segments[..self.len]
    }

    /// The segment under way after `cycles` steps: the last that starts at or before them.
    fn segment_at(&self, cycles: u64) -> &Segment {
        let segments = self.segments();
        let index = segments.partition_point(|segment| segment.start <= cycles);
        &segments[index.saturating_sub(1)]
    }

    /// The state after `cycles` steps from the present, bit-identical to stepping that many
    /// times: a binary search over the segments and one closed form (O(log k)).
    pub fn state_at(&self, cycles: u64) -> State {
        let segment = self.segment_at(cycles);
        segment.state_after(cycles - segment.start)
    }

    /// The steps after which the generator is complete (at rest, nothing left to do), from the
    /// present; `None` if it never is (velocity contouring at a non-zero target velocity).
    pub fn completion(&self) -> Option<u64> {
        let rest = self.segments().last()?;
        if rest.c0 != 0 {
            return None;
        }
        // The rest segment's first step may be the one that arrives (velocity zero).
        Some(rest.start + u64::from(rest.before.velocity != I32F32::ZERO))
    }

    /// The first cycle (steps from the present, 0 for the present state) on which the position
    /// reaches or passes `position`; `None` if it never does.
    ///
    /// The point is taken as the position register shows it, which wraps at 32 integer bits: a
    /// future moving one way only (every move from rest to a destination, velocity contouring)
    /// reaches it at the first distance ahead, in its direction, at which the register shows it,
    /// found by a binary search over the segments and one over the cycles of one (O(log k +
    /// log n)); a future that reverses (a trapezoid whose destination changed behind it) meets
    /// it at the nearer way round (within ±2³¹ counts of the present position), searched
    /// segment by segment.
    pub fn first_cycle_at(&self, position: I32F32) -> Option<u64> {
        let origin = self.segments().first()?.before.position;
        let offset = position.to_bits().wrapping_sub(origin.to_bits());
        if offset == 0 {
            return Some(0);
        }
        match self.direction {
            Some(0) => None,
            Some(direction) => {
                // The first distance in the direction of motion at which the register shows
                // the point: the offset modulo 2^64 raw units (2^32 counts), that way round.
                let target = if direction > 0 {
                    i128::from(offset as u64)
                } else {
                    -i128::from(offset.wrapping_neg() as u64)
                };
                let segments = self.segments();
                let index = segments.partition_point(|segment| {
                    if direction > 0 {
                        segment.end < target
                    } else {
                        segment.end > target
                    }
                });
                let segment = segments.get(index)?;
                Self::first_in(segment, 1, segment.cycles, target, direction)
            }
            None => {
                let target = i128::from(offset);
                self.segments()
                    .iter()
                    .find_map(|segment| Self::reversing(segment, target))
            }
        }
    }

    /// In a segment whose displacement moves in `direction` (±1) from `low − 1` to `high`,
    /// reaching `target` by step `high`: the first step at or past it, as cycles from the origin.
    fn first_in(
        segment: &Segment,
        low: u64,
        high: u64,
        target: i128,
        direction: i128,
    ) -> Option<u64> {
        // Cycles past 2^64 from the origin do not exist.
        let high = high.min(u64::MAX - segment.start);
        let reached = |k: u64| (segment.displacement_after(k) - target) * direction >= 0;
        if low > high || !reached(high) {
            return None;
        }
        // The first k in low ..= high with reached(k): reached is false before it, true after
        // (so after the last k before `high` where it is false).
        let first = if reached(low) {
            low
        } else {
            last_true(low, high, |k| !reached(k)) + 1
        };
        Some(segment.start + first)
    }

    /// [`Self::first_cycle_at`] within one segment of a future that reverses: its velocity is
    /// linear (reversals come only from runs of constant velocity change), so it is monotone on
    /// each side of the one step where the velocity changes sign.
    fn reversing(segment: &Segment, target: i128) -> Option<u64> {
        let cycles = segment.cycles;
        // The last step on the side of the first step's velocity sign: velocities
        // v(k) = c0 + c1·k, k ≥ 1, change sign at most once.
        let first = segment.velocity(1).signum();
        let split = if segment.c1 == 0 || segment.c2 != 0 || first == 0 {
            cycles
        } else {
            // The last k with v(k) of the same sign as v(1) (or zero): k ≤ (−c0)/c1 rounded
            // toward the first side.
            let bound = if first > 0 {
                // c0 + c1·k ≥ 0 with c1 < 0: k ≤ c0 / −c1.
                segment.c0.div_euclid(-segment.c1)
            } else {
                // c0 + c1·k ≤ 0 with c1 > 0: k ≤ −c0 / c1.
                (-segment.c0).div_euclid(segment.c1)
            };
            u64::try_from(bound.max(1)).unwrap_or(u64::MAX).min(cycles)
        };
        let mut start_displacement = segment.displacement;
        for (low, high) in [(1, split), (split.saturating_add(1), cycles)] {
            if low > high {
                continue;
            }
            let end = segment.displacement_after(high.min(u64::MAX - segment.start));
            let direction = (end - start_displacement).signum();
            if direction != 0
                && (target - start_displacement) * direction > 0
                && (end - target) * direction >= 0
            {
                return Self::first_in(segment, low, high, target, direction);
            }
            start_displacement = end;
        }
        None
    }
}
