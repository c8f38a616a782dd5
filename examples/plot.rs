//! Plots a run of `profile_table` (same modes, options and events, SPEC §13) as an SVG: position,
//! velocity and acceleration against time in seconds, in three aligned panels, with the cycle
//! count on a secondary axis, and the S-curve's phases I–VII marked and labelled. In `mcx514`
//! mode: the XY path of the interpolation, pulse by pulse, with the ideal line beside it.
//!
//! `cargo run --release --example plot -- --help` prints the usage.
//!
//! Memory does not grow with the move: a first pass steps the generator only to count the
//! cycles; the second keeps, for each pixel column, the extremes of the cycles that fall in it
//! (what a line through every point would draw there), so a 10,000,000-cycle move costs the same
//! few kilobytes as a short one.

use std::ffi::OsString;
use std::process::ExitCode;

mod cli;

use cli::{Ending, Generator, Key, Mode, Options, Program, Request};
use plotters::prelude::*;
use profilegen::format::CycleTime;
use profilegen::State;

const HELP: &str = "\
plot: one motion-profile generator's run as an SVG (position, velocity, acceleration)

USAGE:
    cargo run --release --example plot -- <MODE> [OPTIONS] --output FILE.svg

MODE and the profile options, events and --cycles: as profile_table (its --help has them all):
    velocity | trapezoidal | scurve
    --velocity V --acceleration A --deceleration D --jerk J --destination X --start-velocity S
    --event N:KEY=VALUE[,KEY=VALUE…]   --cycles N (at most 100,000,000 here)
    mcx514 (the XY path of the first two axes and the ideal line, circle or segments)
    --cycle-time S --initial-speed PPS --drive-speed PPS --acceleration PPS_PER_S
    --deceleration PPS_PER_S --jerk PPS_PER_S2 --decel-jerk PPS_PER_S2
    --decel-point PULSES | --no-decel --finish DX,DY[,DZ[,DU]]
    [--centre CX,CY --direction cw|ccw] | --segment line:DX,DY | --segment arc:CX,CY:FX,FY:cw|ccw

OPTIONS of the plot:
    --output FILE        the SVG to write (required)
    --cycle-time SECONDS the time axis's cycle (default: the chip's own, Juno 0.0001024 s for
                         velocity and trapezoidal, MC1451A 0.00033 s for scurve)
    -h, --help           this text

EXIT STATUS: 0 done, 2 bad command line, 3 the move was cut short by the 10,000,000-cycle cap
(the plot is written, with a warning on stderr).

EXAMPLE:
    plot scurve --destination 400 --velocity 2.75 --acceleration 0.175 --jerk 0.0075 \\
        --output scurve.svg
    plot mcx514 --cycle-time 0.001 --initial-speed 500 --drive-speed 20000 \\
        --acceleration 65000 --finish 37,23 --output line.svg
    plot mcx514 --cycle-time 0.001 --initial-speed 2000 --drive-speed 20000 \\
        --acceleration 200000 --decel-point 100 --finish 0,0 --centre 12,-5 --direction ccw \\
        --output circle.svg
";

/// The picture's size in pixels, and the plotting area's width (the columns of the decimation).
const SIZE: (u32, u32) = (1200, 1050);
const Y_LABELS_WIDTH: u32 = 90;
const MARGIN: u32 = 20;
/// Wider on the right, so the last tick label of the time and cycle axes is not clipped.
const MARGIN_RIGHT: u32 = 50;
const COLUMNS: usize = (SIZE.0 - Y_LABELS_WIDTH - MARGIN - MARGIN_RIGHT) as usize;
/// The longest `--cycles` a plot takes (each pass steps 100,000,000 cycles in about a second).
const MAX_PLOTTED: u64 = 100_000_000;

