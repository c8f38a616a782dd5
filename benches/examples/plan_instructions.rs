//! The x86 instruction count of planning an S-curve move: plans the first N random moves of the
//! planning bench (`benches/common/moves.rs`, every register log-uniform over its whole range)
//! with `SCurve::new`, so that callgrind can count the instructions inside it (deterministic,
//! unlike a time). `tools/instruction_counts.sh` runs it under callgrind and prints the mean per
//! plan.
//!
//! `cargo run --release -p profilegen-benches --example plan_instructions -- 20000`

#[allow(dead_code)] // only `scurve_move`
#[path = "../common/moves.rs"]
mod moves;

use std::hint::black_box;

use profilegen::format::mc1451a::{Jerk, MaxVelocity, ScurveAcceleration};
use profilegen::{SCurve, ScurveParameters};

fn main() {
    let count: u64 = std::env::args()
        .nth(1)
        .and_then(|text| text.replace(['_', ','], "").parse().ok())
        .unwrap_or(20_000);
    let (mut planned, mut cycles) = (0u64, 0u64);
    for index in 0..count {
        let (destination, velocity, acceleration, jerk) = moves::scurve_move(index);
        let parameters = ScurveParameters {
            destination,
            max_velocity: MaxVelocity::from_bits(velocity).expect("velocity in range"),
            max_acceleration: ScurveAcceleration::from_bits(acceleration)
                .expect("acceleration in range"),
            jerk: Jerk::from_bits(jerk).expect("jerk in range"),
        };
        if let Ok(axis) = black_box(SCurve::new(black_box(parameters))) {
            planned += 1;
            cycles += axis.duration();
        }
    }
    println!("{planned} of {count} moves planned, {cycles} cycles in all");
}
