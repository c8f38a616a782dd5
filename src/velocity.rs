//! Juno velocity contouring (SPEC §6, Juno User Guide §11 and Figure 11-1).

use fixed::types::I32F32;

use crate::format::juno::{Acceleration, TargetVelocity};
use crate::predict::{Piece, Prediction};
use crate::state::{advance, Limits, ProfileGenerator, State, StopKind};
use crate::Error;

/// The profile parameters of velocity contouring, in Juno register formats.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct VelocityParameters {
    /// Target velocity, counts/cycle; its sign is the direction of motion.
    pub velocity: TargetVelocity,
    /// Acceleration, counts/cycle²: the rate away from zero velocity. Must be non-zero.
    pub acceleration: Acceleration,
    /// Deceleration, counts/cycle²: the rate toward zero velocity; zero means "use the
    /// acceleration".
    pub deceleration: Acceleration,
}

/// The Juno's velocity-contouring profile generator.
///
/// Per cycle the velocity moves toward the target by at most the active rate and never past it.
/// The rate is the deceleration while the velocity moves toward zero (the target is smaller in
/// magnitude with the same sign, or of the opposite sign); the cycle that reaches or crosses zero
/// is taken at the deceleration, and from the next cycle on the axis accelerates away from zero at
/// the acceleration. Every parameter applies immediately when set.
///
/// ```
/// use profilegen::format::juno::{Acceleration, TargetVelocity};
/// use profilegen::{ProfileGenerator, VelocityContouring, VelocityParameters};
///
/// let mut axis = VelocityContouring::new(VelocityParameters {
///     velocity: TargetVelocity::from_num(2.0)?,
///     acceleration: Acceleration::from_num(0.5)?,
///     deceleration: Acceleration::ZERO, // use the acceleration
/// })?;
/// let velocities: Vec<f64> = axis.states().take(5).map(|s| s.velocity.to_num()).collect();
/// assert_eq!(velocities, [0.5, 1.0, 1.5, 2.0, 2.0]);
/// # Ok::<(), profilegen::Error>(())
/// ```
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct VelocityContouring {
    /// Target velocity as I32F32 bits (the 16.16 register shifted left 16).
    target_velocity: i64,
    /// Acceleration as I32F32 bits (the 8.24 register shifted left 8).
    acceleration: i64,
    /// Deceleration as I32F32 bits, already resolved: a zero register means the acceleration.
    deceleration: i64,
    /// The register as set, so that a later acceleration change re-resolves a zero deceleration.
    deceleration_register: Acceleration,
    state: State,
    /// An abrupt stop waits for the next cycle.
    abrupt_pending: bool,
    /// The state the last abrupt stop produced, until a command: while the generator still
    /// shows it, its last cycle was that stop (for [`ProfileGenerator::limits`], so that stepping
    /// keeps no bookkeeping of its own).
    abrupt_state: Option<State>,
}

/// The 16.16 velocity register as I32F32 bits.
const fn velocity_bits(velocity: TargetVelocity) -> i64 {
    (velocity.to_bits() as i64) << 16
}

/// The 8.24 rate register as I32F32 bits.
const fn rate_bits(rate: Acceleration) -> i64 {
    (rate.to_bits() as i64) << 8
}

fn check_acceleration(acceleration: Acceleration) -> Result<(), Error> {
    if acceleration.is_zero() {
        return Err(Error::Zero {
            parameter: "acceleration",
            range: Acceleration::RANGE,
        });
    }
    Ok(())
}

impl VelocityContouring {
    /// A generator at rest at position 0 with these parameters (it starts moving on the first
    /// step if the velocity is non-zero).
    ///
    /// # Errors
    /// [`Error::Zero`] if the acceleration is zero.
    pub fn new(parameters: VelocityParameters) -> Result<Self, Error> {
        Self::with_position(parameters, I32F32::ZERO)
    }

    /// As [`Self::new`], at rest at `position`.
    ///
    /// # Errors
    /// [`Error::Zero`] if the acceleration is zero.
    pub fn with_position(parameters: VelocityParameters, position: I32F32) -> Result<Self, Error> {
        check_acceleration(parameters.acceleration)?;
        let mut generator = Self {
            target_velocity: velocity_bits(parameters.velocity),
            acceleration: rate_bits(parameters.acceleration),
            deceleration: 0,
            deceleration_register: parameters.deceleration,
            state: State::at_rest(position),
            abrupt_pending: false,
            abrupt_state: None,
        };
        generator.resolve_deceleration();
        Ok(generator)
    }

