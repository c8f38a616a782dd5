//! SPEC §12.3: the linear interpolation geometry. Every expectation here is the ideal line itself,
//! compared exactly in integers (i128): |posᵢ(k) − k·Δᵢ/L| ≤ ½ is |2·posᵢ·L − 2·k·Δᵢ| ≤ L. On top:
//! at most one pulse per axis per step, never backwards, the long axis on every step, the finish
//! point exactly at the end, and the division-free evaluation equal to the rule's division.

use profilegen::interpolation::Line;
use profilegen::Error;
use proptest::prelude::*;

const LIMIT: i32 = 1_073_741_823;

/// `2·pos·L − 2·k·Δ`: twice L times the distance from the ideal line (exact in i128).
fn twice_error(pos: i32, step: u32, delta: i32, steps: u32) -> i128 {
    2 * i128::from(pos) * i128::from(steps) - 2 * i128::from(step) * i128::from(delta)
}

/// The ±½ bound on every axis at `step`, and the exact finish point at the end.
fn check_at<const N: usize>(line: &Line<N>, step: u32, position: [i32; N]) {
    let steps = line.steps();
    for (axis, (&pos, &delta)) in position.iter().zip(&line.finish()).enumerate() {
        let error = twice_error(pos, step, delta, steps);
        assert!(
            error.abs() <= i128::from(steps),
            "axis {axis} of {:?} at step {step}: {pos} is more than ½ off the line",
            line.finish()
        );
    }
    if step == steps {
        assert_eq!(position, line.finish(), "the end is the finish point");
    }
}

/// From `before` to `after` over one step: each axis 0 or one pulse toward its finish, the long
/// axes exactly one.
fn check_one_step<const N: usize>(line: &Line<N>, before: [i32; N], after: [i32; N]) {
    for axis in 0..N {
        let delta = line.finish()[axis];
        let moved = i64::from(after[axis]) - i64::from(before[axis]);
        let toward = i64::from(delta.signum());
        assert!(
            moved == 0 || moved == toward,
            "axis {axis} of {:?} moved {moved} in a step",
            line.finish()
        );
        if delta.unsigned_abs() == line.steps() {
            assert_eq!(moved, toward, "a long axis pulses on every step");
        }
    }
}

/// Every step of a line, by the iterator, checked against the ideal line and against the O(1)
/// evaluation at the same step.
fn check_every_step<const N: usize>(line: &Line<N>) {
    let mut walk = line.walk();
    assert_eq!(walk.len(), line.steps() as usize);
    let mut before = [0; N];
    check_at(line, 0, before);
    let mut step = 0;
    while let Some(after) = walk.next() {
        step += 1;
        assert_eq!(walk.step(), step);
        check_at(line, step, after);
        check_one_step(line, before, after);
        assert_eq!(
            after,
            line.position_by_division(step),
            "the fast form is the rule"
        );
        before = after;
    }
    assert_eq!(step, line.steps());
    assert_eq!(before, line.finish());
    assert!(walk.is_finished());
    assert_eq!(walk.next(), None);
}

#[test]
fn a_hand_worked_line() {
    // Finish (5, 2): Y's ideal positions are 0.4·k = 0.4, 0.8, 1.2, 1.6, 2.0 → 0, 1, 1, 2, 2.
    let line = Line::from_pulses([5, 2]).unwrap();
    let steps: Vec<[i32; 2]> = line.walk().collect();
    assert_eq!(steps, [[1, 0], [2, 1], [3, 1], [4, 2], [5, 2]]);
    // Mirrored: the same magnitudes with the signs of the finish point.
    let line = Line::from_pulses([-5, -2]).unwrap();
    let steps: Vec<[i32; 2]> = line.walk().collect();
    assert_eq!(steps, [[-1, 0], [-2, -1], [-3, -1], [-4, -2], [-5, -2]]);
    // Four axes, two of them long, one still: (3, −3, 1, 0) → the short axis at 1/3, 2/3, 1.
    let line = Line::from_pulses([3, -3, 1, 0]).unwrap();
    let steps: Vec<[i32; 4]> = line.walk().collect();
    assert_eq!(steps, [[1, -1, 0, 0], [2, -2, 1, 0], [3, -3, 1, 0]]);
}

#[test]
fn the_manuals_line_halfway_and_at_the_end() {
    // Reference 003: (−20000, 30000, −50000); halfway the ideal point is an integer point.
    let line = Line::from_pulses([-20_000, 30_000, -50_000]).unwrap();
    assert_eq!(line.steps(), 50_000);
    assert_eq!(line.position_at(25_000), [-10_000, 15_000, -25_000]);
    assert_eq!(line.position_at(50_000), [-20_000, 30_000, -50_000]);
    check_every_step(&line);
}

