//! The `profile_table` command line (SPEC §13): runs one generator from its options and a script
//! of timed events, and prints its states, one row per cycle.
//!
//! ```text
//! cargo run --release --example profile_table -- <MODE> [OPTIONS]
//! MODE: velocity | trapezoidal | scurve
//!   --velocity V  --acceleration A  --deceleration D  --jerk J  --destination X
//!   --start-velocity S  --event N:KEY=VALUE (repeatable)  --cycles N  --every K
//!   --format table|csv|raw
//! ```
//!
//! An event `N:KEY=VALUE` is applied before cycle N is stepped, so it first shows in row N (row 0
//! is the initial state; events at 0 and 1 both apply before the first step). Without `--cycles`
//! the run ends on the first cycle on which the generator is complete and no event is left, at
//! most 10,000,000 cycles. Bad arguments: one line on stderr, exit status 2, nothing on stdout. An
//! event the chip's rules refuse: one line on stderr, and the run goes on unchanged.

use std::io::{self, BufWriter, Write};
use std::process::ExitCode;

use fixed::types::I32F0;
use profilegen::format::juno::{Acceleration, TargetVelocity};
use profilegen::format::mc1451a::{Destination, Jerk, MaxVelocity, ScurveAcceleration};
use profilegen::{
    Error, ProfileGenerator, SCurve, ScurveParameters, State, StopKind, Trapezoidal,
    TrapezoidalParameters, VelocityContouring, VelocityParameters,
};

/// The longest run without `--cycles`.
const MAX_CYCLES: u64 = 10_000_000;

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Mode {
    Velocity,
    Trapezoidal,
    Scurve,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Format {
    Table,
    Csv,
    Raw,
}

/// What an event sets.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Command {
    Velocity(f64),
    Acceleration(f64),
    Deceleration(f64),
    Destination(f64),
    Jerk(f64),
    StartVelocity(f64),
    Stop(StopKind),
}

impl Command {
    fn name(self) -> &'static str {
        match self {
            Command::Velocity(_) => "velocity",
            Command::Acceleration(_) => "acceleration",
            Command::Deceleration(_) => "deceleration",
            Command::Destination(_) => "destination",
            Command::Jerk(_) => "jerk",
            Command::StartVelocity(_) => "start-velocity",
            Command::Stop(_) => "stop",
        }
    }
}

#[derive(Debug, Clone)]
struct Options {
    mode: Mode,
    velocity: Option<f64>,
    acceleration: Option<f64>,
    deceleration: Option<f64>,
    jerk: Option<f64>,
    destination: Option<f64>,
    start_velocity: Option<f64>,
    events: Vec<(u64, Command)>,
    cycles: Option<u64>,
    every: u64,
    format: Format,
}

/// A generator the table can drive: a [`ProfileGenerator`] that takes the events' commands.
trait Axis: ProfileGenerator {
    /// Applies a command, or says why the chip refuses it.
    fn apply(&mut self, command: Command) -> Result<(), Error>;
}

impl Axis for VelocityContouring {
    fn apply(&mut self, command: Command) -> Result<(), Error> {
        match command {
            Command::Velocity(v) => self.set_velocity(TargetVelocity::from_num(v)?),
            Command::Acceleration(a) => self.set_acceleration(Acceleration::from_num(a)?)?,
            Command::Deceleration(d) => self.set_deceleration(Acceleration::from_num(d)?),
            Command::Stop(kind) => self.stop(kind),
            other => {
                return Err(Error::Refused {
                    parameter: other.name(),
                    reason: "in velocity mode",
                })
            }
        }
        Ok(())
    }
}

impl Axis for Trapezoidal {
    fn apply(&mut self, command: Command) -> Result<(), Error> {
        match command {
            Command::Destination(x) => self.set_destination(destination(x)?),
            Command::Velocity(v) => self.set_max_velocity(TargetVelocity::from_num(v)?)?,
            Command::Acceleration(a) => self.set_acceleration(Acceleration::from_num(a)?)?,
            Command::Deceleration(d) => self.set_deceleration(Acceleration::from_num(d)?),
            Command::StartVelocity(s) => self.set_start_velocity(TargetVelocity::from_num(s)?)?,
            Command::Stop(kind) => self.stop(kind),
            Command::Jerk(_) => {
                return Err(Error::Refused {
                    parameter: "jerk",
                    reason: "in trapezoidal mode",
                })
            }
        }
        Ok(())
    }
}

