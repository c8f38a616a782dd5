//! Criterion benches, one group per question: the cost of one cycle of each generator (in the
//! phases that cost most and in cruise), the cost of setting up a move, the microstep lookup, and
//! the same move in the peers (rsruckig, s_curve, ramp-maker), in the same run.
//!
//! `cargo bench --bench cycle_cost`; per-cycle groups report time for 1,000 cycles
//! (throughput in elements = cycles).
#![allow(missing_docs)] // criterion_group! generates undocumented items

mod common;

use criterion::{black_box, criterion_group, criterion_main, BatchSize, Criterion, Throughput};
use profilegen::ProfileGenerator;

const CYCLES: u64 = 1_000;

/// Times `CYCLES` steps of a copy of `start`.
fn steps<G: ProfileGenerator + Clone>(
    c: &mut criterion::BenchmarkGroup<'_, criterion::measurement::WallTime>,
    name: &str,
    start: G,
) {
    c.bench_function(name, |b| {
        b.iter_batched_ref(
            || start.clone(),
            |generator| {
                for _ in 0..CYCLES {
                    black_box(generator.step());
                }
            },
            BatchSize::SmallInput,
        )
    });
}

fn cycle_cost(c: &mut Criterion) {
    let mut group = c.benchmark_group("step (1,000 cycles)");
    group.throughput(Throughput::Elements(CYCLES));
    let velocity = common::velocity();
    steps(&mut group, "velocity/ramp", velocity.clone());
    steps(
        &mut group,
        "velocity/cruise",
        common::advanced(&velocity, 1_000),
    );
    let trapezoid = common::trapezoidal();
    steps(&mut group, "trapezoidal/accelerate", trapezoid.clone());
    steps(
        &mut group,
        "trapezoidal/cruise",
        common::advanced(&trapezoid, 3_000),
    );
    let decelerating = common::trapezoidal_deceleration_start() - 10;
    steps(
        &mut group,
        "trapezoidal/decelerate",
        common::advanced(&trapezoid, decelerating),
    );
    let scurve = common::scurve();
    steps(&mut group, "scurve/phases I-III", scurve.clone());
    steps(
        &mut group,
        "scurve/cruise",
        common::advanced(&scurve, 3_000),
    );
    let end = scurve.plan().total - CYCLES;
    steps(
        &mut group,
        "scurve/phases V-VII",
        common::advanced(&scurve, end),
    );
    group.finish();
}

fn setup_cost(c: &mut Criterion) {
    let mut group = c.benchmark_group("set up a move");
    let scurve = common::scurve_parameters();
    group.bench_function("scurve/plan", |b| {
        b.iter(|| {
            profilegen::SCurve::new(black_box(scurve))
                .unwrap()
                .duration()
        })
    });
    let trapezoid = common::trapezoidal_parameters();
    group.bench_function("trapezoidal/validate", |b| {
        b.iter(|| profilegen::Trapezoidal::new(black_box(trapezoid)).unwrap())
    });
    group.finish();
}

fn microstep(c: &mut Criterion) {
    let table = common::microstep_table();
    let mut group = c.benchmark_group("microstep lookup (1,000 positions)");
    group.throughput(Throughput::Elements(CYCLES));
    group.bench_function("3-phase, N=256, scaled", |b| {
        b.iter(|| {
            for position in 0..CYCLES as i32 {
                black_box(table.outputs(black_box(position * 7 - 3_000)));
            }
        })
    });
    group.finish();
}

fn peers(c: &mut Criterion) {
    use ramp_maker::MotionProfile as _;
    let mut group = c.benchmark_group("peers: the same move");
    let input = common::peers::ruckig_input();
    group.bench_function("rsruckig/calculate", |b| {
        b.iter(|| common::peers::ruckig_plan(black_box(&input)))
    });
    group.bench_function("s_curve/plan", |b| {
        let input = common::peers::s_curve_input();
        b.iter(|| s_curve::s_curve_generator(black_box(&input), s_curve::Derivative::Position).0)
    });
    group.finish();

    let mut group = c.benchmark_group("peers: per cycle (1,000 cycles)");
    group.throughput(Throughput::Elements(CYCLES));
    group.bench_function("rsruckig/update", |b| {
        b.iter_batched_ref(
            || {
                (
                    common::peers::ruckig(),
                    common::peers::ruckig_input(),
                    rsruckig::prelude::OutputParameter::new(None),
                )
            },
            |(otg, input, output)| {
                for _ in 0..CYCLES {
                    black_box(otg.update(input, output).unwrap());
                    output.pass_to_input(input);
                }
            },
            BatchSize::SmallInput,
        )
    });
    let (_, evaluate) = s_curve::s_curve_generator(
        &common::peers::s_curve_input(),
        s_curve::Derivative::Position,
    );
    group.bench_function("s_curve/evaluate", |b| {
        b.iter(|| {
            for cycle in 0..CYCLES {
                black_box(evaluate(black_box(cycle as f64)));
            }
        })
    });
    group.bench_function("ramp-maker/next_delay", |b| {
        b.iter_batched_ref(
            common::peers::ramp_maker,
            |profile| {
                for _ in 0..CYCLES {
                    black_box(profile.next_delay());
                }
            },
            BatchSize::SmallInput,
        )
    });
    group.finish();
}

criterion_group!(benches, cycle_cost, setup_cost, microstep, peers);
criterion_main!(benches);
