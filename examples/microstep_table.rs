//! Prints one electrical cycle of a microstep waveform table.
//!
//! ```text
//! cargo run --example microstep_table -- --microsteps N --phases 2|3 [--current C] [--format table|csv]
//! ```
//!
//! `csv` prints `microstep,phase_a,phase_b` (and `,phase_c` for 3-phase motors) and one row per
//! microstep 0 … M−1. Bad arguments: one line on stderr, exit status 2.

use std::io::{self, BufWriter, Write};
use std::process::ExitCode;

use profilegen::waveform::{MicrostepTable, Phases};

struct Options {
    microsteps: u32,
    phases: u32,
    current: u16,
    csv: bool,
}

fn parse_args() -> Result<Options, String> {
    use lexopt::prelude::*;
    let mut parser = lexopt::Parser::from_env();
    let (mut microsteps, mut phases, mut current, mut csv) = (None, None, 32767u16, false);
    while let Some(arg) = parser.next().map_err(|e| e.to_string())? {
        let name = match arg {
            Long(name) => format!("--{name}"),
            other => return Err(other.unexpected().to_string()),
        };
        let text: String = parser
            .value()
            .map_err(|_| format!("{name}: missing value"))?
            .into_string()
            .map_err(|_| format!("{name}: not valid text"))?;
        let number = |range: &str| {
            text.parse::<u32>()
                .map_err(|_| format!("{name}: '{text}' is not {range}"))
        };
        match name.as_str() {
            "--microsteps" => microsteps = Some(number("1, 2, 4, 8, 16, 32, 64, 128 or 256")?),
            "--phases" => phases = Some(number("2 or 3")?),
            "--current" => {
                current = u16::try_from(number("a current command 0 … 32767")?)
                    .ok()
                    .filter(|&c| c <= 32767)
                    .ok_or(format!(
                        "--current: '{text}' is not a current command 0 … 32767"
                    ))?
            }
            "--format" => {
                csv = match text.as_str() {
                    "csv" => true,
                    "table" => false,
                    other => return Err(format!("--format: '{other}' is not table or csv")),
                }
            }
            _ => return Err(format!("{name}: unknown option")),
        }
    }
    Ok(Options {
        microsteps: microsteps.ok_or("--microsteps: missing (1, 2, 4, …, 256)")?,
        phases: phases.ok_or("--phases: missing (2 or 3)")?,
        current,
        csv,
    })
}

fn main() -> ExitCode {
    let table = parse_args().and_then(|options| {
        let phases = Phases::from_count(options.phases).map_err(|e| format!("--phases: {e}"))?;
        let table = MicrostepTable::new(options.microsteps, phases)
            .map_err(|e| format!("--microsteps: {e}"))?;
        let table = table
            .with_current(options.current)
            .map_err(|e| format!("--current: {e}"))?;
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