    /// Sets the target velocity; applies from the next cycle.
    pub fn set_velocity(&mut self, velocity: TargetVelocity) {
        self.target_velocity = velocity_bits(velocity);
        self.abrupt_state = None;
    }

    /// Sets the acceleration; applies from the next cycle.
    ///
    /// # Errors
    /// [`Error::Zero`] if it is zero (nothing changes).
    pub fn set_acceleration(&mut self, acceleration: Acceleration) -> Result<(), Error> {
        check_acceleration(acceleration)?;
        self.acceleration = rate_bits(acceleration);
        self.resolve_deceleration();
        Ok(())
    }

    /// Sets the deceleration (zero: use the acceleration); applies from the next cycle on which
    /// the axis moves toward zero velocity.
    pub fn set_deceleration(&mut self, deceleration: Acceleration) {
        self.deceleration_register = deceleration;
        self.resolve_deceleration();
    }

    /// The present parameters, as registers (the velocity is zero after a stop).
    pub fn parameters(&self) -> VelocityParameters {
        VelocityParameters {
            // Both were built from these registers by exact shifts, so they convert back exactly.
            velocity: TargetVelocity::from_bits((self.target_velocity >> 16) as i32)
                .unwrap_or(TargetVelocity::ZERO),
            acceleration: Acceleration::from_bits((self.acceleration >> 8) as u32)
                .unwrap_or(Acceleration::ZERO),
            deceleration: self.deceleration_register,
        }
    }

    /// The cycle of an abrupt stop, off the per-cycle path: velocity zero, position held.
    #[cold]
    fn abrupt_stop(&mut self) -> State {
        self.abrupt_pending = false;
        let state = self.state.advanced(I32F32::ZERO);
        self.state = state;
        self.abrupt_state = Some(state);
        state
    }

    fn resolve_deceleration(&mut self) {
        self.deceleration = if self.deceleration_register.is_zero() {
            self.acceleration
        } else {
            rate_bits(self.deceleration_register)
        };
    }
}

impl VelocityContouring {
    /// The future of this axis from its present state, for as long as it gets no further
    /// command: the state after any number of cycles, the cycle on which it comes to rest after
    /// a stop, the cycle that reaches a position — each without stepping (see [`Prediction`]).
    ///
    /// The rule of SPEC §6 makes at most three runs of constant velocity change: toward zero at
    /// the deceleration (the cycle that reaches or crosses zero included), away from zero at the
    /// acceleration, the last cycle of each cut at the target; then the target velocity for
    /// ever. Each run's length is one division.
    ///
    /// ```
    /// use profilegen::format::juno::{Acceleration, TargetVelocity};
    /// use profilegen::{ProfileGenerator, VelocityContouring, VelocityParameters};
    ///
    /// let mut axis = VelocityContouring::new(VelocityParameters {
    ///     velocity: TargetVelocity::from_num(2.0)?,
    ///     acceleration: Acceleration::from_num(0.5)?,
    ///     deceleration: Acceleration::ZERO,
    /// })?;
    /// let future = axis.predict();
    /// assert_eq!(future.completion(), None, "it never stops by itself");
    /// // Velocities 0.5, 1, 1.5, 2, 2, …: positions 0.5, 1.5, 3, 5, 7, …
    /// assert_eq!(future.state_at(5).position, 7);
    /// assert_eq!(future.first_cycle_at(4.into()), Some(4));
    /// assert_eq!(axis.states().nth(4), Some(future.state_at(5)));
    /// # Ok::<(), profilegen::Error>(())
    /// ```
    pub fn predict(&self) -> Prediction {
        // An abrupt stop still to come: its cycle (velocity zero, position held), then the rule
        // from rest toward the target in force — zero, unless a velocity was given after the
        // stop (found by the scripted tests, issue #17).
        let velocity = if self.abrupt_pending {
            0
        } else {
            self.state.velocity.to_bits()
        };
        // In the frame where the target is not below the velocity (mirrored by `sign`, the
        // rule being symmetric): toward zero at D while the velocity is negative, then at A.
        let sign = if self.target_velocity < velocity {
            -1
        } else {
            1
        };
        let (velocity, target) = (velocity * sign, self.target_velocity * sign);
        let turn = |v: i64| v * sign;
        let mut pieces = [Piece::constant(0, 0); 6];
        let mut count = 0;
        if self.abrupt_pending {
            pieces[0] = Piece::constant(0, 1);
            count = 1;
        }
        let mut push = |next: i64, increment: i64, cycles: u64| {
            if let Some(slot) = pieces.get_mut(count) {
                *slot = Piece::run(turn(next), turn(increment), cycles);
                count += 1;
            }
        };
        // Velocities below 2^47 in magnitude and rates ≥ 2^8: every count below 2^40, every
        // sum below 2^48.
        let mut from = velocity;
        if from < 0 && from < target {
            // Steps at D while the velocity before them is negative: ⌈−v / D⌉ of them reach
            // or cross zero, fewer if the target comes first (⌈(target − v) / D⌉).
            let deceleration = self.deceleration;
            let steps = ceiling(-from, deceleration).min(ceiling(target - from, deceleration));
            push(from + deceleration, deceleration, steps - 1);
            let last = (from + deceleration * steps as i64).min(target);
            push(last, 0, 1);
            from = last;
        }
        if from < target {
            let acceleration = self.acceleration;
            let steps = ceiling(target - from, acceleration);
            push(from + acceleration, acceleration, steps - 1);
        }
        // The target for ever (the first of its cycles lands on it).
        push(target, 0, 0);
        Prediction::new(self.state, &pieces[..count]).unwrap_or_else(|| {
            // Six pieces never exceed the capacity (MAX_SEGMENTS): unreachable; at rest, for the type's sake.
            Prediction::new(self.state, &[Piece::constant(0, 0)]).expect("one piece fits")
        })
    }
}

