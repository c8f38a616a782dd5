//! The MCX514 trapezoid's cycles laid out ahead (SPEC §16: a cycle is a replay): from the
//! present state, every cycle the rule ([`super::rule`]) would take until the next command, as
//! runs of constant velocity change.
//!
//! Between the cycles where the rule changes phase (the start, DV reached, the trigger passed,
//! SV reached) or lands (the cut to the pulses left), each phase's cycles are one arithmetic
//! progression: up by AC, at DV, down by DC, at SV. Such a stretch goes on while (a) its own
//! limit holds (below DV − AC before speeding up, above SV after slowing down), (b) the cycle
//! begins before the trigger, and (c) the cycle's velocity is below the pulses left. Each holds
//! from the stretch's first cycle up to some cycle and fails from there on — (b) because the
//! position only grows, (c) because the pulses left less the velocity fall by the next cycle's
//! velocity every cycle — so the stretch's length is the least of three bounds: a division
//! each at constant velocity, a bisection over the quadratic position while speeding up or
//! slowing down. The cycle that ends a stretch is the rule's own, taken once. The phases only
//! move forward (start, speeding up, at DV, slowing down, at SV, over), each with a stretch and
//! a cycle that ends it (a smooth stop's slowing down ends with two: to SV, then to rest), so a
//! move needs at most 12 runs and rest.

use super::rule::{Phase, Rule};
use super::PerCycle;
use crate::bisect::last_true;
use crate::replay::Replay;

/// At rest after the move: velocity zero for 2^64 − 1 cycles (for ever, in practice).
const REST: Replay = Replay::new(0, 0, u64::MAX);

/// The slots of the plan: 12 runs and rest at most, and slot [`ELSEWHERE`]. A power of two, so
/// that `% RUNS` is a mask.
pub(super) const RUNS: usize = 16;
/// The slot whose one cycle is taken by the rule on the slow path, which then lays the cycles
/// out again: where a plan would need more slots than there are (never, by the count above;
/// the slot keeps the generator right if it did).
pub(super) const ELSEWHERE: usize = RUNS - 1;

/// A plan: its runs from slot 0, the rule's state before each run's first cycle (constant over
/// a stretch), the slot of the rest after the move (`RUNS` when it never ends), and whether the
/// cycle that lands was cut below the velocity the rule wanted.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) struct Layout {
    pub(super) runs: [Replay; RUNS],
    pub(super) rules: [Rule; RUNS],
    pub(super) rest_slot: usize,
    pub(super) cut_short: bool,
}

impl Layout {
    /// The cycles from `position` moving at `velocity` (raw I32F32) with the rule in the state
    /// `rule`, until the move is over (or for ever, at a constant velocity that never lands).
    pub(super) fn new(profile: &PerCycle, mut rule: Rule, position: i64, velocity: i64) -> Self {
        let mut layout = Self {
            runs: [Replay::new(0, 0, 0); RUNS],
            rules: [rule; RUNS],
            rest_slot: RUNS,
            cut_short: false,
        };
        let (mut position, mut velocity) = (position, velocity);
        let mut slot = 0;
        while slot < ELSEWHERE {
            layout.rules[slot] = rule;
            if rule.complete {
                layout.runs[slot] = REST;
                layout.rest_slot = slot;
                return layout;
            }
            let (first, increment, count) = stretch(profile, &rule, position, velocity);
            if count > 0 {
                layout.runs[slot] = Replay::new(first, increment, count);
                slot += 1;
                if count == u64::MAX {
                    // At a constant velocity that never lands (zero): for ever.
                    return layout;
                }
                // The stretch's pulses: below the pulses left (its last cycle did not land), so
                // the sum, exact in i128, fits the position.
                let (cycles, first, increment) =
                    (i128::from(count), i128::from(first), i128::from(increment));
                position += (cycles * first + increment * (cycles * (cycles - 1) / 2)) as i64;
                velocity = (first + (cycles - 1) * increment) as i64;
                continue;
            }
            // The cycle that changes the phase or lands, by the rule itself.
            let (next, wanted) = rule.cycle(profile, position, velocity);
            layout.runs[slot] = Replay::new(next, 0, 1);
            slot += 1;
            position += next;
            velocity = next;
            if rule.complete {
                layout.cut_short = wanted > next;
            }
        }
        // Out of slots (see ELSEWHERE): the next cycle is the rule's, then a new plan.
        layout.runs[ELSEWHERE] = Replay::elsewhere();
        layout.rules[ELSEWHERE] = rule;
        layout
    }
}

