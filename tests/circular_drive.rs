//! SPEC §12.4 and #15 item 2: the manual's circle (reference 003) driven by the MCX514's own
//! trapezoid. The registers and the deceleration point are the manual's figures; every cycle is
//! checked by the conformance suite (the driving axis) and against the true circle (the axes).

use profilegen::conformance::Checker;
use profilegen::format::mcx514::{
    acceleration_for_change, deceleration_pulses, manual_deceleration_point, Deceleration,
    DecelerationJerk, DriveSpeed, InitialSpeed, Jerk,
};
use profilegen::format::CycleTime;
use profilegen::interpolation::{Arc, CircularDriving, Direction};
use profilegen::{DecelerationMode, Error, ProfileGenerator, StopKind};

fn millisecond() -> CycleTime {
    CycleTime::from_seconds(1e-3).unwrap()
}

/// The manual's circle: r = 10,000 (the start 10,000 pulses left of the centre), a full turn.
fn manual_circle(direction: Direction) -> Arc {
    Arc::from_pulses([10_000, 0], [0, 0], direction).unwrap()
}

/// SV 500 pps, DV 20,000 pps, AC = DC for 500 → 20,000 pps in 0.3 s, and a deceleration mode.
fn manual_driving(mode: DecelerationMode) -> CircularDriving {
    let initial = InitialSpeed::from_bits(500).unwrap();
    let drive = DriveSpeed::from_bits(20_000).unwrap();
    let acceleration = acceleration_for_change(initial, drive, 0.3).unwrap();
    CircularDriving {
        initial_speed: initial,
        drive_speed: drive,
        acceleration,
        deceleration: Deceleration::from_bits(acceleration.to_bits()).unwrap(),
        jerk: None,
        deceleration_jerk: None,
        deceleration_mode: mode,
    }
}

/// Whether `point` (relative to the start) is within ½ pulse of the circle of `arc`, radially:
/// (2r − 1)² ≤ 4d² ≤ (2r + 1)², with r = √R² kept out by squaring once more (exact in i128).
fn on_circle(arc: &Arc, point: [i32; 2]) -> bool {
    let [cx, cy] = arc.centre().map(i128::from);
    let (x, y) = (i128::from(point[0]) - cx, i128::from(point[1]) - cy);
    let (d2, r2) = (x * x + y * y, i128::from(arc.radius_squared()));
    let upper = 4 * (d2 - r2) - 1;
    let lower = 4 * (r2 - d2) + 1;
    (upper <= 0 || upper * upper <= 16 * r2) && (lower <= 0 || lower * lower <= 16 * r2)
}

#[test]
fn the_manuals_registers_and_deceleration_point() {
    let driving = manual_driving(DecelerationMode::Disabled);
    // "(20000 − 500) / 0.3 = 65000PPS/SEC" … "WR6 ← FDE8h".
    assert_eq!(driving.acceleration.to_bits(), 65_000);
    assert_eq!(driving.acceleration.to_bits(), 0xFDE8);
    // "(500+20000) × 0.3/2 = 3075".
    let pulses = deceleration_pulses(
        driving.initial_speed,
        driving.drive_speed,
        driving.deceleration,
    );
    assert_eq!(pulses, 3_075);
    // "7071×8 = 56568" and "56568 - 3075 = 53493".
    let circle = manual_circle(Direction::CounterClockwise);
    assert_eq!(circle.steps(), 56_568);
    let point = manual_deceleration_point(circle.steps(), pulses).unwrap();
    assert_eq!(point.to_bits(), 53_493);
}

