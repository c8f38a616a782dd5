//! The MCX514 S-curve's cycles laid out ahead (SPEC §16: a cycle is a replay): from the present
//! state, every cycle the rule ([`super::rule`]) would take until the next command, as runs of
//! constant jerk.
//!
//! The rule's ramp ([`Ramp::next`]) takes one of three branches a cycle — up (the rate rises by
//! the jerk, or holds at the cap), the slack (once or twice, at the top), down (the rate falls
//! by the jerk) — and each branch, while it lasts, changes the acceleration by a constant:
//! +J, 0, −J (the slow-down's mirrored), at DV and at SV by nothing. Such a stretch goes on
//! while (a) its branch's own condition holds, a closed form in the cycle count (up: the
//! rate's tail still fits the gap, i·(2·r₀ + J·i) ≤ gap − S(r₀), searched by bisection; at the
//! cap: a division; down: the rate above the slack, a division), (b) the cycle begins before
//! the trigger (speeding up or at DV), and (c) the cycle's velocity is below the pulses left.
//! Each holds from the stretch's first cycle up to some cycle and fails from there on — (b)
//! because the position only grows, (c) because the pulses left less the velocity fall by the
//! next cycle's velocity — so the stretch's length is the least of the bounds; (b) and (c) are
//! looked at on the stretch's last cycle and bisected only where they fail there (at most once
//! or twice a move: where the trigger falls while speeding up, where the move lands before SV).
//! Every other cycle (the start, a branch's first cycle when the acceleration is not yet the
//! rate, the slack, the last step to a rate of zero, landing, the stop) is the rule's own, taken
//! once: a run of one cycle whose jerk is whatever that cycle needs.

use super::ramp::Ramp;
use super::rule::{Phase, Rule};
use super::PerCycle;
use crate::bisect::last_true;
use crate::replay::JerkRun;

/// At rest after the move: no jerk for 2^64 − 1 cycles (for ever, in practice), once the
/// velocity and acceleration have come to zero.
const REST: JerkRun = JerkRun::new(0, u64::MAX);

/// The slots of the plan, and slot [`ELSEWHERE`]. A power of two, so that `% SLOTS` is a mask.
/// A move from rest takes about 25 (each phase's stretches and the rule's cycles between them);
/// a test asserts random moves and stops stay within the slots.
pub(super) const SLOTS: usize = 32;
/// The slot whose one cycle is taken by the rule on the slow path, which then lays the cycles
/// out again: where a plan needs more slots than there are.
pub(super) const ELSEWHERE: usize = SLOTS - 1;

/// A plan: its runs from slot 0, the rule's state before each run's first cycle, whether a run
/// has several cycles (its rate then follows the acceleration: see
/// [`Layout::rule_within`]), the slot where the rest begins (`SLOTS` when it never does), and
/// whether the cycle that lands was cut below the velocity the rule wanted.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) struct Layout {
    pub(super) runs: [JerkRun; SLOTS],
    pub(super) rules: [Rule; SLOTS],
    pub(super) several: [bool; SLOTS],
    pub(super) rest_slot: usize,
    pub(super) cut_short: bool,
}

/// Where the cycles are: the state's position, velocity and acceleration (raw I32F32).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) struct Motion {
    pub(super) position: i64,
    pub(super) velocity: i64,
    pub(super) acceleration: i64,
}

impl Motion {
    /// After a cycle at `velocity`.
    fn cycle(self, velocity: i64) -> Self {
        Self {
            position: self.position.wrapping_add(velocity),
            velocity,
            acceleration: velocity.wrapping_sub(self.velocity),
        }
    }

    /// After `cycles` cycles at `jerk` (wrapping: the values reached are the run's own, in
    /// range, and every product is exact modulo 2^64).
    fn run(self, jerk: i64, cycles: u64) -> Self {
        let k = cycles as i64;
        Self {
            position: self
                .position
                .wrapping_add(moved_modulo(self, jerk, cycles) as i64),
            velocity: self.velocity_after(jerk, cycles),
            acceleration: self.acceleration.wrapping_add(k.wrapping_mul(jerk)),
        }
    }

