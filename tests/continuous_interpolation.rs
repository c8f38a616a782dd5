//! SPEC §12.5, continuous interpolation: segments back to back under one MCX514 trapezoid. The
//! driving axis is checked every cycle by the conformance suite's identities and limits; the axes
//! against each segment's own geometry (the ideal line within ½ pulse, the circle within ½
//! pulse, both exact in i128) and the sum of the segments' finish points at the end.

use profilegen::conformance::{check_identities, check_limits};
use profilegen::format::mcx514::{
    Acceleration, Deceleration, DriveSpeed, InitialSpeed, ManualDecelerationPoint,
};
use profilegen::format::CycleTime;
use profilegen::interpolation::{
    Arc, ContinuousDriving, ContinuousInterpolation, ContinuousState, Direction, Line, Segment,
};
use profilegen::{Error, ProfileGenerator, StopKind};

/// SV 2 pulses/cycle, DV 20, AC = DC = 1 pulse/cycle² at 1 ms.
fn run() -> ContinuousInterpolation {
    ContinuousInterpolation::new(
        ContinuousDriving {
            initial_speed: InitialSpeed::from_bits(2_000).unwrap(),
            drive_speed: DriveSpeed::from_bits(20_000).unwrap(),
            acceleration: Acceleration::from_bits(1_000_000).unwrap(),
            deceleration: Deceleration::from_bits(1_000_000).unwrap(),
        },
        CycleTime::from_seconds(1e-3).unwrap(),
    )
    .unwrap()
}

/// A square with rounded corners: four lines of 1,000 and four quarter circles of radius 200.
fn rounded_square() -> Vec<Segment> {
    let ccw = Direction::CounterClockwise;
    vec![
        Segment::Line(Line::from_pulses([1_000, 0]).unwrap()),
        Segment::Arc(Arc::from_pulses([0, 200], [200, 200], ccw).unwrap()),
        Segment::Line(Line::from_pulses([0, 1_000]).unwrap()),
        Segment::Arc(Arc::from_pulses([-200, 0], [-200, 200], ccw).unwrap()),
        Segment::Line(Line::from_pulses([-1_000, 0]).unwrap()),
        Segment::Arc(Arc::from_pulses([0, -200], [-200, -200], ccw).unwrap()),
        Segment::Line(Line::from_pulses([0, -1_000]).unwrap()),
        Segment::Arc(Arc::from_pulses([200, 0], [200, -200], ccw).unwrap()),
    ]
}

/// Whether `point`, relative to a segment's start, lies on it: within ½ pulse of the line (on
/// each axis) or of the circle (radially), exact in i128.
fn on_segment(segment: &Segment, point: [i32; 2]) -> bool {
    let [x, y] = point.map(i128::from);
    match segment {
        Segment::Line(line) => {
            // The line's step of `point` is its long coordinate; each axis within ½ of k·Δ/L.
            let finish = line.finish().map(i128::from);
            let steps = i128::from(line.steps());
            let long = if finish[0].abs() >= finish[1].abs() {
                0
            } else {
                1
            };
            let k = [x, y][long].abs();
            (0..2).all(|axis| (2 * [x, y][axis] * steps - 2 * k * finish[axis]).abs() <= steps)
        }
        Segment::Arc(arc) => {
            let [cx, cy] = arc.centre().map(i128::from);
            let (dx, dy) = (x - cx, y - cy);
            let (d2, r2) = (dx * dx + dy * dy, i128::from(arc.radius_squared()));
            let upper = 4 * (d2 - r2) - 1;
            let lower = 4 * (r2 - d2) + 1;
            (upper <= 0 || upper * upper <= 16 * r2) && (lower <= 0 || lower * lower <= 16 * r2)
        }
    }
}

/// Steps `run` to its end; checks every cycle and returns the states.
fn drive(run: &mut ContinuousInterpolation, segments: &[Segment]) -> Vec<ContinuousState> {
    let mut states = vec![run.state()];
    while !run.is_complete() {
        let before = *states.last().unwrap();
        let after = run.step();
        check_identities(&before.driving, &after.driving).unwrap();
        check_limits(&before.driving, &after.driving, &run.profile().limits()).unwrap();
        // Where the segment being driven began: the sum of the earlier ones' ends.
        let mut origin = [0i32, 0];
        for segment in &segments[..after.segment as usize] {
            origin = [origin[0] + segment.end()[0], origin[1] + segment.end()[1]];
        }
        let local = [after.axes[0] - origin[0], after.axes[1] - origin[1]];
        assert!(
            on_segment(&segments[after.segment as usize], local),
            "cycle {}: {:?} is off segment {}",
            states.len(),
            after.axes,
            after.segment
        );
        let moved = after.step - before.step;
        for axis in 0..2 {
            assert!(u64::from((after.axes[axis] - before.axes[axis]).unsigned_abs()) <= moved);
        }
        states.push(after);
        assert!(states.len() < 100_000, "the run ends");
    }
    states
}

#[test]
fn segments_run_back_to_back_and_decelerate_only_in_the_last() {
    let segments = rounded_square();
    let total: u64 = segments.iter().map(Segment::steps).sum();
    let mut run = run();
    let (last, rest) = segments.split_last().unwrap();
    for segment in rest {
        run.push(*segment).unwrap();
    }
    // 20 → 2 at 1 per cycle: 18 cycles, 2 + 3 + … + 19 = 189 pulses; the last quarter circle
    // has 4 · 141 + … steps: the point leaves a little creep at SV.
    let point = ManualDecelerationPoint::from_bits(last.steps() as u32 - 200).unwrap();
    run.push_last(*last, point).unwrap();
    let states = drive(&mut run, &segments);
    let end = states.last().unwrap();
    assert_eq!(end.axes, [0, 0], "the square closes exactly");
    assert_eq!(end.step, total);
    assert_eq!(end.segment, 7);
    let last_start = total - last.steps();
    let drive_speed = 20i64 << 32;
    let mut reached = false;
    for pair in states.windows(2) {
        let (before, after) = (pair[0], pair[1]);
        reached |= after.driving.velocity.to_bits() == drive_speed;
        // Once at DV, the speed drops only in the last segment.
        if reached && after.driving.velocity < before.driving.velocity {
            assert!(
                before.step >= last_start,
                "slowing at step {} before the last",
                before.step
            );
        }
    }
    assert!(reached);
}

