//! The smooth stop (SPEC §9): jerk-limited deceleration to rest. Each cycle's acceleration
//! follows from the last acceleration and velocity ([`stopping_acceleration`]); the whole stop is
//! laid out as jerk changes when it is given ([`lay_out`]), and stepping replays them.

use super::schedule::Limits64;
use crate::bisect::last_true;
use crate::trapezoidal::Trapezoidal;

/// At most this many jerk changes lay out a stop ([`lay_out`]): two per run of the trapezoid's
/// plan (one for its first cycle, one for the rest of it), which has at most 15 (seven in
/// practice: moving away, the cycle that turns, speeding up, cruise, braking, the bump, and the
/// rest run, whose first cycle arrives and is one change).
pub(super) const MAX_STOP_CHANGES: usize = 30;

/// The jerk changes of a whole smooth stop from `acceleration` and `velocity` (magnitudes along
/// the move, I32F32 bits), laid out when the stop is given: `(cycles held, jerk along the move)`
/// in order, the last the cycle that arrives at rest (velocity and acceleration zero). Every
/// cycle is [`stopping_acceleration`]'s, bit for bit.
///
/// The stop is the trapezoid's per-cycle rule one derivative up (see [`stopping_acceleration`]):
/// the distance is the velocity left, the trapezoid's velocity the deceleration `m = −a`, its
/// maximum velocity the maximum acceleration, A = D = J, no starting velocity; `m < 0`
/// (still speeding up) is the trapezoid moving away from its destination. So the trapezoid's
/// planner lays it out as runs of constant velocity change ([`Trapezoidal::rule_runs`]), and a
/// run of constant change of `m` is a run of constant jerk: one change on its first cycle (the
/// jump from the last acceleration), one for the rest of it.
///
/// `None` for the states the planner does not cover (a negative velocity, which no stop from
/// a move has, or a state the trapezoid would decide cycle by cycle): those stop cycle by cycle.
pub(super) fn lay_out(
    acceleration: i64,
    velocity: i64,
    limits: Limits64,
) -> Option<([(u64, i64); MAX_STOP_CHANGES], usize)> {
    // The planner's bounds (see `rule_runs`): the S-curve's velocities are below 2^48, its
    // accelerations at most 2^32 − 2^16, its jerks below 2^31.
    if !(0..1 << 60).contains(&velocity) {
        return None;
    }
    let (runs, count) = Trapezoidal::rule_runs(
        velocity,
        -acceleration,
        limits.acceleration as i64,
        limits.jerk as i64,
    )?;
    let mut changes = [(0u64, 0i64); MAX_STOP_CHANGES];
    let mut len = 0;
    let mut push = |hold: u64, jerk: i64| {
        if len > 0 && changes[len - 1].1 == jerk {
            changes[len - 1].0 = changes[len - 1].0.saturating_add(hold);
        } else if let Some(slot) = changes.get_mut(len) {
            *slot = (hold, jerk);
            len += 1;
        }
    };
    let mut last = acceleration;
    for &(next, increment, cycles) in runs.get(..count)? {
        if cycles == u64::MAX {
            // The rest run: its first cycle arrives (acceleration zero), and the end marker
            // holds it — unless the last run's last cycle had already levelled off (the
            // trapezoid's braking may end on a velocity of zero, then rest): the stop is at
            // rest one cycle earlier than the trapezoid says it.
            if last != 0 {
                push(1, -last);
            }
            return Some((changes, len));
        }
        // The run's accelerations are −next, −next − increment, …
        push(1, -next - last);
        if cycles > 1 {
            push(cycles - 1, -increment);
        }
        last = -(next + (cycles as i64 - 1) * increment);
    }
    None
}

/// The velocity (2^-32 units) still shed while raising a negative acceleration `-magnitude` to
/// zero in jerk steps: `Σ (magnitude − k·J)` over the positive terms.
fn velocity_to_level_off(magnitude: i64, jerk: i128) -> i128 {
    if magnitude <= 0 {
        return 0;
    }
    let magnitude = i128::from(magnitude);
    let steps = (magnitude - 1) / jerk;
    steps * magnitude - jerk * steps * (steps + 1) / 2
}

