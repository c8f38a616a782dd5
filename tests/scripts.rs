//! Scripted property tests (issue #17): random command scripts for every generator, checked on
//! every cycle (see `tests/script/mod.rs` for the checks). Each script is a proptest value, so a
//! failure shrinks to a minimal script.
//!
//! The default run (CI, `PROPTEST_RNG_SEED` fixed by `.ci/run`) runs 100,000 scripts in all;
//! `PROFILEGEN_SCRIPT_SCALE` multiplies every test's count and `PROFILEGEN_SCRIPT_CYCLES` sets
//! the cycles one script may step (default 4,000). Millions, with a random seed:
//!
//! ```text
//! PROFILEGEN_SCRIPT_SCALE=30 cargo test --test scripts -- --nocapture
//! ```

mod script;

use proptest::prelude::*;
use proptest::test_runner::{Config, TestRunner};

/// Runs `cases` (times the scale) scripts of `strategy` with `run`, and prints the totals.
fn scripts<S: Strategy>(
    name: &str,
    cases: u32,
    strategy: S,
    run: impl Fn(&S::Value) -> Result<u64, String>,
) where
    S::Value: core::fmt::Debug,
{
    let scale: f64 = std::env::var("PROFILEGEN_SCRIPT_SCALE")
        .ok()
        .and_then(|text| text.parse().ok())
        .unwrap_or(1.0);
    let cases = (f64::from(cases) * scale).round() as u32;
    let config = Config {
        cases,
        // Shrinking walks a script down to the fewest, smallest steps; let it finish.
        max_shrink_iters: 100_000,
        // The seed reproduces a failure (CI fixes it); a found bug becomes a named regression test.
        failure_persistence: None,
        ..Config::default()
    };
    let before = script::totals();
    let started = std::time::Instant::now();
    let mut runner = TestRunner::new(config);
    let result = runner.run(&strategy, |value| {
        run(&value).map(drop).map_err(TestCaseError::fail)
    });
    println!(
        "{name}: {} scripts, {} cycles, {} known shortfalls held to a weaker bound, in {:.1} s",
        script::totals().scripts - before.scripts,
        script::totals().cycles - before.cycles,
        script::totals().excluded - before.excluded,
        started.elapsed().as_secs_f64(),
    );
    if let Err(error) = result {
        panic!("{name}: {error}");
    }
}

#[test]
fn scripted_velocity() {
    let budget = script::cycle_budget();
    scripts("velocity", 22_000, script::velocity::script(), |s| {
        s.run(budget)
    });
}

#[test]
fn scripted_trapezoidal() {
    let budget = script::cycle_budget();
    scripts("trapezoidal", 30_000, script::trapezoidal::script(), |s| {
        s.run(budget)
    });
}

#[test]
fn scripted_scurve() {
    let budget = script::cycle_budget();
    scripts("scurve", 30_000, script::scurve::script(), |s| {
        s.run(budget)
    });
}

#[test]
fn scripted_mcx514() {
    let budget = script::cycle_budget();
    scripts("mcx514", 18_000, script::mcx514::script(), |s| {
        s.run(budget)
    });
}

#[test]
fn scripted_linear_interpolation() {
    let budget = script::cycle_budget();
    scripts(
        "linear interpolation",
        12_000,
        script::interpolation::script(),
        |s| s.run(budget),
    );
}

#[test]
fn scripted_microstep() {
    let budget = script::cycle_budget();
    scripts("microstep", 6_000, script::microstep::script(), |s| {
        s.run(budget)
    });
}

#[test]
fn scripted_mcx514_scurve() {
    let budget = script::cycle_budget();
    scripts(
        "mcx514 S-curve",
        12_000,
        script::mcx514_scurve::script(),
        |s| s.run(budget),
    );
}

#[test]
fn scripted_gearing() {
    let budget = script::cycle_budget();
    scripts(
        "gearing",
        8_000,
        script::gearing::script(script::trapezoidal::script()),
        |s| s.run(budget),
    );
}

#[test]
fn scripted_gearing_to_velocity_contouring() {
    let budget = script::cycle_budget();
    scripts(
        "gearing to velocity contouring",
        3_000,
        script::gearing::script(script::velocity::script()),
        |s| s.run(budget),
    );
}

#[test]
fn scripted_gearing_to_scurve() {
    let budget = script::cycle_budget();
    scripts(
        "gearing to the S-curve",
        3_000,
        script::gearing::script(script::scurve::script()),
        |s| s.run(budget),
    );
}

#[test]
fn scripted_encoder_gearing() {
    let budget = script::cycle_budget();
    scripts(
        "encoder gearing",
        8_000,
        script::encoder_gearing::script(),
        |s| s.run(budget),
    );
}

#[test]
fn scripted_circular_interpolation() {
    let budget = script::cycle_budget();
    scripts(
        "circular interpolation",
        8_000,
        script::circular::script(),
        |s| s.run(budget),
    );
}

#[test]
fn scripted_continuous_interpolation() {
    let budget = script::cycle_budget();
    scripts(
        "continuous interpolation",
        6_000,
        script::continuous::script(),
        |s| s.run(budget),
    );
}
