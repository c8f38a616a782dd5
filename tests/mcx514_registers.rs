//! The MCX514 registers of SPEC §12.1: the ranges of the chip's command table, every value just
//! outside them refused with an error naming the parameter and the range, rounding to the nearest
//! integer pps, and the per-cycle values of §4 worked out by hand here (not taken from the code).

use profilegen::format::mcx514::{
    Acceleration, Centre, Deceleration, DecelerationJerk, DriveSpeed, FinishPoint, InitialSpeed,
    Jerk, ManualDecelerationPoint,
};
use profilegen::format::CycleTime;
use profilegen::Error;

/// Checks that `result` is `Error::OutOfRange` for `parameter`, reporting `value` and the range
/// `min … max` in `unit`, and that the message says so in words.
fn assert_out_of_range<T: core::fmt::Debug>(
    result: Result<T, Error>,
    parameter: &str,
    value: f64,
    (min, max, unit): (f64, f64, &str),
) {
    let error = result.unwrap_err();
    match error {
        Error::OutOfRange {
            parameter: p,
            value: v,
            range,
        } => {
            assert_eq!(p, parameter);
            assert_eq!(v, value, "{parameter}");
            assert_eq!((range.min, range.max, range.unit), (min, max, unit));
        }
        other => panic!("{parameter} {value}: expected OutOfRange, got {other:?}"),
    }
    let text = error.to_string();
    let expected = format!("the legal range is {min} … {max} {unit}");
    assert!(text.starts_with(parameter), "{text}");
    assert!(text.ends_with(&expected), "{text} / {expected}");
}

/// One register: its two ends accepted (from the integer and from a real), one past each end
/// refused both ways, with the parameter name and range of the chip's command table.
macro_rules! range_test {
    ($test:ident, $register:ident, $bits:ty, $parameter:expr, $min:expr, $max:expr, $unit:expr) => {
        #[test]
        fn $test() {
            let (min, max): ($bits, $bits) = ($min, $max);
            let range = (min as f64, max as f64, $unit);
            assert_eq!($register::PARAMETER, $parameter);
            assert_eq!(($register::MIN_BITS, $register::MAX_BITS), (min, max));
            for bits in [min, max] {
                assert_eq!($register::from_bits(bits).unwrap().to_bits(), bits);
                assert_eq!($register::from_num(bits as f64).unwrap().to_bits(), bits);
            }
            assert_eq!($register::MIN.to_bits(), min);
            assert_eq!($register::MAX.to_bits(), max);
            let below = min as i64 - 1;
            let above = max as i64 + 1;
            if let Ok(bits) = <$bits>::try_from(below) {
                assert_out_of_range($register::from_bits(bits), $parameter, below as f64, range);
            }
            if let Ok(bits) = <$bits>::try_from(above) {
                assert_out_of_range($register::from_bits(bits), $parameter, above as f64, range);
            }
            assert_out_of_range(
                $register::from_num(below as f64),
                $parameter,
                below as f64,
                range,
            );
            assert_out_of_range(
                $register::from_num(above as f64),
                $parameter,
                above as f64,
                range,
            );
            for value in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
                assert!(matches!(
                    $register::from_num(value),
                    Err(Error::NotFinite {
                        parameter: $parameter,
                        ..
                    })
                ));
            }
        }
    };
}

range_test!(
    initial_speed,
    InitialSpeed,
    u32,
    "initial speed",
    1,
    8_000_000,
    "pps"
);
range_test!(
    drive_speed,
    DriveSpeed,
    u32,
    "drive speed",
    1,
    8_000_000,
    "pps"
);
range_test!(
    acceleration,
    Acceleration,
    u32,
    "acceleration",
    1,
    536_870_911,
    "pps/s"
);
range_test!(
    deceleration,
    Deceleration,
    u32,
    "deceleration",
    1,
    536_870_911,
    "pps/s"
);
range_test!(jerk, Jerk, u32, "jerk", 1, 1_073_741_823, "pps/s²");
range_test!(
    deceleration_jerk,
    DecelerationJerk,
    u32,
    "deceleration increasing rate",
    1,
    1_073_741_823,
    "pps/s²"
);
range_test!(
    manual_deceleration_point,
    ManualDecelerationPoint,
    u32,
    "manual deceleration point",
    0,
    4_294_967_292,
    "pulses"
);
range_test!(
    finish_point,
    FinishPoint,
    i32,
    "finish point",
    -1_073_741_823,
    1_073_741_823,
    "pulses"
);
range_test!(
    centre,
    Centre,
    i32,
    "centre",
    -1_073_741_823,
    1_073_741_823,
    "pulses"
);

