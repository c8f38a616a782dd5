//! The conformance suite every generator runs (enable the `conformance` feature to use it on your
//! own generators): the exact identities of SPEC §5 and the limits a generator reports, checked
//! on every cycle.
//!
//! ```
//! use profilegen::conformance::Checker;
//! use profilegen::format::juno::{Acceleration, TargetVelocity};
//! use profilegen::{VelocityContouring, VelocityParameters};
//!
//! let mut axis = VelocityContouring::new(VelocityParameters {
//!     velocity: TargetVelocity::from_num(-3.25)?,
//!     acceleration: Acceleration::from_num(0.125)?,
//!     deceleration: Acceleration::ZERO,
//! })?;
//! let mut checker = Checker::new(&axis);
//! for _ in 0..100 {
//!     checker.step(&mut axis).expect("every cycle conforms");
//! }
//! # Ok::<(), profilegen::Error>(())
//! ```

// A violation carries both states and the limits so a failure explains itself; it is large, but
// the suite is for tests, and boxing would need an allocator the crate does not assume.
#![allow(clippy::result_large_err)]

use fixed::types::I32F32;

use crate::state::{Limits, ProfileGenerator, State};

/// What a cycle broke.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum Rule {
    /// acceleration(n) ≠ velocity(n) − velocity(n−1).
    AccelerationIdentity,
    /// position(n) ≠ position(n−1) + velocity(n) (wrapping).
    PositionIdentity,
    /// |velocity| above the maximum.
    MaxVelocity,
    /// |velocity| rose by more than the speed-up limit.
    SpeedUp,
    /// |velocity| fell (or crossed zero) by more than the slow-down limit.
    SlowDown,
    /// |acceleration| above the maximum.
    MaxAcceleration,
    /// |acceleration(n) − acceleration(n−1)| above the jerk.
    Jerk,
    /// A complete generator moved.
    MovedWhileComplete,
    /// An abrupt stop did not zero the velocity on the next cycle with the position held, or
    /// the generator was not at rest and complete after it (SPEC §9).
    AbruptStop,
}

/// A cycle that broke a rule, with the states on either side.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Violation {
    /// The cycle number (the first step is cycle 1).
    pub cycle: u64,
    /// The rule broken.
    pub rule: Rule,
    /// The state before the cycle.
    pub previous: State,
    /// The state the cycle produced.
    pub next: State,
    /// The limits the generator reported for the cycle.
    pub limits: Limits,
}

impl core::fmt::Display for Violation {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        write!(
            f,
            "cycle {}: {:?} broken: {:?} -> {:?} under {:?}",
            self.cycle, self.rule, self.previous, self.next, self.limits
        )
    }
}

/// Checks the identities of SPEC §5 between two consecutive states.
///
/// # Errors
/// The rule broken, [`Rule::AccelerationIdentity`] or [`Rule::PositionIdentity`].
pub fn check_identities(previous: &State, next: &State) -> Result<(), Rule> {
    if next.velocity.checked_sub(previous.velocity) != Some(next.acceleration) {
        return Err(Rule::AccelerationIdentity);
    }
    if previous.position.wrapping_add(next.velocity) != next.position {
        return Err(Rule::PositionIdentity);
    }
    Ok(())
}

fn within(value: I32F32, limit: Option<I32F32>) -> bool {
    limit.is_none_or(|limit| value.unsigned_abs() <= limit.unsigned_abs())
}

/// Checks one cycle against the limits the generator reported for it.
///
/// A cycle whose velocity keeps its sign (or starts or ends at zero) and grows in magnitude is a
/// speed-up; one that shrinks in magnitude, or crosses zero, is a slow-down. Abrupt-stop cycles
/// (`limits.exempt`) are exempt from every rate and jerk limit, but not from the velocity limit.
///
/// # Errors
/// The first rule broken.
pub fn check_limits(previous: &State, next: &State, limits: &Limits) -> Result<(), Rule> {
    if !within(next.velocity, limits.max_velocity) {
        return Err(Rule::MaxVelocity);
    }
    if limits.exempt {
        return Ok(());
    }
    let (before, after) = (previous.velocity, next.velocity);
    let crosses = (before < 0 && after > 0) || (before > 0 && after < 0);
    let change = next.acceleration;
    if crosses || after.unsigned_abs() < before.unsigned_abs() {
        if !within(change, limits.max_slow_down) {
            return Err(Rule::SlowDown);
        }
    } else if !within(change, limits.max_speed_up) {
        return Err(Rule::SpeedUp);
    }
    if !within(next.acceleration, limits.max_acceleration) {
        return Err(Rule::MaxAcceleration);
    }
    let jerk = next.acceleration.wrapping_sub(previous.acceleration);
    if !within(jerk, limits.max_jerk) {
        return Err(Rule::Jerk);
    }
    Ok(())
}

