//! Prediction (SPEC §15): `state_at(n)` is bit-identical to stepping n times, `completion` is
//! the first cycle on which the generator reports complete, and `first_cycle_at(x)` the first
//! cycle whose position reaches or passes x — each checked against a stepped trace (an
//! independent brute force: the generator's own `step`), on every cycle of random moves, from
//! the start and from the middle of moves, from starts near the ±2^31-count wrap.

mod strategies;

use profilegen::fixed::types::I32F32;
use profilegen::format::juno::TargetVelocity;
use profilegen::predict::Prediction;
use profilegen::{ProfileGenerator, SCurve, State, StopKind, Trapezoidal, VelocityContouring};
use proptest::prelude::*;
use strategies::{
    moderate_trapezoidal, scurve_move, trapezoidal_command, trapezoidal_move, velocity_command,
    velocity_parameters, TrapezoidalCommand, VelocityCommand,
};

/// The cycles stepped after a move completes, to see it stay complete and put.
const AFTER: u64 = 5;

/// The states of `cycles` steps of a copy of `axis`, the present one first (index = cycle).
fn trace<G: ProfileGenerator + Clone>(axis: &G, cycles: u64) -> (Vec<State>, Vec<bool>) {
    let mut copy = axis.clone();
    let mut states = vec![copy.state()];
    let mut complete = vec![copy.is_complete()];
    for _ in 0..cycles {
        states.push(copy.step());
        complete.push(copy.is_complete());
    }
    (states, complete)
}

/// The first cycle of `states` whose position reaches or passes `target`, by brute force: the
/// displacement unwrapped by summing velocities; a trace moving one way (`direction` ±1) looks
/// for the first distance that way at which the register shows the point, one that reverses for
/// the point within ±2^31 counts (the nearer way round).
fn first_reaching(states: &[State], target: I32F32, reverses: bool) -> Option<u64> {
    let origin = states[0].position.to_bits();
    let offset = target.to_bits().wrapping_sub(origin);
    if offset == 0 {
        return Some(0);
    }
    let direction = states
        .iter()
        .map(|s| s.velocity.to_bits().signum())
        .find(|&s| s != 0)
        .unwrap_or(0);
    let goal: i128 = if reverses {
        i128::from(offset)
    } else if direction > 0 {
        i128::from(offset as u64)
    } else if direction < 0 {
        -i128::from(offset.wrapping_neg() as u64)
    } else {
        return None;
    };
    let mut displacement = 0i128;
    for (n, state) in states.iter().enumerate().skip(1) {
        let before = displacement;
        displacement += i128::from(state.velocity.to_bits());
        let low = before.min(displacement);
        let high = before.max(displacement);
        if displacement == goal || (low < goal && goal < high) {
            return Some(n as u64);
        }
    }
    None
}

/// Checks a prediction against the trace of `cycles` steps of `axis`: every state, the
/// completion (complete exactly from that cycle on, when it falls inside the trace), and the
/// first cycle at a few positions taken from the trace (each exact position, one raw unit
/// either side) and a few elsewhere.
fn check<G: ProfileGenerator + Clone>(
    axis: &G,
    future: &Prediction,
    cycles: u64,
    extra_targets: &[i64],
    reverses: Option<bool>,
) -> Result<(), TestCaseError> {
    prop_assert!(cycles <= 3_000_000, "a trace of {} cycles", cycles);
    let (states, complete) = trace(axis, cycles);
    for (n, state) in states.iter().enumerate() {
        prop_assert_eq!(future.state_at(n as u64), *state, "cycle {}", n);
    }
    match future.completion() {
        Some(at) if at <= cycles => {
            for (n, &done) in complete.iter().enumerate() {
                prop_assert_eq!(
                    done,
                    n as u64 >= at,
                    "complete on cycle {} (predicted {})",
                    n,
                    at
                );
            }
        }
        Some(at) => prop_assert!(!complete.iter().any(|&c| c), "predicted {}", at),
        None => prop_assert!(!complete.iter().any(|&c| c)),
    }
    // The future reverses if its velocities take both signs (seen in the trace, unless the
    // caller knows better: a velocity-contouring trace may end before the reversal).
    let reverses = reverses.unwrap_or_else(|| {
        states.iter().any(|s| s.velocity > 0) && states.iter().any(|s| s.velocity < 0)
    });
    let step = (states.len() / 7).max(1);
    let mut targets: Vec<i64> = states
        .iter()
        .step_by(step)
        .flat_map(|s| {
            let bits = s.position.to_bits();
            [bits, bits.wrapping_add(1), bits.wrapping_sub(1)]
        })
        .collect();
    targets.extend_from_slice(extra_targets);
    let settled = future.completion().is_some_and(|at| at <= cycles);
    for bits in targets {
        let target = I32F32::from_bits(bits);
        let expected = first_reaching(&states, target, reverses);
        let got = future.first_cycle_at(target);
        match expected {
            Some(n) => prop_assert_eq!(got, Some(n), "target {}", target),
            // Not within the trace: never, if the trace ran to rest; else later, if at all.
            None if settled => prop_assert_eq!(got, None, "target {}", target),
            None => prop_assert!(
                got.is_none_or(|n| n > cycles),
                "target {}: {:?}",
                target,
                got
            ),
        }
    }
    Ok(())
}

