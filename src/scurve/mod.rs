//! MC1451A seven-phase S-curve point-to-point (SPEC §8): jerk-limited, planned before the first
//! step in a bounded number of integer operations, exact on arrival.
//!
//! The pieces, one file each:
//!
//! - this file: the generator, its commands and its stepping (four additions and a countdown
//!   per cycle; everything else happens on the few cycles where the jerk changes);
//! - [`search`]: the continuous optimum in integers and the fixed set of integer shapes tried,
//!   fastest first;
//! - [`shape`]: the shape algebra — the main move as units of triple boxes, and the unit mix
//!   that meets the maximum acceleration and velocity to the raw unit;
//! - [`remainder`]: the notch pairs that take the last of the distance, and the Diophantine
//!   solver that sizes them;
//! - [`volumes`]: short moves where only the jerk binds (under about 35 cycles, mostly what a
//!   stop leaves), planned first as a sum of at most `J` unit volumes `a·b·c` read off a table
//!   built at compile time — no notch pairs, no shapes;
//! - [`tiny`]: tiny moves with a jerk of one or two raw units (a few dozen raw units, what a
//!   stop often leaves), each distance's fastest plan read from a table;
//! - [`pure_jerk`]: moves where only the jerk binds (a few dozen cycles with a jerk of a few raw
//!   units, mostly what a stop leaves), whose notch pairs go wherever the jerk has room;
//! - [`roots`]: the integer square and cube roots the search starts from;
//! - [`products`]: 64-bit products that take one 32-bit multiplication where both factors
//!   fit (most of the planner's), checked as `u64::checked_mul` is;
//! - [`schedule`]: the sorted jerk changes, built once for the winner, and the pass that finds
//!   its peaks;
//! - [`stop`]: the jerk-limited smooth stop.
//!
//! How a move lands exactly is told once, on [`search::search`]'s `complete`: whole cycles of
//! cruise overshoot the distance, units whose cruise ends a cycle early take whole multiples of
//! their areas, and notch pairs take the rest.
//!
//! # Duration and cost
//!
//! Every plan is within 3 cycles of the continuous-time optimum
//! ([`crate::reference::scurve_duration`]): over 40,000,000 random moves across the register
//! ranges the worst was +2.91 cycles and the mean +0.93; over 3,000,000 moves of under 2^17 raw
//! units with a jerk of 1 to 15 raw units from fractional positions (where stops leave an axis)
//! the worst was +2.9993 (both surveys before [`volumes`], whose plans are within three cycles
//! of the optimum's floor by construction). The integer plan may keep a cycle or two
//! of constant acceleration below the maximum (phases II/VI) where the continuous optimum has
//! none; [`ScurvePlan::phases`] reports the phases of the move's main units as they are.
//!
//! Planning takes a bounded number of integer operations, the same on every target (no floating
//! point): at most eight shapes, each solved in closed form, a fixed number of notch-pair
//! placements per shape, one schedule built (and, in builds with debug assertions, replayed and
//! checked). Measured (see the README for the commands): 8,319 Cortex-M4 instructions median,
//! 14,615 at worst over the first 1,000 random moves, 15,233 over 5,000, 16,321 over 20,000,
//! 17,826 over 100,000 and 19,924 over the next 4,000,000, within SPEC §16's 20,000 (a sample:
//! the costliest, with a jerk of one raw unit whose first shapes' remainders do not fit, are a
//! few hundred under it); on the x86 development machine a few hundred nanoseconds median,
//! under about 2 µs at worst.
//! Tiny moves with a jerk of one or two raw units are read from a table of their fastest plans
//! ([`tiny`]: no plan of fewer cycles exists); short moves where only a jerk of three raw units
//! or more binds (mostly from fractional positions) are sums of unit volumes ([`volumes`]), and
//! those with a jerk of up to 15 are planned by [`pure_jerk`] next; moves the shapes near the
//! optimum cannot finish are planned by [`pure_jerk`] where only the jerk binds, else try up to
//! 24 more pairs of ramps around it, then the same shapes with one unit's area more in the
//! remainder, which costs more (random moves from fractional positions with a jerk of 1 to 15
//! raw units: a sample of 20,000 within SPEC §16's 20,000, worst 16,751; CI's sample of 3,000
//! worst 14,893; surveys of 3,000,000 within it, worst 18,913, where before 2026-12-07's changes
//! to [`pure_jerk`] 9 of 1,500,000 were over, up to 29,518: main moves whose rest lies between
//! the bands of spans narrow pairs take, and moves whose every rest is beyond them). A step
//! is at most 33 Cortex-M4 instructions (36 on the cycles after an abrupt stop), 18 on x86.

