//! Juno velocity contouring (SPEC §6, Juno User Guide §11 and Figure 11-1).

use fixed::types::I32F32;

use crate::format::juno::{Acceleration, TargetVelocity};
use crate::predict::{Piece, Prediction};
use crate::replay::{End, Replay};
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
/// Every command lays the cycles out ahead, as at most five runs of constant velocity change
/// (an abrupt stop's cycle, toward zero at the deceleration, the cycle that reaches or crosses
/// zero, away from zero at the acceleration, the target for ever), and a step replays them: one
/// addition and a countdown (SPEC §16).
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
    // The per-cycle fields first.
    /// The run under way: an index into `runs` (always below [`RUNS`]).
    current: usize,
    state: State,
    /// The cycles until the next command (see [`VelocityContouring::lay_out`]).
    runs: [Replay; RUNS],
    /// Target velocity as I32F32 bits (the 16.16 register shifted left 16).
    target_velocity: i64,
    /// Acceleration as I32F32 bits (the 8.24 register shifted left 8).
    acceleration: i64,
    /// Deceleration as I32F32 bits, already resolved: a zero register means the acceleration.
    deceleration: i64,
    /// The register as set, so that a later acceleration change re-resolves a zero deceleration.
    deceleration_register: Acceleration,
    /// The plan's first run is an abrupt stop's cycle (velocity zero, position held): while it
    /// is under way, the stop is still to come.
    starts_abrupt: bool,
    /// The state the last abrupt stop produced (or, while it is still to come, will produce),
    /// until a new velocity: while the generator still shows it, its last cycle was that stop
    /// (for [`ProfileGenerator::limits`], so that stepping keeps no bookkeeping of its own).
    abrupt_state: Option<State>,
    /// The one in force before an abrupt stop still to come.
    earlier_abrupt_state: Option<State>,
}

