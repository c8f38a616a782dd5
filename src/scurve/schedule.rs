//! The schedule: the plan as a sorted list of jerk changes, built once for the plan that won, and
//! its one pass that finds the move's peaks (and confirms its limits).

use fixed::types::I32F32;

use super::remainder::{Placement, MAX_NOTCHES};
use super::shape::{corners, Group, MainMove};
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

/// At most this many changes of the main move are written ([`Changes::add_main`]): one for each
/// corner of the longest units and each of its shortenings (1 + 2 + 2 + 3 + 2 + 3 + 3 + 4 = 20,
/// see [`MAX_CHANGES`]), eight for each of at most two fine units.
const MAX_MAIN_CHANGES: usize = 20 + 2 * 8;

/// At most this many changes from notch pairs: eight per pair.
const MAX_NOTCH_CHANGES: usize = 8 * MAX_NOTCHES;

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
        // Truncated: this width is taken only for a move shorter than 2^31 cycles, whose cycles
        // (and a cycle after them) fit; a saturating conversion cost two instructions a
        // change.
        cycle as u32
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

/// Jerk changes, put in the order of their cycles once all are written ([`Self::sort`]): each
/// the change of the jerk modulo 2^32 (a change is at most 2J < 2^32, so it is zero exactly
/// when its residue is, and the running sum of the residues is the jerk, which fits 32 bits).
/// Changes on the same cycle stay apart: the sealing pass adds them up.
///
/// Two sentinels spare the loops their tests of the ends: the first slot holds cycle 0 with no
/// change, so a scan from the back stops there; the slots past the last change hold
/// [`Cycle::NEVER`], at least one of them, so a merge of two lists ends on them without
/// counting what is left of each ([`Schedule::seal`]). Two arrays, not one of pairs: the
/// sort's scan reads the cycles alone.
struct Changes<C, const SLOTS: usize> {
    cycles: [C; SLOTS],
    residues: [i32; SLOTS],
    len: usize,
}

impl<C: Cycle, const SLOTS: usize> Changes<C, SLOTS> {
    /// No changes (but the sentinel on cycle 0).
    fn new() -> Self {
        let mut cycles = [C::NEVER; SLOTS];
        cycles[0] = C::narrow(0);
        Self {
            cycles,
            residues: [0; SLOTS],
            len: 1,
        }
    }

    /// Adds `residue` on `cycle` to the sorted changes, in its place (added to a change on the
    /// same cycle, if any): the few changes of groups off the table ([`Self::add_main`]), which
    /// must not take more slots than they have distinct cycles. A change past the last free
    /// slot (none comes: see [`MAX_CHANGES`]) is dropped, the sentinel kept.
    fn insert(&mut self, cycle: C, residue: i32) {
        let mut at = self.len.min(SLOTS - 1);
        // Stops on the first slot at the latest: cycle 0 is no later than any.
        while at > 1 && self.cycles[at - 1] > cycle {
            at -= 1;
        }
        if self.cycles[at - 1] == cycle {
            self.residues[at - 1] = self.residues[at - 1].wrapping_add(residue);
            return;
        }
        if self.len + 1 >= SLOTS {
            return;
        }
        self.cycles[self.len] = cycle;
        self.residues[self.len] = residue;
        self.len += 1;
        self.settle(self.len - 1);
    }

    /// Puts the changes in the order of their cycles: an insertion sort, which costs a
    /// comparison a change and a move a step out of place, as they were written nearly in
    /// order (a unit's corners in theirs, a notch pair's too; corners within three cycles of
    /// each other, and notch pairs that overlap, a few steps apart).
    fn sort(&mut self) {
        for next in 2..self.len.min(SLOTS) {
            self.settle(next);
        }
    }

    /// Moves the change at `index` back past the later changes before it (those before it in
    /// order already).
    #[inline(always)]
    fn settle(&mut self, index: usize) {
        let (cycle, residue) = (self.cycles[index], self.residues[index]);
        let mut at = index;
        // Stops on the first slot at the latest: cycle 0 is no later than any.
        while at > 1 && self.cycles[at - 1] > cycle {
            self.cycles[at] = self.cycles[at - 1];
            self.residues[at] = self.residues[at - 1];
            at -= 1;
        }
        self.cycles[at] = cycle;
        self.residues[at] = residue;
    }

