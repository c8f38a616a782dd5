//! The `mcx514` mode of the command line (SPEC §13, §12): an MCX514 interpolation from the chip's
//! own units and a cycle time — the driving axis's speed profile and the geometry it drives, each
//! chosen by options, so a new geometry is one more variant of [`Geometry`] and its options.
//!
//! ```text
//! profile_table mcx514 --cycle-time SECONDS --initial-speed PPS --drive-speed PPS
//!     --acceleration PPS_PER_S [--deceleration PPS_PER_S]
//!     [--jerk PPS_PER_S2 [--decel-jerk PPS_PER_S2]]
//!     [--decel-point PULSES | --no-decel]
//!     (--finish DX,DY[,DZ[,DU]]                                  linear, 2–4 axes
//!      | --finish DX,DY --centre CX,CY --direction cw|ccw        circular; finish 0,0 = full circle
//!      | --segment line:DX,DY | --segment arc:CX,CY:FX,FY:cw|ccw …)   continuous, X and Y
//! ```
//!
//! Every value is checked against its register before anything runs; a mistake is one line
//! naming the option and the value given (exit status 2), like the other modes.

use profilegen::format::mcx514::{
    Acceleration, Deceleration, DecelerationJerk, DriveSpeed, FinishPoint, InitialSpeed, Jerk,
    ManualDecelerationPoint,
};
use profilegen::format::CycleTime;
use profilegen::interpolation::{
    Arc, CircleState, CircularDriving, ContinuousDriving, ContinuousInterpolation, ContinuousState,
    Direction, InterpolationState, Line, Segment,
};
use profilegen::{
    DecelerationMode, Error, Mcx514Parameters, Mcx514SCurve, Mcx514ScurveParameters,
    Mcx514Trapezoidal, ProfileGenerator, State, StopKind,
};

use super::{number, whole, Ending, Format, Program, Usage, MAX_CYCLES};

/// The options only this mode takes (besides `--acceleration`, `--deceleration` and `--jerk`,
/// which it shares by name with the other modes, in its own units). `--no-decel` takes no value.
pub const OPTIONS: [&str; 11] = [
    "--cycle-time",
    "--initial-speed",
    "--drive-speed",
    "--decel-jerk",
    "--decel-point",
    "--no-decel",
    "--finish",
    "--centre",
    "--direction",
    "--segment",
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
    /// `--finish DX,DY --centre CX,CY --direction cw|ccw`: a circular interpolation.
    Circle(Arc),
    /// `--segment …` (repeatable): a continuous interpolation of lines and arcs on X and Y.
    Segments(Vec<Segment>),
}

impl Geometry {
    /// The number of axes, for the header.
    #[allow(dead_code)] // profile_table's, not plot's
    pub fn axes(&self) -> usize {
        match self {
            Geometry::Line(finish) => finish.len(),
            Geometry::Circle(_) | Geometry::Segments(_) => 2,
        }
    }

    /// The driving axis's pulses: the long axis's, max|Δᵢ|, for a line; the short axis's for an
    /// arc; the sum over the segments (saturated: the profile refuses what is too long).
    fn steps(&self) -> u32 {
        let steps = match self {
            Geometry::Line(finish) => finish
                .iter()
                .map(|d| u64::from(d.unsigned_abs()))
                .max()
                .unwrap_or(0),
            Geometry::Circle(arc) => arc.steps(),
            Geometry::Segments(segments) => segments.iter().map(Segment::steps).sum(),
        };
        u32::try_from(steps).unwrap_or(u32::MAX)
    }
}

/// `CX,CY` or `DX,DY`: two whole numbers of pulses (their ranges are the geometry's to check).
fn pair(name: &str, text: &str, whole_text: &str) -> Result<[i32; 2], Usage> {
    let parts: Vec<&str> = text.split(',').collect();
    if parts.len() != 2 {
        return Err(format!(
            "{name} '{whole_text}': '{text}' is not X,Y (two whole numbers of pulses)"
        ));
    }
    let mut out = [0; 2];
    for (slot, part) in out.iter_mut().zip(&parts) {
        *slot = part.trim().parse::<i32>().map_err(|_| {
            format!("{name} '{whole_text}': '{part}' is not a whole number of pulses")
        })?;
    }
    Ok(out)
}

