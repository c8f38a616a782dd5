//! Errors that help (issue #13): every message carries the value given and the legal range in the
//! caller's units; a non-zero value that would round to a zero register is refused; a zero
//! profile parameter is answered with the usable range. The expected bounds are worked out here
//! from the register formats and cycle times (SPEC §3, §4), not taken from the code's output.

use profilegen::format::juno::{Acceleration, TargetVelocity};
use profilegen::format::mc1451a::{Destination, GearRatio, Jerk, MaxVelocity, ScurveAcceleration};
use profilegen::format::CycleTime;
use profilegen::{Error, SCurve, ScurveParameters, Trapezoidal, TrapezoidalParameters};

fn message(result: Result<impl core::fmt::Debug, Error>) -> String {
    result.unwrap_err().to_string()
}

fn assert_contains(message: &str, parts: &[&str]) {
    for part in parts {
        assert!(message.contains(part), "'{part}' not in: {message}");
    }
}

#[test]
fn out_of_range_names_the_value_and_the_range_in_register_units() {
    // 16.16 signed: −2^15 … (2^31 − 1)/2^16 = 32767.9999847…, printed cut to 11 digits.
    let text = message(TargetVelocity::from_num(40_000.0));
    assert_contains(
        &text,
        &[
            "velocity 40000 counts/cycle",
            "-32768 … 32767.999984 counts/cycle",
        ],
    );
    // 8.24 with 31 bits: (2^31 − 1)/2^24 = 127.99999994…
    let text = message(Acceleration::from_num(-3.0));
    assert_contains(
        &text,
        &["acceleration -3 counts/cycle²", "0 … 127.99999994"],
    );
    // Raw bits: 2^31 / 2^24 = 128 counts/cycle².
    let text = message(Acceleration::from_bits(0x8000_0000));
    assert_contains(&text, &["acceleration 128 counts/cycle²"]);
    // A ratio has no unit, and no stray space before the end.
    let text = message(GearRatio::from_num(20_000.0));
    assert!(text.ends_with("-16384 … 16383.999984"), "{text}");
}

#[test]
fn a_physical_input_is_answered_in_physical_units() {
    // At 102.4 µs, −2^15 counts/cycle is −32768 / 102.4e-6 = −320,000,000 counts/s exactly.
    let text = message(TargetVelocity::from_physical(5e9, CycleTime::JUNO));
    assert_contains(
        &text,
        &["velocity 5000000000 counts/s", "-320000000 … 319999999.8"],
    );
    assert!(!text.contains("counts/cycle"), "{text}");
    // MC1451A jerk at 330 µs: the largest is (2^31 − 1)/2^32 / 330e-6³ ≈ 1.39132e10 counts/s³.
    let text = message(Jerk::from_physical(1e12, CycleTime::MC1451A));
    assert_contains(&text, &["jerk 1000000000000 counts/s³", "1.39132"]);
    assert!(!text.contains("counts/cycle"), "{text}");
}

#[test]
fn a_non_zero_value_that_rounds_to_zero_is_refused() {
    // The example: 0.01 counts/s² at 102.4 µs is 1.05e-10 counts/cycle², far below half
    // of the 8.24 register's 2^-24 = 5.96e-8.
    let error = Acceleration::from_physical(0.01, CycleTime::JUNO).unwrap_err();
    assert!(
        matches!(error, Error::Underflow { parameter: "acceleration", value, .. } if value == 0.01),
        "{error:?}"
    );
    // The resolution in counts/s²: 2^-24 / (2^10 · 1e-7)² = 1e14 / 2^44 = 5.6843418860808…
    assert_contains(
        &error.to_string(),
        &["acceleration 0.01 counts/s²", "5.684341886", "counts/s²"],
    );
    // Per-cycle registers: below half an LSB, either sign; an exact half ties to even, to zero.
    for (result, parameter) in [
        (Jerk::from_num(1e-10).map(|_| ()), "jerk"), // 2^-33 ≈ 1.16e-10
        (TargetVelocity::from_num(-1e-6).map(|_| ()), "velocity"), // 2^-17 ≈ 7.6e-6
        (
            MaxVelocity::from_num(0.5 / 65_536.0).map(|_| ()),
            "velocity",
        ),
        (
            ScurveAcceleration::from_num(1e-7).map(|_| ()),
            "acceleration",
        ),
    ] {
        assert!(
            matches!(result, Err(Error::Underflow { parameter: p, .. }) if p == parameter),
            "{result:?}"
        );
    }
    // Just above half an LSB rounds up to one LSB; zero itself is zero.
    assert_eq!(
        MaxVelocity::from_num(0.500_001 / 65_536.0)
            .unwrap()
            .to_bits(),
        1
    );
    assert_eq!(Acceleration::from_num(0.0).unwrap(), Acceleration::ZERO);
    assert_eq!(
        Acceleration::from_physical(0.0, CycleTime::JUNO).unwrap(),
        Acceleration::ZERO
    );
    // A destination is a count, not a rate: 0.3 counts is position 0 (to nearest, as documented).
    assert_eq!(Destination::from_num(0.3).unwrap().to_bits(), 0);
}

