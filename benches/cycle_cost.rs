//! Criterion benches, one group per question:
//!
//! - `cost per cycle`: one cycle of each generator in each phase of the bench move
//!   (`benches/common`), timed over a window that holds only cycles of that phase (at most 1,000;
//!   the longest run of the phase, found by stepping the move first);
//! - `set up a move`: planning (S-curve) and validation (trapezoid);
//! - `microstep lookup`: `MicrostepTable::outputs`;
//! - `3-axis line per cycle`: `LinearInterpolation::step` (profile plus geometry, SPEC §16) on
//!   reference 003's line, driven by the MCX514 trapezoid and S-curve and by the crate's
//!   trapezoid and S-curve, by phase;
//! - `circle per cycle`: `CircularInterpolation::step` (profile plus arc, SPEC §16's 150 on the
//!   Cortex-M4) on reference 003's circle (r = 10,000, 56,568 steps), driven by the MCX514
//!   trapezoid and by the crate's trapezoid;
//! - `peers: per step`: stepgen and ramp-maker on the same move in steps, by phase windows as
//!   above, delays per step;
//! - `peers: per cycle` and `peers: plan`: rsruckig and s_curve on the bench move.
//!
//! Every window is timed from a copy already advanced to its first cycle (the set-up is not
//! timed), and every state is folded into an accumulator that is observed once per window: the
//! state's three fields are all computed, and nothing is stored and reloaded per cycle (a
//! `black_box` of each state would store it to memory every cycle).
//!
//! `cargo bench -p profilegen-benches --bench cycle_cost`; `tools/bench_table.py` prints the README's table (median
//! nanoseconds per cycle or step, ratios to the peers) from the run's results.
#![allow(missing_docs)] // criterion_group! generates undocumented items

mod common;

use std::time::{Duration, Instant};

use common::{generator_window, window, Phase};
use criterion::measurement::WallTime;
use criterion::{
    black_box, criterion_group, criterion_main, BenchmarkGroup, Criterion, Throughput,
};
use profilegen::format::CycleTime;
use profilegen::interpolation::{Arc, Direction};
use profilegen::{
    DecelerationMode, Mcx514Trapezoidal, ProfileGenerator, SCurve, ScurveParameters, State,
    Trapezoidal, TrapezoidalParameters,
};

/// The longest window timed, cycles or steps.
const WINDOW: u64 = 1_000;
/// Windows timed between two reads of the clock, so that reading it is a small share.
const BATCH: u64 = 16;

const PHASES: [(Phase, &str); 3] = [
    (Phase::Accelerate, "accelerate"),
    (Phase::Cruise, "cruise"),
    (Phase::Decelerate, "decelerate"),
];

/// A state folded into the accumulator: every field used, nothing stored.
#[inline(always)]
fn fold(accumulator: i64, state: State) -> i64 {
    accumulator
        .wrapping_add(state.position.to_bits())
        .rotate_left(7)
        ^ state.velocity.to_bits()
        ^ state.acceleration.to_bits()
}

/// Times `length` calls of `step` on each of `BATCH` values from `make`, per iteration of
/// criterion's: the values are made before the clock starts.
fn time_windows<T, M: FnMut() -> T, S: FnMut(&mut T) -> i64>(
    group: &mut BenchmarkGroup<'_, WallTime>,
    name: &str,
    length: u64,
    mut make: M,
    mut step: S,
) {
    group.throughput(Throughput::Elements(length));
    group.bench_function(name, |b| {
        b.iter_custom(|iterations| {
            let mut total = Duration::ZERO;
            let mut left = iterations;
            while left > 0 {
                let batch = left.min(BATCH);
                left -= batch;
                let mut values: Vec<T> = (0..batch).map(|_| make()).collect();
                let start = Instant::now();
                for value in &mut values {
                    let mut accumulator = 0i64;
                    for _ in 0..length {
                        accumulator ^= step(value);
                    }
                    black_box(accumulator);
                }
                total += start.elapsed();
                drop(values);
            }
            total
        })
    });
}

/// One generator's phase windows, each from a copy of `start` advanced to the window.
fn generator_phases<G: ProfileGenerator + Clone>(
    group: &mut BenchmarkGroup<'_, WallTime>,
    name: &str,
    start: &G,
) {
    for (phase, label) in PHASES {
        let (first, length) = generator_window(start, phase, WINDOW);
        if length == 0 {
            continue;
        }
        let at = common::advanced(start, first);
        time_windows(
            group,
            &format!("{name}/{label}"),
            length,
            || at.clone(),
            |axis| fold(0, axis.step()),
        );
    }
}