/// Whether a velocity-contouring axis's future reverses: its velocity and its target have
/// opposite signs (the velocity moves monotonically to the target).
fn reverses(axis: &VelocityContouring) -> bool {
    let velocity = axis.state().velocity.to_bits().signum();
    let target = i64::from(axis.parameters().velocity.to_bits()).signum();
    velocity * target < 0
}

/// A whole count to start from, a third of the time within 2^20 counts of the 32-bit wrap, and
/// a fraction.
fn anchor() -> impl Strategy<Value = (i32, i64)> {
    (
        prop_oneof![
            2 => any::<i32>(),
            1 => (any::<bool>(), 0i32..1 << 20).prop_map(|(below, offset)| if below {
                i32::MAX - offset
            } else {
                i32::MIN + offset
            }),
        ],
        0i64..1 << 32,
    )
}

/// The position `anchor` counts plus `fraction` raw units.
fn at(anchor: i32, fraction: i64) -> I32F32 {
    I32F32::from_bits((i64::from(anchor) << 32) | fraction)
}

/// Any position at all (velocity contouring, which has no destination).
fn start_position() -> impl Strategy<Value = I32F32> {
    anchor().prop_map(|(anchor, fraction)| at(anchor, fraction))
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(300))]

    /// S-curve moves from rest across the register ranges (up to 2^30 counts, up to ~200,000
    /// cycles): every cycle of the move and a few after it, predicted from the start and again
    /// from a random cycle in the middle.
    #[test]
    fn scurve_states_match_stepping(
        mut parameters in scurve_move(),
        (anchor, fraction) in anchor(),
        middle in 0.0f64..1.0,
        extra in prop::collection::vec(any::<i64>(), 3),
    ) {
        // The move from the anchor (within the destination register's ±2^30), from a fraction.
        let anchor = anchor.clamp(-(1 << 30), (1 << 30) - 1);
        let destination = i64::from(anchor) + i64::from(parameters.destination);
        parameters.destination = destination.clamp(-(1 << 30), (1 << 30) - 1) as i32;
        let start = at(anchor, fraction);
        let Ok(mut axis) = SCurve::with_position(parameters, start) else { return Ok(()) };
        let total = axis.plan().total;
        let future = axis.predict().expect("a planned move is predicted");
        prop_assert_eq!(future.completion(), Some(total));
        check(&axis, &future, total + AFTER, &extra, None)?;
        let stepped = (total as f64 * middle) as u64;
        for _ in 0..stepped {
            axis.step();
        }
        let future = axis.predict().expect("a planned move is predicted");
        prop_assert_eq!(future.completion(), Some(total - stepped));
        check(&axis, &future, total - stepped + AFTER, &extra, None)?;
    }

    /// Trapezoidal moves from rest across the register ranges, from wrapping starts; then a
    /// script of commands in motion, each followed by a prediction checked over the cycles to
    /// the next command (a plan is predicted whenever the axis is not deciding cycle by cycle).
    #[test]
    fn trapezoidal_states_match_stepping(
        mut parameters in trapezoidal_move(),
        (anchor, fraction) in anchor(),
        extra in prop::collection::vec(any::<i64>(), 3),
    ) {
        // The move from the anchor, across the wrap when the anchor is near it.
        parameters.destination = anchor.wrapping_add(parameters.destination);
        let start = at(anchor, fraction);
        let axis = Trapezoidal::with_position(parameters, start).unwrap();
        let future = axis.predict().expect("a move from rest is predicted");
        let complete = future.completion().expect("it arrives");
        check(&axis, &future, complete + AFTER, &extra, None)?;
    }

    #[test]
    fn trapezoidal_commands_in_motion(
        mut parameters in moderate_trapezoidal(),
        (anchor, fraction) in anchor(),
        script in prop::collection::vec((1u64..400, trapezoidal_command()), 1..8),
    ) {
        // Destinations relative to the anchor.
        parameters.destination = anchor.wrapping_add(parameters.destination);
        let start = at(anchor, fraction);
        let mut axis = Trapezoidal::with_position(parameters, start).unwrap();
        let mut predicted = 0;
        for (cycles, command) in script {
            if let Some(future) = axis.predict() {
                predicted += 1;
                let horizon = future.completion().map_or(cycles, |c| c.max(cycles)) + AFTER;
                check(&axis, &future, horizon, &[], None)?;
            }
            for _ in 0..cycles {
                axis.step();
            }
            match command {
                TrapezoidalCommand::Destination(d) => {
                    axis.set_destination(anchor.wrapping_add(d));
                }
                TrapezoidalCommand::MaxVelocity(v) => axis.set_max_velocity(v).unwrap(),
                TrapezoidalCommand::Acceleration(a) => axis.set_acceleration(a).unwrap(),
                TrapezoidalCommand::Deceleration(d) => axis.set_deceleration(d),
                TrapezoidalCommand::Stop(kind) => axis.stop(kind),
            }
        }
        prop_assert!(predicted > 0);
    }

    /// Velocity contouring from any velocity toward any target, at any rates (the future runs
    /// for ever: checked over 3,000 cycles, and at a cycle past 2^40 against the closed form
    /// of the constant part), after random commands, stops included.
    #[test]
    fn velocity_states_match_stepping(
        parameters in velocity_parameters(),
        start in start_position(),
        script in prop::collection::vec((0u64..300, velocity_command()), 1..6),
        extra in prop::collection::vec(any::<i64>(), 3),
    ) {
        let mut axis = VelocityContouring::with_position(parameters, start).unwrap();
        for (cycles, command) in script {
            let future = axis.predict();
            check(&axis, &future, cycles.max(1_000), &extra, Some(reverses(&axis)))?;
            for _ in 0..cycles {
                axis.step();
            }
            match command {
                VelocityCommand::Velocity(v) => axis.set_velocity(v),
                VelocityCommand::Acceleration(a) => axis.set_acceleration(a).unwrap(),
                VelocityCommand::Deceleration(d) => axis.set_deceleration(d),
                VelocityCommand::Stop(kind) => axis.stop(kind),
            }
        }
        let future = axis.predict();
        check(&axis, &future, 3_000, &extra, Some(reverses(&axis)))?;
    }
}