/// The plan's slots: at most five runs, a power of two so that `% RUNS` is a mask.
const RUNS: usize = 8;

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
            current: 0,
            state: State::at_rest(position),
            runs: [Replay::new(0, 0, 0); RUNS],
            target_velocity: velocity_bits(parameters.velocity),
            acceleration: rate_bits(parameters.acceleration),
            deceleration: 0,
            deceleration_register: parameters.deceleration,
            starts_abrupt: false,
            abrupt_state: None,
            earlier_abrupt_state: None,
        };
        generator.resolve_deceleration();
        generator.lay_out();
        Ok(generator)
    }

    /// Sets the target velocity; applies from the next cycle.
    pub fn set_velocity(&mut self, velocity: TargetVelocity) {
        self.target_velocity = velocity_bits(velocity);
        // The abrupt stop shown is forgotten; one still to come is shown when it comes.
        if self.abrupt_pending() {
            self.earlier_abrupt_state = None;
        } else {
            self.abrupt_state = None;
        }
        self.lay_out();
    }

    /// Sets the acceleration; applies from the next cycle.
    ///
    /// # Errors
    /// [`Error::Zero`] if it is zero (nothing changes).
    pub fn set_acceleration(&mut self, acceleration: Acceleration) -> Result<(), Error> {
        check_acceleration(acceleration)?;
        self.acceleration = rate_bits(acceleration);
        self.resolve_deceleration();
        self.lay_out();
        Ok(())
    }

    /// Sets the deceleration (zero: use the acceleration); applies from the next cycle on which
    /// the axis moves toward zero velocity.
    pub fn set_deceleration(&mut self, deceleration: Acceleration) {
        self.deceleration_register = deceleration;
        self.resolve_deceleration();
        self.lay_out();
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

    /// An abrupt stop is still to come: the plan's first run, its cycle, is under way.
    fn abrupt_pending(&self) -> bool {
        self.starts_abrupt && self.current == 0
    }

    /// Lays the cycles out from the present state until the next command: an abrupt stop's
    /// cycle still to come (velocity zero, position held), then the rule of SPEC §6 toward the
    /// target in force — at most three runs of constant velocity change: toward zero at the
    /// deceleration (the cycle that reaches or crosses zero included), away from zero at the
    /// acceleration, the last cycle of each cut at the target; then the target for ever. Each
    /// run's length is one division.
    fn lay_out(&mut self) {
        let pending = self.abrupt_pending();
        let mut runs = [Replay::new(0, 0, 0); RUNS];
        let mut count = 0;
        let mut push = |next: i64, increment: i64, cycles: u64| {
            // Empty runs are skipped; five at most (RUNS is eight).
            if cycles > 0 {
                if let Some(slot) = runs.get_mut(count) {
                    *slot = Replay::new(next, increment, cycles);
                    count += 1;
                }
            }
        };
        let velocity = if pending {
            push(0, 0, 1);
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
        let mut push = |next: i64, increment: i64, cycles: u64| {
            push(next * sign, increment * sign, cycles);
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
        push(target, 0, u64::MAX);
        self.runs = runs;
        self.current = 0;
        self.starts_abrupt = pending;
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
        // The plan's runs from the one under way: the last, the target, for ever.
        let mut pieces = [Piece::constant(0, 0); RUNS];
        let first = self.current % RUNS;
        let mut count = 0;
        for run in &self.runs[first..] {
            pieces[count] = Piece::run(run.next(), run.increment(), run.cycles());
            count += 1;
            if run.cycles() >= 1 << 63 {
                break;
            }
        }
        Prediction::new(self.state, &pieces[..count]).unwrap_or_else(|| {
            // A plan of at most five runs never exceeds the capacity (MAX_SEGMENTS):
            // unreachable; at rest, for the type's sake.
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
        // `% RUNS` is free (`current` < RUNS) and spares the bounds check.
        let current = self.current % RUNS;
        let (velocity, end) = self.runs[current].take();
        match end {
            End::No => {}
            // The run's last cycle: the next run is already laid out.
            End::Run => self.current = current + 1,
            End::Lap => self.runs[current].lap(),
        }
        advance(&mut self.state, I32F32::from_bits(velocity))
    }

    fn state(&self) -> State {
        self.state
    }

    fn is_complete(&self) -> bool {
        self.state.velocity == I32F32::ZERO && self.target_velocity == 0 && !self.abrupt_pending()
    }

    fn stop(&mut self, kind: StopKind) {
        // Either stop zeroes the target velocity register: a restart needs a new velocity.
        self.target_velocity = 0;
        if kind == StopKind::Abrupt && !self.abrupt_pending() {
            // Its cycle is the next: the state it leaves is known now.
            self.earlier_abrupt_state = self.abrupt_state;
            self.abrupt_state = Some(self.state.advanced(I32F32::ZERO));
            self.starts_abrupt = true;
            self.current = 0;
        }
        self.lay_out();
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
            exempt: if self.abrupt_pending() {
                self.earlier_abrupt_state == Some(self.state)
            } else {
                self.abrupt_state == Some(self.state)
            },
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// The rule stepped cycle by cycle, as the generator did before its cycles were laid out:
    /// the yardstick for the plan, commands included.
    struct Decided {
        target: i64,
        acceleration: i64,
        deceleration: i64,
        deceleration_register: Acceleration,
        state: State,
        abrupt_pending: bool,
        abrupt_state: Option<State>,
    }

    impl Decided {
        fn new(parameters: VelocityParameters) -> Self {
            let mut decided = Self {
                target: velocity_bits(parameters.velocity),
                acceleration: rate_bits(parameters.acceleration),
                deceleration: 0,
                deceleration_register: parameters.deceleration,
                state: State::default(),
                abrupt_pending: false,
                abrupt_state: None,
            };
            decided.resolve();
            decided
        }

        fn resolve(&mut self) {
            self.deceleration = if self.deceleration_register.is_zero() {
                self.acceleration
            } else {
                rate_bits(self.deceleration_register)
            };
        }

        fn step(&mut self) -> State {
            if self.abrupt_pending {
                self.abrupt_pending = false;
                self.state = self.state.advanced(I32F32::ZERO);
                self.abrupt_state = Some(self.state);
                return self.state;
            }
            let velocity = self.state.velocity.to_bits();
            let next = if self.target > velocity {
                let rate = if velocity < 0 {
                    self.deceleration
                } else {
                    self.acceleration
                };
                (velocity + rate).min(self.target)
            } else {
                let rate = if velocity > 0 {
                    self.deceleration
                } else {
                    self.acceleration
                };
                (velocity - rate).max(self.target)
            };
            advance(&mut self.state, I32F32::from_bits(next))
        }

        fn command(&mut self, command: Command) {
            match command {
                Command::Velocity(velocity) => {
                    self.target = velocity_bits(velocity);
                    self.abrupt_state = None;
                }
                Command::Acceleration(acceleration) => {
                    self.acceleration = rate_bits(acceleration);
                    self.resolve();
                }
                Command::Deceleration(deceleration) => {
                    self.deceleration_register = deceleration;
                    self.resolve();
                }
                Command::Stop(kind) => {
                    self.target = 0;
                    if kind == StopKind::Abrupt {
                        self.abrupt_pending = true;
                    }
                }
            }
        }
    }

    #[derive(Debug, Clone, Copy)]
    enum Command {
        Velocity(TargetVelocity),
        Acceleration(Acceleration),
        Deceleration(Acceleration),
        Stop(StopKind),
    }

    fn velocity() -> impl Strategy<Value = TargetVelocity> {
        prop_oneof![
            any::<i32>().prop_map(|bits| TargetVelocity::from_bits(bits).unwrap()),
            (-2_000_000i32..2_000_000).prop_map(|bits| TargetVelocity::from_bits(bits).unwrap()),
        ]
    }

    fn rate() -> impl Strategy<Value = Acceleration> {
        prop_oneof![
            (1u32..=u32::MAX)
                .prop_map(|bits| Acceleration::from_bits(bits).unwrap_or(Acceleration::MAX)),
            (1u32..100_000_000)
                .prop_map(|bits| Acceleration::from_bits(bits).unwrap_or(Acceleration::MAX)),
        ]
    }

    fn command() -> impl Strategy<Value = Command> {
        prop_oneof![
            3 => velocity().prop_map(Command::Velocity),
            1 => rate().prop_map(Command::Acceleration),
            1 => prop_oneof![Just(Acceleration::ZERO), rate()].prop_map(Command::Deceleration),
            1 => Just(Command::Stop(StopKind::Smooth)),
            2 => Just(Command::Stop(StopKind::Abrupt)),
        ]
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(2_000))]

        /// Random commands at random cycles (several on one cycle too): every cycle's state,
        /// completion and exemption the same as the rule's cycle by cycle, and the prediction's
        /// next states the steps'.
        #[test]
        fn the_plan_is_the_rule_cycle_by_cycle(
            start in (velocity(), rate(), prop_oneof![Just(Acceleration::ZERO), rate()]),
            commands in prop::collection::vec((0u32..300, command()), 0..12),
        ) {
            let parameters = VelocityParameters {
                velocity: start.0,
                acceleration: start.1,
                deceleration: start.2,
            };
            let mut axis = VelocityContouring::new(parameters).unwrap();
            let mut decided = Decided::new(parameters);
            for (gap, command) in commands.into_iter().chain([(500, Command::Stop(StopKind::Smooth))]) {
                let future = axis.predict();
                for cycle in 0..gap {
                    let state = axis.step();
                    prop_assert_eq!(state, decided.step(), "cycle {}", cycle);
                    if u64::from(cycle) < 40 {
                        prop_assert_eq!(future.state_at(u64::from(cycle) + 1), state);
                    }
                    let complete = decided.state.velocity == I32F32::ZERO
                        && decided.target == 0
                        && !decided.abrupt_pending;
                    prop_assert_eq!(axis.is_complete(), complete);
                    prop_assert_eq!(axis.limits().exempt, decided.abrupt_state == Some(decided.state));
                }
                match command {
                    Command::Velocity(velocity) => axis.set_velocity(velocity),
                    Command::Acceleration(acceleration) => {
                        if axis.set_acceleration(acceleration).is_err() {
                            continue;
                        }
                    }
                    Command::Deceleration(deceleration) => axis.set_deceleration(deceleration),
                    Command::Stop(kind) => axis.stop(kind),
                }
                decided.command(command);
                prop_assert_eq!(axis.limits().exempt, decided.abrupt_state == Some(decided.state));
                prop_assert_eq!(
                    axis.is_complete(),
                    decided.state.velocity == I32F32::ZERO && decided.target == 0 && !decided.abrupt_pending
                );
            }
        }
    }
}
