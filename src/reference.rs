//! Continuous-time `f64` models: the yardstick the exact generators are tested against, and a
//! way to plan in floats. Nothing here is on a per-cycle path of the exact generators.
//!
//! Time is in cycles and distances in counts, so a continuous model's velocity at time `n` is
//! comparable with the exact generator's state after `n` steps.

// Without `std`, `abs`, `signum` and (in later models) `sqrt` come from `num_traits::Float`
// through libm; with `std` the inherent methods win and the import goes unused.
#[allow(unused_imports)]
use num_traits::Float;

use crate::StopKind;

/// Continuous-time velocity contouring with the rules of SPEC §6: the velocity moves toward the
/// target at the deceleration while it moves toward zero, switching to the acceleration at the
/// instant it crosses zero.
///
/// ```
/// use profilegen::reference::VelocityContouringF64;
/// let mut model = VelocityContouringF64::new(2.0, 0.5, 0.0);
/// model.advance(3.0);
/// assert_eq!(model.velocity(), 1.5);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct VelocityContouringF64 {
    position: f64,
    velocity: f64,
    target_velocity: f64,
    acceleration: f64,
    deceleration: f64,
}

impl VelocityContouringF64 {
    /// At rest at position 0, with a target velocity (counts/cycle), acceleration and deceleration
    /// (counts/cycle², deceleration 0 meaning "use the acceleration").
    pub fn new(target_velocity: f64, acceleration: f64, deceleration: f64) -> Self {
        Self {
            position: 0.0,
            velocity: 0.0,
            target_velocity,
            acceleration,
            deceleration,
        }
    }

    /// Sets the target velocity, counts/cycle.
    pub fn set_velocity(&mut self, target_velocity: f64) {
        self.target_velocity = target_velocity;
    }

    /// Sets the acceleration, counts/cycle².
    pub fn set_acceleration(&mut self, acceleration: f64) {
        self.acceleration = acceleration;
    }

    /// Sets the deceleration, counts/cycle² (0: use the acceleration).
    pub fn set_deceleration(&mut self, deceleration: f64) {
        self.deceleration = deceleration;
    }

    /// A smooth stop (target zero) or an abrupt one (velocity and target zero at once).
    pub fn stop(&mut self, kind: StopKind) {
        self.target_velocity = 0.0;
        if kind == StopKind::Abrupt {
            self.velocity = 0.0;
        }
    }

    /// The velocity, counts/cycle.
    pub fn velocity(&self) -> f64 {
        self.velocity
    }

    /// The position, counts.
    pub fn position(&self) -> f64 {
        self.position
    }

    /// The rate that governs the motion now: the deceleration toward zero, else the acceleration.
    pub fn active_rate(&self) -> f64 {
        if self.toward_zero() {
            self.effective_deceleration()
        } else {
            self.acceleration
        }
    }

    fn effective_deceleration(&self) -> f64 {
        if self.deceleration == 0.0 {
            self.acceleration
        } else {
            self.deceleration
        }
    }

    fn toward_zero(&self) -> bool {
        let (v, target) = (self.velocity, self.target_velocity);
        v != 0.0 && (target.signum() != v.signum() || target == 0.0 || target.abs() < v.abs())
    }

    /// Advances `cycles` cycles of continuous time.
    pub fn advance(&mut self, cycles: f64) {
        let mut remaining = cycles;
        while remaining > 0.0 && self.velocity != self.target_velocity {
            let direction = (self.target_velocity - self.velocity).signum();
            let rate = self.active_rate();
            if rate <= 0.0 {
                break;
            }
            // The next event: zero crossing (when heading for the other side), else the target.
            let crossing = self.toward_zero()
                && (self.target_velocity == 0.0
                    || self.target_velocity.signum() != self.velocity.signum());
            let event_velocity = if crossing { 0.0 } else { self.target_velocity };
            let time_to_event = (event_velocity - self.velocity).abs() / rate;
            let dt = time_to_event.min(remaining);
            self.position += self.velocity * dt + 0.5 * direction * rate * dt * dt;
            self.velocity = if dt == time_to_event {
                event_velocity
            } else {
                self.velocity + direction * rate * dt
            };
            remaining -= dt;
        }
        self.position += self.velocity * remaining.max(0.0);
    }
}

