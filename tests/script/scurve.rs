//! S-curve point-to-point (SPEC §8) scripts: moves planned from rest at any fraction, commands
//! in motion (refused, changing nothing), smooth and abrupt stops from every phase, restarts.

use fixed::types::I32F32;
use profilegen::format::mc1451a::{Destination, Jerk, MaxVelocity, ScurveAcceleration};
use profilegen::reference::scurve_duration;
use profilegen::{Error, ProfileGenerator, SCurve, ScurveParameters, State};

use super::{counts, Bytes, Scripted, Step};

/// The destination register's range.
const DESTINATIONS: (i64, i64) = (Destination::MIN_BITS as i64, Destination::MAX_BITS as i64);

/// A destination, from the live state.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Target {
    /// This many counts from the present position's integer part (within the register; 0 and
    /// ±1 are moves under a count or two from a fractional position).
    Relative(i64),
    /// This register value.
    Absolute(i32),
}

impl Target {
    fn resolve(self, position: I32F32) -> Result<i32, Error> {
        let bits = match self {
            Target::Relative(offset) => {
                ((position.to_bits() >> 32) + offset).clamp(DESTINATIONS.0, DESTINATIONS.1) as i32
            }
            Target::Absolute(destination) => destination,
        };
        // The register's range, checked here so a script names it as the generator would.
        Destination::from_bits(bits).map(|destination| destination.to_bits())
    }

    fn decode(bytes: &mut Bytes) -> Self {
        if bytes.byte() & 3 == 0 {
            Target::Absolute(
                bytes
                    .boosted_signed(1 << 30)
                    .clamp(DESTINATIONS.0, DESTINATIONS.1) as i32,
            )
        } else {
            Target::Relative(bytes.boosted_signed(1 << 31))
        }
    }
}

/// A command of an S-curve script, registers in raw bits (zeros are refused, and every command
/// is refused in motion).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Command {
    /// Every parameter: destination, maximum velocity, maximum acceleration, jerk.
    Parameters(Target, u32, u16, u32),
    /// A new destination (refused after a stop, which cleared the velocity).
    Destination(Target),
    /// After a stop: a new destination and maximum velocity together.
    Restart(Target, u32),
    /// A new maximum velocity.
    MaxVelocity(u32),
    /// A new maximum acceleration.
    MaxAcceleration(u16),
    /// A new jerk.
    Jerk(u32),
}

fn velocity_bits(bytes: &mut Bytes) -> u32 {
    bytes.boosted(MaxVelocity::MAX_BITS.into()) as u32
}
fn acceleration_bits(bytes: &mut Bytes) -> u16 {
    bytes.boosted(ScurveAcceleration::MAX_BITS.into()) as u16
}
fn jerk_bits(bytes: &mut Bytes) -> u32 {
    bytes.boosted(Jerk::MAX_BITS.into()) as u32
}

impl Command {
    fn decode(bytes: &mut Bytes) -> Self {
        match bytes.byte() % 6 {
            0 => Command::Parameters(
                Target::decode(bytes),
                velocity_bits(bytes),
                acceleration_bits(bytes),
                jerk_bits(bytes),
            ),
            1 => Command::Destination(Target::decode(bytes)),
            2 => Command::Restart(Target::decode(bytes), velocity_bits(bytes)),
            3 => Command::MaxVelocity(velocity_bits(bytes)),
            4 => Command::MaxAcceleration(acceleration_bits(bytes)),
            _ => Command::Jerk(jerk_bits(bytes)),
        }
    }
}

/// The generator and its script.
#[derive(Debug, Clone)]
pub struct Script {
    /// The first move: destination, maximum velocity, maximum acceleration, jerk (raw).
    pub parameters: (Target, u32, u16, u32),
    /// Where it starts.
    pub position: I32F32,
    /// The steps.
    pub steps: Vec<Step<Command>>,
}

fn parameters(
    (target, velocity, acceleration, jerk): (Target, u32, u16, u32),
    position: I32F32,
) -> Result<ScurveParameters, Error> {
    Ok(ScurveParameters {
        destination: target.resolve(position)?,
        max_velocity: MaxVelocity::from_bits(velocity)?,
        max_acceleration: ScurveAcceleration::from_bits(acceleration)?,
        jerk: Jerk::from_bits(jerk)?,
    })
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
    pub fn build(&self) -> Result<Option<SCurve>, String> {
        let parameters = parameters(self.parameters, self.position).map_err(|e| e.to_string())?;
        match SCurve::with_position(parameters, self.position) {
            Ok(generator) => Ok(Some(generator)),
            Err(error) => refusal(&parameters, self.position, &error).map(|()| None),
        }
    }

    /// Decodes a script from raw bytes (the fuzz target).
    pub fn decode(bytes: &mut Bytes) -> Self {
        let parameters = (
            Target::decode(bytes),
            velocity_bits(bytes),
            acceleration_bits(bytes),
            jerk_bits(bytes),
        );
        let position = bytes.position();
        let steps = bytes.steps(|bytes| Some(Command::decode(bytes)));
        Self {
            parameters,
            position,
            steps,
        }
    }
}

