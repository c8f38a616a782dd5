//! Trapezoidal point-to-point (SPEC §7) scripts: every parameter changed in motion, destinations
//! relative to the live position (across the ±2^31 wrap), stops and restarts.

use fixed::types::I32F32;
use profilegen::format::juno::{Acceleration, TargetVelocity};
use profilegen::reference::trapezoidal_duration;
use profilegen::{Error, ProfileGenerator, Trapezoidal, TrapezoidalParameters};

use super::{counts, Bytes, Scripted, Step};

/// A destination, from the live state.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Target {
    /// This many counts from the present position (wrapping at 32 bits, like the register).
    Relative(i64),
    /// This register value.
    Absolute(i32),
}

impl Target {
    fn resolve(self, position: I32F32) -> i32 {
        match self {
            // The integer part of the position, plus the offset, wrapped to the register.
            Target::Relative(offset) => ((position.to_bits() >> 32) + offset) as i32,
            Target::Absolute(destination) => destination,
        }
    }

    fn decode(bytes: &mut Bytes) -> Self {
        if bytes.byte() & 3 == 0 {
            Target::Absolute(
                bytes
                    .boosted_signed(1 << 31)
                    .clamp(i32::MIN.into(), i32::MAX.into()) as i32,
            )
        } else {
            Target::Relative(bytes.boosted_signed(1 << 32))
        }
    }
}

/// A command of a trapezoidal script, registers in raw bits.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Command {
    /// A new destination (never restarts a stopped axis).
    Destination(Target),
    /// A new maximum velocity (16.16; zero and negative are refused); restarts a stopped axis.
    MaxVelocity(i32),
    /// A new acceleration (8.24; zero is refused).
    Acceleration(u32),
    /// A new deceleration (8.24; zero means the acceleration).
    Deceleration(u32),
    /// A new starting velocity (16.16; refused outside 0 … the maximum velocity).
    StartVelocity(i32),
    /// After a stop: a new destination and maximum velocity together (`set_parameters`).
    Restart(Target, i32),
}

impl Command {
    /// Decodes a command from raw bytes (the fuzz targets).
    pub fn decode(bytes: &mut Bytes) -> Self {
        let velocity = |bytes: &mut Bytes| {
            bytes
                .boosted_signed(1 << 31)
                .clamp(i32::MIN.into(), i32::MAX.into()) as i32
        };
        let rate = |bytes: &mut Bytes| bytes.boosted(Acceleration::MAX_BITS.into()) as u32;
        match bytes.byte() % 6 {
            0 => Command::Destination(Target::decode(bytes)),
            1 => Command::MaxVelocity(velocity(bytes)),
            2 => Command::Acceleration(rate(bytes)),
            3 => Command::Deceleration(rate(bytes)),
            4 => Command::StartVelocity(velocity(bytes)),
            _ => Command::Restart(Target::decode(bytes), velocity(bytes)),
        }
    }
}

/// The generator and its script.
#[derive(Debug, Clone)]
pub struct Script {
    /// Destination, maximum velocity, acceleration, deceleration, starting velocity (raw; the
    /// starting velocity is capped at the maximum).
    pub parameters: (Target, i32, u32, u32, i32),
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
    pub fn build(&self) -> Result<Option<Trapezoidal>, String> {
        let (target, max_velocity, acceleration, deceleration, start_velocity) = self.parameters;
        let register = |result: Result<TargetVelocity, Error>| result.map_err(|e| e.to_string());
        let parameters = TrapezoidalParameters {
            destination: target.resolve(self.position),
            max_velocity: register(TargetVelocity::from_bits(max_velocity))?,
            acceleration: Acceleration::from_bits(acceleration).map_err(|e| e.to_string())?,
            deceleration: Acceleration::from_bits(deceleration).map_err(|e| e.to_string())?,
            start_velocity: register(TargetVelocity::from_bits(start_velocity.min(max_velocity)))?,
        };
        match Trapezoidal::with_position(parameters, self.position) {
            Ok(generator) => Ok(Some(generator)),
            Err(_) if max_velocity <= 0 || acceleration == 0 || start_velocity < 0 => Ok(None),
            Err(error) => Err(format!("valid parameters refused: {error}")),
        }
    }

    /// Decodes a script from raw bytes (the fuzz target).
    pub fn decode(bytes: &mut Bytes) -> Self {
        let target = Target::decode(bytes);
        let velocity = bytes.boosted(i32::MAX as u64) as i32;
        let acceleration = bytes.boosted(Acceleration::MAX_BITS.into()) as u32;
        let deceleration = bytes.boosted(Acceleration::MAX_BITS.into()) as u32;
        let start = if bytes.byte() & 1 == 0 {
            0
        } else {
            bytes.boosted(i32::MAX as u64) as i32
        };
        let position = bytes.position();
        let steps = bytes.steps(|bytes| Some(Command::decode(bytes)));
        Self {
            parameters: (target, velocity, acceleration, deceleration, start),
            position,
            steps,
        }
    }
}

/// Stopping or stopped: the maximum velocity register reads zero.
fn stopped(generator: &Trapezoidal) -> bool {
    generator.parameters().max_velocity.is_zero()
}