    /// The velocity after `cycles` cycles at `jerk`: v₀ + k·a₀ + J·k(k+1)/2 (wrapping, exact
    /// where the velocity is the run's).
    fn velocity_after(self, jerk: i64, cycles: u64) -> i64 {
        self.velocity
            .wrapping_add((cycles as i64).wrapping_mul(self.acceleration))
            .wrapping_add(jerk.wrapping_mul(triangular(cycles) as i64))
    }
}

impl Layout {
    /// A plan with no cycles yet, to be laid out ([`Layout::lay_out`]).
    pub(super) const fn empty(rule: Rule) -> Self {
        Self {
            runs: [JerkRun::new(0, 0); SLOTS],
            rules: [rule; SLOTS],
            several: [false; SLOTS],
            rest_slot: SLOTS,
            cut_short: false,
        }
    }

    /// Lays out, in place, the cycles from `motion` with the rule in the state `rule`, until the
    /// move is over (or for ever, at a constant velocity that never lands). In place: the plan
    /// is 1.7 KB, which a 32-bit core copies in several hundred instructions. Slots past those
    /// laid out keep what they held, never replayed.
    pub(super) fn lay_out(&mut self, profile: &PerCycle, mut rule: Rule, mut motion: Motion) {
        let layout = self;
        layout.rest_slot = SLOTS;
        layout.cut_short = false;
        layout.runs[ELSEWHERE] = JerkRun::new(0, 0);
        let mut slot = 0;
        while slot < ELSEWHERE {
            layout.rules[slot] = rule;
            if rule.complete {
                layout.rest_slot = layout.rest_slot.min(slot);
                // The rest takes up to three slots; short of them, its cycles are the rule's
                // (velocity zero), one a slot, up to the slow path.
                if slot + 3 <= ELSEWHERE {
                    layout.rest(slot, motion);
                    return;
                }
            }
            if let Some(Stretch { jerk, cycles, rate }) = stretch(profile, &rule, motion) {
                layout.runs[slot] = JerkRun::new(jerk, cycles);
                layout.several[slot] = true;
                slot += 1;
                if cycles == u64::MAX {
                    // At a constant velocity that never lands (zero): for ever.
                    return;
                }
                let first_rate = rule.rate;
                motion = motion.run(jerk, cycles);
                rule.rate = motion.acceleration.saturating_abs();
                // Σ_{m<k} (r₀ + m·J) added, Σ_{m≤k} (r₀ − m·J) taken off (both exact: the tails
                // are in range; the products wrap where they pass i64).
                let k = cycles as i64;
                rule.tail = match rate {
                    Rate::Rises(ramp_jerk) => rule.tail.wrapping_add(
                        k.wrapping_mul(first_rate)
                            .wrapping_add(ramp_jerk.wrapping_mul(triangular(cycles - 1) as i64)),
                    ),
                    Rate::Falls(ramp_jerk) => rule.tail.wrapping_sub(
                        k.wrapping_mul(first_rate)
                            .wrapping_sub(ramp_jerk.wrapping_mul(triangular(cycles) as i64)),
                    ),
                    Rate::Held => rule.tail,
                };
                if rule.phase == Phase::Accelerating && motion.velocity == profile.drive {
                    // The run's last cycle reached DV (only a last one can).
                    rule.at_drive_speed(profile, motion.position);
                }
                continue;
            }
            // The cycle the rule takes on its own.
            let landing = !rule.complete;
            let (next, wanted) = rule.cycle(profile, motion.position, motion.velocity);
            let after = motion.cycle(next);
            layout.runs[slot] =
                JerkRun::new(after.acceleration.wrapping_sub(motion.acceleration), 1);
            layout.several[slot] = false;
            slot += 1;
            motion = after;
            if landing && rule.complete {
                layout.cut_short = wanted > next;
            }
        }
        // Out of slots: the next cycle is the rule's, then a new plan.
        layout.runs[ELSEWHERE] = JerkRun::elsewhere();
        layout.rules[ELSEWHERE] = rule;
        layout.several[ELSEWHERE] = false;
    }

