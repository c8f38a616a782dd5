//! SPEC §12.4: the circular interpolation geometry, against references written here in i128
//! with no code of the crate's: the true circle (exact integer comparisons), a brute-force
//! enumeration of the lattice points nearest to it, and the angle (cross products).

use profilegen::interpolation::{Arc, Direction};
use profilegen::Error;
use proptest::prelude::*;

const LIMIT: i32 = 1_073_741_823;

/// ⌊√n⌋ by bisection in i128 (the reference's own root, independent of the crate's).
fn floor_root(n: i128) -> i128 {
    let (mut low, mut high) = (0i128, 1i128 << 32);
    while high - low > 1 {
        let middle = (low + high) / 2;
        if middle * middle <= n {
            low = middle;
        } else {
            high = middle;
        }
    }
    low
}

/// Whether `long` is the integer nearest to √(R² − s²): (2l − 1)² < 4(R² − s²) < (2l + 1)².
fn is_nearest(long: i128, short: i128, radius_squared: i128) -> bool {
    let four = 4 * (radius_squared - short * short);
    four >= 0 && (2 * long - 1).pow(2) < four && four < (2 * long + 1).pow(2)
        || long == 0 && four < 1
}

/// |√(x² + y²) − r| ≤ ½, exactly: (2·d − 2r)² ≤ 1 without roots, through
/// 4d² + 4R² − 1 … the two one-sided tests (2r − 1)² ≤ 4d² ≤ (2r + 1)², each squared once more.
fn within_half_radially(x: i128, y: i128, radius_squared: i128) -> bool {
    let d2 = x * x + y * y;
    // 4d² ≤ 4R² + 4r + 1  ⇔  4(d² − R²) − 1 ≤ 4r  ⇔  (lhs ≤ 0) or lhs² ≤ 16R².
    let upper = 4 * (d2 - radius_squared) - 1;
    let upper_ok = upper <= 0 || upper * upper <= 16 * radius_squared;
    // 4d² ≥ 4R² − 4r + 1  ⇔  4r ≥ 4(R² − d²) + 1  ⇔  lhs² ≤ 16R² (lhs > 0 here unless d² > R²).
    let lower = 4 * (radius_squared - d2) + 1;
    let lower_ok = lower <= 0 || lower * lower <= 16 * radius_squared;
    upper_ok && lower_ok
}

/// Checks one point of `arc` (relative to the start): nearest to the circle in its long axis,
/// within ½ radially.
fn check_point(arc: &Arc, step: u64, point: [i32; 2]) {
    let [cx, cy] = arc.centre().map(i128::from);
    let (x, y) = (i128::from(point[0]) - cx, i128::from(point[1]) - cy);
    let r2 = i128::from(arc.radius_squared());
    let (short, long) = if x.abs() <= y.abs() {
        (x.abs(), y.abs())
    } else {
        (y.abs(), x.abs())
    };
    assert!(
        is_nearest(long, short, r2),
        "{arc:?} step {step}: {point:?} is not the nearest point to the circle"
    );
    assert!(
        within_half_radially(x, y, r2),
        "{arc:?} step {step}: {point:?} is off the circle"
    );
}