impl Scripted for Trapezoidal {
    /// SPEC §15: the prediction from the present state (`None` where the generator decides
    /// cycle by cycle, as during a smooth stop), checked against stepping by the runner.
    fn predict(&self, cycles: u64) -> Option<profilegen::State> {
        self.predict().map(|prediction| prediction.state_at(cycles))
    }

    type Command = Command;

    fn apply(&mut self, command: &Command) -> Result<(), Error> {
        let position = self.state().position;
        match *command {
            Command::Destination(target) => self.set_destination(target.resolve(position)),
            Command::MaxVelocity(bits) => {
                self.set_max_velocity(TargetVelocity::from_bits(bits)?)?
            }
            Command::Acceleration(bits) => self.set_acceleration(Acceleration::from_bits(bits)?)?,
            Command::Deceleration(bits) => self.set_deceleration(Acceleration::from_bits(bits)?),
            Command::StartVelocity(bits) => {
                self.set_start_velocity(TargetVelocity::from_bits(bits)?)?;
            }
            Command::Restart(target, velocity) => self.set_parameters(TrapezoidalParameters {
                destination: target.resolve(position),
                max_velocity: TargetVelocity::from_bits(velocity)?,
                ..self.parameters()
            })?,
        }
        Ok(())
    }

    /// Stopping: |v| / D. Heading for the destination: no slower than stopping at D and then
    /// making the rest-to-rest move from where it stopped (the continuous optimum of
    /// [`trapezoidal_duration`], with the starting-velocity jumps), with the discrete stop's
    /// extra distance (< |v| + 1) and a few cycles of discretization. The jump to the starting
    /// velocity (and the drop from it) only from rest: an axis in motion reverses through zero at
    /// D and A (SPEC §7), so it is left out of the bound then (a slower, still valid bound).
    fn settle_bound(&self, _stopped: bool) -> f64 {
        let parameters = self.parameters();
        let acceleration = parameters.acceleration.to_f64();
        let deceleration = match parameters.deceleration.to_f64() {
            0.0 => acceleration,
            rate => rate,
        };
        let state = self.state();
        let velocity = counts(state.velocity.to_bits());
        let stopping = velocity.abs() / deceleration + 1.0;
        if stopped(self) {
            return stopping + 2.0;
        }
        let position = counts(state.position.to_bits());
        let start_velocity = if state.velocity == 0 && state.acceleration == 0 {
            parameters.start_velocity.to_f64()
        } else {
            0.0
        };
        let go = |distance: f64| {
            trapezoidal_duration(
                distance,
                parameters.max_velocity.to_f64(),
                acceleration,
                deceleration,
                start_velocity,
            )
        };
        let destination = f64::from(parameters.destination);
        let stop_point = position + velocity * velocity.abs() / (2.0 * deceleration);
        let smooth = stopping + go((destination - stop_point).abs() + velocity.abs() + 1.0);
        // An abrupt stop may be pending (invisible from outside): stopped where it is, at once.
        let abrupt = 1.0 + go((destination - position).abs() + 1.0);
        smooth.max(abrupt) + 8.0
    }

    fn velocity_register(&self) -> Option<i64> {
        Some(self.parameters().max_velocity.to_bits().into())
    }

    /// At rest; exactly on the destination unless stopped.
    fn check_settled(&self, _stopped: bool) -> Result<(), String> {
        let state = self.state();
        let destination = i64::from(self.parameters().destination) << 32;
        if state.velocity != 0 || (!stopped(self) && state.position.to_bits() != destination) {
            return Err(format!(
                "settled off the destination {destination} (bits): {state:?}"
            ));
        }
        Ok(())
    }
}

/// The proptest strategy.
#[cfg(test)]
pub fn script() -> impl proptest::strategy::Strategy<Value = Script> {
    use super::{boosted, boosted_signed, position, steps};
    use proptest::prelude::*;
    let target = || {
        prop_oneof![
            3 => boosted_signed(1 << 32).prop_map(Target::Relative),
            1 => boosted_signed(1 << 31)
                .prop_map(|bits| Target::Absolute(bits.clamp(i32::MIN.into(), i32::MAX.into()) as i32)),
        ]
    };
    let signed_velocity = || {
        boosted_signed(1 << 31).prop_map(|bits| bits.clamp(i32::MIN.into(), i32::MAX.into()) as i32)
    };
    let velocity = || boosted(1, i32::MAX as u64).prop_map(|bits| bits as i32);
    let rate = || boosted(0, Acceleration::MAX_BITS.into()).prop_map(|bits| bits as u32);
    let start = prop_oneof![3 => Just(0), 1 => velocity()];
    let command = prop_oneof![
        3 => target().prop_map(Command::Destination),
        2 => signed_velocity().prop_map(Command::MaxVelocity),
        2 => rate().prop_map(Command::Acceleration),
        2 => rate().prop_map(Command::Deceleration),
        1 => signed_velocity().prop_map(Command::StartVelocity),
        2 => (target(), velocity()).prop_map(|(target, velocity)| Command::Restart(target, velocity)),
    ];
    (
        (target(), velocity(), rate(), rate(), start),
        position(),
        steps(command, 12),
    )
        .prop_map(|(parameters, position, steps)| Script {
            parameters,
            position,
            steps,
        })
}