/// The signed distance (I32F32 bits) from `position` to the destination, the short way round
/// the 32-bit register.
fn distance(destination: i32, position: I32F32) -> i64 {
    (i64::from(destination) << 32).wrapping_sub(position.to_bits())
}

/// A move refused from rest must be one SPEC §8 and the docs allow to refuse: a zero register,
/// or 2^-32 counts with a jerk of 1 LSB.
fn refusal(parameters: &ScurveParameters, position: I32F32, error: &Error) -> Result<(), String> {
    let zero = parameters.max_velocity.is_zero()
        || parameters.max_acceleration.is_zero()
        || parameters.jerk.is_zero();
    let unreachable = distance(parameters.destination, position).unsigned_abs() == 1
        && parameters.jerk.to_bits() == 1;
    if zero || unreachable {
        Ok(())
    } else {
        Err(format!(
            "a valid move refused from rest at {position}: {parameters:?}: {error}"
        ))
    }
}

/// A stop came after the last move began: the velocity register reads zero.
fn cleared(generator: &SCurve) -> bool {
    generator.parameters().max_velocity.is_zero()
}

impl Scripted for SCurve {
    /// SPEC §15: the prediction from the present state (`None` where the generator decides
    /// cycle by cycle, as during a smooth stop), checked against stepping by the runner.
    fn predict(&self, cycles: u64) -> Option<State> {
        self.predict().map(|prediction| prediction.state_at(cycles))
    }

    type Command = Command;

    fn apply(&mut self, command: &Command) -> Result<(), Error> {
        let position = self.state().position;
        let at_rest = self.is_complete();
        let (result, attempted) = match *command {
            Command::Parameters(target, velocity, acceleration, jerk) => {
                match parameters((target, velocity, acceleration, jerk), position) {
                    Ok(parameters) => (self.set_parameters(parameters), Some(parameters)),
                    Err(error) => (Err(error), None),
                }
            }
            Command::Destination(target) => {
                let destination = target.resolve(position)?;
                let attempted = ScurveParameters {
                    destination,
                    ..self.parameters()
                };
                (self.set_destination(destination), Some(attempted))
            }
            Command::Restart(target, velocity) => {
                let destination = target.resolve(position)?;
                let max_velocity = MaxVelocity::from_bits(velocity)?;
                let attempted = ScurveParameters {
                    destination,
                    max_velocity,
                    ..self.parameters()
                };
                (self.restart(destination, max_velocity), Some(attempted))
            }
            Command::MaxVelocity(bits) => {
                (self.set_max_velocity(MaxVelocity::from_bits(bits)?), None)
            }
            Command::MaxAcceleration(bits) => (
                self.set_max_acceleration(ScurveAcceleration::from_bits(bits)?),
                None,
            ),
            Command::Jerk(bits) => (self.set_jerk(Jerk::from_bits(bits)?), None),
        };
        // A refusal at rest, of a full set of valid registers, must be one the docs allow.
        if let (Err(error), true, Some(attempted)) = (&result, at_rest, attempted) {
            if !(cleared(self) && matches!(command, Command::Destination(_))) {
                if let Err(message) = refusal(&attempted, position, error) {
                    panic!("{message}");
                }
            }
        }
        result
    }

    /// A planned move: its whole plan (no more is left of it). A stop: level the acceleration
    /// off (|a| / J, changing the velocity by a²/2J), then the continuous time of a jerk-limited
    /// stop from that velocity — at most 2·Amax/J + |v|/Amax, or 2·√(|v|/J) — plus a few cycles.
    fn settle_bound(&self, _stopped: bool) -> f64 {
        if self.is_complete() {
            return 0.0;
        }
        if !cleared(self) {
            return self.duration() as f64 + 2.0;
        }
        let parameters = self.parameters();
        let jerk = parameters.jerk.to_f64();
        let maximum = parameters.max_acceleration.to_f64();
        let state = self.state();
        let (velocity, acceleration) = (
            counts(state.velocity.to_bits()),
            counts(state.acceleration.to_bits()),
        );
        let sign = if velocity != 0.0 {
            velocity.signum()
        } else {
            acceleration.signum()
        };
        let (velocity, acceleration) = (velocity * sign, acceleration * sign);
        let level = acceleration.abs() / jerk;
        let left = (velocity + acceleration * acceleration.abs() / (2.0 * jerk)).abs();
        level + 2.0 * maximum / jerk + left / maximum + 2.0 * (left / jerk).sqrt() + 8.0
    }

