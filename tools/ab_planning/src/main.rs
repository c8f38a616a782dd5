//! `SCurve::new` of two revisions of the crate ("new" and "old", written by
//! `tools/ab_planning.sh`, which runs this both ways round): the planning bench's random moves
//! (`benches/common/moves.rs`), each timed with both builds in the same sweep, the order
//! alternating from move to move and sweep to sweep, each time the least of 3 runs over all
//! sweeps. A neighbour's load or a change of clock then falls on both builds alike, where the
//! planning bench's own runs, minutes apart, move by up to 20 %.
//!
//! `profilegen-ab-planning [moves (100000)] [sweeps (10)]`

use std::hint::black_box;
use std::time::Instant;

#[allow(dead_code)] // only `scurve_parameters`
#[path = "../../../benches/common/moves.rs"]
mod moves;

/// Runs per move in each sweep; the least of all is kept.
const REPETITIONS: usize = 3;

/// The same registers for the other build.
fn old_parameters(p: profilegen::ScurveParameters) -> profilegen_old::ScurveParameters {
    use profilegen_old::format::mc1451a::{Jerk, MaxVelocity, ScurveAcceleration};
    profilegen_old::ScurveParameters {
        destination: p.destination,
        max_velocity: MaxVelocity::from_bits(p.max_velocity.to_bits()).expect("in range"),
        max_acceleration: ScurveAcceleration::from_bits(p.max_acceleration.to_bits())
            .expect("in range"),
        jerk: Jerk::from_bits(p.jerk.to_bits()).expect("in range"),
    }
}

/// The least time of `REPETITIONS` runs of `f` into `best`, in ns; the result is kept where `f`
/// returned it, only its address escapes.
fn time<R>(best: &mut u64, mut f: impl FnMut() -> R) {
    for _ in 0..REPETITIONS {
        let start = Instant::now();
        let result = f();
        black_box(&result);
        *best = (*best).min(start.elapsed().as_nanos() as u64);
    }
}

fn main() {
    let mut arguments = std::env::args().skip(1).map(|a| a.parse::<usize>());
    let moves = arguments.next().and_then(Result::ok).unwrap_or(100_000);
    let sweeps = arguments.next().and_then(Result::ok).unwrap_or(10);
    let new: Vec<_> = (0..moves as u64).map(moves::scurve_parameters).collect();
    let old: Vec<_> = new.iter().map(|&p| old_parameters(p)).collect();
    let (mut best_new, mut best_old) = (vec![u64::MAX; moves], vec![u64::MAX; moves]);
    for sweep in 0..sweeps {
        for i in 0..moves {
            let new_first = (i + sweep) % 2 == 0;
            for turn in 0..2 {
                if (turn == 0) == new_first {
                    time(&mut best_new[i], || {
                        profilegen::SCurve::new(black_box(new[i]))
                    });
                } else {
                    time(&mut best_old[i], || {
                        profilegen_old::SCurve::new(black_box(old[i]))
                    });
                }
            }
        }
    }
    let mean = |v: &[u64]| v.iter().sum::<u64>() as f64 / v.len() as f64;
    let median = |v: &[u64]| {
        let mut sorted = v.to_vec();
        sorted.sort_unstable();
        sorted[sorted.len() / 2]
    };
    println!(
        "{moves} moves, {sweeps} sweeps (ns, the timer's own cost included): \
         new mean {:.1}, median {} | old mean {:.1}, median {} | new/old means {:.4}",
        mean(&best_new),
        median(&best_new),
        mean(&best_old),
        median(&best_old),
        mean(&best_new) / mean(&best_old)
    );
}
