//! The cost of planning an S-curve move (`SCurve::new`) over many random moves across the whole
//! MC1451A register ranges (`common/moves.rs`), with the peers (s_curve, rsruckig) planning the
//! same moves in floating point, and the planned durations against the continuous optimum.
//!
//! ```text
//! cargo bench -p profilegen-benches --bench planning               # 100,000 moves
//! cargo bench -p profilegen-benches --bench planning -- --quick    # 10,000 moves
//! cargo bench -p profilegen-benches --bench planning -- 250000     # any number
//! PLANNING_MOVES=250000 cargo bench -p profilegen-benches --bench planning
//! ```
//!
//! Each move is timed with `std::time::Instant` as the minimum of `REPETITIONS` runs in each of
//! `SWEEPS` sweeps over all the moves (to reject interrupts, preemption and a neighbour's load on
//! this shared machine), less the timer's own cost (the same measurement of an empty
//! region, reported as the floor). Every generator is timed on every move, failed or not; the
//! peers' failures (no plan, a plan that misses the destination or breaks a limit) are counted.
//! A plain `main` (harness = false) that prints tables; unknown arguments (`--bench`, filters) are
//! ignored.

#[allow(dead_code)] // the bench takes only `scurve_move` and `scurve_parameters`
#[path = "common/moves.rs"]
mod moves;

use std::collections::BTreeMap;
use std::hint::black_box;
use std::time::{Duration, Instant};

use profilegen::reference::scurve_duration;
use profilegen::{SCurve, ScurveParameters};
use rsruckig::prelude::*;

/// Moves measured by default, with `--quick`, and the names of the override.
const DEFAULT_MOVES: u64 = 100_000;
const QUICK_MOVES: u64 = 10_000;
const MOVES_VARIABLE: &str = "PLANNING_MOVES";
/// Runs per move in each sweep; the minimum over all runs of all sweeps is kept.
const REPETITIONS: usize = 3;
/// Sweeps over all the moves, one generator after the other. One generator's sweep lasts a
/// fraction of a second, and this machine is shared: a neighbour's load that slows one sweep
/// seldom lasts through all of them, so the minimum over the sweeps is the code's cost rather
/// than the neighbour's (with one sweep the median moved by ±20 % between runs).
const SWEEPS: usize = 10;
/// Moves planned (untimed) before measuring, per generator.
const WARM_UP: u64 = 1_000;
/// The planner's bounds on `plan().total` − continuous optimum (cycles): worst and mean.
const WORST_OVER_OPTIMUM: f64 = 3.0;
const MEAN_OVER_OPTIMUM: f64 = 1.2;

/// One move: its raw register bits and the same move in floats (counts, counts/cycle, …).
#[derive(Debug, Clone, Copy)]
struct Move {
    index: u64,
    raw: (i32, u32, u16, u32),
    parameters: ScurveParameters,
    distance: f64,
    velocity: f64,
    acceleration: f64,
    jerk: f64,
}

impl Move {
    fn new(index: u64) -> Self {
        let raw = moves::scurve_move(index);
        let parameters = moves::scurve_parameters(index);
        Self {
            index,
            raw,
            parameters,
            distance: f64::from(parameters.destination),
            velocity: parameters.max_velocity.to_f64(),
            acceleration: parameters.max_acceleration.to_f64(),
            jerk: parameters.jerk.to_f64(),
        }
    }

    fn describe(&self) -> String {
        let (d, v, a, j) = self.raw;
        format!(
            "move #{}: destination {d}, velocity {v} (= {:.6} counts/cycle), acceleration {a} \
             (= {:.6e} counts/cycle²), jerk {j} (= {:.6e} counts/cycle³)",
            self.index, self.velocity, self.acceleration, self.jerk
        )
    }
}

/// The minimum over `REPETITIONS` runs of `f`, in ns.
fn time<R>(mut f: impl FnMut() -> R) -> u64 {
    let mut best = Duration::MAX;
    for _ in 0..REPETITIONS {
        let start = Instant::now();
        // The result is kept where `f` returned it and only its address escapes: a move of it
        // into `black_box` would add a copy (of a generator, about a kilobyte) that a caller
        // of `SCurve::new` does not pay, as its result lands in the caller's own variable.
        let result = f();
        black_box(&result);
        best = best.min(start.elapsed());
    }
    best.as_nanos() as u64
}

