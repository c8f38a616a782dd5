//! SPEC §12.2, trapezoidal: the MCX514 driving-axis profile. Hand-traced moves at a 1 ms cycle
//! (SV 2,000 pps = 2 pulses/cycle, DV 10,000 pps = 10, AC = DC = 2,000,000 pps/s = 2
//! pulses/cycle², 100 pulses) for each deceleration mode, the conformance suite on every cycle,
//! and property tests over random registers: exact arrival, never past the finish point.

use profilegen::conformance::{check_abrupt_stop, Checker};
use profilegen::format::mcx514::{
    Acceleration, Deceleration, DriveSpeed, InitialSpeed, ManualDecelerationPoint,
};
use profilegen::format::CycleTime;
use profilegen::{
    DecelerationMode, Error, Mcx514Parameters, Mcx514Trapezoidal, ProfileGenerator, StopKind,
};
use proptest::prelude::*;

fn millisecond() -> CycleTime {
    CycleTime::from_seconds(1e-3).unwrap()
}

fn parameters(mode: DecelerationMode) -> Mcx514Parameters {
    Mcx514Parameters {
        pulses: 100,
        initial_speed: InitialSpeed::from_bits(2_000).unwrap(),
        drive_speed: DriveSpeed::from_bits(10_000).unwrap(),
        acceleration: Acceleration::from_bits(2_000_000).unwrap(),
        deceleration: Deceleration::from_bits(2_000_000).unwrap(),
        deceleration_mode: mode,
    }
}

/// The velocities (whole pulses/cycle) of a move, every cycle checked by the conformance suite,
/// and whether its last cycle was exempt from the rate limits.
fn velocities(parameters: Mcx514Parameters) -> (Vec<i64>, bool) {
    let mut axis = Mcx514Trapezoidal::new(parameters, millisecond()).unwrap();
    let mut checker = Checker::new(&axis);
    let mut velocities = Vec::new();
    while !axis.is_complete() {
        let state = checker.step(&mut axis).unwrap();
        assert_eq!(state.velocity.frac(), 0);
        velocities.push(state.velocity.to_num::<i64>());
        assert!(velocities.len() < 1_000);
    }
    assert_eq!(axis.state().position, 100);
    (velocities, axis.limits().exempt)
}

#[test]
fn automatic_deceleration_starts_when_the_pulses_left_are_at_most_those_of_the_speed_up() {
    // Speed-up 2+4+6+8+10 = 30 pulses; cruise until 30 are left (at 70); down by 2 to SV at 90;
    // creep at SV to 100; stop.
    let (v, exempt) = velocities(parameters(DecelerationMode::Automatic));
    let expected = [2, 4, 6, 8, 10, 10, 10, 10, 10, 8, 6, 4, 2, 2, 2, 2, 2, 2, 0];
    assert_eq!(v, expected);
    assert!(!exempt, "the stop from SV is within the limits");
}

#[test]
fn an_early_manual_point_creeps_at_the_initial_speed() {
    // Cruise to 50 (the point), down to SV at 70, then 15 cycles at 2 to 100.
    let point = ManualDecelerationPoint::from_bits(50).unwrap();
    let (v, _) = velocities(parameters(DecelerationMode::Manual(point)));
    let mut expected = vec![2, 4, 6, 8, 10, 10, 10, 8, 6, 4, 2];
    expected.extend([2; 15]);
    expected.push(0);
    assert_eq!(v, expected);
}

#[test]
fn a_late_manual_point_stops_at_the_finish_point_above_the_initial_speed() {
    // 95 is never reached before the finish: cruise at 10 to 100, then drop 10 → 0 (exempt).
    let point = ManualDecelerationPoint::from_bits(95).unwrap();
    let (v, exempt) = velocities(parameters(DecelerationMode::Manual(point)));
    let mut expected = vec![2, 4, 6, 8];
    expected.extend([10; 8]);
    expected.push(0);
    assert_eq!(v, expected);
    assert!(exempt);
}

#[test]
fn with_deceleration_disabled_the_move_runs_at_the_drive_speed() {
    let (v, exempt) = velocities(parameters(DecelerationMode::Disabled));
    let mut expected = vec![10; 10];
    expected.push(0);
    assert_eq!(v, expected);
    assert!(exempt);
}