/// Every step of `arc`: one pulse on the octant's short axis, at most one on the other, the
/// angle advancing in the arc's direction; every point checked; the O(1) evaluation equal to the
/// walk. Returns the points visited.
fn check_every_step(arc: &Arc) -> Vec<[i32; 2]> {
    let mut points = vec![[0, 0]];
    let mut before = [0, 0];
    let mut walk = arc.walk();
    let sign = match arc.direction() {
        Direction::CounterClockwise => 1,
        Direction::Clockwise => -1,
    };
    let [cx, cy] = arc.centre().map(i128::from);
    while let Some(after) = walk.next() {
        let step = walk.step();
        check_point(arc, step, after);
        let octant = walk.octant();
        let moved = [0, 1].map(|axis| (after[axis] - before[axis]).abs());
        assert_eq!(
            moved[octant.short_axis()],
            1,
            "{arc:?} step {step}: the short axis pulses"
        );
        assert!(
            moved[1 - octant.short_axis()] <= 1,
            "{arc:?} step {step}: at most one pulse"
        );
        // The cross product of the two radius vectors: positive counter-clockwise.
        let (ax, ay) = (i128::from(before[0]) - cx, i128::from(before[1]) - cy);
        let (bx, by) = (i128::from(after[0]) - cx, i128::from(after[1]) - cy);
        assert!(
            sign * (ax * by - ay * bx) > 0,
            "{arc:?} step {step}: the angle goes back"
        );
        assert!(
            ax * bx + ay * by >= 0,
            "{arc:?} step {step}: a step of over 90°"
        );
        if step % 7 == 1 || walk.is_finished() {
            assert_eq!(arc.position_at(step), after, "{arc:?}: O(1) at step {step}");
        }
        points.push(after);
        before = after;
    }
    assert_eq!(points.len() as u64, arc.steps() + 1);
    assert_eq!(before, arc.end(), "{arc:?}: the walk ends on the end");
    points
}

/// The lattice points nearest to the circle of R² around the origin, by brute force over the
/// whole square: the points whose larger |coordinate| is the integer nearest to the circle at
/// the smaller one.
fn nearest_points(radius_squared: i128) -> Vec<[i128; 2]> {
    let reach = floor_root(radius_squared) + 1;
    let mut points = Vec::new();
    for x in -reach..=reach {
        for y in -reach..=reach {
            let (short, long) = (x.abs().min(y.abs()), x.abs().max(y.abs()));
            if is_nearest(long, short, radius_squared) {
                points.push([x, y]);
            }
        }
    }
    points
}

#[test]
fn the_manuals_circle_takes_56568_steps() {
    // Reference 003: "The total output pulses number of the short axis is 7071×8 = 56568."
    for direction in [Direction::CounterClockwise, Direction::Clockwise] {
        for centre in [[10_000, 0], [0, 10_000], [-10_000, 0], [0, -10_000]] {
            let circle = Arc::from_pulses(centre, [0, 0], direction).unwrap();
            assert_eq!(circle.steps(), 56_568, "{centre:?} {direction:?}");
            assert_eq!(circle.full_circle_steps(), 7_071 * 8);
            assert_eq!(circle.end(), [0, 0]);
            assert_eq!(circle.position_at(56_568), [0, 0]);
        }
    }
    // From (−10000, 0) around the origin counter-clockwise: octant 4 first (Y short, going
    // down), a quarter later the bottom of the circle.
    let circle = Arc::from_pulses([10_000, 0], [0, 0], Direction::CounterClockwise).unwrap();
    assert_eq!(circle.octant_at(1).index(), 4);
    assert_eq!(circle.position_at(1), [0, -1]);
    assert_eq!(circle.position_at(7_071), [10_000 - 7_071, -7_071]);
    assert_eq!(circle.octant_at(7_072).index(), 5);
    assert_eq!(circle.position_at(14_142), [10_000, -10_000]);
    assert_eq!(circle.octant_at(14_143).index(), 6);
    assert_eq!(circle.position_at(28_284), [20_000, 0]);
    let visited = check_every_step(&circle);
    assert_eq!(visited.len(), 56_569);
}

#[test]
fn full_circles_visit_every_nearest_point_once_for_small_radii() {
    for cx in -13..=13 {
        for cy in -13..=13 {
            if (cx, cy) == (0, 0) {
                continue;
            }
            let r2 = i128::from(cx * cx + cy * cy);
            let mut expected: Vec<[i128; 2]> = nearest_points(r2);
            expected.sort_unstable();
            for direction in [Direction::CounterClockwise, Direction::Clockwise] {
                let circle = Arc::from_pulses([cx, cy], [0, 0], direction).unwrap();
                assert_eq!(
                    circle.steps(),
                    expected.len() as u64,
                    "R² = {r2}, {direction:?}"
                );
                let visited = check_every_step(&circle);
                let mut around_centre: Vec<[i128; 2]> = visited[1..]
                    .iter()
                    .map(|p| [i128::from(p[0] - cx), i128::from(p[1] - cy)])
                    .collect();
                around_centre.sort_unstable();
                assert_eq!(around_centre, expected, "R² = {r2}, {direction:?}");
            }
        }
    }
}