/// Nearest-rank percentile of sorted `values`.
fn percentile(sorted: &[u64], fraction: f64) -> u64 {
    let rank = (fraction * sorted.len() as f64).ceil() as usize;
    sorted[rank.clamp(1, sorted.len()) - 1]
}

/// Timings of one generator, with the move each came from.
struct Timings {
    name: &'static str,
    ns: Vec<u64>,
    failures: BTreeMap<String, u64>,
}

impl Timings {
    fn new(name: &'static str, capacity: usize) -> Self {
        Self {
            name,
            ns: vec![u64::MAX; capacity],
            failures: BTreeMap::new(),
        }
    }

    fn fail(&mut self, reason: impl Into<String>) {
        *self.failures.entry(reason.into()).or_default() += 1;
    }

    fn failed(&self) -> u64 {
        self.failures.values().sum()
    }

    fn sorted(&self) -> Vec<u64> {
        let mut sorted = self.ns.clone();
        sorted.sort_unstable();
        sorted
    }

    fn median(&self) -> u64 {
        percentile(&self.sorted(), 0.5)
    }

    /// The index (in the run) of the slowest move.
    fn worst(&self) -> usize {
        (0..self.ns.len()).max_by_key(|&i| self.ns[i]).unwrap()
    }
}

/// The continuous optimal duration of `m`, cycles.
/// The same registers from a fractional position: after a stop an axis rests between counts, so
/// a move's distance is any number of raw units (2^-32 counts), not a whole number of counts as
/// from 0. The distance in raw units is log-uniform over 1 … 2^62 (its own stream per move), the
/// destination the move's own. Durations only (not timed): counted against the same bound. With
/// `PLANNING_LIST_OVER` set in the environment, every move over the bound is listed.
fn fractional_starts(moves: &[Move]) {
    let mut over = Vec::with_capacity(moves.len());
    let mut refused = 0;
    let mut worst: Option<(f64, String)> = None;
    for m in moves {
        let mut random = moves::SplitMix64::for_move(m.index ^ 0xF4AC_7105);
        let magnitude = random.log_uniform(62) as i64;
        let distance = if random.next_u64() >> 63 == 1 {
            -magnitude
        } else {
            magnitude
        };
        let target = i64::from(m.raw.0) << 32;
        let start = fixed::types::I32F32::from_bits(target.wrapping_sub(distance));
        let Ok(axis) = SCurve::with_position(m.parameters, start) else {
            refused += 1; // one raw unit with a jerk of one raw unit: unreachable, by design
            continue;
        };
        let counts = magnitude as f64 / 4_294_967_296.0;
        let optimum = scurve_duration(counts, m.velocity, m.acceleration, m.jerk).max(1.0);
        let excess = axis.duration() as f64 - optimum;
        if excess > WORST_OVER_OPTIMUM && std::env::var_os("PLANNING_LIST_OVER").is_some() {
            println!(
                "over ({excess:+.1}; {} cycles, optimum {optimum:.2}): {}, from {} raw units away",
                axis.duration(),
                m.describe(),
                distance
            );
        }
        if worst.as_ref().is_none_or(|(w, _)| excess > *w) {
            worst = Some((
                excess,
                format!("{}, from {} raw units away", m.describe(), distance),
            ));
        }
        over.push(excess);
    }
    let beyond = over.iter().filter(|&&x| x > WORST_OVER_OPTIMUM).count();
    let far = over.iter().filter(|&&x| x > 100.0).count();
    println!();
    println!(
        "From fractional positions ({} moves, distance log-uniform in raw units; {refused} refused as \
         unreachable): {beyond} over optimum + {WORST_OVER_OPTIMUM} ({far} by more than 100 cycles); \
         {}",
        over.len(),
        if beyond == 0 { "PASS" } else { "FAIL (issue #11)" },
    );
    if let Some((excess, move_)) = worst {
        println!("farthest over the optimum ({excess:+.1} cycles): {move_}");
    }
}

fn optimum(m: &Move) -> f64 {
    scurve_duration(m.distance.abs(), m.velocity, m.acceleration, m.jerk)
}

/// The s_curve crate's input for `m` (time unit = one cycle).
fn s_curve_input(m: &Move) -> s_curve::SCurveInput {
    s_curve::SCurveInput {
        constraints: s_curve::SCurveConstraints {
            max_jerk: m.jerk,
            max_acceleration: m.acceleration,
            max_velocity: m.velocity,
        },
        start_conditions: s_curve::SCurveStartConditions {
            q0: 0.0,
            q1: m.distance,
            v0: 0.0,
            v1: 0.0,
        },
    }
}