/// The continuous-time optimal duration, in cycles, of a rest-to-rest trapezoidal move of
/// `distance` counts (> 0) with maximum velocity `max_velocity`, acceleration `acceleration`,
/// deceleration `deceleration` (counts/cycle, counts/cycle², both > 0), where the move may start
/// by jumping to `start_velocity` (0 … `max_velocity`) and end by dropping from it (SPEC §7): the
/// velocity starts at s, rises at a to a peak p ≤ V, falls at d back to s, and drops.
///
/// ```
/// use profilegen::reference::trapezoidal_duration;
/// // Triangle: 2·√(distance / a) when a = d and the maximum velocity is not reached.
/// assert!((trapezoidal_duration(100.0, 50.0, 1.0, 1.0, 0.0) - 20.0).abs() < 1e-12);
/// // Starting velocity = maximum velocity: cruise all the way, both jumps.
/// assert!((trapezoidal_duration(100.0, 4.0, 1.0, 1.0, 4.0) - 25.0).abs() < 1e-12);
/// ```
pub fn trapezoidal_duration(
    distance: f64,
    max_velocity: f64,
    acceleration: f64,
    deceleration: f64,
    start_velocity: f64,
) -> f64 {
    let (v, s) = (max_velocity, start_velocity);
    // From s up to a peak p and back down to s: (p² − s²)·(1/2a + 1/2d).
    let ramps = |peak: f64| {
        (peak * peak - s * s) * (1.0 / (2.0 * acceleration) + 1.0 / (2.0 * deceleration))
    };
    let time = |peak: f64| (peak - s) / acceleration + (peak - s) / deceleration;
    if ramps(v) <= distance {
        return time(v) + (distance - ramps(v)) / v;
    }
    // No cruise: the peak solves ramps(p) = distance (p ≥ s, so any distance has one).
    let peak =
        (s * s + distance / (1.0 / (2.0 * acceleration) + 1.0 / (2.0 * deceleration))).sqrt();
    time(peak)
}

/// The continuous-time optimal duration, in cycles, of a symmetric rest-to-rest double-S
/// (jerk-limited) move of `distance` counts with maximum velocity, acceleration and jerk (per
/// cycle, per cycle², per cycle³; all > 0): the profile the MC1451A S-curve approximates.
///
/// ```
/// use profilegen::reference::scurve_duration;
/// // Jerk-limited only: distance = 2·j·t³ per half, so t = (d / 2j)^(1/3) and T = 4t.
/// assert!((scurve_duration(2.0, 1e9, 1e9, 1.0) - 4.0).abs() < 1e-9);
/// ```
pub fn scurve_duration(distance: f64, max_velocity: f64, max_acceleration: f64, jerk: f64) -> f64 {
    let (v, a, j) = (max_velocity, max_acceleration, jerk);
    // Time to reach v from rest (and, mirrored, to stop from it), and the distance both take.
    let to_max_velocity = if v * j >= a * a {
        v / a + a / j
    } else {
        2.0 * (v / j).sqrt()
    };
    let ramps = v * to_max_velocity;
    if distance >= ramps {
        return 2.0 * to_max_velocity + (distance - ramps) / v;
    }
    // The maximum velocity is not reached. With the acceleration limit reached, the peak w solves
    // w·(w/a + a/j) = distance; that needs w ≥ a²/j, i.e. distance ≥ 2a³/j².
    if distance >= 2.0 * a * a * a / (j * j) {
        let peak = (-(a / j) + ((a / j) * (a / j) + 4.0 * distance / a).sqrt()) * a / 2.0;
        return 2.0 * (peak / a + a / j);
    }
    4.0 * (distance / (2.0 * j)).cbrt()
}

/// The phase durations (in cycles, real) of that optimal profile: `(jerk phase, constant
/// acceleration phase, cruise)`; the move is I = III = V = VII = jerk phase, II = VI = constant
/// acceleration, IV = cruise.
pub fn scurve_phases(
    distance: f64,
    max_velocity: f64,
    max_acceleration: f64,
    jerk: f64,
) -> (f64, f64, f64) {
    let (v, a, j) = (max_velocity, max_acceleration, jerk);
    let (jerk_time, constant_time) = if v * j >= a * a {
        (a / j, v / a - a / j)
    } else {
        ((v / j).sqrt(), 0.0)
    };
    let ramps = v * (2.0 * jerk_time + constant_time);
    if distance >= ramps {
        return (jerk_time, constant_time, (distance - ramps) / v);
    }
    if distance >= 2.0 * a * a * a / (j * j) {
        let peak = (-(a / j) + ((a / j) * (a / j) + 4.0 * distance / a).sqrt()) * a / 2.0;
        return (a / j, peak / a - a / j, 0.0);
    }
    ((distance / (2.0 * j)).cbrt(), 0.0, 0.0)
}
