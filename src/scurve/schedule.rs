//! The schedule: the plan as a sorted list of jerk changes, built once for the plan that won, and
//! its one pass that finds the move's peaks (and confirms its limits).

use super::remainder::{Placement, MAX_NOTCHES};
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

/// At most this many jerk changes (after changes on the same cycle are added up): the main move's
/// four kinds of unit, with first ramps `a − 1` or `a`, second ramps `b − 1` or `b` and phase V
/// from `c − 1` or `c`, have their eight corners on at most 1 + 2 + 2 + 3 + 2 + 3 + 3 + 4 = 20
/// cycles; two fine units add at most 10 more, three notch pairs 24 (fine units and notch pairs
/// never come together): 44, and the end marker — 64, a power of two, so that a replay indexes
/// it with a mask instead of a bounds check.
pub(super) const MAX_CHANGES: usize = 64;

/// The index of the sentinel, a change that holds no cycle (never written: a schedule has at
/// most 45 changes). A replay pointed at it takes the slow path on its next event.
pub(super) const SENTINEL: usize = MAX_CHANGES - 1;

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
    /// While building: the cycle of each change (0 = the first step). Sealed: the cycles it
    /// holds.
    holds: [u64; MAX_CHANGES],
    /// While building: the change of the jerk, modulo 2^32 (a change is at most 2J < 2^32, so
    /// it is zero exactly when its residue is, and the running sum of the residues is the jerk,
    /// which fits 32 bits). Sealed: the jerk it sets.
    jerks: [i32; MAX_CHANGES],
    len: usize,
    /// The plan's summary (its peaks zero: [`Self::replay`] finds them when they are asked for).
    pub plan: ScurvePlan,
}

impl Schedule {
    /// No move.
    pub const EMPTY: Self = Self {
        holds: [0; MAX_CHANGES],
        jerks: [0; MAX_CHANGES],
        len: 0,
        plan: ScurvePlan {
            phases: [0; 7],
            total: 0,
            peak_acceleration: 0,
            peak_velocity: 0,
        },
    };

    /// The sealed change at `index` modulo [`MAX_CHANGES`] (no bounds check on the replay's
    /// path).
    #[inline]
    pub fn change(&self, index: usize) -> JerkChange {
        JerkChange {
            hold: self.holds[index % MAX_CHANGES],
            jerk: i64::from(self.jerks[index % MAX_CHANGES]),
        }
    }

    /// How many changes the sealed replay has, its end marker included.
    pub fn len(&self) -> usize {
        self.len
    }

    /// No move.
    pub fn clear(&mut self) {
        self.len = 0;
        self.plan = ScurvePlan::default();
    }

    /// Makes this a move of one raw unit: a velocity of 1 on one cycle (jerk +1, −2, +1).
    pub fn single_unit(&mut self, direction: i64) {
        self.clear();
        for (cycle, amount) in [(0, 1), (1, -3), (2, 3)] {
            self.add(cycle, amount * direction);
        }
        self.plan = ScurvePlan {
            phases: [1, 0, 1, 0, 0, 0, 1],
            total: 3,
            peak_acceleration: 0,
            peak_velocity: 0,
        };
        self.seal();
    }