    /// Writes the main move's changes, in the direction `sign` (±1), and sorts them.
    ///
    /// The groups of a unit mix differ from the longest ramps and cruise `(a, b, c)` by at most
    /// one cycle each, so the eight corners of all of them fall on at most 20 cycles: the corner
    /// `s` of a group with ramps shorter by `(δa, δb, δc)` lands `δ` = the sum of the `δ`s it
    /// includes before the longest group's. Their counts are added up in a table first (no
    /// search), then written corner by corner, each corner's cycles from the earliest: in order,
    /// but where two corners are within three cycles. Groups further off (fine units, and the
    /// main units where only fine units set the longest phase V) are then inserted corner by
    /// corner, each added to a change on its cycle if there is one: their corners are many,
    /// their cycles few.
    fn add_main(&mut self, main: &MainMove, sign: i32) {
        let (a, b, c) = main.longest_units();
        let near = |g: &Group| {
            (a - 1..=a).contains(&g.a) && (b - 1..=b).contains(&g.b) && (c - 1..=c).contains(&g.c)
        };
        // Counts of at most J < 2^31 units in all, with their sign: 32 bits.
        let mut table = [[0i32; 4]; 8];
        let mut far = false;
        for group in main.groups() {
            if !near(group) {
                far = true;
                continue;
            }
            let count = group.count as i32 * sign;
            let (da, db, dc) = (
                (a - group.a) as usize,
                (b - group.b) as usize,
                (c - group.c) as usize,
            );
            for (slot, delta) in [0, da, db, da + db, dc, dc + da, dc + db, dc + da + db]
                .into_iter()
                .enumerate()
            {
                // δ ≤ 3 (the mask tells the compiler so).
                table[slot][delta & 3] += count;
            }
        }
        // The largest δ of each corner: the number of ramps and cruises it includes.
        const MOST_DELTA: [usize; 8] = [0, 1, 1, 2, 1, 2, 2, 3];
        // At most 20 changes (see MAX_MAIN_CHANGES), counted in a local: the compiler keeps
        // it in a register, where a field is reloaded after every write to the arrays.
        let mut len = self.len;
        // Whether a change came before the one written ahead of it: only then is there a sort
        // to do (when two corners are within three cycles: about one move in five).
        let (mut latest, mut out_of_order) = (C::narrow(0), false);
        for (slot, (base, corner)) in corners(a, b, c).into_iter().enumerate() {
            for delta in (0..=MOST_DELTA[slot]).rev() {
                let count = table[slot][delta];
                if count != 0 && len < SLOTS - 1 {
                    // base ≥ δ: a shorter ramp or cruise is still at least one cycle.
                    let cycle = C::narrow(base - delta as u64);
                    out_of_order |= cycle < latest;
                    latest = cycle;
                    self.cycles[len] = cycle;
                    self.residues[len] = corner as i32 * count;
                    len += 1;
                }
            }
        }
        self.len = len;
        if out_of_order {
            self.sort();
        }
        if far {
            for group in main.groups().iter().filter(|g| !near(g)) {
                let count = group.count as i32 * sign;
                for (cycle, corner) in corners(group.a, group.b, group.c) {
                    self.insert(C::narrow(cycle), corner as i32 * count);
                }
            }
        }
    }

    /// Writes the notch pairs' changes, in the direction `sign` (±1), in order.
    ///
    /// A pair lowers the acceleration by one unit at `s` and raises it back at `s + w`, and
    /// later raises it at `s + k` and lowers it back at `s + k + w` (`1 ≤ w < k`): four jerk
    /// impulses, each a change on its cycle and the reverse on the next. The impulses of all
    /// pairs are put in order first (a pair's own four are in order, so each is inserted a few
    /// steps from the end at most), those on one cycle added up; written out, their changes are
    /// then in order too (an impulse's return on cycle `n + 1` is no later than the next
    /// impulse, on a later cycle). Sorting the changes themselves instead moved twice as many,
    /// where two pairs overlap: ~600 Cortex-M4 instructions of a two-pair plan's build.
    fn add_notches(&mut self, placement: &Placement, sign: i32) {
        // One pair's impulses are in order, on four cycles: written as they are (no table).
        if let [pair] = placement.notches() {
            for (cycle, amount) in pair.impulses() {
                self.add_impulse(cycle, amount as i32 * sign);
            }
            return;
        }
        let mut impulses = [(0u64, 0i32); 4 * MAX_NOTCHES];
        let mut count = 0;
        for notch in placement.notches().iter().take(MAX_NOTCHES) {
            for (cycle, amount) in notch.impulses() {
                let mut at = count;
                while at > 0 && impulses[at - 1].0 > cycle {
                    impulses[at] = impulses[at - 1];
                    at -= 1;
                }
                // ±1 in the direction of the move.
                impulses[at] = (cycle, amount as i32 * sign);
                count += 1;
            }
        }
        let mut next = 0;
        while next < count {
            let (cycle, mut amount) = impulses[next];
            next += 1;
            while next < count && impulses[next].0 == cycle {
                amount += impulses[next].1;
                next += 1;
            }
            if amount != 0 {
                self.add_impulse(cycle, amount);
            }
        }
    }

