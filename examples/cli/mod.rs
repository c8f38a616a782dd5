//! The command line shared by `profile_table` and `plot` (SPEC §13): modes, options, events, the
//! generator each mode builds, and the run through the events.
//!
//! Parsing is lexopt's (it splits the words, `--name value` and `--name=value`); what this module
//! adds is the contract: which options each mode takes, their values converted to the mode's
//! registers before anything runs, and every mistake reported as one line naming the option and
//! the value given (exit status 2).

pub mod mcx514;

use std::collections::BTreeMap;
use std::ffi::OsString;

use fixed::types::{I32F0, I32F32};
use profilegen::format::juno::{Acceleration, TargetVelocity};
use profilegen::format::mc1451a::{Destination, Jerk, MaxVelocity, ScurveAcceleration};
use profilegen::{
    Error, ProfileGenerator, SCurve, ScurveParameters, State, StopKind, Trapezoidal,
    TrapezoidalParameters, VelocityContouring, VelocityParameters,
};

/// The longest run without `--cycles`.
pub const MAX_CYCLES: u64 = 10_000_000;

/// Exit status of a bad command line.
pub const USAGE: u8 = 2;
/// Exit status of a move cut short by [`MAX_CYCLES`].
pub const CUT_SHORT: u8 = 3;

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Mode {
    Velocity,
    Trapezoidal,
    Scurve,
}

impl Mode {
    fn name(self) -> &'static str {
        match self {
            Mode::Velocity => "velocity",
            Mode::Trapezoidal => "trapezoidal",
            Mode::Scurve => "scurve",
        }
    }
}

/// Which example is parsing: each has options of its own besides the shared ones.
#[allow(dead_code)] // each example constructs its own
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Program {
    /// `profile_table`: `--cycles`, `--every`, `--format`.
    Table,
    /// `plot`: `--cycles`, `--output`, `--cycle-time`.
    Plot,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Format {
    Table,
    Csv,
    Raw,
}

/// One profile parameter, as an option (`--start-velocity`) and as an event key
/// (`start-velocity=`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub enum Key {
    Velocity,
    Acceleration,
    Deceleration,
    Destination,
    Jerk,
    StartVelocity,
}

impl Key {
    const ALL: [Key; 6] = [
        Key::Velocity,
        Key::Acceleration,
        Key::Deceleration,
        Key::Destination,
        Key::Jerk,
        Key::StartVelocity,
    ];

    pub fn name(self) -> &'static str {
        match self {
            Key::Velocity => "velocity",
            Key::Acceleration => "acceleration",
            Key::Deceleration => "deceleration",
            Key::Destination => "destination",
            Key::Jerk => "jerk",
            Key::StartVelocity => "start-velocity",
        }
    }

    fn from_name(name: &str) -> Option<Key> {
        Key::ALL.into_iter().find(|key| key.name() == name)
    }

    /// Whether `mode` uses this parameter.
    fn used_by(self, mode: Mode) -> bool {
        match self {
            Key::Velocity | Key::Acceleration => true,
            Key::Deceleration => mode != Mode::Scurve,
            Key::Destination => mode != Mode::Velocity,
            Key::Jerk => mode == Mode::Scurve,
            Key::StartVelocity => mode == Mode::Trapezoidal,
        }
    }

    /// Whether `mode` needs this parameter on the command line (the others default to zero, which
    /// for a deceleration means "use the acceleration" and for a starting velocity "from rest").
    fn required_by(self, mode: Mode) -> bool {
        self.used_by(mode) && !matches!(self, Key::Deceleration | Key::StartVelocity)
    }

    /// The key a library error's parameter name stands for.
    fn of_parameter(parameter: &str) -> Option<Key> {
        Key::from_name(&parameter.replace(' ', "-"))
    }
}

/// What an event sets, all at once: one command to the chip.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Change {
    /// The parameters it sets, each with the value given.
    pub values: BTreeMap<Key, f64>,
    /// A stop instead of parameters.
    pub stop: Option<StopKind>,
}

/// A change applied before a cycle is stepped, and the text it was given as (for messages).
#[derive(Debug, Clone)]
pub struct Event {
    pub cycle: u64,
    pub change: Change,
    pub text: String,
}

#[derive(Debug, Clone)]
pub struct Options {
    pub mode: Mode,
    /// The parameters given as options, each with its text as given.
    pub values: BTreeMap<Key, (f64, String)>,
    /// In the order of their cycles; events for the same cycle in the order given.
    pub events: Vec<Event>,
    pub cycles: Option<u64>,
    pub every: u64,
    pub format: Format,
    /// `--output FILE` (plot).
    pub output: Option<String>,
    /// `--cycle-time SECONDS` (plot).
    pub cycle_time: Option<f64>,
}

