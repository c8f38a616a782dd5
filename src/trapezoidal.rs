//! Trapezoidal point-to-point (SPEC §7): accelerate at A (from an optional starting velocity),
//! cruise at the maximum velocity, decelerate at D and arrive exactly, deciding every cycle from
//! the present state so that every parameter can change in motion.

use fixed::types::I32F32;

use crate::format::juno::{Acceleration, TargetVelocity};
use crate::state::{Limits, ProfileGenerator, State, StopKind};
use crate::Error;

/// The parameters of a trapezoidal move, in Juno register formats.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct TrapezoidalParameters {
    /// Destination, counts.
    pub destination: i32,
    /// Maximum velocity, counts/cycle (16.16), positive.
    pub max_velocity: TargetVelocity,
    /// Acceleration, counts/cycle² (8.24), non-zero.
    pub acceleration: Acceleration,
    /// Deceleration, counts/cycle² (8.24); zero means "use the acceleration".
    pub deceleration: Acceleration,
    /// Starting velocity, counts/cycle (16.16), 0 … the maximum velocity (MC1x51A): a move from
    /// rest begins at it, so its first cycle may jump to the starting velocity plus one cycle's
    /// acceleration.
    pub start_velocity: TargetVelocity,
}

const START_VELOCITY_RANGE: &str = "0 … the maximum velocity, counts/cycle (16.16)";
const MAX_VELOCITY_RANGE: &str =
    "0.00002 … 32767.99998 counts/cycle, and at least the starting velocity (16.16)";

/// The limits, validated, as I32F32 bits (a separate value from the per-cycle state).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
struct Profile {
    max_velocity: i64,
    acceleration: i64,
    /// Resolved: a zero register means the acceleration.
    deceleration: i64,
    start_velocity: i64,
}

impl TrapezoidalParameters {
    /// Checks every parameter.
    ///
    /// # Errors
    /// [`Error::Zero`] for a zero maximum velocity or acceleration; [`Error::OutOfRange`] for a
    /// negative maximum velocity, or a starting velocity outside 0 … the maximum velocity.
    pub fn validate(&self) -> Result<(), Error> {
        self.profile().map(|_| ())
    }

    fn profile(&self) -> Result<Profile, Error> {
        let max_velocity = i64::from(self.max_velocity.to_bits());
        if max_velocity == 0 {
            return Err(Error::Zero {
                parameter: "velocity",
                range: MAX_VELOCITY_RANGE,
            });
        }
        if max_velocity < 0 {
            return Err(Error::OutOfRange {
                parameter: "velocity",
                range: MAX_VELOCITY_RANGE,
            });
        }
        if self.acceleration.is_zero() {
            return Err(Error::Zero {
                parameter: "acceleration",
                range: Acceleration::RANGE,
            });
        }
        let start_velocity = i64::from(self.start_velocity.to_bits());
        if !(0..=max_velocity).contains(&start_velocity) {
            return Err(Error::OutOfRange {
                parameter: "start velocity",
                range: START_VELOCITY_RANGE,
            });
        }
        let acceleration = i64::from(self.acceleration.to_bits()) << 8;
        let deceleration = match self.deceleration.to_bits() {
            0 => acceleration,
            bits => i64::from(bits) << 8,
        };
        // 16.16 → I32F32: shift left 16; 8.24 → I32F32: shift left 8. Both exact.
        Ok(Profile {
            max_velocity: max_velocity << 16,
            acceleration,
            deceleration,
            start_velocity: start_velocity << 16,
        })
    }
}

/// What the generator is doing.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Mode {
    /// Heading for the destination (or resting on it).
    Move,
    /// Smooth stop: decelerating to rest, destination abandoned.
    Stopping,
    /// Abrupt stop pending for the next cycle; then `Move` if a new maximum velocity came in the
    /// meantime (`resume`), else `Stopped`.
    AbruptPending { resume: bool },
    /// Stopped: the velocity register is zero; a new maximum velocity restarts.
    Stopped,
}

