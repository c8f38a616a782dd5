//! The trapezoidal point-to-point generator (SPEC §7) and its stops (SPEC §9).

mod strategies;

use fixed::types::I32F32;
use profilegen::conformance::{check_abrupt_stop, Checker};
use profilegen::format::juno::{Acceleration, TargetVelocity};
use profilegen::reference::trapezoidal_duration;
use profilegen::{Error, ProfileGenerator, State, StopKind, Trapezoidal, TrapezoidalParameters};
use proptest::prelude::*;
use strategies::{moderate_trapezoidal, trapezoidal_command, trapezoidal_move, TrapezoidalCommand};

fn parameters(
    destination: i32,
    max_velocity: f64,
    acceleration: f64,
    deceleration: f64,
) -> TrapezoidalParameters {
    TrapezoidalParameters {
        destination,
        max_velocity: TargetVelocity::from_num(max_velocity).unwrap(),
        acceleration: Acceleration::from_num(acceleration).unwrap(),
        deceleration: Acceleration::from_num(deceleration).unwrap(),
        start_velocity: TargetVelocity::ZERO,
    }
}

/// Runs to completion through the conformance checker; returns every state after the first.
fn run(axis: &mut Trapezoidal) -> Vec<State> {
    let mut checker = Checker::new(axis);
    let mut states = Vec::new();
    while !axis.is_complete() {
        states.push(checker.step(axis).unwrap());
        assert!(states.len() < 10_000_000, "no arrival");
    }
    states
}

fn velocities(states: &[State]) -> Vec<f64> {
    states.iter().map(|s| s.velocity.to_num()).collect()
}

#[test]
fn a_one_count_move() {
    // From rest: v = 1 reaches the destination (T(1) = 1 ≤ 1); then the drop of 1 ≤ D to rest.
    let mut axis = Trapezoidal::new(parameters(1, 10.0, 1.0, 0.0)).unwrap();
    let states = run(&mut axis);
    assert_eq!(velocities(&states), [1.0, 0.0]);
    assert_eq!(
        states.last().unwrap(),
        &State {
            position: I32F32::ONE,
            velocity: I32F32::ZERO,
            acceleration: -I32F32::ONE
        }
    );
}

#[test]
fn a_triangle() {
    // A = D = 1, 9 counts: 1 + 2 + 3 + 2 + 1 = 9, never reaching the maximum velocity.
    let mut axis = Trapezoidal::new(parameters(9, 100.0, 1.0, 1.0)).unwrap();
    let states = run(&mut axis);
    assert_eq!(velocities(&states), [1.0, 2.0, 3.0, 2.0, 1.0, 0.0]);
    let positions: Vec<f64> = states.iter().map(|s| s.position.to_num()).collect();
    assert_eq!(positions, [1.0, 3.0, 6.0, 8.0, 9.0, 9.0]);
}

#[test]
fn a_move_whose_cruise_is_one_cycle() {
    // A = D = 1, maximum 3, 12 counts: 1 + 2 + 3 + 3 + 2 + 1 = 12: one cycle at 3 after the ramp.
    let mut axis = Trapezoidal::new(parameters(12, 3.0, 1.0, 0.0)).unwrap();
    let states = run(&mut axis);
    assert_eq!(velocities(&states), [1.0, 2.0, 3.0, 3.0, 2.0, 1.0, 0.0]);
}

#[test]
fn a_fractional_landing() {
    // A = D = 1, 10 counts: after 1 + 2 + 3 the remaining 4 counts need T(v) ≤ 4, which is
    // v = 7/3 (T(v) = 3v − 3 on 2 ≤ v < 3), floored to 2^-32; then 4/3 and 1/3 (each rounding
    // leaves its remainder to the next cycle) and exact arrival at 10.
    let mut axis = Trapezoidal::new(parameters(-10, 100.0, 1.0, 0.0)).unwrap();
    let states = run(&mut axis);
    let raw: Vec<i64> = states.iter().map(|s| -s.velocity.to_bits()).collect();
    let seven_thirds = (7i64 << 32) / 3;
    let four = 4i64 << 32;
    let next = ((four - seven_thirds) + (1i64 << 32)) / 2; // q = 1: (d + D) / 2
    assert_eq!(
        raw,
        [
            1 << 32,
            2 << 32,
            3 << 32,
            seven_thirds,
            next,
            four - seven_thirds - next,
            0
        ]
    );
    assert_eq!(states.last().unwrap().position, I32F32::from_num(-10));
}

