//! Microstep waveform tables (SPEC §10): every entry against a correctly rounded f64 reference,
//! symmetries, current scaling, and the 2-phase magnitude and 3-phase sum bounds.

use profilegen::format::juno::{Acceleration, TargetVelocity};
use profilegen::waveform::{MicrostepTable, Phases};
use profilegen::{Error, VelocityContouring, VelocityParameters};
use proptest::prelude::*;
use std::f64::consts::PI;

const RESOLUTIONS: [u32; 9] = [1, 2, 4, 8, 16, 32, 64, 128, 256];

/// The value 32767·cos(2πk/M − i·φ) and its rounding, ties away from zero (`f64::round`).
/// Angles at multiples of 60° have rational cosines (0, ±1/2, ±1; Niven's theorem), taken exactly:
/// ±16383.5 is a true tie there. Every other value is irrational, far from a tie (checked below).
fn reference(k: u32, cycle: u32, phase: usize, phases: Phases) -> (f64, i16) {
    // The angle as an exact fraction of a turn, numerator / (12·M): 12k − i·3M (90° apart) or
    // 12k − i·4M (120° apart). It is a multiple of a sixth of a turn iff 2M divides the numerator.
    let m = i64::from(cycle);
    let per_phase = match phases {
        Phases::Two => 3 * m,
        Phases::Three => 4 * m,
    };
    let numerator = 12 * i64::from(k) - phase as i64 * per_phase;
    let exact = if numerator % (2 * m) == 0 {
        32767.0 * [1.0, 0.5, -0.5, -1.0, -0.5, 0.5][(numerator / (2 * m)).rem_euclid(6) as usize]
    } else {
        32767.0 * (2.0 * PI * numerator as f64 / (12 * m) as f64).cos()
    };
    (exact, exact.round() as i16)
}

/// Every entry for every N and both phase counts equals the correctly rounded value. f64 cos errs
/// by far less than 1e-9 here, so an entry whose exact value is more than 1e-9 from a tie is
/// rounded correctly by f64: the test checks that margin too, which makes it a proof.
#[test]
fn every_entry_is_correctly_rounded() {
    let mut checked = 0;
    for phases in [Phases::Two, Phases::Three] {
        for n in RESOLUTIONS {
            let table = MicrostepTable::new(n, phases).unwrap();
            let cycle = table.microsteps_per_cycle();
            for k in 0..cycle {
                let outputs = table.outputs(k as i32);
                for (i, &value) in outputs.as_slice().iter().enumerate() {
                    let (exact, rounded) = reference(k, cycle, i, phases);
                    let distance_to_tie = ((exact.abs().fract()) - 0.5).abs();
                    let exact_tie = exact.abs() == 16383.5;
                    assert!(
                        exact_tie || distance_to_tie > 1e-9,
                        "k={k} near a tie: {exact}"
                    );
                    assert_eq!(
                        value, rounded,
                        "N={n} {phases:?} k={k} phase {i}: exact {exact}"
                    );
                    checked += 1;
                }
            }
        }
    }
    assert_eq!(
        checked,
        2 * (4 + 8 + 16 + 32 + 64 + 128 + 256 + 512 + 1024) + 3 * 6 * 511
    );
}

#[test]
fn quarter_wave_symmetry_of_two_phase_tables() {
    for n in RESOLUTIONS {
        let table = MicrostepTable::new(n, Phases::Two).unwrap();
        let m = table.microsteps_per_cycle() as i32;
        let a = |k: i32| table.outputs(k).as_slice()[0];
        for k in 0..m {
            assert_eq!(a(k), a(-k), "even");
            assert_eq!(a(m / 2 - k), -a(k), "odd about the quarter");
            assert_eq!(a(k + m / 2), -a(k), "half-wave");
            assert_eq!(
                table.outputs(k).as_slice()[1],
                a(k - m / 4),
                "B lags A by 90°"
            );
        }
    }
}

#[test]
fn three_phase_tables_rotate_by_120_degrees() {
    for n in RESOLUTIONS {
        let table = MicrostepTable::new(n, Phases::Three).unwrap();
        let m = table.microsteps_per_cycle() as i32;
        for k in 0..m {
            let now = table.outputs(k);
            let later = table.outputs(k + m / 3);
            // One third of a cycle on, B takes A's value and C takes B's.
            assert_eq!(later.as_slice()[1], now.as_slice()[0]);
            assert_eq!(later.as_slice()[2], now.as_slice()[1]);
            assert_eq!(later.as_slice()[0], now.as_slice()[2]);
        }
    }
}

