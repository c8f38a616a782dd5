//! The smooth stop (SPEC §9): jerk-limited deceleration to rest, decided one cycle at a time
//! from the present acceleration and velocity.

use super::schedule::Limits64;
use crate::bisect::last_true;

/// The velocity (2^-32 units) still shed while raising a negative acceleration `-magnitude` to
/// zero in jerk steps: `Σ (magnitude − k·J)` over the positive terms.
fn velocity_to_level_off(magnitude: i64, jerk: i128) -> i128 {
    if magnitude <= 0 {
        return 0;
    }
    let magnitude = i128::from(magnitude);
    let steps = (magnitude - 1) / jerk;
    steps * magnitude - jerk * steps * (steps + 1) / 2
}

/// The next cycle's acceleration of a smooth stop from `acceleration` and `velocity` (magnitudes
/// along the move, I32F32 bits): the most negative acceleration (within the jerk and the maximum
/// acceleration) from which the axis can still level off at velocity zero, found by bisection on
/// a monotone condition. Up to three phases emerge: the acceleration falls to its floor, holds,
/// and rises back to zero as the velocity reaches zero.
pub(super) fn stopping_acceleration(acceleration: i64, velocity: i64, limits: Limits64) -> i64 {
    let jerk = limits.jerk as i64;
    let floor = -(limits.acceleration as i64);
    let feasible = |next: i64| {
        let after = i128::from(velocity) + i128::from(next);
        after >= 0 && after >= velocity_to_level_off(-next, i128::from(jerk))
    };
    let low = (acceleration - jerk).max(floor);
    let high = acceleration + jerk;
    if feasible(low) {
        return low;
    }
    // feasible(high) holds on every cycle of a stop (the smooth-stop property tests step it from
    // every phase); the smallest feasible value is the one after the last infeasible.
    last_true(low, high, |next| !feasible(next)) + 1
}