    /// The runs of the sealed replay, `(cycles, jerk)` in order, the end marker left out.
    pub fn runs(&self) -> impl Iterator<Item = (u64, i64)> + '_ {
        let runs = self.len.saturating_sub(1);
        self.holds[..runs]
            .iter()
            .zip(&self.jerks[..runs])
            .map(|(&hold, &jerk)| (hold, i64::from(jerk)))
    }

    /// Adds `amount` on `cycle`, keeping the list sorted: from the end back to its place (the
    /// group corners arrive slot by slot, nearly in order, so this is a step or two each), added
    /// to a change on the same cycle.
    fn add(&mut self, cycle: u64, amount: i64) {
        // Modulo 2^32 (see `jerks`): the truncation is the residue.
        let amount = amount as i32;
        let mut at = self.len.min(SENTINEL - 1);
        while at > 0 && self.holds[at - 1] > cycle {
            at -= 1;
        }
        if at > 0 && self.holds[at - 1] == cycle {
            self.jerks[at - 1] = self.jerks[at - 1].wrapping_add(amount);
            return;
        }
        if self.len + 1 >= SENTINEL {
            return; // Unreachable: MAX_CHANGES covers every group and pair, and the marker.
        }
        // A step or two back at most: a loop, not a library call.
        let mut k = self.len;
        while k > at {
            self.holds[k] = self.holds[k - 1];
            self.jerks[k] = self.jerks[k - 1];
            k -= 1;
        }
        self.holds[at] = cycle;
        self.jerks[at] = amount;
        self.len += 1;
    }

    /// Makes this the schedule of `main` less the notch pairs of `placement`, in the direction
    /// `direction` (±1), with `plan` as its summary, and seals it ([`Self::seal`]).
    pub fn build(
        &mut self,
        main: &MainMove,
        placement: &Placement,
        direction: i64,
        plan: ScurvePlan,
    ) {
        self.len = 0;
        self.plan = plan;
        // The groups of a unit mix differ from the longest ramps and cruise (a, b, c) by at most
        // one cycle each, so the eight corners of all of them fall on at most 20 cycles: the
        // corner `s` of a group with ramps one shorter by (δa, δb, δc) lands δ = the sum of the
        // δs it includes before the longest group's. Their changes are added up in a table
        // first (no search), then appended in order; groups further off (fine units) are added
        // corner by corner.
        let (a, b, c) = (main.most(|g| g.a), main.most(|g| g.b), main.most(|g| g.c));
        // Counts of at most J < 2^31 units each, with their sign: 32 bits.
        let mut table = [[0i32; 4]; 8];
        for group in main.groups() {
            let (da, db, dc) = (a - group.a, b - group.b, c - group.c);
            let count = group.count as i32 * direction as i32;
            if da > 1 || db > 1 || dc > 1 {
                for (cycle, sign) in corners(group.a, group.b, group.c) {
                    self.add(cycle, sign * i64::from(count));
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
        for (slot, (base, sign)) in corners(a, b, c).into_iter().enumerate() {
            for delta in (0..4).rev() {
                let amount = table[slot][delta];
                if amount != 0 {
                    // base ≥ δ: a shorter ramp or cruise is still at least one cycle.
                    self.add(base - delta as u64, sign * i64::from(amount));
                }
            }
        }
        if !placement.notches().is_empty() {
            self.merge(placement, direction);
        }
        self.seal();
    }

    /// Merges the notch pairs of `placement` into the sorted changes.
    fn merge(&mut self, placement: &Placement, direction: i64) {
        // A jerk of ±1 on one cycle is a change by ±1 on it and back on the next. The pairs'
        // changes, sorted apart (at most 24), are merged in from the end in one pass.
        let mut cycles = [0u64; 8 * MAX_NOTCHES];
        let mut amounts = [0i32; 8 * MAX_NOTCHES];
        let mut count = 0;
        for notch in placement.notches() {
            for (cycle, amount) in notch.impulses() {
                let amount = (amount * direction) as i32;
                for (cycle, amount) in [(cycle, amount), (cycle + 1, -amount)] {
                    let mut k = count;
                    while k > 0 && cycles[k - 1] > cycle {
                        cycles[k] = cycles[k - 1];
                        amounts[k] = amounts[k - 1];
                        k -= 1;
                    }
                    cycles[k] = cycle;
                    amounts[k] = amount;
                    count += 1;
                }
            }
        }
        let (mut i, mut k) = (self.len, count);
        let mut write = (self.len + count).min(SENTINEL - 2);
        self.len = write;
        while k > 0 && write > 0 {
            write -= 1;
            if i > 0 && self.holds[i - 1] > cycles[k - 1] {
                self.holds[write] = self.holds[i - 1];
                self.jerks[write] = self.jerks[i - 1];
                i -= 1;
            } else {
                self.holds[write] = cycles[k - 1];
                self.jerks[write] = amounts[k - 1];
                k -= 1;
            }
        }
    }

    /// Makes the built schedule (changes sorted by cycle) a replay: runs of constant jerk, each
    /// the jerk it sets and the cycles it holds, closed by an end marker (setting the jerk to
    /// zero, held for ever: the acceleration and velocity are zero there already). Changes on the
    /// same cycle are added up; changes that leave the jerk as it was, and those on or after the
    /// last cycle, would cost a replay's slow path for nothing and are dropped. The replay
    /// starts with the run from cycle 0 (of zero jerk if nothing changes there).
    fn seal(&mut self) {
        let total = self.plan.total;
        // At most one run per change and the one from cycle 0, then the marker: all before the
        // sentinel.
        let len = self.len.min(SENTINEL - 2);
        // The run open from cycle `start` with jerk `jerk`; runs before `written` are sealed.
        // Each run is written at or before the change being read, which is read first.
        let (mut written, mut start, mut jerk) = (0, 0u64, 0i32);
        for i in 0..=len {
            let (cycle, change) = if i < len {
                (self.holds[i].min(total), self.jerks[i])
            } else {
                (total, 0)
            };
            if cycle != start {
                if written > 0 && self.jerks[written - 1] == jerk {
                    self.holds[written - 1] += cycle - start;
                } else {
                    self.holds[written] = cycle - start;
                    self.jerks[written] = jerk;
                    written += 1;
                }
                start = cycle;
            }
            // The running sum modulo 2^32 is the jerk (see `jerks`).
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
