//! The x86 instruction counts of one cycle, by phase: each run of this program steps one
//! generator through one window of cycles that all lie in one phase of the bench move
//! (`benches/common`), calling `step` through `&mut dyn ProfileGenerator` so that callgrind can
//! count the instructions inside it. `tools/instruction_counts.sh` runs every window under
//! callgrind and prints the table (x86 and Cortex-M4).
//!
//! `cargo run --release -p profilegen-benches --example step_instructions -- --list` lists the
//! windows; `… -- WINDOW` steps one (the generator is advanced to the window's first cycle outside
//! the counted function, `measure`).

#[path = "../common/mod.rs"]
mod common;

use std::hint::black_box;

use profilegen::{ProfileGenerator, State};

/// What a cycle did to the speed.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
enum Phase {
    SpeedUp,
    Steady,
    SlowDown,
}

fn phase_of(before: State, after: State) -> Phase {
    let (a, b) = (
        before.velocity.unsigned_abs(),
        after.velocity.unsigned_abs(),
    );
    match b.cmp(&a) {
        std::cmp::Ordering::Greater => Phase::SpeedUp,
        std::cmp::Ordering::Equal => Phase::Steady,
        std::cmp::Ordering::Less => Phase::SlowDown,
    }
}

/// The first and last cycle (1-based) of the longest stretch of moving cycles in `phase`, at
/// most `limit` cycles long, of a copy of `generator` stepped to completion (or 200,000 cycles).
fn window<G: ProfileGenerator + Clone>(generator: &G, phase: Phase, limit: u64) -> (u64, u64) {
    let mut copy = generator.clone();
    let mut before = copy.state();
    let (mut best, mut start, mut stepped) = ((0, 0), None, 0);
    for cycle in 1..=200_000u64 {
        stepped = cycle;
        let after = copy.step();
        let inside = phase_of(before, after) == phase && after.velocity != 0;
        match (inside, start) {
            (true, None) => start = Some(cycle),
            (false, Some(first)) => {
                if cycle - first > best.1 - best.0 {
                    best = (first, cycle - 1);
                }
                start = None;
            }
            _ => {}
        }
        before = after;
        if copy.is_complete() {
            break;
        }
    }
    if let Some(first) = start {
        if stepped - first > best.1 - best.0 {
            best = (first, stepped);
        }
    }
    (best.0, best.1.min(best.0 + limit - 1))
}

/// The counted function: `cycles` steps through the trait object.
#[inline(never)]
fn measure(generator: &mut dyn ProfileGenerator, cycles: u64) {
    for _ in 0..cycles {
        black_box(generator.step());
    }
}

fn run<G: ProfileGenerator + Clone>(generator: G, phase: Phase, list: Option<&str>) {
    let (first, last) = window(&generator, phase, 1_000);
    if let Some(name) = list {
        println!("{name} {first} {last}");
        return;
    }
    let mut axis = common::advanced(&generator, first - 1);
    measure(&mut axis, last - first + 1);
}

/// Lists (with its name) or steps one window.
type Window = Box<dyn Fn(Option<&str>)>;

fn main() {
    let arguments: Vec<String> = std::env::args().skip(1).collect();
    // No argument: the list too (what `.ci/run` runs).
    let list = matches!(arguments.first().map(String::as_str), None | Some("--list"));
    let windows: [(&str, Window); 17] = [
        (
            "velocity/ramp",
            Box::new(|l| run(common::velocity(), Phase::SpeedUp, l)),
        ),
        (
            "velocity/cruise",
            Box::new(|l| {
                run(
                    common::advanced(&common::velocity(), 1_000),
                    Phase::Steady,
                    l,
                )
            }),
        ),
        (
            "trapezoidal/accelerate",
            Box::new(|l| run(common::trapezoidal(), Phase::SpeedUp, l)),
        ),
        (
            "trapezoidal/cruise",
            Box::new(|l| run(common::trapezoidal(), Phase::Steady, l)),
        ),
        (
            "trapezoidal/decelerate",
            Box::new(|l| run(common::trapezoidal(), Phase::SlowDown, l)),
        ),
        (
            "scurve/speed-up",
            Box::new(|l| run(common::scurve(), Phase::SpeedUp, l)),
        ),
        (
            "scurve/cruise",
            Box::new(|l| run(common::scurve(), Phase::Steady, l)),
        ),
        (
            "scurve/slow-down",
            Box::new(|l| run(common::scurve(), Phase::SlowDown, l)),
        ),
        (
            "mcx514/speed-up",
            Box::new(|l| run(common::manual_line_mcx514(), Phase::SpeedUp, l)),
        ),
        (
            "mcx514/cruise",
            Box::new(|l| run(common::manual_line_mcx514(), Phase::Steady, l)),
        ),
        (
            "mcx514/slow-down",
            Box::new(|l| run(common::manual_line_mcx514(), Phase::SlowDown, l)),
        ),
        (
            "mcx514_scurve/speed-up",
            Box::new(|l| run(common::manual_line_mcx514_scurve(), Phase::SpeedUp, l)),
        ),
        (
            "mcx514_scurve/cruise",
            Box::new(|l| run(common::manual_line_mcx514_scurve(), Phase::Steady, l)),
        ),
        (
            "mcx514_scurve/slow-down",
            Box::new(|l| run(common::manual_line_mcx514_scurve(), Phase::SlowDown, l)),
        ),
        (
            "gearing/follow",
            Box::new(|l| {
                if let Some(name) = l {
                    println!("{name} 1 1000");
                    return;
                }
                follow(&mut common::gear(), 0);
            }),
        ),
        (
            "gearing/stopping",
            Box::new(|l| {
                if let Some(name) = l {
                    println!("{name} 1 1000");
                    return;
                }
                // Engaged at 150 counts/cycle, then a smooth stop: it slows down at 0.25
                // counts/cycle² for 600 cycles and rests for the rest of the window.
                let mut gear = common::gear();
                for cycle in 1..=100 {
                    gear.follow(cycle * 100);
                }
                gear.stop(profilegen::StopKind::Smooth);
                follow(&mut gear, 100 * 100);
            }),
        ),
        (
            "microstep/outputs",
            Box::new(|l| {
                if let Some(name) = l {
                    println!("{name} 1 1000");
                    return;
                }
                let table = common::microstep_table();
                outputs(&table);
            }),
        ),
    ];
    for (name, window) in &windows {
        if list {
            window(Some(name));
        } else if arguments.first().map(String::as_str) == Some(*name) {
            window(None);
            return;
        }
    }
    if !list {
        eprintln!("usage: step_instructions --list | WINDOW");
        std::process::exit(2);
    }
}

/// 1,000 lookups, 7 microsteps apart (every residue of the 3-phase cycle's phases comes up).
#[inline(never)]
fn outputs(table: &profilegen::waveform::MicrostepTable) {
    for position in 0..1_000i32 {
        black_box(table.outputs(black_box(position * 7 - 3_000)));
    }
}

/// 1,000 cycles of the gear behind a master that counts 100 a cycle from `master`: its `follow`
/// called through a function pointer, so it stays a function of its own to count.
#[inline(never)]
fn follow(gear: &mut profilegen::gearing::ElectronicGear, master: i32) {
    let follow: fn(&mut profilegen::gearing::ElectronicGear, i32) -> profilegen::State =
        black_box(profilegen::gearing::ElectronicGear::follow);
    for cycle in 1..=1_000i32 {
        black_box(follow(gear, black_box(master + cycle * 100)));
    }
}
