//! Property tests of the register formats: round trips within half an LSB, every out-of-range
//! value refused, and no `f64` at all can make a conversion panic.

use profilegen::format::juno::{Acceleration, TargetVelocity};
use profilegen::format::mc1451a::{
    Destination, GearRatio, Jerk, MaxVelocity, ScurveAcceleration, TrapezoidalAcceleration,
};
use profilegen::format::CycleTime;
use profilegen::Error;
use proptest::num::f64::ANY;
use proptest::prelude::*;

/// Values that break careless conversions: NaN, infinities, subnormals, huge and tiny magnitudes,
/// both zeros, and the half-LSB ties.
fn hostile_f64() -> impl Strategy<Value = f64> {
    prop_oneof![
        ANY,
        Just(f64::NAN),
        Just(f64::INFINITY),
        Just(f64::NEG_INFINITY),
        Just(1e300),
        Just(-1e300),
        Just(f64::MIN_POSITIVE / 2.0),
        Just(-f64::MIN_POSITIVE / 2.0),
        Just(-0.0),
        Just(0.0),
        Just(f64::MAX),
        Just(f64::MIN),
        (-1e12f64..1e12),
        (-1i64 << 40..1i64 << 40).prop_map(|k| k as f64 / 65_536.0 + 0.5 / 65_536.0),
    ]
}

macro_rules! register_properties {
    ($module:ident, $register:ty, $frac:expr) => {
        mod $module {
            use super::*;

            const LSB: f64 = 1.0 / (1u64 << $frac) as f64;
            const MIN: f64 = <$register>::MIN_BITS as f64 * LSB;
            const MAX: f64 = <$register>::MAX_BITS as f64 * LSB;

            proptest! {
                #![proptest_config(ProptestConfig::with_cases(4096))]

                #[test]
                fn real_to_register_to_real_is_within_half_an_lsb(value in MIN..=MAX) {
                    let register = match <$register>::from_num(value) {
                        // Non-zero and within half an LSB of zero: refused, not silently zero.
                        Err(Error::Underflow { .. }) if $frac > 0 => {
                            prop_assert!(value != 0.0 && value.abs() <= LSB / 2.0);
                            return Ok(());
                        }
                        other => other.unwrap(),
                    };
                    let back = register.to_f64();
                    prop_assert!((back - value).abs() <= LSB / 2.0, "{value} -> {back}");
                    prop_assert_eq!(<$register>::from_bits(register.to_bits()), Ok(register));
                }

                #[test]
                fn every_out_of_range_value_is_an_error(excess in 0.0f64..1e12) {
                    // More than half an LSB outside the range rounds outside it.
                    let above = MAX + LSB * 0.500_001 + excess;
                    let below = MIN - LSB * 0.500_001 - excess;
                    assert!(matches!(
                        <$register>::from_num(above),
                        Err(Error::OutOfRange { parameter, .. }) if parameter == <$register>::PARAMETER
                    ));
                    assert!(matches!(<$register>::from_num(below), Err(Error::OutOfRange { .. })));
                }

                #[test]
                fn no_f64_panics_and_results_are_in_range(value in hostile_f64()) {
                    match <$register>::from_num(value) {
                        Ok(register) => {
                            prop_assert!(value.is_finite());
                            prop_assert!(register >= <$register>::MIN && register <= <$register>::MAX);
                            prop_assert!((register.to_f64() - value).abs() <= LSB / 2.0);
                        }
                        Err(Error::NotFinite { .. }) => prop_assert!(!value.is_finite()),
                        Err(Error::Underflow { .. }) => prop_assert!(
                            $frac > 0 && value != 0.0 && value.abs() <= LSB / 2.0
                        ),
                        Err(Error::OutOfRange { .. }) => assert!(
                            !(MIN - LSB / 2.0..=MAX + LSB / 2.0).contains(&value)
                                || (MIN == 0.0 && value < 0.0)
                        ),
                        Err(other) => prop_assert!(false, "unexpected {other:?}"),
                    }
                }
            }

            #[test]
            fn raw_bits_outside_the_range_are_refused() {
                if let Some(above) = <$register>::MAX_BITS.checked_add(1) {
                    assert!(<$register>::from_bits(above).is_err());
                }
                if let Some(below) = <$register>::MIN_BITS.checked_sub(1) {
                    assert!(<$register>::from_bits(below).is_err());
                }
                assert!(<$register>::from_bits(<$register>::MAX_BITS).is_ok());
                assert!(<$register>::from_bits(<$register>::MIN_BITS).is_ok());
            }
        }
    };
}