/// 2-phase magnitude: each entry errs by at most 0.5, so √(a² + b²) lies within 0.5·√2 ≈ 0.71 of
/// 32767. 3-phase sum: the exact cosines sum to zero, so the rounded ones sum to at most 1.5 in
/// magnitude, and being an integer, to at most 1.
#[test]
fn magnitude_and_sum_bounds() {
    for n in RESOLUTIONS {
        let two = MicrostepTable::new(n, Phases::Two).unwrap();
        for k in 0..two.microsteps_per_cycle() as i32 {
            let o = two.outputs(k);
            let (a, b) = (f64::from(o.as_slice()[0]), f64::from(o.as_slice()[1]));
            assert!(
                ((a * a + b * b).sqrt() - 32767.0).abs() <= 0.5 * 2f64.sqrt(),
                "k={k}"
            );
        }
        let three = MicrostepTable::new(n, Phases::Three).unwrap();
        for k in 0..three.microsteps_per_cycle() as i32 {
            let sum: i32 = three
                .outputs(k)
                .as_slice()
                .iter()
                .map(|&v| i32::from(v))
                .sum();
            assert!(sum.abs() <= 1, "k={k}: {sum}");
        }
    }
}

#[test]
fn bad_parameters_name_the_legal_values() {
    for bad in [0, 3, 12, 512, 1024, u32::MAX] {
        let error = MicrostepTable::new(bad, Phases::Two).unwrap_err();
        assert_eq!(error, Error::Microsteps { value: bad });
        assert!(error
            .to_string()
            .contains("1, 2, 4, 8, 16, 32, 64, 128, 256"));
    }
    assert!(matches!(
        Phases::from_count(4),
        Err(Error::Phases { value: 4 })
    ));
    let table = MicrostepTable::new(64, Phases::Two).unwrap();
    assert!(matches!(
        table.with_current(32768),
        Err(Error::OutOfRange {
            parameter: "current",
            ..
        })
    ));
}

#[test]
fn a_generator_drives_the_table() {
    // 2 microsteps/cycle² to 16 microsteps/cycle: positions 2, 6, 12, 20, …
    let mut axis = VelocityContouring::new(VelocityParameters {
        velocity: TargetVelocity::from_num(16.0).unwrap(),
        acceleration: Acceleration::from_num(2.0).unwrap(),
        deceleration: Acceleration::ZERO,
    })
    .unwrap();
    let table = MicrostepTable::new(16, Phases::Two).unwrap();
    for (state, outputs) in table.drive(&mut axis).take(40) {
        let microstep = state.position.to_num::<f64>().floor() as i32;
        assert_eq!(outputs, table.outputs(microstep));
    }
}

proptest! {
    /// Any position, including negative and wrapping ones, is reduced modulo the cycle.
    #[test]
    fn any_position(position in any::<i32>(), n_index in 0usize..9, three in any::<bool>()) {
        let phases = if three { Phases::Three } else { Phases::Two };
        let table = MicrostepTable::new(RESOLUTIONS[n_index], phases).unwrap();
        let cycle = i64::from(table.microsteps_per_cycle());
        let reduced = i64::from(position).rem_euclid(cycle) as i32;
        prop_assert_eq!(table.outputs(position), table.outputs(reduced));
    }

    /// Scaled outputs are within 1 LSB of C·cos(…).
    #[test]
    fn scaled_outputs_within_one_lsb(current in 0u16..=32767, k in 0u32..1536, three in any::<bool>()) {
        let phases = if three { Phases::Three } else { Phases::Two };
        let table = MicrostepTable::new(256, phases).unwrap().with_current(current).unwrap();
        let cycle = table.microsteps_per_cycle();
        let k = k % cycle;
        for (i, &value) in table.outputs(k as i32).as_slice().iter().enumerate() {
            let (exact, _) = reference(k, cycle, i, phases);
            let ideal = f64::from(current) * exact / 32767.0;
            prop_assert!((f64::from(value) - ideal).abs() <= 1.0, "{} vs {}", value, ideal);
        }
    }
}