impl Options {
    /// The value of a parameter option, zero when absent (only optional ones are ever absent).
    pub fn value(&self, key: Key) -> f64 {
        self.values.get(&key).map_or(0.0, |(value, _)| *value)
    }
}

/// What the command line asks for.
pub enum Request {
    Help,
    Run(Options),
    /// The `mcx514` mode: an interpolation, with options of its own (boxed: its geometry, an
    /// arc with its per-octant tables, is much larger than the other modes' options).
    Mcx514(Box<mcx514::Options>),
}

/// A one-line message about the command line.
pub type Usage = String;

fn number(option: &str, text: &str) -> Result<f64, Usage> {
    let value: f64 = text
        .trim()
        .parse()
        .map_err(|_| format!("{option} '{text}': not a decimal number"))?;
    if !value.is_finite() {
        return Err(format!("{option} '{text}': not a finite number"));
    }
    Ok(value)
}

fn whole(option: &str, text: &str) -> Result<u64, Usage> {
    text.trim()
        .parse()
        .map_err(|_| format!("{option} '{text}': not a whole number of cycles (0 … 2^64 − 1)"))
}

/// `N:KEY=VALUE[,KEY=VALUE…]`, the keys checked against the mode.
fn parse_event(mode: Mode, text: &str) -> Result<Event, Usage> {
    let malformed = || format!("--event '{text}': not N:KEY=VALUE[,KEY=VALUE…]");
    let (cycle, assignments) = text.split_once(':').ok_or_else(malformed)?;
    let cycle = whole("--event", cycle).map_err(|_| {
        format!("--event '{text}': '{cycle}' is not a cycle number (a whole number)")
    })?;
    let mut change = Change::default();
    for assignment in assignments.split(',') {
        let (key, value) = assignment.split_once('=').ok_or_else(malformed)?;
        let (key, value) = (key.trim(), value.trim());
        if key == "stop" {
            change.stop = Some(match value {
                "smooth" => StopKind::Smooth,
                "abrupt" => StopKind::Abrupt,
                _ => {
                    return Err(format!(
                        "--event '{text}': stop '{value}' is not smooth or abrupt"
                    ))
                }
            });
            continue;
        }
        let parameter = Key::from_name(key).ok_or_else(|| {
            format!(
                "--event '{text}': unknown key '{key}' (velocity, acceleration, deceleration, \
                 destination, jerk, start-velocity, stop)"
            )
        })?;
        if !parameter.used_by(mode) {
            return Err(format!(
                "--event '{text}': {key} is not used in {} mode",
                mode.name()
            ));
        }
        let value = number(&format!("--event '{text}': {key}"), value)?;
        if change.values.insert(parameter, value).is_some() {
            return Err(format!("--event '{text}': {key} is given twice"));
        }
    }
    if change.stop.is_some() && !change.values.is_empty() {
        return Err(format!(
            "--event '{text}': a stop is a command of its own; give the other keys at another \
             cycle"
        ));
    }
    Ok(Event {
        cycle,
        change,
        text: text.to_owned(),
    })
}

/// The mode word: one of the one-axis modes, or `mcx514`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum ModeWord {
    Profile(Mode),
    Mcx514,
}

fn mode_of(word: &str) -> Result<ModeWord, Usage> {
    match word {
        "velocity" => Ok(ModeWord::Profile(Mode::Velocity)),
        "trapezoidal" => Ok(ModeWord::Profile(Mode::Trapezoidal)),
        "scurve" => Ok(ModeWord::Profile(Mode::Scurve)),
        "mcx514" => Ok(ModeWord::Mcx514),
        _ => Err(format!(
            "MODE '{word}': not a mode (velocity, trapezoidal, scurve or mcx514)"
        )),
    }
}