impl Axis for SCurve {
    fn apply(&mut self, command: Command) -> Result<(), Error> {
        match command {
            Command::Destination(x) => self.set_destination(Destination::from_num(x)?),
            Command::Velocity(v) => self.set_max_velocity(MaxVelocity::from_num(v)?),
            Command::Acceleration(a) => self.set_max_acceleration(ScurveAcceleration::from_num(a)?),
            Command::Jerk(j) => self.set_jerk(Jerk::from_num(j)?),
            Command::Stop(kind) => {
                self.stop(kind);
                Ok(())
            }
            other => Err(Error::Refused {
                parameter: other.name(),
                reason: "in S-curve mode",
            }),
        }
    }
}

/// A destination in counts: a signed 32-bit integer, rounded to nearest (ties to even).
fn destination(value: f64) -> Result<i32, Error> {
    I32F0::checked_from_num(value)
        .map(I32F0::to_num)
        .ok_or(Error::OutOfRange {
            parameter: "destination",
            range: "-2147483648 … 2147483647 counts",
        })
}

/// Converts an option's value to a register, naming the option in the error.
fn register<R>(
    option: &str,
    value: Option<f64>,
    convert: fn(f64) -> Result<R, Error>,
) -> Result<R, String> {
    convert(value.unwrap_or(0.0)).map_err(|error| format!("{option}: {error}"))
}

/// Builds the generator of the chosen mode from the options.
fn build(options: &Options) -> Result<Box<dyn Axis>, String> {
    match options.mode {
        Mode::Velocity => {
            let parameters = VelocityParameters {
                velocity: register("--velocity", options.velocity, TargetVelocity::from_num)?,
                acceleration: register(
                    "--acceleration",
                    options.acceleration,
                    Acceleration::from_num,
                )?,
                deceleration: register(
                    "--deceleration",
                    options.deceleration,
                    Acceleration::from_num,
                )?,
            };
            let axis = VelocityContouring::new(parameters)
                .map_err(|error| format!("--acceleration: {error}"))?;
            Ok(Box::new(axis))
        }
        Mode::Trapezoidal => {
            let parameters = TrapezoidalParameters {
                destination: register("--destination", options.destination, destination)?,
                max_velocity: register("--velocity", options.velocity, TargetVelocity::from_num)?,
                acceleration: register(
                    "--acceleration",
                    options.acceleration,
                    Acceleration::from_num,
                )?,
                deceleration: register(
                    "--deceleration",
                    options.deceleration,
                    Acceleration::from_num,
                )?,
                start_velocity: register(
                    "--start-velocity",
                    options.start_velocity,
                    TargetVelocity::from_num,
                )?,
            };
            let axis = Trapezoidal::new(parameters)
                .map_err(|error| format!("{}: {error}", option_of(&error)))?;
            Ok(Box::new(axis))
        }
        Mode::Scurve => {
            let parameters = ScurveParameters {
                destination: register("--destination", options.destination, Destination::from_num)?,
                max_velocity: register("--velocity", options.velocity, MaxVelocity::from_num)?,
                max_acceleration: register(
                    "--acceleration",
                    options.acceleration,
                    ScurveAcceleration::from_num,
                )?,
                jerk: register("--jerk", options.jerk, Jerk::from_num)?,
            };
            let axis = SCurve::new(parameters)
                .map_err(|error| format!("{}: {error}", option_of(&error)))?;
            Ok(Box::new(axis))
        }
    }
}

/// The command-line option that sets the parameter an error names.
fn option_of(error: &Error) -> String {
    let parameter = match *error {
        Error::OutOfRange { parameter, .. }
        | Error::NotFinite { parameter, .. }
        | Error::Zero { parameter, .. } => parameter,
        _ => "value",
    };
    format!("--{}", parameter.replace(' ', "-"))
}