/// Whether a floating-point plan of `m` ending at `end` (position at its duration) after
/// `duration` cycles is a plan: finite, positive, at the destination (to half a count, or 1e-9 of
/// the distance). `None` if it is, else why not.
fn check_end(m: &Move, duration: f64, end: f64) -> Option<&'static str> {
    if !duration.is_finite() || duration <= 0.0 {
        return Some("no plan (non-finite or non-positive duration)");
    }
    if !end.is_finite() || (end - m.distance).abs() > 0.5_f64.max(1e-9 * m.distance.abs()) {
        return Some("misses the destination");
    }
    None
}

/// Relative slack allowed on the peers' limits (floating-point rounding).
const LIMIT_SLACK: f64 = 1.0 + 1e-6;

/// Sets rsruckig's input to `m` (time unit = one cycle).
fn set_input(input: &mut InputParameter<1>, m: &Move) {
    input.current_position[0] = 0.0;
    input.target_position[0] = m.distance;
    input.max_velocity[0] = m.velocity;
    input.max_acceleration[0] = m.acceleration;
    input.max_jerk[0] = m.jerk;
}

/// Silences panic messages from peers (a panic is counted as a failure).
fn quiet_panics() {
    std::panic::set_hook(Box::new(|_| {}));
}

fn moves_requested() -> u64 {
    let mut moves = std::env::var(MOVES_VARIABLE)
        .ok()
        .and_then(|value| value.replace(['_', ','], "").parse().ok())
        .unwrap_or(DEFAULT_MOVES);
    for argument in std::env::args().skip(1) {
        if argument == "--quick" {
            moves = QUICK_MOVES;
        } else if let Ok(n) = argument.replace(['_', ','], "").parse::<u64>() {
            moves = n;
        } else if let Some(n) = argument
            .strip_prefix("--moves=")
            .and_then(|n| n.replace(['_', ','], "").parse().ok())
        {
            moves = n;
        }
        // Anything else (`--bench`, a filter) is cargo's or criterion's: ignored.
    }
    moves.max(1)
}

/// One row of the planning-cost table; `reference` is profilegen's median, for the ratio.
fn print_distribution(timings: &Timings, reference: Option<u64>) {
    let sorted = timings.sorted();
    let ratio = match reference {
        Some(ours) => format!(
            "{:.2}",
            ours as f64 / percentile(&sorted, 0.5).max(1) as f64
        ),
        None => "—".to_owned(),
    };
    // The mean as well: the clock's steps are about 10 ns, which the percentiles keep and the
    // mean averages out (it tells two builds apart where their medians are one step apart).
    let mean = sorted.iter().sum::<u64>() as f64 / sorted.len() as f64;
    println!(
        "| {:<28} | {:>9} | {:>9} | {:>9} | {:>9} | {:>10} | {:>7.1} | {:>7} | {:>16} |",
        timings.name,
        percentile(&sorted, 0.5),
        percentile(&sorted, 0.9),
        percentile(&sorted, 0.99),
        percentile(&sorted, 0.999),
        sorted[sorted.len() - 1],
        mean,
        timings.failed(),
        ratio,
    );
}