fn main() -> ExitCode {
    let arguments: Vec<OsString> = std::env::args_os().skip(1).collect();
    let options = match cli::parse(Program::Plot, arguments) {
        Ok(Request::Help) => {
            print!("{HELP}");
            return ExitCode::SUCCESS;
        }
        Ok(Request::Run(options)) => options,
        Ok(Request::Mcx514(options)) => return plot_mcx514(&options),
        Err(message) => return fail(&message, cli::USAGE),
    };
    // Two passes over the run: a length that takes minutes to step is refused up front.
    if let Some(cycles) = options.cycles.filter(|&cycles| cycles > MAX_PLOTTED) {
        return fail(
            &format!("--cycles '{cycles}': a plot steps at most {MAX_PLOTTED} cycles"),
            cli::USAGE,
        );
    }
    let generator = match cli::generator(&options) {
        Ok(generator) => generator,
        Err(message) => return fail(&message, cli::USAGE),
    };
    let cycle_time = match options.cycle_time {
        Some(seconds) => CycleTime::from_seconds(seconds).expect("checked when parsed"),
        None if options.mode == Mode::Scurve => CycleTime::MC1451A,
        None => CycleTime::JUNO,
    };
    // First pass: the run's length, to map cycles to columns. Events refused here are refused
    // again, and reported, in the second pass; this one keeps quiet about them.
    let mut counter = generator.clone();
    let mut last = 0;
    let ending = cli::simulate_quietly(&options, &mut counter, |cycle, _| {
        last = cycle;
        Ok::<(), ()>(())
    })
    .expect("counting does not fail");
    let mut columns = Columns::new(last);
    let mut drawn = generator.clone();
    let _ = cli::simulate(&options, &mut drawn, |cycle, state| {
        columns.add(cycle, state);
        Ok::<(), ()>(())
    });
    let phases = phases(&options, &generator);
    let output = options.output.clone().expect("required when parsed");
    let mut title = title(&options, cycle_time);
    if ending == Ending::CutShort {
        let (first, rest) = title.split_once('\n').unwrap_or((&title, ""));
        title = format!("{first}, cut short at {} cycles\n{rest}", cli::MAX_CYCLES);
    }
    if let Err(error) = draw(&output, &title, &columns, &phases, cycle_time) {
        return fail(&format!("--output '{output}': {error}"), 1);
    }
    if ending == Ending::CutShort {
        eprintln!("{}", cli::cut_short_warning());
        return ExitCode::from(cli::CUT_SHORT);
    }
    ExitCode::SUCCESS
}

/// The points of the XY path kept for the picture: every change of position while the line has
/// at most this many steps, else one every steps/this steps (and the last).
const PATH_POINTS: u64 = 20_000;

/// `mcx514` mode: the XY path (the first two axes, pulses) and the ideal line to the finish point.
fn plot_mcx514(options: &cli::mcx514::Options) -> ExitCode {
    if let Some(cycles) = options.cycles.filter(|&cycles| cycles > MAX_PLOTTED) {
        return fail(
            &format!("--cycles '{cycles}': a plot steps at most {MAX_PLOTTED} cycles"),
            cli::USAGE,
        );
    }
    let (ideal, what, label) = ideal_path(&options.geometry);
    let steps = u64::from(options.profile.pulses);
    let stride = (steps / PATH_POINTS).max(1);
    let mut path: Vec<(i32, i32)> = vec![(0, 0)];
    let (mut last_step, mut last_cycle, mut last_point) = (0u64, 0, (0, 0));
    let ending = cli::mcx514::run(options, |cycle, row| {
        let step = (row.driving.position.to_bits() >> 32).max(0) as u64;
        let point = (row.axes[0], row.axes[1]);
        if step >= last_step + stride && path.last() != Some(&point) {
            path.push(point);
            last_step = step;
        }
        (last_cycle, last_point) = (cycle, point);
        Ok::<(), ()>(())
    })
    .expect("collecting does not fail");
    // The final position is always on the path.
    if path.last() != Some(&last_point) {
        path.push(last_point);
    }
    let title = format!(
        "MCX514 {what}, {} µs per cycle, {last_cycle} cycles\n\
         SV {}, DV {}, AC {}, DC {}{}, {}",
        options.cycle_seconds * 1e6,
        options.profile.initial_speed,
        options.profile.drive_speed,
        options.profile.acceleration,
        options.profile.deceleration,
        match options.jerks {
            Some((jerk, deceleration_jerk)) => format!(", JK {jerk}, DJ {deceleration_jerk}"),
            None => String::new(),
        },
        match options.profile.deceleration_mode {
            profilegen::DecelerationMode::Automatic => "automatic deceleration".to_string(),
            profilegen::DecelerationMode::Manual(point) => format!("deceleration at {point}"),
            profilegen::DecelerationMode::Disabled => "deceleration disabled".to_string(),
        }
    );
    let output = options.output.clone().expect("required when parsed");
    if let Err(error) = draw_path(&output, &title, &path, &ideal, label) {
        return fail(&format!("--output '{output}': {error}"), 1);
    }
    if ending == Ending::CutShort {
        eprintln!("{}", cli::cut_short_warning());
        return ExitCode::from(cli::CUT_SHORT);
    }
    ExitCode::SUCCESS
}