/// Checks that an event's value fits its register in this mode (so a bad value is an argument
/// error, found before anything is printed), by applying it to a scratch generator.
fn check_event(options: &Options, command: Command) -> Result<(), String> {
    let mut scratch = build(options)?;
    match scratch.apply(command) {
        // Zero rates and refusals in motion are the chip's business at run time, not bad input.
        Err(Error::Zero { .. } | Error::Refused { .. }) | Ok(()) => Ok(()),
        Err(error) => Err(format!("--event {}: {error}", command.name())),
    }
}

fn parse_number(option: &str, text: &str) -> Result<f64, String> {
    let value: f64 = text
        .trim()
        .parse()
        .map_err(|_| format!("{option}: '{text}' is not a decimal number"))?;
    if !value.is_finite() {
        return Err(format!("{option}: '{text}' is not a finite number"));
    }
    Ok(value)
}

fn parse_count(option: &str, text: &str) -> Result<u64, String> {
    text.trim()
        .parse()
        .map_err(|_| format!("{option}: '{text}' is not a whole number of cycles"))
}

fn parse_event(text: &str) -> Result<(u64, Command), String> {
    let malformed = || format!("--event: '{text}' is not N:KEY=VALUE");
    let (cycle, assignment) = text.split_once(':').ok_or_else(malformed)?;
    let (key, value) = assignment.split_once('=').ok_or_else(malformed)?;
    let cycle = parse_count("--event", cycle)?;
    let option = format!("--event {key}");
    let command = match key.trim() {
        "velocity" => Command::Velocity(parse_number(&option, value)?),
        "acceleration" => Command::Acceleration(parse_number(&option, value)?),
        "deceleration" => Command::Deceleration(parse_number(&option, value)?),
        "destination" => Command::Destination(parse_number(&option, value)?),
        "jerk" => Command::Jerk(parse_number(&option, value)?),
        "start-velocity" | "start_velocity" => Command::StartVelocity(parse_number(&option, value)?),
        "stop" => match value.trim() {
            "smooth" => Command::Stop(StopKind::Smooth),
            "abrupt" => Command::Stop(StopKind::Abrupt),
            other => return Err(format!("--event stop: '{other}' is not smooth or abrupt")),
        },
        other => return Err(format!("--event: unknown key '{other}' (velocity, acceleration, deceleration, destination, jerk, stop)")),
    };
    Ok((cycle, command))
}

fn parse_args() -> Result<Options, String> {
    use lexopt::prelude::*;
    let mut parser = lexopt::Parser::from_env();
    let mut mode = None;
    let mut options = Options {
        mode: Mode::Velocity,
        velocity: None,
        acceleration: None,
        deceleration: None,
        jerk: None,
        destination: None,
        start_velocity: None,
        events: Vec::new(),
        cycles: None,
        every: 1,
        format: Format::Table,
    };
    loop {
        // Own the option's name so the parser is free to read its value.
        let name = match parser.next().map_err(|e| e.to_string())? {
            None => break,
            Some(Long(name)) => format!("--{name}"),
            Some(Value(word)) if mode.is_none() => {
                mode = Some(match word.to_str() {
                    Some("velocity") => Mode::Velocity,
                    Some("trapezoidal") => Mode::Trapezoidal,
                    Some("scurve") => Mode::Scurve,
                    _ => {
                        return Err(format!(
                            "MODE: '{}' is not velocity, trapezoidal or scurve",
                            word.to_string_lossy()
                        ))
                    }
                });
                continue;
            }
            Some(other) => return Err(other.unexpected().to_string()),
        };
        let text = parser
            .value()
            .map_err(|_| format!("{name}: missing value"))?
            .into_string()
            .map_err(|_| format!("{name}: not valid text"))?;
        let number = || parse_number(&name, &text);
        match name.as_str() {
            "--velocity" => options.velocity = Some(number()?),
            "--acceleration" => options.acceleration = Some(number()?),
            "--deceleration" => options.deceleration = Some(number()?),
            "--jerk" => options.jerk = Some(number()?),
            "--destination" => options.destination = Some(number()?),
            "--start-velocity" => options.start_velocity = Some(number()?),
            "--event" => options.events.push(parse_event(&text)?),
            "--cycles" => options.cycles = Some(parse_count(&name, &text)?),
            "--every" => {
                options.every = parse_count(&name, &text)?;
                if options.every == 0 {
                    return Err("--every: must be at least 1".into());
                }
            }
            "--format" => {
                options.format = match text.as_str() {
                    "table" => Format::Table,
                    "csv" => Format::Csv,
                    "raw" => Format::Raw,
                    other => return Err(format!("--format: '{other}' is not table, csv or raw")),
                }
            }
            _ => return Err(format!("{name}: unknown option")),
        }
    }
    options.mode = mode.ok_or("MODE: missing (velocity, trapezoidal or scurve)")?;
    // Stable sort: events for the same cycle apply in the order given.
    options.events.sort_by_key(|&(cycle, _)| cycle);
    Ok(options)
}

