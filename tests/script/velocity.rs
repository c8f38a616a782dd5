//! Velocity contouring (SPEC §6) scripts: target velocity, acceleration and deceleration changed
//! at any time; the motion settles when the velocity reaches the target.

use fixed::types::I32F32;
use profilegen::format::juno::{Acceleration, TargetVelocity};
use profilegen::{Error, ProfileGenerator, State, VelocityContouring, VelocityParameters};

use super::{counts, Bytes, Scripted, Step};

/// A command of a velocity-contouring script, in raw register bits.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Command {
    /// A new target velocity (16.16 bits).
    Velocity(i32),
    /// The present velocity, reversed, as the target (from the live state).
    Reverse,
    /// A new acceleration (8.24 bits; zero is refused).
    Acceleration(u32),
    /// A new deceleration (8.24 bits; zero means the acceleration).
    Deceleration(u32),
}

/// The generator and its script.
#[derive(Debug, Clone)]
pub struct Script {
    /// The parameters it starts with, raw.
    pub parameters: (i32, u32, u32),
    /// Where it starts.
    pub position: I32F32,
    /// The steps.
    pub steps: Vec<Step<Command>>,
}

impl Script {
    /// Builds the generator and runs the script.
    ///
    /// # Errors
    /// The first check that failed.
    pub fn run(&self, budget: u64) -> Result<u64, String> {
        match self.build()? {
            Some(generator) => super::run(generator, &self.steps, budget),
            None => Ok(0),
        }
    }

    /// Builds the generator: `None` if the parameters are refused, as they must be then.
    ///
    /// # Errors
    /// Valid parameters refused.
    pub fn build(&self) -> Result<Option<VelocityContouring>, String> {
        let (velocity, acceleration, deceleration) = self.parameters;
        let parameters = VelocityParameters {
            velocity: TargetVelocity::from_bits(velocity).map_err(|e| e.to_string())?,
            acceleration: Acceleration::from_bits(acceleration).map_err(|e| e.to_string())?,
            deceleration: Acceleration::from_bits(deceleration).map_err(|e| e.to_string())?,
        };
        match VelocityContouring::with_position(parameters, self.position) {
            Ok(generator) => Ok(Some(generator)),
            Err(_) if acceleration == 0 => Ok(None),
            Err(error) => Err(format!("valid parameters refused: {error}")),
        }
    }

    /// Decodes a script from raw bytes (the fuzz target).
    pub fn decode(bytes: &mut Bytes) -> Self {
        let parameters = (
            velocity_bits(bytes.boosted_signed(1 << 31)),
            bytes.boosted(Acceleration::MAX_BITS.into()) as u32,
            bytes.boosted(Acceleration::MAX_BITS.into()) as u32,
        );
        let position = bytes.position();
        let steps = bytes.steps(|bytes| {
            Some(match bytes.byte() % 4 {
                0 => Command::Velocity(velocity_bits(bytes.boosted_signed(1 << 31))),
                1 => Command::Reverse,
                2 => Command::Acceleration(bytes.boosted(Acceleration::MAX_BITS.into()) as u32),
                _ => Command::Deceleration(bytes.boosted(Acceleration::MAX_BITS.into()) as u32),
            })
        });
        Self {
            parameters,
            position,
            steps,
        }
    }
}

/// A signed magnitude up to 2^31 as 16.16 bits (−2^31 is the register's minimum).
fn velocity_bits(value: i64) -> i32 {
    value.clamp(i64::from(i32::MIN), i64::from(i32::MAX)) as i32
}

/// The target velocity, I32F32 bits.
fn target(generator: &VelocityContouring) -> i64 {
    i64::from(generator.parameters().velocity.to_bits()) << 16
}

impl Scripted for VelocityContouring {
    /// SPEC §15: the prediction from the present state (`None` where the generator decides
    /// cycle by cycle, as during a smooth stop), checked against stepping by the runner.
    fn predict(&self, cycles: u64) -> Option<State> {
        Some(self.predict().state_at(cycles))
    }

    type Command = Command;