#[test]
fn reals_round_to_the_nearest_integer_ties_to_even() {
    assert_eq!(DriveSpeed::from_num(20_000.4).unwrap().to_bits(), 20_000);
    assert_eq!(DriveSpeed::from_num(20_000.6).unwrap().to_bits(), 20_001);
    assert_eq!(DriveSpeed::from_num(1.5).unwrap().to_bits(), 2);
    assert_eq!(DriveSpeed::from_num(2.5).unwrap().to_bits(), 2);
    assert_eq!(FinishPoint::from_num(-2.5).unwrap().to_bits(), -2);
    assert_eq!(FinishPoint::from_num(-0.4).unwrap().to_bits(), 0);
    // The top of a range is reached by rounding down from just above it.
    assert_eq!(
        Jerk::from_num(1_073_741_823.4).unwrap().to_bits(),
        1_073_741_823
    );
}

#[test]
fn zero_and_what_rounds_to_it_are_out_of_range_for_speeds_and_rates() {
    // The command table starts at 1: no zero speed, rate or jerk. 0.5 ties to even, to 0.
    let range = (1.0, 8_000_000.0, "pps");
    assert_out_of_range(InitialSpeed::from_bits(0), "initial speed", 0.0, range);
    assert_out_of_range(InitialSpeed::from_num(0.0), "initial speed", 0.0, range);
    assert_out_of_range(InitialSpeed::from_num(0.5), "initial speed", 0.5, range);
    assert_out_of_range(InitialSpeed::from_num(-3.0), "initial speed", -3.0, range);
    assert_eq!(InitialSpeed::from_num(0.6).unwrap().to_bits(), 1);
    // Points include zero: an axis that does not move, a deceleration point at the start.
    assert_eq!(FinishPoint::from_bits(0).unwrap().to_bits(), 0);
    assert_eq!(ManualDecelerationPoint::from_num(0.0).unwrap().to_bits(), 0);
    assert_out_of_range(
        ManualDecelerationPoint::from_num(-1.0),
        "manual deceleration point",
        -1.0,
        (0.0, 4_294_967_292.0, "pulses"),
    );
}

#[test]
fn per_cycle_values_are_the_register_times_the_power_of_the_cycle_time() {
    let millisecond = CycleTime::from_seconds(1e-3).unwrap();
    // 20,000 pps · 1 ms = 20 pulses/cycle.
    let speed = DriveSpeed::from_bits(20_000).unwrap();
    assert_eq!(speed.per_cycle(millisecond).unwrap().to_bits(), 20i64 << 32);
    // 65,000 pps/s · (1 ms)² = 0.065 pulses/cycle²; · 2^32 = 279,172,874.24 → 279,172,874.
    let acceleration = Acceleration::from_bits(65_000).unwrap();
    assert_eq!(
        acceleration.per_cycle(millisecond).unwrap().to_bits(),
        279_172_874
    );
    // The same from the deceleration register.
    let deceleration = Deceleration::from_bits(65_000).unwrap();
    assert_eq!(
        deceleration.per_cycle(millisecond).unwrap().to_bits(),
        279_172_874
    );
    // (2^30 − 1) pps/s² · (1 ms)³ = 1.073741823 pulses/cycle³; · 2^32 = 4,611,686,014.13.
    for jerk in [
        Jerk::MAX.per_cycle(millisecond).unwrap(),
        DecelerationJerk::MAX.per_cycle(millisecond).unwrap(),
    ] {
        assert_eq!(jerk.to_bits(), 4_611_686_014);
    }
    // A power-of-two cycle, 2^-10 s: 8,000,000 pps → 7,812.5 pulses/cycle, exactly.
    let binary = CycleTime::from_seconds(1.0 / 1024.0).unwrap();
    let fastest = InitialSpeed::MAX.per_cycle(binary).unwrap();
    assert_eq!(fastest.to_bits(), 33_554_432_000_000);
    assert_eq!(fastest.to_bits(), 15_625i64 << 31);
}

#[test]
fn a_per_cycle_value_that_rounds_to_zero_is_underflow_in_the_registers_units() {
    // 1 pps/s² at 100 µs is 1e-12 pulses/cycle³, below half of 2^-32 (1.16e-10).
    let cycle = CycleTime::from_seconds(100e-6).unwrap();
    let error = Jerk::MIN.per_cycle(cycle).unwrap_err();
    assert!(
        matches!(error, Error::Underflow { parameter: "jerk", value, range } if value == 1.0 && range.unit == "pps/s²"),
        "{error:?}"
    );
    assert!(error.to_string().starts_with("jerk 1 pps/s² rounds to 0"));
    // The next power down still works: 1 pps/s at 100 µs is 1e-8 pulses/cycle² (≈ 43 LSB).
    let acceleration = Acceleration::MIN.per_cycle(cycle).unwrap();
    assert_eq!(acceleration.to_bits(), 43); // 1e-8 · 2^32 = 42.95 → 43
}