/// The trapezoidal point-to-point generator.
///
/// Every cycle it takes the largest velocity that (a) speeds up by at most A (or jumps to the
/// starting velocity from rest), (b) stays within the maximum velocity, and (c) still lets the
/// axis stop exactly on the destination decelerating by at most D per cycle — see
/// [`Trapezoidal::braking_velocity`] for how (c) is exact. So it arrives exactly, with no
/// precomputed deceleration point, and any parameter can change in motion.
///
/// ```
/// use profilegen::format::juno::{Acceleration, TargetVelocity};
/// use profilegen::{ProfileGenerator, Trapezoidal, TrapezoidalParameters};
///
/// let mut axis = Trapezoidal::new(TrapezoidalParameters {
///     destination: 1_000,
///     max_velocity: TargetVelocity::from_num(20.0)?,
///     acceleration: Acceleration::from_num(0.5)?,
///     deceleration: Acceleration::ZERO,
///     start_velocity: TargetVelocity::ZERO,
/// })?;
/// let last = axis.states_until_complete().last().unwrap();
/// assert_eq!((last.position, last.velocity), (1_000.into(), 0.into()));
/// # Ok::<(), profilegen::Error>(())
/// ```
#[derive(Debug, Clone)]
pub struct Trapezoidal {
    parameters: TrapezoidalParameters,
    profile: Profile,
    /// The destination as I32F32 bits.
    destination: i64,
    state: State,
    mode: Mode,
    /// The speed-up limit that governed the last cycle (A, or the starting-velocity jump).
    last_speed_up: i64,
    /// The velocity limit of the last cycle: the maximum velocity, or the velocity before it if
    /// that was higher (a lowered maximum is reached by decelerating at D).
    last_velocity_bound: i64,
    last_was_abrupt: bool,
    /// `(velocity, stopping distance)`: the last [`Self::stopping_distance`] computed, which in cruise
    /// is asked for the same velocity every cycle.
    cached_stop: (i64, i128),
}

impl Trapezoidal {
    /// A generator at rest at position 0 that starts the move on its first step.
    ///
    /// # Errors
    /// As [`TrapezoidalParameters::validate`].
    pub fn new(parameters: TrapezoidalParameters) -> Result<Self, Error> {
        Self::with_position(parameters, I32F32::ZERO)
    }

    /// As [`Self::new`], starting at rest at `position`.
    ///
    /// # Errors
    /// As [`TrapezoidalParameters::validate`].
    pub fn with_position(
        parameters: TrapezoidalParameters,
        position: I32F32,
    ) -> Result<Self, Error> {
        let profile = parameters.profile()?;
        Ok(Self {
            parameters,
            profile,
            destination: i64::from(parameters.destination) << 32,
            state: State::at_rest(position),
            mode: Mode::Move,
            last_speed_up: profile.acceleration,
            last_velocity_bound: profile.max_velocity,
            last_was_abrupt: false,
            cached_stop: (-1, 0),
        })
    }

    /// The parameters in force (after a stop the maximum velocity reads zero, as the chip's
    /// register does).
    pub fn parameters(&self) -> TrapezoidalParameters {
        let mut parameters = self.parameters;
        if matches!(
            self.mode,
            Mode::Stopped | Mode::Stopping | Mode::AbruptPending { resume: false }
        ) {
            parameters.max_velocity = TargetVelocity::ZERO;
        }
        parameters
    }

    /// Replaces all parameters at once, in motion or at rest; they apply from the next cycle.
    /// During or after a stop this restarts motion (after the abrupt stop's cycle, for that kind).
    ///
    /// # Errors
    /// As [`TrapezoidalParameters::validate`]; on error nothing changes.
    pub fn set_parameters(&mut self, parameters: TrapezoidalParameters) -> Result<(), Error> {
        self.change(parameters)?;
        self.destination = i64::from(parameters.destination) << 32;
        // A new velocity restarts a stopped or stopping axis (the abrupt stop still happens).
        self.mode = match self.mode {
            Mode::Stopped | Mode::Stopping | Mode::Move => Mode::Move,
            Mode::AbruptPending { .. } => Mode::AbruptPending { resume: true },
        };
        Ok(())
    }

    /// Sets a new destination; applies from the next cycle (a destination behind the axis means
    /// decelerate, reverse and arrive). After a stop, motion restarts only with a new maximum
    /// velocity.
    pub fn set_destination(&mut self, destination: i32) {
        self.parameters.destination = destination;
        self.destination = i64::from(destination) << 32;
    }

    /// Sets a new maximum velocity; applies from the next cycle (a lower one means decelerate at
    /// D down to it). After a stop this restarts motion.
    ///
    /// # Errors
    /// As [`TrapezoidalParameters::validate`]; on error nothing changes.
    pub fn set_max_velocity(&mut self, max_velocity: TargetVelocity) -> Result<(), Error> {
        self.set_parameters(TrapezoidalParameters {
            max_velocity,
            ..self.parameters
        })
    }