/// The ideal path of a geometry (relative to the start, in pulses, for the picture only: `f64`),
/// what it is, and its legend: the line to the finish point, the true circle along the arc, the
/// segments one after the other.
fn ideal_path(geometry: &cli::mcx514::Geometry) -> (Vec<(f64, f64)>, String, &'static str) {
    use cli::mcx514::Geometry;
    use profilegen::interpolation::Segment;
    let join = |values: &[i32]| {
        values
            .iter()
            .map(i32::to_string)
            .collect::<Vec<_>>()
            .join(", ")
    };
    match geometry {
        Geometry::Line(finish) => (
            vec![(0.0, 0.0), (f64::from(finish[0]), f64::from(finish[1]))],
            format!("linear interpolation to ({})", join(finish)),
            "the ideal line",
        ),
        Geometry::Circle(arc) => (
            ideal_arc((0.0, 0.0), arc),
            format!(
                "circular interpolation around ({}) to ({}), {}",
                join(&arc.centre()),
                join(&arc.finish()),
                match arc.direction() {
                    profilegen::interpolation::Direction::Clockwise => "clockwise",
                    profilegen::interpolation::Direction::CounterClockwise => "counter-clockwise",
                }
            ),
            "the true circle",
        ),
        Geometry::Segments(segments) => {
            let mut points = vec![(0.0, 0.0)];
            let mut origin = (0.0, 0.0);
            for segment in segments {
                match segment {
                    Segment::Line(line) => {
                        let [dx, dy] = line.finish();
                        points.push((origin.0 + f64::from(dx), origin.1 + f64::from(dy)));
                    }
                    Segment::Arc(arc) => points.extend(ideal_arc(origin, arc)),
                }
                let [dx, dy] = segment.end();
                origin = (origin.0 + f64::from(dx), origin.1 + f64::from(dy));
            }
            (
                points,
                format!("continuous interpolation, {} segments", segments.len()),
                "the ideal lines and circles",
            )
        }
    }
}

/// Points of the true circle of `arc` from its start (at `origin`) to its end, in its direction.
fn ideal_arc(origin: (f64, f64), arc: &profilegen::interpolation::Arc) -> Vec<(f64, f64)> {
    use std::f64::consts::TAU;
    let [cx, cy] = arc.centre().map(f64::from);
    let radius = (arc.radius_squared() as f64).sqrt();
    let start = (-cy).atan2(-cx);
    let [ex, ey] = arc.end().map(f64::from);
    let sign = match arc.direction() {
        profilegen::interpolation::Direction::CounterClockwise => 1.0,
        profilegen::interpolation::Direction::Clockwise => -1.0,
    };
    let mut sweep = (sign * ((ey - cy).atan2(ex - cx) - start)).rem_euclid(TAU);
    if sweep < 1e-12 {
        sweep = TAU; // a full circle
    }
    let samples = 720;
    (0..=samples)
        .map(|i| {
            let angle = start + sign * sweep * f64::from(i) / f64::from(samples);
            (
                origin.0 + cx + radius * angle.cos(),
                origin.1 + cy + radius * angle.sin(),
            )
        })
        .collect()
}