fn cycle_cost(c: &mut Criterion) {
    let mut group = c.benchmark_group("cost per cycle");
    // Velocity contouring cruises for ever: its deceleration is a smooth stop from cruise.
    generator_phases(&mut group, "velocity", &common::velocity());
    let mut velocity = common::advanced(&common::velocity(), 1_000);
    velocity.stop(profilegen::StopKind::Smooth);
    let (first, length) = generator_window(&velocity, Phase::Decelerate, WINDOW);
    let at = common::advanced(&velocity, first);
    time_windows(
        &mut group,
        "velocity/decelerate",
        length,
        || at.clone(),
        |axis| fold(0, axis.step()),
    );
    generator_phases(&mut group, "trapezoidal", &common::trapezoidal());
    generator_phases(&mut group, "scurve", &common::scurve());
    // The MCX514 profiles on reference 003's line (20 steps/cycle): the cost of a cycle does not
    // depend on the move's size.
    generator_phases(&mut group, "mcx514", &common::manual_line_mcx514());
    generator_phases(
        &mut group,
        "mcx514_scurve",
        &common::manual_line_mcx514_scurve(),
    );
    // The electronic gear engaged behind a master counting 100 a cycle: its cruise.
    time_windows(
        &mut group,
        "gearing/cruise",
        WINDOW,
        || (common::gear(), 0i32),
        |(gear, master)| {
            *master = master.wrapping_add(100);
            fold(0, gear.follow(*master))
        },
    );
    group.finish();
}

/// The crate's trapezoid on the same line: 20 steps/cycle, 0.065 steps/cycle².
fn manual_line_trapezoid() -> Trapezoidal {
    use profilegen::format::juno::{Acceleration, TargetVelocity};
    Trapezoidal::new(TrapezoidalParameters {
        destination: common::manual_line().steps() as i32,
        max_velocity: TargetVelocity::from_num(20.0).unwrap(),
        acceleration: Acceleration::from_num(0.065).unwrap(),
        deceleration: Acceleration::ZERO,
        start_velocity: TargetVelocity::ZERO,
    })
    .unwrap()
}

/// The crate's S-curve on the same line: 20 steps/cycle, 0.065 steps/cycle², 0.00065
/// steps/cycle³ (the MCX514 S-curve's registers at 1 ms).
fn manual_line_scurve() -> SCurve {
    use profilegen::format::mc1451a::{Jerk, MaxVelocity, ScurveAcceleration};
    SCurve::new(ScurveParameters {
        destination: common::manual_line().steps() as i32,
        max_velocity: MaxVelocity::from_num(20.0).unwrap(),
        max_acceleration: ScurveAcceleration::from_num(0.065).unwrap(),
        jerk: Jerk::from_num(0.00065).unwrap(),
    })
    .unwrap()
}

/// One profile's phase windows on the manual's line: each window times `LinearInterpolation::step`
/// from a copy of the profile advanced to it (the line's set-up, one jump, is not timed).
fn line_phases<G: ProfileGenerator + Clone>(
    group: &mut BenchmarkGroup<'_, WallTime>,
    name: &str,
    start: &G,
) {
    let line = common::manual_line();
    for (phase, label) in PHASES {
        let (first, length) = generator_window(start, phase, WINDOW);
        if length == 0 {
            continue;
        }
        let at = common::advanced(start, first);
        group.throughput(Throughput::Elements(length));
        group.bench_function(format!("{name}/{label}"), |b| {
            b.iter_custom(|iterations| {
                let mut total = Duration::ZERO;
                for _ in 0..iterations {
                    let mut profile = at.clone();
                    let mut interpolation = line.drive(&mut profile);
                    let start = Instant::now();
                    let mut accumulator = 0i64;
                    for _ in 0..length {
                        let state = interpolation.step();
                        accumulator = fold(accumulator, state.driving)
                            ^ i64::from(state.axes[0])
                            ^ i64::from(state.axes[1]).rotate_left(21)
                            ^ i64::from(state.axes[2]).rotate_left(42);
                    }
                    total += start.elapsed();
                    black_box(accumulator);
                }
                total
            })
        });
    }
}