    /// The rest from `slot` on, from `motion`: the velocity to zero, the acceleration to zero
    /// (a cycle each, where they are not yet), then no change for ever.
    fn rest(&mut self, mut slot: usize, motion: Motion) {
        let rule = self.rules[slot];
        let (velocity, acceleration) = (motion.velocity, motion.acceleration);
        // To velocity zero: acceleration −v; then to acceleration zero: +v.
        for jerk in [
            (velocity != 0 || acceleration != 0)
                .then(|| velocity.wrapping_neg().wrapping_sub(acceleration)),
            (velocity != 0).then_some(velocity),
        ]
        .into_iter()
        .flatten()
        {
            self.runs[slot] = JerkRun::new(jerk, 1);
            self.rules[slot] = rule;
            self.several[slot] = false;
            slot += 1;
        }
        self.runs[slot] = REST;
        self.rules[slot] = rule;
        self.several[slot] = true;
    }

    /// The rule's state now, with the run of `slot` under way from `motion`: the rule before the
    /// run, whose rate, in a run of several cycles, is the acceleration's size (every cycle of
    /// such a run leaves it so, and its first begins so) and whose tail is S(rate).
    pub(super) fn rule_within(&self, profile: &PerCycle, slot: usize, motion: Motion) -> Rule {
        let mut rule = self.rules[slot];
        if self.several[slot] && !rule.complete {
            let ramp = match rule.phase {
                Phase::Accelerating | Phase::Easing => &profile.speed_up,
                Phase::Decelerating => &profile.slow_down,
                _ => return rule,
            };
            rule.rate = motion.acceleration.saturating_abs();
            rule.tail = Ramp::tail(rule.rate, ramp.jerk);
        }
        rule
    }
}

/// How a stretch moves the ramp's rate, so that its tail can follow: by the ramp's jerk up or
/// down, or not at all (held at the cap, or no ramp).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Rate {
    Held,
    Rises(i64),
    Falls(i64),
}

/// A stretch of cycles at one jerk (raw I32F32 bits per cycle³): `cycles` of them (`u64::MAX`:
/// for ever), the ramp's rate moved as `rate` says.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
struct Stretch {
    jerk: i64,
    cycles: u64,
    rate: Rate,
}

/// The stretch of the rule's present branch from `motion`; `None`: the next cycle is the
/// rule's own. See the module's documentation.
fn stretch(profile: &PerCycle, rule: &Rule, motion: Motion) -> Option<Stretch> {
    if rule.complete {
        return None;
    }
    let (velocity, acceleration) = (motion.velocity, motion.acceleration);
    let most = match rule.phase {
        Phase::Start => return None,
        Phase::Cruising | Phase::Creeping => {
            if acceleration != 0 {
                return None;
            }
            Stretch {
                jerk: 0,
                cycles: u64::MAX,
                rate: Rate::Held,
            }
        }
        Phase::Accelerating => branch(
            &profile.speed_up,
            rule,
            profile.drive - velocity,
            acceleration,
        )?,
        Phase::Decelerating => {
            if rule.stopping && velocity <= profile.initial {
                return None;
            }
            let mirrored = branch(
                &profile.slow_down,
                rule,
                velocity - profile.initial,
                -acceleration,
            )?;
            Stretch {
                jerk: -mirrored.jerk,
                ..mirrored
            }
        }
        Phase::Easing => {
            // The rate falls by JK while it stays above zero (then the rule's cycle to zero).
            let ramp_jerk = profile.speed_up.jerk;
            if rule.rate <= 0 || acceleration != rule.rate {
                return None;
            }
            Stretch {
                jerk: -ramp_jerk,
                cycles: (rule.rate - 1) as u64 / ramp_jerk as u64,
                rate: Rate::Falls(ramp_jerk),
            }
        }
    };
    let trigger = match rule.phase {
        Phase::Accelerating | Phase::Cruising => rule.trigger,
        _ => i64::MAX,
    };
    let cycles = within(profile.finish, trigger, motion, most.jerk, most.cycles);
    (cycles > 0).then_some(Stretch { cycles, ..most })
}