#[test]
fn an_scurve_destination_outside_the_register_is_refused() {
    // The MC1451A destination register holds −2^30 … 2^30 − 1 counts (SPEC §3).
    let parameters = ScurveParameters {
        destination: 1 << 30,
        max_velocity: MaxVelocity::from_num(2.0).unwrap(),
        max_acceleration: ScurveAcceleration::from_num(0.1).unwrap(),
        jerk: Jerk::from_num(0.01).unwrap(),
    };
    let text = message(SCurve::new(parameters));
    assert_contains(&text, &["destination", "1073741824", "-1073741824"]);
    let mut axis = SCurve::new(ScurveParameters {
        destination: -(1 << 30),
        ..parameters
    })
    .unwrap();
    let plan = axis.plan();
    // Moving: refused. At rest (a fresh axis at the destination 0): out of range, nothing changes.
    assert!(axis.set_destination(-(1 << 30) - 1).is_err());
    assert_eq!(axis.plan(), plan);
}

#[test]
fn times_in_seconds_name_their_range() {
    let cycle = CycleTime::MC1451A;
    // 1 s at 330 µs is 3,030.30… cycles: 3,030 whole ones.
    assert_eq!(cycle.cycles_at(1.0).unwrap(), 3_030);
    assert_eq!(cycle.cycles_at(0.0).unwrap(), 0);
    assert_contains(&message(cycle.cycles_at(-1.0)), &["time", "-1"]);
    assert_contains(&message(cycle.cycles_at(f64::NAN)), &["time"]);
    assert_contains(&message(cycle.cycles_at(1e30)), &["time"]);
    assert!((cycle.seconds_for(3_030) - 0.9999).abs() < 1e-12);
}

#[test]
fn a_zero_parameter_says_what_a_usable_value_is() {
    let parameters = ScurveParameters {
        destination: 100,
        max_velocity: MaxVelocity::from_num(2.0).unwrap(),
        max_acceleration: ScurveAcceleration::from_num(0.1).unwrap(),
        jerk: Jerk::ZERO,
    };
    let text = message(SCurve::new(parameters));
    // One raw unit of jerk is 2^-32 = 2.3283064365…e-10; the largest (2^31 − 1)/2^32.
    assert_contains(
        &text,
        &[
            "jerk is 0",
            "from 2.3283064365e-10 to 0.49999999976 counts/cycle³",
        ],
    );
    assert!(!text.contains("range is 0"), "{text}");
    let text = message(Trapezoidal::new(TrapezoidalParameters {
        destination: 100,
        max_velocity: TargetVelocity::ZERO,
        acceleration: Acceleration::from_num(0.5).unwrap(),
        deceleration: Acceleration::ZERO,
        start_velocity: TargetVelocity::ZERO,
    }));
    // 2^-16 = 0.0000152587890625.
    assert_contains(
        &text,
        &[
            "velocity is 0",
            "from 0.000015258789062 to 32767.999984 counts/cycle",
        ],
    );
}

#[test]
fn other_errors_carry_their_value() {
    let text = message(TargetVelocity::from_num(f64::NAN));
    assert_contains(&text, &["velocity NaN is not a finite number"]);
    let text = message(CycleTime::from_seconds(-1.0));
    assert_contains(
        &text,
        &[
            "cycle time -1 s is out of range",
            "the legal range is above 0 s",
        ],
    );
    let text = message(CycleTime::from_hertz(0.0));
    assert_contains(&text, &["cycle rate 0 cycles/s"]);
    let text = message(CycleTime::JUNO.cycles_in(-0.5));
    assert_contains(&text, &["duration -0.5 s"]);
    // The trapezoid's starting velocity against its maximum, in counts/cycle.
    let text = message(Trapezoidal::new(TrapezoidalParameters {
        destination: 100,
        max_velocity: TargetVelocity::from_num(2.0).unwrap(),
        acceleration: Acceleration::from_num(0.5).unwrap(),
        deceleration: Acceleration::ZERO,
        start_velocity: TargetVelocity::from_num(3.0).unwrap(),
    }));
    assert_contains(
        &text,
        &["start velocity 3 counts/cycle", "0 … 2 counts/cycle"],
    );
}