#[test]
fn the_queue_refills_while_running_and_refuses_when_full() {
    let segments = rounded_square();
    let mut run = run();
    let mut pushed = 0;
    // Fill the pre-buffer: 8 waiting.
    for segment in segments.iter().cycle().take(8) {
        run.push(*segment).unwrap();
        pushed += 1;
    }
    assert_eq!((run.waiting(), run.free()), (8, 0));
    let full = run.push(segments[0]);
    assert!(matches!(
        full,
        Err(Error::Refused {
            parameter: "segment",
            ..
        })
    ));
    assert_eq!(run.waiting(), 8, "a refused push changes nothing");
    // Drive, refilling whenever there is room: three squares in all.
    let all: Vec<Segment> = segments.iter().cycle().take(24).copied().collect();
    let mut states = vec![run.state()];
    let mut refills = 0;
    while !run.is_complete() {
        let state = run.step();
        states.push(state);
        while run.free() > 0 && pushed < all.len() {
            if pushed == all.len() - 1 {
                let point = ManualDecelerationPoint::from_bits(0).unwrap();
                run.push_last(all[pushed], point).unwrap();
            } else {
                run.push(all[pushed]).unwrap();
            }
            pushed += 1;
            refills += 1;
        }
        assert!(states.len() < 100_000);
    }
    assert_eq!(refills, 16);
    let end = states.last().unwrap();
    assert_eq!(end.axes, [0, 0]);
    assert_eq!(end.segment, 23);
    assert_eq!(end.step, all.iter().map(Segment::steps).sum::<u64>());
    // Nothing after the last segment, nor after the end.
    assert!(run.push(segments[0]).is_err());
}

#[test]
fn a_dry_queue_stops_at_the_end_of_what_it_has() {
    let segments = rounded_square();
    let mut run = run();
    run.push(segments[0]).unwrap();
    run.push(segments[1]).unwrap();
    let states = drive(&mut run, &segments);
    let end = states.last().unwrap();
    assert_eq!(end.axes, [1_200, 200]);
    // It arrived at speed and stopped at once (the chip's late finish), exempt.
    let before_end = states[states.len() - 2];
    assert!(before_end.driving.velocity > 2);
    assert!(matches!(
        run.push(segments[2]),
        Err(Error::Refused {
            parameter: "segment",
            ..
        })
    ));
}

#[test]
fn a_stop_abandons_the_queue() {
    let segments = rounded_square();
    for kind in [StopKind::Smooth, StopKind::Abrupt] {
        let mut run = run();
        for segment in &segments {
            run.push(*segment).unwrap();
        }
        let mut state = run.state();
        while state.step < 500 {
            state = run.step();
        }
        run.stop(kind);
        assert_eq!(run.waiting(), 0);
        assert!(matches!(
            run.push(segments[0]),
            Err(Error::Refused {
                parameter: "segment",
                ..
            })
        ));
        let states = drive(&mut run, &segments);
        let end = states.last().unwrap();
        assert_eq!(end.segment, 0, "{kind:?}: it ends on the first segment");
        assert!(end.step <= 1_000);
        if kind == StopKind::Abrupt {
            assert_eq!(end.axes, state.axes, "an abrupt stop holds in place");
        }
    }
}

/// Found by the scripts (issue #17): a smooth stop with the position a fraction past the end of
/// the segment being driven (its step still the end's) could not make that end the finish point
/// and kept the old one, in the abandoned segments: the run went on past the segment, the axes
/// held at its end. Now the end has come first: the stop is at once.
#[test]
fn a_smooth_stop_a_fraction_past_the_segments_end_stops_there() {
    // SV 0.3 pulse/cycle, AC = DC 0.5 (1 ms): velocities 0.3, 0.8, 1.3, 1.8, positions 0.3,
    // 1.1, 2.4, 4.2 (step 4, the first line's end). The old smooth stop went on at 1.3 to 5.5.
    let mut run = ContinuousInterpolation::new(
        ContinuousDriving {
            initial_speed: InitialSpeed::from_bits(300).unwrap(),
            drive_speed: DriveSpeed::from_bits(20_000).unwrap(),
            acceleration: Acceleration::from_bits(500_000).unwrap(),
            deceleration: Deceleration::from_bits(500_000).unwrap(),
        },
        CycleTime::from_seconds(1e-3).unwrap(),
    )
    .unwrap();
    run.push(Segment::Line(Line::from_pulses([4, 0]).unwrap()))
        .unwrap();
    run.push(Segment::Line(Line::from_pulses([0, 1_000]).unwrap()))
        .unwrap();
    for _ in 0..3 {
        run.step();
    }
    let state = run.step();
    assert_eq!((state.step, state.segment, state.axes), (4, 0, [4, 0]));
    assert!(state.driving.position > 4);
    run.stop(StopKind::Smooth);
    let mut cycles = 0;
    while !run.is_complete() {
        let state = run.step();
        assert_eq!((state.step, state.segment, state.axes), (4, 0, [4, 0]));
        cycles += 1;
        assert!(cycles < 100, "the run went on: {state:?}");
    }
    assert_eq!(run.state().driving.velocity, 0);
}