mod predict;
mod products;
mod pure_jerk;
mod remainder;
mod roots;
mod schedule;
mod search;
mod shape;
mod stop;
mod tiny;
mod volumes;

use fixed::types::I32F32;

use crate::format::mc1451a::{Destination, Jerk, MaxVelocity, ScurveAcceleration};
use crate::state::{Limits, ProfileGenerator, State, StopKind};
use crate::Error;
use schedule::{Limits64, Run, Schedule, ABRUPT_REST, AFTER_ABRUPT_REST, LAPS, PENDING, SENTINEL};

/// The parameters of an S-curve move, in MC1451A register formats.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct ScurveParameters {
    /// Destination, counts: the MC1451A destination register's range, −2³⁰ … 2³⁰ − 1
    /// ([`Destination`]); the same plain count as [`crate::TrapezoidalParameters::destination`].
    pub destination: i32,
    /// Maximum velocity, counts/cycle (1/2¹⁶), non-zero.
    pub max_velocity: MaxVelocity,
    /// Maximum acceleration, counts/cycle² (16 bits, 1/2¹⁶), non-zero.
    pub max_acceleration: ScurveAcceleration,
    /// Jerk, counts/cycle³ (1/2³²), non-zero.
    pub jerk: Jerk,
}

/// The plan of a move, known before its first step.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct ScurvePlan {
    /// Cycles in phases I–VII of the move's main units (II/VI are zero when the maximum
    /// acceleration is not reached, IV when the maximum velocity is not).
    pub phases: [u64; 7],
    /// Cycles from the first step to the last state (at the destination with velocity and
    /// acceleration zero), inclusive: the move is complete after this many steps.
    pub total: u64,
    /// The largest acceleration magnitude on any cycle of the move (speeding up or slowing
    /// down), counts/cycle²: exactly what stepping the move shows.
    pub peak_acceleration: I32F32,
    /// The largest velocity magnitude on any cycle of the move, counts/cycle: exactly what
    /// stepping the move shows.
    pub peak_velocity: I32F32,
}

/// Whether the axis is moving, and how.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Motion {
    /// At rest: complete.
    Rest,
    /// Following the plan.
    Planned,
    /// Smooth stop: jerk-limited deceleration to rest.
    Stopping,
    /// Abrupt stop on the next cycle.
    AbruptPending,
}

/// The MC1451A S-curve point-to-point generator.
///
/// ```
/// use profilegen::format::mc1451a::{Jerk, MaxVelocity, ScurveAcceleration};
/// use profilegen::{ProfileGenerator, SCurve, ScurveParameters};
///
/// // The datasheet's numbers: velocity 2.75, acceleration 0.175, jerk 0.0075.
/// let mut axis = SCurve::new(ScurveParameters {
///     destination: 1_000,
///     max_velocity: MaxVelocity::from_num(2.75)?,
///     max_acceleration: ScurveAcceleration::from_num(0.175)?,
///     jerk: Jerk::from_num(0.0075)?,
/// })?;
/// let plan = axis.plan();
/// let states: Vec<_> = axis.states_until_complete().collect();
/// assert_eq!(states.len() as u64, plan.total);
/// assert_eq!(states.last().unwrap().position, 1_000);
/// # Ok::<(), profilegen::Error>(())
/// ```
#[derive(Debug, Clone, PartialEq, Eq)]
// In declaration order, the state first: a step's hot fields then sit at the start of the
// generator, where a Cortex-M4 stores the state with one `stm` from the generator's address.
#[repr(C)]
pub struct SCurve {
    /// The state after the last step: its acceleration and velocity are the integrators.
    state: State,
    /// The run under way: the jerk the next step adds to the acceleration (I32F32 bits,
    /// direction included), the steps until the next event (a jerk change, the end of the move,
    /// a stop's next cycle), and where the replay goes then — the schedule's next run, replayed
    /// on the fast path of [`ProfileGenerator::step`] (a smooth stop's runs, after the plan's,
    /// too); past the schedule, [`PENDING`] (the change kept in `pending`), [`ABRUPT_REST`],
    /// a run's laps; off the plan (rest, a stop decided per cycle) the sentinel, which sends
    /// every event to the slow path. The move has arrived once its end marker is replayed.
    run: Run,
    /// The phase, as the last command or slow-path event left it (an abrupt stop's cycles do
    /// not update it: [`Self::motion`] reads it with them).
    motion: Motion,
    /// +1 or −1: the direction of the move.
    direction: i64,
    /// A change the fast path takes at index [`PENDING`], past the schedule: an abrupt stop's
    /// second cycle, whose jerk levels the drop's acceleration off (the plan's changes stay as
    /// they are, for [`Self::plan`]), then [`ABRUPT_REST`]; or, after the
    /// first step of a move started right after an abrupt stop (whose jerk was corrected for the
    /// drop's acceleration), the plan's replay from its second cycle.
    pending: Run,
    /// After a stop the velocity register reads zero (SPEC §9).
    velocity_cleared: bool,
    parameters: ScurveParameters,
    limits: Limits64,
    schedule: Schedule,
}