#[test]
fn every_small_3_axis_line_is_the_nearest_integer_at_every_step() {
    // Exhaustive over −8 … 8 on each axis: where k·Δ/L is not a half-integer the nearest integer
    // is unique, and the rule must give it (|error| < ½); at a tie either neighbour is ½ off.
    for x in -8..=8 {
        for y in -8..=8 {
            for z in -8..=8 {
                let line = Line::from_pulses([x, y, z]).unwrap();
                check_every_step(&line);
                let steps = line.steps();
                for step in 0..=steps {
                    let position = line.position_at(step);
                    for (&pos, &delta) in position.iter().zip(&line.finish()) {
                        let error = twice_error(pos, step, delta, steps);
                        let twice_ideal = 2 * i128::from(step) * i128::from(delta);
                        let tie = steps > 0
                            && (twice_ideal - i128::from(steps)).rem_euclid(2 * i128::from(steps))
                                == 0;
                        assert!(error.abs() < i128::from(steps) || tie || steps == 0);
                    }
                }
            }
        }
    }
}

#[test]
fn a_finish_point_at_the_start_has_no_steps() {
    let line = Line::from_pulses([0, 0, 0]).unwrap();
    assert_eq!(line.steps(), 0);
    assert_eq!(line.walk().next(), None);
    assert_eq!(line.position_at(1_000), [0, 0, 0]);
    let mut walk = line.walk();
    assert_eq!(walk.advance_to(u32::MAX), [0, 0, 0]);
    assert!(walk.is_finished());
}

#[test]
fn steps_past_the_end_stay_on_the_finish_point_and_the_walk_can_go_back() {
    let line = Line::from_pulses([LIMIT, -LIMIT, 7, -LIMIT / 3]).unwrap();
    let mut walk = line.walk();
    assert_eq!(walk.advance_to(u32::MAX), line.finish());
    assert_eq!(walk.step(), line.steps());
    assert_eq!(walk.next(), None);
    // Back to the start, then one step: the long axes pulse, 7/L and (L/3)/L are still 0.
    assert_eq!(walk.advance_to(0), [0; 4]);
    assert_eq!(walk.next(), Some([1, -1, 0, 0]));
}

#[test]
fn a_finish_point_out_of_range_is_an_error_naming_it() {
    for bad in [LIMIT + 1, -LIMIT - 1, i32::MIN, i32::MAX] {
        let error = Line::from_pulses([0, bad]).unwrap_err();
        assert!(
            matches!(error, Error::OutOfRange { parameter: "finish point", value, range }
                if value == f64::from(bad) && range.max == f64::from(LIMIT) && range.min == -f64::from(LIMIT)),
            "{error:?}"
        );
        assert!(error
            .to_string()
            .ends_with("-1073741823 … 1073741823 pulses"));
    }
}

/// A coordinate anywhere in ±(2³⁰ − 1), with the edges, zero and small values over-weighted.
fn coordinate() -> impl Strategy<Value = i32> {
    prop_oneof![
        8 => -LIMIT..=LIMIT,
        1 => Just(0),
        1 => Just(LIMIT),
        1 => Just(-LIMIT),
        1 => -16..=16i32,
    ]
}

/// A short move: magnitudes up to 3,000, so every step is checked.
fn short_coordinate() -> impl Strategy<Value = i32> {
    prop_oneof![4 => -3_000..=3_000i32, 1 => Just(0), 1 => Just(3_000), 1 => Just(-3_000)]
}

/// xorshift64: the pseudo-random steps per cycle of a long move, from a proptest seed.
fn next_random(state: &mut u64) -> u64 {
    *state ^= *state << 13;
    *state ^= *state >> 7;
    *state ^= *state << 17;
    *state
}

