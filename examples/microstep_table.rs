//! Prints one electrical cycle of a microstep waveform table.
//!
//! `cargo run --example microstep_table -- --help` prints the usage below.

use std::ffi::OsString;
use std::io::{self, BufWriter, Write};
use std::process::ExitCode;

use profilegen::waveform::{MicrostepTable, Phases};

const HELP: &str = "\
microstep_table: one electrical cycle of a microstep waveform table (SPEC §10)

USAGE:
    cargo run --example microstep_table -- --microsteps N --phases 2|3 [OPTIONS]

OPTIONS:
    --microsteps N    microsteps per full step: 1, 2, 4, 8, 16, 32, 64, 128 or 256 (required)
    --phases P        2 (90° apart, 4 full steps per cycle) or 3 (120°, 6 full steps) (required)
    --current C       motor command (power level) 0 … 32767 (default 32767, full scale)
    --format FORMAT   table (default, aligned) | csv (microstep,phase_a,phase_b[,phase_c])
    -h, --help        this text

One row per microstep 0 … M−1 of the electrical cycle, each phase's signed 16-bit output.
Exit status: 0 done, 2 bad command line (one line on stderr, nothing on stdout).

EXAMPLE:
    microstep_table --microsteps 64 --phases 3 --current 16000 --format csv
";

struct Options {
    microsteps: u32,
    phases: u32,
    current: u16,
    csv: bool,
}

enum Request {
    Help,
    Print(Options),
}

fn parse(arguments: Vec<OsString>) -> Result<Request, String> {
    use lexopt::prelude::*;
    if arguments.iter().any(|a| a == "--help" || a == "-h") {
        return Ok(Request::Help);
    }
    let mut parser = lexopt::Parser::from_args(arguments);
    let (mut microsteps, mut phases, mut current, mut csv) = (None, None, 32767u16, false);
    while let Some(argument) = parser.next().map_err(|e| e.to_string())? {
        let name = match argument {
            Long(name) => format!("--{name}"),
            Short(letter) => return Err(format!("-{letter}: unknown option (see --help)")),
            Value(word) => {
                return Err(format!(
                    "'{}': unexpected argument (see --help)",
                    word.to_string_lossy()
                ))
            }
        };
        if !matches!(
            name.as_str(),
            "--microsteps" | "--phases" | "--current" | "--format"
        ) {
            return Err(format!("{name}: unknown option (see --help)"));
        }
        let text: String = parser
            .value()
            .map_err(|_| format!("{name}: missing value"))?
            .into_string()
            .map_err(|text| format!("{name} '{}': not valid text", text.to_string_lossy()))?;
        let number = |range: &str| {
            text.parse::<u32>()
                .map_err(|_| format!("{name} '{text}': not {range}"))
        };
        match name.as_str() {
            "--microsteps" => microsteps = Some(number("1, 2, 4, 8, 16, 32, 64, 128 or 256")?),
            "--phases" => phases = Some(number("2 or 3")?),
            "--current" => {
                current = u16::try_from(number("a motor command 0 … 32767")?)
                    .ok()
                    .filter(|&c| c <= 32767)
                    .ok_or(format!("{name} '{text}': not a motor command 0 … 32767"))?
            }
            _ => {
                csv = match text.as_str() {
                    "csv" => true,
                    "table" => false,
                    _ => return Err(format!("{name} '{text}': not table or csv")),
                }
            }
        }
    }
    Ok(Request::Print(Options {
        microsteps: microsteps.ok_or("--microsteps: missing (1, 2, 4, …, 256; see --help)")?,
        phases: phases.ok_or("--phases: missing (2 or 3; see --help)")?,
        current,
        csv,
    }))
}

fn main() -> ExitCode {
    let options = match parse(std::env::args_os().skip(1).collect()) {
        Ok(Request::Help) => {
            print!("{HELP}");
            return ExitCode::SUCCESS;
        }
        Ok(Request::Print(options)) => Ok(options),
        Err(message) => Err(message),
    };
    let table = options.and_then(|options| {
        let phases = Phases::from_count(options.phases)
            .map_err(|e| format!("--phases '{}': {e}", options.phases))?;
        let table = MicrostepTable::new(options.microsteps, phases)
            .map_err(|e| format!("--microsteps '{}': {e}", options.microsteps))?;
        let table = table
            .with_current(options.current)
            .map_err(|e| format!("--current '{}': {e}", options.current))?;
        Ok((table, options.csv))
    });
    let (table, csv) = match table {
        Ok(found) => found,
        Err(message) => {
            eprintln!("error: {message}");
            return ExitCode::from(2);
        }
    };
    let mut out = BufWriter::new(io::stdout().lock());
    match print(&table, csv, &mut out) {
        Ok(()) => ExitCode::SUCCESS,
        Err(error) if error.kind() == io::ErrorKind::BrokenPipe => ExitCode::SUCCESS,
        Err(error) => {
            eprintln!("error: {error}");
            ExitCode::FAILURE
        }
    }
}

fn print(table: &MicrostepTable, csv: bool, out: &mut impl Write) -> io::Result<()> {
    let names = ["phase_a", "phase_b", "phase_c"];
    let names = &names[..table.phases().count()];
    if csv {
        writeln!(out, "microstep,{}", names.join(","))?;
    } else {
        write!(out, "{:>9}", "microstep")?;
        for name in names {
            write!(out, " {name:>8}")?;
        }
        writeln!(out)?;
    }
    for k in 0..table.microsteps_per_cycle() as i32 {
        let outputs = table.outputs(k);
        if csv {
            let values: Vec<String> = outputs.as_slice().iter().map(i16::to_string).collect();
            writeln!(out, "{k},{}", values.join(","))?;
        } else {
            write!(out, "{k:>9}")?;
            for value in outputs.as_slice() {
                write!(out, " {value:>8}")?;
            }
            writeln!(out)?;
        }
    }
    out.flush()
}