const REFUSED_IN_MOTION: &str = "while an S-curve move is in motion (MC1451A command error)";

/// The error of a destination outside its register.
#[cold]
#[inline(never)]
fn destination_error(destination: i32) -> Error {
    match Destination::from_bits(destination) {
        Err(error) => error,
        Ok(_) => Error::Refused {
            parameter: "destination",
            reason: "outside the register's range",
        },
    }
}

fn check(parameters: &ScurveParameters) -> Result<Limits64, Error> {
    // The destination register's range (±2^30 counts): two comparisons; its own error (built
    // off the planning path) names it.
    let destination = parameters.destination;
    if !(Destination::MIN_BITS..=Destination::MAX_BITS).contains(&destination) {
        return Err(destination_error(destination));
    }
    if parameters.max_velocity.is_zero() {
        return Err(Error::Zero {
            parameter: "velocity",
            range: MaxVelocity::RANGE,
        });
    }
    if parameters.max_acceleration.is_zero() {
        return Err(Error::Zero {
            parameter: "acceleration",
            range: ScurveAcceleration::RANGE,
        });
    }
    if parameters.jerk.is_zero() {
        return Err(Error::Zero {
            parameter: "jerk",
            range: Jerk::RANGE,
        });
    }
    // To I32F32 bits: velocity and acceleration are 1/2^16 (shift 16), jerk is 1/2^32 already.
    Ok(Limits64 {
        jerk: u64::from(parameters.jerk.to_bits()),
        acceleration: u64::from(parameters.max_acceleration.to_bits()) << 16,
        velocity: u64::from(parameters.max_velocity.to_bits()) << 16,
    })
}

/// Plans the move from `position` (at rest) to `parameters.destination` into `out`, and returns
/// its direction.
fn plan_move(
    parameters: &ScurveParameters,
    limits: Limits64,
    position: I32F32,
    out: &mut Schedule,
) -> Result<i64, Error> {
    let target = i64::from(parameters.destination) << 32;
    // The signed distance modulo the 32-bit position register: the short way round.
    let distance = target.wrapping_sub(position.to_bits());
    let direction = if distance < 0 { -1 } else { 1 };
    let magnitude = distance.unsigned_abs();
    if magnitude == 0 {
        out.clear();
        return Ok(direction);
    }
    if magnitude == 1 && limits.jerk < 2 {
        return Err(Error::Unreachable {
            parameter: "destination",
            reason: "it is 2^-32 counts away, and moving that little needs a jerk of 2^-31 \
                     counts/cycle³ (2 raw units): raise the jerk or choose another destination",
        });
    }
    // A velocity of the whole distance on one cycle, where the limits allow it: three cycles,
    // the fewest any move takes (a move shorter than a cycle of the continuous optimum, common
    // from the fractional position a stop leaves).
    if magnitude
        <= (limits.jerk / 2)
            .min(limits.acceleration)
            .min(limits.velocity)
    {
        out.pulse(magnitude, direction);
        return Ok(direction);
    }
    if search::at_velocity_in_one_cycle(magnitude, direction, limits, out)
        || search::search(magnitude, direction, limits, out)
    {
        Ok(direction)
    } else {
        Err(Error::Unreachable {
            parameter: "destination",
            reason: "no plan within the limits was found (please report this move)",
        })
    }
}

impl SCurve {
    /// A generator at rest at position 0, with the move to `parameters.destination` planned; it
    /// starts on the first step.
    ///
    /// # Errors
    /// [`Error::OutOfRange`] for a destination outside −2³⁰ … 2³⁰ − 1 counts (the MC1451A
    /// register); [`Error::Zero`] for a zero maximum velocity, maximum acceleration or jerk;
    /// [`Error::Unreachable`] for a destination 2^-32 counts away with a jerk of 2^-32
    /// counts/cycle³, the one distance no jerk-limited move can cover; also, were the planner
    /// to find no plan whose runs its schedule holds (none is known: its last resort, ramps of
    /// one cycle, fits any other distance within 2^48 cycles of cruise), for that move.
    pub fn new(parameters: ScurveParameters) -> Result<Self, Error> {
        Self::with_position(parameters, I32F32::ZERO)
    }

