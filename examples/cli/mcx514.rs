//! The `mcx514` mode of the command line (SPEC §13, §12): an MCX514 interpolation from the chip's
//! own units and a cycle time — the driving axis's speed profile and the geometry it drives, each
//! chosen by options, so a new geometry is one more variant of [`Geometry`] and its options.
//!
//! ```text
//! profile_table mcx514 --cycle-time SECONDS --initial-speed PPS --drive-speed PPS
//!     --acceleration PPS_PER_S [--deceleration PPS_PER_S] [--jerk PPS_PER_S2] [--decel-jerk PPS_PER_S2]
//!     [--decel-point PULSES | --no-decel]  --finish DX,DY[,DZ[,DU]]
//! ```
//!
//! Every value is checked against its register before anything runs; a mistake is one line
//! naming the option and the value given (exit status 2), like the other modes.

use profilegen::format::mcx514::{
    Acceleration, Deceleration, DriveSpeed, FinishPoint, InitialSpeed, ManualDecelerationPoint,
};
use profilegen::format::CycleTime;
use profilegen::interpolation::{InterpolationState, Line};
use profilegen::{
    DecelerationMode, Error, Mcx514Parameters, Mcx514Trapezoidal, ProfileGenerator, State, StopKind,
};

use super::{number, whole, Ending, Format, Program, Usage, MAX_CYCLES};

/// The options only this mode takes (besides `--acceleration`, `--deceleration` and `--jerk`,
/// which it shares by name with the other modes, in its own units). `--no-decel` takes no value.
pub const OPTIONS: [&str; 8] = [
    "--cycle-time",
    "--initial-speed",
    "--drive-speed",
    "--decel-jerk",
    "--decel-point",
    "--no-decel",
    "--finish",
    "--event",
];

/// Options that this mode does not take although other modes do.
const OTHER_MODES: [&str; 3] = ["--velocity", "--destination", "--start-velocity"];

/// What the interpolation follows. A new geometry (a circle: `--centre`, `--direction`) is a new
/// variant, chosen by its own options, checked in [`parse`] and run in [`run`].
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Geometry {
    /// `--finish DX,DY[,DZ[,DU]]`: a linear interpolation of 2–4 axes to that finish point.
    Line(Vec<i32>),
}

impl Geometry {
    /// The number of axes, for the header.
    #[allow(dead_code)] // profile_table's, not plot's
    pub fn axes(&self) -> usize {
        match self {
            Geometry::Line(finish) => finish.len(),
        }
    }

    /// The driving axis's pulses: the long axis's, max|Δᵢ|, for a line.
    fn steps(&self) -> u32 {
        match self {
            Geometry::Line(finish) => finish.iter().map(|d| d.unsigned_abs()).max().unwrap_or(0),
        }
    }
}

/// A stop at a cycle (the events this mode takes: the MCX514 takes no new parameters while an
/// interpolation runs).
#[derive(Debug, Clone)]
pub struct Event {
    pub cycle: u64,
    pub stop: StopKind,
}

/// The whole `mcx514` command line, every register checked.
#[allow(dead_code)] // each example reads the fields of its own options
#[derive(Debug, Clone)]
pub struct Options {
    pub cycle_time: CycleTime,
    /// The cycle time as given, in seconds.
    pub cycle_seconds: f64,
    pub profile: Mcx514Parameters,
    pub geometry: Geometry,
    pub events: Vec<Event>,
    pub cycles: Option<u64>,
    pub every: u64,
    pub format: Format,
    /// `--output FILE` (plot).
    pub output: Option<String>,
}

/// One option's register: its value read as a decimal and rounded by the register, an error
/// naming the option and the text given.
fn register<T>(
    name: &str,
    text: &str,
    from_num: impl FnOnce(f64) -> Result<T, Error>,
) -> Result<T, Usage> {
    from_num(number(name, text)?).map_err(|error| format!("{name} '{text}': {error}"))
}

/// `DX,DY[,DZ[,DU]]`: 2–4 finish points, each a whole number of pulses in range.
fn finish(text: &str) -> Result<Vec<i32>, Usage> {
    let parts: Vec<&str> = text.split(',').collect();
    if !(2..=4).contains(&parts.len()) {
        return Err(format!(
            "--finish '{text}': not DX,DY[,DZ[,DU]] (2 to 4 axes, pulses relative to the start)"
        ));
    }
    parts
        .iter()
        .map(|part| {
            let pulses: i64 = part.trim().parse().map_err(|_| {
                format!("--finish '{text}': '{part}' is not a whole number of pulses")
            })?;
            i32::try_from(pulses)
                .ok()
                .and_then(|pulses| FinishPoint::from_bits(pulses).ok())
                .map(FinishPoint::to_bits)
                .ok_or_else(|| {
                    format!(
                        "--finish '{text}': '{part}' is out of range ({})",
                        FinishPoint::RANGE
                    )
                })
        })
        .collect()
}