    fn velocity_register(&self) -> Option<i64> {
        Some(self.parameters().max_velocity.to_bits().into())
    }

    /// SPEC §8: a move never passes its destination.
    fn check_cycle(&self, previous: &State, _commanded: bool) -> Result<(), String> {
        if cleared(self) {
            return Ok(());
        }
        let destination = self.parameters().destination;
        let (before, after) = (
            distance(destination, previous.position),
            distance(destination, self.state().position),
        );
        if before != 0 && after != 0 && (before < 0) != (after < 0) {
            return Err(format!("passed the destination {destination:?}"));
        }
        Ok(())
    }

    /// SPEC §8: a move from rest is planned within 4 cycles of the continuous-time optimum.
    fn check_command(&self) -> Result<(), String> {
        if cleared(self) {
            return Ok(());
        }
        let parameters = self.parameters();
        let distance = distance(parameters.destination, self.state().position);
        if distance == 0 {
            return Ok(());
        }
        let optimum = scurve_duration(
            counts(distance).abs(),
            parameters.max_velocity.to_f64(),
            parameters.max_acceleration.to_f64(),
            parameters.jerk.to_f64(),
        );
        let plan = self.plan();
        // KNOWN (issue #11, open): when no shape of the search nor the ramps around the optimum
        // fit (moves of a few counts or less with a jerk of a few raw units, mostly from the
        // fractional positions stops leave), the planner falls back to ramps of one cycle
        // (`search::one_cycle_ramps`: phases [1, 0, 1, c, 1, 0, 1], peak acceleration = peak
        // velocity = the units). Such a move is held to that plan's own length, by hand: at
        // most m = min(J, A, V) per moving cycle, c = max(⌈D/m⌉, 2) or one more of them, and two
        // cycles to rest — so it still finishes in a bound derived from the registers, and each
        // one past the optimum's bound is counted (a planner shortfall, not a skipped check).
        let one_cycle_ramps = matches!(plan.phases, [1, 0, 1, _, 1, 0, 1])
            && plan.peak_acceleration == plan.peak_velocity;
        // KNOWN, same note: a move whose continuous optimum is under a cycle (a sub-count move
        // with a large jerk) may take 5 cycles where 3 would do (one cycle of velocity, the
        // arrival, the cycle that zeroes the acceleration); the bound counts from one cycle.
        let floor = optimum.max(1.0);
        if self.duration() as f64 > floor + 4.0 {
            let most = u64::from(parameters.jerk.to_bits())
                .min(u64::from(parameters.max_acceleration.to_bits()) << 16)
                .min(u64::from(parameters.max_velocity.to_bits()) << 16);
            let ramps_bound = distance.unsigned_abs().div_ceil(most).max(2) + 3;
            if one_cycle_ramps && self.duration() <= ramps_bound {
                super::excluded();
                return Ok(());
            }
            return Err(format!(
                "planned {} cycles, the optimum is {optimum:.3}: {parameters:?}, {plan:?}",
                self.duration()
            ));
        }
        Ok(())
    }

    /// At rest with zero acceleration; exactly on the destination unless stopped.
    fn check_settled(&self, _stopped: bool) -> Result<(), String> {
        let state = self.state();
        let on = distance(self.parameters().destination, state.position) == 0;
        if state.velocity != 0
            || state.acceleration != 0 && !cleared(self)
            || !(on || cleared(self))
        {
            return Err(format!("settled off the destination: {state:?}"));
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
            3 => boosted_signed(1 << 31).prop_map(Target::Relative),
            1 => boosted_signed(1 << 30)
                .prop_map(|bits| Target::Absolute(bits.clamp(DESTINATIONS.0, DESTINATIONS.1) as i32)),
        ]
    };
    let velocity = || boosted(0, MaxVelocity::MAX_BITS.into()).prop_map(|bits| bits as u32);
    let acceleration =
        || boosted(0, ScurveAcceleration::MAX_BITS.into()).prop_map(|bits| bits as u16);
    let jerk = || boosted(0, Jerk::MAX_BITS.into()).prop_map(|bits| bits as u32);
    let all = || (target(), velocity(), acceleration(), jerk());
    let command = prop_oneof![
        2 => all().prop_map(|(t, v, a, j)| Command::Parameters(t, v, a, j)),
        2 => target().prop_map(Command::Destination),
        3 => (target(), velocity()).prop_map(|(target, velocity)| Command::Restart(target, velocity)),
        1 => velocity().prop_map(Command::MaxVelocity),
        1 => acceleration().prop_map(Command::MaxAcceleration),
        1 => jerk().prop_map(Command::Jerk),
    ];
    (all(), position(), steps(command, 12)).prop_map(|(parameters, position, steps)| Script {
        parameters,
        position,
        steps,
    })
}
