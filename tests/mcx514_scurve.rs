//! SPEC §12.2, S-curve: the MCX514 driving-axis profile with jerk. A hand-traced move at a 1 ms
//! cycle (SV 1,000 pps = 1 pulse/cycle, DV 10,000 pps = 10, AC = DC = 2,000,000 pps/s = 2
//! pulses/cycle², JK = DJ = 1,000,000,000 pps/s² = 1 pulse/cycle³), the conformance suite on
//! every cycle (identities; speed-ups within AC, slow-downs within DC, the rate within AC/DC and
//! its change within JK/DJ, between the start, the cuts to the pulses left and the stop), and
//! property tests over the register ranges: exact arrival, never past the finish point, never
//! below SV while moving, no overflow at the largest registers.

use profilegen::conformance::{check_abrupt_stop, Checker};
use profilegen::format::mcx514::{
    Acceleration, Deceleration, DecelerationJerk, DriveSpeed, InitialSpeed, Jerk,
    ManualDecelerationPoint,
};
use profilegen::format::CycleTime;
use profilegen::reference::scurve_duration;
use profilegen::{
    DecelerationMode, Error, Mcx514Parameters, Mcx514SCurve, Mcx514ScurveParameters,
    ProfileGenerator, StopKind,
};
use proptest::prelude::*;

fn millisecond() -> CycleTime {
    CycleTime::from_seconds(1e-3).unwrap()
}

fn parameters(pulses: u32, mode: DecelerationMode) -> Mcx514ScurveParameters {
    Mcx514ScurveParameters {
        trapezoid: Mcx514Parameters {
            pulses,
            initial_speed: InitialSpeed::from_bits(1_000).unwrap(),
            drive_speed: DriveSpeed::from_bits(10_000).unwrap(),
            acceleration: Acceleration::from_bits(2_000_000).unwrap(),
            deceleration: Deceleration::from_bits(2_000_000).unwrap(),
            deceleration_mode: mode,
        },
        jerk: Jerk::from_bits(1_000_000_000).unwrap(),
        deceleration_jerk: DecelerationJerk::from_bits(1_000_000_000).unwrap(),
    }
}

/// The velocities (whole pulses/cycle) of a move, every cycle checked by the conformance suite,
/// and whether its last cycle was exempt from the limits.
fn velocities(parameters: Mcx514ScurveParameters) -> (Vec<i64>, bool) {
    let mut axis = Mcx514SCurve::new(parameters, millisecond()).unwrap();
    let mut checker = Checker::new(&axis);
    let mut velocities = Vec::new();
    while !axis.is_complete() {
        let state = checker.step(&mut axis).unwrap();
        assert_eq!(state.velocity.frac(), 0);
        velocities.push(state.velocity.to_num::<i64>());
        assert!(velocities.len() < 1_000);
    }
    assert_eq!(axis.state().position, parameters.trapezoid.pulses);
    (velocities, axis.limits().exempt)
}

#[test]
fn a_hand_traced_automatic_move() {
    // Speed-up from SV 1: the rate rises by 1 to AC 2 while a ramp-down from it still fits under
    // DV (1 + 1 + S(1) = 2, 2 + 2 + S(2) = 2 + 2 + 1 ≤ 10, …), holds at 2 (4, 6, 8), then falls:
    // 8 + 2 + 1 > 10 so 1 (9), 9 + 1 = 10 (the rate 1 fits exactly), and 0 at DV. Pulses
    // output while speeding up: 1 + 2 + 4 + 6 + 8 + 9 + 10 = 40. Cruise while more than 40 are
    // left (positions 50, 60); at 60, 40 are left: the mirror image down to SV (9, 7, 5, 3, 2,
    // 1) reaches 87; creep at 1 to 100 (13 cycles); stop.
    let (v, _) = velocities(parameters(100, DecelerationMode::Automatic));
    let mut expected = vec![1, 2, 4, 6, 8, 9, 10, 10, 10, 9, 7, 5, 3, 2, 1];
    expected.extend([1; 13]);
    expected.push(0); // the stop from SV at the finish point
    assert_eq!(v, expected);
}

#[test]
fn a_manual_point_decelerates_there_and_creeps() {
    // Cruise at 10 from 40: the output count reaches 70 at the start of the cycle after 70
    // (positions 50, 60, 70), then down 9, 7, 5, 3, 2, 1 to 97, creep 3 cycles at 1, stop.
    let point = ManualDecelerationPoint::from_bits(70).unwrap();
    let (v, _) = velocities(parameters(100, DecelerationMode::Manual(point)));
    assert_eq!(
        v,
        [1, 2, 4, 6, 8, 9, 10, 10, 10, 10, 9, 7, 5, 3, 2, 1, 1, 1, 1, 0]
    );
}