/// ⌈a / b⌉ for a ≥ 0, b > 0, as a count.
fn ceiling(a: i64, b: i64) -> u64 {
    (a.max(0) as u64).div_ceil(b as u64)
}

impl ProfileGenerator for VelocityContouring {
    #[inline]
    fn step(&mut self) -> State {
        if self.abrupt_pending {
            return self.abrupt_stop();
        }
        let velocity = self.state.velocity.to_bits();
        let target = self.target_velocity;
        // Toward zero, the rate is the deceleration: the velocity moves against its own sign.
        // That is the target being smaller with the same sign, or of the other sign (zero
        // included), and it covers the cycle that reaches or crosses zero. So going up, D while
        // the velocity is negative; going down, D while it is positive. |velocity| < 2^47 and
        // rate < 2^39: no overflow, and never past the target.
        let next = if target > velocity {
            let rate = if velocity < 0 {
                self.deceleration
            } else {
                self.acceleration
            };
            (velocity + rate).min(target)
        } else {
            let rate = if velocity > 0 {
                self.deceleration
            } else {
                self.acceleration
            };
            (velocity - rate).max(target)
        };
        advance(&mut self.state, I32F32::from_bits(next))
    }

    fn state(&self) -> State {
        self.state
    }

    fn is_complete(&self) -> bool {
        self.state.velocity == I32F32::ZERO && self.target_velocity == 0 && !self.abrupt_pending
    }

    fn stop(&mut self, kind: StopKind) {
        // Either stop zeroes the target velocity register: a restart needs a new velocity.
        self.target_velocity = 0;
        if kind == StopKind::Abrupt {
            self.abrupt_pending = true;
        }
    }

    fn limits(&self) -> Limits {
        Limits {
            // The register's largest magnitude: −32768 counts/cycle, its minimum (found by the
            // scripted tests, issue #17: the maximum, 32767.99998, refused a legal target).
            max_velocity: Some(I32F32::from_bits(-velocity_bits(TargetVelocity::MIN))),
            max_speed_up: Some(I32F32::from_bits(self.acceleration)),
            // Toward zero, and the cycle that crosses it, at the deceleration.
            max_slow_down: Some(I32F32::from_bits(self.deceleration)),
            max_acceleration: None,
            max_jerk: None,
            exempt: self.abrupt_state == Some(self.state),
        }
    }
}