#[test]
fn a_per_cycle_value_beyond_i32f32_is_out_of_range_in_the_registers_units() {
    // (2^29 − 1) pps/s · (2.5 s)² = 3.36e9 pulses/cycle², above the I32F32 limit of 2^31.
    let cycle = CycleTime::from_seconds(2.5).unwrap();
    let error = Acceleration::MAX.per_cycle(cycle).unwrap_err();
    match error {
        Error::OutOfRange {
            parameter,
            value,
            range,
        } => {
            assert_eq!(parameter, "acceleration");
            assert_eq!(value, 536_870_911.0);
            assert_eq!(range.unit, "pps/s");
            // 2^31 pulses/cycle² / (2.5 s)² = 343,597,383.68 pps/s (less a hair: 2^63 − 1024 raw).
            assert!((range.max - 343_597_383.68).abs() < 1e-3, "{}", range.max);
        }
        other => panic!("{other:?}"),
    }
    // One second is fine: 536,870,911 pulses/cycle².
    let one_second = CycleTime::from_seconds(1.0).unwrap();
    assert_eq!(
        Acceleration::MAX.per_cycle(one_second).unwrap(),
        536_870_911
    );
}

#[test]
fn display_shows_the_value_in_the_chips_units() {
    assert_eq!(
        Acceleration::from_bits(65_000).unwrap().to_string(),
        "65000 pps/s"
    );
    assert_eq!(
        FinishPoint::from_bits(-20_000).unwrap().to_string(),
        "-20000 pulses"
    );
}

mod helpers {
    use super::*;
    use profilegen::format::mcx514::{
        acceleration_for_change, deceleration_pulses, linear_manual_deceleration_point,
        manual_deceleration_point,
    };

    fn speeds(initial: u32, drive: u32) -> (InitialSpeed, DriveSpeed) {
        (
            InitialSpeed::from_bits(initial).unwrap(),
            DriveSpeed::from_bits(drive).unwrap(),
        )
    }

    #[test]
    fn deceleration_pulses_are_the_ramps_area_rounded_up() {
        let rate = |r| Deceleration::from_bits(r).unwrap();
        // 1 → 3 pps at 1 pps/s: 2 s at a mean of 2 pps = 4 pulses, exactly.
        let (sv, dv) = speeds(1, 3);
        assert_eq!(deceleration_pulses(sv, dv, rate(1)), 4);
        // 1 → 2 pps at 1 pps/s: 1 s at a mean of 1.5 pps = 1.5 pulses → 2 (up: decelerate early).
        let (sv, dv) = speeds(1, 2);
        assert_eq!(deceleration_pulses(sv, dv, rate(1)), 2);
        // No ramp when the drive speed is not above the initial speed.
        let (sv, dv) = speeds(5_000, 5_000);
        assert_eq!(deceleration_pulses(sv, dv, rate(1)), 0);
        let (sv, dv) = speeds(6_000, 5_000);
        assert_eq!(deceleration_pulses(sv, dv, rate(1)), 0);
        // The widest: 1 → 8,000,000 pps at 1 pps/s is (6.4e13 − 1)/2 → 32,000,000,000,000 pulses
        // (no overflow).
        let (sv, dv) = (InitialSpeed::MIN, DriveSpeed::MAX);
        assert_eq!(deceleration_pulses(sv, dv, rate(1)), 32_000_000_000_000);
    }

    #[test]
    fn a_deceleration_longer_than_the_move_is_an_error() {
        let range = (0.0, 4_294_967_292.0, "pulses");
        let parameter = "manual deceleration point";
        assert_out_of_range(manual_deceleration_point(100, 101), parameter, -1.0, range);
        // Above the register, whether or not it fits a u32.
        assert_out_of_range(
            manual_deceleration_point(4_294_967_293, 0),
            parameter,
            4_294_967_293.0,
            range,
        );
        assert_out_of_range(
            manual_deceleration_point(1 << 40, 0),
            parameter,
            (1u64 << 40) as f64,
            range,
        );
        assert_eq!(manual_deceleration_point(100, 100).unwrap().to_bits(), 0);
        // Linear: the long axis is the largest magnitude, whatever its sign or place.
        let finish = [3, -7].map(|p| FinishPoint::from_bits(p).unwrap());
        assert_eq!(
            linear_manual_deceleration_point(&finish, 2)
                .unwrap()
                .to_bits(),
            5
        );
        assert_out_of_range(
            linear_manual_deceleration_point(&finish, 8),
            parameter,
            -1.0,
            range,
        );
        let extreme = [
            FinishPoint::MIN,
            FinishPoint::MAX,
            FinishPoint::MIN,
            FinishPoint::MIN,
        ];
        assert_eq!(
            linear_manual_deceleration_point(&extreme, 0)
                .unwrap()
                .to_bits(),
            1_073_741_823
        );
    }