/// The branch of the ramp from its rate and tail with `gap` of speed to gain (or shed), the
/// acceleration `acceleration` (mirrored for the slow-down: the change per cycle), as a stretch
/// of the cycles its own condition allows (mirrored too). `None` where the next cycle is the
/// rule's own: the landing from a rate of zero, a branch whose first cycle changes the
/// acceleration by something else than the branch's jerk (the rate is not yet the
/// acceleration), a step to the cap, the slack, the step to a rate of zero.
fn branch(ramp: &Ramp, rule: &Rule, gap: i64, acceleration: i64) -> Option<Stretch> {
    let (rate, tail) = (rule.rate, rule.tail);
    // The tail fits the gap (the ramp's invariant): room ≥ 0, looked at all the same.
    if (rate == 0 && gap < ramp.first) || acceleration != rate || gap < tail {
        return None;
    }
    let jerk = ramp.jerk;
    let room = (gap - tail) as u64;
    if rate < ramp.cap_less_jerk {
        // Up by J while the rate before the cycle is below cap − J, and the rise i cycles on
        // still fits: r₀ + i·J + S(r₀ + i·J) ≤ gap − Σ_{m<i} (r₀ + m·J), which is
        // i·(2·r₀ + J·i) ≤ gap − S(r₀) (S(r + J) = S(r) + r, summed).
        let fits = |i: u64| {
            (jerk as u64)
                .checked_mul(i)
                .and_then(|rise| rise.checked_add(2 * rate as u64))
                .and_then(|per| per.checked_mul(i))
                .is_some_and(|needed| needed <= room)
        };
        if fits(1) {
            let below_cap = (ramp.cap_less_jerk - rate - 1) as u64 / jerk as u64 + 1;
            // J·i² ≤ room bounds i by √(room / J).
            let most = below_cap.min((room / jerk as u64).isqrt());
            return Some(Stretch {
                jerk,
                cycles: last_true(1, most + 1, fits),
                rate: Rate::Rises(jerk),
            });
        }
    } else if rate == ramp.cap {
        // Held at the cap while cap + S(cap) fits what is left of the gap.
        let cap = ramp.cap;
        if cap <= gap && ramp.cap_tail <= gap - cap {
            let most = (gap - cap - ramp.cap_tail) as u64 / cap as u64 + 1;
            return Some(Stretch {
                jerk: 0,
                cycles: most,
                rate: Rate::Held,
            });
        }
    } else if ramp.cap <= gap && ramp.cap_tail <= gap - ramp.cap {
        // The step up to the cap: the rule's.
        return None;
    }
    // Down by J while the rate stays above the slack (then the slack is taken) and above zero.
    // Between, the slack gap − tail is constant: each cycle takes off the gap what the tail
    // loses.
    let slack = room as i64;
    let most = (rate - slack.max(1)) / jerk;
    (most > 0).then_some(Stretch {
        jerk: -jerk,
        cycles: most as u64,
        rate: Rate::Falls(jerk),
    })
}

/// Of the first `most` cycles at `jerk` from `motion`, how many go on before (b) a cycle begins
/// at or past `trigger` or (c) a cycle's velocity reaches the pulses left to `finish` (those
/// cycles the rule takes). The velocities of a stretch are non-negative and monotone.
fn within(finish: i64, trigger: i64, motion: Motion, jerk: i64, most: u64) -> u64 {
    let position = motion.position;
    let left = finish.saturating_sub(position).max(0) as u64;
    if jerk == 0 && motion.acceleration == 0 {
        // Constant velocity: a division each.
        let velocity = motion.velocity as u64;
        if velocity == 0 {
            return if position < trigger && left > 0 {
                most
            } else {
                0
            };
        }
        let before_trigger = if trigger > position {
            ((trigger - position) as u64).div_ceil(velocity)
        } else {
            0
        };
        return most
            .min(before_trigger)
            .min(left.saturating_sub(1) / velocity);
    }
    // (c) fails by the cycle where the least velocity has covered the pulses left.
    let first = motion.velocity_after(jerk, 1) as u64;
    let last = motion.velocity_after(jerk, most) as u64;
    let bound = most.min(left / first.min(last).max(1) + 1);
    let (position, finish) = (position as u64, finish as u64);
    let trigger = u64::try_from(trigger).unwrap_or(0);
    // (b) and (c) for cycle i: the position after it, and before it (less its velocity).
    let holds = |i: u64| {
        let velocity = motion.velocity_after(jerk, i) as u64;
        match moved(motion, jerk, i, velocity).and_then(|moved| position.checked_add(moved)) {
            Some(after) => after < finish && after - velocity < trigger,
            None => false,
        }
    };
    if bound == 0 || !holds(1) {
        return 0;
    }
    if holds(bound) {
        return bound;
    }
    last_true(1, bound, holds)
}

