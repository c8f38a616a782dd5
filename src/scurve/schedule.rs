//! The schedule: the plan as a sorted list of jerk changes, built once for the plan that won, and
//! its one pass that finds the move's peaks (and confirms its limits).

use fixed::types::I32F32;

use super::remainder::{Notch, Placement, MAX_NOTCHES};
use super::shape::{corners, MainMove};
use super::ScurvePlan;

/// One change of the sealed replay: the jerk it sets (2^-32 counts/cycle³, the direction of the
/// move folded in) and the cycles it holds, to the next change.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) struct JerkChange {
    /// The cycles the change holds; the end marker's: for ever (`u64::MAX`).
    pub hold: u64,
    /// The jerk from this change on, raw units.
    pub jerk: i64,
}

/// At most this many runs in a sealed replay, its end marker included. The changes of a plan fall
/// on at most 44 distinct cycles: the main move's four kinds of unit, with first ramps `a − 1` or
/// `a`, second ramps `b − 1` or `b` and phase V from `c − 1` or `c`, have their eight corners on
/// at most 1 + 2 + 2 + 3 + 2 + 3 + 3 + 4 = 20 cycles; two fine units add at most 10 more, three
/// notch pairs 24 (fine units and notch pairs never come together). Each distinct cycle before
/// the last starts one run (the first, cycle 0, is a corner of every unit), and the end marker
/// closes the replay: 45.
pub(super) const MAX_CHANGES: usize = 45;

/// The index that stands for "no jerk change": past the end of the arrays, so a replay pointed at
/// it takes the slow path on its next event.
pub(super) const SENTINEL: usize = MAX_CHANGES;

/// Past the sentinel, a change the fast path replays that is not the schedule's ([`super::SCurve`]
/// keeps it: an abrupt stop's level-off, whose jerk is too wide for the arrays; the replay after
/// the corrected first step of a move started right after an abrupt stop).
pub(super) const PENDING: usize = SENTINEL + 1;
/// Rest after an abrupt stop (jerk zero for ever).
pub(super) const ABRUPT_REST: usize = SENTINEL + 2;

/// At most this many changes of the main move (see [`MAX_CHANGES`]): 20 with notch pairs, 30
/// with fine units.
const MAX_MAIN_CHANGES: usize = 30;

/// At most this many changes from notch pairs: eight per pair.
const MAX_NOTCH_CHANGES: usize = 8 * MAX_NOTCHES;

// The sealing pass writes runs from the start of the arrays while it reads the main move's
// changes from their end; it cannot overtake them while the notch pairs' changes are fewer than
// the free slots before the main move's 20 ([`Schedule::seal`]).
const _: () = assert!(MAX_NOTCH_CHANGES < MAX_CHANGES - 20);

/// The exact limits in I32F32 bits.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub(super) struct Limits64 {
    /// Jerk, counts/cycle³ · 2^32.
    pub jerk: u64,
    /// Acceleration, counts/cycle² · 2^32.
    pub acceleration: u64,
    /// Velocity, counts/cycle · 2^32.
    pub velocity: u64,
}

/// A cycle number in the width a sealing pass works in: 32 bits for a move shorter than 2^31
/// cycles (most moves: a 32-bit core then compares two cycles in one instruction, not three),
/// 64 otherwise.
trait Cycle: Copy + Ord + core::ops::Add<Output = Self> + core::ops::Sub<Output = Self> {
    /// Later than any change.
    const NEVER: Self;
    /// The cycle as this width (the pass only narrows cycles of the move, which fit).
    fn narrow(cycle: u64) -> Self;
    /// Back to 64 bits.
    fn widen(self) -> u64;
}

impl Cycle for u32 {
    const NEVER: Self = u32::MAX;
    fn narrow(cycle: u64) -> Self {
        // Cycles past the move (none are) would sort last, as they should.
        u32::try_from(cycle).unwrap_or(u32::MAX)
    }
    fn widen(self) -> u64 {
        u64::from(self)
    }
}

impl Cycle for u64 {
    const NEVER: Self = u64::MAX;
    fn narrow(cycle: u64) -> Self {
        cycle
    }
    fn widen(self) -> u64 {
        self
    }
}

