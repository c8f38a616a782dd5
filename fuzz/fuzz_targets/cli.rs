//! The examples' command line (SPEC §13, `examples/cli/mod.rs`): any argument list (NUL-separated
//! words, not necessarily UTF-8) for either program is parsed, checked against the registers and,
//! when valid, run for up to 2,000 cycles through its events — and never panics.
#![no_main]

use std::ffi::OsString;
use std::os::unix::ffi::OsStringExt;

use libfuzzer_sys::fuzz_target;

#[allow(dead_code)] // the examples' own entry points are not called here
#[path = "../../examples/cli/mod.rs"]
mod cli;

fuzz_target!(|data: &[u8]| {
    let words: Vec<OsString> = data
        .split(|&byte| byte == 0)
        .map(|word| OsString::from_vec(word.to_vec()))
        .collect();
    for program in [cli::Program::Table, cli::Program::Plot] {
        let Ok(cli::Request::Run(options)) = cli::parse(program, words.clone()) else {
            continue;
        };
        let Ok(mut generator) = cli::generator(&options) else {
            continue;
        };
        // Bounded: the visitor ends the run after 2,000 cycles.
        let _ = cli::simulate_quietly(&options, &mut generator, |cycle, _| {
            if cycle < 2_000 {
                Ok(())
            } else {
                Err(())
            }
        });
    }
});
