//! Plots a run of `profile_table` (same modes and options, SPEC §13) as an SVG: position,
//! velocity and acceleration against time in three aligned panels, cycles below and seconds on
//! top (Juno 102.4 µs for velocity and trapezoidal, MC1451A 330 µs for S-curve), and the S-curve's
//! phase boundaries marked.
//!
//! ```text
//! cargo run --release --example plot -- scurve --destination 2000 --velocity 2.75 \
//!     --acceleration 0.175 --jerk 0.0075 --output scurve.svg
//! ```

use std::process::ExitCode;

mod cli;

use cli::{build, check_event, parse_args, simulate, Mode, Options};
use plotters::prelude::*;
use profilegen::format::mc1451a::{Destination, Jerk, MaxVelocity, ScurveAcceleration};
use profilegen::format::CycleTime;
use profilegen::{SCurve, ScurveParameters, State};

/// Points per series at most: longer runs are thinned evenly (the last point always kept).
const MAX_POINTS: usize = 4_000;

fn main() -> ExitCode {
    match plot() {
        Ok(()) => ExitCode::SUCCESS,
        Err(message) => {
            eprintln!("error: {message}");
            ExitCode::from(2)
        }
    }
}

fn plot() -> Result<(), String> {
    let options = parse_args(true)?;
    let output = options
        .output
        .clone()
        .ok_or("--output: missing (FILE.svg)")?;
    let mut axis = build(&options)?;
    for &(_, command) in &options.events {
        check_event(&options, command)?;
    }
    let mut states: Vec<(u64, State)> = Vec::new();
    simulate(&options, axis.as_mut(), |cycle, state| {
        states.push((cycle, *state));
        Ok(())
    })
    .map_err(|e| e.to_string())?;
    let stride = states.len().div_ceil(MAX_POINTS).max(1);
    let last = *states.last().expect("row 0 is always there");
    let mut points: Vec<(u64, State)> = states.into_iter().step_by(stride).collect();
    if points.last() != Some(&last) {
        points.push(last);
    }
    let (cycle_time, chip) = match options.mode {
        Mode::Scurve => (CycleTime::MC1451A, "MC1451A, 330 µs"),
        _ => (CycleTime::JUNO, "Juno, 102.4 µs"),
    };
    draw(
        &output,
        &points,
        &phase_boundaries(&options),
        cycle_time,
        chip,
    )
    .map_err(|e| format!("--output: {e}"))
}

/// The S-curve plan's phase boundaries (cumulative cycles), for marking.
fn phase_boundaries(options: &Options) -> Vec<u64> {
    if options.mode != Mode::Scurve {
        return Vec::new();
    }
    let parameters = (|| {
        Some(ScurveParameters {
            destination: Destination::from_num(options.destination?).ok()?,
            max_velocity: MaxVelocity::from_num(options.velocity?).ok()?,
            max_acceleration: ScurveAcceleration::from_num(options.acceleration?).ok()?,
            jerk: Jerk::from_num(options.jerk?).ok()?,
        })
    })();
    let Some(plan) = parameters
        .and_then(|p| SCurve::new(p).ok())
        .map(|axis| axis.plan())
    else {
        return Vec::new();
    };
    plan.phases
        .iter()
        .scan(0, |at, &n| {
            *at += n;
            Some(*at)
        })
        .take(6)
        .collect()
}

fn draw(
    path: &str,
    points: &[(u64, State)],
    boundaries: &[u64],
    cycle_time: CycleTime,
    chip: &str,
) -> Result<(), Box<dyn std::error::Error>> {
    let root = SVGBackend::new(path, (1000, 900)).into_drawing_area();
    root.fill(&WHITE)?;
    let panels = root.split_evenly((3, 1));
    let last_cycle = points.last().map_or(1, |p| p.0).max(1);
    type Pick = fn(&State) -> f64;
    let series: [(&str, Pick, RGBColor); 3] = [
        ("position (counts)", |s| s.position.to_num(), BLUE),
        (
            "velocity (counts/cycle)",
            |s| s.velocity.to_num(),
            RGBColor(0, 128, 0),
        ),
        (
            "acceleration (counts/cycle²)",
            |s| s.acceleration.to_num(),
            RED,
        ),
    ];
    for (index, (panel, (name, pick, color))) in panels.iter().zip(series).enumerate() {
        let values: Vec<(f64, f64)> = points.iter().map(|(c, s)| (*c as f64, pick(s))).collect();
        let (low, high) = values
            .iter()
            .fold((0.0f64, 0.0f64), |(lo, hi), &(_, v)| (lo.min(v), hi.max(v)));
        let margin = ((high - low) * 0.05).max(1e-12);
        let seconds = last_cycle as f64 * cycle_time.seconds();
        let mut chart = ChartBuilder::on(panel)
            .margin(10)
            .x_label_area_size(30)
            .top_x_label_area_size(if index == 0 { 30 } else { 0 })
            .y_label_area_size(80)
            .caption(name, ("sans-serif", 18))
            .build_cartesian_2d(0f64..last_cycle as f64, (low - margin)..(high + margin))?
            .set_secondary_coord(0f64..seconds, (low - margin)..(high + margin));
        chart.configure_mesh().x_desc("cycle").draw()?;
        if index == 0 {
            chart
                .configure_secondary_axes()
                .x_desc(format!("seconds ({chip})"))
                .draw()?;
        }
        for &boundary in boundaries {
            let x = boundary as f64;
            chart.draw_series(LineSeries::new(
                [(x, low - margin), (x, high + margin)],
                BLACK.mix(0.3),
            ))?;
        }
        chart.draw_series(LineSeries::new(values, color.stroke_width(2)))?;
    }
    root.present()?;
    Ok(())
}