#[test]
fn every_point_of_a_small_circle_is_a_finish_that_ends_exactly() {
    for (cx, cy) in [(5, 0), (3, 4), (-7, 2), (1, 1), (0, -1), (12, -5), (9, 9)] {
        for direction in [Direction::CounterClockwise, Direction::Clockwise] {
            let circle = Arc::from_pulses([cx, cy], [0, 0], direction).unwrap();
            let points: Vec<[i32; 2]> = circle.walk().collect();
            for (index, &finish) in points.iter().enumerate() {
                let arc = Arc::from_pulses([cx, cy], finish, direction).unwrap();
                assert_eq!(arc.end(), finish);
                assert_eq!(arc.steps(), index as u64 + 1, "{finish:?} on {cx},{cy}");
                check_every_step(&arc);
            }
        }
    }
}

#[test]
fn bad_centres_and_finishes_are_typed_errors() {
    let ccw = Direction::CounterClockwise;
    assert!(matches!(
        Arc::from_pulses([0, 0], [1, 1], ccw),
        Err(Error::Zero {
            parameter: "centre",
            ..
        })
    ));
    assert!(matches!(
        Arc::from_pulses([LIMIT + 1, 0], [0, 0], ccw),
        Err(Error::OutOfRange {
            parameter: "centre",
            ..
        })
    ));
    assert!(matches!(
        Arc::from_pulses([1, 0], [-LIMIT - 1, 0], ccw),
        Err(Error::OutOfRange {
            parameter: "finish point",
            ..
        })
    ));
    // A radius of 1.5·10⁹ with the centre 1.07·10⁹ away along X leaves the i32 range.
    assert!(matches!(
        Arc::from_pulses([LIMIT, LIMIT], [0, 0], ccw),
        Err(Error::OutOfRange {
            parameter: "radius",
            ..
        })
    ));
    // The finish far inside the circle, and two pulses off it.
    assert!(matches!(
        Arc::from_pulses([100, 0], [100, 50], ccw),
        Err(Error::Unreachable {
            parameter: "finish point",
            ..
        })
    ));
    assert!(matches!(
        Arc::from_pulses([100, 0], [198, 2], ccw),
        Err(Error::Unreachable {
            parameter: "finish point",
            ..
        })
    ));
    // One pulse off: the arc ends on the circle next to it, with the same short coordinate.
    let arc = Arc::from_pulses([100, 0], [201, 0], ccw).unwrap();
    assert_eq!(arc.end(), [200, 0]);
}

/// The integer point nearest to the circle of R² around the origin at angle `angle` (radians):
/// the smaller |coordinate| rounded, the larger the integer nearest to the circle there (i128,
/// by the reference's own root), in the octant where that is the larger one.
fn nearest_at_angle(radius_squared: i128, angle: f64) -> [i128; 2] {
    let radius = (radius_squared as f64).sqrt();
    let (x, y) = (radius * angle.cos(), radius * angle.sin());
    let nearest_long = |short: i128| {
        let n = radius_squared - short * short;
        let root = floor_root(n);
        // Round: up when n ≥ q² + q + 1 (n − q² > q).
        root + i128::from(n - root * root > root)
    };
    // Near the diagonal the rounded short coordinate can lie past the octant's end: then the
    // one toward the axis.
    let candidates = [
        (y.round() as i128, true),  // Y short
        (x.round() as i128, false), // X short
        (y.trunc() as i128, true),
        (x.trunc() as i128, false),
    ];
    for (short, y_is_short) in candidates {
        if short * short > radius_squared {
            continue;
        }
        let long = nearest_long(short);
        if long < short.abs() {
            continue;
        }
        return if y_is_short {
            [long * (x.signum() as i128), short]
        } else {
            [short, long * (y.signum() as i128)]
        };
    }
    unreachable!("one of the two axes is the short one")
}