/// The next cycle's acceleration of a smooth stop from `acceleration` and `velocity` (magnitudes
/// along the move, I32F32 bits): the most negative acceleration (within the jerk and the maximum
/// acceleration) from which the axis can still level off at velocity zero. Up to three phases
/// emerge: the acceleration falls to its floor, holds, and rises back to zero as the velocity
/// reaches zero.
///
/// A next acceleration `−m < 0` can level off when `v − m ≥ Σ (m − k·J)` over the positive
/// terms, that is `T(m) = m + (m − J) + … ≤ v`: the trapezoid's stopping distance with D = J,
/// one derivative up. `T` increases, so the accelerations that can level off are those at or
/// above `−M(v)`, `M` the trapezoid's braking velocity ([`Trapezoidal::braking_velocity`], an
/// integer square root and three divisions), and the answer is `−M(v)` held within
/// `a − J` (or the floor) … `a + J`: the bisection this replaced (kept for the states the closed
/// form does not cover, and as the tests' yardstick) took a few dozen trials.
pub(super) fn stopping_acceleration(acceleration: i64, velocity: i64, limits: Limits64) -> i64 {
    let jerk = limits.jerk as i64;
    let floor = -(limits.acceleration as i64);
    let low = (acceleration - jerk).max(floor);
    let high = acceleration + jerk;
    // A velocity below 2^60 keeps `braking_velocity` in 64 bits without overflow for any jerk
    // ≥ 1 (2·v / J < 2^62 there); a negative one (never on a stop from a move) is left to the
    // bisection, whose condition then also bounds the velocity itself.
    if (0..1 << 60).contains(&velocity) && low <= high {
        // The unclamped form: the public one holds its deceleration to the 8.24 rates (≥ 2^8),
        // and a jerk may be one raw unit.
        let deepest = -Trapezoidal::braking(i128::from(velocity), jerk);
        return low.max(deepest.min(high));
    }
    bisect_stopping_acceleration(acceleration, velocity, limits)
}

