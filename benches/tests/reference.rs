//! The continuous-time references, checked against independent derivations: the S-curve
//! optimum against rsruckig (a port of Ruckig, time-optimal by construction), the trapezoid
//! optimum against its closed form by hand.

use profilegen::reference::{scurve_duration, scurve_phases, trapezoidal_duration};
use proptest::prelude::*;
use rsruckig::prelude::*;

fn ruckig_duration(distance: f64, velocity: f64, acceleration: f64, jerk: f64) -> f64 {
    let mut otg = Ruckig::<1, ThrowErrorHandler>::new(None, 1.0);
    let mut input = InputParameter::new(None);
    input.current_position[0] = 0.0;
    input.target_position[0] = distance;
    input.max_velocity[0] = velocity;
    input.max_acceleration[0] = acceleration;
    input.max_jerk[0] = jerk;
    let mut trajectory = Trajectory::new(None);
    otg.calculate(&input, &mut trajectory)
        .expect("a valid rest-to-rest move");
    trajectory.get_duration()
}

/// Log-uniform in [low, high].
fn log_range(low: f64, high: f64) -> impl Strategy<Value = f64> {
    (low.ln()..high.ln()).prop_map(f64::exp)
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 1_000, max_global_rejects: 100_000, ..ProptestConfig::default() })]

    /// Rest-to-rest durations agree with rsruckig to 1e-9 relative, across jerk-limited,
    /// acceleration-limited and velocity-limited moves.
    #[test]
    fn scurve_optimum_matches_rsruckig(
        distance in log_range(1.0, 1e9),
        velocity in log_range(1e-4, 1e4),
        acceleration in log_range(1e-5, 0.5),
        jerk in log_range(1e-9, 0.5),
    ) {
        let ours = scurve_duration(distance, velocity, acceleration, jerk);
        // Ruckig's root finding is tuned for machine scales (it reports calculator errors for
        // tiny jerks over 10^5-cycle moves), so compare in normalized units: distance 1 and time
        // ~1. The time-optimal profile is covariant under x → x/k, t → t/s (v·s/k, a·s²/k,
        // j·s³/k), so the duration scales back by s exactly.
        // Ruckig also fails where a phase is a vanishing fraction of the move (ramps of 10^-12 of
        // a cruise); such profiles are degenerate and tell nothing, so each ramp must be ≥ 10^-3
        // of the move.
        let (jerk_time, _, _) = scurve_phases(distance, velocity, acceleration, jerk);
        prop_assume!(jerk_time >= 1e-3 * ours);
        let (k, s) = (distance, ours);
        let theirs = s * ruckig_duration(1.0, velocity * s / k, acceleration * s * s / k, jerk * s * s * s / k);
        prop_assert!((ours - theirs).abs() <= 1e-9 * theirs, "ours {} rsruckig {}", ours, theirs);
    }
}

#[test]
fn trapezoid_optimum_by_hand() {
    // Cruise: 100 counts at v = 2, a = d = 0.5: 4 cycles up (4 counts), 4 down (4), 46 cruising.
    assert!((trapezoidal_duration(100.0, 2.0, 0.5, 0.5, 0.0) - 54.0).abs() < 1e-12);
    // A starting velocity of 1, jumped to at the start and dropped from at the end (SPEC §7): up
    // from 1 to 2 takes 2 cycles and 3 counts, down from 2 to 1 the same; 94/2 cruising.
    assert!((trapezoidal_duration(100.0, 2.0, 0.5, 0.5, 1.0) - (2.0 + 2.0 + 47.0)).abs() < 1e-12);
    // The same jumps, triangle: 12 counts with s = 2, a = 1, d = 2: (p² − 4)·(1/2 + 1/4) = 12,
    // so p = √20, and the time is (p − 2)/1 + (p − 2)/2.
    let p = 20f64.sqrt();
    assert!((trapezoidal_duration(12.0, 100.0, 1.0, 2.0, 2.0) - 1.5 * (p - 2.0)).abs() < 1e-12);
    // Separate deceleration, triangle: peak p with p²/2 + p²/4 = 12 → p = 4; 4 up + 2 down.
    assert!((trapezoidal_duration(12.0, 100.0, 1.0, 2.0, 0.0) - 6.0).abs() < 1e-12);
}