    fn apply(&mut self, command: &Command) -> Result<(), Error> {
        match *command {
            Command::Velocity(bits) => self.set_velocity(TargetVelocity::from_bits(bits)?),
            Command::Reverse => {
                // The present velocity's 16.16 part, negated (−(−2^31) saturates to 2^31 − 1).
                let bits = (self.state().velocity.to_bits() >> 16) as i32;
                self.set_velocity(TargetVelocity::from_bits(bits.saturating_neg())?);
            }
            Command::Acceleration(bits) => {
                self.set_acceleration(Acceleration::from_bits(bits)?)?;
            }
            Command::Deceleration(bits) => {
                self.set_deceleration(Acceleration::from_bits(bits)?);
            }
        }
        Ok(())
    }

    /// SPEC §6 in continuous time: toward zero at D, away from it at A (the zero-crossing cycle,
    /// taken at D, costs at most one more cycle). A pending abrupt stop (invisible from outside)
    /// may first drop the velocity to zero: the bound is the larger of the two starts, plus that
    /// cycle.
    fn settle_bound(&self, _stopped: bool) -> f64 {
        let parameters = self.parameters();
        let acceleration = parameters.acceleration.to_f64();
        let deceleration = match parameters.deceleration.to_f64() {
            0.0 => acceleration,
            rate => rate,
        };
        let target = counts(target(self));
        let time = |velocity: f64| {
            let same_side = velocity != 0.0 && target != 0.0 && (velocity > 0.0) == (target > 0.0);
            if velocity == 0.0 || (same_side && target.abs() >= velocity.abs()) {
                (target - velocity).abs() / acceleration
            } else if same_side {
                (velocity - target).abs() / deceleration
            } else {
                velocity.abs() / deceleration + target.abs() / acceleration
            }
        };
        time(counts(self.state().velocity.to_bits())).max(time(0.0)) + 3.0
    }

    fn settled(&self) -> bool {
        self.state().velocity.to_bits() == target(self)
    }

    fn velocity_register(&self) -> Option<i64> {
        Some(target(self))
    }

    /// Left alone, the velocity never moves away from the target (and never past it).
    fn check_cycle(&self, previous: &State, commanded: bool) -> Result<(), String> {
        let target = i128::from(target(self));
        let before = (target - i128::from(previous.velocity.to_bits())).abs();
        let after = (target - i128::from(self.state().velocity.to_bits())).abs();
        if !commanded && after > before {
            return Err(format!("the velocity moved away from the target {target}"));
        }
        Ok(())
    }

    fn check_settled(&self, _stopped: bool) -> Result<(), String> {
        if self.state().velocity.to_bits() != target(self) {
            return Err("settled off the target".into());
        }
        Ok(())
    }
}

/// A new target velocity anywhere in the register, −2^31 boosted too.
#[cfg(test)]
fn velocity() -> impl proptest::strategy::Strategy<Value = i32> {
    use super::boosted_signed;
    use proptest::prelude::*;
    prop_oneof![
        8 => boosted_signed(1 << 31).prop_map(velocity_bits),
        1 => Just(i32::MIN),
    ]
}

/// The proptest strategy of one command.
#[cfg(test)]
pub fn command() -> impl proptest::strategy::Strategy<Value = Command> {
    use super::boosted;
    use proptest::prelude::*;
    let rate = || boosted(0, Acceleration::MAX_BITS.into()).prop_map(|bits| bits as u32);
    prop_oneof![
        4 => velocity().prop_map(Command::Velocity),
        1 => Just(Command::Reverse),
        2 => rate().prop_map(Command::Acceleration),
        2 => rate().prop_map(Command::Deceleration),
    ]
}

/// The proptest strategy.
#[cfg(test)]
pub fn script() -> impl proptest::strategy::Strategy<Value = Script> {
    use super::{boosted, position, steps};
    use proptest::prelude::*;
    let rate = || boosted(0, Acceleration::MAX_BITS.into()).prop_map(|bits| bits as u32);
    (
        (velocity(), rate(), rate()),
        position(),
        steps(command(), 12),
    )
        .prop_map(|(parameters, position, steps)| Script {
            parameters,
            position,
            steps,
        })
}