/// Draws the XY path as steps (each pulse a unit move, as the axes output them) and the ideal
/// path beside it, on equal scales.
fn draw_path(
    path: &str,
    title: &str,
    points: &[(i32, i32)],
    ideal: &[(f64, f64)],
    ideal_label: &'static str,
) -> Result<(), Box<dyn std::error::Error>> {
    let root = SVGBackend::new(path, (900, 900)).into_drawing_area();
    root.fill(&WHITE)?;
    let mut root = root;
    for (line, size) in title.lines().zip([20, 16]) {
        root = root.titled(line, ("sans-serif", size))?;
    }
    // Equal scales: one square range around the path and the ideal path.
    let xs = points
        .iter()
        .map(|p| f64::from(p.0))
        .chain(ideal.iter().map(|p| p.0));
    let ys = points
        .iter()
        .map(|p| f64::from(p.1))
        .chain(ideal.iter().map(|p| p.1));
    let (x0, x1) = xs.fold((0.0f64, 0.0f64), |(lo, hi), x| (lo.min(x), hi.max(x)));
    let (y0, y1) = ys.fold((0.0f64, 0.0f64), |(lo, hi), y| (lo.min(y), hi.max(y)));
    let span = (x1 - x0).max(y1 - y0).max(1.0) * 1.08;
    let (cx, cy) = ((x0 + x1) / 2.0, (y0 + y1) / 2.0);
    let mut chart = ChartBuilder::on(&root)
        .margin(MARGIN)
        .x_label_area_size(40)
        .y_label_area_size(Y_LABELS_WIDTH)
        .build_cartesian_2d(
            cx - span / 2.0..cx + span / 2.0,
            cy - span / 2.0..cy + span / 2.0,
        )?;
    chart
        .configure_mesh()
        .x_desc("x (pulses)")
        .y_desc("y (pulses)")
        .light_line_style(RGBColor(235, 235, 235))
        .draw()?;
    let ideal_color = RGBColor(214, 39, 40);
    chart
        .draw_series(DashedLineSeries::new(
            ideal.iter().copied(),
            6,
            4,
            ideal_color.stroke_width(1),
        ))?
        .label(ideal_label)
        .legend(move |(x, y)| PathElement::new([(x, y), (x + 20, y)], ideal_color.stroke_width(1)));
    // Each pulse as the axes make it: x first, then y (a staircase when points are one pulse
    // apart; a polyline through the kept points otherwise).
    let mut staircase = Vec::with_capacity(points.len() * 2);
    for pair in points.windows(2) {
        let ((xa, ya), (xb, yb)) = (pair[0], pair[1]);
        staircase.push((xa as f64, ya as f64));
        if (xb - xa).abs() <= 1 && (yb - ya).abs() <= 1 {
            staircase.push((xb as f64, ya as f64));
        }
    }
    if let Some(&(x, y)) = points.last() {
        staircase.push((x as f64, y as f64));
    }
    let path_color = RGBColor(31, 119, 180);
    chart
        .draw_series(LineSeries::new(staircase, path_color.stroke_width(2)))?
        .label("the interpolated path (x, y pulses)")
        .legend(move |(x, y)| PathElement::new([(x, y), (x + 20, y)], path_color.stroke_width(2)));
    chart
        .configure_series_labels()
        .position(SeriesLabelPosition::UpperLeft)
        .background_style(WHITE.mix(0.85))
        .border_style(RGBColor(180, 180, 180))
        .label_font(("sans-serif", 14))
        .draw()?;
    root.present()?;
    Ok(())
}

fn fail(message: &str, status: u8) -> ExitCode {
    eprintln!("error: {message}");
    ExitCode::from(status)
}

/// The extremes of each quantity over the cycles of one pixel column, in the order the line
/// visits them.
#[derive(Clone, Copy)]
struct Column {
    first_cycle: u64,
    /// Per quantity (position, velocity, acceleration): the first, lowest, highest and last
    /// value, and whether the lowest came before the highest.
    values: [[f64; 4]; 3],
    low_first: [bool; 3],
}