    /// As [`Self::new`], starting at rest at `position`.
    ///
    /// # Errors
    /// As [`Self::new`].
    pub fn with_position(parameters: ScurveParameters, position: I32F32) -> Result<Self, Error> {
        let limits = check(&parameters)?;
        let mut generator = Self {
            state: State::at_rest(position),
            run: Run::END,
            motion: Motion::Rest,
            direction: 1,
            pending: Run::END,
            velocity_cleared: false,
            parameters,
            limits,
            schedule: Schedule::EMPTY,
        };
        // Planned in place: the schedule is the largest part of the generator.
        generator.direction = plan_move(&parameters, limits, position, &mut generator.schedule)?;
        generator.start();
        Ok(generator)
    }

    /// The plan of the present move (all zero when at rest with nothing to do).
    ///
    /// Its peaks are found when asked for, by one pass over the plan's few dozen jerk changes
    /// (planning itself does not need them); [`Self::duration`] is the length alone, for nothing.
    pub fn plan(&self) -> ScurvePlan {
        // A smooth stop laid out over the plan's changes kept the plan with its peaks.
        if self.schedule.plan.peak_velocity != I32F32::ZERO {
            return self.schedule.plan;
        }
        // The peaks are found when asked for, off the planning path: one pass over the replay.
        let replay = self.schedule.replay(self.direction, self.limits);
        ScurvePlan {
            peak_acceleration: I32F32::from_bits(replay.peak_acceleration),
            peak_velocity: I32F32::from_bits(replay.peak_velocity),
            ..self.schedule.plan
        }
    }

    /// The present move's length in cycles (`plan().total`, without finding the peaks).
    pub fn duration(&self) -> u64 {
        self.schedule.plan.total
    }

    /// The parameters in force (after a stop the maximum velocity reads zero).
    pub fn parameters(&self) -> ScurveParameters {
        let mut parameters = self.parameters;
        if self.velocity_cleared {
            parameters.max_velocity = MaxVelocity::ZERO;
        }
        parameters
    }

    /// New parameters: at rest, they start a new move from the present position.
    ///
    /// # Errors
    /// [`Error::Refused`] while moving (the MC1451A "command error"; nothing changes);
    /// [`Error::OutOfRange`] for a destination outside the register's range;
    /// [`Error::Zero`] for a zero maximum velocity, acceleration or jerk;
    /// [`Error::Unreachable`] as for [`Self::new`]. Nothing changes on an error.
    pub fn set_parameters(&mut self, parameters: ScurveParameters) -> Result<(), Error> {
        if !self.is_complete() {
            return Err(Error::Refused {
                parameter: "S-curve parameters",
                reason: REFUSED_IN_MOTION,
            });
        }
        let limits = check(&parameters)?;
        // Planned in place: the planner writes the schedule only with a whole plan it has
        // found (every write is a `Schedule::build`, `pulse` or `clear` that succeeds; a
        // `build` that fails writes nothing, and a second plan made while one is in place is
        // made aside), so a refused plan changes nothing — and no 808-byte schedule is cleared
        // and copied in per move.
        #[cfg(debug_assertions)]
        let before = self.schedule;
        let direction =
            match plan_move(&parameters, limits, self.state.position, &mut self.schedule) {
                Ok(direction) => direction,
                Err(error) => {
                    #[cfg(debug_assertions)]
                    debug_assert!(
                        self.schedule == before,
                        "a refused plan changed the schedule"
                    );
                    return Err(error);
                }
            };
        self.parameters = parameters;
        self.limits = limits;
        self.direction = direction;
        self.velocity_cleared = false;
        self.start();
        Ok(())
    }

    /// A new destination, keeping the other parameters; as [`Self::set_parameters`].
    ///
    /// # Errors
    /// As [`Self::set_parameters`]; after a stop, [`Error::Refused`]: the stop cleared the
    /// velocity register, so a new move needs a velocity too ([`Self::restart`]).
    pub fn set_destination(&mut self, destination: i32) -> Result<(), Error> {
        if self.velocity_cleared && self.is_complete() {
            return Err(Error::Refused {
                parameter: "destination",
                reason: "alone after a stop: the stop cleared the velocity register; give the \
                         destination with a velocity (SCurve::restart, or set_parameters)",
            });
        }
        self.set_parameters(ScurveParameters {
            destination,
            ..self.parameters()
        })
    }