/// [`stopping_acceleration`] by bisection on its condition, as it was first written.
fn bisect_stopping_acceleration(acceleration: i64, velocity: i64, limits: Limits64) -> i64 {
    let jerk = limits.jerk as i64;
    let floor = -(limits.acceleration as i64);
    let feasible = |next: i64| {
        let after = i128::from(velocity) + i128::from(next);
        after >= 0 && after >= velocity_to_level_off(-next, i128::from(jerk))
    };
    let low = (acceleration - jerk).max(floor);
    let high = acceleration + jerk;
    if feasible(low) {
        return low;
    }
    // feasible(high) holds on every cycle of a stop (the smooth-stop property tests step it from
    // every phase); the smallest feasible value is the one after the last infeasible.
    last_true(low, high, |next| !feasible(next)) + 1
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::format::mc1451a::{Jerk, MaxVelocity, ScurveAcceleration};
    use crate::{ProfileGenerator, SCurve, ScurveParameters, State, StopKind};
    use fixed::types::I32F32;
    use proptest::prelude::*;

    /// The smooth stop as it was decided before it was laid out, one cycle at a time from the
    /// state (the yardstick: the bisection on the level-off condition), in the frame of the
    /// move (`direction` ±1): the state after `state`, or `None` at rest (velocity and
    /// acceleration zero).
    fn next_by_the_rule(state: State, direction: i64, limits: Limits64) -> Option<State> {
        let (a, v) = (state.acceleration.to_bits(), state.velocity.to_bits());
        if a == 0 && v == 0 {
            return None;
        }
        let next = direction * bisect_stopping_acceleration(direction * a, direction * v, limits);
        let velocity = v + next;
        Some(State {
            position: I32F32::from_bits(state.position.to_bits().wrapping_add(velocity)),
            velocity: I32F32::from_bits(velocity),
            acceleration: I32F32::from_bits(next),
        })
    }

    /// Puts a move that has not stepped yet where `cycle` steps take it (a move too long to
    /// step there): the state from its prediction, the replay at the jerk change under way.
    fn skip_to(axis: &mut SCurve, cycle: u64) {
        let state = axis.predict().unwrap().state_at(cycle);
        let mut from = 0u64;
        for index in 0..axis.schedule.len() {
            let run = axis.schedule.run(index);
            let to = from.saturating_add(run.change().hold);
            if cycle < to {
                axis.state = state;
                axis.run = super::super::Run::new(run.jerk, to - cycle, run.after());
                return;
            }
            from = to;
        }
    }

    /// A raw value log-uniform in `1 ..= max`.
    fn log_uniform(max: u64) -> impl Strategy<Value = u64> {
        (1..=64 - max.leading_zeros()).prop_flat_map(move |bits| {
            let low = 1u64 << (bits - 1);
            low..=((low << 1) - 1).min(max)
        })
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(3_000))]

        /// A smooth stop at a random cycle of a random move (every register across its range,
        /// from a position with any fraction) is, cycle by cycle, the stop decided one cycle at
        /// a time: every cycle stepped while the stop is short (up to 100,000 cycles), and on
        /// longer ones every cycle from then on around each jerk change of the laid-out stop
        /// (and at its end), read from the stop's prediction. It ends complete, at rest, on the
        /// cycle its prediction (made when the stop is given) says, every state as predicted.
        #[test]
        fn a_laid_out_stop_is_the_per_cycle_stop(
            destination in log_uniform((1 << 30) - 1),
            negative in any::<bool>(),
            start in any::<i64>(),
            velocity in log_uniform(MaxVelocity::MAX_BITS.into()),
            acceleration in log_uniform(ScurveAcceleration::MAX_BITS.into()),
            jerk in log_uniform(Jerk::MAX_BITS.into()),
            at in any::<u64>(),
        ) {
            let destination = if negative { -(destination as i32) } else { destination as i32 };
            let parameters = ScurveParameters {
                destination,
                max_velocity: MaxVelocity::from_bits(velocity as u32).unwrap(),
                max_acceleration: ScurveAcceleration::from_bits(acceleration as u16).unwrap(),
                jerk: Jerk::from_bits(jerk as u32).unwrap(),
            };
            let Ok(mut axis) = SCurve::with_position(parameters, I32F32::from_bits(start)) else {
                return Ok(());
            };
            let total = axis.plan().total;
            // A uniform cycle of the move: total · at / 2^64.
            let cycle = ((u128::from(total) * u128::from(at)) >> 64) as u64;
            if cycle <= 20_000 {
                for _ in 0..cycle {
                    axis.step();
                }
            } else {
                skip_to(&mut axis, cycle);
            }
            let (direction, limits) = (axis.direction, axis.limits);
            axis.stop(StopKind::Smooth);
            if axis.motion == super::super::Motion::Stopping {
                prop_assert!(axis.run.next != super::super::SENTINEL, "laid out");
            }
            let mut state = axis.state();
            // The stop's prediction, as soon as it is given, against the steps.
            let predicted = axis.predict().unwrap();
            let mut stepped = 0u64;
            while let Some(expected) = next_by_the_rule(state, direction, limits) {
                if stepped == 100_000 {
                    break;
                }
                prop_assert!(!axis.is_complete());
                state = axis.step();
                stepped += 1;
                prop_assert_eq!(state, expected, "stop cycle {}", stepped);
                prop_assert_eq!(predicted.state_at(stepped), state, "predicted, cycle {}", stepped);
            }
            if next_by_the_rule(state, direction, limits).is_none() {
                prop_assert_eq!(predicted.completion(), Some(stepped));
                prop_assert!(axis.is_complete());
                prop_assert_eq!(axis.step(), state, "it rests");
                return Ok(());
            }
            // A long stop: its future from here, at every cycle within 3 of a jerk change.
            prop_assert!(axis.motion == super::super::Motion::Stopping);
            let future = axis.predict().unwrap();
            let end = future.completion().unwrap();
            let mut change = axis.run.cycles();
            let mut index = axis.run.after();
            let mut checked = 0;
            loop {
                for k in change.saturating_sub(3)..(change + 3).min(end + 1) {
                    let before = future.state_at(k);
                    match next_by_the_rule(before, direction, limits) {
                        Some(expected) => prop_assert_eq!(future.state_at(k + 1), expected),
                        None => prop_assert_eq!(k, end, "at rest only at the end"),
                    }
                    checked += 1;
                }
                if change >= end || usize::from(index) >= super::super::schedule::MAX_CHANGES {
                    break;
                }
                change = change.saturating_add(axis.schedule.change(index).hold);
                index += 1;
            }
            prop_assert!(checked > 0);
            prop_assert_eq!(future.state_at(end).velocity, I32F32::ZERO);
            prop_assert_eq!(future.state_at(end).acceleration, I32F32::ZERO);
        }
    }

    /// A stop whose changes do not fit after the plan's overwrites them (a plan of more than
    /// about 31 changes and a stop of many: not met over 200,000 random moves of few-unit
    /// jerks from fractional positions, whose plans have up to 34, with stops of up to 8; the
    /// bound allows 44 and 30), so the plan is kept with its peaks first: the kept plan reads
    /// as the one replayed before, even with every change overwritten.
    #[test]
    fn a_plan_kept_over_overwritten_changes_reads_the_same() {
        let mut random = Random(0xD1B5_4A32_D192_ED03);
        for _ in 0..1_000 {
            let parameters = ScurveParameters {
                destination: random.log_uniform(20) as i32,
                max_velocity: MaxVelocity::from_bits(random.log_uniform(29) as u32).unwrap(),
                max_acceleration: ScurveAcceleration::from_bits(random.log_uniform(15) as u16)
                    .unwrap(),
                jerk: Jerk::from_bits(random.log_uniform(31) as u32).unwrap(),
            };
            let Ok(mut axis) = SCurve::new(parameters) else {
                continue;
            };
            let plan = axis.plan();
            assert!(plan.peak_velocity > 0 && plan.peak_acceleration > 0);
            axis.schedule.plan = axis.plan();
            axis.schedule.seal_at_end(&[(1, 0); 44], 1);
            // The changes read now have no peaks of the move.
            let replay = axis.schedule.replay(axis.direction, axis.limits);
            assert_ne!(replay.peak_velocity, plan.peak_velocity.to_bits());
            assert_eq!(axis.plan(), plan);
        }
    }

    /// `set_parameters` plans in place, over what the last move left in the schedule: a plan
    /// kept with its peaks (as a stop that overwrote the plan's changes leaves it) and a stop's
    /// changes at the end of the array. The new plan reads, and runs, as a fresh generator's.
    #[test]
    fn a_plan_made_over_a_kept_one_reads_as_a_fresh_one() {
        let mut random = Random(0x9E37_79B9_7F4A_7C15);
        for _ in 0..300 {
            let mut parameters = || ScurveParameters {
                destination: random.log_uniform(20) as i32,
                max_velocity: MaxVelocity::from_bits(random.log_uniform(29) as u32).unwrap(),
                max_acceleration: ScurveAcceleration::from_bits(random.log_uniform(15) as u16)
                    .unwrap(),
                jerk: Jerk::from_bits(random.log_uniform(31) as u32).unwrap(),
            };
            let (last, next) = (parameters(), parameters());
            let Ok(mut axis) = SCurve::new(last) else {
                continue;
            };
            // What an overwriting stop leaves (see the test above), then at rest where it was.
            axis.schedule.plan = axis.plan();
            axis.schedule.seal_at_end(&[(1, 0); 44], 1);
            axis.state = State::at_rest(axis.state.position);
            axis.rest();
            assert!(axis.is_complete());
            let Ok(fresh) = SCurve::new(next) else {
                continue;
            };
            axis.set_parameters(next).unwrap();
            assert_eq!(axis.plan(), fresh.plan());
            assert_eq!(axis.schedule.len(), fresh.schedule.len());
            for index in 0..fresh.schedule.len() {
                assert_eq!(axis.schedule.run(index), fresh.schedule.run(index));
            }
        }
    }

    /// Laid out from random states across the ranges (not only those of a move: any
    /// acceleration within the floor, any velocity from which the stop can level off, jerks
    /// from one raw unit), every cycle of the layout is the per-cycle rule's.
    #[test]
    fn the_layout_is_the_rule_from_any_state() {
        let mut random = Random(0x2545_F491_4F6C_DD1D);
        let mut long = 0;
        for _ in 0..3_000 {
            let jerk = random.log_uniform(31);
            // At most 2^14 jerk steps to the maximum acceleration, so the stops can be stepped.
            let ratio = random.log_uniform(14);
            let raw = ((jerk * ratio) >> 16).clamp(1, 0xFFFF);
            let limits = Limits64 {
                jerk,
                acceleration: raw << 16,
                velocity: 1 << 48,
            };
            let magnitude = random.next() % (limits.acceleration + 1);
            let acceleration = if random.next() % 2 == 0 {
                magnitude as i64
            } else {
                -(magnitude as i64)
            };
            // The least velocity from which the stop levels off: T(m − J) with m = −a, and a
            // random amount more (up to 2^40).
            let m = (-acceleration - jerk as i64).max(0);
            let least = m as i128 + velocity_to_level_off(m, i128::from(jerk));
            let velocity = least as i64 + (random.log_uniform(40) as i64 - 1);
            let Some((changes, count)) = lay_out(acceleration, velocity, limits) else {
                panic!("not laid out: a {acceleration} v {velocity} {limits:?}");
            };
            let (mut a, mut v) = (acceleration, velocity);
            let mut cycles = 0u64;
            for (index, &(hold, jerk_change)) in changes[..count].iter().enumerate() {
                for _ in 0..hold {
                    let expected = bisect_stopping_acceleration(a, v, limits);
                    a += jerk_change;
                    v += a;
                    cycles += 1;
                    assert_eq!(a, expected, "cycle {cycles} change {index} {limits:?}");
                    assert!(cycles < 1 << 26, "a stop too long to step");
                }
            }
            assert_eq!((a, v), (0, 0), "at rest after the last change");
            long += u32::from(cycles > 1_000);
        }
        assert!(long > 100, "{long} stops of more than 1,000 cycles");
    }

    /// A small deterministic generator (xorshift), so the test needs no dependency.
    struct Random(u64);

    impl Random {
        fn next(&mut self) -> u64 {
            self.0 ^= self.0 << 13;
            self.0 ^= self.0 >> 7;
            self.0 ^= self.0 << 17;
            self.0
        }

        /// Log-uniform in 1 ..= 2^bits − 1.
        fn log_uniform(&mut self, bits: u32) -> u64 {
            let width = 1 + self.next() % u64::from(bits);
            (self.next() >> (64 - width)).max(1)
        }
    }

    /// The closed form against the bisection on random states across the ranges (jerks from one
    /// raw unit, accelerations within the floor, velocities up to 2^50), and on the states near
    /// the kinks of `T` (velocities T(m) − 1, T(m), T(m) + 1).
    #[test]
    fn the_closed_form_is_the_bisection() {
        let mut random = Random(0x9E37_79B9_7F4A_7C15);
        let mut inside = 0;
        for case in 0..200_000 {
            let jerk = random.log_uniform(32);
            let max_acceleration = random.log_uniform(40).max(jerk);
            let limits = Limits64 {
                jerk,
                acceleration: max_acceleration,
                velocity: 1 << 50,
            };
            let magnitude = random.next() % (max_acceleration + 1);
            let acceleration = if random.next() % 2 == 0 {
                magnitude as i64
            } else {
                -(magnitude as i64)
            };
            // A random velocity, or one at a kink of T (T(m) − 1, T(m), T(m) + 1) for an m
            // within 2J of the present deceleration, where the answer lies strictly between
            // the jerk's bounds.
            let velocity = if case % 2 == 0 {
                random.log_uniform(50) as i64
            } else {
                let spread = (random.next() % (4 * jerk + 1)) as i64 - 2 * jerk as i64;
                let m = (-acceleration + spread).max(0);
                let t = m as i128 + velocity_to_level_off(m, i128::from(jerk));
                let t = i64::try_from(t).unwrap_or(i64::MAX).min(1 << 59);
                t + (random.next() % 3) as i64 - 1
            }
            .max(0);
            let expected = bisect_stopping_acceleration(acceleration, velocity, limits);
            let low = (acceleration - jerk as i64).max(-(max_acceleration as i64));
            inside += u32::from(low < expected && expected < acceleration + jerk as i64);
            assert_eq!(
                stopping_acceleration(acceleration, velocity, limits),
                expected,
                "a {acceleration} v {velocity} J {jerk} A {max_acceleration}"
            );
        }
        // The cases that bind the level-off condition itself are many.
        assert!(
            inside > 10_000,
            "{inside} cases strictly inside the jerk's bounds"
        );
    }
}