/// A run reduced to at most [`COLUMNS`] columns (or one per cycle, if the run is shorter).
struct Columns {
    last_cycle: u64,
    columns: Vec<Option<Column>>,
}

impl Columns {
    fn new(last_cycle: u64) -> Self {
        let count = (last_cycle + 1).min(COLUMNS as u64) as usize;
        Self {
            last_cycle,
            columns: vec![None; count],
        }
    }

    fn add(&mut self, cycle: u64, state: &State) {
        // Cycle 0 … last over the columns, evenly (u128: no overflow for any u64 cycle count).
        let index = (u128::from(cycle) * self.columns.len() as u128
            / (u128::from(self.last_cycle) + 1)) as usize;
        let values = [
            state.position.to_num::<f64>(),
            state.velocity.to_num::<f64>(),
            state.acceleration.to_num::<f64>(),
        ];
        let column = self.columns[index].get_or_insert(Column {
            first_cycle: cycle,
            values: values.map(|v| [v; 4]),
            low_first: [true; 3],
        });
        for (quantity, &value) in values.iter().enumerate() {
            let [_, low, high, last] = &mut column.values[quantity];
            if value < *low {
                *low = value;
                column.low_first[quantity] = false;
            }
            if value > *high {
                *high = value;
                column.low_first[quantity] = true;
            }
            *last = value;
        }
    }

    /// The line through the columns for one quantity, in cycles and per-cycle units: each column
    /// contributes its first, extreme, extreme and last values, in the order they came.
    fn line(&self, quantity: usize) -> Vec<(f64, f64)> {
        let mut points = Vec::with_capacity(self.columns.len() * 4);
        for column in self.columns.iter().flatten() {
            let x = column.first_cycle as f64;
            let [first, low, high, last] = column.values[quantity];
            let (a, b) = if column.low_first[quantity] {
                (low, high)
            } else {
                (high, low)
            };
            points.extend([(x, first), (x, a), (x, b), (x, last)]);
        }
        points
    }
}

/// The S-curve plan's phases as (first cycle, last cycle) for each of I–VII, when the plot shows
/// that plan: an S-curve run without events (an event replans or stops the move).
fn phases(options: &Options, generator: &Generator) -> Vec<(u64, u64)> {
    let Generator::Scurve(axis) = generator else {
        return Vec::new();
    };
    if !options.events.is_empty() {
        return Vec::new();
    }
    let mut start = 0;
    axis.plan()
        .phases
        .iter()
        .map(|&length| {
            let phase = (start, start + length);
            start += length;
            phase
        })
        .collect()
}

/// A tick label with as many decimals as the ticks' spacing needs (so small values do not all
/// read "0.0"), every label of an axis in the same notation: scientific when the axis reaches a
/// million or stays below a thousandth.
fn tick_label(value: f64, low: f64, high: f64) -> String {
    // About ten ticks over the span: one significant digit of the step tells them apart.
    let step = ((high - low) / 10.0).abs().max(f64::MIN_POSITIVE);
    let step_digit = step.log10().floor() as i32;
    let extent = low.abs().max(high.abs()).max(f64::MIN_POSITIVE);
    if value == 0.0 {
        return "0".into();
    }
    if !(1e-3..1e6).contains(&extent) {
        let exponent = value.abs().log10().floor() as i32;
        let decimals = (exponent - step_digit).clamp(0, 12) as usize;
        format!("{value:.decimals$e}")
    } else {
        let decimals = (-step_digit).clamp(0, 12) as usize;
        format!("{value:.decimals$}")
    }
}

