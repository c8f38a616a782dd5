//! The x86 instruction count of planning an S-curve move: plans the first N random moves of the
//! planning bench (`benches/common/moves.rs`, every register log-uniform over its whole range)
//! with `SCurve::new`, so that callgrind can count the instructions inside it (deterministic,
//! unlike a time). `tools/instruction_counts.sh` runs it under callgrind and prints the mean per
//! plan.
//!
//! `cargo run --release -p profilegen-benches --example plan_instructions -- 20000`

#[allow(dead_code)] // only `scurve_parameters`
#[path = "../common/moves.rs"]
mod moves;

use std::hint::black_box;

use profilegen::SCurve;

fn main() {
    let count: u64 = std::env::args()
        .nth(1)
        .and_then(|text| text.replace(['_', ','], "").parse().ok())
        .unwrap_or(20_000);
    let (mut planned, mut cycles) = (0u64, 0u64);
    for index in 0..count {
        let parameters = moves::scurve_parameters(index);
        if let Ok(axis) = black_box(SCurve::new(black_box(parameters))) {
            planned += 1;
            cycles += axis.duration();
        }
    }
    println!("{planned} of {count} moves planned, {cycles} cycles in all");
}