/// A velocity-contouring axis that reaches its target within a few cycles: far in the future
/// the velocity is the target and the position advances by it exactly, wrapping (i128 sums).
#[test]
fn velocity_far_in_the_future() {
    use profilegen::format::juno::Acceleration;
    use profilegen::VelocityParameters;
    let target = TargetVelocity::from_num(-12_345.678).unwrap();
    let mut axis = VelocityContouring::with_position(
        VelocityParameters {
            velocity: target,
            acceleration: Acceleration::from_num(100.0).unwrap(),
            deceleration: Acceleration::ZERO,
        },
        I32F32::from_num(-2_000_000_000),
    )
    .unwrap();
    let future = axis.predict();
    // 124 cycles at 100 counts/cycle² reach it; step past them.
    let states: Vec<State> = axis.states().take(200).collect();
    assert_eq!(future.state_at(200), states[199]);
    let v = i128::from(states[199].velocity.to_bits());
    assert_eq!(v, i128::from(target.to_bits()) << 16);
    for n in [1u64 << 20, 1 << 40, u64::MAX / 3, u64::MAX] {
        let expected = i128::from(states[199].position.to_bits()) + v * i128::from(n - 200);
        let state = future.state_at(n);
        assert_eq!(state.position.to_bits(), expected as i64, "cycle {n}");
        assert_eq!(
            (state.velocity.to_bits(), state.acceleration),
            (v as i64, I32F32::ZERO)
        );
    }
    // Moving down: the point 1 count above the start is reached after going down 2^32 − 1 counts.
    let up = I32F32::from_num(-1_999_999_999);
    let cycle = future.first_cycle_at(up).unwrap();
    let before = future.state_at(cycle - 1).position.to_bits();
    let after = future.state_at(cycle).position.to_bits();
    // The register passes the point between those two cycles (going down, wrapping).
    assert!(before.wrapping_sub(up.to_bits()) > 0 && after.wrapping_sub(up.to_bits()) <= 0);
    assert!(cycle > (1u64 << 32) / 12_346);
}