/// One notch pair's jerk changes, one at a time, in order: a jerk of ±1 on one cycle is a
/// change by ±1 on it and back on the next, so the pair's four impulses at `s`, `s + w`, `s + k`
/// and `s + k + w` are eight changes, `−1, +1, +1, −1, +1, −1, −1, +1`, each one cycle after the
/// last or `w − 1` or `k − w − 1` cycles after it (they come in order because `1 ≤ w < k`).
#[derive(Debug, Clone, Copy)]
struct Stream<C> {
    /// The cycle of the next change; [`Cycle::NEVER`] when done.
    cycle: C,
    /// Which of the eight changes is next.
    index: u32,
    /// Cycles from the second change to the third (and the sixth to the seventh): `w − 1`.
    short_gap: C,
    /// Cycles from the fourth change to the fifth: `k − w − 1`.
    long_gap: C,
}

impl<C: Cycle> Stream<C> {
    /// No changes.
    const DONE: Self = Self {
        cycle: C::NEVER,
        index: 8,
        short_gap: C::NEVER,
        long_gap: C::NEVER,
    };

    /// The pair's changes, from the first.
    fn new(notch: &Notch) -> Self {
        Self {
            cycle: C::narrow(notch.start),
            index: 0,
            short_gap: C::narrow(notch.width - 1),
            long_gap: C::narrow(notch.span - notch.width - 1),
        }
    }

    /// The change at `cycle` (±1, raw units), moving on to the next.
    fn advance(&mut self) -> i32 {
        // Bit i of 0b1001_0110 is set where change i raises the jerk.
        let amount = if (0b1001_0110 >> (self.index & 7)) & 1 == 1 {
            1
        } else {
            -1
        };
        let gap = match self.index {
            1 | 5 => self.short_gap,
            3 => self.long_gap,
            _ => C::narrow(1),
        };
        self.index += 1;
        self.cycle = if self.index >= 8 {
            C::NEVER
        } else {
            self.cycle + gap
        };
        amount
    }
}

/// What a replay of a sealed schedule does, run by run ([`Schedule::replay`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub(super) struct Replay {
    /// The largest |acceleration| on any cycle, I32F32 bits.
    pub peak_acceleration: i64,
    /// The largest velocity along the direction of the move, I32F32 bits.
    pub peak_velocity: i64,
    /// Every cycle keeps |jerk| ≤ J, |acceleration| ≤ A and 0 ≤ velocity ≤ V along the
    /// direction, and the move ends at rest.
    pub within_limits: bool,
    /// The distance covered along the direction, 2^-32 counts (valid when `within_limits`).
    pub distance: i128,
}

/// A plan in force: its jerk changes in the order they come (one per cycle, changes on the same
/// cycle added up), closed by an end marker on the cycle after the last (which brings the jerk
/// back to zero), and its summary.
///
/// Two arrays rather than one of pairs: a jerk is at most J < 2^31 raw units, so 32 bits hold it,
/// and the generator — which carries the schedule, and is copied when it is returned — is a
/// quarter smaller (a copy costs about an instruction per byte on a Cortex-M4).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) struct Schedule {
    /// While building: the cycle of each change of the main move (0 = the first step), sorted,
    /// in the top `main_len` entries. Sealed: the cycles each run holds, in `[0, len)`.
    holds: [u64; MAX_CHANGES],
    /// While building: the change of the jerk, modulo 2^32 (a change is at most 2J < 2^32, so
    /// it is zero exactly when its residue is, and the running sum of the residues is the jerk,
    /// which fits 32 bits). Sealed: the jerk each run sets.
    jerks: [i32; MAX_CHANGES],
    /// Sealed: how many runs, the end marker included.
    len: usize,
    /// While building: how many changes of the main move there are, at the top of the arrays
    /// (zero, not an index, when empty: the empty schedule is then all zeros, which a clear
    /// makes, where anything else is a copy from flash twice the cost on a Cortex-M4).
    main_len: usize,
    /// The plan's summary (its peaks zero: [`Self::replay`] finds them when they are asked for).
    pub plan: ScurvePlan,
}