/// The centre (relative to the start) of a circle of about `radius` whose start lies at
/// `angle` from the centre: the start must lie exactly on the circle, so R² is whatever the
/// rounded centre gives.
fn centre_for(radius: f64, angle: f64) -> [i32; 2] {
    [
        -(radius * angle.cos()).round() as i32,
        -(radius * angle.sin()).round() as i32,
    ]
}

/// Every path point of a full circle sorted by angle from the start in the direction of travel:
/// the reference step count of any arc is the index of its finish point here.
fn points_by_angle(centre: [i32; 2], direction: Direction) -> Vec<[i32; 2]> {
    let r2 = i128::from(centre[0]).pow(2) + i128::from(centre[1]).pow(2);
    let start_angle = (-f64::from(centre[1])).atan2(-f64::from(centre[0]));
    let sign = if direction == Direction::CounterClockwise {
        1.0
    } else {
        -1.0
    };
    let mut points: Vec<(f64, [i32; 2])> = nearest_points(r2)
        .into_iter()
        .map(|[x, y]| {
            let angle = (y as f64).atan2(x as f64);
            let mut from_start = sign * (angle - start_angle);
            while from_start <= 1e-12 {
                from_start += std::f64::consts::TAU;
            }
            let relative = [x as i32 + centre[0], y as i32 + centre[1]];
            (from_start, relative)
        })
        .collect();
    points.sort_by(|a, b| a.0.partial_cmp(&b.0).unwrap());
    points.into_iter().map(|(_, point)| point).collect()
}

#[test]
fn every_octant_pair_both_directions_against_the_angle_order() {
    // 65² = 16² + 63² = 25² + 60² = 33² + 56² = 39² + 52²: starts exactly on the circle in every
    // octant, on the axes and off them.
    let mut starts = Vec::new();
    for (a, b) in [(65, 0), (63, 16), (60, 25), (56, 33), (52, 39)] {
        for (x, y) in [(a, b), (b, a)] {
            for (sx, sy) in [(1, 1), (-1, 1), (-1, -1), (1, -1)] {
                starts.push([sx * x, sy * y]);
            }
        }
    }
    starts.sort_unstable();
    starts.dedup();
    let mut pairs = std::collections::HashSet::new();
    for start in &starts {
        let centre = [-start[0], -start[1]];
        for direction in [Direction::CounterClockwise, Direction::Clockwise] {
            let order = points_by_angle(centre, direction);
            let circle = Arc::from_pulses(centre, [0, 0], direction).unwrap();
            assert_eq!(circle.steps(), order.len() as u64);
            // Every 5th point as a finish, covering every octant.
            for (index, &finish) in order.iter().enumerate().step_by(5) {
                if finish == [0, 0] {
                    continue;
                }
                let arc = Arc::from_pulses(centre, finish, direction).unwrap();
                assert_eq!(
                    arc.steps(),
                    index as u64 + 1,
                    "{start:?} → {finish:?} {direction:?}"
                );
                assert_eq!(arc.end(), finish);
                assert_eq!(arc.position_at(arc.steps()), finish);
                pairs.insert((
                    arc.octant_at(1).index(),
                    arc.octant_at(arc.steps()).index(),
                    direction == Direction::Clockwise,
                ));
            }
        }
    }
    assert_eq!(
        pairs.len(),
        8 * 8 * 2,
        "every octant pair in both directions"
    );
}

fn direction() -> impl Strategy<Value = Direction> {
    prop_oneof![
        Just(Direction::Clockwise),
        Just(Direction::CounterClockwise)
    ]
}