/// Parses the command line of `program` (without the program name).
pub fn parse(program: Program, arguments: Vec<OsString>) -> Result<Request, Usage> {
    use lexopt::prelude::*;
    // `--help` wins wherever it stands, so a half-written command line still gets the usage.
    if arguments.iter().any(|a| a == "--help" || a == "-h") {
        return Ok(Request::Help);
    }
    let mut parser = lexopt::Parser::from_args(arguments);
    let mut mode = None;
    let mut words: Vec<(String, String)> = Vec::new();
    while let Some(argument) = parser.next().map_err(|e| e.to_string())? {
        let name = match argument {
            Long(name) => format!("--{name}"),
            Short(letter) => return Err(format!("-{letter}: unknown option (see --help)")),
            Value(word) => {
                let word = word.to_string_lossy().into_owned();
                if mode.is_some() {
                    return Err(format!("'{word}': unexpected argument (see --help)"));
                }
                mode = Some(mode_of(&word)?);
                continue;
            }
        };
        // Known to some mode: which mode takes it is checked once the mode is known.
        let known = matches!(name.as_str(), "--event" | "--cycles")
            || name
                .strip_prefix("--")
                .is_some_and(|n| Key::from_name(n).is_some())
            || mcx514::OPTIONS.contains(&name.as_str())
            || match program {
                Program::Table => matches!(name.as_str(), "--every" | "--format"),
                Program::Plot => matches!(name.as_str(), "--output" | "--cycle-time"),
            };
        if !known {
            return Err(format!("{name}: unknown option (see --help)"));
        }
        if name == "--no-decel" {
            // A flag: it takes no value.
            words.push((name, String::new()));
            continue;
        }
        let text = parser
            .value()
            .map_err(|_| format!("{name}: missing value"))?
            .into_string()
            .map_err(|text| format!("{name} '{}': not valid text", text.to_string_lossy()))?;
        words.push((name, text));
    }
    let mode = match mode
        .ok_or("MODE: missing (velocity, trapezoidal, scurve or mcx514; see --help)".to_owned())?
    {
        ModeWord::Mcx514 => {
            return mcx514::parse(program, words).map(|options| Request::Mcx514(Box::new(options)))
        }
        ModeWord::Profile(mode) => mode,
    };
    let mut options = Options {
        mode,
        values: BTreeMap::new(),
        events: Vec::new(),
        cycles: None,
        every: 1,
        format: Format::Table,
        output: None,
        cycle_time: None,
    };
    let mut seen = Vec::new();
    for (name, text) in words {
        if name != "--event" {
            if seen.contains(&name) {
                return Err(format!("{name} '{text}': given twice"));
            }
            seen.push(name.clone());
        }
        if mcx514::OPTIONS.contains(&name.as_str())
            && !(name == "--event" || program == Program::Plot && name == "--cycle-time")
        {
            // A flag has no value to show.
            let given = if name == "--no-decel" {
                name.clone()
            } else {
                format!("{name} '{text}'")
            };
            return Err(format!(
                "{given}: not used in {} mode (see --help)",
                mode.name()
            ));
        }
        match name.as_str() {
            "--event" => options.events.push(parse_event(mode, &text)?),
            "--cycles" => options.cycles = Some(whole(&name, &text)?),
            "--every" => {
                options.every = whole(&name, &text)?;
                if options.every == 0 {
                    return Err(format!("{name} '{text}': must be at least 1"));
                }
            }
            "--format" => {
                options.format = match text.as_str() {
                    "table" => Format::Table,
                    "csv" => Format::Csv,
                    "raw" => Format::Raw,
                    _ => return Err(format!("{name} '{text}': not table, csv or raw")),
                }
            }
            "--output" => options.output = Some(text),
            "--cycle-time" => {
                let seconds = number(&name, &text)?;
                profilegen::format::CycleTime::from_seconds(seconds)
                    .map_err(|error| format!("{name} '{text}': {error}"))?;
                options.cycle_time = Some(seconds);
            }
            _ => {
                // A parameter: `known` above let only the keys through.
                let key = Key::from_name(&name[2..]).expect("checked when read");
                if !key.used_by(mode) {
                    return Err(format!(
                        "{name} '{text}': not used in {} mode (see --help)",
                        mode.name()
                    ));
                }
                options.values.insert(key, (number(&name, &text)?, text));
            }
        }
    }
    if let Some(key) = Key::ALL
        .into_iter()
        .find(|key| key.required_by(mode) && !options.values.contains_key(key))
    {
        return Err(format!(
            "--{}: missing ({} mode needs it; see --help)",
            key.name(),
            mode.name()
        ));
    }
    if program == Program::Plot && options.output.is_none() {
        return Err("--output: missing (the SVG file to write)".into());
    }
    // Stable sort: events for the same cycle apply in the order given.
    options.events.sort_by_key(|event| event.cycle);
    Ok(Request::Run(options))
}

/// A generator of one of the modes.
// One per run (and a copy per event): boxing the S-curve would save nothing.
#[allow(clippy::large_enum_variant)]
#[derive(Clone)]
pub enum Generator {
    Velocity(VelocityContouring),
    Trapezoidal(Trapezoidal),
    Scurve(SCurve),
}