/// The legend's place: of six candidate boxes (a third of the width, a quarter of the height,
/// clear of the phase labels along the top), the one the line crosses least.
fn legend_position(line: &[(f64, f64)], x_end: f64, bottom: f64, top: f64) -> SeriesLabelPosition {
    use SeriesLabelPosition::*;
    let candidates = [
        (LowerMiddle, (0.33, 0.67), (0.0, 0.3)),
        (LowerRight, (0.62, 1.0), (0.0, 0.3)),
        (LowerLeft, (0.0, 0.38), (0.0, 0.3)),
        (MiddleRight, (0.62, 1.0), (0.35, 0.65)),
        (MiddleLeft, (0.0, 0.38), (0.35, 0.65)),
        (UpperRight, (0.62, 1.0), (0.55, 0.85)),
    ];
    let crossings = |&(_, (x0, x1), (y0, y1)): &(SeriesLabelPosition, (f64, f64), (f64, f64))| {
        line.iter()
            .filter(|&&(x, y)| {
                let (x, y) = (x / x_end, (y - bottom) / (top - bottom));
                (x0..=x1).contains(&x) && (y0..=y1).contains(&y)
            })
            .count()
    };
    let best = candidates
        .iter()
        .min_by_key(|candidate| crossings(candidate))
        .expect("six candidates");
    match best.0 {
        LowerMiddle => LowerMiddle,
        LowerRight => LowerRight,
        LowerLeft => LowerLeft,
        MiddleRight => MiddleRight,
        MiddleLeft => MiddleLeft,
        _ => UpperRight,
    }
}

fn roman(phase: usize) -> &'static str {
    ["I", "II", "III", "IV", "V", "VI", "VII"][phase]
}

fn title(options: &Options, cycle_time: CycleTime) -> String {
    let given = |key: Key, unit: &str| {
        options
            .values
            .get(&key)
            .map(|(_, text)| format!("{} {text} {unit}", key.name()))
    };
    let (chip, parameters) = match options.mode {
        Mode::Velocity => (
            "Juno velocity contouring",
            [
                given(Key::Velocity, "counts/cycle"),
                given(Key::Acceleration, "counts/cycle²"),
                given(Key::Deceleration, "counts/cycle²"),
            ]
            .to_vec(),
        ),
        Mode::Trapezoidal => (
            "trapezoidal point-to-point",
            [
                given(Key::Destination, "counts"),
                given(Key::Velocity, "counts/cycle"),
                given(Key::Acceleration, "counts/cycle²"),
                given(Key::Deceleration, "counts/cycle²"),
                given(Key::StartVelocity, "counts/cycle"),
            ]
            .to_vec(),
        ),
        Mode::Scurve => (
            "MC1451A S-curve",
            [
                given(Key::Destination, "counts"),
                given(Key::Velocity, "counts/cycle"),
                given(Key::Acceleration, "counts/cycle²"),
                given(Key::Jerk, "counts/cycle³"),
            ]
            .to_vec(),
        ),
    };
    let parameters: Vec<String> = parameters.into_iter().flatten().collect();
    let events = match options.events.len() {
        0 => String::new(),
        n => format!(", {n} event{}", if n == 1 { "" } else { "s" }),
    };
    // Two lines: what ran, then its parameters (a single line overflows the picture).
    let micros = format!("{:.3}", cycle_time.seconds() * 1e6);
    let micros = micros.trim_end_matches('0').trim_end_matches('.');
    format!(
        "{chip}, {micros} µs per cycle{events}\n{}",
        parameters.join(", ")
    )
}