    /// After a smooth or abrupt stop (or at any time at rest): a new destination and a new
    /// maximum velocity together, keeping the acceleration and jerk, start a move from where the
    /// axis rests — the MC1451A way to restart after a stop cleared the velocity register.
    ///
    /// ```
    /// use profilegen::format::mc1451a::{Jerk, MaxVelocity, ScurveAcceleration};
    /// use profilegen::{ProfileGenerator, SCurve, ScurveParameters, StopKind};
    ///
    /// let mut axis = SCurve::new(ScurveParameters {
    ///     destination: 1_000,
    ///     max_velocity: MaxVelocity::from_num(2.0)?,
    ///     max_acceleration: ScurveAcceleration::from_num(0.1)?,
    ///     jerk: Jerk::from_num(0.01)?,
    /// })?;
    /// axis.states().take(40).for_each(drop);
    /// axis.stop(StopKind::Smooth);
    /// axis.states_until_complete().for_each(drop);
    /// axis.restart(-500, MaxVelocity::from_num(3.0)?)?;
    /// let last = axis.states_until_complete().last().unwrap();
    /// assert_eq!(last.position, -500);
    /// # Ok::<(), profilegen::Error>(())
    /// ```
    ///
    /// # Errors
    /// As [`Self::set_parameters`].
    pub fn restart(&mut self, destination: i32, max_velocity: MaxVelocity) -> Result<(), Error> {
        self.set_parameters(ScurveParameters {
            destination,
            max_velocity,
            ..self.parameters
        })
    }

    /// A new maximum velocity; as [`Self::set_parameters`].
    ///
    /// # Errors
    /// As [`Self::set_parameters`].
    pub fn set_max_velocity(&mut self, max_velocity: MaxVelocity) -> Result<(), Error> {
        self.set_parameters(ScurveParameters {
            max_velocity,
            ..self.parameters()
        })
    }

    /// A new maximum acceleration; as [`Self::set_parameters`].
    ///
    /// # Errors
    /// As [`Self::set_parameters`].
    pub fn set_max_acceleration(
        &mut self,
        max_acceleration: ScurveAcceleration,
    ) -> Result<(), Error> {
        self.set_parameters(ScurveParameters {
            max_acceleration,
            ..self.parameters()
        })
    }

    /// A new jerk; as [`Self::set_parameters`].
    ///
    /// # Errors
    /// As [`Self::set_parameters`].
    pub fn set_jerk(&mut self, jerk: Jerk) -> Result<(), Error> {
        self.set_parameters(ScurveParameters {
            jerk,
            ..self.parameters()
        })
    }

    /// The phase: as [`Self::motion`]'s field says, but at rest once an abrupt stop's cycle (the
    /// drop to zero velocity) has been stepped.
    fn motion(&self) -> Motion {
        match self.motion {
            Motion::AbruptPending if self.run.next != PENDING => Motion::Rest,
            motion => motion,
        }
    }

    /// The last step was an abrupt stop's drop, exempt from the limits (SPEC §9).
    fn exempt(&self) -> bool {
        self.motion == Motion::AbruptPending && self.run.next == ABRUPT_REST
    }

    /// Starts the planned move (or rests, if it is empty) on the next step.
    fn start(&mut self) {
        if self.schedule.plan.total == 0 {
            self.rest();
            return;
        }
        self.motion = Motion::Planned;
        // The first change is on cycle 0: it is the first step's jerk.
        let first = self.schedule.run(0);
        self.run = first;
        // Right after an abrupt stop the last acceleration is the drop: the first step of the
        // move starts from zero, so its jerk is corrected for that one cycle, and the replay
        // goes on from the plan's second cycle (a change past the schedule, `PENDING`).
        let acceleration = self.state.acceleration.to_bits();
        if acceleration != 0 {
            self.run = Run::new(first.jerk - acceleration, 1, PENDING);
            let cycles = first.cycles();
            self.pending = if cycles > 1 {
                Run::new(first.jerk, cycles - 1, first.after())
            } else {
                self.schedule.run(first.after())
            };
        }
    }

    /// Whether the planned move has replayed its end marker, or a smooth stop laid out as jerk
    /// changes has come to rest (it passes no other state of velocity and acceleration zero).
    fn arrived(&self) -> bool {
        match self.motion {
            Motion::Planned => self.run.next == SENTINEL,
            Motion::Stopping => self.state.velocity == 0 && self.state.acceleration == 0,
            _ => false,
        }
    }