/// `N:stop=smooth|abrupt`.
fn event(text: &str) -> Result<Event, Usage> {
    let bad =
        || format!("--event '{text}': not N:stop=smooth|abrupt (the only events of mcx514 mode)");
    let (cycle, assignment) = text.split_once(':').ok_or_else(bad)?;
    let cycle = whole("--event", cycle).map_err(|_| bad())?;
    let stop = match assignment.trim() {
        "stop=smooth" => StopKind::Smooth,
        "stop=abrupt" => StopKind::Abrupt,
        _ => return Err(bad()),
    };
    Ok(Event { cycle, stop })
}

/// Parses the `mcx514` mode's options (`words`: every option and its text, in order; `--no-decel`
/// with an empty text).
pub fn parse(program: Program, words: Vec<(String, String)>) -> Result<Options, Usage> {
    let mut given: Vec<(String, String)> = Vec::new();
    let mut events = Vec::new();
    let (mut cycles, mut every, mut format, mut output) = (None, 1, Format::Table, None);
    for (name, text) in words {
        if OTHER_MODES.contains(&name.as_str()) {
            return Err(format!(
                "{name} '{text}': not used in mcx514 mode (see --help)"
            ));
        }
        if name == "--event" {
            events.push(event(&text)?);
            continue;
        }
        if given.iter().any(|(seen, _)| *seen == name) {
            return Err(format!("{name} '{text}': given twice"));
        }
        match name.as_str() {
            "--cycles" => cycles = Some(whole(&name, &text)?),
            "--every" => {
                every = whole(&name, &text)?;
                if every == 0 {
                    return Err(format!("{name} '{text}': must be at least 1"));
                }
            }
            "--format" => {
                format = match text.as_str() {
                    "table" => Format::Table,
                    "csv" => Format::Csv,
                    "raw" => Format::Raw,
                    _ => return Err(format!("{name} '{text}': not table, csv or raw")),
                }
            }
            "--output" => output = Some(text.clone()),
            _ => {}
        }
        given.push((name, text));
    }
    let text_of = |name: &str| {
        given
            .iter()
            .find(|(seen, _)| seen == name)
            .map(|(_, text)| text.as_str())
    };
    let required = |name: &str| {
        text_of(name).ok_or_else(|| format!("{name}: missing (mcx514 mode needs it; see --help)"))
    };
    // The command line's order of mistakes: the required options first, in the usage's order.
    let cycle_text = required("--cycle-time")?;
    let initial_text = required("--initial-speed")?;
    let drive_text = required("--drive-speed")?;
    let acceleration_text = required("--acceleration")?;
    let finish_text = required("--finish")?;

    let cycle_seconds = number("--cycle-time", cycle_text)?;
    let cycle_time = CycleTime::from_seconds(cycle_seconds)
        .map_err(|error| format!("--cycle-time '{cycle_text}': {error}"))?;
    let initial_speed = register("--initial-speed", initial_text, InitialSpeed::from_num)?;
    let drive_speed = register("--drive-speed", drive_text, DriveSpeed::from_num)?;
    let acceleration = register("--acceleration", acceleration_text, Acceleration::from_num)?;
    let deceleration = match text_of("--deceleration") {
        Some(text) => register("--deceleration", text, Deceleration::from_num)?,
        // Symmetric by default, as automatic deceleration needs.
        None => Deceleration::from_bits(acceleration.to_bits())
            .map_err(|error| format!("--acceleration '{acceleration_text}': {error}"))?,
    };
    if let Some(text) = text_of("--jerk").or(text_of("--decel-jerk")) {
        let name = if text_of("--jerk").is_some() {
            "--jerk"
        } else {
            "--decel-jerk"
        };
        return Err(format!(
            "{name} '{text}': the MCX514 S-curve is not in this version (trapezoidal only: \
             leave out --jerk and --decel-jerk)"
        ));
    }
    let deceleration_mode = match (text_of("--decel-point"), text_of("--no-decel")) {
        (Some(text), Some(_)) => {
            return Err(format!(
                "--decel-point '{text}': not with --no-decel (one or the other)"
            ))
        }
        (Some(text), None) => DecelerationMode::Manual(register(
            "--decel-point",
            text,
            ManualDecelerationPoint::from_num,
        )?),
        (None, Some(_)) => DecelerationMode::Disabled,
        (None, None) => DecelerationMode::Automatic,
    };
    let geometry = Geometry::Line(finish(finish_text)?);
    let profile = Mcx514Parameters {
        pulses: geometry.steps(),
        initial_speed,
        drive_speed,
        acceleration,
        deceleration,
        deceleration_mode,
    };
    // The profile once, so what it refuses (SV above DV, AC ≠ DC with automatic deceleration, a
    // register that vanishes or overflows at this cycle time) is a command-line error.
    Mcx514Trapezoidal::new(profile, cycle_time).map_err(|error| blame(&given, &error))?;
    if program == Program::Plot && output.is_none() {
        return Err("--output: missing (the SVG file to write)".into());
    }
    events.sort_by_key(|event| event.cycle);
    Ok(Options {
        cycle_time,
        cycle_seconds,
        profile,
        geometry,
        events,
        cycles,
        every,
        format,
        output,
    })
}

