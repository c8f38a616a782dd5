//! Prints the manuals' worked examples as this crate computes them: the input, the register in
//! decimal and hex, and the figure the manual prints.
//!
//! `cargo run --example registers`

use profilegen::format::juno::{Acceleration, TargetVelocity};
use profilegen::format::mc1451a::{GearRatio, Jerk, MaxVelocity, ScurveAcceleration};
use profilegen::format::CycleTime;
use profilegen::Error;

fn main() -> Result<(), Error> {
    let juno = CycleTime::JUNO;
    let exact_acceleration = juno.acceleration_for_change(0.0, 135_000.0, 0.120)?;
    let rows: [(&str, String, i64, u32, &str); 8] = [
        row(
            "Juno velocity (manual's chain)",
            "13.825 counts/cycle",
            TargetVelocity::from_num(13.825)?.to_bits().into(),
            "906,035",
        ),
        row(
            "Juno velocity (exact)",
            "135,000 counts/s at 102.4 µs",
            TargetVelocity::from_physical(135_000.0, juno)?
                .to_bits()
                .into(),
            "(13.824 counts/cycle)",
        ),
        row(
            "Juno acceleration (manual's chain)",
            "0.01180 counts/cycle²",
            Acceleration::from_num(0.01180)?.to_bits().into(),
            "197,971",
        ),
        row(
            "Juno acceleration (exact)",
            "0 → 135,000 counts/s in 0.120 s",
            Acceleration::from_num(exact_acceleration)?.to_bits().into(),
            "(1,171.875 cycles)",
        ),
        row(
            "MC1451A maximum velocity",
            "2.75 counts/cycle",
            MaxVelocity::from_num(2.75)?.to_bits().into(),
            "180,224 (0x2c000)",
        ),
        row(
            "MC1451A S-curve acceleration",
            "0.175 counts/cycle²",
            ScurveAcceleration::from_num(0.175)?.to_bits().into(),
            "11,469 (0x2ccd)",
        ),
        row(
            "MC1451A jerk",
            "0.0075 counts/cycle³",
            Jerk::from_num(0.0075)?.to_bits().into(),
            "32,212,256 (0x1eb8520): 1 LSB high",
        ),
        row(
            "MC1451A gear ratio",
            "-11.39",
            GearRatio::from_num(-11.39)?.to_bits().into(),
            "-746,455 (0xfff49c29)",
        ),
    ];
    println!(
        "{:<36} {:<34} {:>12} {:>10}  manual",
        "register", "input", "decimal", "hex"
    );
    for (name, input, decimal, hex, manual) in rows {
        println!(
            "{name:<36} {input:<34} {decimal:>12} {:>10}  {manual}",
            format!("{hex:#x}")
        );
    }
    Ok(())
}

/// One table row; the hex column shows the 32 bits sent to the chip (two's complement if signed).
fn row(
    name: &'static str,
    input: &str,
    decimal: i64,
    manual: &'static str,
) -> (&'static str, String, i64, u32, &'static str) {
    (name, input.to_string(), decimal, decimal as u32, manual)
}