impl Schedule {
    /// No move.
    pub const EMPTY: Self = Self {
        holds: [0; MAX_CHANGES],
        jerks: [0; MAX_CHANGES],
        len: 0,
        main_len: 0,
        plan: ScurvePlan {
            phases: [0; 7],
            total: 0,
            peak_acceleration: I32F32::ZERO,
            peak_velocity: I32F32::ZERO,
        },
    };

    /// The sealed change at `index`; `None` past the arrays ([`SENTINEL`]). One comparison on
    /// the replay's path, which the bounds checks of both arrays share.
    #[inline]
    pub fn change(&self, index: usize) -> Option<JerkChange> {
        (index < MAX_CHANGES).then(|| JerkChange {
            hold: self.holds[index],
            jerk: i64::from(self.jerks[index]),
        })
    }

    /// The sealed change at `index`, or the end marker's past the arrays (for the slow path).
    pub fn run(&self, index: usize) -> JerkChange {
        self.change(index).unwrap_or(JerkChange {
            hold: u64::MAX,
            jerk: 0,
        })
    }

    /// How many changes the sealed replay has, its end marker included.
    pub fn len(&self) -> usize {
        self.len
    }

    /// No move.
    pub fn clear(&mut self) {
        self.len = 0;
        self.main_len = 0;
        self.plan = ScurvePlan::default();
    }

    /// Makes this a move of `distance` raw units in three cycles, the fewest any move takes: a
    /// velocity of `distance` on one cycle (jerk `+d, −2d, +d`), for `distance` within the
    /// acceleration and the velocity and at most half the jerk (checked by the caller).
    pub fn pulse(&mut self, distance: u64, direction: i64) {
        self.main_len = 0;
        // The changes +d, −3d, +3d, each below 2^33 and kept modulo 2^32 (see `jerks`).
        let d = distance as i64;
        for (cycle, amount) in [(2, 3 * d), (1, -3 * d), (0, d)] {
            self.prepend(cycle, amount * direction);
        }
        self.plan = ScurvePlan {
            phases: [1, 0, 1, 0, 0, 0, 1],
            total: 3,
            peak_acceleration: I32F32::ZERO,
            peak_velocity: I32F32::ZERO,
        };
        self.seal(&Placement::default(), direction);
    }

    /// Writes `changes` (`(cycles held, jerk along the move)`, in order: a smooth stop's,
    /// [`super::stop::lay_out`], at most [`MAX_CHANGES`] − 1) in the direction `direction` (±1)
    /// at the end of the arrays, closed by an end marker in the last slot, and returns the index
    /// of the first: a replay from there ends with the marker, and the index after it is
    /// [`SENTINEL`]. The plan's own changes before them stay as they are unless the two overlap
    /// ([`Self::fits_after`]); its summary and length are left as they are.
    pub fn seal_at_end(&mut self, changes: &[(u64, i64)], direction: i64) -> usize {
        let count = changes.len().min(MAX_CHANGES - 1);
        let first = MAX_CHANGES - 1 - count;
        for (index, &(hold, jerk)) in changes[..count].iter().enumerate() {
            self.holds[first + index] = hold;
            // |jerk| ≤ J < 2^31: within 32 bits.
            self.jerks[first + index] = (jerk * direction) as i32;
        }
        self.holds[MAX_CHANGES - 1] = u64::MAX;
        self.jerks[MAX_CHANGES - 1] = 0;
        first
    }

    /// Whether `count` changes and an end marker fit after the plan's changes
    /// ([`Self::seal_at_end`] then leaves them intact).
    pub fn fits_after(&self, count: usize) -> bool {
        self.len + count < MAX_CHANGES
    }