/// Reference 003's circle: r = 10,000, a full turn counter-clockwise, 56,568 steps.
fn manual_circle() -> Arc {
    Arc::from_pulses([10_000, 0], [0, 0], Direction::CounterClockwise).unwrap()
}

/// Its MCX514 trapezoid at 1 ms: SV 500, DV 20,000 pps, AC = DC = 65,000 pps/s, the manual
/// deceleration point 53,493.
fn manual_circle_mcx514() -> Mcx514Trapezoidal {
    use profilegen::format::mcx514::{
        Acceleration, Deceleration, DriveSpeed, InitialSpeed, ManualDecelerationPoint,
    };
    use profilegen::interpolation::CircularDriving;
    manual_circle()
        .mcx514_profile(
            CircularDriving {
                initial_speed: InitialSpeed::from_bits(500).unwrap(),
                drive_speed: DriveSpeed::from_bits(20_000).unwrap(),
                acceleration: Acceleration::from_bits(65_000).unwrap(),
                deceleration: Deceleration::from_bits(65_000).unwrap(),
                jerk: None,
                deceleration_jerk: None,
                deceleration_mode: DecelerationMode::Manual(
                    ManualDecelerationPoint::from_bits(53_493).unwrap(),
                ),
            },
            CycleTime::from_seconds(1e-3).unwrap(),
        )
        .unwrap()
}

/// The crate's trapezoid on the same circle: 20 steps/cycle, 0.065 steps/cycle².
fn manual_circle_trapezoid() -> Trapezoidal {
    use profilegen::format::juno::{Acceleration, TargetVelocity};
    Trapezoidal::new(TrapezoidalParameters {
        destination: manual_circle().steps() as i32,
        max_velocity: TargetVelocity::from_num(20.0).unwrap(),
        acceleration: Acceleration::from_num(0.065).unwrap(),
        deceleration: Acceleration::ZERO,
        start_velocity: TargetVelocity::ZERO,
    })
    .unwrap()
}

/// One profile's phase windows on the manual's circle, as `line_phases` does for the line.
fn circle_phases<G: ProfileGenerator + Clone>(
    group: &mut BenchmarkGroup<'_, WallTime>,
    name: &str,
    start: &G,
) {
    let circle = manual_circle();
    for (phase, label) in PHASES {
        let (first, length) = generator_window(start, phase, WINDOW);
        if length == 0 {
            continue;
        }
        let at = common::advanced(start, first);
        group.throughput(Throughput::Elements(length));
        group.bench_function(format!("{name}/{label}"), |b| {
            b.iter_custom(|iterations| {
                let mut total = Duration::ZERO;
                for _ in 0..iterations {
                    let mut profile = at.clone();
                    let mut interpolation = circle.drive(&mut profile);
                    let start = Instant::now();
                    let mut accumulator = 0i64;
                    for _ in 0..length {
                        let state = interpolation.step();
                        accumulator = fold(accumulator, state.driving)
                            ^ i64::from(state.axes[0])
                            ^ i64::from(state.axes[1]).rotate_left(21);
                    }
                    total += start.elapsed();
                    black_box(accumulator);
                }
                total
            })
        });
    }
}

fn circle_cost(c: &mut Criterion) {
    let mut group = c.benchmark_group("circle per cycle");
    circle_phases(&mut group, "mcx514", &manual_circle_mcx514());
    circle_phases(&mut group, "trapezoidal", &manual_circle_trapezoid());
    group.finish();
}

fn line_cost(c: &mut Criterion) {
    let mut group = c.benchmark_group("3-axis line per cycle");
    line_phases(&mut group, "mcx514", &common::manual_line_mcx514());
    line_phases(
        &mut group,
        "mcx514_scurve",
        &common::manual_line_mcx514_scurve(),
    );
    line_phases(&mut group, "trapezoidal", &manual_line_trapezoid());
    line_phases(&mut group, "scurve", &manual_line_scurve());
    group.finish();
}

fn setup_cost(c: &mut Criterion) {
    let mut group = c.benchmark_group("set up a move");
    let scurve = common::scurve_parameters();
    group.bench_function("scurve/plan", |b| {
        b.iter(|| SCurve::new(black_box(scurve)).unwrap().duration())
    });
    let trapezoid = common::trapezoidal_parameters();
    group.bench_function("trapezoidal/plan", |b| {
        b.iter(|| profilegen::Trapezoidal::new(black_box(trapezoid)).unwrap())
    });
    group.finish();
}