    /// Sets a new acceleration; applies from the next cycle.
    ///
    /// # Errors
    /// [`Error::Zero`] if it is zero; on error nothing changes.
    pub fn set_acceleration(&mut self, acceleration: Acceleration) -> Result<(), Error> {
        self.change(TrapezoidalParameters {
            acceleration,
            ..self.parameters
        })
    }

    /// Sets a new deceleration (zero: use the acceleration); applies from the next cycle.
    pub fn set_deceleration(&mut self, deceleration: Acceleration) {
        // Only the deceleration changes, and any deceleration register is valid.
        let _ = self.change(TrapezoidalParameters {
            deceleration,
            ..self.parameters
        });
    }

    /// Sets a new starting velocity; applies to the next cycle that starts from rest.
    ///
    /// # Errors
    /// [`Error::OutOfRange`] unless 0 ≤ it ≤ the maximum velocity; on error nothing changes.
    pub fn set_start_velocity(&mut self, start_velocity: TargetVelocity) -> Result<(), Error> {
        self.change(TrapezoidalParameters {
            start_velocity,
            ..self.parameters
        })
    }

    /// A change that, unlike a new maximum velocity, does not restart a stopped axis.
    fn change(&mut self, parameters: TrapezoidalParameters) -> Result<(), Error> {
        self.profile = parameters.profile()?;
        self.parameters = parameters;
        self.cached_stop = (-1, 0);
        Ok(())
    }

    /// The distance (I32F32 bits) travelled from a cycle at `velocity` ≥ 0 (that cycle
    /// included) until rest, slowing down by the full deceleration D every cycle:
    /// `T(v) = v + (v − D) + (v − 2D) + … ` over the positive terms, then 0 (the last positive
    /// term is ≤ D, so that drop is allowed). With `q = ⌊v / D⌋`:
    /// `T(v) = (q + 1)·v − D·q(q + 1)/2`. Exact in i128 (v < 2^48, q < 2^40).
    fn stopping_distance(&mut self, velocity: i64) -> i128 {
        if self.cached_stop.0 == velocity {
            return self.cached_stop.1;
        }
        let deceleration = i128::from(self.profile.deceleration);
        let velocity_wide = i128::from(velocity);
        // Floor division of non-negative values.
        let q = velocity_wide / deceleration;
        let distance = (q + 1) * velocity_wide - deceleration * q * (q + 1) / 2;
        self.cached_stop = (velocity, distance);
        distance
    }

    /// The largest velocity `v` (I32F32 bits) with `T(v) ≤ distance`: the fastest this cycle may
    /// go and still stop exactly on the destination, decelerating by at most D per cycle.
    ///
    /// `T` is increasing and piecewise linear: on `q·D ≤ v < (q + 1)·D` it is
    /// `(q + 1)·v − D·q(q + 1)/2`, and `T(q·D) = D·q(q + 1)/2`. So find the segment, the largest
    /// `q` with `D·q(q + 1)/2 ≤ distance` (`q(q + 1) ≤ m = ⌊2·distance / D⌋` ⇔
    /// `2q + 1 ≤ ⌊√(4m + 1)⌋`, an exact integer square root), then solve the segment's line and
    /// round down: `v = ⌊(distance + D·q(q + 1)/2) / (q + 1)⌋`. Any distance left over,
    /// `distance − T(v) < q + 1` units of 2^-32 counts, is absorbed on later cycles, because the
    /// velocity can take any 2^-32 value: the axis lands exactly.
    pub fn braking_velocity(distance: i128, deceleration: i64) -> i64 {
        if distance <= 0 {
            return 0;
        }
        // Distances up to 2^62 (2^30 counts) take 64-bit divisions, several times cheaper than
        // 128-bit ones: 2·distance < 2^63, and the numerator below is < 2·distance + D·(q+1)
        // < 2^64. Longer distances take the same arithmetic in 128 bits.
        if let (Ok(distance), Ok(deceleration)) =
            (u64::try_from(distance), u64::try_from(deceleration))
        {
            if distance < 1 << 62 {
                let m = 2 * distance / deceleration;
                let q = ((4 * m + 1).isqrt() - 1) / 2;
                // D·q(q+1)/2 ≤ distance (that is how q was chosen), so no overflow.
                let numerator = distance + deceleration * (q * (q + 1) / 2);
                return (numerator / (q + 1)) as i64;
            }
        }
        let deceleration = i128::from(deceleration);
        // distance < 2^64 and D ≥ 2^8, so m < 2^57 and 4m + 1 < 2^59: u64 throughout.
        let m = (2 * distance / deceleration) as u64;
        let q = i128::from(((4 * m + 1).isqrt() - 1) / 2);
        let numerator = distance + deceleration * q * (q + 1) / 2;
        (numerator / (q + 1)) as i64
    }