/// `cw` or `ccw`.
fn direction(name: &str, text: &str, whole_text: &str) -> Result<Direction, Usage> {
    match text.trim() {
        "cw" => Ok(Direction::Clockwise),
        "ccw" => Ok(Direction::CounterClockwise),
        _ => Err(format!("{name} '{whole_text}': '{text}' is not cw or ccw")),
    }
}

/// `line:DX,DY` or `arc:CX,CY:FX,FY:cw|ccw`, relative to the previous segment's end.
fn segment(text: &str) -> Result<Segment, Usage> {
    let bad = |error: Error| format!("--segment '{text}': {error}");
    let parts: Vec<&str> = text.split(':').collect();
    match parts.as_slice() {
        ["line", finish] => {
            let finish = pair("--segment", finish, text)?;
            Line::from_pulses(finish).map(Segment::Line).map_err(bad)
        }
        ["arc", centre, finish, turn] => {
            let centre = pair("--segment", centre, text)?;
            let finish = pair("--segment", finish, text)?;
            let turn = direction("--segment", turn, text)?;
            Arc::from_pulses(centre, finish, turn)
                .map(Segment::Arc)
                .map_err(bad)
        }
        _ => Err(format!(
            "--segment '{text}': not line:DX,DY or arc:CX,CY:FX,FY:cw|ccw"
        )),
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
    /// `--jerk` (and `--decel-jerk`, default the same): the S-curve; `None`: the trapezoid.
    pub jerks: Option<(Jerk, DecelerationJerk)>,
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
    let mut segments = Vec::new();
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
        if name == "--segment" {
            segments.push(segment(&text)?);
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
    if !segments.is_empty() {
        if let Some(name) = ["--finish", "--centre", "--direction"]
            .into_iter()
            .find(|name| text_of(name).is_some())
        {
            let text = text_of(name).unwrap_or_default();
            return Err(format!(
                "{name} '{text}': not with --segment (the segments are the whole path)"
            ));
        }
    }
    let finish_text = if segments.is_empty() {
        required("--finish")?
    } else {
        ""
    };

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
    let jerks = match (text_of("--jerk"), text_of("--decel-jerk")) {
        (None, None) => None,
        (None, Some(text)) => {
            return Err(format!(
                "--decel-jerk '{text}': needs --jerk (the S-curve; without it the profile is \
                 trapezoidal)"
            ))
        }
        (Some(jerk_text), decel_text) => {
            let jerk = register("--jerk", jerk_text, Jerk::from_num)?;
            let deceleration_jerk = match decel_text {
                Some(text) => register("--decel-jerk", text, DecelerationJerk::from_num)?,
                // Symmetric by default, as automatic deceleration needs.
                None => DecelerationJerk::from_bits(jerk.to_bits())
                    .map_err(|error| format!("--jerk '{jerk_text}': {error}"))?,
            };
            Some((jerk, deceleration_jerk))
        }
    };
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
    let geometry = match (text_of("--centre"), text_of("--direction")) {
        _ if !segments.is_empty() => Geometry::Segments(segments),
        (None, None) => Geometry::Line(finish(finish_text)?),
        (Some(text), None) => {
            return Err(format!(
                "--centre '{text}': a circle needs --direction cw|ccw too"
            ))
        }
        (None, Some(text)) => {
            return Err(format!(
                "--direction '{text}': only for a circle (give --centre CX,CY too)"
            ))
        }
        (Some(centre_text), Some(turn_text)) => {
            let centre = pair("--centre", centre_text, centre_text)?;
            let turn = direction("--direction", turn_text, turn_text)?;
            let end = pair("--finish", finish_text, finish_text)?;
            let arc = Arc::from_pulses(centre, end, turn).map_err(|error| {
                let (name, text) = match error {
                    Error::OutOfRange {
                        parameter: "finish point",
                        ..
                    }
                    | Error::Unreachable {
                        parameter: "finish point",
                        ..
                    } => ("--finish", finish_text),
                    _ => ("--centre", centre_text),
                };
                format!("{name} '{text}': {error}")
            })?;
            Geometry::Circle(arc)
        }
    };
    let continuous = matches!(geometry, Geometry::Segments(_));
    if !matches!(geometry, Geometry::Line(_)) && deceleration_mode == DecelerationMode::Automatic {
        let (name, text) = if continuous {
            ("--segment", "")
        } else {
            ("--centre", text_of("--centre").unwrap_or_default())
        };
        let shown = if continuous {
            name.to_owned()
        } else {
            format!("{name} '{text}'")
        };
        return Err(format!(
            "{shown}: {} needs --decel-point PULSES or --no-decel (the MCX514 has no automatic \
             deceleration there)",
            if continuous {
                "a continuous interpolation"
            } else {
                "a circle"
            }
        ));
    }
    let profile = Mcx514Parameters {
        pulses: geometry.steps(),
        initial_speed,
        drive_speed,
        acceleration,
        deceleration,
        deceleration_mode,
    };
    // The profile once, so what it refuses (SV above DV, AC ≠ DC or JK ≠ DJ with automatic
    // deceleration, a register that vanishes or overflows at this cycle time) is a command-line
    // error. Circles and segments drive trapezoidally only, as on the chip.
    if let (Some((_, _)), false) = (jerks, matches!(geometry, Geometry::Line(_))) {
        let (name, text) = match text_of("--jerk") {
            Some(text) => ("--jerk", text),
            None => ("--decel-jerk", text_of("--decel-jerk").unwrap_or_default()),
        };
        return Err(format!(
            "{name} '{text}': a circle or segments drive trapezoidally only (the MCX514's S-curve \
             is for linear interpolation)"
        ));
    }
    match &geometry {
        Geometry::Line(_) => {
            Profile::new(profile, jerks, cycle_time).map_err(|error| blame(&given, &error))?;
        }
        Geometry::Circle(arc) => {
            arc.mcx514_profile(circular_driving(&profile), cycle_time)
                .map_err(|error| blame(&given, &error))?;
        }
        Geometry::Segments(_) => {
            ContinuousInterpolation::new(continuous_driving(&profile), cycle_time)
                .map_err(|error| blame(&given, &error))?;
        }
    }
    if program == Program::Plot && output.is_none() {
        return Err("--output: missing (the SVG file to write)".into());
    }
    events.sort_by_key(|event| event.cycle);
    Ok(Options {
        cycle_time,
        cycle_seconds,
        profile,
        jerks,
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
        "jerk" => "--jerk",
        "deceleration increasing rate" if given.iter().any(|(name, _)| name == "--decel-jerk") => {
            "--decel-jerk"
        }
        "deceleration increasing rate" => "--jerk",
        "finish point" => "--finish",
        "arc steps" => "--centre",
        _ => return error.to_string(),
    };
    match given.iter().find(|(seen, _)| seen == name) {
        Some((_, text)) => format!("{name} '{text}': {error}"),
        None => format!("{name}: {error}"),
    }
}

/// The driving axis's profile: the MCX514 trapezoid or its S-curve (each boxed: their cycles
/// laid out ahead make them large).
#[derive(Debug, Clone)]
pub enum Profile {
    Trapezoidal(Box<Mcx514Trapezoidal>),
    SCurve(Box<Mcx514SCurve>),
}

impl Profile {
    /// The S-curve when there are jerks, else the trapezoid.
    ///
    /// # Errors
    /// What the profile refuses.
    pub fn new(
        parameters: Mcx514Parameters,
        jerks: Option<(Jerk, DecelerationJerk)>,
        cycle: CycleTime,
    ) -> Result<Self, Error> {
        Ok(match jerks {
            None => Profile::Trapezoidal(Box::new(Mcx514Trapezoidal::new(parameters, cycle)?)),
            Some((jerk, deceleration_jerk)) => Profile::SCurve(Box::new(Mcx514SCurve::new(
                Mcx514ScurveParameters {
                    trapezoid: parameters,
                    jerk,
                    deceleration_jerk,
                },
                cycle,
            )?)),
        })
    }

    fn axis(&mut self) -> &mut dyn ProfileGenerator {
        match self {
            Profile::Trapezoidal(axis) => axis.as_mut(),
            Profile::SCurve(axis) => axis.as_mut(),
        }
    }
}

/// One cycle of the run: the driving axis's state and every axis's pulses.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Row {
    pub driving: State,
    pub axes: Vec<i32>,
}

impl From<CircleState> for Row {
    fn from(state: CircleState) -> Self {
        Row {
            driving: state.driving,
            axes: state.axes.to_vec(),
        }
    }
}

impl From<ContinuousState> for Row {
    fn from(state: ContinuousState) -> Self {
        Row {
            driving: state.driving,
            axes: state.axes.to_vec(),
        }
    }
}

/// The circle's driving registers from the checked profile (trapezoidal; the deceleration mode
/// is manual or disabled, checked when parsed).
fn circular_driving(profile: &Mcx514Parameters) -> CircularDriving {
    CircularDriving {
        initial_speed: profile.initial_speed,
        drive_speed: profile.drive_speed,
        acceleration: profile.acceleration,
        deceleration: profile.deceleration,
        jerk: None,
        deceleration_jerk: None,
        deceleration_mode: profile.deceleration_mode,
    }
}

fn continuous_driving(profile: &Mcx514Parameters) -> ContinuousDriving {
    ContinuousDriving {
        initial_speed: profile.initial_speed,
        drive_speed: profile.drive_speed,
        acceleration: profile.acceleration,
        deceleration: profile.deceleration,
    }
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
    match &options.geometry {
        Geometry::Line(finish) => {
            let mut profile = Profile::new(options.profile, options.jerks, options.cycle_time)
                .expect("checked when parsed");
            let profile = profile.axis();
            match finish.len() {
                2 => run_line(options, line::<2>(finish), profile, visit),
                3 => run_line(options, line::<3>(finish), profile, visit),
                _ => run_line(options, line::<4>(finish), profile, visit),
            }
        }
        Geometry::Circle(arc) => {
            let mut profile = arc
                .mcx514_profile(circular_driving(&options.profile), options.cycle_time)
                .expect("checked when parsed");
            let mut interpolation = arc.drive(&mut profile);
            let first = interpolation.state().into();
            drive_rows(options, first, visit, |stop| match stop {
                Some(kind) => {
                    interpolation.stop(kind);
                    None
                }
                None => Some((interpolation.step().into(), interpolation.is_complete())),
            })
        }
        Geometry::Segments(segments) => {
            let mut run = ContinuousInterpolation::new(
                continuous_driving(&options.profile),
                options.cycle_time,
            )
            .expect("checked when parsed");
            // The queue is refilled before every cycle; the last segment carries the point.
            let mut queued = 0;
            let point = match options.profile.deceleration_mode {
                DecelerationMode::Manual(point) => Some(point),
                _ => None,
            };
            let mut refill = move |run: &mut ContinuousInterpolation| {
                while run.free() > 0 && queued < segments.len() {
                    let result = match point {
                        Some(point) if queued + 1 == segments.len() => {
                            run.push_last(segments[queued], point)
                        }
                        _ => run.push(segments[queued]),
                    };
                    if result.is_err() {
                        // After a stop or a dry end: the rest is abandoned.
                        queued = segments.len();
                        break;
                    }
                    queued += 1;
                }
            };
            refill(&mut run);
            let first = run.state().into();
            drive_rows(options, first, visit, |stop| match stop {
                Some(kind) => {
                    run.stop(kind);
                    None
                }
                None => {
                    refill(&mut run);
                    Some((run.step().into(), run.is_complete()))
                }
            })
        }
    }
}

/// The cycle loop of a geometry that is not a line: `advance(Some(stop))` applies a stop,
/// `advance(None)` steps one cycle and returns its row and whether the run is complete.
fn drive_rows<E>(
    options: &Options,
    first: Row,
    mut visit: impl FnMut(u64, &Row) -> Result<(), E>,
    mut advance: impl FnMut(Option<StopKind>) -> Option<(Row, bool)>,
) -> Result<Ending, E> {
    visit(0, &first)?;
    let mut events = options.events.iter().peekable();
    let (mut cycle, mut complete) = (0u64, false);
    loop {
        match options.cycles {
            Some(cycles) if cycle >= cycles => return Ok(Ending::Done),
            Some(_) => {}
            None if events.peek().is_none() && complete => return Ok(Ending::Done),
            None if cycle >= MAX_CYCLES => return Ok(Ending::CutShort),
            None => {}
        }
        cycle += 1;
        while let Some(event) = events.next_if(|event| event.cycle <= cycle) {
            advance(Some(event.stop));
        }
        let (row, done) = advance(None).expect("a step returns a row");
        complete = done;
        visit(cycle, &row)?;
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
