//! `SCurve::new` of two revisions of the crate ("new" and "old", written by
//! `tools/ab_planning.sh`, which runs this both ways round): the planning bench's random moves
//! (`benches/common/moves.rs`), each timed with both builds in the same sweep, the order
//! alternating from move to move and sweep to sweep, each time the least of 3 runs over all
//! sweeps. A neighbour's load or a change of clock then falls on both builds alike, where the
//! planning bench's own runs, minutes apart, move by up to 20 %.
//!
//! `profilegen-ab-planning [moves (100000)] [sweeps (10)]`
//!
//! `profilegen-ab-planning --plans [moves (100000)] [fractional moves (100000)]` times nothing:
//! it checks that the two builds plan the same moves (`tools/ab_plans.sh`): the planning bench's
//! random moves by their plans (result, phases, total, peaks), and moves of a few raw units of
//! jerk from fractional positions (what a stop leaves: the class `pure_jerk` plans) cycle by
//! cycle, every state of the two runs compared.

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

/// The plan of `p` from `start` by both builds, as text (`Err` included), and, for moves of at
/// most `stepped` cycles, every state stepped to the end.
fn both_plans(p: profilegen::ScurveParameters, start: i64, stepped: u64) -> (String, String) {
    use profilegen::ProfileGenerator as _;
    use profilegen_old::ProfileGenerator as _;
    let new =
        profilegen::SCurve::with_position(p, profilegen::fixed::types::I32F32::from_bits(start));
    let old = profilegen_old::SCurve::with_position(
        old_parameters(p),
        profilegen_old::fixed::types::I32F32::from_bits(start),
    );
    match (new, old) {
        (Ok(mut new), Ok(mut old)) => {
            let (mut a, mut b) = (format!("{:?}", new.plan()), format!("{:?}", old.plan()));
            if new.duration() <= stepped && a == b {
                for _ in 0..new.duration() + 2 {
                    let (x, y) = (new.step(), old.step());
                    let x = (
                        x.position.to_bits(),
                        x.velocity.to_bits(),
                        x.acceleration.to_bits(),
                    );
                    let y = (
                        y.position.to_bits(),
                        y.velocity.to_bits(),
                        y.acceleration.to_bits(),
                    );
                    if x != y {
                        a.push_str(&format!(" state {x:?}"));
                        b.push_str(&format!(" state {y:?}"));
                        break;
                    }
                }
            }
            (a, b)
        }
        (new, old) => (
            format!("{:?}", new.map(|g| g.plan())),
            format!("{:?}", old.map(|g| g.plan())),
        ),
    }
}

/// The `total` of a plan printed by `both_plans`, if it has one.
fn total_of(plan: &str) -> Option<i64> {
    let digits = &plan[plan.find("total: ")? + "total: ".len()..];
    let end = digits.find(|c: char| !c.is_ascii_digit())?;
    digits[..end].parse().ok()
}

/// `--plans`: the moves whose plans differ between the builds, and how many; of those, how many
/// are shorter and longer in the new build, and by how many cycles in all.
fn compare_plans(moves: u64, fractional: u64) {
    use profilegen::format::mc1451a::{Jerk, MaxVelocity, ScurveAcceleration};
    let mut differ = 0;
    let (mut shorter, mut longer, mut change) = (0, 0, 0i64);
    let mut report = |what: String, (a, b): (String, String)| {
        if a != b {
            differ += 1;
            if differ <= 10 {
                println!("{what}:\n  new {a}\n  old {b}");
            }
            if let (Some(new), Some(old)) = (total_of(&a), total_of(&b)) {
                shorter += u32::from(new < old);
                longer += u32::from(new > old);
                change += new - old;
            }
        }
    };
    for i in 0..moves {
        let p = moves::scurve_parameters(i);
        report(format!("move #{i}"), both_plans(p, 0, 0));
    }
    // Distances log-uniform over 2 .. 2^17 raw units to a fractional position short of 7 counts,
    // a jerk of 1 to 15 raw units, the other registers log-uniform (as the Cortex-M4 probe's
    // `--sub-count-moves`), stepped to the end.
    for i in 0..fractional {
        let mut random = moves::SplitMix64::for_move(i ^ 0xF4AC_7100);
        let distance = random.log_uniform(17).max(2) as i64;
        let p = profilegen::ScurveParameters {
            destination: 7,
            max_velocity: MaxVelocity::from_bits(random.log_uniform(30) as u32).expect("in range"),
            max_acceleration: ScurveAcceleration::from_bits(random.log_uniform(15) as u16)
                .expect("in range"),
            jerk: Jerk::from_bits(1 + (random.next_u64() % 15) as u32).expect("in range"),
        };
        report(
            format!("fractional #{i} ({distance} raw units, {p:?})"),
            both_plans(p, (7 << 32) - distance, 100_000),
        );
    }
    println!("{moves} random moves, {fractional} from fractional positions: {differ} planned differently");
    if differ > 0 {
        println!("  of those, {shorter} shorter and {longer} longer in the new build ({change:+} cycles in all)");
    }
    if differ > 0 {
        std::process::exit(1);
    }
}

fn main() {
    if std::env::args().nth(1).as_deref() == Some("--plans") {
        let mut counts = std::env::args().skip(2).map(|a| a.parse::<u64>());
        let moves = counts.next().and_then(Result::ok).unwrap_or(100_000);
        let fractional = counts.next().and_then(Result::ok).unwrap_or(100_000);
        return compare_plans(moves, fractional);
    }
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
