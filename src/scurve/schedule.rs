//! The schedule: the plan as a sorted list of jerk changes, built once for the plan that won, and
//! its one pass that finds the move's peaks (and confirms its limits).

use super::remainder::{Placement, MAX_NOTCHES};
use super::shape::MainMove;
use super::ScurvePlan;

/// A jerk change (2^-32 counts/cycle³, the direction of the move folded in).
///
/// While the schedule is built and checked, `cycle` is the cycle whose acceleration is the first
/// to see the change (0 = the first step) and `amount` the change. Once it is sealed
/// ([`Schedule::seal`]), it is what a replay needs and nothing more: `cycle` is the number of
/// cycles the change holds (to the next one) and `amount` the jerk it sets.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub(super) struct JerkChange {
    /// The cycle of the change; sealed: the cycles it holds.
    pub cycle: u64,
    /// The change of the jerk, raw units; sealed: the jerk from this change on.
    pub amount: i64,
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

/// A plan in force: its sorted jerk changes (one per cycle, changes on the same cycle added up),
/// closed by an end marker on the cycle after the last (which brings the jerk back to zero),
/// and its summary.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) struct Schedule {
    changes: [JerkChange; MAX_CHANGES],
    len: usize,
    /// The plan's summary.
    pub plan: ScurvePlan,
}

impl Schedule {
    /// No move.
    pub const EMPTY: Self = Self {
        changes: [JerkChange {
            cycle: 0,
            amount: 0,
        }; MAX_CHANGES],
        len: 0,
        plan: ScurvePlan {
            phases: [0; 7],
            total: 0,
            peak_acceleration: 0,
            peak_velocity: 0,
        },
    };