/// A radius log-uniform in 1 … 2²⁹ and an angle.
fn radius_and_angle() -> impl Strategy<Value = (f64, f64)> {
    ((0.0f64..29.0), (0.0f64..std::f64::consts::TAU))
        .prop_map(|(log2, angle)| (log2.exp2().max(1.0), angle))
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(300))]

    /// Short arcs (at most a few thousand steps): every step checked, the exact end.
    #[test]
    fn short_arcs_every_step((radius, angle) in radius_and_angle(), span in 1e-4f64..1.0,
                             direction in direction()) {
        let centre = centre_for(radius, angle);
        prop_assume!(centre != [0, 0]);
        let r2 = i128::from(centre[0]).pow(2) + i128::from(centre[1]).pow(2);
        // At most ~3,000 steps: an angle of 3,000 / (√2·r) radians.
        let span = span * (3_000.0 / (r2 as f64).sqrt()).min(std::f64::consts::TAU);
        let start_angle = (-f64::from(centre[1])).atan2(-f64::from(centre[0]));
        let sign = if direction == Direction::CounterClockwise { 1.0 } else { -1.0 };
        let target = nearest_at_angle(r2, start_angle + sign * span);
        let finish = [target[0] as i32 + centre[0], target[1] as i32 + centre[1]];
        prop_assume!(finish != [0, 0]);
        let arc = Arc::from_pulses(centre, finish, direction).unwrap();
        prop_assert_eq!(arc.end(), finish);
        prop_assert!(arc.steps() <= 4_500 || span > 6.0, "{arc:?}: {} steps", arc.steps());
        if arc.steps() <= 10_000 {
            check_every_step(&arc);
        }
    }

    /// Long arcs: the O(1) evaluation at a thousand spread steps, each point checked against
    /// the circle; the exact end, and the full circle's count.
    #[test]
    fn long_arcs_at_spread_steps((radius, angle) in radius_and_angle(),
                                 span in 0.0f64..std::f64::consts::TAU,
                                 direction in direction()) {
        let centre = centre_for(radius, angle);
        prop_assume!(centre != [0, 0]);
        let r2 = i128::from(centre[0]).pow(2) + i128::from(centre[1]).pow(2);
        let start_angle = (-f64::from(centre[1])).atan2(-f64::from(centre[0]));
        let sign = if direction == Direction::CounterClockwise { 1.0 } else { -1.0 };
        let target = nearest_at_angle(r2, start_angle + sign * span);
        let finish = [target[0] as i32 + centre[0], target[1] as i32 + centre[1]];
        let arc = Arc::from_pulses(centre, finish, direction).unwrap();
        prop_assert_eq!(arc.end(), finish);
        // The count of a full circle: each octant's short axis runs between the axis and the
        // diagonal, about r/√2 pulses: 8·r/√2 within 8.
        let full = arc.full_circle_steps() as f64;
        prop_assert!((full - 8.0 * (r2 as f64).sqrt() / 2f64.sqrt()).abs() <= 8.0);
        // About the angle's share of it (the steps are not uniform in angle: within 1.5 %
        // of the full count plus a step).
        let expected = if finish == [0, 0] { full } else { full * span / std::f64::consts::TAU };
        prop_assert!((arc.steps() as f64 - expected).abs() <= 0.015 * full + 2.0,
                     "{arc:?}: {} steps for {span} rad", arc.steps());
        let mut walk = arc.walk();
        let mut before = [0, 0];
        let stride = (arc.steps() / 1_000).max(1);
        let mut step = 0;
        while step < arc.steps() {
            step = (step + stride).min(arc.steps());
            let point = walk.advance_to(step);
            check_point(&arc, step, point);
            prop_assert_eq!(arc.position_at(step), point);
            // At most one pulse per axis per step.
            for axis in 0..2 {
                prop_assert!(u64::from((point[axis] - before[axis]).unsigned_abs()) <= stride);
            }
            before = point;
        }
        prop_assert_eq!(before, finish);
    }
}