/// A long move driven the way a speed profile drives it: `cycles` cycles of many steps each
/// (random, about L/cycles), one O(1) jump per cycle, each checked against the ideal line, for
/// monotonicity since the last cycle, and for agreement of one further step with the rule.
fn check_cycles<const N: usize>(line: &Line<N>, cycles: u32, seed: u64) {
    let steps = line.steps();
    let mut state = seed | 1;
    let mean = u64::from(steps / cycles).max(1);
    let mut walk = line.walk();
    let (mut step, mut before) = (0u32, [0i32; N]);
    while step < steps {
        let take = 1 + next_random(&mut state) % (2 * mean);
        let next = u64::from(step) + take;
        let next = next.min(u64::from(steps)) as u32;
        let after = walk.advance_to(next);
        check_at(line, next, after);
        assert_eq!(after, line.position_at(next));
        for axis in 0..N {
            let toward = i64::from(line.finish()[axis].signum());
            let moved = (i64::from(after[axis]) - i64::from(before[axis])) * toward;
            assert!(
                (0..=i64::from(next - step)).contains(&moved),
                "axis {axis} of {:?}: {moved} pulses in {} steps",
                line.finish(),
                next - step
            );
        }
        // One step by the iterator from here: one pulse at most, equal to the rule, then back.
        if let Some(single) = walk.clone().next() {
            check_one_step(line, after, single);
            check_at(line, next + 1, single);
            assert_eq!(single, line.position_at(next + 1));
        }
        (step, before) = (next, after);
    }
    assert_eq!(before, line.finish());
    assert!(walk.is_finished());
}

/// The bound at random steps of a long move, and order between them.
fn check_random_steps<const N: usize>(line: &Line<N>, fractions: &[u32]) {
    let steps = line.steps();
    let mut picked: Vec<u32> = fractions
        .iter()
        .map(|&f| (u64::from(steps) * u64::from(f) / u64::from(u32::MAX)) as u32)
        .collect();
    picked.sort_unstable();
    let mut before = [0i32; N];
    for &step in &picked {
        let position = line.position_at(step);
        check_at(line, step, position);
        for axis in 0..N {
            let toward = line.finish()[axis].signum();
            assert!((position[axis] - before[axis]) * toward >= 0, "monotone");
        }
        before = position;
    }
    assert_eq!(line.position_at(steps), line.finish());
}

/// The division-free evaluation against the rule's division, side by side, at `count` random
/// steps (anywhere on the line, the ends, and past them) and at every step near both ends.
fn check_against_division<const N: usize>(line: &Line<N>, count: u32, seed: u64) {
    let steps = line.steps();
    let mut state = seed | 1;
    let near_ends = (0..steps.min(64)).chain(steps.saturating_sub(64)..=steps);
    let random = (0..count).map(|_| {
        let random = next_random(&mut state);
        match random % 8 {
            0 => u32::MAX,
            1 => steps.saturating_add((random >> 8) as u32 % 4),
            _ => ((random >> 8) % (u64::from(steps) + 1)) as u32,
        }
    });
    for step in near_ends.chain(random) {
        assert_eq!(
            line.position_at(step),
            line.position_by_division(step),
            "{:?} at step {step}",
            line.finish()
        );
    }
}

#[test]
fn the_extremes_equal_the_division() {
    // L = 2³⁰ − 1 with magnitudes next to L, 1 and L/2, whose constants are rounded hardest, in
    // both signs; and every line of 1 or 2 steps.
    for sign in [1, -1] {
        let line = Line::from_pulses([
            sign * LIMIT,
            -sign * (LIMIT - 1),
            sign,
            -sign * (LIMIT / 2 + 1),
        ])
        .unwrap();
        check_against_division(&line, 100_000, 7);
    }
    for finish in [[1, 0], [1, -1], [2, 1], [-2, -1], [2, -2], [0, -2]] {
        check_against_division(&Line::from_pulses(finish).unwrap(), 10, 1);
    }
}

macro_rules! axes_properties {
    ($module:ident, $n:literal) => {
        mod $module {
            use super::*;

            proptest! {
                #![proptest_config(ProptestConfig::with_cases(2_000))]

                #[test]
                fn every_step_of_a_short_move(finish in prop::array::uniform::<_, $n>(short_coordinate())) {
                    check_every_step(&Line::from_pulses(finish).unwrap());
                }

                #[test]
                fn every_cycle_of_a_long_move(
                    finish in prop::array::uniform::<_, $n>(coordinate()),
                    cycles in 1u32..3_000,
                    seed in any::<u64>(),
                ) {
                    check_cycles(&Line::from_pulses(finish).unwrap(), cycles, seed);
                }

                #[test]
                fn the_fast_form_equals_the_division(
                    finish in prop::array::uniform::<_, $n>(coordinate()),
                    seed in any::<u64>(),
                ) {
                    check_against_division(&Line::from_pulses(finish).unwrap(), 500, seed);
                }

                #[test]
                fn random_steps_of_a_long_move(
                    finish in prop::array::uniform::<_, $n>(coordinate()),
                    fractions in prop::collection::vec(any::<u32>(), 1..200),
                ) {
                    check_random_steps(&Line::from_pulses(finish).unwrap(), &fractions);
                }
            }
        }
    };
}

axes_properties!(two_axes, 2);
axes_properties!(three_axes, 3);
axes_properties!(four_axes, 4);