#[test]
fn a_late_manual_point_stops_at_the_finish_point_above_the_initial_speed() {
    // The point at 95: at 90 (after 10, 10, 10, 10, 10 from 40) the point is not reached; the
    // next cycle's 10 is cut to the 10 left... the move arrives at DV and stops there, exempt.
    let point = ManualDecelerationPoint::from_bits(95).unwrap();
    let (v, exempt) = velocities(parameters(100, DecelerationMode::Manual(point)));
    assert_eq!(v, [1, 2, 4, 6, 8, 9, 10, 10, 10, 10, 10, 10, 10, 0]);
    assert!(exempt, "a stop from DV is exempt");
}

#[test]
fn with_deceleration_disabled_the_move_runs_at_the_drive_speed() {
    let (v, _) = velocities(parameters(35, DecelerationMode::Disabled));
    assert_eq!(v, [10, 10, 10, 5, 0]);
}

#[test]
fn a_move_too_short_for_the_drive_speed_eases_then_stops_above_the_initial_speed() {
    // 30 pulses: 1, 2, 4, 6, 8 (21 output, all speeding up, the rate 2); at 21, 9 are left
    // ≤ 21: deceleration starts with the rate still 2, which first falls by JK to 1: 9, and that
    // reaches the finish point, above SV, where the move stops (exempt). The automatic point is
    // the chip's rule; a short S-curve can arrive above SV.
    let (v, exempt) = velocities(parameters(30, DecelerationMode::Automatic));
    assert_eq!(v, [1, 2, 4, 6, 8, 9, 0]);
    assert!(exempt);
}

#[test]
fn stops() {
    // Smooth: from the cruise, the S-curve down to SV, then stop (not at the finish point).
    let mut axis = Mcx514SCurve::new(
        parameters(1_000, DecelerationMode::Automatic),
        millisecond(),
    )
    .unwrap();
    let mut checker = Checker::new(&axis);
    for _ in 0..10 {
        checker.step(&mut axis).unwrap();
    }
    assert_eq!(axis.state().velocity, 10);
    axis.stop(StopKind::Smooth);
    let mut v = Vec::new();
    while !axis.is_complete() {
        v.push(checker.step(&mut axis).unwrap().velocity.to_num::<i64>());
    }
    // Down to SV (the rates 1, 2, 2, 2, 1, 1), and the stop from there.
    assert_eq!(v, [9, 7, 5, 3, 2, 1, 0]);
    // Abrupt: velocity zero on the next cycle, position held.
    let mut axis = Mcx514SCurve::new(
        parameters(1_000, DecelerationMode::Automatic),
        millisecond(),
    )
    .unwrap();
    for _ in 0..4 {
        axis.step();
    }
    check_abrupt_stop(&mut axis).unwrap();
}

#[test]
fn parameters_the_chip_would_not_take_are_errors() {
    let mut asymmetric = parameters(100, DecelerationMode::Automatic);
    asymmetric.deceleration_jerk = DecelerationJerk::from_bits(5).unwrap();
    match Mcx514SCurve::new(asymmetric, millisecond()) {
        Err(Error::Refused { parameter, .. }) => {
            assert_eq!(parameter, "deceleration increasing rate")
        }
        other => panic!("{other:?}"),
    }
    // With a manual point, asymmetric is fine.
    asymmetric.trapezoid.deceleration_mode =
        DecelerationMode::Manual(ManualDecelerationPoint::from_bits(50).unwrap());
    assert!(Mcx514SCurve::new(asymmetric, millisecond()).is_ok());
    // A jerk that vanishes at this cycle time: 1 pps/s² · (1 µs)³ rounds to zero.
    let tiny = parameters(100, DecelerationMode::Disabled);
    let microsecond = CycleTime::from_seconds(1e-6).unwrap();
    let mut tiny_jerk = tiny;
    tiny_jerk.jerk = Jerk::from_bits(1).unwrap();
    tiny_jerk.deceleration_jerk = DecelerationJerk::from_bits(1).unwrap();
    assert!(matches!(
        Mcx514SCurve::new(tiny_jerk, microsecond),
        Err(Error::Underflow {
            parameter: "jerk",
            ..
        })
    ));
    // SV above DV: as the trapezoid.
    let mut slow = tiny;
    slow.trapezoid.initial_speed = InitialSpeed::from_bits(20_000).unwrap();
    assert!(matches!(
        Mcx514SCurve::new(slow, millisecond()),
        Err(Error::OutOfRange {
            parameter: "initial speed",
            ..
        })
    ));
}