/// Σ_{m=1}^{i} v_m, the pulses of the first `i` cycles at `jerk` from `motion` (vᵢ
/// `last_velocity`), exactly; `None` past 2^64. Where i·max(v₁, vᵢ) < 2^64, the closed form
/// modulo 2^64 (see [`moved_modulo`]). Else: the stretch's accelerations a_m keep one sign, so its velocities are
/// monotone, and the sum is written as terms that are all non-negative, each formed with
/// checked 64-bit arithmetic (one past 2^64 puts the sum past it): from the start where the
/// velocities rise, from the end (vᵢ) where they fall. With T₂(n) = n(n+1)/2 and
/// T₃(n) = n(n+1)(n+2)/6:
/// - rising, jerk ≥ 0: i·v₀ + a₀·T₂(i) + J·T₃(i);
/// - rising, jerk < 0 (a_m = aᵢ + (i − m)·|J|): i·v₀ + aᵢ·T₂(i) + |J|·2·T₃(i − 1);
/// - falling, |a| rising (jerk ≤ 0): i·vᵢ + |a₀|·T₂(i − 1) + |J|·2·T₃(i − 1);
/// - falling, |a| falling (jerk > 0): i·vᵢ + |aᵢ|·T₂(i − 1) + J·T₃(i − 2).
///
/// (A 32-bit core multiplies 64-bit words in a few instructions; 128-bit products are library
/// calls.)
fn moved(motion: Motion, jerk: i64, i: u64, last_velocity: u64) -> Option<u64> {
    if i == 0 {
        return Some(0);
    }
    // The common case first: i·max(v₁, vᵢ) below 2^64 bounds the sum, which the closed form
    // modulo 2^64 then gives exactly (wrapping products: a few instructions each).
    let first_velocity = motion.velocity_after(jerk, 1) as u64;
    if i.checked_mul(first_velocity.max(last_velocity)).is_some() {
        return Some(moved_modulo(motion, jerk, i));
    }
    moved_exactly(motion, jerk, i, last_velocity)
}

/// [`moved`] past its shortcut: the sum as non-negative terms, each checked (see [`moved`]).
fn moved_exactly(motion: Motion, jerk: i64, i: u64, last_velocity: u64) -> Option<u64> {
    if i == 0 {
        return Some(0);
    }
    let first = motion.acceleration;
    // Exact: the stretch's own acceleration after i cycles (wrapping products).
    let last = first.wrapping_add((i as i64).wrapping_mul(jerk));
    let size = jerk.unsigned_abs();
    let terms = if first >= 0 && last >= 0 {
        let velocity = motion.velocity as u64;
        if jerk >= 0 {
            [
                i.checked_mul(velocity)?,
                times(first as u64, exact_triangular(i))?,
                jerk_term(i, size, 1)?,
            ]
        } else {
            [
                i.checked_mul(velocity)?,
                times(last as u64, exact_triangular(i))?,
                jerk_term(i - 1, size, 2)?,
            ]
        }
    } else if first <= 0 && last <= 0 {
        let velocity = last_velocity;
        if jerk <= 0 {
            [
                i.checked_mul(velocity)?,
                times(first.unsigned_abs(), exact_triangular(i - 1))?,
                jerk_term(i - 1, size, 2)?,
            ]
        } else {
            [
                i.checked_mul(velocity)?,
                times(last.unsigned_abs(), exact_triangular(i - 1))?,
                jerk_term(i.saturating_sub(2), size, 1)?,
            ]
        }
    } else {
        // Not a stretch (the acceleration changes sign): the closed form in 128 bits.
        let wide = i128::from(i);
        let triangular = wide * (wide + 1) / 2;
        let tetrahedral = triangular.checked_mul(wide + 2)? / 3;
        let sum = wide
            .checked_mul(i128::from(motion.velocity))?
            .checked_add(triangular.checked_mul(i128::from(first))?)?
            .checked_add(tetrahedral.checked_mul(i128::from(jerk))?)?;
        return u64::try_from(sum).ok();
    };
    terms[0].checked_add(terms[1])?.checked_add(terms[2])
}

