//! #14 item 3: a line driven by the crate's speed profiles. On every cycle the driving state keeps
//! the SPEC §5 identities (it is the profile's own), the step count is the integer part of its
//! position, every axis is within ½ pulse of the ideal line at that step (exact, i128), moves at
//! most as many pulses as the cycle took steps and never backwards; the move ends exactly on the
//! finish point. Stops (SPEC §9) stop the whole line: smooth along the path, abrupt in place.

use fixed::types::I32F32;
use profilegen::conformance::check_identities;
use profilegen::format::juno::{Acceleration, TargetVelocity};
use profilegen::format::mc1451a::{Jerk, MaxVelocity, ScurveAcceleration};
use profilegen::interpolation::{InterpolationState, Line};
use profilegen::{
    ProfileGenerator, SCurve, ScurveParameters, StopKind, Trapezoidal, TrapezoidalParameters,
};

fn trapezoid(steps: u32, velocity: f64, acceleration: f64) -> Trapezoidal {
    Trapezoidal::new(TrapezoidalParameters {
        destination: steps as i32,
        max_velocity: TargetVelocity::from_num(velocity).unwrap(),
        acceleration: Acceleration::from_num(acceleration).unwrap(),
        deceleration: Acceleration::ZERO,
        start_velocity: TargetVelocity::ZERO,
    })
    .unwrap()
}

fn scurve(steps: u32) -> SCurve {
    SCurve::new(ScurveParameters {
        destination: steps as i32,
        max_velocity: MaxVelocity::from_num(3_000.0).unwrap(),
        max_acceleration: ScurveAcceleration::from_num(0.25).unwrap(),
        jerk: Jerk::from_num(0.001).unwrap(),
    })
    .unwrap()
}

/// Checks one cycle from `before` to `after` on `line`; returns the steps the cycle took.
fn check_cycle<const N: usize>(
    line: &Line<N>,
    before: &InterpolationState<N>,
    after: &InterpolationState<N>,
) -> u32 {
    check_identities(&before.driving, &after.driving).unwrap();
    let whole = after.driving.position.to_bits() >> 32;
    assert_eq!(
        i64::from(after.step),
        whole.clamp(0, i64::from(line.steps()))
    );
    let steps = line.steps();
    for axis in 0..N {
        let delta = line.finish()[axis];
        let pos = after.axes[axis];
        // |pos − k·Δ/L| ≤ ½  ⇔  |2·pos·L − 2·k·Δ| ≤ L, exactly.
        let error = 2 * i128::from(pos) * i128::from(steps)
            - 2 * i128::from(after.step) * i128::from(delta);
        assert!(error.abs() <= i128::from(steps), "axis {axis} off the line");
        let moved = (i64::from(pos) - i64::from(before.axes[axis])) * i64::from(delta.signum());
        assert!(moved >= 0, "axis {axis} went backwards");
        assert!(moved <= i64::from(after.step) - i64::from(before.step));
    }
    after.step - before.step
}

/// Runs `profile` on `line` to completion, checking every cycle; returns the cycle count and the
/// largest number of steps in one cycle.
fn run<G: ProfileGenerator + ?Sized, const N: usize>(
    line: &Line<N>,
    profile: &mut G,
) -> (u32, u32) {
    let mut interpolation = line.drive(profile);
    let mut before = interpolation.state();
    assert_eq!(before.axes, [0; N]);
    let (mut cycles, mut most) = (0, 0);
    while !interpolation.is_complete() {
        let after = interpolation.step();
        most = most.max(check_cycle(line, &before, &after));
        before = after;
        cycles += 1;
        assert!(cycles < 10_000_000, "does not finish");
    }
    assert_eq!(before.axes, line.finish(), "ends on the finish point");
    assert_eq!(before.step, line.steps());
    assert_eq!(before.driving.position, I32F32::from_num(line.steps()));
    (cycles, most)
}