fn log_uniform(max: u32) -> impl Strategy<Value = u32> {
    (0..32 - max.leading_zeros())
        .prop_flat_map(move |b| (1u32 << b)..=((1u64 << (b + 1)) - 1).min(u64::from(max)) as u32)
}

prop_compose! {
    /// Random registers at 1 ms, SV ≥ 1,000 pps (≥ 1 pulse/cycle, so a move of ≤ 200,000 pulses
    /// ends within 200,000 cycles), JK and DJ over their whole range (≥ 10⁻⁹ pulses/cycle³ here);
    /// symmetric for automatic deceleration.
    fn move_parameters()(
        drive in log_uniform(8_000_000).prop_map(|d| d.max(1_000)),
        initial_fraction in 0.0f64..=1.0,
        acceleration in log_uniform(536_870_911),
        deceleration in log_uniform(536_870_911),
        jerk in log_uniform(1_073_741_823),
        deceleration_jerk in log_uniform(1_073_741_823),
        pulses in prop_oneof![0u32..=200, 0u32..=200_000],
        mode in 0..3u8,
        point_fraction in 0.0f64..=1.2,
    ) -> Mcx514ScurveParameters {
        let initial = (1_000.0 + initial_fraction * f64::from(drive - 1_000)) as u32;
        let point = (point_fraction * f64::from(pulses)) as u32;
        let deceleration_mode = match mode {
            0 => DecelerationMode::Automatic,
            1 => DecelerationMode::Manual(ManualDecelerationPoint::from_bits(point).unwrap()),
            _ => DecelerationMode::Disabled,
        };
        let (deceleration, deceleration_jerk) =
            if mode == 0 { (acceleration, jerk) } else { (deceleration, deceleration_jerk) };
        Mcx514ScurveParameters {
            trapezoid: Mcx514Parameters {
                pulses,
                initial_speed: InitialSpeed::from_bits(initial).unwrap(),
                drive_speed: DriveSpeed::from_bits(drive).unwrap(),
                acceleration: Acceleration::from_bits(acceleration).unwrap(),
                deceleration: Deceleration::from_bits(deceleration).unwrap(),
                deceleration_mode,
            },
            jerk: Jerk::from_bits(jerk).unwrap(),
            deceleration_jerk: DecelerationJerk::from_bits(deceleration_jerk).unwrap(),
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(2_000))]

    #[test]
    fn every_move_conforms_and_lands_exactly(parameters in move_parameters()) {
        let mut axis = Mcx514SCurve::new(parameters, millisecond()).unwrap();
        let mut checker = Checker::new(&axis);
        let finish = i64::from(parameters.trapezoid.pulses) << 32;
        let initial =
            i64::from(parameters.trapezoid.initial_speed.to_bits()) * (1i64 << 32) / 1_000;
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

    #[test]
    fn a_smooth_stop_anywhere_ends_at_rest_within_the_limits(
        parameters in move_parameters(),
        at in 0u32..400,
    ) {
        let mut axis = Mcx514SCurve::new(parameters, millisecond()).unwrap();
        let mut checker = Checker::new(&axis);
        for _ in 0..at {
            checker.step(&mut axis).unwrap();
        }
        axis.stop(StopKind::Smooth);
        checker.run_until_complete(&mut axis, 300_000).unwrap();
        prop_assert!(axis.is_complete());
        prop_assert!(axis.state().position.to_bits() <= i64::from(parameters.trapezoid.pulses) << 32);
    }
}

#[test]
fn the_largest_registers_at_a_long_cycle_do_not_overflow() {
    // At 1 s: JK = 2³⁰ − 1 pulses/cycle³, AC = 2²⁹ − 1 pulses/cycle², DV 8,000,000 pulses/cycle,
    // SV 4,000,000 (so the creep, if any, is short).
    let second = CycleTime::from_seconds(1.0).unwrap();
    for mode in [
        DecelerationMode::Automatic,
        DecelerationMode::Manual(ManualDecelerationPoint::from_bits(1 << 29).unwrap()),
        DecelerationMode::Disabled,
    ] {
        let parameters = Mcx514ScurveParameters {
            trapezoid: Mcx514Parameters {
                pulses: 1_073_741_823,
                initial_speed: InitialSpeed::from_bits(4_000_000).unwrap(),
                drive_speed: DriveSpeed::MAX,
                acceleration: Acceleration::MAX,
                deceleration: Deceleration::MAX,
                deceleration_mode: mode,
            },
            jerk: Jerk::MAX,
            deceleration_jerk: DecelerationJerk::MAX,
        };
        let mut axis = Mcx514SCurve::new(parameters, second).unwrap();
        let mut checker = Checker::new(&axis);
        checker.run_until_complete(&mut axis, 1_000_000).unwrap();
        assert_eq!(axis.state().position, 1_073_741_823);
    }
}

#[test]
fn the_largest_manual_point_is_never_reached() {
    // The register's top is past every finish point: as the late point above, DV to the finish
    // point (40 while speeding up, then 6 cycles at 10) and the stop there.
    let point = ManualDecelerationPoint::MAX;
    let (v, exempt) = velocities(parameters(100, DecelerationMode::Manual(point)));
    assert_eq!(v, [1, 2, 4, 6, 8, 9, 10, 10, 10, 10, 10, 10, 10, 0]);
    assert!(exempt);
}

/// A gap (DV − SV, or the excess over SV when slowing) below one cycle's jerk: the rate steps to
/// the gap itself. Found by the scripts (issue #17): with the rate at zero the ramp only offered
/// +J (too much) or staying, so the speed never reached DV and a smooth stop never ended.
#[test]
fn a_gap_below_one_jerk_step_is_closed_in_one_cycle() {
    // SV 1 pulse/cycle, DV 1.5, AC 2, JK = DJ 1 (1 ms). By hand: SV on the first cycle; the gap
    // 0.5 < J: rate 0.5, DV on the second (2.5 pulses output: the automatic trigger is
    // 100 − 2.5 = 97.5); cruise to 98.5 (65 cycles at 1.5 from 1), then the excess 0.5 in one
    // cycle (1, at 99.5) and the last 0.5 pulse, cut.
    let mut registers = parameters(100, DecelerationMode::Automatic);
    registers.trapezoid.drive_speed = DriveSpeed::from_bits(1_500).unwrap();
    let mut axis = Mcx514SCurve::new(registers, millisecond()).unwrap();
    let mut checker = Checker::new(&axis);
    let mut v = Vec::new();
    while !axis.is_complete() && v.len() < 1_000 {
        v.push(checker.step(&mut axis).unwrap().velocity.to_num::<f64>());
    }
    let mut expected = vec![1.0];
    expected.extend([1.5; 65]);
    expected.extend([1.0, 0.5, 0.0]);
    assert_eq!(v, expected);
    assert_eq!(axis.state().position, 100);

    // A smooth stop in the cruise: down to SV in one cycle, then the stop.
    let mut axis = Mcx514SCurve::new(registers, millisecond()).unwrap();
    let mut checker = Checker::new(&axis);
    for _ in 0..10 {
        checker.step(&mut axis).unwrap();
    }
    axis.stop(StopKind::Smooth);
    let mut v = Vec::new();
    while !axis.is_complete() && v.len() < 1_000 {
        v.push(checker.step(&mut axis).unwrap().velocity.to_num::<f64>());
    }
    assert_eq!(v, [1.0, 0.0]);
}

/// A 1/1024 s cycle, so that the registers below convert exactly (powers of two).
fn cycle_1024() -> CycleTime {
    CycleTime::from_seconds(1.0 / 1024.0).unwrap()
}

#[test]
fn a_cap_between_two_jerk_steps_reaches_the_drive_speed_without_creeping() {
    // At 1/1024 s: SV 1,024 pps = 1 pulse/cycle, DV 2,560 = 2.5, AC = DC 327,680 pps/s = 5/16
    // pulse/cycle², JK = DJ 268,435,456 pps/s² = 1/4 pulse/cycle³: the cap is 1¼ jerk steps.
    // Speed-up, gap 3/2: rate 1/4 (gap 5/4); the cap 5/16 (its ramp-down adds S(5/16) = 1/16,
    // 5/16 + 1/16 ≤ 5/4; gap 15/16), 5/16 (5/8), 5/16 (5/16); now the cap no longer fits
    // (3/8 > 5/16) and the slack over the tail, 5/16 − 1/16 = 1/4, lies between rate − J = 1/16
    // and the rate: 1/4 in one cycle (gap 1/16 = the tail), then the tail's 1/16, at DV with
    // the rate at zero: 6 cycles. (Choosing only rate ± J, the rate fell to 1/16 with 5/16 to
    // go and crept there for 5 cycles.) The slow-down from the manual point mirrors it.
    let point = ManualDecelerationPoint::from_bits(100).unwrap();
    let parameters = Mcx514ScurveParameters {
        trapezoid: Mcx514Parameters {
            pulses: 200,
            initial_speed: InitialSpeed::from_bits(1_024).unwrap(),
            drive_speed: DriveSpeed::from_bits(2_560).unwrap(),
            acceleration: Acceleration::from_bits(327_680).unwrap(),
            deceleration: Deceleration::from_bits(327_680).unwrap(),
            deceleration_mode: DecelerationMode::Manual(point),
        },
        jerk: Jerk::from_bits(268_435_456).unwrap(),
        deceleration_jerk: DecelerationJerk::from_bits(268_435_456).unwrap(),
    };
    let mut axis = Mcx514SCurve::new(parameters, cycle_1024()).unwrap();
    let mut checker = Checker::new(&axis);
    let mut sixteenths = Vec::new();
    while !axis.is_complete() {
        let state = checker.step(&mut axis).unwrap();
        let bits = state.velocity.to_bits();
        assert_eq!(bits % (1 << 28), 0, "{state:?}");
        sixteenths.push(bits >> 28);
        assert!(sixteenths.len() < 1_000);
    }
    assert_eq!(axis.state().position, 200);
    // SV 16/16, then +4, +5, +5, +5, +4, +1 to DV 40/16.
    assert_eq!(sixteenths[..8], [16, 20, 25, 30, 35, 39, 40, 40]);
    let slowing = 6 + sixteenths[6..].iter().position(|&v| v < 40).unwrap();
    assert!(slowing > 8);
    assert!(sixteenths[8..slowing].iter().all(|&v| v == 40));
    // Down by the same rates to SV, then creep at SV to the finish point (the last moving cycle
    // cut to the pulses left), and stop.
    assert_eq!(
        sixteenths[slowing..slowing + 7],
        [36, 31, 26, 21, 17, 16, 16]
    );
    let last = sixteenths.len() - 1;
    assert!(sixteenths[slowing + 5..last - 1].iter().all(|&v| v == 16));
    assert!((1..=16).contains(&sixteenths[last - 1]));
    assert_eq!(sixteenths[last], 0);
}

#[test]
fn the_issue_17_move_reaches_the_drive_speed_within_the_continuous_bound() {
    // Issue #17's example (raw registers, 4 ms): per cycle SV = 309,169 · 0.004 = 1,236.676,
    // DV = 32,000, AC = DC = 16,777,216 · 0.004² = 268.435456, JK = DJ = 833,997,503 · 0.004³ ≈
    // 53.3758: the cap is 5.03 jerk steps. The continuous S-curve from rest to rest takes
    // 2 · (DV/AC + AC/JK) + (P − DV · (DV/AC + AC/JK)) / DV = 2 · 124.24 + 34.00 ≈ 282.5 cycles.
    // The speed-up (gap 30,763.3) takes at most ⌈gap/AC + AC/JK⌉ = ⌈114.6 + 5.03⌉ = 120 cycles
    // plus 2 (a cycle held below the cap, one taking the slack between two steps of the
    // descent) — choosing only rate ± J it ended with 35 cycles at a rate of 1.56
    // pulses/cycle². With automatic deceleration decided on whole cycles, the slow-down may
    // then end up to DV + SV pulses early: at most (DV + SV)/SV = 26.9 cycles of creep at SV
    // (it was 430). So at most 282.5 + 8 (whole cycles of the two ramps) + 26.9 + 1 (the stop).
    let parameters = Mcx514ScurveParameters {
        trapezoid: Mcx514Parameters {
            pulses: 5_063_858,
            initial_speed: InitialSpeed::from_bits(309_169).unwrap(),
            drive_speed: DriveSpeed::from_bits(8_000_000).unwrap(),
            acceleration: Acceleration::from_bits(16_777_216).unwrap(),
            deceleration: Deceleration::from_bits(16_777_216).unwrap(),
            deceleration_mode: DecelerationMode::Automatic,
        },
        jerk: Jerk::from_bits(833_997_503).unwrap(),
        deceleration_jerk: DecelerationJerk::from_bits(833_997_503).unwrap(),
    };
    let mut axis = Mcx514SCurve::new(parameters, CycleTime::from_seconds(4e-3).unwrap()).unwrap();
    let mut checker = Checker::new(&axis);
    let drive_speed = 32_000i64 << 32;
    let mut cycles = 0;
    let mut at_drive_speed = None;
    while !axis.is_complete() {
        let state = checker.step(&mut axis).unwrap();
        cycles += 1;
        if state.velocity.to_bits() == drive_speed && at_drive_speed.is_none() {
            at_drive_speed = Some(cycles);
        }
        assert!(cycles < 1_000);
    }
    assert_eq!(axis.state().position, 5_063_858);
    // The start cycle at SV, then the speed-up.
    let speed_up = at_drive_speed.expect("DV reached") - 1;
    assert!(speed_up <= 122, "speed-up in {speed_up} cycles");
    assert!(cycles <= 319, "{cycles} cycles");
}

#[test]
fn automatic_moves_take_the_continuous_s_curve_and_the_creep_of_the_chips_rule_at_most() {
    // 4,000 random automatic moves short enough to step (as the probe's random lines: at most a
    // few thousand cycles), each within the bound of `tests/script/mcx514_scurve.rs` (derived
    // there): the continuous S-curve from rest to rest, 8 cycles for the ramps' whole cycles,
    // and a creep at SV over DV + SV + JK·R·N pulses. Before the ramp could take the slack
    // between two jerk steps, moves crept past it (the first: 1,088 cycles against 442.8).
    let mut seed = 0x5eed_u64;
    let mut uniform = move || {
        seed = seed
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        (seed >> 11) as f64 / (1u64 << 53) as f64
    };
    let mut log_uniform = |low: f64, high: f64| {
        let r = uniform();
        (low.ln() + r * (high.max(low).ln() - low.ln())).exp() as u32
    };
    let mut moves = 0;
    while moves < 4_000 {
        let cycle = [1e-4, 2.5e-4, 1e-3, 2e-3, 4e-3][log_uniform(1.0, 5.99) as usize - 1];
        let pulses = log_uniform(1.0, 1e6).max(1);
        let drive = log_uniform((f64::from(pulses) / (2_000.0 * cycle)).ceil(), 8e6);
        let initial = log_uniform((f64::from(pulses) / (8_000.0 * cycle)).ceil(), drive.into());
        let initial = initial.clamp(1, drive);
        let acceleration =
            log_uniform((f64::from(drive) / (1_500.0 * cycle)).ceil(), 536_870_911.0);
        let jerk = log_uniform(
            (f64::from(acceleration) / (1_500.0 * cycle))
                .ceil()
                .min(1e9),
            1_073_741_823.0,
        );
        let parameters = Mcx514ScurveParameters {
            trapezoid: Mcx514Parameters {
                pulses,
                initial_speed: InitialSpeed::from_bits(initial).unwrap(),
                drive_speed: DriveSpeed::from_bits(drive).unwrap(),
                acceleration: Acceleration::from_bits(acceleration).unwrap(),
                deceleration: Deceleration::from_bits(acceleration).unwrap(),
                deceleration_mode: DecelerationMode::Automatic,
            },
            jerk: Jerk::from_bits(jerk).unwrap(),
            deceleration_jerk: DecelerationJerk::from_bits(jerk).unwrap(),
        };
        let Ok(mut axis) = Mcx514SCurve::new(parameters, CycleTime::from_seconds(cycle).unwrap())
        else {
            continue; // a register that vanishes per cycle
        };
        moves += 1;
        let per_cycle = |value: u32, power: i32| f64::from(value) * cycle.powi(power);
        let (s, v) = (per_cycle(initial, 1), per_cycle(drive, 1));
        let (a, j, p) = (
            per_cycle(acceleration, 2),
            per_cycle(jerk, 3),
            f64::from(pulses),
        );
        let gain = v - s;
        let ramp = (a / j).min((gain / j).sqrt()) + 4.0;
        let speed_up = gain / a + a / j + 2.0 * (gain / j).sqrt() + 3.0;
        let creep = (v + s + j * ramp * speed_up) / s;
        let bound = (p / s).min(scurve_duration(p, v, a, j) + 8.0 + creep) + 3.0;
        let cycles = axis.states_until_complete().take(1_000_000).count();
        assert!(
            cycles as f64 <= bound,
            "{cycles} cycles > {bound:.1}: {parameters:?} at {cycle} s"
        );
        assert_eq!(axis.state().position, pulses);
    }
}