fn main() {
    let started = Instant::now();
    let count = moves_requested();
    println!(
        "S-curve planning over {count} random moves (benches/common/moves.rs), each timed as the \
         minimum of {REPETITIONS} runs in each of {SWEEPS} sweeps"
    );
    let moves: Vec<Move> = (0..count).map(Move::new).collect();

    // The timer's own cost, measured the same way on an empty region; subtracted from every move.
    let mut empty: Vec<u64> = (0..10_000).map(|_| time(|| ())).collect();
    empty.sort_unstable();
    let floor = percentile(&empty, 0.5);
    let net = |ns: u64| ns.saturating_sub(floor);

    // profilegen: its durations against the continuous optimum (untimed).
    let mut ours = Timings::new("profilegen SCurve::new", moves.len());
    let mut over = Vec::with_capacity(moves.len());
    for m in &moves {
        match SCurve::new(m.parameters) {
            Ok(axis) => over.push(axis.plan().total as f64 - optimum(m)),
            Err(error) => {
                ours.fail(format!("error: {error}"));
                over.push(f64::NAN);
            }
        }
    }

    // s_curve: each plan checked (untimed).
    quiet_panics();
    let s_curve_inputs: Vec<s_curve::SCurveInput> = moves.iter().map(s_curve_input).collect();
    let mut s_curve_timings = Timings::new("s_curve s_curve_generator", moves.len());
    let mut s_curve_over = Vec::new();
    for (m, input) in moves.iter().zip(&s_curve_inputs) {
        let Ok((plan, position)) = std::panic::catch_unwind(|| {
            s_curve::s_curve_generator(input, s_curve::Derivative::Position)
        }) else {
            s_curve_timings.fail("panic");
            continue;
        };
        let duration = plan.time_intervals.total_duration();
        if let Some(reason) = check_end(m, duration, position(duration)) {
            s_curve_timings.fail(reason);
        } else if plan.v_lim.abs() > m.velocity * LIMIT_SLACK
            || plan.a_lim_a.abs().max(plan.a_lim_d.abs()) > m.acceleration * LIMIT_SLACK
        {
            s_curve_timings.fail("exceeds the velocity or acceleration limit");
        } else {
            s_curve_over.push(duration - optimum(m));
        }
    }

    // rsruckig: `calculate` into a reused trajectory, each end position checked (untimed).
    let mut otg = Ruckig::<1, ThrowErrorHandler>::new(None, 1.0);
    let mut trajectory = Trajectory::new(None);
    let mut input = InputParameter::<1>::new(None);
    let mut ruckig_timings = Timings::new("rsruckig Ruckig::calculate", moves.len());
    let mut ruckig_over = Vec::new();
    for m in &moves {
        set_input(&mut input, m);
        let result = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
            otg.calculate(&input, &mut trajectory)
        }));
        match result {
            Err(_) => ruckig_timings.fail("panic"),
            Ok(Err(RuckigError::ValidationError(_))) => ruckig_timings.fail("validation error"),
            Ok(Err(RuckigError::CalculatorError(_))) => ruckig_timings.fail("calculator error"),
            Ok(Ok(RuckigResult::Working)) => {
                let duration = trajectory.get_duration();
                let mut end = DataArrayOrVec::<f64, 1>::new(None, f64::NAN);
                if duration.is_finite() {
                    trajectory.at_time(
                        duration,
                        &mut Some(&mut end),
                        &mut None,
                        &mut None,
                        &mut None,
                        &mut None,
                    );
                }
                if let Some(reason) = check_end(m, duration, end[0]) {
                    ruckig_timings.fail(reason);
                } else {
                    ruckig_over.push(duration - optimum(m));
                }
            }
            Ok(Ok(other)) => ruckig_timings.fail(format!("result {other:?}")),
        }
    }

    // The timed sweeps: every generator over every move, SWEEPS times in turn, each move's
    // time the least of all its runs (failed or not).
    let (mut ours_time, mut s_curve_time, mut ruckig_time) =
        (Duration::ZERO, Duration::ZERO, Duration::ZERO);
    for _ in 0..SWEEPS {
        for m in moves.iter().take(WARM_UP as usize) {
            black_box(SCurve::new(m.parameters).unwrap());
        }
        let phase = Instant::now();
        for (best, m) in ours.ns.iter_mut().zip(&moves) {
            *best = (*best).min(net(time(|| SCurve::new(black_box(m.parameters)))));
        }
        ours_time += phase.elapsed();

        for input in s_curve_inputs.iter().take(WARM_UP as usize) {
            let _ = std::panic::catch_unwind(|| {
                black_box(s_curve::s_curve_generator(input, s_curve::Derivative::Position).0)
            });
        }
        let phase = Instant::now();
        for (best, input) in s_curve_timings.ns.iter_mut().zip(&s_curve_inputs) {
            let ns = net(time(|| {
                std::panic::catch_unwind(|| {
                    s_curve::s_curve_generator(black_box(input), s_curve::Derivative::Position).0
                })
                .is_ok()
            }));
            *best = (*best).min(ns);
        }
        s_curve_time += phase.elapsed();

        for m in moves.iter().take(WARM_UP as usize) {
            set_input(&mut input, m);
            let _ = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
                black_box(otg.calculate(&input, &mut trajectory).is_ok())
            }));
        }
        let phase = Instant::now();
        for (best, m) in ruckig_timings.ns.iter_mut().zip(&moves) {
            set_input(&mut input, m);
            let ns = net(time(|| {
                std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
                    otg.calculate(black_box(&input), &mut trajectory)
                }))
                .is_ok()
            }));
            *best = (*best).min(ns);
        }
        ruckig_time += phase.elapsed();
    }
    let _ = std::panic::take_hook();

    // Planning cost.
    println!();
    println!("Planning cost, ns per move (timer floor {floor} ns subtracted):");
    println!();
    println!(
        "| {:<28} | {:>9} | {:>9} | {:>9} | {:>9} | {:>10} | {:>7} | {:>7} | {:>16} |",
        "planner", "p50", "p90", "p99", "p99.9", "worst", "mean", "failed", "p50 ours / peer"
    );
    println!(
        "|{:-<30}|{:->10}:|{:->10}:|{:->10}:|{:->10}:|{:->11}:|{:->8}:|{:->8}:|{:->17}:|",
        "", "", "", "", "", "", "", "", ""
    );
    let our_median = ours.median();
    print_distribution(&ours, None);
    print_distribution(&s_curve_timings, Some(our_median));
    print_distribution(&ruckig_timings, Some(our_median));
    println!();
    for timings in [&ours, &s_curve_timings, &ruckig_timings] {
        let worst = timings.worst();
        println!(
            "slowest for {} ({} ns): {}",
            timings.name,
            timings.ns[worst],
            moves[worst].describe()
        );
    }
    for timings in [&ours, &s_curve_timings, &ruckig_timings] {
        for (reason, n) in &timings.failures {
            println!(
                "{} failed on {n} of {} moves ({:.2} %): {reason}",
                timings.name,
                moves.len(),
                100.0 * *n as f64 / moves.len() as f64
            );
        }
    }

    // Durations against the continuous optimum.
    println!();
    println!("Duration − continuous optimum (reference::scurve_duration), cycles:");
    println!();
    println!(
        "| {:<28} | {:>8} | {:>8} | {:>8} | {:>8} | {:>8} | {:>9} |",
        "planner", "moves", "mean", "p50", "p99", "worst", "> +3"
    );
    println!(
        "|{:-<30}|{:->9}:|{:->9}:|{:->9}:|{:->9}:|{:->9}:|{:->10}:|",
        "", "", "", "", "", "", ""
    );
    let summary = |name: &str, over: &[f64]| -> (f64, f64) {
        let mut sorted: Vec<f64> = over.iter().copied().filter(|x| !x.is_nan()).collect();
        sorted.sort_by(f64::total_cmp);
        let n = sorted.len().max(1);
        let at = |fraction: f64| sorted[((fraction * n as f64).ceil() as usize).clamp(1, n) - 1];
        let mean = sorted.iter().sum::<f64>() / n as f64;
        let worst = sorted.last().copied().unwrap_or(f64::NAN);
        println!(
            "| {:<28} | {:>8} | {:>+8.3} | {:>+8.3} | {:>+8.3} | {:>+8.3} | {:>9} |",
            name,
            sorted.len(),
            mean,
            at(0.5),
            at(0.99),
            worst,
            sorted.iter().filter(|&&x| x > WORST_OVER_OPTIMUM).count(),
        );
        (mean, worst)
    };
    let (mean, worst) = summary("profilegen plan().total", &over);
    summary("s_curve (continuous)", &s_curve_over);
    summary("rsruckig (continuous)", &ruckig_over);
    println!();
    let worst_move = (0..over.len())
        .filter(|&i| !over[i].is_nan())
        .max_by(|&a, &b| over[a].total_cmp(&over[b]));
    if let Some(i) = worst_move {
        println!(
            "farthest over the optimum ({:+.3} cycles): {}",
            over[i],
            moves[i].describe()
        );
    }
    let verdict = |ok: bool| if ok { "PASS" } else { "FAIL" };
    println!(
        "bound: worst ≤ optimum + {WORST_OVER_OPTIMUM}: {} (worst {worst:+.3}); mean ≤ +{MEAN_OVER_OPTIMUM}: {} (mean {mean:+.3})",
        verdict(worst <= WORST_OVER_OPTIMUM),
        verdict(mean <= MEAN_OVER_OPTIMUM),
    );

    fractional_starts(&moves);

    println!();
    println!(
        "run time: {:.1} s (timed: profilegen {:.1} s, s_curve {:.1} s, rsruckig {:.1} s; \
         {REPETITIONS} runs per move in each of {SWEEPS} sweeps)",
        started.elapsed().as_secs_f64(),
        ours_time.as_secs_f64(),
        s_curve_time.as_secs_f64(),
        ruckig_time.as_secs_f64(),
    );
}
