//! The command line shared by `profile_table` and `plot` (SPEC §13): modes, options, events, and
//! the generator each mode builds.

use fixed::types::I32F0;
use profilegen::format::juno::{Acceleration, TargetVelocity};
use profilegen::format::mc1451a::{Destination, Jerk, MaxVelocity, ScurveAcceleration};
use profilegen::{
    Error, ProfileGenerator, SCurve, ScurveParameters, StopKind, Trapezoidal,
    TrapezoidalParameters, VelocityContouring, VelocityParameters,
};

/// The longest run without `--cycles`.
pub const MAX_CYCLES: u64 = 10_000_000;

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Mode {
    Velocity,
    Trapezoidal,
    Scurve,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Format {
    Table,
    Csv,
    Raw,
}

/// What an event sets.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Command {
    Velocity(f64),
    Acceleration(f64),
    Deceleration(f64),
    Destination(f64),
    Jerk(f64),
    StartVelocity(f64),
    Stop(StopKind),
}

impl Command {
    pub fn name(self) -> &'static str {
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
pub struct Options {
    pub mode: Mode,
    pub velocity: Option<f64>,
    pub acceleration: Option<f64>,
    pub deceleration: Option<f64>,
    pub jerk: Option<f64>,
    pub destination: Option<f64>,
    pub start_velocity: Option<f64>,
    pub events: Vec<(u64, Command)>,
    pub cycles: Option<u64>,
    pub every: u64,
    pub format: Format,
    /// `--output FILE` (the `plot` example only).
    pub output: Option<String>,
}

/// A generator the table can drive: a [`ProfileGenerator`] that takes the events' commands.
pub trait Axis: ProfileGenerator {
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
pub fn destination(value: f64) -> Result<i32, Error> {
    I32F0::checked_from_num(value)
        .map(I32F0::to_num)
        .ok_or(Error::OutOfRange {
            parameter: "destination",
            value,
            range: profilegen::Range::of_register(i32::MIN.into(), i32::MAX.into(), 0, "counts"),
        })
}

/// Converts an option's value to a register, naming the option in the error.
pub fn register<R>(
    option: &str,
    value: Option<f64>,
    convert: fn(f64) -> Result<R, Error>,
) -> Result<R, String> {
    convert(value.unwrap_or(0.0)).map_err(|error| format!("{option}: {error}"))
}

/// `--acceleration` and `--deceleration` as Juno 8.24 rates (velocity and trapezoidal modes).
fn juno_rates(options: &Options) -> Result<(Acceleration, Acceleration), String> {
    Ok((
        register(
            "--acceleration",
            options.acceleration,
            Acceleration::from_num,
        )?,
        register(
            "--deceleration",
            options.deceleration,
            Acceleration::from_num,
        )?,
    ))
}

/// Builds the generator of the chosen mode from the options.
pub fn build(options: &Options) -> Result<Box<dyn Axis>, String> {
    match options.mode {
        Mode::Velocity => {
            let (acceleration, deceleration) = juno_rates(options)?;
            let parameters = VelocityParameters {
                velocity: register("--velocity", options.velocity, TargetVelocity::from_num)?,
                acceleration,
                deceleration,
            };
            let axis = VelocityContouring::new(parameters)
                .map_err(|error| format!("{}: {error}", option_of(&error)))?;
            Ok(Box::new(axis))
        }
        Mode::Trapezoidal => {
            let (acceleration, deceleration) = juno_rates(options)?;
            let parameters = TrapezoidalParameters {
                destination: register("--destination", options.destination, destination)?,
                max_velocity: register("--velocity", options.velocity, TargetVelocity::from_num)?,
                acceleration,
                deceleration,
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
pub fn option_of(error: &Error) -> String {
    let parameter = match *error {
        Error::OutOfRange { parameter, .. }
        | Error::NotFinite { parameter, .. }
        | Error::Underflow { parameter, .. }
        | Error::Zero { parameter, .. } => parameter,
        _ => "value",
    };
    format!("--{}", parameter.replace(' ', "-"))
}

/// Checks that an event's value fits its register in this mode (so a bad value is an argument
/// error, found before anything is printed), by applying it to a scratch generator.
pub fn check_event(options: &Options, command: Command) -> Result<(), String> {
    let mut scratch = build(options)?;
    match scratch.apply(command) {
        // Zero rates and refusals in motion are the chip's business at run time, not bad input.
        Err(Error::Zero { .. } | Error::Refused { .. }) | Ok(()) => Ok(()),
        Err(error) => Err(format!("--event {}: {error}", command.name())),
    }
}

pub fn parse_number(option: &str, text: &str) -> Result<f64, String> {
    let value: f64 = text
        .trim()
        .parse()
        .map_err(|_| format!("{option}: '{text}' is not a decimal number"))?;
    if !value.is_finite() {
        return Err(format!("{option}: '{text}' is not a finite number"));
    }
    Ok(value)
}

pub fn parse_count(option: &str, text: &str) -> Result<u64, String> {
    text.trim()
        .parse()
        .map_err(|_| format!("{option}: '{text}' is not a whole number of cycles"))
}

pub fn parse_event(text: &str) -> Result<(u64, Command), String> {
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

/// Parses the command line; `--output FILE` is accepted only when `allow_output`.
pub fn parse_args(allow_output: bool) -> Result<Options, String> {
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
        output: None,
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
            "--output" if allow_output => options.output = Some(text),
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

/// Runs the generator through the options' script, calling `visit` with row 0 (the initial
/// state) and then each cycle's state. An event `N:KEY=VALUE` applies before cycle N is stepped;
/// one the chip refuses is reported on stderr and the run goes on. Without `--cycles` the run ends
/// on the first cycle on which the generator is complete and no event is left, at most
/// [`MAX_CYCLES`].
pub fn simulate(
    options: &Options,
    axis: &mut dyn Axis,
    mut visit: impl FnMut(u64, &profilegen::State) -> std::io::Result<()>,
) -> std::io::Result<()> {
    visit(0, &axis.state())?;
    let mut events = options.events.iter().peekable();
    let mut cycle = 0u64;
    loop {
        let finished = match options.cycles {
            Some(cycles) => cycle >= cycles,
            None => cycle >= MAX_CYCLES || (axis.is_complete() && events.peek().is_none()),
        };
        if finished {
            return Ok(());
        }
        cycle += 1;
        while let Some(&&(_, command)) = events.peek().filter(|&&&(at, _)| at <= cycle) {
            events.next();
            if let Err(error) = axis.apply(command) {
                eprintln!("cycle {cycle}: {} event refused: {error}", command.name());
            }
        }
        visit(cycle, &axis.step())?;
    }
}