    /// The next velocity in the frame where the destination lies ahead (`distance ≥ 0`).
    fn next_velocity_ahead(&mut self, distance: i128, velocity: i64) -> i64 {
        let Profile {
            max_velocity,
            acceleration,
            deceleration,
            start_velocity,
        } = self.profile;
        // From rest the first cycle may jump to the starting velocity and accelerate from there:
        // "accelerating at the commanded acceleration, beginning at the starting velocity".
        let speed_up = if velocity == 0 {
            acceleration + start_velocity
        } else {
            acceleration
        };
        self.last_speed_up = speed_up;
        if velocity < 0 {
            // Moving away from the destination: slow down by D; the cycle that crosses zero
            // changes the velocity by at most D in all and speeds up by at most A.
            let slowed = velocity + deceleration;
            if slowed <= 0 {
                return slowed;
            }
            let braking = Self::braking_velocity(distance, deceleration);
            return slowed.min(acceleration).min(max_velocity).min(braking);
        }
        let upper = if velocity > max_velocity {
            // A lower maximum velocity: decelerate at D down to it.
            (velocity - deceleration).max(max_velocity)
        } else {
            (velocity + speed_up).min(max_velocity)
        };
        if self.stopping_distance(upper) <= distance {
            return upper;
        }
        // Braking is due. From any state reached under constant parameters the braking velocity
        // is at least velocity − D (the previous cycle checked T(velocity) ≤ distance before it);
        // after a change of destination or D it may not be, and then the axis slows by D and
        // overshoots as little as it can.
        Self::braking_velocity(distance, deceleration).max(velocity - deceleration)
    }
}

impl ProfileGenerator for Trapezoidal {
    fn step(&mut self) -> State {
        let velocity = self.state.velocity.to_bits();
        self.last_was_abrupt = false;
        self.last_speed_up = self.profile.acceleration;
        self.last_velocity_bound = self.profile.max_velocity.max(velocity.abs());
        let next = match self.mode {
            Mode::AbruptPending { resume } => {
                self.mode = if resume { Mode::Move } else { Mode::Stopped };
                self.last_was_abrupt = true;
                0
            }
            Mode::Stopped => 0,
            Mode::Stopping => {
                let deceleration = self.profile.deceleration;
                let next = if velocity > 0 {
                    (velocity - deceleration).max(0)
                } else {
                    (velocity + deceleration).min(0)
                };
                if next == 0 {
                    self.mode = Mode::Stopped;
                }
                next
            }
            Mode::Move => {
                // The signed distance to go, modulo the 32-bit position register: the move goes
                // the short way round, as on the chip (exact for every |distance| < 2^31 counts).
                let distance = self.destination.wrapping_sub(self.state.position.to_bits());
                if distance == 0 && velocity == 0 {
                    self.state = State::at_rest(self.state.position);
                    return self.state;
                }
                // Work in the frame where the destination lies ahead.
                let direction: i64 = if distance != 0 {
                    distance.signum()
                } else {
                    velocity.signum()
                };
                let ahead = i128::from(distance) * i128::from(direction);
                direction * self.next_velocity_ahead(ahead, velocity * direction)
            }
        };
        self.state = self.state.advanced(I32F32::from_bits(next));
        self.state
    }

    fn state(&self) -> State {
        self.state
    }

    fn is_complete(&self) -> bool {
        self.state.velocity == I32F32::ZERO
            && match self.mode {
                Mode::Move => self.destination == self.state.position.to_bits(),
                Mode::Stopped => true,
                Mode::Stopping | Mode::AbruptPending { .. } => false,
            }
    }

    fn stop(&mut self, kind: StopKind) {
        self.mode = match (kind, self.mode) {
            (StopKind::Smooth, Mode::AbruptPending { .. }) | (StopKind::Abrupt, _) => {
                Mode::AbruptPending { resume: false }
            }
            (StopKind::Smooth, _) => Mode::Stopping,
        };
    }

    fn limits(&self) -> Limits {
        Limits {
            max_velocity: Some(I32F32::from_bits(self.last_velocity_bound)),
            max_speed_up: Some(I32F32::from_bits(self.last_speed_up)),
            max_slow_down: Some(I32F32::from_bits(self.profile.deceleration)),
            max_acceleration: None,
            max_jerk: None,
            exempt: self.last_was_abrupt,
        }
    }
}