    /// The runs of the sealed replay, `(cycles, jerk)` in order, the end marker left out.
    pub fn runs(&self) -> impl Iterator<Item = (u64, i64)> + '_ {
        let runs = self.len.saturating_sub(1);
        self.holds[..runs]
            .iter()
            .zip(&self.jerks[..runs])
            .map(|(&hold, &jerk)| (hold, i64::from(jerk)))
    }

    /// Adds `amount` on `cycle` to the main move's changes (the top `main_len` entries), keeping
    /// them sorted: the corners arrive latest first, so a change goes in at the front, or a step
    /// or two in, or is added to a change on the same cycle.
    fn prepend(&mut self, cycle: u64, amount: i64) {
        // Modulo 2^32 (see `jerks`): the truncation is the residue.
        let amount = amount as i32;
        let start = MAX_CHANGES - self.main_len.min(MAX_CHANGES);
        let mut at = start;
        while at < MAX_CHANGES && self.holds[at] < cycle {
            at += 1;
        }
        if at < MAX_CHANGES && self.holds[at] == cycle {
            self.jerks[at] = self.jerks[at].wrapping_add(amount);
            return;
        }
        if start + MAX_MAIN_CHANGES <= MAX_CHANGES {
            return; // Unreachable: the main move has at most MAX_MAIN_CHANGES (see MAX_CHANGES).
        }
        // A step or two at most: a loop, not a library call.
        for k in start..at {
            self.holds[k - 1] = self.holds[k];
            self.jerks[k - 1] = self.jerks[k];
        }
        self.holds[at - 1] = cycle;
        self.jerks[at - 1] = amount;
        self.main_len += 1;
    }

    /// Makes this the schedule of `main` less the notch pairs of `placement`, in the direction
    /// `direction` (±1), its main units' ramps `(a, b)`, sealed ([`Self::seal`]); `false` (and
    /// nothing built) if the move is shorter than its ramps.
    pub fn build(
        &mut self,
        main: &MainMove,
        placement: &Placement,
        direction: i64,
        (a, b): (u64, u64),
    ) -> bool {
        let total = main.total();
        let Some(cruise) = total.checked_sub(2 * (a + b)) else {
            return false;
        };
        self.main_len = 0;
        // Written in place, field by field (a summary built apart would be copied in).
        self.plan.phases = [a, b - a, a, cruise, a, b - a, a];
        self.plan.total = total;
        self.plan.peak_acceleration = I32F32::ZERO;
        self.plan.peak_velocity = I32F32::ZERO;
        // The groups of a unit mix differ from the longest ramps and cruise (a, b, c) by at most
        // one cycle each, so the eight corners of all of them fall on at most 20 cycles: the
        // corner `s` of a group with ramps one shorter by (δa, δb, δc) lands δ = the sum of the
        // δs it includes before the longest group's. Their changes are added up in a table
        // first (no search), then put in order, latest first; groups further off (fine units)
        // are added corner by corner.
        let (a, b, c) = (main.most(|g| g.a), main.most(|g| g.b), main.most(|g| g.c));
        // Counts of at most J < 2^31 units each, with their sign: 32 bits.
        let mut table = [[0i32; 4]; 8];
        for group in main.groups() {
            let (da, db, dc) = (a - group.a, b - group.b, c - group.c);
            let count = group.count as i32 * direction as i32;
            if da > 1 || db > 1 || dc > 1 {
                for (cycle, sign) in corners(group.a, group.b, group.c).into_iter().rev() {
                    self.prepend(cycle, sign * i64::from(count));
                }
                continue;
            }
            let (da, db, dc) = (da as usize, db as usize, dc as usize);
            for (slot, delta) in [0, da, db, da + db, dc, dc + da, dc + db, dc + da + db]
                .into_iter()
                .enumerate()
            {
                table[slot][delta] += count;
            }
        }
        for (slot, (base, sign)) in corners(a, b, c).into_iter().enumerate().rev() {
            for (delta, &amount) in table[slot].iter().enumerate() {
                if amount != 0 {
                    // base ≥ δ: a shorter ramp or cruise is still at least one cycle.
                    self.prepend(base - delta as u64, sign * i64::from(amount));
                }
            }
        }
        self.seal(placement, direction);
        true
    }

    /// Makes the main move's changes (sorted, the top `main_len` entries) and the notch pairs of
    /// `placement` a replay: runs of constant jerk, each the jerk it sets and the cycles it
    /// holds, from index 0, closed by an end marker (setting the jerk to zero, held for ever:
    /// the acceleration and velocity are zero there already).
    ///
    /// One forward pass merges the three streams of notch changes (each pair's eight changes
    /// come in order: a jerk of ±1 on one cycle is a change by ±1 on it and back on the next)
    /// into the main move's, adds up changes on the same cycle and drops changes that leave the
    /// jerk as it was (and those on or after the last cycle), which would cost a replay's slow
    /// path for nothing. The runs are written from the start of the arrays while the main
    /// move's changes are read from their end: after `r` main and `n` notch changes at most
    /// `r + n` runs are written, and `n ≤ 24 < MAX_CHANGES − 20`, so the writing never
    /// overtakes the reading.
    fn seal(&mut self, placement: &Placement, direction: i64) {
        if self.plan.total < 1 << 31 {
            self.seal_in::<u32>(placement, direction);
        } else {
            self.seal_in::<u64>(placement, direction);
        }
    }

    /// [`Self::seal`] with cycles of type `C`, wide enough for every cycle of the move.
    fn seal_in<C: Cycle>(&mut self, placement: &Placement, direction: i64) {
        let total = C::narrow(self.plan.total);
        // The pairs' streams, earliest next change first; a stream that is done sinks to the
        // end. One comparison per change picks the main move's or the first stream's.
        let mut queue = [Stream::<C>::DONE; MAX_NOTCHES];
        for (stream, notch) in queue.iter_mut().zip(placement.notches()) {
            *stream = Stream::new(notch);
        }
        queue.sort_unstable_by_key(|stream| stream.cycle);
        let sign = direction as i32;
        let mut main = MAX_CHANGES - self.main_len.min(MAX_CHANGES);
        // The run open from cycle `from` with jerk `jerk`; runs before `written` are sealed.
        let (mut written, mut from, mut jerk) = (0, C::narrow(0), 0i32);
        loop {
            let main_cycle = if main < MAX_CHANGES {
                C::narrow(self.holds[main])
            } else {
                C::NEVER
            };
            let from_notch = queue[0].cycle < main_cycle;
            let cycle = if from_notch {
                queue[0].cycle
            } else {
                main_cycle
            }
            .min(total);
            if cycle != from {
                let hold = (cycle - from).widen();
                if written > 0 && self.jerks[written - 1] == jerk {
                    self.holds[written - 1] += hold;
                } else if written < MAX_CHANGES - 1 {
                    self.holds[written] = hold;
                    self.jerks[written] = jerk;
                    written += 1;
                }
                from = cycle;
            }
            if cycle == total {
                break;
            }
            // The running sum modulo 2^32 is the jerk (see `jerks`).
            let change = if from_notch {
                let amount = queue[0].advance();
                // Back into the queue: a step or two down.
                if queue[1].cycle < queue[0].cycle {
                    queue.swap(0, 1);
                    if queue[2].cycle < queue[1].cycle {
                        queue.swap(1, 2);
                    }
                }
                amount * sign
            } else {
                main += 1;
                self.jerks[main - 1]
            };
            jerk = jerk.wrapping_add(change);
        }
        self.holds[written] = u64::MAX;
        self.jerks[written] = 0;
        self.len = written + 1;
    }

    /// Replays the sealed schedule run by run, in the move's direction (`direction` ±1): its
    /// peaks, whether it keeps `limits` on every cycle and ends at rest, and the distance it
    /// covers.
    ///
    /// On a run of constant jerk the acceleration is linear and the velocity quadratic, so the
    /// ends of the run and the velocity's turning point are the only cycles that can set a peak
    /// or break a limit. Planning does not run this: the planner's inequalities keep the limits
    /// where the remainder sits, and in builds with debug assertions (the tests) every plan is
    /// checked with it. [`super::SCurve::plan`] runs it for the peaks, when they are asked for.
    pub fn replay(&self, direction: i64, limits: Limits64) -> Replay {
        let (j_max, a_max, v_max) = (
            limits.jerk as i128,
            limits.acceleration as i128,
            limits.velocity as i128,
        );
        let (mut acceleration, mut velocity, mut distance) = (0i128, 0i128, 0i128);
        let (mut peak_acceleration, mut peak_velocity) = (0i128, 0i128);
        let mut within_limits = true;
        for (cycles, jerk) in self.runs() {
            let (m, jerk) = (i128::from(cycles), i128::from(jerk * direction));
            within_limits &= jerk.abs() <= j_max;
            // Σ_{n=1..m} (v + a·n + j·n(n+1)/2) = m·v + a·m(m+1)/2 + j·m(m+1)(m+2)/6. Only
            // runs without a jerk are long (with one, j·m ≤ 2A bounds m by 2^32), so every
            // product stays under 2^127.
            distance += m * velocity + acceleration * (m * (m + 1) / 2);
            if jerk != 0 {
                distance += jerk * (m * (m + 1) * (m + 2) / 6);
            }
            let (first, last) = (acceleration + jerk, acceleration + jerk * m);
            peak_acceleration = peak_acceleration.max(first.abs()).max(last.abs());
            // The velocity turns inside the run only where the acceleration changes sign: at
            // n* = ⌊−a/j − ½⌋ or the cycle after, where it is v + a·n + j·n(n+1)/2.
            if first.signum() * last.signum() < 0 {
                let turn = (-2 * acceleration - jerk).div_euclid(2 * jerk);
                for n in [turn, turn + 1] {
                    if (1..=m).contains(&n) {
                        let v = velocity + acceleration * n + jerk * (n * (n + 1) / 2);
                        within_limits &= (0..=v_max).contains(&v);
                        peak_velocity = peak_velocity.max(v);
                    }
                }
            }
            velocity += acceleration * m + jerk * (m * (m + 1) / 2);
            acceleration = last;
            within_limits &= (0..=v_max).contains(&velocity);
            peak_velocity = peak_velocity.max(velocity);
        }
        within_limits &= acceleration == 0 && velocity == 0 && peak_acceleration <= a_max;
        Replay {
            // Within the limits both fit 64 bits (|a| ≤ A < 2^31, v ≤ V < 2^47).
            peak_acceleration: i64::try_from(peak_acceleration).unwrap_or(i64::MAX),
            peak_velocity: i64::try_from(peak_velocity).unwrap_or(i64::MAX),
            within_limits,
            distance,
        }
    }
}
#[cfg(test)]
mod tests {
    use super::*;
    use crate::scurve::shape::Group;