/// An abrupt stop pending is predicted: its one cycle drops the velocity, then rest.
#[test]
fn pending_abrupt_stops() {
    let mut axis = SCurve::new(profilegen::ScurveParameters {
        destination: 10_000,
        max_velocity: profilegen::format::mc1451a::MaxVelocity::from_num(20.0).unwrap(),
        max_acceleration: profilegen::format::mc1451a::ScurveAcceleration::from_num(0.25).unwrap(),
        jerk: profilegen::format::mc1451a::Jerk::from_num(0.01).unwrap(),
    })
    .unwrap();
    axis.states().take(100).for_each(drop);
    axis.stop(StopKind::Abrupt);
    let future = axis.predict().unwrap();
    assert_eq!(future.completion(), Some(1));
    let states: Vec<State> = axis.clone().states().take(4).collect();
    for (n, state) in states.iter().enumerate() {
        assert_eq!(future.state_at(n as u64 + 1), *state);
    }
    // Past the abrupt stop the axis rests, and rest is predicted.
    let mut rested = axis.clone();
    rested.states().take(3).for_each(drop);
    assert!(rested.predict().is_some(), "at rest after the abrupt stop");
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(2_000))]

    /// S-curve moves of any length over the whole register ranges (up to ~7·10^13 cycles: too
    /// long to step): at random cycles the identities of SPEC §5 hold between consecutive
    /// predicted states, the velocity never exceeds the plan's peak, the position never passes
    /// the destination, and the last state is exactly the destination at rest.
    #[test]
    fn long_scurve_predictions_keep_the_identities(
        parameters in strategies::any_scurve_move(),
        samples in prop::collection::vec(0.0f64..1.0, 8),
    ) {
        let Ok(axis) = SCurve::new(parameters) else { return Ok(()) };
        let plan = axis.plan();
        let future = axis.predict().unwrap();
        prop_assert_eq!(future.completion(), Some(plan.total));
        let destination = I32F32::from_num(parameters.destination);
        let last = future.state_at(plan.total);
        prop_assert_eq!(last, State { position: destination, ..State::default() });
        prop_assert_eq!(future.state_at(u64::MAX), last);
        let direction = parameters.destination.signum();
        for sample in samples {
            let n = ((plan.total as f64 * sample) as u64).clamp(1, plan.total);
            let (before, state) = (future.state_at(n - 1), future.state_at(n));
            prop_assert_eq!(state.acceleration, state.velocity - before.velocity, "cycle {}", n);
            prop_assert_eq!(state.position, before.position.wrapping_add(state.velocity));
            prop_assert!(state.velocity.abs() <= plan.peak_velocity);
            prop_assert!(state.acceleration.abs() <= plan.peak_acceleration);
            let short = (destination - state.position) * I32F32::from_num(direction);
            prop_assert!(short >= 0, "passed the destination on cycle {}", n);
        }
        let reached = future.first_cycle_at(destination).unwrap();
        prop_assert!(reached <= plan.total);
        prop_assert_eq!(future.state_at(reached).position, destination);
        if reached > 0 {
            prop_assert!(future.state_at(reached - 1).position != destination);
        }
    }
}

