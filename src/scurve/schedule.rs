//! The schedule: the plan as a sorted list of jerk changes, built once for the plan that won, and
//! its one pass that finds the move's peaks (and confirms its limits).

use fixed::types::I32F32;

use super::remainder::{Notch, Placement, MAX_NOTCHES};
use super::shape::{corners, MainMove};
use super::ScurvePlan;
use crate::replay::{count_and_laps, cycles_of};

/// One change of the sealed replay: the jerk it sets (2^-32 counts/cycle³, the direction of the
/// move folded in) and the cycles it holds, to the next change (for the slow path, the
/// predictions and the tests; the replay reads [`Run`]s).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) struct JerkChange {
    /// The cycles the change holds; the end marker's: for ever (`u64::MAX`).
    pub hold: u64,
    /// The jerk from this change on, raw units.
    pub jerk: i64,
}

/// One run of the sealed replay as the fast path of [`super::SCurve`]'s step copies it, whole,
/// into the generator: the jerk it sets and a 32-bit countdown that carries, in the same eight
/// bytes, where the replay goes when it runs out (on a Cortex-M4 the copy is two 8-byte loads
/// and two stores, and the countdown one 32-bit subtraction a cycle, not three).
///
/// A run longer than 2^32 cycles (only a run without jerk can be: with one, J·m ≤ 2A bounds
/// m by 2^32) counts its first `count` cycles, then `laps` of 2^32 on the slow path, which its
/// `next` (past [`LAPS`]) sends it to. Its length is below 2^48 cycles — the longest is a
/// cruise, at most distance/velocity < 2^64 / 2^16 raw (the velocity register's least step is
/// 2^-16 counts/cycle) — so 16 bits hold the laps.
///
/// While the schedule is being built, a slot at the top of the array holds a change of the main
/// move instead ([`Self::main_change`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[repr(C)]
pub(super) struct Run {
    /// The jerk from this change on, raw units (I32F32 bits), the direction folded in.
    pub jerk: i64,
    /// Cycles to the next event, modulo 2^32 (0 stands for 2^32: a step counts down first).
    pub count: u32,
    /// Where the replay goes when the count runs out: the index of the next run; past the
    /// array the slow path's ([`SENTINEL`], [`PENDING`], [`ABRUPT_REST`], [`LAPS`] + the next
    /// run's index while laps remain).
    pub next: u16,
    /// Laps of 2^32 cycles still to count after `count` (see [`LAPS`]).
    pub laps: u16,
}

impl Run {
    /// The end marker, after a move's last run: no jerk (the move is at rest there), and the
    /// slow path after 2^32 cycles, which rests.
    pub const END: Self = Self {
        jerk: 0,
        count: 0,
        next: SENTINEL,
        laps: 0,
    };

    /// `jerk` for `cycles` (≥ 1; 0 counts as 1) cycles, then the run at index `next`.
    pub const fn new(jerk: i64, cycles: u64, next: u16) -> Self {
        // 0 counts as 1 (written as the saturating subtraction `count_and_laps` undoes: the
        // form that keeps an abrupt stop's cycle at 36 Cortex-M4 instructions, where a branch
        // took 37).
        let (count, laps) = count_and_laps(cycles.saturating_sub(1) + 1);
        Self {
            jerk,
            count,
            next: if laps == 0 { next } else { LAPS + next },
            // Below 2^16 (see the type); saturated, not wrapped, were it ever not.
            laps: if laps > u16::MAX as u64 {
                u16::MAX
            } else {
                laps as u16
            },
        }
    }

    /// The cycles left in the run: its count, then its laps.
    pub const fn cycles(&self) -> u64 {
        cycles_of(self.count, self.laps as u64)
    }

    /// The index the replay goes on at after the run (its laps counted).
    pub const fn after(&self) -> u16 {
        if self.next >= LAPS {
            self.next - LAPS
        } else {
            self.next
        }
    }

    /// As a change: the cycles it holds (an end marker's for ever) and its jerk.
    pub const fn change(&self) -> JerkChange {
        JerkChange {
            hold: if self.next == SENTINEL {
                u64::MAX
            } else {
                self.cycles()
            },
            jerk: self.jerk,
        }
    }

    /// While building: a change of the main move by `residue` (the change of the jerk modulo
    /// 2^32, see the schedule's slots) on `cycle`, kept in the slot's jerk and count.
    const fn main_change(cycle: u64, residue: i32) -> Self {
        Self {
            jerk: cycle as i64,
            count: residue as u32,
            next: 0,
            laps: 0,
        }
    }