#[test]
fn a_trapezoid_drives_the_manuals_3_axis_line() {
    let line = Line::from_pulses([-20_000, 30_000, -50_000]).unwrap();
    let (cycles, most) = run(&line, &mut trapezoid(line.steps(), 250.0, 2.0));
    // 250 steps per cycle at the cruise: many pulses per cycle, one jump each.
    assert_eq!(most, 250);
    assert!(cycles > 200);
}

#[test]
fn an_scurve_drives_a_4_axis_line_across_the_whole_range() {
    let line = Line::from_pulses([1_073_741_823, -536_870_911, 3, -1_000_000_007]).unwrap();
    let (_, most) = run(&line, &mut scurve(line.steps()));
    assert_eq!(most, 3_000);
}

#[test]
fn a_2_axis_line_through_a_dyn_profile() {
    let line = Line::from_pulses([7, -1_234]).unwrap();
    let mut profile = trapezoid(line.steps(), 3.5, 0.125);
    let dynamic: &mut dyn ProfileGenerator = &mut profile;
    run(&line, dynamic);
}

#[test]
fn a_smooth_stop_decelerates_along_the_line_and_an_abrupt_one_holds_every_axis() {
    let line = Line::from_pulses([1_000_000, -400_000, 150_003]).unwrap();
    // Smooth: stop at full speed (500 cycles of speed-up, 1 + 2 + … + 500 = 125,250 steps, then
    // 200 cycles at 500), keep on the line to rest, short of the finish point (about 125,000
    // more steps to slow down).
    let mut profile = trapezoid(line.steps(), 500.0, 1.0);
    let mut interpolation = line.drive(&mut profile);
    let mut before = interpolation.state();
    for _ in 0..700 {
        let after = interpolation.step();
        check_cycle(&line, &before, &after);
        before = after;
    }
    let stopped_at = before.step;
    assert_eq!(stopped_at, 125_250 + 100_000);
    interpolation.stop(StopKind::Smooth);
    while !interpolation.is_complete() {
        let after = interpolation.step();
        check_cycle(&line, &before, &after);
        before = after;
    }
    assert!(stopped_at < before.step && before.step < line.steps());
    assert_eq!(interpolation.step().axes, before.axes, "at rest, held");

    // Abrupt: the next cycle has the same step count and axes.
    let mut profile = trapezoid(line.steps(), 500.0, 1.0);
    let mut interpolation = line.drive(&mut profile);
    for _ in 0..700 {
        interpolation.step();
    }
    let before = interpolation.state();
    interpolation.stop(StopKind::Abrupt);
    let after = interpolation.step();
    check_cycle(&line, &before, &after);
    assert_eq!((after.step, after.axes), (before.step, before.axes));
    assert!(interpolation.is_complete());
}

#[test]
fn a_profile_past_either_end_holds_the_axes_at_that_end() {
    let line = Line::from_pulses([10, 4]).unwrap();
    // A destination beyond the line's 10 steps: the axes stop at the finish point.
    let mut profile = trapezoid(25, 2.0, 0.5);
    let last = line.drive(&mut profile).take(100).last().unwrap();
    assert_eq!((last.step, last.axes), (10, [10, 4]));
    // A destination behind the start: the axes stay at the start.
    let mut profile = Trapezoidal::new(TrapezoidalParameters {
        destination: -25,
        ..profile.parameters()
    })
    .unwrap();
    let last = line.drive(&mut profile).take(100).last().unwrap();
    assert_eq!((last.step, last.axes), (0, [0, 0]));
}