/// by·|J|·T₃(n), exactly; `None` past 2^64. Zero without a jerk, for any n (a stretch at a
/// constant acceleration can be far longer than T₃ allows).
fn jerk_term(n: u64, size: u64, by: u64) -> Option<u64> {
    times(size, exact_tetrahedral(n))?.checked_mul(by)
}

/// factor·count, exactly; `None` past 2^64 — zero for a factor zero, whatever the count (which
/// may be past 2^64 itself, `None`).
fn times(factor: u64, count: Option<u64>) -> Option<u64> {
    if factor == 0 {
        return Some(0);
    }
    count?.checked_mul(factor)
}

/// n(n+1)/2, exactly; `None` past 2^64.
fn exact_triangular(n: u64) -> Option<u64> {
    if n % 2 == 0 {
        (n / 2).checked_mul(n + 1)
    } else {
        n.checked_mul(n / 2 + 1)
    }
}

/// n(n+1)(n+2)/6, exactly; `None` past 2^64. The factor divisible by 3 is divided first, by
/// the inverse of 3 modulo 2^64 (exact on a multiple of 3), found by the digit sum in base 2^32
/// (2^32 ≡ 1 modulo 3), and an even one halved: no 64-bit division.
fn exact_tetrahedral(n: u64) -> Option<u64> {
    const INVERSE_OF_3: u64 = 0xAAAA_AAAA_AAAA_AAAB;
    let remainder = (((n >> 32) as u32 % 3) + (n as u32 % 3)) % 3;
    // The multiple of 3 among n, n + 1, n + 2, and the other two in order.
    let (third, low, high) = match remainder {
        0 => (n, n.checked_add(1)?, n.checked_add(2)?),
        1 => (n.checked_add(2)?, n, n.checked_add(1)?),
        _ => (n.checked_add(1)?, n, n.checked_add(2)?),
    };
    let third = third.wrapping_mul(INVERSE_OF_3);
    // The even one halved (n, n + 2 both odd: n + 1, a multiple of 6, is `third`).
    let (third, low, high) = if low % 2 == 0 {
        (third, low / 2, high)
    } else if high % 2 == 0 {
        (third, low, high / 2)
    } else {
        (third / 2, low, high)
    };
    third.checked_mul(low)?.checked_mul(high)
}

/// Σ_{m=1}^{i} v_m modulo 2^64 (see [`moved`]).
fn moved_modulo(motion: Motion, jerk: i64, i: u64) -> u64 {
    let sum = i
        .wrapping_mul(motion.velocity as u64)
        .wrapping_add(triangular(i).wrapping_mul(motion.acceleration as u64));
    if jerk == 0 {
        return sum;
    }
    sum.wrapping_add(tetrahedral(i).wrapping_mul(jerk as u64))
}

/// i(i+1)/2 modulo 2^64, exactly (the even factor halved first).
fn triangular(i: u64) -> u64 {
    if i % 2 == 0 {
        (i / 2).wrapping_mul(i.wrapping_add(1))
    } else {
        i.wrapping_mul(i / 2 + 1)
    }
}

