//! The `profile_table` command line (SPEC §13): runs one generator from its options and a script
//! of timed events, and prints its states, one row per cycle, as they are computed.
//!
//! `cargo run --release --example profile_table -- --help` prints the usage below.

use std::ffi::OsString;
use std::io::{self, BufWriter, Write};
use std::process::ExitCode;

mod cli;

use cli::mcx514::Row;
use cli::{Ending, Format, Options, Program, Request};
use profilegen::State;

const HELP: &str = "\
profile_table: one motion-profile generator, cycle by cycle (SPEC §13)

USAGE:
    cargo run --release --example profile_table -- <MODE> [OPTIONS]

MODE:
    velocity       Juno velocity contouring      needs --velocity --acceleration
    trapezoidal    trapezoidal point-to-point    needs --destination --velocity --acceleration
    scurve         MC1451A S-curve               needs --destination --velocity --acceleration --jerk
    mcx514         NOVA MCX514 interpolation     needs --cycle-time --initial-speed --drive-speed
                                                 --acceleration, and --finish or --segment (its
                                                 options below)

OPTIONS (values are decimals in per-cycle units, rounded to the mode's registers):
    --velocity V         counts/cycle (velocity mode: signed target; others: maximum)
    --acceleration A     counts/cycle²
    --deceleration D     counts/cycle² (velocity, trapezoidal; default 0 = use A)
    --jerk J             counts/cycle³ (scurve)
    --destination X      counts (trapezoidal, scurve)
    --start-velocity S   counts/cycle (trapezoidal; default 0)
    --event N:KEY=VALUE[,KEY=VALUE…]
                         before cycle N is stepped, set the KEYs together as one command
                         (velocity, acceleration, deceleration, destination, jerk, start-velocity:
                         those the mode uses), or stop=smooth|abrupt; repeatable. An event the
                         chip refuses is reported on stderr and the run goes on.
    --cycles N           print exactly cycles 0…N, even past completion (default: until the move
                         is complete, or in velocity mode settled at its target, at most
                         10,000,000 cycles)
    --every K            print every K-th cycle (default 1); the last cycle is always printed
    --format FORMAT      table (default, aligned) | csv (decimal values) | raw (I32F32 bits)
    -h, --help           this text

Row 0 is the initial state; columns: cycle, position (counts), velocity (counts/cycle),
acceleration (counts/cycle²).

MCX514 MODE (SPEC §12: the chip's own units, converted with the cycle time):
    --cycle-time SECONDS        the cycle (the controller's timer tick)
    --initial-speed PPS         SV, 1 … 8,000,000 pps: the start and the end of the ramps
    --drive-speed PPS           DV, 1 … 8,000,000 pps
    --acceleration PPS_PER_S    AC, 1 … 536,870,911 pps/s
    --deceleration PPS_PER_S    DC (default AC; automatic deceleration needs DC = AC)
    --jerk PPS_PER_S2           JK, 1 … 1,073,741,823 pps/s²: the S-curve (default: trapezoidal)
    --decel-jerk PPS_PER_S2     DJ (default JK; automatic deceleration needs DJ = JK)
    --decel-point PULSES        manual deceleration point, in driving-axis (long-axis) pulses
    --no-decel                  deceleration disabled: DV from the start to the finish point
    --finish DX,DY[,DZ[,DU]]    linear interpolation of 2–4 axes to that relative finish point
    --centre CX,CY              with --finish DX,DY: circular interpolation around that
                                centre (relative to the start); --finish 0,0 is a full circle
    --direction cw|ccw          the circle's direction
    --segment line:DX,DY | --segment arc:CX,CY:FX,FY:cw|ccw
                                continuous interpolation on X and Y: the segments back to back,
                                each relative to the previous end (repeatable, in order; instead
                                of --finish); --decel-point counts from the last segment's start
    --event N:stop=smooth|abrupt
                                a stop before cycle N (the only events of this mode)
    --cycles, --every, --format as above.
Without --decel-point or --no-decel, deceleration is automatic (lines only: a circle or segments
need one of the two, as on the chip). The columns are the driving axis (position in
interpolation steps: long-axis pulses of a line, short-axis pulses of a circle; velocity,
acceleration, as above) and then every axis's pulse position relative to the start:
cycle,position,velocity,acceleration,x,y[,z,u].

EXIT STATUS:
    0  done    2  bad command line (one line on stderr, nothing on stdout)
    3  the move was cut short by the 10,000,000-cycle cap (a warning on stderr)

EXAMPLES:
    profile_table velocity --velocity 4 --acceleration 0.25 --deceleration 0.125 \\
        --event 20:velocity=6 --event 60:velocity=-2 --cycles 100 --every 10
    profile_table scurve --destination 400 --velocity 2.75 --acceleration 0.175 --jerk 0.0075 \\
        --event 40:stop=smooth --event 120:destination=0,velocity=2 --format csv
    profile_table trapezoidal --destination 1000 --velocity 8 --acceleration 0.5 \\
        --start-velocity 1 --event 100:destination=-500
    profile_table mcx514 --cycle-time 0.001 --initial-speed 500 --drive-speed 20000 \\
        --acceleration 65000 --decel-point 45000 --finish -20000,30000,-50000 --every 100
    profile_table mcx514 --cycle-time 0.001 --initial-speed 500 --drive-speed 20000 \\
        --acceleration 65000 --decel-point 53493 --finish 0,0 --centre 10000,0 --direction ccw
";

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

/// The `mcx514` header: the driving axis, then one column per axis.
fn write_mcx514_header(out: &mut impl Write, format: Format, axes: usize) -> io::Result<()> {
    const NAMES: [&str; 4] = ["x", "y", "z", "u"];
    match format {
        Format::Table => {
            write!(
                out,
                "{:>9} {:>22} {:>22} {:>22}",
                "cycle", "position", "velocity", "acceleration"
            )?;
            for name in &NAMES[..axes] {
                write!(out, " {name:>11}")?;
            }
        }
        Format::Csv | Format::Raw => {
            write!(out, "cycle,position,velocity,acceleration")?;
            for name in &NAMES[..axes] {
                write!(out, ",{name}")?;
            }
        }
    }
    writeln!(out)
}

/// One `mcx514` row: the driving axis as in the other modes, then each axis's pulses (integers
/// in every format).
fn write_mcx514_row(out: &mut impl Write, format: Format, cycle: u64, row: &Row) -> io::Result<()> {
    let state = &row.driving;
    match format {
        Format::Table => {
            write!(
                out,
                "{cycle:>9} {:>22} {:>22} {:>22}",
                state.position.to_string(),
                state.velocity.to_string(),
                state.acceleration.to_string()
            )?;
            for axis in &row.axes {
                write!(out, " {axis:>11}")?;
            }
        }
        Format::Csv => {
            write!(
                out,
                "{cycle},{},{},{}",
                state.position, state.velocity, state.acceleration
            )?;
            for axis in &row.axes {
                write!(out, ",{axis}")?;
            }
        }
        Format::Raw => {
            write!(
                out,
                "{cycle},{},{},{}",
                state.position.to_bits(),
                state.velocity.to_bits(),
                state.acceleration.to_bits()
            )?;
            for axis in &row.axes {
                write!(out, ",{axis}")?;
            }
        }
    }
    writeln!(out)
}

/// As [`run`], for the `mcx514` mode.
fn run_mcx514(options: &cli::mcx514::Options, out: &mut impl Write) -> io::Result<Ending> {
    write_mcx514_header(out, options.format, options.geometry.axes())?;
    let mut last: Option<(u64, Row)> = None;
    let ending = cli::mcx514::run(options, |cycle, row| {
        if cycle % options.every == 0 {
            last = None;
            write_mcx514_row(out, options.format, cycle, row)
        } else {
            last = Some((cycle, row.clone()));
            Ok(())
        }
    })?;
    if let Some((cycle, row)) = last {
        write_mcx514_row(out, options.format, cycle, &row)?;
    }
    out.flush()?;
    Ok(ending)
}

/// Prints the run as it is computed (buffered, so each row is not a system call), every K-th row
/// and the last one.
fn run(
    options: &Options,
    generator: &mut cli::Generator,
    out: &mut impl Write,
) -> io::Result<Ending> {
    write_header(out, options.format)?;
    let mut last: Option<(u64, State)> = None;
    let ending = cli::simulate(options, generator, |cycle, state| {
        if cycle % options.every == 0 {
            last = None;
            write_row(out, options.format, cycle, state)
        } else {
            last = Some((cycle, *state));
            Ok(())
        }
    })?;
    if let Some((cycle, state)) = last {
        write_row(out, options.format, cycle, &state)?;
    }
    out.flush()?;
    Ok(ending)
}

fn main() -> ExitCode {
    let arguments: Vec<OsString> = std::env::args_os().skip(1).collect();
    let options = match cli::parse(Program::Table, arguments) {
        Ok(Request::Help) => {
            print!("{HELP}");
            return ExitCode::SUCCESS;
        }
        Ok(Request::Run(options)) => options,
        Ok(Request::Mcx514(options)) => {
            let mut out = BufWriter::new(io::stdout().lock());
            return finish(run_mcx514(&options, &mut out));
        }
        Err(message) => return usage_error(&message),
    };
    let mut generator = match cli::generator(&options) {
        Ok(generator) => generator,
        Err(message) => return usage_error(&message),
    };
    let mut out = BufWriter::new(io::stdout().lock());
    finish(run(&options, &mut generator, &mut out))
}

/// The exit status of a run: its ending, or the output's error.
fn finish(result: io::Result<Ending>) -> ExitCode {
    match result {
        Ok(Ending::Done) => ExitCode::SUCCESS,
        Ok(Ending::CutShort) => {
            eprintln!("{}", cli::cut_short_warning());
            ExitCode::from(cli::CUT_SHORT)
        }
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
    ExitCode::from(cli::USAGE)
}