#[test]
fn the_manuals_circle_driven_by_the_trapezoid_ends_where_it_started() {
    for direction in [Direction::CounterClockwise, Direction::Clockwise] {
        let circle = manual_circle(direction);
        let point = manual_deceleration_point(circle.steps(), 3_075).unwrap();
        let mut profile = circle
            .mcx514_profile(
                manual_driving(DecelerationMode::Manual(point)),
                millisecond(),
            )
            .unwrap();
        let mut checker = Checker::new(&profile);
        let mut walk = circle.walk();
        let (mut cycles, mut last_step, mut peak) = (0u64, 0u64, 0i64);
        while !profile.is_complete() {
            let driving = checker.step(&mut profile).unwrap();
            cycles += 1;
            assert!(cycles < 10_000, "the move ends");
            let step = (driving.position.to_bits() >> 32) as u64;
            assert!(step >= last_step, "never backwards");
            // Cycle by cycle: the O(1) jump equals the stateless evaluation, on the circle.
            let axes = walk.advance_to(step);
            assert_eq!(axes, circle.position_at(step));
            assert!(on_circle(&circle, axes), "cycle {cycles}: {axes:?}");
            peak = peak.max(driving.velocity.to_bits());
            last_step = step;
        }
        assert_eq!(last_step, 56_568);
        assert_eq!(walk.current_position(), [0, 0], "exactly where it started");
        // DV reached: 20,000 pps at 1 ms is 20 pulses per cycle.
        assert_eq!(peak, 20i64 << 32);
        // The manual's move takes about 0.3 s up, 0.3 s down and (56,568 − 2·3,075)/20,000 s
        // at DV: 3.12 s, 3,121 cycles; the cycle-based ramp's own pulse count differs from the
        // continuous one by a few pulses, which end at SV (a short creep) or cut short.
        assert!((3_110..=3_140).contains(&cycles), "{cycles} cycles");
    }
}

#[test]
fn the_interpolation_adapter_follows_the_profile() {
    let circle = manual_circle(Direction::Clockwise);
    let point = manual_deceleration_point(circle.steps(), 3_075).unwrap();
    let mut profile = circle
        .mcx514_profile(
            manual_driving(DecelerationMode::Manual(point)),
            millisecond(),
        )
        .unwrap();
    let mut interpolation = circle.drive(&mut profile);
    let mut octants = Vec::new();
    while !interpolation.is_complete() {
        let state = interpolation.step();
        assert_eq!(state.step, (state.driving.position.to_bits() >> 32) as u64);
        assert_eq!(state.axes, circle.position_at(state.step));
        if octants.last() != Some(&state.octant.index()) {
            octants.push(state.octant.index());
        }
    }
    // Clockwise from (−r, 0) around the centre: octants 3, 2, 1, 0, 7, 6, 5, 4.
    assert_eq!(octants, [3, 2, 1, 0, 7, 6, 5, 4]);
    assert_eq!(interpolation.state().axes, [0, 0]);
    // A smooth stop in the middle of a second move stays on the circle.
    let mut profile = circle
        .mcx514_profile(
            manual_driving(DecelerationMode::Manual(point)),
            millisecond(),
        )
        .unwrap();
    let mut interpolation = circle.drive(&mut profile);
    interpolation.by_ref().take(1_000).for_each(drop);
    interpolation.stop(StopKind::Smooth);
    let mut last = interpolation.state();
    while !interpolation.is_complete() {
        last = interpolation.step();
        assert!(on_circle(&circle, last.axes));
    }
    assert!(last.step < 56_568);
    interpolation.stop(StopKind::Abrupt);
    assert_eq!(interpolation.step().axes, last.axes);
}

#[test]
fn circular_mode_refuses_s_curve_and_automatic_deceleration() {
    let circle = manual_circle(Direction::CounterClockwise);
    let mut driving = manual_driving(DecelerationMode::Automatic);
    assert!(matches!(
        circle.mcx514_profile(driving, millisecond()),
        Err(Error::Refused {
            parameter: "deceleration point",
            ..
        })
    ));
    driving.deceleration_mode = DecelerationMode::Disabled;
    driving.jerk = Some(Jerk::from_bits(1_000_000).unwrap());
    assert!(matches!(
        circle.mcx514_profile(driving, millisecond()),
        Err(Error::Refused {
            parameter: "jerk",
            ..
        })
    ));
    driving.jerk = None;
    driving.deceleration_jerk = Some(DecelerationJerk::from_bits(1_000_000).unwrap());
    assert!(matches!(
        circle.mcx514_profile(driving, millisecond()),
        Err(Error::Refused {
            parameter: "deceleration increasing rate",
            ..
        })
    ));
    driving.deceleration_jerk = None;
    assert!(circle.mcx514_profile(driving, millisecond()).is_ok());
    // An arc longer than the chip's pulse count.
    let huge = Arc::from_pulses([400_000_000, 0], [0, 0], Direction::Clockwise).unwrap();
    assert!(huge.steps() > 1_073_741_823);
    assert!(matches!(
        huge.mcx514_profile(driving, millisecond()),
        Err(Error::OutOfRange {
            parameter: "arc steps",
            ..
        })
    ));
}