#[test]
fn bad_parameters_are_refused_and_change_nothing() {
    let good = parameters(100, 2.0, 0.5, 0.0);
    let mut zero_velocity = good;
    zero_velocity.max_velocity = TargetVelocity::ZERO;
    assert!(matches!(
        Trapezoidal::new(zero_velocity),
        Err(Error::Zero {
            parameter: "velocity",
            ..
        })
    ));
    let mut negative = good;
    negative.max_velocity = TargetVelocity::from_num(-2.0).unwrap();
    assert!(matches!(
        Trapezoidal::new(negative),
        Err(Error::OutOfRange {
            parameter: "velocity",
            ..
        })
    ));
    let mut zero_acceleration = good;
    zero_acceleration.acceleration = Acceleration::ZERO;
    assert!(matches!(
        Trapezoidal::new(zero_acceleration),
        Err(Error::Zero {
            parameter: "acceleration",
            ..
        })
    ));
    let mut fast_start = good;
    fast_start.start_velocity = TargetVelocity::from_num(3.0).unwrap();
    assert!(matches!(
        Trapezoidal::new(fast_start),
        Err(Error::OutOfRange {
            parameter: "start velocity",
            ..
        })
    ));

    let mut axis = Trapezoidal::new(good).unwrap();
    axis.step();
    let before = (axis.parameters(), axis.state());
    assert!(axis.set_acceleration(Acceleration::ZERO).is_err());
    assert!(axis.set_max_velocity(TargetVelocity::ZERO).is_err());
    assert!(axis
        .set_start_velocity(TargetVelocity::from_num(5.0).unwrap())
        .is_err());
    assert_eq!((axis.parameters(), axis.state()), before);
}

#[test]
fn starting_velocity_jump() {
    let mut move_with_start = parameters(1_000, 8.0, 0.25, 0.0);
    move_with_start.start_velocity = TargetVelocity::from_num(3.0).unwrap();
    let mut axis = Trapezoidal::new(move_with_start).unwrap();
    let states = run(&mut axis);
    assert_eq!(
        states[0].velocity, 3.25,
        "the first cycle begins at the starting velocity and accelerates"
    );
    assert_eq!(states[1].velocity, 3.5, "then accelerates at A");
    assert_eq!(states.last().unwrap().position, 1_000);
}

#[test]
fn reversal_when_the_destination_moves_behind() {
    let mut axis = Trapezoidal::new(parameters(10_000, 20.0, 0.5, 0.25)).unwrap();
    let mut checker = Checker::new(&axis);
    for _ in 0..100 {
        checker.step(&mut axis).unwrap();
    }
    axis.set_destination(-500);
    let mut states = Vec::new();
    while !axis.is_complete() {
        states.push(checker.step(&mut axis).unwrap());
    }
    let crossing = states.iter().position(|s| s.velocity < 0).unwrap();
    assert!(
        states[..crossing].iter().all(|s| s.acceleration == -0.25),
        "decelerate at D"
    );
    assert!(
        states[crossing + 1..]
            .iter()
            .take(10)
            .all(|s| s.acceleration == -0.5),
        "then accelerate at A"
    );
    assert_eq!(states.last().unwrap().position, -500);
}

#[test]
fn a_lower_maximum_velocity_decelerates_at_d_to_it() {
    let mut axis = Trapezoidal::new(parameters(100_000, 20.0, 1.0, 0.5)).unwrap();
    let mut checker = Checker::new(&axis);
    for _ in 0..30 {
        checker.step(&mut axis).unwrap();
    }
    axis.set_max_velocity(TargetVelocity::from_num(10.0).unwrap())
        .unwrap();
    let states: Vec<State> = (0..30).map(|_| checker.step(&mut axis).unwrap()).collect();
    assert_eq!(
        velocities(&states)[..21],
        (0..21)
            .map(|k| (19.5 - 0.5 * k as f64).max(10.0))
            .collect::<Vec<_>>()[..]
    );
    assert_eq!(run(&mut axis).last().unwrap().position, 100_000);
}

#[test]
fn smooth_stop_then_restart_needs_a_velocity() {
    let mut axis = Trapezoidal::new(parameters(100_000, 20.0, 1.0, 0.5)).unwrap();
    let mut checker = Checker::new(&axis);
    for _ in 0..30 {
        checker.step(&mut axis).unwrap();
    }
    axis.stop(StopKind::Smooth);
    assert_eq!(axis.parameters().max_velocity, TargetVelocity::ZERO);
    let mut states = Vec::new();
    while !axis.is_complete() {
        states.push(checker.step(&mut axis).unwrap());
    }
    assert_eq!(states.len(), 40, "20 counts/cycle at 0.5");
    assert!(states.iter().all(|s| s.acceleration == -0.5));
    let rest = axis.state();
    axis.set_destination(0);
    assert!(axis.is_complete(), "a destination alone does not restart");
    assert_eq!(axis.step(), State::at_rest(rest.position));
    axis.set_max_velocity(TargetVelocity::from_num(5.0).unwrap())
        .unwrap();
    assert!(!axis.is_complete());
    assert_eq!(run(&mut axis).last().unwrap().position, 0);
}