/// A destination for the trapezoid: a signed 32-bit count, rounded to nearest (ties to even).
fn trapezoid_destination(value: f64) -> Result<i32, Error> {
    I32F0::checked_from_num(value)
        .map(I32F0::to_num)
        .ok_or(Error::OutOfRange {
            parameter: "destination",
            value,
            range: profilegen::Range::of_register(i32::MIN.into(), i32::MAX.into(), 0, "counts"),
        })
}

impl Generator {
    /// The generator of the options' mode and parameters.
    ///
    /// # Errors
    /// A register that does not hold its value, or parameters that cannot make a move.
    pub fn new(options: &Options) -> Result<Self, Error> {
        let value = |key| options.value(key);
        Ok(match options.mode {
            Mode::Velocity => Generator::Velocity(VelocityContouring::new(VelocityParameters {
                velocity: TargetVelocity::from_num(value(Key::Velocity))?,
                acceleration: Acceleration::from_num(value(Key::Acceleration))?,
                deceleration: Acceleration::from_num(value(Key::Deceleration))?,
            })?),
            Mode::Trapezoidal => Generator::Trapezoidal(Trapezoidal::new(TrapezoidalParameters {
                destination: trapezoid_destination(value(Key::Destination))?,
                max_velocity: TargetVelocity::from_num(value(Key::Velocity))?,
                acceleration: Acceleration::from_num(value(Key::Acceleration))?,
                deceleration: Acceleration::from_num(value(Key::Deceleration))?,
                start_velocity: TargetVelocity::from_num(value(Key::StartVelocity))?,
            })?),
            Mode::Scurve => Generator::Scurve(SCurve::new(ScurveParameters {
                destination: Destination::from_num(value(Key::Destination))?.to_bits(),
                max_velocity: MaxVelocity::from_num(value(Key::Velocity))?,
                max_acceleration: ScurveAcceleration::from_num(value(Key::Acceleration))?,
                jerk: Jerk::from_num(value(Key::Jerk))?,
            })?),
        })
    }

    pub fn axis(&mut self) -> &mut dyn ProfileGenerator {
        match self {
            Generator::Velocity(axis) => axis,
            Generator::Trapezoidal(axis) => axis,
            Generator::Scurve(axis) => axis,
        }
    }

    /// Applies a change as one command: all of it, or (on an error) none of it.
    ///
    /// # Errors
    /// A value its register does not hold, or a command the chip refuses.
    pub fn apply(&mut self, change: &Change) -> Result<(), Error> {
        if let Some(kind) = change.stop {
            self.axis().stop(kind);
            return Ok(());
        }
        // Applied to a copy, kept only if every part succeeds.
        let mut next = self.clone();
        let given = |key| change.values.get(&key).copied();
        match &mut next {
            Generator::Velocity(axis) => {
                if let Some(a) = given(Key::Acceleration) {
                    axis.set_acceleration(Acceleration::from_num(a)?)?;
                }
                if let Some(d) = given(Key::Deceleration) {
                    axis.set_deceleration(Acceleration::from_num(d)?);
                }
                if let Some(v) = given(Key::Velocity) {
                    axis.set_velocity(TargetVelocity::from_num(v)?);
                }
            }
            Generator::Trapezoidal(axis) => {
                if let Some(x) = given(Key::Destination) {
                    axis.set_destination(trapezoid_destination(x)?);
                }
                if let Some(a) = given(Key::Acceleration) {
                    axis.set_acceleration(Acceleration::from_num(a)?)?;
                }
                if let Some(d) = given(Key::Deceleration) {
                    axis.set_deceleration(Acceleration::from_num(d)?);
                }
                // The maximum velocity last: after a stop it is the one that restarts motion, so
                // the move it starts sees the other new values. The starting velocity is checked
                // against the maximum, so it comes after it when both change.
                if let Some(v) = given(Key::Velocity) {
                    axis.set_max_velocity(TargetVelocity::from_num(v)?)?;
                }
                if let Some(s) = given(Key::StartVelocity) {
                    axis.set_start_velocity(TargetVelocity::from_num(s)?)?;
                }
            }
            Generator::Scurve(axis) => {
                // The MC1451A takes a move's parameters together: one plan for all of them.
                let old = axis.parameters();
                let parameters = ScurveParameters {
                    destination: given(Key::Destination).map_or(Ok(old.destination), |x| {
                        Destination::from_num(x).map(Destination::to_bits)
                    })?,
                    max_velocity: given(Key::Velocity)
                        .map_or(Ok(old.max_velocity), MaxVelocity::from_num)?,
                    max_acceleration: given(Key::Acceleration)
                        .map_or(Ok(old.max_acceleration), ScurveAcceleration::from_num)?,
                    jerk: given(Key::Jerk).map_or(Ok(old.jerk), Jerk::from_num)?,
                };
                if given(Key::Destination).is_some() && given(Key::Velocity).is_none() {
                    // Without a velocity the chip's rules for a lone destination hold (refused
                    // after a stop, which cleared the velocity register): asked of a copy.
                    axis.clone().set_destination(parameters.destination)?;
                }
                axis.set_parameters(parameters)?;
            }
        }
        *self = next;
        Ok(())
    }

