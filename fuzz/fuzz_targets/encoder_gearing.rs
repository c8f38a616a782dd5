//! Raw bytes decoded into an encoder gearing script (`tests/script/encoder_gearing.rs`) and run
//! with every check of the scripted tests as an assertion.
#![no_main]

use libfuzzer_sys::fuzz_target;

#[path = "../../tests/script/mod.rs"]
mod script;

fuzz_target!(|data: &[u8]| {
    let script = script::encoder_gearing::Script::decode(&mut script::Bytes::new(data));
    if let Err(error) = script.run(script::FUZZ_CYCLES) {
        panic!("{error}\n{script:?}");
    }
});