fn write_row(out: &mut impl Write, format: Format, cycle: u64, state: &State) -> io::Result<()> {
    match format {
        Format::Table => writeln!(
            out,
            "{cycle:>9} {:>22} {:>22} {:>22}",
            state.position.to_string(),
            state.velocity.to_string(),
            state.acceleration.to_string()
        ),
        Format::Csv => writeln!(
            out,
            "{cycle},{},{},{}",
            state.position, state.velocity, state.acceleration
        ),
        Format::Raw => writeln!(
            out,
            "{cycle},{},{},{}",
            state.position.to_bits(),
            state.velocity.to_bits(),
            state.acceleration.to_bits()
        ),
    }
}

fn write_header(out: &mut impl Write, format: Format) -> io::Result<()> {
    match format {
        Format::Table => writeln!(
            out,
            "{:>9} {:>22} {:>22} {:>22}",
            "cycle", "position", "velocity", "acceleration"
        ),
        Format::Csv | Format::Raw => writeln!(out, "cycle,position,velocity,acceleration"),
    }
}

fn run(options: &Options, axis: &mut dyn Axis, out: &mut impl Write) -> io::Result<()> {
    write_header(out, options.format)?;
    write_row(out, options.format, 0, &axis.state())?;
    let mut events = options.events.iter().peekable();
    let mut cycle = 0u64;
    let mut last_printed = true;
    let mut state = axis.state();
    loop {
        let pending = events.peek().is_some();
        let finished = match options.cycles {
            Some(cycles) => cycle >= cycles,
            None => cycle >= MAX_CYCLES || (axis.is_complete() && !pending),
        };
        if finished {
            break;
        }
        cycle += 1;
        while let Some(&&(_, command)) = events.peek().filter(|&&&(at, _)| at <= cycle) {
            events.next();
            if let Err(error) = axis.apply(command) {
                eprintln!("cycle {cycle}: {} event refused: {error}", command.name());
            }
        }
        state = axis.step();
        last_printed = cycle % options.every == 0;
        if last_printed {
            write_row(out, options.format, cycle, &state)?;
        }
    }
    if !last_printed {
        write_row(out, options.format, cycle, &state)?;
    }
    out.flush()
}

fn main() -> ExitCode {
    let options = match parse_args() {
        Ok(options) => options,
        Err(message) => return usage_error(&message),
    };
    let mut axis = match build(&options) {
        Ok(axis) => axis,
        Err(message) => return usage_error(&message),
    };
    for &(_, command) in &options.events {
        if let Err(message) = check_event(&options, command) {
            return usage_error(&message);
        }
    }
    let stdout = io::stdout();
    let mut out = BufWriter::new(stdout.lock());
    match run(&options, axis.as_mut(), &mut out) {
        Ok(()) => ExitCode::SUCCESS,
        // A closed pipe (`| head`) is the reader's choice, not an error.
        Err(error) if error.kind() == io::ErrorKind::BrokenPipe => ExitCode::SUCCESS,
        Err(error) => {
            eprintln!("error: {error}");
            ExitCode::FAILURE
        }
    }
}

fn usage_error(message: &str) -> ExitCode {
    eprintln!("error: {message}");
    ExitCode::from(2)
}