/// The longest S-curve move across the position register's wrap: from 2^31 − 1000.5 counts up
/// to −2^30 + 5 (the short way round: 2^30 + 1005.5 counts) at the largest velocity,
/// acceleration and jerk, checked on every one of its cycles against stepping.
#[test]
fn the_longest_scurve_move_across_the_wrap() {
    use profilegen::format::mc1451a::{Jerk, MaxVelocity, ScurveAcceleration};
    let start = I32F32::from_bits(i64::MAX - (1000 << 32) - (1 << 31) + 1);
    let axis = SCurve::with_position(
        profilegen::ScurveParameters {
            destination: -(1 << 30) + 5,
            max_velocity: MaxVelocity::MAX,
            max_acceleration: ScurveAcceleration::MAX,
            jerk: Jerk::MAX,
        },
        start,
    )
    .unwrap();
    let future = axis.predict().unwrap();
    let total = axis.plan().total;
    let mut copy = axis.clone();
    for n in 1..=total {
        assert_eq!(future.state_at(n), copy.step(), "cycle {n}");
    }
    assert_eq!(copy.state().position, -(1 << 30) + 5);
    assert_eq!(future.completion(), Some(total));
    // −2^31 + 7 counts: passed just after the wrap, on the first cycle whose position is at or
    // above it (and below the destination) — the one before is still above 2^30.
    let point = I32F32::MIN + I32F32::from_num(7);
    let n = future.first_cycle_at(point).unwrap();
    assert!(future.state_at(n - 1).position > 1 << 30);
    let there = future.state_at(n).position;
    assert!(there >= point && there <= -(1 << 30) + 5);
    // Zero lies behind the move's way round: never reached.
    assert_eq!(future.first_cycle_at(I32F32::ZERO), None);
}

/// Predictions right after an abrupt stop's command, where the generators take their detours:
/// an S-curve restarted on the cycle after the stop (its first step corrects the acceleration
/// the stop left), and a trapezoid given a new maximum velocity while the stop is pending (it
/// stops, then resumes from rest) — every cycle against stepping.
#[test]
fn restarts_after_abrupt_stops() {
    use profilegen::format::juno::Acceleration;
    use profilegen::format::mc1451a::{Jerk, MaxVelocity, ScurveAcceleration};
    let mut axis = SCurve::new(profilegen::ScurveParameters {
        destination: 3_000,
        max_velocity: MaxVelocity::from_num(20.0).unwrap(),
        max_acceleration: ScurveAcceleration::from_num(0.25).unwrap(),
        jerk: Jerk::from_num(0.01).unwrap(),
    })
    .unwrap();
    axis.states().take(60).for_each(drop);
    axis.stop(StopKind::Abrupt);
    axis.step();
    assert!(axis.state().acceleration != 0, "the stop's drop");
    axis.restart(-2_000, MaxVelocity::from_num(15.0).unwrap())
        .unwrap();
    let future = axis.predict().unwrap();
    let total = axis.plan().total;
    assert_eq!(future.completion(), Some(total));
    let mut copy = axis.clone();
    for n in 1..=total + 3 {
        assert_eq!(future.state_at(n), copy.step(), "cycle {n}");
    }

    let mut axis = Trapezoidal::new(profilegen::TrapezoidalParameters {
        destination: 5_000,
        max_velocity: TargetVelocity::from_num(30.0).unwrap(),
        acceleration: Acceleration::from_num(0.5).unwrap(),
        deceleration: Acceleration::ZERO,
        start_velocity: TargetVelocity::from_num(2.0).unwrap(),
    })
    .unwrap();
    axis.states().take(40).for_each(drop);
    axis.stop(StopKind::Abrupt);
    axis.set_max_velocity(TargetVelocity::from_num(12.0).unwrap())
        .unwrap();
    let future = axis.predict().unwrap();
    let complete = future.completion().unwrap();
    let mut copy = axis.clone();
    assert_eq!(future.state_at(1).velocity, 0, "the abrupt stop's cycle");
    for n in 1..=complete + 3 {
        assert_eq!(future.state_at(n), copy.step(), "cycle {n}");
        assert_eq!(copy.is_complete(), n >= complete, "cycle {n}");
    }
    assert_eq!(copy.state().position, 5_000);
}

/// The prediction's size, as its documentation states it (about 6 KB).
#[test]
fn a_prediction_is_about_six_kilobytes() {
    let size = core::mem::size_of::<Prediction>();
    assert!((5_000..=7_000).contains(&size), "{size} bytes");
}
