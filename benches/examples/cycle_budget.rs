//! The cycle-budget summary: the median cost of one cycle of each generator and of the peers on
//! the same move (benches/common), as nanoseconds and as a share of the Juno (102.4 µs) and
//! MC1451A (330 µs) cycle times, printed as the README's table.
//!
//! `cargo run --release -p profilegen-benches --example cycle_budget` (criterion's `cargo bench`
//! measures the same moves with confidence intervals; this is the quick summary).

#[path = "../common/mod.rs"]
mod common;

use std::hint::black_box;
use std::time::Instant;

use profilegen::format::CycleTime;
use profilegen::ProfileGenerator;

/// Cycles per timed chunk.
const CHUNK: usize = 1_000;

/// Median and worst (slowest chunk) nanoseconds per cycle, over chunks of `CHUNK` cycles of
/// `repeats` runs of `cycle`, which returns false when the move is over.
fn per_cycle(repeats: usize, mut start: impl FnMut() -> Box<dyn FnMut() -> bool>) -> (f64, f64) {
    let mut chunks = Vec::new();
    for _ in 0..repeats {
        let mut cycle = start();
        loop {
            let began = Instant::now();
            let mut done = 0;
            while done < CHUNK && cycle() {
                done += 1;
            }
            if done < CHUNK {
                break;
            }
            chunks.push(began.elapsed().as_nanos() as f64 / CHUNK as f64);
        }
    }
    chunks.sort_by(f64::total_cmp);
    (chunks[chunks.len() / 2], *chunks.last().unwrap())
}

fn generator<G: ProfileGenerator + 'static>(
    make: fn() -> G,
) -> impl FnMut() -> Box<dyn FnMut() -> bool> {
    // Velocity contouring never completes: its first 20,000 cycles.
    move || {
        let mut axis = make();
        let mut cycles = 0;
        Box::new(move || {
            black_box(axis.step());
            cycles += 1;
            !axis.is_complete() && cycles < 20_000
        })
    }
}

/// Median nanoseconds of one call.
fn per_call<T>(mut call: impl FnMut() -> T) -> f64 {
    let mut times: Vec<f64> = (0..201)
        .map(|_| {
            let began = Instant::now();
            for _ in 0..10 {
                black_box(call());
            }
            began.elapsed().as_nanos() as f64 / 10.0
        })
        .collect();
    times.sort_by(f64::total_cmp);
    times[times.len() / 2]
}

fn main() {
    use ramp_maker::MotionProfile as _;
    let repeats = 5;
    let mut rows: Vec<(&str, (f64, f64))> = vec![
        (
            "profilegen VelocityContouring::step",
            per_cycle(repeats, generator(common::velocity)),
        ),
        (
            "profilegen Trapezoidal::step",
            per_cycle(repeats, generator(common::trapezoidal)),
        ),
        (
            "profilegen SCurve::step",
            per_cycle(repeats, generator(common::scurve)),
        ),
    ];
    let table = common::microstep_table();
    let mut position = 0i32;
    rows.push((
        "profilegen MicrostepTable::outputs (3-phase, scaled)",
        per_cycle(repeats, move || {
            Box::new(move || {
                position = position.wrapping_add(7);
                black_box(table.outputs(black_box(position)));
                position < 10_000_000
            })
        }),
    ));
    rows.push((
        "rsruckig Ruckig::update (online, per cycle)",
        per_cycle(1, || {
            let mut otg = common::peers::ruckig();
            let mut input = common::peers::ruckig_input();
            let mut output = rsruckig::prelude::OutputParameter::new(None);
            let mut cycles = 0;
            Box::new(move || {
                let working = otg.update(&input, &mut output).unwrap()
                    == rsruckig::prelude::RuckigResult::Working;
                output.pass_to_input(&mut input);
                cycles += 1;
                working && cycles < 20_000
            })
        }),
    ));
    let (_, evaluate) = s_curve::s_curve_generator(
        &common::peers::s_curve_input(),
        s_curve::Derivative::Position,
    );
    rows.push((
        "s_curve evaluate (per cycle)",
        per_cycle(repeats, || {
            let (_, evaluate) = s_curve::s_curve_generator(
                &common::peers::s_curve_input(),
                s_curve::Derivative::Position,
            );
            let mut t = 0.0;
            Box::new(move || {
                black_box(evaluate(black_box(t)));
                t += 1.0;
                t < 20_000.0
            })
        }),
    ));
    drop(evaluate);
    rows.push((
        "ramp-maker Trapezoidal::next_delay (per step)",
        per_cycle(repeats, || {
            let mut profile = common::peers::ramp_maker();
            let mut steps = 0;
            Box::new(move || {
                steps += 1;
                black_box(profile.next_delay()).is_some() && steps < 100_000
            })
        }),
    ));

    let juno = CycleTime::JUNO.seconds() * 1e9;
    let mc1451a = CycleTime::MC1451A.seconds() * 1e9;
    println!("| per cycle | median ns | slowest 1,000-cycle chunk, ns/cycle | share of Juno 102.4 µs | share of MC1451A 330 µs |");
    println!("|---|---:|---:|---:|---:|");
    for (name, (median, worst)) in &rows {
        println!(
            "| {name} | {median:.1} | {worst:.1} | {:.4} % | {:.4} % |",
            100.0 * median / juno,
            100.0 * median / mc1451a
        );
    }
    println!();
    println!("| set up a move | median ns |");
    println!("|---|---:|");
    let scurve = common::scurve_parameters();
    println!(
        "| profilegen SCurve::new (plan) | {:.0} |",
        per_call(|| profilegen::SCurve::new(scurve).unwrap().duration())
    );
    let trapezoid = common::trapezoidal_parameters();
    println!(
        "| profilegen Trapezoidal::new (validate) | {:.0} |",
        per_call(|| profilegen::Trapezoidal::new(trapezoid).unwrap())
    );
    let input = common::peers::ruckig_input();
    println!(
        "| rsruckig Ruckig::calculate | {:.0} |",
        per_call(|| common::peers::ruckig_plan(&input))
    );
    let s_input = common::peers::s_curve_input();
    println!(
        "| s_curve s_curve_generator | {:.0} |",
        per_call(|| s_curve::s_curve_generator(&s_input, s_curve::Derivative::Position).0)
    );
}