/// The scaling of the previous implementation (before issue #12): `round(C · entry / 32767)`, ties
/// away from zero, by an integer division of the magnitude.
fn previous_scaled(current: u16, entry: i16) -> i16 {
    let product = i32::from(current) * i32::from(entry);
    let magnitude = (2 * product.abs() + 32767) / (2 * 32767);
    (product.signum() * magnitude) as i16
}

/// The division-free lookup gives the previous lookup's outputs: for every resolution, both phase
/// counts, every microstep of the cycle and every motor command, each phase equals the previous
/// formula applied to the correctly rounded full-scale entry (which `every_entry_is_correctly_rounded`
/// shows the table holds).
#[test]
fn same_outputs_as_the_previous_formula() {
    for phases in [Phases::Two, Phases::Three] {
        for n in RESOLUTIONS {
            let full = MicrostepTable::new(n, phases).unwrap();
            let cycle = full.microsteps_per_cycle();
            let entries: Vec<Vec<i16>> = (0..cycle)
                .map(|k| {
                    (0..phases.count())
                        .map(|i| reference(k, cycle, i, phases).1)
                        .collect()
                })
                .collect();
            // Every command for the coarse tables, every 7th (and the ends) for the fine ones.
            let step = if n <= 16 { 1 } else { 7 };
            for current in (0..=32767u16).step_by(step).chain([32767]) {
                let table = full.with_current(current).unwrap();
                for (k, entry) in entries.iter().enumerate() {
                    let expected: Vec<i16> =
                        entry.iter().map(|&e| previous_scaled(current, e)).collect();
                    assert_eq!(
                        table.outputs(k as i32).as_slice(),
                        &expected[..],
                        "N = {n}, {phases:?}, microstep {k}, current {current}"
                    );
                }
            }
        }
    }
}

/// The reduction modulo the electrical cycle (a multiplication by a reciprocal since issue #12) at
/// the ends of the i32 range and around multiples of the cycle, for every resolution: the same
/// outputs as at the position's `rem_euclid`.
#[test]
fn reduction_at_the_extremes() {
    for phases in [Phases::Two, Phases::Three] {
        for n in RESOLUTIONS {
            let table = MicrostepTable::new(n, phases).unwrap();
            let cycle = i64::from(table.microsteps_per_cycle());
            let multiples = [
                0,
                cycle,
                -cycle,
                (i64::from(i32::MAX) / cycle) * cycle,
                (i64::from(i32::MIN) / cycle) * cycle,
            ];
            let positions = multiples
                .iter()
                .flat_map(|&m| (-2..=2).map(move |d| m + d))
                .chain([i64::from(i32::MIN), i64::from(i32::MAX)])
                .filter_map(|p| i32::try_from(p).ok());
            for position in positions {
                let reduced = i64::from(position).rem_euclid(cycle) as i32;
                assert_eq!(
                    table.outputs(position),
                    table.outputs(reduced),
                    "N = {n}, {phases:?}, position {position}"
                );
            }
        }
    }
}

#[test]
fn drive_until_complete_ends_with_the_move() {
    // 1 microstep/cycle² up to 4 then a smooth stop: velocities 1, 2, 3, 4, then 3, 2, 1, 0 —
    // the until-complete drive ends on the cycle that reaches rest, at 1+2+3+4+3+2+1 = 16.
    let mut axis = VelocityContouring::new(VelocityParameters {
        velocity: TargetVelocity::from_num(4.0).unwrap(),
        acceleration: Acceleration::from_num(1.0).unwrap(),
        deceleration: Acceleration::ZERO,
    })
    .unwrap();
    let table = MicrostepTable::new(16, Phases::Three).unwrap();
    assert_eq!(table.drive(&mut axis).take(4).count(), 4);
    profilegen::ProfileGenerator::stop(&mut axis, profilegen::StopKind::Smooth);
    let rows: Vec<_> = table.drive_until_complete(&mut axis).collect();
    assert_eq!(rows.len(), 4);
    let (last, outputs) = rows[3];
    assert_eq!((last.position, last.velocity), (16.into(), 0.into()));
    assert_eq!(outputs, table.outputs(16));
    // Complete already: nothing more, on a trait object too.
    let axis: &mut dyn profilegen::ProfileGenerator = &mut axis;
    assert_eq!(table.drive_until_complete(axis).count(), 0);
}
