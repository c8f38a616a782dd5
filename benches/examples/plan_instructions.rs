//! The x86 instruction count of planning an S-curve move: plans the first N random moves of the
//! planning bench (`benches/common/moves.rs`, every register log-uniform over its whole range)
//! with `SCurve::new`, so that callgrind can count the instructions inside it (deterministic,
//! unlike a time). `tools/instruction_counts.sh` runs it under callgrind and prints the mean per
//! plan.
//!
//! With `--set-parameters`, each move is planned by `SCurve::set_parameters` on a generator at
//! rest at 0 instead (a re-plan, as firmware starts each new move on the generator it keeps);
//! callgrind then counts `SCurve::set_parameters`.
//!
//! `cargo run --release -p profilegen-benches --example plan_instructions -- 20000`
//! `cargo run --release -p profilegen-benches --example plan_instructions -- 20000 --set-parameters`

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
    let replan = std::env::args().any(|argument| argument == "--set-parameters");
    let (mut planned, mut cycles) = (0u64, 0u64);
    for index in 0..count {
        let parameters = moves::scurve_parameters(index);
        if replan {
            // At rest at 0 (a plan of no move), then the move planned into it.
            let mut axis = SCurve::new(profilegen::ScurveParameters {
                destination: 0,
                ..parameters
            })
            .expect("a move of nothing");
            if black_box(&mut axis)
                .set_parameters(black_box(parameters))
                .is_ok()
            {
                planned += 1;
                cycles += axis.duration();
            }
            continue;
        }
        if let Ok(axis) = black_box(SCurve::new(black_box(parameters))) {
            planned += 1;
            cycles += axis.duration();
        }
    }
    println!("{planned} of {count} moves planned, {cycles} cycles in all");
}