/// The stretch of the present phase from `position` moving at `velocity` (raw I32F32, both
/// non-negative, the position at most the finish point): its first velocity, its change per
/// cycle and its cycles (0: the next cycle is the rule's own; `u64::MAX`: for ever). See the
/// module's documentation for the three bounds. In 64 bits throughout (a 32-bit core divides
/// and multiplies those several times faster than 128-bit ones).
fn stretch(profile: &PerCycle, rule: &Rule, position: i64, velocity: i64) -> (i64, i64, u64) {
    let none = (0, 0, 0);
    let (first, increment, most) = match rule.phase {
        Phase::Start => return none,
        Phase::Accelerating => {
            // Cycle j speeds up while the velocity before it, v + (j − 1)·AC, is below DV − AC.
            let below = profile.below_last_speed_up;
            let acceleration = profile.acceleration;
            if velocity >= below {
                return none;
            }
            (
                velocity + acceleration,
                acceleration,
                (below - 1 - velocity) as u64 / acceleration as u64 + 1,
            )
        }
        Phase::Decelerating => {
            // Cycle j slows down while v − j·DC stays above SV. (No overflow: 0 ≤ v, DC < 2⁶³.)
            let (initial, deceleration) = (profile.initial, profile.deceleration);
            if velocity - deceleration <= initial {
                return none;
            }
            (
                velocity - deceleration,
                -deceleration,
                (velocity - initial - 1) as u64 / deceleration as u64,
            )
        }
        Phase::Cruising | Phase::Creeping => (velocity, 0, u64::MAX),
    };
    let (trigger, finish) = (rule.trigger, profile.finish);
    // The pulses left, and to the trigger (≤ 0: it is passed).
    let left = finish.saturating_sub(position).max(0) as u64;
    if increment == 0 {
        // (b) position + (j − 1)·v < trigger; (c) j·v < finish − position.
        if first == 0 {
            let holds = position < trigger && left > 0;
            return (0, 0, if holds { u64::MAX } else { 0 });
        }
        let before_trigger = if trigger > position {
            ((trigger - position) as u64).div_ceil(first as u64)
        } else {
            0
        };
        let before_landing = left.saturating_sub(1) / first as u64;
        return (first, 0, before_trigger.min(before_landing));
    }
    // Every velocity of the stretch is at least 1 raw unit and the first cycles' sum stays
    // below the pulses left, so (c) fails by cycle (finish − position) / (least velocity) + 1.
    let least = first.min(first + (most - 1) as i64 * increment).max(1);
    let bound = most.min(left / least as u64 + 1);
    // (b) and (c) for cycle j: the position before it and its velocity. Every velocity of the
    // stretch, j ≤ `most`, lies within 0 … DV < 2^63, so cycle j's is exact; the pulses before
    // it, k = j − 1 cycles, are k·(first + last) / 2 with first + last < 2^64, and a product past
    // 2^64 means a sum past 2^63, beyond every finish point (< 2^62): (c) fails there.
    let position = position as u64;
    let trigger = u64::try_from(trigger).unwrap_or(0);
    let finish = finish as u64;
    let holds = |j: u64| {
        let k = j - 1;
        let velocity = (first + k as i64 * increment) as u64;
        let moved = if k == 0 {
            Some(0)
        } else {
            let last = first + (k as i64 - 1) * increment;
            k.checked_mul(first as u64 + last as u64)
                .map(|twice| twice / 2)
        };
        match moved.and_then(|moved| position.checked_add(moved)) {
            Some(before) => before < trigger && before < finish && velocity < finish - before,
            None => false,
        }
    };
    (
        first,
        increment,
        last_true(0, bound.saturating_add(1), holds),
    )
}