    /// While building: the cycle of the main move's change this slot holds.
    const fn cycle(&self) -> u64 {
        self.jerk as u64
    }

    /// While building: the change of the jerk modulo 2^32 this slot holds.
    const fn residue(&self) -> i32 {
        self.count as i32
    }
}

/// At most this many runs in a sealed replay, its end marker included. The changes of a plan fall
/// on at most 44 distinct cycles: the main move's four kinds of unit, with first ramps `a − 1` or
/// `a`, second ramps `b − 1` or `b` and phase V from `c − 1` or `c`, have their eight corners on
/// at most 1 + 2 + 2 + 3 + 2 + 3 + 3 + 4 = 20 cycles; two fine units add at most 10 more, three
/// notch pairs 24 (fine units and notch pairs never come together). Each distinct cycle before
/// the last starts one run (the first, cycle 0, is a corner of every unit), and the end marker
/// closes the replay: 45.
pub(super) const MAX_CHANGES: usize = 45;

/// The index that stands for "no jerk change": past the end of the array, so a replay pointed at
/// it takes the slow path on its next event. (An end marker's `next`.)
pub(super) const SENTINEL: u16 = MAX_CHANGES as u16;

/// Past the sentinel, a change the fast path replays that is not the schedule's ([`super::SCurve`]
/// keeps it: an abrupt stop's level-off, which leaves the plan's changes as they are; the replay
/// after the corrected first step of a move started right after an abrupt stop).
pub(super) const PENDING: u16 = SENTINEL + 1;
/// Rest after an abrupt stop (jerk zero; the slow path every 2^32 cycles).
pub(super) const ABRUPT_REST: u16 = SENTINEL + 2;
/// An abrupt stop's rest under way.
pub(super) const AFTER_ABRUPT_REST: u16 = SENTINEL + 3;
/// `LAPS + i`: a run's laps of 2^32 cycles are being counted (on the slow path), then the replay
/// goes on at index `i`.
pub(super) const LAPS: u16 = 64;
const _: () = assert!(AFTER_ABRUPT_REST < LAPS);

/// A run is shorter than this many cycles: its count and 16 bits of laps of 2^32 (see [`Run`]).
/// Every run of a plan at a velocity of at least 2^-16 counts/cycle is; the planner refuses a
/// plan with a longer one rather than let its laps saturate (and its cruise fall short).
pub(super) const LONGEST_RUN: u64 = 1 << 48;

/// At most this many changes of the main move (see [`MAX_CHANGES`]): 20 with notch pairs, 30
/// with fine units.
const MAX_MAIN_CHANGES: usize = 30;

/// At most this many changes from notch pairs: eight per pair.
const MAX_NOTCH_CHANGES: usize = 8 * MAX_NOTCHES;

// The sealing pass writes runs from the start of the array while it reads the main move's
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
    /// The run of this many cycles (≥ 1) at `jerk`, then the run at index `next`.
    fn run(self, jerk: i64, next: u16) -> Run;
}

impl Cycle for u32 {
    const NEVER: Self = u32::MAX;
    fn narrow(cycle: u64) -> Self {
        // Cycles past the move (none are) would sort last, as they should.
        u32::try_from(cycle).unwrap_or(u32::MAX)
    }
    fn run(self, jerk: i64, next: u16) -> Run {
        // Below 2^31 cycles: the count alone, no laps.
        Run {
            jerk,
            count: self,
            next,
            laps: 0,
        }
    }
}