#[test]
fn stops() {
    // Smooth, at 6 pulses/cycle: down by DC to SV, then rest (the chip's decelerating stop).
    let mut axis =
        Mcx514Trapezoidal::new(parameters(DecelerationMode::Automatic), millisecond()).unwrap();
    let mut checker = Checker::new(&axis);
    for _ in 0..3 {
        checker.step(&mut axis).unwrap();
    }
    axis.stop(StopKind::Smooth);
    let mut v = Vec::new();
    while !axis.is_complete() {
        v.push(checker.step(&mut axis).unwrap().velocity.to_num::<i64>());
    }
    assert_eq!(v, [4, 2, 0]);
    assert_eq!(axis.state().position, 2 + 4 + 6 + 4 + 2);
    assert_eq!(axis.step().position, 18, "complete: stays put");
    // Abrupt, at full speed.
    let mut axis =
        Mcx514Trapezoidal::new(parameters(DecelerationMode::Automatic), millisecond()).unwrap();
    for _ in 0..6 {
        axis.step();
    }
    check_abrupt_stop(&mut axis).unwrap();
}

#[test]
fn parameters_the_chip_would_not_take_are_errors() {
    let mut bad = parameters(DecelerationMode::Automatic);
    bad.initial_speed = InitialSpeed::from_bits(10_001).unwrap();
    let error = Mcx514Trapezoidal::new(bad, millisecond()).unwrap_err();
    assert!(
        matches!(error, Error::OutOfRange { parameter: "initial speed", value, range }
            if value == 10_001.0 && range.min == 1.0 && range.max == 10_000.0),
        "{error:?}"
    );
    let mut bad = parameters(DecelerationMode::Automatic);
    bad.deceleration = Deceleration::from_bits(1_000_000).unwrap();
    let error = Mcx514Trapezoidal::new(bad, millisecond()).unwrap_err();
    assert!(matches!(
        error,
        Error::Refused {
            parameter: "deceleration",
            ..
        }
    ));
    assert!(error.to_string().contains("manual deceleration point"));
    // The same rates are fine with a manual point.
    bad.deceleration_mode =
        DecelerationMode::Manual(ManualDecelerationPoint::from_bits(60).unwrap());
    assert!(Mcx514Trapezoidal::new(bad, millisecond()).is_ok());
    let mut bad = parameters(DecelerationMode::Automatic);
    bad.pulses = 1 << 30;
    let error = Mcx514Trapezoidal::new(bad, millisecond()).unwrap_err();
    assert!(
        matches!(error, Error::OutOfRange { parameter: "finish point", value, .. } if value == (1u64 << 30) as f64)
    );
    // A jerk-free register that vanishes at a short cycle: 1 pps/s at 1 µs is 1e-12/cycle².
    let mut bad = parameters(DecelerationMode::Automatic);
    bad.acceleration = Acceleration::MIN;
    bad.deceleration = Deceleration::MIN;
    let error = Mcx514Trapezoidal::new(bad, CycleTime::from_seconds(1e-6).unwrap()).unwrap_err();
    assert!(matches!(
        error,
        Error::Underflow {
            parameter: "acceleration",
            ..
        }
    ));
}

#[test]
fn zero_pulses_is_complete_at_once() {
    let mut zero = parameters(DecelerationMode::Automatic);
    zero.pulses = 0;
    let mut axis = Mcx514Trapezoidal::new(zero, millisecond()).unwrap();
    assert!(axis.is_complete());
    assert_eq!(axis.step().position, 0);
}

/// A log-uniform integer in 1 ..= max.
fn log_uniform(max: u32) -> impl Strategy<Value = u32> {
    (0..32 - max.leading_zeros())
        .prop_flat_map(move |b| (1u32 << b)..=((1u64 << (b + 1)) - 1).min(u64::from(max)) as u32)
}

