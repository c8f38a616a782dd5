//! Every public function that takes raw numbers is total (issue #17 item 3): no panic, overflow
//! (the tests run with overflow checks on) or hang on any input, NaN and infinities included;
//! out-of-range input is a typed error, and every error formats. The generators' commands and
//! `step()` are covered by the scripted tests (`tests/scripts.rs`) and the fuzz targets.

use fixed::types::I32F32;
use profilegen::format::{juno, mc1451a, mcx514, CycleTime};
use profilegen::interpolation::Line;
use profilegen::waveform::{MicrostepTable, Phases};
use profilegen::{Range, Trapezoidal};
use proptest::prelude::*;

/// Any `f64`: NaN, infinities, subnormals, zeros of both signs, and every finite value.
fn real() -> impl Strategy<Value = f64> {
    prop_oneof![
        any::<f64>(),
        Just(f64::NAN),
        Just(f64::INFINITY),
        Just(f64::NEG_INFINITY),
        Just(-0.0),
        Just(f64::MIN_POSITIVE / 4.0),
        any::<i64>().prop_map(|x| x as f64),
        any::<u64>().prop_map(f64::from_bits),
    ]
}

/// The stopping distance of SPEC §7's braking rule: from a cycle at `v` (I32F32 bits, ≥ 0),
/// slowing by `d` every cycle while positive: `Σ (v − k·d)` over the positive terms, summed in
/// closed form with `q = ⌊v / d⌋`: `(q + 1)·v − d·q(q + 1)/2`.
fn stopping_distance(v: i128, d: i128) -> i128 {
    let q = v / d;
    (q + 1) * v - d * q * (q + 1) / 2
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(20_000))]

    /// Within its domain the braking velocity is the largest whose stopping distance fits;
    /// outside it (a deceleration under one 8.24 unit, zero or negative; any distance) it is
    /// defined and non-negative, and never larger for a shorter distance.
    #[test]
    fn braking_velocity_is_total(distance in any::<i128>(), deceleration in any::<i64>(),
                                 small in 0i128..(1 << 50), rate in 256i64..(1 << 40)) {
        let velocity = Trapezoidal::braking_velocity(distance, deceleration);
        prop_assert!(velocity >= 0);
        prop_assert!(Trapezoidal::braking_velocity(distance / 2, deceleration) <= velocity || distance < 0);
        let v = i128::from(Trapezoidal::braking_velocity(small, rate));
        prop_assert!(stopping_distance(v, rate.into()) <= small);
        prop_assert!(stopping_distance(v + 1, rate.into()) > small);
    }

    /// Every register from any real and from any raw bits: a value or an error that formats.
    #[test]
    fn registers_take_any_input(value in real(), bits in any::<i64>(), seconds in real(), power in 0u32..6) {
        let mut texts = Vec::new();
        macro_rules! each {
            ($($register:ty as $bits:ty),*) => {$(
                match <$register>::from_num(value) {
                    Ok(register) => prop_assert!(register.to_f64().is_finite()),
                    Err(error) => texts.push(error.to_string()),
                }
                if let Err(error) = <$register>::from_bits(bits as $bits) {
                    texts.push(error.to_string());
                }
            )*};
        }
        each!(juno::TargetVelocity as i32, juno::Acceleration as u32,
              mc1451a::Destination as i32, mc1451a::MaxVelocity as u32,
              mc1451a::ScurveAcceleration as u16, mc1451a::Jerk as u32,
              mc1451a::TrapezoidalAcceleration as u32, mc1451a::GearRatio as i32,
              mcx514::InitialSpeed as u32, mcx514::DriveSpeed as u32, mcx514::Acceleration as u32,
              mcx514::Deceleration as u32, mcx514::Jerk as u32, mcx514::DecelerationJerk as u32,
              mcx514::ManualDecelerationPoint as u32, mcx514::FinishPoint as i32,
              mcx514::Centre as i32);
        for cycle in [CycleTime::from_seconds(seconds), CycleTime::from_hertz(seconds)] {
            match cycle {
                Ok(cycle) => {
                    let _ = cycle.per_cycle(value, power);
                    let _ = cycle.per_second(value, power);
                    if let Err(error) = cycle.cycles_in(value) {
                        texts.push(error.to_string());
                    }
                    if let Err(error) = cycle.acceleration_for_change(value, seconds, value) {
                        texts.push(error.to_string());
                    }
                    if let Ok(speed) = mcx514::DriveSpeed::from_bits(bits as u32) {
                        if let Err(error) = speed.per_cycle(cycle) {
                            texts.push(error.to_string());
                        }
                    }
                    if let Err(error) = juno::TargetVelocity::from_physical(value, cycle) {
                        texts.push(error.to_string());
                    }
                }
                Err(error) => texts.push(error.to_string()),
            }
        }
        let range = Range::of_register(bits, bits.wrapping_add(1), power * 8, "u").scaled(value, "v");
        texts.push(range.to_string());
        prop_assert!(texts.iter().all(|text| !text.is_empty()));
    }

    /// The MCX514 helpers on any registers and counts.
    #[test]
    fn mcx514_helpers_take_any_input(total in any::<u64>(), pulses in any::<u64>(),
                                     initial in 1u32..=8_000_000, drive in 1u32..=8_000_000,
                                     rate in 1u32..=536_870_911, seconds in real(),
                                     finish in prop::array::uniform3(-1_073_741_823i32..=1_073_741_823)) {
        let initial = mcx514::InitialSpeed::from_bits(initial).unwrap();
        let drive = mcx514::DriveSpeed::from_bits(drive).unwrap();
        let deceleration = mcx514::Deceleration::from_bits(rate).unwrap();
        let _ = mcx514::manual_deceleration_point(total, pulses).map_err(|e| e.to_string());
        let finish = finish.map(|point| mcx514::FinishPoint::from_bits(point).unwrap());
        let _ = mcx514::linear_manual_deceleration_point(&finish, pulses).map_err(|e| e.to_string());
        // (DV² − SV²)/2DC pulses, rounded up: at most DV²/2 for the smallest rate.
        prop_assert!(mcx514::deceleration_pulses(initial, drive, deceleration) <= 32_000_000_000_000);
        let _ = mcx514::acceleration_for_change(initial, drive, seconds).map_err(|e| e.to_string());
    }

    /// A line's positions and walks at any step (past the end: the finish point).
    #[test]
    fn lines_take_any_step(finish in prop::array::uniform4(-1_073_741_823i32..=1_073_741_823),
                           step in any::<u32>(), other in any::<u32>()) {
        let line = Line::from_pulses(finish).unwrap();
        let at = line.position_at(step);
        let mut walk = line.walk();
        walk.advance_to(other);
        prop_assert_eq!(walk.advance_to(step), at);
        if step >= line.steps() {
            prop_assert_eq!(at, finish);
        }
        prop_assert!(walk.by_ref().take(3).count() <= 3);
    }

    /// A microstep table's outputs at any microstep (across the wrap), within the current.
    #[test]
    fn microstep_outputs_at_any_microstep(shift in 0u32..9, three in any::<bool>(),
                                          current in 0u16..=32_767, microstep in any::<i32>(),
                                          microsteps in any::<u32>(), phases in any::<u32>()) {
        let phases_of = if three { Phases::Three } else { Phases::Two };
        let table = MicrostepTable::new(1 << shift, phases_of).unwrap().with_current(current).unwrap();
        let outputs = table.outputs(microstep);
        prop_assert!(outputs.as_slice().iter().all(|v| v.unsigned_abs() <= current));
        let _ = MicrostepTable::new(microsteps, phases_of).map_err(|e| e.to_string());
        let _ = Phases::from_count(phases).map_err(|e| e.to_string());
        let _ = table.with_current(microsteps as u16).map_err(|e| e.to_string());
        prop_assert!(I32F32::from_bits(i64::from(microstep) << 32).to_num::<i64>() == i64::from(microstep));
    }
}