    /// The slow path of [`ProfileGenerator::step`]: the event that the countdown reached.
    #[cold]
    #[inline(never)]
    fn event(&mut self) {
        if self.run.next >= LAPS {
            // A long run's next lap of 2^32 cycles (it has laps left: it came here), after
            // which, if it was the last, the replay goes on.
            self.run.laps -= 1;
            self.run.count = 0;
            if self.run.laps == 0 {
                self.run.next -= LAPS;
            }
            return;
        }
        let (acceleration, velocity) = (
            self.state.acceleration.to_bits(),
            self.state.velocity.to_bits(),
        );
        match self.motion {
            // Arrived: the end marker's hold ran out (after 2^64 steps), or nothing to follow.
            Motion::Planned => self.rest(),
            Motion::Stopping => {
                if velocity == 0 && acceleration == 0 {
                    self.rest();
                } else {
                    self.slow_down();
                }
            }
            // (An abrupt stop's cycles are replayed by the fast path of `step`.)
            Motion::AbruptPending | Motion::Rest => self.rest(),
        }
    }

    /// A smooth stop from the present state: laid out whole as jerk changes after the plan's
    /// ([`stop::lay_out`]), which the fast path of [`ProfileGenerator::step`] replays; from a
    /// state it does not cover, cycle by cycle ([`Self::slow_down`]).
    fn lay_out_stop(&mut self) {
        let laid_out = stop::lay_out(
            self.direction * self.state.acceleration.to_bits(),
            self.direction * self.state.velocity.to_bits(),
            self.limits,
        );
        let Some((changes, count)) = laid_out else {
            self.slow_down();
            return;
        };
        if !self.schedule.fits_after(count) {
            // The stop overwrites some of the plan's changes: the plan with its peaks is kept
            // for [`Self::plan`] (a pass over the changes, so only when needed).
            self.schedule.plan = self.plan();
        }
        let first = self.schedule.seal_at_end(&changes[..count], self.direction);
        self.run = self.schedule.run(first);
    }

    /// The next cycle of a smooth stop: the jerk that brings the acceleration to the stop's next
    /// one ([`stop::stopping_acceleration`]), for one step.
    fn slow_down(&mut self) {
        let acceleration = self.state.acceleration.to_bits();
        let next = stop::stopping_acceleration(
            self.direction * acceleration,
            self.direction * self.state.velocity.to_bits(),
            self.limits,
        );
        self.run = Run::new(self.direction * next - acceleration, 1, SENTINEL);
    }

    /// At rest: the next step levels the acceleration off if it is not zero yet.
    fn rest(&mut self) {
        self.motion = Motion::Rest;
        // Levelled off, the slow path comes back every 2^32 cycles (and rests again).
        let jerk = -self.state.acceleration.to_bits();
        self.run = Run::new(jerk, if jerk == 0 { 1 << 32 } else { 1 }, SENTINEL);
    }
}

impl ProfileGenerator for SCurve {
    #[inline]
    fn step(&mut self) -> State {
        // The identities of SPEC §5 by construction: the acceleration is the velocity change,
        // the position advances by the new velocity (wrapping like the chip's register). The
        // values stay within the limits, so the additions cannot overflow.
        let acceleration = self.state.acceleration.to_bits() + self.run.jerk;
        let velocity = self.state.velocity.to_bits() + acceleration;
        let state = State {
            position: I32F32::from_bits(self.state.position.to_bits().wrapping_add(velocity)),
            velocity: I32F32::from_bits(velocity),
            acceleration: I32F32::from_bits(acceleration),
        };
        self.state = state;
        self.run.count = self.run.count.wrapping_sub(1);
        if self.run.count == 0 {
            // The next run of the plan, replayed: copied whole, its jerk, its count and where
            // it goes next. The end marker, the last, sets the jerk to zero; the slow path's
            // indices, past the schedule, send the event there.
            let next = self.run.next;
            match self.schedule.run_at(next) {
                Some(run) => self.run = *run,
                // Past the schedule: the change kept apart (an abrupt stop's level-off, which
                // leaves the plan's changes as they are; the replay after a move's corrected
                // first step), then an abrupt stop's rest.
                None if next == PENDING => self.run = self.pending,
                None if next == ABRUPT_REST => {
                    self.run = Run::new(0, 1 << 32, AFTER_ABRUPT_REST);
                }
                None => self.event(),
            }
        }
        state
    }

    fn state(&self) -> State {
        self.state
    }

