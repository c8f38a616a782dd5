//! The S-curve planner against an exhaustive search, on moves small enough to search: every
//! jerk sequence within the limits, breadth-first over (acceleration, velocity, position).
//!
//! Two things follow for each move. No plan may be shorter than the exhaustive optimum (a plan
//! that is would break a limit or miss the distance: an independent check of the planner). And
//! the exhaustive optimum says how far the planner is from the best any plan can do, which is
//! what the continuous bound of SPEC §8 (optimum + 3 cycles) is a proxy for. On moves from
//! fractional positions with a jerk of a few raw units the planner was 2 to 7 cycles over this
//! optimum and up to 7.5 over the continuous one, until the plans where only the jerk binds
//! (`src/scurve/pure_jerk.rs`); now it is at most 2 over it, and within the continuous bound: run
//! `cargo test --release --test scurve_exhaustive -- --nocapture` to see the gaps.

use std::collections::HashSet;

use fixed::types::I32F32;
use profilegen::format::mc1451a::{Jerk, MaxVelocity, ScurveAcceleration};
use profilegen::reference::scurve_duration;
use profilegen::{ProfileGenerator, SCurve, ScurveParameters};

/// The fewest cycles of any move of `distance` raw units (2^-32 counts) from rest to rest with
/// |jerk| ≤ `jerk`, |acceleration| ≤ `acceleration`, 0 ≤ velocity ≤ `velocity` (raw 2^-32
/// units per cycle, per cycle², per cycle³), counted as the planner counts them: cycles from the
/// first step to the first state at the destination with velocity and acceleration zero. `None`
/// past `cycles_at_most`.
fn fewest_cycles(
    distance: i64,
    jerk: i64,
    acceleration: i64,
    velocity: i64,
    cycles_at_most: u32,
) -> Option<u32> {
    let mut layer: HashSet<(i64, i64, i64)> = HashSet::from([(0, 0, 0)]);
    for cycles in 1..=cycles_at_most {
        let mut next = HashSet::new();
        for &(a, v, p) in &layer {
            for j in -jerk..=jerk {
                let a = a + j;
                let v = v + a;
                let p = p + v;
                if a.abs() > acceleration || !(0..=velocity).contains(&v) || p > distance {
                    continue;
                }
                // Each later velocity is at least v + k·a − J·k(k + 1)/2 (braking as hard as the
                // jerk allows, ignoring the acceleration limit, which only brakes more slowly)
                // and never below 0: a lower bound on the distance still to come.
                let mut still = 0;
                let mut k = 1;
                loop {
                    let least = v + k * a - jerk * k * (k + 1) / 2;
                    if least <= 0 && k * jerk >= a {
                        break;
                    }
                    still += least.max(0);
                    if p + still > distance {
                        break;
                    }
                    k += 1;
                }
                if p + still <= distance {
                    next.insert((a, v, p));
                }
            }
        }
        if next.contains(&(0, 0, distance)) {
            return Some(cycles);
        }
        layer = next;
    }
    None
}

/// A small move `distance` raw units short of `destination`.
fn small_move(
    distance: i64,
    velocity: u32,
    acceleration: u16,
    jerk: u32,
) -> (ScurveParameters, I32F32) {
    let parameters = ScurveParameters {
        destination: 1_000,
        max_velocity: MaxVelocity::from_bits(velocity).unwrap(),
        max_acceleration: ScurveAcceleration::from_bits(acceleration).unwrap(),
        jerk: Jerk::from_bits(jerk).unwrap(),
    };
    let start = I32F32::from_bits((1_000i64 << 32) - distance);
    (parameters, start)
}