    /// The change at `index` modulo [`MAX_CHANGES`] (no bounds check on the replay's path).
    #[inline]
    pub fn change(&self, index: usize) -> JerkChange {
        self.changes[index % MAX_CHANGES]
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
            peak_acceleration: 1,
            peak_velocity: 1,
        };
        self.seal();
    }

    /// The changes, sorted by cycle, at most one per cycle (once sealed: with the end marker, each
    /// holding the cycles to the next).
    pub fn changes(&self) -> &[JerkChange] {
        &self.changes[..self.len]
    }

    /// Adds `amount` on `cycle`, keeping the list sorted: from the end back to its place (the
    /// group corners arrive slot by slot, nearly in order, so this is a step or two each), added
    /// to a change on the same cycle.
    fn add(&mut self, cycle: u64, amount: i64) {
        // Nearly always on the last cycle, or after it.
        if let Some(last) = self
            .len
            .checked_sub(1)
            .map(|i| &mut self.changes[i % MAX_CHANGES])
        {
            if last.cycle == cycle {
                last.amount += amount;
                return;
            }
        }
        let mut at = self.len.min(SENTINEL - 1);
        while at > 0 && self.changes[at - 1].cycle > cycle {
            at -= 1;
        }
        if at > 0 && self.changes[at - 1].cycle == cycle {
            self.changes[at - 1].amount += amount;
            return;
        }
        if self.len + 1 >= SENTINEL {
            return; // Unreachable: MAX_CHANGES covers every group and pair, and the marker.
        }
        let mut k = self.len;
        while k > at {
            self.changes[k] = self.changes[k - 1];
            k -= 1;
        }
        self.changes[at] = JerkChange { cycle, amount };
        self.len += 1;
    }

    /// Inserts `change` before every other.
    fn add_first(&mut self, change: JerkChange) {
        let len = self.len.min(MAX_CHANGES - 2);
        self.changes.copy_within(..len, 1);
        self.changes[0] = change;
        self.len = len + 1;
    }

    /// Makes this the schedule of `main` less the notch pairs of `placement`, in the direction
    /// `direction` (±1), with `plan` as its summary (its peaks filled in by
    /// [`Self::find_peaks`]).
    pub fn build(
        &mut self,
        main: &MainMove,
        placement: &Placement,
        direction: i64,
        plan: ScurvePlan,
    ) {
        self.len = 0;
        self.plan = plan;
        // Slot by slot (the eight corners of a triple box in the order they come), so each
        // change lands at or near the end of the list.
        for slot in 0..8 {
            for group in main.groups() {
                let (a, b, c) = (group.a, group.b, group.c);
                let (cycle, sign) = match slot {
                    0 => (0, 1),
                    1 => (a, -1),
                    2 => (b, -1),
                    3 => (a + b, 1),
                    4 => (c, -1),
                    5 => (c + a, 1),
                    6 => (c + b, 1),
                    _ => (c + a + b, -1),
                };
                self.add(cycle, sign * direction * group.count as i64);
            }
        }
        // A jerk of ±1 on one cycle is a change by ±1 on it and back on the next. The pairs'
        // changes, sorted apart (at most 24), are merged in from the end in one pass.
        let mut notches = [JerkChange::default(); 8 * MAX_NOTCHES];
        let mut count = 0;
        for notch in placement.notches() {
            for (cycle, amount) in notch.impulses() {
                for (cycle, amount) in [(cycle, amount), (cycle + 1, -amount)] {
                    let mut k = count;
                    while k > 0 && notches[k - 1].cycle > cycle {
                        notches[k] = notches[k - 1];
                        k -= 1;
                    }
                    notches[k] = JerkChange {
                        cycle,
                        amount: amount * direction,
                    };
                    count += 1;
                }
            }
        }
        let (mut i, mut k) = (self.len, count);
        let mut write = (self.len + count).min(MAX_CHANGES - 1);
        self.len = write;
        while k > 0 {
            write -= 1;
            if i > 0 && self.changes[i - 1].cycle > notches[k - 1].cycle {
                self.changes[write] = self.changes[i - 1];
                i -= 1;
            } else {
                self.changes[write] = notches[k - 1];
                k -= 1;
            }
        }
        // Changes on the same cycle are added up; changes on or after the last cycle never act,
        // and changes that cancel out would cost a cycle's slow path for nothing.
        let total = plan.total;
        let mut kept = 0;
        for i in 0..self.len {
            let change = self.changes[i];
            if change.cycle >= total {
                break;
            }
            if kept > 0 && self.changes[kept - 1].cycle == change.cycle {
                self.changes[kept - 1].amount += change.amount;
            } else {
                if kept > 0 && self.changes[kept - 1].amount == 0 {
                    kept -= 1;
                }
                self.changes[kept] = change;
                kept += 1;
            }
        }
        if kept > 0 && self.changes[kept - 1].amount == 0 {
            kept -= 1;
        }
        self.len = kept;
    }

    /// Makes the checked schedule a replay: appends the end marker (on cycle `total`, setting the
    /// jerk to zero; the acceleration and velocity are zero there already), and turns each change
    /// into the jerk it sets and the cycles it holds (the marker's: for ever).
    pub fn seal(&mut self) {
        // A replay starts with the change on cycle 0: one of nothing if the changes there
        // cancelled out.
        if self.changes().first().is_none_or(|c| c.cycle > 0) {
            self.add_first(JerkChange::default());
        }
        let end = self.len.min(SENTINEL - 1);
        self.changes[end] = JerkChange {
            cycle: self.plan.total,
            amount: 0,
        };
        self.len = end + 1;
        let mut jerk = 0;
        for i in 0..end {
            jerk += self.changes[i].amount;
            self.changes[i] = JerkChange {
                cycle: self.changes[i + 1].cycle - self.changes[i].cycle,
                amount: jerk,
            };
        }
        self.changes[end].cycle = u64::MAX;
    }

    /// Fills in the plan's peaks and returns `true` if every cycle keeps |jerk| ≤ J,
    /// |acceleration| ≤ A and 0 ≤ velocity ≤ V (along the direction), and the move covers
    /// exactly `distance` and ends at rest; `false` otherwise.
    ///
    /// One pass over the runs of constant jerk: on a run the acceleration is linear and the
    /// velocity quadratic, so the ends of the run and the velocity's turning point are the only
    /// cycles that can set a peak or break a limit. The planner's inequalities already keep the
    /// limits; this pass gives the exact peaks the plan reports, and is the last word on a plan.
    pub fn find_peaks(&mut self, distance: u64, direction: i64, limits: Limits64) -> bool {
        self.scan(distance, direction, limits).is_some()
    }

    fn scan(&mut self, distance: u64, direction: i64, limits: Limits64) -> Option<()> {
        let total = self.plan.total;
        let (j_max, a_max, v_max) = (
            limits.jerk as i64,
            limits.acceleration as i64,
            limits.velocity as i64,
        );
        let (mut jerk, mut acceleration, mut velocity) = (0i64, 0i64, 0i64);
        let (mut peak_acceleration, mut peak_velocity) = (0i64, 0i64);
        #[cfg(debug_assertions)]
        let mut covered = 0i128;
        let changes = self.changes();
        // Before the first change (if it is not on cycle 0) nothing moves.
        for (i, change) in changes.iter().enumerate() {
            if change.cycle >= total {
                break;
            }
            jerk += if direction < 0 {
                -change.amount
            } else {
                change.amount
            };
            let end = changes.get(i + 1).map_or(total, |c| c.cycle.min(total));
            let cycles = end - change.cycle;
            #[cfg(debug_assertions)]
            let start = (velocity, acceleration);
            // Within the limits every product below stays under 2^62: a run with a jerk is at
            // most 2^30 cycles (its acceleration changes by j·m ≤ 2A < 2^33), one with only an
            // acceleration moves the velocity by a·m, checked by the widths of a and m.
            let (first, last) = if jerk == 0 {
                let slope = acceleration.unsigned_abs();
                if slope != 0 && (128 - slope.leading_zeros() - cycles.leading_zeros()) > 62 {
                    return None;
                }
                (acceleration, acceleration)
            } else {
                if jerk.abs() > j_max || cycles > 1 << 30 {
                    return None;
                }
                let m = cycles as i64;
                let (first, last) = (acceleration + jerk, acceleration + jerk * m);
                if first.abs() > a_max || last.abs() > a_max {
                    return None;
                }
                // The velocity turns inside the run only where the acceleration changes sign:
                // at n* = ⌊−acceleration/jerk − ½⌋ or the cycle after, where it is
                // v + a·n + j·n(n+1)/2 (n(n+1) is even).
                if first.signum() * last.signum() < 0 {
                    let turn = (-2 * acceleration - jerk).div_euclid(2 * jerk);
                    for n in [turn, turn + 1] {
                        if (1..=m).contains(&n) {
                            let ramp = if n % 2 == 0 {
                                jerk * (n / 2) * (n + 1)
                            } else {
                                jerk * n * ((n + 1) / 2)
                            };
                            let v = velocity + acceleration * n + ramp;
                            if !(0..=v_max).contains(&v) {
                                return None;
                            }
                            peak_velocity = peak_velocity.max(v);
                        }
                    }
                }
                (first, last)
            };
            // The accelerations of the run are an arithmetic series: the velocity changes by
            // m·(first + last)/2 (an integer: m·(2a + j·(m+1)) is even).
            if first != 0 || last != 0 {
                velocity += (first + last) * cycles as i64 / 2;
            }
            // The velocity is monotone on the run otherwise: its start was the last run's end.
            if !(0..=v_max).contains(&velocity) {
                return None;
            }
            peak_velocity = peak_velocity.max(velocity);
            peak_acceleration = peak_acceleration.max(first.abs()).max(last.abs());
            acceleration = last;
            #[cfg(debug_assertions)]
            {
                covered += run_distance(start.0, start.1, jerk, cycles);
            }
        }
        if acceleration != 0 || velocity != 0 || peak_acceleration > a_max {
            return None;
        }
        #[cfg(debug_assertions)]
        if covered != i128::from(distance) {
            return None;
        }
        #[cfg(not(debug_assertions))]
        let _ = distance;
        self.plan.peak_acceleration = peak_acceleration;
        self.plan.peak_velocity = peak_velocity;
        Some(())
    }
}

/// `Σ_{n=1..m} (v + a·n + j·n(n+1)/2) = m·v + a·m(m+1)/2 + j·m(m+1)(m+2)/6`: the distance a run of
/// `m` cycles of constant jerk covers (with `a` and `j` non-zero only on runs shorter than 2^30
/// cycles, as in every plan within the limits).
#[cfg(debug_assertions)]
fn run_distance(velocity: i64, acceleration: i64, jerk: i64, m: u64) -> i128 {
    let m = i128::from(m);
    i128::from(velocity) * m
        + i128::from(acceleration) * (m * (m + 1) / 2)
        + if jerk == 0 {
            0
        } else {
            i128::from(jerk) * (m * (m + 1) * (m + 2) / 6)
        }
}