    /// At rest with the acceleration levelled off (or just after an abrupt stop, whose drop is
    /// exempt, SPEC §9), or at the end of the plan. A smooth stop on the cycle a move arrives
    /// (velocity zero, acceleration not yet) rests one cycle later: a move started at once would
    /// otherwise start its jerk from that acceleration and break the jerk limit (found by the
    /// scripted tests of issue #17).
    fn is_complete(&self) -> bool {
        (self.motion() == Motion::Rest
            && (self.state.acceleration == I32F32::ZERO || self.exempt()))
            || self.arrived()
    }

    fn stop(&mut self, kind: StopKind) {
        // Either stop clears the velocity register, moving or not (SPEC §9).
        self.velocity_cleared = true;
        let (acceleration, velocity) = (
            self.state.acceleration.to_bits(),
            self.state.velocity.to_bits(),
        );
        if self.arrived() {
            self.motion = Motion::Rest;
            self.run.next = SENTINEL;
        }
        match (kind, self.motion()) {
            (_, Motion::Rest) | (StopKind::Smooth, Motion::Stopping | Motion::AbruptPending) => {}
            // Not moved yet (a stop before the first step of a move): at rest already.
            (StopKind::Smooth, Motion::Planned) if velocity == 0 => self.rest(),
            (StopKind::Smooth, Motion::Planned) => {
                self.motion = Motion::Stopping;
                self.run.next = SENTINEL;
                self.lay_out_stop();
            }
            (StopKind::Abrupt, _) => {
                // The next step's acceleration is the whole drop to zero velocity, the one after
                // levels it off (a jerk of the velocity dropped), then rest: replayed by the
                // fast path of `step`.
                self.motion = Motion::AbruptPending;
                self.run = Run::new(-velocity - acceleration, 1, PENDING);
                self.pending = Run::new(velocity, 1, ABRUPT_REST);
            }
        }
    }