#[test]
fn abrupt_stop_holds_position() {
    let mut axis = Trapezoidal::new(parameters(100_000, 20.0, 1.0, 0.5)).unwrap();
    let mut checker = Checker::new(&axis);
    for _ in 0..30 {
        checker.step(&mut axis).unwrap();
    }
    check_abrupt_stop(&mut axis).unwrap();
}

#[test]
fn the_short_way_round_the_32_bit_position() {
    // From −2^31 + 5 to 2^31 − 6 is 11 counts backwards through the wrap, as on the chip.
    let start = I32F32::from_num(i32::MIN + 5);
    let mut axis =
        Trapezoidal::with_position(parameters(i32::MAX - 5, 4.0, 1.0, 0.0), start).unwrap();
    let states = run(&mut axis);
    assert!(states.iter().all(|s| s.velocity <= 0));
    assert_eq!(
        states.last().unwrap().position,
        I32F32::from_num(i32::MAX - 5)
    );
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(10_000))]

    /// Moves from rest with constant parameters: exact arrival at rest, the limits and identities
    /// on every cycle (the conformance checker), no overshoot, and at most 2 cycles more than the
    /// continuous-time optimum.
    #[test]
    fn moves_from_rest(move_ in trapezoidal_move()) {
        let mut axis = Trapezoidal::new(move_).unwrap();
        let mut checker = Checker::new(&axis);
        let destination = I32F32::from_num(move_.destination);
        let direction = destination.signum();
        let mut cycles = 0u64;
        let mut last = axis.state();
        while !axis.is_complete() {
            let state = checker.step(&mut axis).map_err(|v| TestCaseError::fail(v.to_string()))?;
            cycles += 1;
            prop_assert!((state.position - last.position) * direction >= 0, "monotone");
            prop_assert!((destination - state.position) * direction >= 0, "no overshoot");
            last = state;
            prop_assert!(cycles < 10_000_000);
        }
        prop_assert_eq!(last.position, destination);
        prop_assert_eq!(last.velocity, I32F32::ZERO);
        let optimum = trapezoidal_duration(
            f64::from(move_.destination).abs(),
            move_.max_velocity.to_f64(),
            move_.acceleration.to_f64(),
            if move_.deceleration.is_zero() { move_.acceleration.to_f64() } else { move_.deceleration.to_f64() },
            move_.start_velocity.to_f64(),
        );
        prop_assert!(cycles as f64 <= optimum + 2.0, "{} cycles, optimum {}", cycles, optimum);
    }

    /// Random changes in motion: identities and limits on every cycle, and the axis always
    /// comes to rest exactly on the final destination (or, after a stop, at rest).
    #[test]
    fn changes_in_motion(
        initial in moderate_trapezoidal(),
        script in prop::collection::vec((0u32..400, trapezoidal_command()), 1..10),
    ) {
        let mut axis = Trapezoidal::new(initial).unwrap();
        let mut checker = Checker::new(&axis);
        let mut stopped = false;
        for (gap, command) in script {
            for _ in 0..gap {
                checker.step(&mut axis).map_err(|v| TestCaseError::fail(v.to_string()))?;
            }
            match command {
                TrapezoidalCommand::Destination(d) => axis.set_destination(d),
                TrapezoidalCommand::MaxVelocity(v) => { axis.set_max_velocity(v).unwrap(); stopped = false; }
                TrapezoidalCommand::Acceleration(a) => axis.set_acceleration(a).unwrap(),
                TrapezoidalCommand::Deceleration(d) => axis.set_deceleration(d),
                TrapezoidalCommand::Stop(kind) => { axis.stop(kind); stopped = true; }
            }
            checker.command_given(&axis);
        }
        let mut cycles = 0;
        while !axis.is_complete() {
            checker.step(&mut axis).map_err(|v| TestCaseError::fail(v.to_string()))?;
            cycles += 1;
            prop_assert!(cycles < 5_000_000, "never came to rest");
        }
        prop_assert_eq!(axis.state().velocity, I32F32::ZERO);
        if !stopped {
            prop_assert_eq!(axis.state().position, I32F32::from_num(axis.parameters().destination));
        }
    }
}