register_properties!(juno_velocity, TargetVelocity, 16);
register_properties!(juno_acceleration, Acceleration, 24);
register_properties!(mc1451a_destination, Destination, 0);
register_properties!(mc1451a_velocity, MaxVelocity, 16);
register_properties!(mc1451a_scurve_acceleration, ScurveAcceleration, 16);
register_properties!(mc1451a_jerk, Jerk, 32);
register_properties!(
    mc1451a_trapezoidal_acceleration,
    TrapezoidalAcceleration,
    16
);
register_properties!(mc1451a_gear_ratio, GearRatio, 16);

#[test]
fn ties_round_to_even() {
    // 1.5 and 2.5 LSB round to 2 LSB; 3.5 to 4.
    assert_eq!(
        TargetVelocity::from_num(1.5 / 65_536.0).unwrap().to_bits(),
        2
    );
    assert_eq!(
        TargetVelocity::from_num(2.5 / 65_536.0).unwrap().to_bits(),
        2
    );
    assert_eq!(
        TargetVelocity::from_num(-2.5 / 65_536.0).unwrap().to_bits(),
        -2
    );
    assert_eq!(
        TargetVelocity::from_num(3.5 / 65_536.0).unwrap().to_bits(),
        4
    );
}

#[test]
fn negative_values_for_unsigned_registers_are_refused_even_when_tiny() {
    assert!(matches!(
        Acceleration::from_num(-1e-30),
        Err(Error::OutOfRange { .. })
    ));
    assert_eq!(Acceleration::from_num(-0.0).unwrap().to_bits(), 0);
}

#[test]
fn the_error_names_the_parameter_and_range() {
    let message = Acceleration::from_num(128.0).unwrap_err().to_string();
    assert!(
        message.contains("acceleration") && message.contains("127.99999994"),
        "{message}"
    );
}

#[test]
fn cycle_time_rejects_bad_values() {
    for bad in [0.0, -1.0, f64::NAN, f64::INFINITY, -0.0] {
        assert!(CycleTime::from_seconds(bad).is_err(), "{bad}");
    }
    for bad in [0.0, f64::NAN, f64::INFINITY] {
        assert!(CycleTime::from_hertz(bad).is_err(), "{bad}");
    }
    assert!(CycleTime::JUNO.cycles_in(0.0).is_err());
    assert!(CycleTime::JUNO
        .acceleration_for_change(0.0, 1.0, f64::NAN)
        .is_err());
    assert!(CycleTime::JUNO
        .acceleration_for_change(f64::INFINITY, 1.0, 1.0)
        .is_err());
}

proptest! {
    #[test]
    fn scaling_round_trips(counts_per_second in -1e6f64..1e6, power in 1u32..=3) {
        let cycle = CycleTime::MC1451A;
        let back = cycle.per_second(cycle.per_cycle(counts_per_second, power), power);
        prop_assert!((back - counts_per_second).abs() <= 1e-9 * counts_per_second.abs().max(1.0));
    }

    #[test]
    fn physical_conversions_agree_with_by_hand_scaling(jerk in 0.0f64..1e9) {
        let cycle = CycleTime::MC1451A;
        let t = cycle.seconds();
        match Jerk::from_physical(jerk, cycle) {
            Ok(register) => prop_assert_eq!(register, Jerk::from_num(jerk * t * t * t).unwrap()),
            Err(error) => assert!(matches!(error, Error::OutOfRange { .. })),
        }
    }
}
