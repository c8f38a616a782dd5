//! Raw bytes decoded into a gearing script (`tests/script/gearing.rs`; the first byte picks the
//! master: the trapezoid, velocity contouring or the S-curve) and run with every check of the
//! scripted tests as an assertion.
#![no_main]

use libfuzzer_sys::fuzz_target;

#[path = "../../tests/script/mod.rs"]
mod script;

use script::gearing::{MasterScript, Script};

fn run<S: MasterScript>(bytes: &mut script::Bytes) {
    let script = Script::<S>::decode(bytes);
    if let Err(error) = script.run(script::FUZZ_CYCLES) {
        panic!("{error}\n{script:?}");
    }
}

fuzz_target!(|data: &[u8]| {
    let mut bytes = script::Bytes::new(data);
    match bytes.byte() % 3 {
        0 => run::<script::trapezoidal::Script>(&mut bytes),
        1 => run::<script::velocity::Script>(&mut bytes),
        _ => run::<script::scurve::Script>(&mut bytes),
    }
});
