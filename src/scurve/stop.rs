//! The smooth stop (SPEC §9): jerk-limited deceleration to rest, decided one cycle at a time
//! from the present acceleration and velocity.

use super::schedule::Limits64;
use crate::bisect::last_true;
use crate::trapezoidal::Trapezoidal;

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
/// acceleration) from which the axis can still level off at velocity zero. Up to three phases
/// emerge: the acceleration falls to its floor, holds, and rises back to zero as the velocity
/// reaches zero.
///
/// A next acceleration `−m < 0` can level off when `v − m ≥ Σ (m − k·J)` over the positive
/// terms, that is `T(m) = m + (m − J) + … ≤ v`: the trapezoid's stopping distance with D = J,
/// one derivative up. `T` increases, so the accelerations that can level off are those at or
/// above `−M(v)`, `M` the trapezoid's braking velocity ([`Trapezoidal::braking_velocity`], an
/// integer square root and three divisions), and the answer is `−M(v)` held within
/// `a − J` (or the floor) … `a + J`: the bisection this replaced (kept for the states the closed
/// form does not cover, and as the tests' yardstick) took a few dozen trials.
pub(super) fn stopping_acceleration(acceleration: i64, velocity: i64, limits: Limits64) -> i64 {
    let jerk = limits.jerk as i64;
    let floor = -(limits.acceleration as i64);
    let low = (acceleration - jerk).max(floor);
    let high = acceleration + jerk;
    // A velocity below 2^60 keeps `braking_velocity` in 64 bits without overflow for any jerk
    // ≥ 1 (2·v / J < 2^62 there); a negative one (never on a stop from a move) is left to the
    // bisection, whose condition then also bounds the velocity itself.
    if (0..1 << 60).contains(&velocity) && low <= high {
        // The unclamped form: the public one holds its deceleration to the 8.24 rates (≥ 2^8),
        // and a jerk may be one raw unit.
        let deepest = -Trapezoidal::braking(i128::from(velocity), jerk);
        return low.max(deepest.min(high));
    }
    bisect_stopping_acceleration(acceleration, velocity, limits)
}

/// [`stopping_acceleration`] by bisection on its condition, as it was first written.
fn bisect_stopping_acceleration(acceleration: i64, velocity: i64, limits: Limits64) -> i64 {
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

#[cfg(test)]
mod tests {
    use super::*;

    /// A small deterministic generator (xorshift), so the test needs no dependency.
    struct Random(u64);

    impl Random {
        fn next(&mut self) -> u64 {
            self.0 ^= self.0 << 13;
            self.0 ^= self.0 >> 7;
            self.0 ^= self.0 << 17;
            self.0
        }

        /// Log-uniform in 1 ..= 2^bits − 1.
        fn log_uniform(&mut self, bits: u32) -> u64 {
            let width = 1 + self.next() % u64::from(bits);
            (self.next() >> (64 - width)).max(1)
        }
    }

    /// The closed form against the bisection on random states across the ranges (jerks from one
    /// raw unit, accelerations within the floor, velocities up to 2^50), and on the states near
    /// the kinks of `T` (velocities T(m) − 1, T(m), T(m) + 1).
    #[test]
    fn the_closed_form_is_the_bisection() {
        let mut random = Random(0x9E37_79B9_7F4A_7C15);
        let mut inside = 0;
        for case in 0..200_000 {
            let jerk = random.log_uniform(32);
            let max_acceleration = random.log_uniform(40).max(jerk);
            let limits = Limits64 {
                jerk,
                acceleration: max_acceleration,
                velocity: 1 << 50,
            };
            let magnitude = random.next() % (max_acceleration + 1);
            let acceleration = if random.next() % 2 == 0 {
                magnitude as i64
            } else {
                -(magnitude as i64)
            };
            // A random velocity, or one at a kink of T (T(m) − 1, T(m), T(m) + 1) for an m
            // within 2J of the present deceleration, where the answer lies strictly between
            // the jerk's bounds.
            let velocity = if case % 2 == 0 {
                random.log_uniform(50) as i64
            } else {
                let spread = (random.next() % (4 * jerk + 1)) as i64 - 2 * jerk as i64;
                let m = (-acceleration + spread).max(0);
                let t = m as i128 + velocity_to_level_off(m, i128::from(jerk));
                let t = i64::try_from(t).unwrap_or(i64::MAX).min(1 << 59);
                t + (random.next() % 3) as i64 - 1
            }
            .max(0);
            let expected = bisect_stopping_acceleration(acceleration, velocity, limits);
            let low = (acceleration - jerk as i64).max(-(max_acceleration as i64));
            inside += u32::from(low < expected && expected < acceleration + jerk as i64);
            assert_eq!(
                stopping_acceleration(acceleration, velocity, limits),
                expected,
                "a {acceleration} v {velocity} J {jerk} A {max_acceleration}"
            );
        }
        // The cases that bind the level-off condition itself are many.
        assert!(
            inside > 10_000,
            "{inside} cases strictly inside the jerk's bounds"
        );
    }
}