/// Applies an abrupt stop and checks SPEC §9 on the next two cycles: the first holds the position
/// with velocity zero (its acceleration is the whole drop, by the identities); the generator is
/// then complete, and the cycle after it is at rest.
///
/// # Errors
/// [`Rule::AbruptStop`] (or an identity) on the first cycle that breaks it.
pub fn check_abrupt_stop<G: ProfileGenerator + ?Sized>(generator: &mut G) -> Result<(), Rule> {
    let before = generator.state();
    generator.stop(crate::StopKind::Abrupt);
    let stopped = generator.step();
    check_identities(&before, &stopped)?;
    let held = State {
        position: before.position,
        velocity: I32F32::ZERO,
        acceleration: -before.velocity,
    };
    if stopped != held || !generator.is_complete() {
        return Err(Rule::AbruptStop);
    }
    if generator.step() != State::at_rest(before.position) {
        return Err(Rule::AbruptStop);
    }
    Ok(())
}

/// Steps a generator and checks every cycle: the identities, the reported limits, and that a
/// complete generator stays put.
#[derive(Debug, Clone)]
pub struct Checker {
    previous: State,
    /// The previous cycle was an abrupt stop: the axis is at rest with zero acceleration after
    /// it (SPEC §9), so the next cycle's jerk counts from zero, not from the drop.
    previous_exempt: bool,
    was_complete: bool,
    cycle: u64,
}

impl Checker {
    /// A checker starting from the generator's present state.
    pub fn new<G: ProfileGenerator + ?Sized>(generator: &G) -> Self {
        Self {
            previous: generator.state(),
            previous_exempt: false,
            was_complete: generator.is_complete(),
            cycle: 0,
        }
    }

    /// Call after changing a generator's parameters from outside, before the next step: a
    /// complete generator may move again once it has a new command.
    pub fn command_given<G: ProfileGenerator + ?Sized>(&mut self, generator: &G) {
        self.was_complete = generator.is_complete();
    }

    /// Steps the generator once and checks the cycle.
    ///
    /// # Errors
    /// The [`Violation`], if the cycle broke a rule.
    pub fn step<G: ProfileGenerator + ?Sized>(
        &mut self,
        generator: &mut G,
    ) -> Result<State, Violation> {
        let next = generator.step();
        let limits = generator.limits();
        self.cycle += 1;
        let violation = |rule| Violation {
            cycle: self.cycle,
            rule,
            previous: self.previous,
            next,
            limits,
        };
        check_identities(&self.previous, &next).map_err(violation)?;
        let mut from = self.previous;
        if self.previous_exempt {
            from.acceleration = I32F32::ZERO;
        }
        check_limits(&from, &next, &limits).map_err(violation)?;
        if self.was_complete
            && next != State::at_rest(self.previous.position)
            && next != self.previous
        {
            return Err(violation(Rule::MovedWhileComplete));
        }
        self.previous = next;
        self.previous_exempt = limits.exempt;
        self.was_complete = generator.is_complete();
        Ok(next)
    }

    /// Steps until the generator is complete, at most `max_cycles` cycles, checking each.
    ///
    /// # Errors
    /// The first [`Violation`].
    pub fn run_until_complete<G: ProfileGenerator + ?Sized>(
        &mut self,
        generator: &mut G,
        max_cycles: u64,
    ) -> Result<u64, Violation> {
        let start = self.cycle;
        while !generator.is_complete() && self.cycle - start < max_cycles {
            self.step(generator)?;
        }
        Ok(self.cycle - start)
    }

    /// The number of cycles checked so far.
    pub fn cycles(&self) -> u64 {
        self.cycle
    }
}