    /// The sealed runs are, cycle by cycle, the main move's jerk (from its groups' closed form)
    /// plus the notch pairs' impulses: the one-pass merge loses, reorders and drops nothing,
    /// even with two pairs starting on the same cycle.
    #[test]
    fn sealed_runs_are_the_jerk_of_the_move() {
        let groups = [
            Group {
                count: 1,
                a: 443,
                b: 444,
                c: 21846,
            },
            Group {
                count: 2,
                a: 442,
                b: 444,
                c: 21845,
            },
        ];
        let main = MainMove::from_groups(&groups);
        let placement = Placement::default()
            .with(Notch {
                start: 360,
                width: 84,
                span: 21845,
            })
            .with(Notch {
                start: 440,
                width: 5,
                span: 10972,
            })
            .with(Notch {
                start: 440,
                width: 6,
                span: 12716,
            });
        let total = main.total();
        for direction in [1, -1] {
            let mut schedule = Schedule::EMPTY;
            assert!(schedule.build(&main, &placement, direction, (443, 444)));
            let mut cycle = 0u64;
            for (hold, jerk) in schedule.runs() {
                for n in cycle..cycle + hold {
                    let impulses: i64 = placement
                        .notches()
                        .iter()
                        .flat_map(|notch| notch.impulses())
                        .filter(|&(at, _)| at == n)
                        .map(|(_, amount)| amount)
                        .sum();
                    assert_eq!(jerk, direction * (main.jerk_at(n) + impulses), "cycle {n}");
                }
                cycle += hold;
            }
            assert_eq!(cycle, total);
        }
    }
}