/// The exhaustive optimum by hand, on the smallest moves. A move of N cycles has at most N − 2
/// moving ones (the velocity, then the acceleration, must come back to zero). 2 raw units: one
/// cycle of velocity 2 jerks by 2, −4, 2, so 3 cycles with J = 4; with J ≤ 3, velocity [1, 1]
/// (jerk 1, −1, −1, 1) in 4. 6 raw units with J = 1: [1, 2, 2, 1] (jerk 1, 0, −1, −1, 0, 1) in
/// 6; three moving cycles [v₁, v₂, v₃] have v₁, v₃ ≤ 1 (the first and last jerks) and
/// v₃ − 2v₂ + v₁ ≥ −1, so v₂ ≤ 1 and at most 3 raw units in 5 cycles. 1 raw unit with J = 1:
/// no move at all (it needs a jerk of 2).
#[test]
fn the_exhaustive_search_agrees_with_hand_counts() {
    let wide = 1 << 40;
    assert_eq!(fewest_cycles(2, 4, wide, wide, 40), Some(3));
    assert_eq!(fewest_cycles(2, 3, wide, wide, 40), Some(4));
    assert_eq!(fewest_cycles(2, 1, wide, wide, 40), Some(4));
    assert_eq!(fewest_cycles(6, 1, wide, wide, 40), Some(6));
    assert_eq!(fewest_cycles(1, 1, wide, wide, 40), None);
}

/// Moves of a few hundred raw units with a jerk of 1 to 6 raw units (from fractional positions,
/// what stops leave; the other registers large, small, and at the extremes): the plan arrives
/// exactly in `plan().total` cycles, never fewer than the exhaustive optimum, and both the
/// exhaustive optimum and the plan are within 3 cycles of the continuous one (SPEC §8's bound).
#[test]
fn no_plan_is_shorter_than_the_exhaustive_optimum() {
    let mut worst_gap = 0;
    let mut moves = 0;
    for jerk in 1u32..=6 {
        for distance in [2i64, 3, 7, 37, 41, 63, 101, 163, 194] {
            // Every velocity here is at most the distance, under 2^16 raw units: the smallest
            // acceleration and velocity registers (one raw unit each, 2^16 in 2^-32 units) do not
            // bind, so one search serves every pair of them below.
            let fewest = fewest_cycles(distance, i64::from(jerk), 1 << 16, 1 << 16, 80);
            for (velocity, acceleration) in [
                (1u32, 1u16),
                (3, 1),
                (21, 14),
                (16_343, 62),
                (u32::MAX >> 2, u16::MAX >> 1),
            ] {
                let (parameters, start) = small_move(distance, velocity, acceleration, jerk);
                let Ok(mut axis) = SCurve::with_position(parameters, start) else {
                    assert!(distance == 1 && jerk == 1);
                    continue;
                };
                let total = axis.plan().total;
                let fewest = fewest.expect("a plan exists: the planner found one");
                assert!(
                    total >= u64::from(fewest),
                    "{total} cycles, fewer than the exhaustive {fewest}: {parameters:?} from {start}"
                );
                let counts = distance as f64 / 4_294_967_296.0;
                let continuous = scurve_duration(
                    counts,
                    parameters.max_velocity.to_f64(),
                    parameters.max_acceleration.to_f64(),
                    parameters.jerk.to_f64(),
                )
                .max(1.0);
                assert!(
                    f64::from(fewest) <= continuous + 3.0,
                    "exhaustive {fewest}, continuous {continuous}"
                );
                assert!(
                    total as f64 <= continuous + 3.0,
                    "planner {total}, exhaustive {fewest}, continuous {continuous}: {parameters:?} \
                     from {start}"
                );
                let mut steps = 0;
                while !axis.is_complete() {
                    axis.step();
                    steps += 1;
                }
                assert_eq!(steps, total);
                assert_eq!(axis.state().position, I32F32::from_num(1_000));
                let gap = total - u64::from(fewest);
                if gap > worst_gap {
                    println!(
                        "planner {total} cycles, exhaustive {fewest}, continuous {continuous:.2}: \
                         {distance} raw units, J {jerk}, A {acceleration}, V {velocity} (raw)"
                    );
                }
                worst_gap = worst_gap.max(gap);
                moves += 1;
            }
        }
    }
    println!("{moves} moves; the planner at most {worst_gap} cycles over the exhaustive optimum");
}