    #[test]
    fn acceleration_for_change_checks_the_duration_and_the_result() {
        let (sv, dv) = speeds(500, 20_000);
        for bad in [0.0, -0.3] {
            assert!(matches!(
                acceleration_for_change(sv, dv, bad),
                Err(Error::OutOfRange {
                    parameter: "duration",
                    ..
                })
            ));
        }
        assert!(matches!(
            acceleration_for_change(sv, dv, f64::NAN),
            Err(Error::NotFinite {
                parameter: "duration",
                ..
            })
        ));
        // A slow-down gives the same magnitude: 20,000 → 500 in 0.3 s.
        let (sv_high, dv_low) = speeds(20_000, 500);
        assert_eq!(
            acceleration_for_change(sv_high, dv_low, 0.3)
                .unwrap()
                .to_bits(),
            65_000
        );
        // Equal speeds: 0 pps/s, below the register's 1.
        let (sv, dv) = speeds(500, 500);
        assert_out_of_range(
            acceleration_for_change(sv, dv, 1.0),
            "acceleration",
            0.0,
            (1.0, 536_870_911.0, "pps/s"),
        );
        // 8,000,000 − 1 pps in 1 ms: 7.999999e9 pps/s, above 2^29 − 1.
        let (sv, dv) = (InitialSpeed::MIN, DriveSpeed::MAX);
        assert!(matches!(
            acceleration_for_change(sv, dv, 1e-3),
            Err(Error::OutOfRange {
                parameter: "acceleration",
                ..
            })
        ));
    }
}

mod properties {
    use super::*;
    use proptest::prelude::*;

    /// For one register: every integer outside the range is refused (from the integer where the
    /// type holds it, and as a real), naming the parameter, the value and the range; every integer
    /// inside is kept exactly; a real inside rounds to the nearest integer.
    macro_rules! register_properties {
        ($module:ident, $register:ident, $bits:ty, $unit:expr) => {
            mod $module {
                use super::*;

                fn range() -> (f64, f64, &'static str) {
                    ($register::MIN_BITS as f64, $register::MAX_BITS as f64, $unit)
                }

                proptest! {
                    #![proptest_config(ProptestConfig::with_cases(4_096))]

                    #[test]
                    fn outside_is_refused(value in prop_oneof![
                        any::<i64>(),
                        ($register::MAX_BITS as i64 + 1)..($register::MAX_BITS as i64 + 1_000),
                        ($register::MIN_BITS as i64 - 1_000)..($register::MIN_BITS as i64),
                    ]) {
                        let (min, max) = ($register::MIN_BITS as i64, $register::MAX_BITS as i64);
                        prop_assume!(value < min || value > max);
                        if let Ok(bits) = <$bits>::try_from(value) {
                            assert_out_of_range(
                                $register::from_bits(bits), $register::PARAMETER, value as f64, range());
                        }
                        let real = value as f64;
                        assert_out_of_range(
                            $register::from_num(real), $register::PARAMETER, real, range());
                    }

                    #[test]
                    fn inside_is_exact(value in $register::MIN_BITS..=$register::MAX_BITS) {
                        prop_assert_eq!($register::from_bits(value).unwrap().to_bits(), value);
                        prop_assert_eq!($register::from_num(value as f64).unwrap().to_bits(), value);
                        prop_assert_eq!($register::from_bits(value).unwrap().to_f64(), value as f64);
                    }

                    #[test]
                    fn reals_round_to_nearest(value in $register::MIN_BITS..=$register::MAX_BITS,
                                              offset in -0.49f64..0.49) {
                        let real = value as f64 + offset;
                        prop_assert_eq!($register::from_num(real).unwrap().to_bits(), value);
                    }
                }
            }
        };
    }

    register_properties!(initial_speed, InitialSpeed, u32, "pps");
    register_properties!(drive_speed, DriveSpeed, u32, "pps");
    register_properties!(acceleration, Acceleration, u32, "pps/s");
    register_properties!(deceleration, Deceleration, u32, "pps/s");
    register_properties!(jerk, Jerk, u32, "pps/s²");
    register_properties!(deceleration_jerk, DecelerationJerk, u32, "pps/s²");
    register_properties!(
        manual_deceleration_point,
        ManualDecelerationPoint,
        u32,
        "pulses"
    );
    register_properties!(finish_point, FinishPoint, i32, "pulses");
    register_properties!(centre, Centre, i32, "pulses");
}