prop_compose! {
    /// Random registers at 1 ms, SV ≥ 1,000 pps (≥ 1 pulse/cycle) so a move of ≤ 200,000 pulses
    /// ends within 200,000 cycles; AC = DC for automatic deceleration.
    fn move_parameters()(
        drive in log_uniform(8_000_000).prop_map(|d| d.max(1_000)),
        initial_fraction in 0.0f64..=1.0,
        acceleration in log_uniform(536_870_911),
        deceleration in log_uniform(536_870_911),
        pulses in prop_oneof![0u32..=200, 0u32..=200_000],
        mode in 0..3u8,
        point_fraction in 0.0f64..=1.2,
    ) -> Mcx514Parameters {
        let initial = (1_000.0 + initial_fraction * f64::from(drive - 1_000)) as u32;
        let point = (point_fraction * f64::from(pulses)) as u32;
        let deceleration_mode = match mode {
            0 => DecelerationMode::Automatic,
            1 => DecelerationMode::Manual(ManualDecelerationPoint::from_bits(point).unwrap()),
            _ => DecelerationMode::Disabled,
        };
        let deceleration = if mode == 0 { acceleration } else { deceleration };
        Mcx514Parameters {
            pulses,
            initial_speed: InitialSpeed::from_bits(initial).unwrap(),
            drive_speed: DriveSpeed::from_bits(drive).unwrap(),
            acceleration: Acceleration::from_bits(acceleration).unwrap(),
            deceleration: Deceleration::from_bits(deceleration).unwrap(),
            deceleration_mode,
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(3_000))]

    #[test]
    fn every_move_conforms_and_lands_exactly(parameters in move_parameters()) {
        let mut axis = Mcx514Trapezoidal::new(parameters, millisecond()).unwrap();
        let mut checker = Checker::new(&axis);
        let finish = i64::from(parameters.pulses) << 32;
        let initial = i64::from(parameters.initial_speed.to_bits()) * (1i64 << 32) / 1_000;
        while !axis.is_complete() {
            let before = axis.state();
            let state = checker.step(&mut axis).unwrap();
            let (position, velocity) = (state.position.to_bits(), state.velocity.to_bits());
            prop_assert!(position <= finish, "past the finish point");
            // Moving at or above SV, except the cycle cut to the pulses left and the stop.
            let left = finish - before.position.to_bits();
            prop_assert!(velocity + 1 >= initial || velocity == left || velocity == 0);
            prop_assert!(checker.cycles() <= 250_000);
        }
        prop_assert_eq!(axis.state().position.to_bits(), finish);
    }
}

#[test]
fn the_largest_registers_at_a_long_cycle_do_not_overflow() {
    // At 2 s: AC = (2^29 − 1)·4 = 2,147,483,644 pulses/cycle², just under I32F32's 2^31; SV
    // 8,000,000 pulses/cycle. The speed-up from SV would pass i64 in raw bits unless saturated.
    let two_seconds = CycleTime::from_seconds(2.0).unwrap();
    for mode in [
        DecelerationMode::Automatic,
        DecelerationMode::Manual(ManualDecelerationPoint::from_bits(1 << 29).unwrap()),
    ] {
        let parameters = Mcx514Parameters {
            pulses: 1_073_741_823,
            initial_speed: InitialSpeed::from_bits(4_000_000).unwrap(),
            drive_speed: DriveSpeed::MAX,
            acceleration: Acceleration::MAX,
            deceleration: Deceleration::MAX,
            deceleration_mode: mode,
        };
        let mut axis = Mcx514Trapezoidal::new(parameters, two_seconds).unwrap();
        let mut checker = Checker::new(&axis);
        checker.run_until_complete(&mut axis, 1_000).unwrap();
        assert!(axis.is_complete());
        assert_eq!(axis.state().position, 1_073_741_823);
    }
}

#[test]
fn the_largest_manual_point_is_never_reached() {
    // 4,294,967,292 pulses, the register's top, is past every finish point: the move cruises at
    // DV to the finish point and stops there (2, 4, 6, 8, 10 then 10s to 100: 30 + 7·10), as a
    // late point does; not (as a point wrapped negative would make it) a creep from the start.
    let point = ManualDecelerationPoint::MAX;
    let (v, exempt) = velocities(parameters(DecelerationMode::Manual(point)));
    assert_eq!(v, [2, 4, 6, 8, 10, 10, 10, 10, 10, 10, 10, 10, 0]);
    assert!(exempt);
}