    /// Adds a jerk of `amount` on `cycle` alone: a change by it there and back on the next, after
    /// the changes written (at most 24, see [`MAX_NOTCH_CHANGES`]; past the last free slot, none
    /// comes, it is dropped).
    #[inline(always)]
    fn add_impulse(&mut self, cycle: u64, amount: i32) {
        let len = self.len;
        if len + 2 < SLOTS {
            let cycle = C::narrow(cycle);
            self.cycles[len] = cycle;
            self.residues[len] = amount;
            self.cycles[len + 1] = cycle + C::narrow(1);
            self.residues[len + 1] = -amount;
            self.len = len + 2;
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
    /// The runs in `[0, len)`, and a smooth stop's at the end of the array. (The empty schedule
    /// is all zeros, which a clear makes, where anything else is a copy from flash twice the
    /// cost on a Cortex-M4.)
    runs: [Run; MAX_CHANGES],
    /// How many runs, the end marker included.
    len: usize,
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
        self.plan = ScurvePlan::default();
    }

    /// Makes this a move of `distance` raw units in three cycles, the fewest any move takes: a
    /// velocity of `distance` on one cycle (jerk `+d, −2d, +d`), for `distance` within the
    /// acceleration and the velocity and at most half the jerk (checked by the caller).
    pub fn pulse(&mut self, distance: u64, direction: i64) {
        // |jerk| ≤ 2d ≤ J < 2^31.
        let d = distance as i64 * direction;
        for (index, jerk) in [d, -2 * d, d].into_iter().enumerate() {
            self.runs[index] = Run::new(jerk, 1, index as u16 + 1);
        }
        self.runs[3] = Run::END;
        self.len = 4;
        self.plan = ScurvePlan {
            phases: [1, 0, 1, 0, 0, 0, 1],
            total: 3,
            peak_acceleration: I32F32::ZERO,
            peak_velocity: I32F32::ZERO,
        };
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

    /// The cruise (phase IV) [`Self::build`] reports for a move of `total` cycles whose main
    /// units' ramps are `(a, b)`: `None` if the move is shorter than its ramps, the one case in
    /// which it builds nothing (a planner that builds last asks this first).
    pub fn cruise(total: u64, (a, b): (u64, u64)) -> Option<u64> {
        total.checked_sub(2 * (a + b))
    }

    /// Makes this the schedule of `main` less the notch pairs of `placement`, in the direction
    /// `direction` (±1), its main units' ramps `(a, b)`, sealed ([`Self::seal`]); `false` (and
    /// nothing built) if the move is shorter than its ramps ([`Self::cruise`]).
    pub fn build(
        &mut self,
        main: &MainMove,
        placement: &Placement,
        direction: i64,
        (a, b): (u64, u64),
    ) -> bool {
        let total = main.total();
        let Some(cruise) = Self::cruise(total, (a, b)) else {
            return false;
        };
        // Written in place, field by field (a summary built apart would be copied in).
        self.plan.phases = [a, b - a, a, cruise, a, b - a, a];
        self.plan.total = total;
        self.plan.peak_acceleration = I32F32::ZERO;
        self.plan.peak_velocity = I32F32::ZERO;
        let sign = direction as i32;
        if total < 1 << 31 {
            self.seal_from::<u32>(main, placement, sign, total as u32);
        } else {
            self.seal_from::<u64>(main, placement, sign, total);
        }
        true
    }

    /// Makes this the schedule of the units of `groups` alone (no notch pairs), all starting on
    /// cycle 0, in the direction `direction` (±1), its phases those of the first group's ramps,
    /// sealed; `false` (and nothing built) if the move is longer than [`MAX_CHANGES`] − 1
    /// cycles or `groups` is empty. For the short moves of [`super::volumes`]: their changes,
    /// a few groups' corners on at most that many cycles, are added up per cycle in a table
    /// and read off in one pass (no sorted lists to merge).
    pub fn build_short(&mut self, groups: &[Group], direction: i64) -> bool {
        let total = groups.iter().map(|g| g.a + g.b + g.c).max().unwrap_or(0);
        let Some(first) = groups.first() else {
            return false;
        };
        if total >= MAX_CHANGES as u64 || first.b < first.a || total < 2 * (first.a + first.b) {
            return false;
        }
        // The jerk's change on each cycle; a unit's last corner, on the move's last cycle or
        // before, is not a change within it (the end marker zeroes the jerk there).
        let mut changes = [0i64; MAX_CHANGES];
        for group in groups {
            // count ≤ J < 2^31: every sum here stays within ±2^33.
            let count = group.count as i64 * direction;
            for (cycle, corner) in corners(group.a, group.b, group.c) {
                // cycle < total < MAX_CHANGES.
                if cycle < total {
                    changes[cycle as usize] += corner * count;
                }
            }
        }
        let total = total as usize;
        let jerks = changes[..total].iter().scan(0i64, |jerk, &change| {
            *jerk += change;
            Some(*jerk)
        });
        self.seal_per_cycle(jerks);
        let (a, b) = (first.a, first.b);
        self.plan = ScurvePlan {
            phases: [a, b - a, a, total as u64 - 2 * (a + b), a, b - a, a],
            total: total as u64,
            peak_acceleration: I32F32::ZERO,
            peak_velocity: I32F32::ZERO,
        };
        true
    }

    /// Makes this the schedule of `jerks`, the jerk (raw units, signed as the move goes) on
    /// each of the move's cycles in turn, its plan's phases `phases`, sealed; `false` (and
    /// nothing built) if the move is longer than [`MAX_CHANGES`] − 1 cycles. For
    /// [`super::tiny`]'s tabled plans, a dozen cycles or so.
    pub fn build_per_cycle(&mut self, jerks: &[i64], phases: [u64; 7]) -> bool {
        if jerks.len() >= MAX_CHANGES {
            return false;
        }
        self.seal_per_cycle(jerks.iter().copied());
        self.plan = ScurvePlan {
            phases,
            total: jerks.len() as u64,
            peak_acceleration: I32F32::ZERO,
            peak_velocity: I32F32::ZERO,
        };
        true
    }

    /// Seals the jerk on each cycle of a move of fewer than [`MAX_CHANGES`] cycles, in turn,
    /// as runs: cycles of equal jerk are one run, closed by the end marker (setting the jerk to
    /// zero for good: the move is at rest after its last cycle).
    fn seal_per_cycle(&mut self, mut jerks: impl Iterator<Item = i64>) {
        let mut written = 0;
        if let Some(first) = jerks.next() {
            let (mut start, mut run_jerk, mut cycle) = (0u32, first, 1);
            for jerk in jerks {
                if jerk != run_jerk {
                    self.write_run(&mut written, cycle - start, run_jerk);
                    (start, run_jerk) = (cycle, jerk);
                }
                cycle += 1;
            }
            self.write_run(&mut written, cycle - start, run_jerk);
        }
        self.runs[written] = Run::END;
        self.len = written + 1;
    }

    /// [`Self::seal`]s the changes of `main` and `placement` in the direction `sign`, its cycles
    /// of type `C`.
    fn seal_from<C: Cycle>(&mut self, main: &MainMove, placement: &Placement, sign: i32, total: C) {
        let mut main_changes = Changes::<C, { MAX_MAIN_CHANGES + 2 }>::new();
        main_changes.add_main(main, sign);
        let mut notch_changes = Changes::<C, { MAX_NOTCH_CHANGES + 2 }>::new();
        notch_changes.add_notches(placement, sign);
        self.seal(&main_changes, &notch_changes, total);
    }

    /// Makes the main move's changes and the notch pairs' (each in order, [`Changes`]) a
    /// replay of `total` cycles: runs of constant jerk, each the jerk it sets and the cycles it
    /// holds, from index 0, closed by an end marker (setting the jerk to zero for good: the
    /// acceleration and velocity are zero there already; [`Run::END`]).
    ///
    /// One forward pass merges the two lists (each ends in [`Cycle::NEVER`], so the merge
    /// reads on without a test of its length: the end is the first change on or after the last
    /// cycle, the main move's last corner at the latest), adds up changes on the same cycle and
    /// drops changes that leave the jerk as it was (and those on or after the last cycle),
    /// which would cost a replay's slow path for nothing. The cycles are 32 bits wide for a
    /// move shorter than 2^31 cycles (most moves: a 32-bit core then compares two cycles in one
    /// instruction, not three), 64 otherwise.
    fn seal<C: Cycle, const MAIN: usize, const NOTCHES: usize>(
        &mut self,
        main: &Changes<C, MAIN>,
        notches: &Changes<C, NOTCHES>,
        total: C,
    ) {
        let zero = C::narrow(0);
        // The changes on cycle 0 (the sentinels among them, see [`Changes`]): the first run's.
        let (mut next_main, mut next_notch, mut jerk) = (0, 0, 0i32);
        while next_main < MAIN && main.cycles[next_main] == zero {
            jerk = jerk.wrapping_add(main.residues[next_main]);
            next_main += 1;
        }
        while next_notch < NOTCHES && notches.cycles[next_notch] == zero {
            jerk = jerk.wrapping_add(notches.residues[next_notch]);
            next_notch += 1;
        }
        // The open run starts on `start` at `run_jerk`; the changes on cycle `at` read so far
        // make the jerk `jerk`.
        let (mut start, mut run_jerk, mut at, mut written) = (zero, jerk, zero, 0);
        loop {
            let main_cycle = main.cycles.get(next_main).copied().unwrap_or(C::NEVER);
            let notch_cycle = notches.cycles.get(next_notch).copied().unwrap_or(C::NEVER);
            // A notch change on the same cycle as the main move's comes after it: the two add
            // up either way.
            let (cycle, residue) = if notch_cycle < main_cycle {
                next_notch += 1;
                (notch_cycle, notches.residues[next_notch - 1])
            } else {
                next_main += 1;
                (main_cycle, main.residues[next_main - 1])
            };
            if cycle != at {
                if cycle >= total {
                    break;
                }
                // The jerk from `at` on is `jerk`: a new run unless it is the open run's.
                if jerk != run_jerk {
                    self.write_run(&mut written, at - start, i64::from(run_jerk));
                    (start, run_jerk) = (at, jerk);
                }
                at = cycle;
            }
            jerk = jerk.wrapping_add(residue);
        }
        // The jerk from `at` to the last cycle is `jerk`; the end marker follows.
        if jerk != run_jerk {
            self.write_run(&mut written, at - start, i64::from(run_jerk));
            start = at;
        }
        self.write_run(&mut written, total - start, i64::from(jerk));
        self.runs[written] = Run::END;
        self.len = written + 1;
    }

    /// Writes the run of `cycles` at `jerk` at index `written`, moving on; the slots before the
    /// end marker's are enough (see [`MAX_CHANGES`]).
    #[inline(always)]
    fn write_run<C: Cycle>(&mut self, written: &mut usize, cycles: C, jerk: i64) {
        if *written < MAX_CHANGES - 1 {
            self.runs[*written] = cycles.run(jerk, *written as u16 + 1);
            *written += 1;
        }
    }

    /// Whether the sealed schedule, replayed in `direction`, keeps `limits` on every cycle, ends
    /// at rest and covers exactly `distance` (2^-32 counts): what every planner's debug
    /// assertion checks of the plan it made.
    pub fn lands(&self, direction: i64, limits: Limits64, distance: u64) -> bool {
        let replay = self.replay(direction, limits);
        replay.within_limits && replay.distance == i128::from(distance)
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
            // n* = ⌊−a/j − ½⌋ or the cycle after, where it is v + a·n + j·n(n+1)/2. The floor
            // is taken with a positive divisor: `div_euclid` by a negative one rounds up (it
            // keeps the remainder ≥ 0), and with j < 0 (a peak, not a dip) the replay then
            // looked at the two cycles after the peak and reported a peak velocity two raw
            // units low (a plan of four kinds of unit, found by `random_moves`).
            if first.signum() * last.signum() < 0 {
                let (numerator, divisor) = if jerk < 0 {
                    (2 * acceleration + jerk, -2 * jerk)
                } else {
                    (-2 * acceleration - jerk, 2 * jerk)
                };
                let turn = numerator.div_euclid(divisor);
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
    use crate::scurve::remainder::Notch;

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
        assert_runs_are_the_jerk(&main, &placement, (443, 444));
    }

    /// Checks that the schedule built of `main` and `placement` (in both directions) is, cycle
    /// by cycle, the main move's jerk plus the pairs' impulses, that it lasts the move's
    /// cycles, and that no two runs in a row have the same jerk (each would cost the replay a
    /// change for nothing). Moves longer than 20,000 cycles are checked on each run's first and
    /// last cycle (the jerk is constant between changes either way).
    fn assert_runs_are_the_jerk(main: &MainMove, placement: &Placement, ramps: (u64, u64)) {
        let total = main.total();
        let expected = |n: u64| {
            let impulses: i64 = placement
                .notches()
                .iter()
                .flat_map(|notch| notch.impulses())
                .filter(|&(at, _)| at == n)
                .map(|(_, amount)| amount)
                .sum();
            main.jerk_at(n) + impulses
        };
        for direction in [1, -1] {
            let mut schedule = Schedule::EMPTY;
            assert!(schedule.build(main, placement, direction, ramps));
            let (mut cycle, mut last_jerk) = (0u64, None);
            for (hold, jerk) in schedule.runs() {
                assert!(hold >= 1);
                assert_ne!(Some(jerk), last_jerk, "two runs at one jerk, cycle {cycle}");
                let checked: &mut dyn Iterator<Item = u64> = if total <= 20_000 {
                    &mut (cycle..cycle + hold)
                } else {
                    &mut [cycle, cycle + hold - 1].into_iter()
                };
                for n in checked {
                    assert_eq!(jerk, direction * expected(n), "cycle {n}");
                }
                (cycle, last_jerk) = (cycle + hold, Some(jerk));
            }
            assert_eq!(cycle, total);
            assert_eq!(schedule.run(schedule.len() - 1), Run::END);
        }
    }

    /// A mix with a fine unit whose phase V starts after every main unit's: the main units are
    /// then off the table of their own longest ramps and are inserted corner by corner, on as
    /// many slots as they have cycles (a case a debug assertion of the planner caught).
    #[test]
    fn fine_units_later_than_the_main_units() {
        let group = |count, a, b, c| Group { count, a, b, c };
        let groups = [
            group(14_294_443, 4, 5, 11),
            group(9_119_693, 4, 5, 10),
            group(2_881_831, 4, 4, 11),
            group(1, 4, 4, 10),
            group(1, 3, 5, 11),
            group(1, 3, 5, 10),
            group(1, 1, 1, 14),
        ];
        assert_runs_are_the_jerk(&MainMove::of_groups(&groups), &Placement::default(), (4, 5));
    }

    /// A move of more than 2^31 cycles is sealed in 64-bit cycles, with laps.
    #[test]
    fn moves_longer_than_2_pow_31_cycles() {
        let group = |count, a, b, c| Group { count, a, b, c };
        let c = (1 << 33) + 7;
        let groups = [group(3, 20, 25, c), group(2, 19, 25, c - 1)];
        let placement = Placement::default().with(Notch {
            start: 30,
            width: 3,
            span: c - 40,
        });
        assert_runs_are_the_jerk(&MainMove::of_groups(&groups), &placement, (20, 25));
    }

    proptest::proptest! {
        #![proptest_config(proptest::prelude::ProptestConfig::with_cases(2_000))]

        /// Any mix of units within a cycle of the longest ramps and phase V start, and up to
        /// two fine units anywhere or up to three notch pairs anywhere inside the move (on the
        /// same cycles or not, overlapping or not), seal to the move's jerk.
        #[test]
        fn sealed_runs_are_the_jerk_of_any_mix(
            (a, b, cruise) in (1u64..12, 0u64..12, 0u64..40),
            kinds in proptest::collection::vec((0u64..2, 0u64..2, 0u64..2, 1u64..1_000), 1..8),
            fine in proptest::collection::vec(0u64..1_000, 0..3),
            notches in proptest::collection::vec((0u64..1_000, 1u64..5, 0u64..1_000), 0..4),
        ) {
            let b = a + b;
            let c = a + b + cruise;
            let mut groups: Vec<Group> = kinds
                .iter()
                .map(|&(da, db, dc, count)| {
                    let (a, b) = ((a - da).max(1), (b - db).max((a - da).max(1)));
                    // Phase V starts after phase III ends (with no cruise, a shorter phase V
                    // start would come first: not a triple box).
                    Group { count, a, b, c: (c - dc).max(a + b) }
                })
                .collect();
            let total = groups.iter().map(|g| g.a + g.b + g.c).max().unwrap();
            for x in fine {
                if total >= 4 {
                    groups.push(Group { count: 1, a: 1, b: 1, c: 2 + x % (total - 3) });
                }
            }
            let mut placement = Placement::default();
            // Fine units and notch pairs never come together (see MAX_CHANGES).
            let notches = if groups.len() > kinds.len() { Vec::new() } else { notches };
            for (start, width, span) in notches {
                // Inside the move: its last change, s + k + w + 1, before the last cycle.
                let Some(room) = total.checked_sub(width + 4) else { continue };
                let span = width + 1 + span % room.max(1);
                let Some(starts) = total.checked_sub(span + width + 2) else { continue };
                placement = placement.with(Notch { start: start % starts.max(1), width, span });
            }
            assert_runs_are_the_jerk(&MainMove::of_groups(&groups), &placement, (1, 1));
        }

        /// Any few groups of units of at most 35 cycles, each its own triple box: the short
        /// build is their jerk cycle by cycle, in both directions, and the replay's peaks,
        /// distance and limits check are those of stepping it cycle by cycle (acceleration,
        /// then velocity, then position, as the generator steps).
        #[test]
        fn short_builds_are_the_units_and_replay_as_stepped(
            units in proptest::collection::vec((1u64..9, 0u64..9, 0u64..18, 1u64..1_000), 1..6),
        ) {
            let groups: Vec<Group> = units
                .iter()
                .map(|&(a, more, cruise, count)| {
                    let b = a + more;
                    Group { count, a, b, c: a + b + cruise }
                })
                .filter(|g| g.a + g.b + g.c <= 35)
                .collect();
            proptest::prop_assume!(!groups.is_empty());
            let total = groups.iter().map(|g| g.a + g.b + g.c).max().unwrap();
            let main = MainMove::of_groups(&groups);
            for direction in [1, -1] {
                let mut schedule = Schedule::EMPTY;
                // The first group's ramps name the phases: only a longer move is refused.
                let first = groups[0];
                let fits = total >= 2 * (first.a + first.b);
                proptest::prop_assert_eq!(schedule.build_short(&groups, direction), fits);
                if !fits {
                    continue;
                }
                proptest::prop_assert_eq!(schedule.plan.total, total);
                let (mut cycle, mut last_jerk) = (0u64, None);
                let (mut acceleration, mut velocity, mut distance) = (0i128, 0i128, 0i128);
                let (mut peak_acceleration, mut peak_velocity) = (0i128, 0i128);
                for (hold, jerk) in schedule.runs() {
                    proptest::prop_assert!(hold >= 1);
                    proptest::prop_assert_ne!(Some(jerk), last_jerk);
                    for n in cycle..cycle + hold {
                        proptest::prop_assert_eq!(jerk, direction * main.jerk_at(n));
                        acceleration += i128::from(jerk * direction);
                        velocity += acceleration;
                        distance += velocity;
                        peak_acceleration = peak_acceleration.max(acceleration.abs());
                        peak_velocity = peak_velocity.max(velocity);
                    }
                    (cycle, last_jerk) = (cycle + hold, Some(jerk));
                }
                proptest::prop_assert_eq!(cycle, total);
                proptest::prop_assert_eq!((acceleration, velocity), (0, 0));
                let covered: u64 = groups.iter().map(|g| g.count * g.a * g.b * g.c).sum();
                proptest::prop_assert_eq!(distance, i128::from(covered));
                let units: u64 = groups.iter().map(|g| g.count).sum();
                let limits = Limits64 {
                    jerk: units,
                    acceleration: u64::MAX >> 2,
                    velocity: u64::MAX >> 2,
                };
                let replay = schedule.replay(direction, limits);
                proptest::prop_assert!(replay.within_limits);
                proptest::prop_assert_eq!(replay.distance, distance);
                proptest::prop_assert_eq!(i128::from(replay.peak_velocity), peak_velocity);
                proptest::prop_assert_eq!(i128::from(replay.peak_acceleration), peak_acceleration);
                // One raw unit under the peak velocity is a limit broken on the cycle of it.
                let under = Limits64 { velocity: peak_velocity as u64 - 1, ..limits };
                proptest::prop_assert!(!schedule.replay(direction, under).within_limits);
            }
        }
    }
}