/// Reference 003's line driven by the MCX514's own profile: SV 500 pps, DV 20,000 pps,
/// AC = DC = 65,000 pps/s, at 1 ms (0.5, 20 pulses/cycle, 0.065 pulses/cycle²), with the manual
/// deceleration point 50,000 − 3,075 = 46,925 from the helpers.
#[test]
fn the_mcx514_profile_drives_the_manuals_line_with_its_manual_deceleration_point() {
    use profilegen::format::mcx514::{self, FinishPoint};
    use profilegen::{DecelerationMode, Mcx514Parameters, Mcx514Trapezoidal};

    let finish = [-20_000, 30_000, -50_000].map(|p| FinishPoint::from_bits(p).unwrap());
    let line = Line::new(finish);
    let initial = mcx514::InitialSpeed::from_bits(500).unwrap();
    let drive = mcx514::DriveSpeed::from_bits(20_000).unwrap();
    let deceleration = mcx514::Deceleration::from_bits(65_000).unwrap();
    let pulses = mcx514::deceleration_pulses(initial, drive, deceleration);
    let point = mcx514::linear_manual_deceleration_point(&finish, pulses).unwrap();
    assert_eq!(point.to_bits(), 46_925);
    let new_profile = || {
        Mcx514Trapezoidal::new(
            Mcx514Parameters {
                pulses: line.steps(),
                initial_speed: initial,
                drive_speed: drive,
                acceleration: mcx514::Acceleration::from_bits(65_000).unwrap(),
                deceleration,
                deceleration_mode: DecelerationMode::Manual(point),
            },
            profilegen::format::CycleTime::from_seconds(1e-3).unwrap(),
        )
        .unwrap()
    };
    let mut profile = new_profile();
    let (_, most) = run(&line, &mut profile);
    assert_eq!(most, 20);
    // The creep: the cycle-by-cycle ramp down (20 − 0.065·k for k = 1 … 300) outputs about
    // 3,065 pulses, about 10 fewer than the manual's continuous 3,075, and the point is crossed
    // within a cycle (≤ 20 pulses) of 46,925: so roughly 10 pulses at 0.5 per cycle are left,
    // about 20 cycles at SV, and the stop from SV is within the limits.
    assert!(!profile.limits().exempt);
    let mut alone = new_profile();
    let states: Vec<_> = alone.states_until_complete().collect();
    let cruise_end = states.iter().rposition(|s| s.velocity == 20).unwrap();
    let creep = states[cruise_end..]
        .iter()
        .filter(|s| s.velocity == 0.5)
        .count();
    assert!((15..=25).contains(&creep), "{creep} cycles at SV");
}

/// Reference 003's line driven by the MCX514's S-curve (#14 items 2 and 3): SV 500 pps, DV 20,000
/// pps, AC = DC = 65,000 pps/s, JK = DJ = 650,000 pps/s² (the rate reaches AC in 0.1 s), at 1 ms,
/// automatic deceleration; every cycle checked as above, and DV reached (20 steps per cycle).
#[test]
fn the_mcx514_scurve_drives_the_manuals_line() {
    use profilegen::format::mcx514;
    use profilegen::{DecelerationMode, Mcx514Parameters, Mcx514SCurve, Mcx514ScurveParameters};

    let line = Line::from_pulses([-20_000, 30_000, -50_000]).unwrap();
    let mut profile = Mcx514SCurve::new(
        Mcx514ScurveParameters {
            trapezoid: Mcx514Parameters {
                pulses: line.steps(),
                initial_speed: mcx514::InitialSpeed::from_bits(500).unwrap(),
                drive_speed: mcx514::DriveSpeed::from_bits(20_000).unwrap(),
                acceleration: mcx514::Acceleration::from_bits(65_000).unwrap(),
                deceleration: mcx514::Deceleration::from_bits(65_000).unwrap(),
                deceleration_mode: DecelerationMode::Automatic,
            },
            jerk: mcx514::Jerk::from_bits(650_000).unwrap(),
            deceleration_jerk: mcx514::DecelerationJerk::from_bits(650_000).unwrap(),
        },
        profilegen::format::CycleTime::from_seconds(1e-3).unwrap(),
    )
    .unwrap();
    let (_, most) = run(&line, &mut profile);
    assert_eq!(most, 20);
}