#[test]
fn a_walk_jumps_back_and_forth_in_o1() {
    // Forward, back to the start, past octant ends in both directions: always the evaluation
    // from scratch.
    for (centre, direction) in [
        ([10_000, 0], Direction::CounterClockwise),
        ([3, 4], Direction::Clockwise),
        ([-1, 0], Direction::CounterClockwise),
        ([700, -300], Direction::Clockwise),
    ] {
        let arc = Arc::from_pulses(centre, [0, 0], direction).unwrap();
        let steps = arc.steps();
        let mut walk = arc.walk();
        for target in [
            steps / 3,
            0,
            steps,
            1,
            steps / 2,
            steps / 8,
            0,
            steps - 1,
            2,
            steps,
        ] {
            let point = walk.advance_to(target);
            let mut fresh = arc.walk();
            assert_eq!(point, fresh.advance_to(target), "{centre:?} at {target}");
            assert_eq!(walk.octant(), fresh.octant(), "{centre:?} at {target}");
            assert_eq!(walk.octant(), arc.octant_at(target));
        }
    }
}

/// A profile that drives a walk through scripted whole positions (the integer parts a speed
/// profile's positions would have), forward and back, inside and outside the arc.
fn scripted_positions(steps: u64, seed: u64) -> Vec<i32> {
    let mut state = seed | 1;
    let mut next = move || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        state
    };
    let last = steps.min(i32::MAX as u64) as i64;
    let mut whole = 0i64;
    let mut out = Vec::new();
    for _ in 0..400 {
        whole = match next() % 16 {
            // Mostly forward by up to a sixteenth of the arc (crossing octants), sometimes back.
            0..=10 => whole + (next() % (last as u64 / 16 + 2)) as i64,
            11 | 12 => whole - (next() % (last as u64 / 32 + 2)) as i64,
            // Just past either end, far past them, and the ends themselves.
            13 => [-1, last + 1, i64::from(i32::MIN), i64::from(i32::MAX)][(next() % 4) as usize],
            14 => [0, last][(next() % 2) as usize],
            _ => (next() % (last as u64 + 1)) as i64,
        }
        .clamp(i64::from(i32::MIN), i64::from(i32::MAX));
        out.push(whole as i32);
    }
    out
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(300))]

    /// The per-cycle path (`ArcWalk::advance_to_whole`, which a driven arc takes every cycle,
    /// keeping its octant from the cycle before) lands on the same point and octant as
    /// `Arc::position_at` / `Arc::octant_at` (a fresh walk finding its octant from the start)
    /// on every cycle of random arcs, whole positions outside the arc holding the nearer end.
    #[test]
    fn the_per_cycle_path_is_position_at_on_every_cycle(
        (radius, angle) in radius_and_angle(),
        span in 0.0f64..std::f64::consts::TAU,
        direction in direction(),
        seed in any::<u64>(),
    ) {
        let centre = centre_for(radius, angle);
        prop_assume!(centre != [0, 0]);
        let r2 = i128::from(centre[0]).pow(2) + i128::from(centre[1]).pow(2);
        let start_angle = (-f64::from(centre[1])).atan2(-f64::from(centre[0]));
        let sign = if direction == Direction::CounterClockwise { 1.0 } else { -1.0 };
        let target = nearest_at_angle(r2, start_angle + sign * span);
        let finish = [target[0] as i32 + centre[0], target[1] as i32 + centre[1]];
        let arc = Arc::from_pulses(centre, finish, direction).unwrap();
        let mut walk = arc.walk();
        for whole in scripted_positions(arc.steps(), seed) {
            let step = u64::try_from(whole).unwrap_or(0).min(arc.steps());
            let point = walk.advance_to_whole(whole);
            prop_assert_eq!(walk.step(), step, "whole {}", whole);
            prop_assert_eq!(point, arc.position_at(step), "whole {}", whole);
            prop_assert_eq!(walk.current_position(), point);
            prop_assert_eq!(walk.octant(), arc.octant_at(step), "whole {}", whole);
        }
    }
}