/// i(i+1)(i+2)/6 modulo 2^64, exactly: the product is a multiple of 3, so modulo 2^64 it is 3
/// times the quotient, which the inverse of 3 modulo 2^64 gives back (no division).
fn tetrahedral(i: u64) -> u64 {
    /// 3 · 0xAAAA_AAAA_AAAA_AAAB = 1 modulo 2^64.
    const INVERSE_OF_3: u64 = 0xAAAA_AAAA_AAAA_AAAB;
    triangular(i)
        .wrapping_mul(i.wrapping_add(2))
        .wrapping_mul(INVERSE_OF_3)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The closed forms against sums, small and across 2^64.
    #[test]
    fn the_sums_are_exact() {
        for i in 0u64..200 {
            assert_eq!(
                u128::from(triangular(i)),
                u128::from(i) * (u128::from(i) + 1) / 2
            );
            let exact = u128::from(i) * (u128::from(i) + 1) * (u128::from(i) + 2) / 6;
            assert_eq!(u128::from(tetrahedral(i)), exact);
        }
        for i in [u64::MAX, u64::MAX - 1, 1 << 40, (1 << 40) + 1, 3 << 50] {
            let wide = u128::from(i);
            assert_eq!(triangular(i), (wide * (wide + 1) / 2) as u64);
            // i(i+1)(i+2)/6 modulo 2^64 another way: the product modulo 2^128 times the
            // inverse of 3 modulo 2^128 (exact, the product being a multiple of 3).
            let t = wide * (wide + 1) / 2; // < 2^127
            let inverse_of_3 = u128::MAX / 3 * 2 + 1; // 0xAAAA…AAAB
            assert_eq!(inverse_of_3.wrapping_mul(3), 1);
            let sixth = t.wrapping_mul(wide + 2).wrapping_mul(inverse_of_3);
            assert_eq!(tetrahedral(i), sixth as u64, "{i}");
        }
        // The pulses of a stretch against its cycles summed.
        let motion = Motion {
            position: 0,
            velocity: 1 << 40,
            acceleration: -(1 << 20),
        };
        let (mut velocity, mut acceleration, mut sum) = (1i64 << 40, -(1i64 << 20), 0u64);
        for i in 1..1_000u64 {
            acceleration += 3;
            velocity += acceleration;
            sum += velocity as u64;
            assert_eq!(moved(motion, 3, i, velocity as u64), Some(sum));
            assert_eq!(motion.velocity_after(3, i), velocity);
        }
        // Every sign of stretch, against the sums term by term.
        for (acceleration, jerk) in [
            (0i64, 5i64),
            (7, 0),
            (400, -3),
            (-2, -5),
            (-400, 3),
            (-9, 0),
        ] {
            let motion = Motion {
                position: 0,
                velocity: 1 << 20,
                acceleration,
            };
            let (mut velocity, mut now, mut sum) = (1i64 << 20, acceleration, 0u64);
            for i in 1..130u64 {
                now += jerk;
                if (acceleration > 0 && now < 0) || (acceleration < 0 && now > 0) {
                    break; // past the stretch
                }
                velocity += now;
                sum += velocity as u64;
                assert_eq!(
                    moved(motion, jerk, i, velocity as u64),
                    Some(sum),
                    "a {acceleration} j {jerk} i {i}"
                );
                // The exact form too, which the shortcut spares here.
                assert_eq!(moved_exactly(motion, jerk, i, velocity as u64), Some(sum));
            }
        }
        for n in 0..300u64 {
            let wide = u128::from(n) * (u128::from(n) + 1) * (u128::from(n) + 2) / 6;
            assert_eq!(exact_tetrahedral(n).map(u128::from), Some(wide));
        }
        for n in [
            (1u64 << 32) - 1,
            1 << 32,
            (1 << 32) + 1,
            2_642_245,
            2_642_246,
            4_801_278_548,
        ] {
            let wide = u128::from(n) * (u128::from(n) + 1) * (u128::from(n) + 2) / 6;
            assert_eq!(
                exact_tetrahedral(n).map(u128::from),
                u64::try_from(wide).ok().map(u128::from),
                "{n}"
            );
        }
        // Past 2^64.
        let fast = Motion {
            position: 0,
            velocity: 1 << 62,
            acceleration: 0,
        };
        assert_eq!(moved(fast, 0, 4, 1 << 62), None);
        assert_eq!(moved(fast, 0, 3, 1 << 62), Some(3 << 62));
    }
}