    /// Whether the run can end here: complete, or (velocity mode, which completes only at rest)
    /// cruising at the target velocity, where every later cycle is the same but for position.
    fn settled(&mut self) -> bool {
        if let Generator::Velocity(axis) = self {
            let state = axis.state();
            let target = I32F32::from_num(axis.parameters().velocity.to_fixed());
            if state.velocity == target && state.acceleration == I32F32::ZERO {
                return true;
            }
        }
        self.axis().is_complete()
    }
}

/// How a run ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Ending {
    /// `--cycles` reached, or the move complete (settled, in velocity mode).
    Done,
    /// [`MAX_CYCLES`] reached while still moving.
    CutShort,
}

/// Runs the generator through the options' events, calling `visit` with row 0 (the initial
/// state) and then each cycle's state. An event at cycle N applies before cycle N is stepped; one
/// the chip refuses is reported on stderr and the run goes on. Without `--cycles` the run ends on
/// the first cycle on which the generator is settled and no event is left, or at [`MAX_CYCLES`].
pub fn simulate<E>(
    options: &Options,
    generator: &mut Generator,
    visit: impl FnMut(u64, &State) -> Result<(), E>,
) -> Result<Ending, E> {
    run(options, generator, true, visit)
}

/// As [`simulate`], without reporting refused events (for a pass that is repeated).
#[allow(dead_code)] // plot's, not profile_table's
pub fn simulate_quietly<E>(
    options: &Options,
    generator: &mut Generator,
    visit: impl FnMut(u64, &State) -> Result<(), E>,
) -> Result<Ending, E> {
    run(options, generator, false, visit)
}

fn run<E>(
    options: &Options,
    generator: &mut Generator,
    report: bool,
    mut visit: impl FnMut(u64, &State) -> Result<(), E>,
) -> Result<Ending, E> {
    visit(0, &generator.axis().state())?;
    let mut events = options.events.iter().peekable();
    let mut cycle = 0u64;
    loop {
        match options.cycles {
            Some(cycles) if cycle >= cycles => return Ok(Ending::Done),
            Some(_) => {}
            None if events.peek().is_none() && generator.settled() => return Ok(Ending::Done),
            None if cycle >= MAX_CYCLES => return Ok(Ending::CutShort),
            None => {}
        }
        cycle += 1;
        while let Some(event) = events.next_if(|event| event.cycle <= cycle) {
            match generator.apply(&event.change) {
                Err(error) if report => {
                    eprintln!("cycle {cycle}: event '{}' refused: {error}", event.text);
                }
                _ => {}
            }
        }
        visit(cycle, &generator.axis().step())?;
    }
}

/// The option a library error is about, with the text given for it.
fn blame(options: &Options, error: &Error) -> String {
    let parameter = match *error {
        Error::OutOfRange { parameter, .. }
        | Error::NotFinite { parameter, .. }
        | Error::Underflow { parameter, .. }
        | Error::Zero { parameter, .. }
        | Error::Unreachable { parameter, .. } => parameter,
        _ => "",
    };
    match Key::of_parameter(parameter) {
        Some(key) => match options.values.get(&key) {
            Some((_, text)) => format!("--{} '{text}': {error}", key.name()),
            None => format!("--{}: {error}", key.name()),
        },
        None => error.to_string(),
    }
}

/// The generator the options describe, every event checked against its registers: the part of
/// the contract that needs the library. Values a register can't hold are errors on the command
/// line; what the chip decides at run time (a zero rate, a change refused in motion) is not.
pub fn generator(options: &Options) -> Result<Generator, Usage> {
    let generator = Generator::new(options).map_err(|error| blame(options, &error))?;
    for event in &options.events {
        match generator.clone().apply(&event.change) {
            Ok(())
            | Err(Error::Zero { .. } | Error::Refused { .. } | Error::Unreachable { .. }) => {}
            Err(error) => return Err(format!("--event '{}': {error}", event.text)),
        }
    }
    Ok(generator)
}

/// The warning for a run cut short.
pub fn cut_short_warning() -> String {
    format!(
        "warning: the move was cut short at the cap of {MAX_CYCLES} cycles, still moving; give \
         --cycles N to run longer"
    )
}