fn draw(
    path: &str,
    title: &str,
    columns: &Columns,
    phases: &[(u64, u64)],
    cycle_time: CycleTime,
) -> Result<(), Box<dyn std::error::Error>> {
    let root = SVGBackend::new(path, SIZE).into_drawing_area();
    root.fill(&WHITE)?;
    let mut root = root;
    for (line, size) in title.lines().zip([22, 17]) {
        root = root.titled(line, ("sans-serif", size))?;
    }
    let panels = root.split_evenly((3, 1));
    let last_cycle = columns.last_cycle.max(1) as f64;
    let seconds = last_cycle * cycle_time.seconds();
    let decimated = columns.last_cycle + 1 > columns.columns.len() as u64;
    // Per quantity: name, unit, per-cycle to per-second factor (1/T^power), colour.
    let quantities: [(&str, &str, i32, RGBColor); 3] = [
        ("position", "counts", 0, RGBColor(31, 119, 180)),
        ("velocity", "counts/s", 1, RGBColor(44, 160, 44)),
        ("acceleration", "counts/s²", 2, RGBColor(214, 39, 40)),
    ];
    for (index, (panel, (name, unit, power, color))) in panels.iter().zip(quantities).enumerate() {
        let scale = cycle_time.seconds().powi(-power);
        let line: Vec<(f64, f64)> = columns
            .line(index)
            .into_iter()
            .map(|(cycle, value)| (cycle * cycle_time.seconds(), value * scale))
            .collect();
        let (low, high) = line
            .iter()
            .fold((0.0f64, 0.0f64), |(lo, hi), &(_, v)| (lo.min(v), hi.max(v)));
        // Room above the line for the phase labels, and a little below.
        let pad = if high > low { (high - low) * 0.08 } else { 1.0 };
        let (bottom, top) = (low - pad, high + 2.0 * pad);
        let mut chart = ChartBuilder::on(panel)
            .margin(MARGIN)
            .margin_right(MARGIN_RIGHT)
            .x_label_area_size(40)
            .top_x_label_area_size(if index == 0 { 40 } else { 0 })
            .y_label_area_size(Y_LABELS_WIDTH)
            .build_cartesian_2d(0.0..seconds, bottom..top)?
            .set_secondary_coord(0.0..last_cycle, bottom..top);
        let time_label = |t: &f64| tick_label(*t, 0.0, seconds);
        let value_label = |v: &f64| tick_label(*v, bottom, top);
        let legend = legend_position(&line, seconds, bottom, top);
        chart
            .configure_mesh()
            .x_desc(if index == 2 { "time (s)" } else { "" })
            .y_desc(format!("{name} ({unit})"))
            .x_label_formatter(&time_label)
            .y_label_formatter(&value_label)
            .light_line_style(RGBColor(235, 235, 235))
            .draw()?;
        if index == 0 {
            let cycle_label = |c: &f64| tick_label(c.round(), 0.0, last_cycle);
            chart
                .configure_secondary_axes()
                .x_desc("cycle")
                .x_label_formatter(&cycle_label)
                .draw()?;
        }
        let boundary = RGBColor(110, 110, 110);
        for (phase, &(start, end)) in phases.iter().enumerate() {
            if end == start || start >= columns.last_cycle {
                continue; // a phase the plan does not have, or the run does not reach
            }
            let end = end.min(columns.last_cycle);
            let (from, to) = (
                start as f64 * cycle_time.seconds(),
                end as f64 * cycle_time.seconds(),
            );
            if end < columns.last_cycle {
                chart.draw_series(DashedLineSeries::new(
                    [(to, bottom), (to, top)],
                    4,
                    4,
                    boundary.stroke_width(1),
                ))?;
            }
            chart.draw_series(std::iter::once(Text::new(
                roman(phase),
                ((from + to) / 2.0, high + 1.6 * pad),
                ("sans-serif", 15).into_font().color(&boundary),
            )))?;
        }
        let label = if decimated {
            format!("{name} (min/max of the cycles in each pixel column)")
        } else {
            name.to_string()
        };
        chart
            .draw_series(LineSeries::new(line, color.stroke_width(2)))?
            .label(label)
            .legend(move |(x, y)| PathElement::new([(x, y), (x + 20, y)], color.stroke_width(2)));
        if !phases.is_empty() {
            chart
                .draw_series(std::iter::empty::<PathElement<(f64, f64)>>())?
                .label("phase boundary (S-curve plan, phases I–VII)")
                .legend(move |(x, y)| {
                    plotters::element::DashedPathElement::new(
                        [(x, y), (x + 20, y)],
                        4,
                        4,
                        boundary.stroke_width(1),
                    )
                });
        }
        chart
            .configure_series_labels()
            .position(legend)
            .background_style(WHITE.mix(0.85))
            .border_style(RGBColor(180, 180, 180))
            .label_font(("sans-serif", 14))
            .draw()?;
    }
    root.present()?;
    Ok(())
}