fn microstep(c: &mut Criterion) {
    let table = common::microstep_table();
    let mut group = c.benchmark_group("microstep lookup");
    group.throughput(Throughput::Elements(WINDOW));
    group.bench_function("3-phase, N=256, scaled", |b| {
        b.iter(|| {
            for position in 0..WINDOW as i32 {
                black_box(table.outputs(black_box(position * 7 - 3_000)));
            }
        })
    });
    group.finish();
}

/// The peers' phase windows in steps, found from their delays (a shorter delay is a faster
/// step), each timed on a fresh profile advanced to the window (they are not `Clone`).
fn peers_per_step(c: &mut Criterion) {
    use ramp_maker::MotionProfile as _;
    let mut group = c.benchmark_group("peers: per step");
    let delays = |mut next: Box<dyn FnMut() -> Option<i64>>| {
        let mut before: Option<i64> = None;
        let mut phases = Vec::new();
        while let Some(delay) = next() {
            // Speed-like: the negated delay rises while accelerating.
            let speed = -delay;
            phases.push(before.map_or(Some(Phase::Accelerate), |b| Phase::of(b, speed)));
            before = Some(speed);
        }
        phases
    };
    let stepgen_phases = {
        let mut stepgen = common::peers::stepgen();
        delays(Box::new(move || {
            stepgen.next().filter(|&delay| delay != 0).map(i64::from)
        }))
    };
    let ramp_maker_phases = {
        let mut profile = common::peers::ramp_maker_steps();
        delays(Box::new(move || {
            profile.next_delay().map(|d| d.to_bits() as i64)
        }))
    };
    for (phase, label) in PHASES {
        let (first, length) = window(stepgen_phases.iter().copied(), phase, WINDOW);
        time_windows(
            &mut group,
            &format!("stepgen/{label}"),
            length,
            || {
                let mut stepgen = common::peers::stepgen();
                for _ in 0..first {
                    stepgen.next();
                }
                stepgen
            },
            |stepgen| i64::from(stepgen.next().unwrap_or(0)),
        );
        let (first, length) = window(ramp_maker_phases.iter().copied(), phase, WINDOW);
        time_windows(
            &mut group,
            &format!("ramp-maker/{label}"),
            length,
            || {
                let mut profile = common::peers::ramp_maker_steps();
                for _ in 0..first {
                    profile.next_delay();
                }
                profile
            },
            |profile| profile.next_delay().map_or(0, |d| d.to_bits() as i64),
        );
    }
    group.finish();
}

fn peers_per_cycle(c: &mut Criterion) {
    let mut group = c.benchmark_group("peers: plan");
    let input = common::peers::ruckig_input();
    group.bench_function("rsruckig/calculate", |b| {
        b.iter(|| common::peers::ruckig_plan(black_box(&input)))
    });
    group.bench_function("s_curve/plan", |b| {
        let input = common::peers::s_curve_input();
        b.iter(|| s_curve::s_curve_generator(black_box(&input), s_curve::Derivative::Position).0)
    });
    group.finish();

    let mut group = c.benchmark_group("peers: per cycle");
    time_windows(
        &mut group,
        "rsruckig/update",
        WINDOW,
        || {
            // One cycle first: the first update plans the whole trajectory.
            let (mut otg, mut input) = (common::peers::ruckig(), common::peers::ruckig_input());
            let mut output = rsruckig::prelude::OutputParameter::new(None);
            otg.update(&input, &mut output).unwrap();
            output.pass_to_input(&mut input);
            (otg, input, output)
        },
        |(otg, input, output)| {
            otg.update(input, output).unwrap();
            output.pass_to_input(input);
            output.new_position[0].to_bits() as i64
        },
    );
    let (_, evaluate) = s_curve::s_curve_generator(
        &common::peers::s_curve_input(),
        s_curve::Derivative::Position,
    );
    time_windows(
        &mut group,
        "s_curve/evaluate",
        WINDOW,
        || 0u64,
        |cycle| {
            *cycle += 1;
            evaluate(black_box(*cycle as f64)).to_bits() as i64
        },
    );
    group.finish();
}

criterion_group!(
    benches,
    cycle_cost,
    line_cost,
    circle_cost,
    setup_cost,
    microstep,
    peers_per_step,
    peers_per_cycle
);
criterion_main!(benches);