    fn limits(&self) -> Limits {
        let acceleration = Some(I32F32::from_bits(self.limits.acceleration as i64));
        Limits {
            max_velocity: Some(I32F32::from_bits(self.limits.velocity as i64)),
            max_speed_up: acceleration,
            max_slow_down: acceleration,
            max_acceleration: acceleration,
            max_jerk: Some(I32F32::from_bits(self.limits.jerk as i64)),
            exempt: self.exempt(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// A raw value log-uniform in `1 ..= max`.
    fn log_uniform(max: u64) -> impl Strategy<Value = u64> {
        (1..=64 - max.leading_zeros()).prop_flat_map(move |bits| {
            let low = 1u64 << (bits - 1);
            low..=((low << 1) - 1).min(max)
        })
    }

    /// What the sealed replay of a plan does, integrated in closed form per hold with 128-bit
    /// sums (independent of the planner's own check): the position, velocity and acceleration
    /// after the last cycle, and the largest |jerk| on the way.
    fn replay_end(schedule: &Schedule) -> (i128, i128, i128, i128) {
        let total = i128::from(schedule.plan.total);
        let (mut position, mut velocity, mut acceleration, mut steepest) = (0i128, 0, 0, 0);
        let mut cycle = 0i128;
        for (hold, jerk) in schedule.runs() {
            let jerk = i128::from(jerk);
            steepest = steepest.max(jerk.abs());
            let m = i128::from(hold).min(total - cycle);
            // m cycles of constant jerk: Σ velocity = m·v + a·m(m+1)/2 + j·m(m+1)(m+2)/6.
            position += m * velocity + acceleration * (m * (m + 1) / 2);
            if jerk != 0 {
                position += jerk * (m * (m + 1) * (m + 2) / 6);
            }
            velocity += acceleration * m + jerk * (m * (m + 1) / 2);
            acceleration += jerk * m;
            cycle += m;
            if cycle >= total {
                break;
            }
        }
        (position, velocity, acceleration, steepest)
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(10_000))]

        /// Every plan over the whole register ranges, moves of any length (too long to step),
        /// from positions with any fraction: its replay covers exactly the distance and ends at
        /// rest, its jerk within the limit, in exactly `plan.total` cycles.
        #[test]
        fn every_plan_lands_exactly(
            destination in log_uniform((1 << 30) - 1),
            negative in any::<bool>(),
            start in any::<i64>(),
            velocity in log_uniform(MaxVelocity::MAX_BITS.into()),
            acceleration in log_uniform(ScurveAcceleration::MAX_BITS.into()),
            jerk in log_uniform(Jerk::MAX_BITS.into()),
        ) {
            let destination = if negative { -(destination as i32) } else { destination as i32 };
            let parameters = ScurveParameters {
                destination,
                max_velocity: MaxVelocity::from_bits(velocity as u32).unwrap(),
                max_acceleration: ScurveAcceleration::from_bits(acceleration as u16).unwrap(),
                jerk: Jerk::from_bits(jerk as u32).unwrap(),
            };
            let start = I32F32::from_bits(start);
            let Ok(axis) = SCurve::with_position(parameters, start) else {
                // Only the one distance no jerk-limited move covers.
                let distance = (i64::from(destination) << 32).wrapping_sub(start.to_bits());
                prop_assert!(distance.unsigned_abs() == 1 && jerk == 1);
                return Ok(());
            };
            let distance = (i64::from(destination) << 32).wrapping_sub(start.to_bits());
            if distance == 0 {
                prop_assert_eq!(axis.plan().total, 0);
                return Ok(());
            }
            let (position, velocity, acceleration, steepest) = replay_end(&axis.schedule);
            prop_assert_eq!(position, i128::from(distance), "{:?}", axis.plan());
            prop_assert_eq!((velocity, acceleration), (0, 0));
            prop_assert!(steepest <= i128::from(jerk));
            let holds: u64 = axis.schedule.runs().map(|(hold, _)| hold).sum();
            prop_assert_eq!(holds, axis.plan().total, "the replay takes exactly the plan's cycles");
        }
    }

    /// A run's count and laps hold its length, from one cycle to the longest a move has
    /// (below 2^48), and a run that needs laps goes to the slow path after its count.
    #[test]
    fn runs_hold_their_lengths_in_count_and_laps() {
        for cycles in [
            1,
            2,
            (1 << 31) - 1,
            (1 << 32) - 1,
            1 << 32,
            (1 << 32) + 1,
            (1 << 33) + 5,
            (1 << 48) - 1,
        ] {
            let run = Run::new(-7, cycles, 3);
            assert_eq!(run.cycles(), cycles);
            assert_eq!(run.after(), 3);
            assert_eq!(run.next >= LAPS, cycles > 1 << 32, "{cycles}");
            assert_eq!(run.change().hold, cycles);
        }
        assert_eq!(
            Run::END.change().hold,
            u64::MAX,
            "an end marker holds for ever"
        );
    }

    /// The longest runs there are: a cruise at the least velocity (2^-16 counts/cycle) across
    /// the whole destination range, about 2^47 cycles. Stepped across the ends of its count,
    /// of a lap in the middle and of its last lap (put just before each by the prediction's
    /// closed forms, which read the runs' lengths, not the stepping), every state is the
    /// prediction's, and the cruise ends where the plan says.
    #[test]
    fn long_runs_count_their_laps() {
        let parameters = ScurveParameters {
            destination: (1 << 30) - 1,
            max_velocity: MaxVelocity::from_bits(1).unwrap(),
            max_acceleration: ScurveAcceleration::from_num(0.01).unwrap(),
            jerk: Jerk::from_num(0.001).unwrap(),
        };
        let start = SCurve::with_position(parameters, I32F32::from_num(-(1 << 30))).unwrap();
        let prediction = start.predict().unwrap();
        let (mut from, mut long) = (0u64, None);
        for (index, (cycles, _)) in start.schedule.runs().enumerate() {
            if cycles > 3 << 32 {
                long = Some((index as u16, from, cycles));
            }
            from += cycles;
        }
        let (index, first, cycles) = long.expect("a cruise of more than 2^33 cycles");
        let laps = (cycles - 1) >> 32;
        let count = cycles - (laps << 32);
        for (boundary, laps_left) in [
            (first + count, laps - 1),
            (first + count + (2 << 32), laps - 3),
            (first + cycles, 0),
        ] {
            let mut axis = start.clone();
            let at = boundary - 2;
            axis.state = prediction.state_at(at);
            axis.run = Run::new(
                start.schedule.run(index).jerk,
                first + cycles - at,
                index + 1,
            );
            for cycle in at + 1..=boundary + 2 {
                assert_eq!(axis.step(), prediction.state_at(cycle), "cycle {cycle}");
                if cycle < first + cycles {
                    assert_eq!(
                        axis.run.cycles(),
                        first + cycles - cycle,
                        "left after {cycle}"
                    );
                }
                if cycle == boundary && laps_left > 0 {
                    assert_eq!(axis.run.laps, laps_left as u16, "laps left after {cycle}");
                    assert_eq!(axis.run.next, LAPS + index + 1);
                }
            }
            if laps_left == 0 {
                assert!(axis.run.next < LAPS, "past the cruise, its laps counted");
            }
        }
    }
}