/// The option a library error is about, with the text given for it.
fn blame(given: &[(String, String)], error: &Error) -> String {
    let parameter = match *error {
        Error::OutOfRange { parameter, .. }
        | Error::NotFinite { parameter, .. }
        | Error::Underflow { parameter, .. }
        | Error::Zero { parameter, .. }
        | Error::Refused { parameter, .. }
        | Error::Unreachable { parameter, .. } => parameter,
        _ => "",
    };
    let name = match parameter {
        "initial speed" => "--initial-speed",
        "drive speed" => "--drive-speed",
        "acceleration" => "--acceleration",
        "deceleration" if given.iter().any(|(name, _)| name == "--deceleration") => {
            "--deceleration"
        }
        // The deceleration defaults to the acceleration.
        "deceleration" => "--acceleration",
        "manual deceleration point" => "--decel-point",
        "finish point" => "--finish",
        _ => return error.to_string(),
    };
    match given.iter().find(|(seen, _)| seen == name) {
        Some((_, text)) => format!("{name} '{text}': {error}"),
        None => format!("{name}: {error}"),
    }
}

/// One cycle of the run: the driving axis's state and every axis's pulses.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Row {
    pub driving: State,
    pub axes: Vec<i32>,
}

impl<const N: usize> From<InterpolationState<N>> for Row {
    fn from(state: InterpolationState<N>) -> Self {
        Row {
            driving: state.driving,
            axes: state.axes.to_vec(),
        }
    }
}

/// Runs the interpolation, calling `visit` with row 0 (at rest at the start) and each cycle's
/// row; stops apply before the cycle they name. Without `--cycles` the run ends when the
/// driving profile is complete and no event is left, or at [`MAX_CYCLES`].
pub fn run<E>(
    options: &Options,
    visit: impl FnMut(u64, &Row) -> Result<(), E>,
) -> Result<Ending, E> {
    let mut profile =
        Mcx514Trapezoidal::new(options.profile, options.cycle_time).expect("checked when parsed");
    match &options.geometry {
        Geometry::Line(finish) => match finish.len() {
            2 => run_line(options, line::<2>(finish), &mut profile, visit),
            3 => run_line(options, line::<3>(finish), &mut profile, visit),
            _ => run_line(options, line::<4>(finish), &mut profile, visit),
        },
    }
}

fn line<const N: usize>(finish: &[i32]) -> Line<N> {
    let finish: [i32; N] = finish.try_into().expect("N axes");
    Line::from_pulses(finish).expect("checked when parsed")
}

fn run_line<E, const N: usize>(
    options: &Options,
    line: Line<N>,
    profile: &mut dyn ProfileGenerator,
    mut visit: impl FnMut(u64, &Row) -> Result<(), E>,
) -> Result<Ending, E> {
    let mut interpolation = line.drive(profile);
    visit(0, &interpolation.state().into())?;
    let mut events = options.events.iter().peekable();
    let mut cycle = 0u64;
    loop {
        match options.cycles {
            Some(cycles) if cycle >= cycles => return Ok(Ending::Done),
            Some(_) => {}
            None if events.peek().is_none() && interpolation.is_complete() => {
                return Ok(Ending::Done)
            }
            None if cycle >= MAX_CYCLES => return Ok(Ending::CutShort),
            None => {}
        }
        cycle += 1;
        while let Some(event) = events.next_if(|event| event.cycle <= cycle) {
            interpolation.stop(event.stop);
        }
        visit(cycle, &interpolation.step().into())?;
    }
}
