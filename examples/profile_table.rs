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

mod cli;

use cli::{build, check_event, parse_args, simulate, Axis, Format, Options};
use profilegen::State;

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
    let mut last = (0, axis.state(), true);
    simulate(options, axis, |cycle, state| {
        // Every K-th row, and the last one whatever K.
        let due = cycle % options.every == 0;
        last = (cycle, *state, due);
        if due {
            write_row(out, options.format, cycle, state)?;
        }
        Ok(())
    })?;
    if !last.2 {
        write_row(out, options.format, last.0, &last.1)?;
    }
    out.flush()
}

fn main() -> ExitCode {
    let options = match parse_args(false) {
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