impl Cycle for u64 {
    const NEVER: Self = u64::MAX;
    fn narrow(cycle: u64) -> Self {
        cycle
    }
    fn run(self, jerk: i64, next: u16) -> Run {
        Run::new(jerk, self, next)
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

/// The first stream's next change (±1), the stream put back in order (a step or two down).
fn next_notch_change<C: Cycle>(queue: &mut [Stream<C>; MAX_NOTCHES]) -> i32 {
    let amount = queue[0].advance();
    if queue[1].cycle < queue[0].cycle {
        queue.swap(0, 1);
        if queue[2].cycle < queue[1].cycle {
            queue.swap(1, 2);
        }
    }
    amount
}

/// A sealing pass under way ([`Schedule::seal`]): the jerk from cycle `from` on is `jerk`; runs
/// before `written` are sealed, and the run before `from`, `open_cycles` at `open_jerk`, is
/// written once the next run's jerk differs (a run's count and laps need its whole length). No
/// jerk is i32::MIN (|jerk| ≤ J < 2^31), so the first run merges with nothing.
struct Sealing<C> {
    written: usize,
    from: C,
    jerk: i32,
    open_cycles: C,
    open_jerk: i32,
}

impl<C: Cycle> Sealing<C> {
    /// The jerk changes by `change` (modulo 2^32) on `cycle` (not before `from`).
    #[inline]
    fn change(&mut self, runs: &mut [Run; MAX_CHANGES], cycle: C, change: i32) {
        if cycle != self.from {
            let hold = cycle - self.from;
            if self.jerk == self.open_jerk {
                self.open_cycles = self.open_cycles + hold;
            } else {
                self.write_open(runs);
                (self.open_cycles, self.open_jerk) = (hold, self.jerk);
            }
            self.from = cycle;
        }
        self.jerk = self.jerk.wrapping_add(change);
    }

    /// Writes the open run, if any, at index `written`, moving on; the slots before the end
    /// marker's are enough (see [`MAX_CHANGES`]).
    #[inline]
    fn write_open(&mut self, runs: &mut [Run; MAX_CHANGES]) {
        if self.open_cycles != C::narrow(0) && self.written < MAX_CHANGES - 1 {
            runs[self.written] = self
                .open_cycles
                .run(i64::from(self.open_jerk), self.written as u16 + 1);
            self.written += 1;
        }
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
/// One array of [`Run`]s, each what the replay's change (the fast path of [`super::SCurve`]'s
/// step, on the cycles its jerk changes) copies whole: its jerk 64 bits wide, its countdown and
/// the index after it in one 8-byte word. Two arrays, 64-bit holds and 32-bit jerks, a quarter
/// smaller, cost that path two addresses, a sign extension and the index's increment, and every
/// cycle a 64-bit countdown: on a Cortex-M4 the S-curve's step took 39 instructions at most
/// (now 33) and its 3-axis line 63 (now 60, SPEC §16's budget). The price is the copy of the
/// larger generator when a move is planned, a few hundred instructions.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) struct Schedule {
    /// While building: in the top `main_len` slots, each change of the main move, sorted by its
    /// cycle (0 = the first step), with the change of the jerk modulo 2^32 (a change is at most
    /// 2J < 2^32, so it is zero exactly when its residue is, and the running sum of the
    /// residues is the jerk, which fits 32 bits) — [`Run::main_change`]. Sealed: the runs in
    /// `[0, len)`, and a smooth stop's at the end of the array.
    runs: [Run; MAX_CHANGES],
    /// Sealed: how many runs, the end marker included.
    len: usize,
    /// While building: how many changes of the main move there are, at the top of the array
    /// (zero, not an index, when empty: the empty schedule is then all zeros, which a clear
    /// makes, where anything else is a copy from flash twice the cost on a Cortex-M4).
    main_len: usize,
    /// The plan's summary (its peaks zero: [`Self::replay`] finds them when they are asked for).
    pub plan: ScurvePlan,
}

impl Schedule {
    /// No move.
    pub const EMPTY: Self = Self {
        runs: [Run {
            jerk: 0,
            count: 0,
            next: 0,
            laps: 0,
        }; MAX_CHANGES],
        len: 0,
        main_len: 0,
        plan: ScurvePlan {
            phases: [0; 7],
            total: 0,
            peak_acceleration: I32F32::ZERO,
            peak_velocity: I32F32::ZERO,
        },
    };

    /// The sealed run at `index`; `None` past the array (the slow path's indices): one
    /// comparison and one address on the replay's path.
    #[inline(always)]
    pub fn run_at(&self, index: u16) -> Option<&Run> {
        self.runs.get(usize::from(index))
    }

    /// The sealed run at `index`, or an end marker past the array.
    pub fn run(&self, index: u16) -> Run {
        self.run_at(index).copied().unwrap_or(Run::END)
    }

    /// The sealed change at `index` (an end marker's past the array), for the slow path.
    pub fn change(&self, index: u16) -> JerkChange {
        self.run(index).change()
    }

    /// How many changes the sealed replay has, its end marker included.
    pub fn len(&self) -> u16 {
        self.len as u16
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
        // The changes +d, −3d, +3d, each below 2^33 and kept modulo 2^32 (see `runs`).
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
    /// at the end of the array, closed by an end marker in the last slot, and returns the index
    /// of the first: a replay from there ends with the marker, and the index after it is
    /// [`SENTINEL`]. The plan's own changes before them stay as they are unless the two overlap
    /// ([`Self::fits_after`]); its summary and length are left as they are.
    pub fn seal_at_end(&mut self, changes: &[(u64, i64)], direction: i64) -> u16 {
        let count = changes.len().min(MAX_CHANGES - 1);
        let first = MAX_CHANGES - 1 - count;
        for (index, &(hold, jerk)) in changes[..count].iter().enumerate() {
            let at = first + index;
            self.runs[at] = Run::new(jerk * direction, hold, at as u16 + 1);
        }
        self.runs[MAX_CHANGES - 1] = Run::END;
        first as u16
    }

    /// Whether `count` changes and an end marker fit after the plan's changes
    /// ([`Self::seal_at_end`] then leaves them intact).
    pub fn fits_after(&self, count: usize) -> bool {
        self.len + count < MAX_CHANGES
    }

    /// The runs of the sealed replay, `(cycles, jerk)` in order, the end marker left out.
    pub fn runs(&self) -> impl Iterator<Item = (u64, i64)> + '_ {
        let runs = self.len.saturating_sub(1);
        self.runs[..runs].iter().map(|run| (run.cycles(), run.jerk))
    }

    /// Adds `amount` on `cycle` to the main move's changes (the top `main_len` entries), keeping
    /// them sorted: the corners arrive latest first, so a change goes in at the front, or a step
    /// or two in, or is added to a change on the same cycle.
    fn prepend(&mut self, cycle: u64, amount: i64) {
        // Modulo 2^32 (see `runs`): the truncation is the residue.
        let amount = amount as i32;
        let start = MAX_CHANGES - self.main_len.min(MAX_CHANGES);
        let mut at = start;
        while at < MAX_CHANGES && self.runs[at].cycle() < cycle {
            at += 1;
        }
        if at < MAX_CHANGES && self.runs[at].cycle() == cycle {
            let residue = self.runs[at].residue().wrapping_add(amount);
            self.runs[at] = Run::main_change(cycle, residue);
            return;
        }
        if start + MAX_MAIN_CHANGES <= MAX_CHANGES {
            return; // Unreachable: the main move has at most MAX_MAIN_CHANGES (see MAX_CHANGES).
        }
        // A step or two at most: a loop, not a library call.
        for k in start..at {
            self.runs[k - 1] = self.runs[k];
        }
        self.runs[at - 1] = Run::main_change(cycle, amount);
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
    /// holds, from index 0, closed by an end marker (setting the jerk to zero for good: the
    /// acceleration and velocity are zero there already; [`Run::END`]).
    ///
    /// One forward pass merges the three streams of notch changes (each pair's eight changes
    /// come in order: a jerk of ±1 on one cycle is a change by ±1 on it and back on the next)
    /// into the main move's, adds up changes on the same cycle and drops changes that leave the
    /// jerk as it was (and those on or after the last cycle), which would cost a replay's slow
    /// path for nothing. The runs are written from the start of the array while the main
    /// move's changes are read from its end: after `r` main and `n` notch changes at most
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
        // end.
        let mut queue = [Stream::<C>::DONE; MAX_NOTCHES];
        for (stream, notch) in queue.iter_mut().zip(placement.notches()) {
            *stream = Stream::new(notch);
        }
        queue.sort_unstable_by_key(|stream| stream.cycle);
        let sign = direction as i32;
        let mut sealing = Sealing {
            written: 0,
            from: C::narrow(0),
            jerk: 0,
            open_cycles: C::narrow(0),
            open_jerk: i32::MIN,
        };
        // The main move's changes in order, each after the notch changes before it (a notch
        // change on the same cycle comes after it: the two add up either way).
        for main in MAX_CHANGES - self.main_len.min(MAX_CHANGES)..MAX_CHANGES {
            // Both read before any run is written (the writing stays behind, see above).
            let (cycle, residue) = (
                C::narrow(self.runs[main].cycle()).min(total),
                self.runs[main].residue(),
            );
            while queue[0].cycle < cycle {
                let at = queue[0].cycle;
                let amount = next_notch_change(&mut queue);
                sealing.change(&mut self.runs, at, amount * sign);
            }
            if cycle == total {
                break;
            }
            sealing.change(&mut self.runs, cycle, residue);
        }
        while queue[0].cycle < total {
            let at = queue[0].cycle;
            let amount = next_notch_change(&mut queue);
            sealing.change(&mut self.runs, at, amount * sign);
        }
        // The last run ends on the last cycle; the end marker follows it.
        sealing.change(&mut self.runs, total, 0);
        sealing.write_open(&mut self.runs);
        self.runs[sealing.written] = Run::END;
        self.len = sealing.written + 1;
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
        let main = MainMove::of_groups(&groups);
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
