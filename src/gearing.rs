//! MC1451A electronic gearing (SPEC §14): a follower whose commanded position is a master's
//! position times the gear ratio, exactly, for ever.
//!
//! The master is a position register in whole counts: another generator's (the integer part of
//! its position, as the chip's register holds it) or an encoder's count given each cycle. Its
//! 32-bit wrap is undone by taking each cycle's change modulo 2³² (a master moves less than 2³¹
//! counts per cycle). The follower is, on every cycle,
//!
//! ```text
//! slave(n) = slave(0) + ratio · (master(n) − master(0))      (ratio: signed, 1/2^16)
//! ```
//!
//! exactly: each cycle moves it by the ratio times the master's change, and the product of a
//! count and a 1/2¹⁶ ratio has 16 fractional bits, which I32F32 holds, so every cycle's step is
//! an exact number of raw units and their sum is exactly the product of the whole travel — no
//! rounding to accumulate, no drift over any number of cycles. The position register wraps at
//! 32 integer bits, so the sum is kept modulo 2⁶⁴ raw units, as the register is (and as the
//! product of the whole travel would be). The velocity and acceleration are the differences
//! (SPEC §5); a ratio change applies from the present position on, so the velocity jumps, as
//! on the chip.
//!
//! The follower's speed is the ratio times the master's change in a cycle: it must stay below
//! 2³⁰ counts per cycle (e.g. a master moving at most 2¹⁶ counts a cycle at the largest ratio,
//! 16,384), so that its velocity and acceleration (a difference of two velocities) fit I32F32.
//! Past that they wrap (the position stays exact modulo the register; the §5 acceleration
//! identity no longer holds in plain arithmetic): no physical drive moves half its position
//! register in one cycle, and the counts come in each cycle with no error to return.
//!
//! Stops disengage the gear: abrupt, velocity zero on the next cycle; smooth, the velocity falls
//! to zero by the follower's deceleration per cycle (the crate's choice: the manuals are silent).

use fixed::types::I32F32;

use crate::format::mc1451a::{GearRatio, TrapezoidalAcceleration};
use crate::replay::{Countdown, End};
use crate::state::{advance, Limits, ProfileGenerator, State, StopKind};
use crate::Error;

/// Whether the gear follows its master.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Mode {
    /// Following.
    Engaged,
    /// Smooth stop: decelerating to rest.
    Stopping,
    /// Abrupt stop on the next cycle.
    AbruptPending,
    /// At rest, disengaged, the last cycle an abrupt stop's (exempt from the limits).
    AbruptStopped,
    /// At rest, disengaged.
    Stopped,
}

/// The follower of an electronic gear, fed the master's count each cycle
/// ([`Self::follow`]). [`Follower`] and [`EncoderFollower`] wrap it into a
/// [`ProfileGenerator`].
///
/// ```
/// use profilegen::fixed::types::I32F32;
/// use profilegen::format::mc1451a::{GearRatio, TrapezoidalAcceleration};
/// use profilegen::gearing::ElectronicGear;
///
/// let mut gear = ElectronicGear::new(
///     GearRatio::from_num(1.5)?,
///     1_000,                  // the master's count now
///     I32F32::from_num(-20),  // the follower's position now
///     TrapezoidalAcceleration::from_num(0.5)?,
/// )?;
/// gear.follow(1_001);
/// let state = gear.follow(1_004);
/// // −20 + 1.5 · (1,004 − 1,000) = −14, moving 1.5 · 3 = 4.5 counts on that cycle.
/// assert_eq!((state.position, state.velocity), (I32F32::from_num(-14), I32F32::from_num(4.5)));
/// # Ok::<(), profilegen::Error>(())
/// ```
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ElectronicGear {
    state: State,
    /// The ratio in force as the follower's travel per master count, I32F32 bits: the 16.16
    /// register shifted left 16 (below 2^47), so a cycle multiplies once and shifts nothing.
    ratio: i64,
    /// The master's last count.
    master: i32,
    mode: Mode,
    /// The smooth stop's deceleration, I32F32 bits (the 16.16 register shifted left 16).
    deceleration: i64,
    /// Disengaged: what each cycle adds to the velocity (while stopping, the deceleration
    /// against the velocity's sign; at rest, nothing), worked out when the stop is given, so a
    /// cycle decides nothing.
    braking: i64,
    /// Disengaged: the cycles until the next comes to rest (the smooth stop's count, worked out
    /// when it is given; one for an abrupt stop and the cycle after it; 2^64 − 1 at rest, so
    /// that a cycle at rest takes the same path). Counted in 32 bits with the laps apart
    /// ([`Countdown`]): a 32-bit core counts a 32-bit word down in two instructions where a
    /// 64-bit one takes five, and a stop takes more than 2^32 cycles only from a velocity
    /// wrapped far past the speed limit.
    until_rest: Countdown,
}

impl ElectronicGear {
    /// A follower at rest at `slave_position`, engaged with `ratio` to a master whose count is
    /// `master` now; `deceleration` is its smooth stop's.
    ///
    /// # Errors
    /// [`Error::Zero`] for a zero deceleration.
    pub fn new(
        ratio: GearRatio,
        master: i32,
        slave_position: I32F32,
        deceleration: TrapezoidalAcceleration,
    ) -> Result<Self, Error> {
        if deceleration.is_zero() {
            return Err(Error::Zero {
                parameter: "deceleration",
                range: TrapezoidalAcceleration::RANGE,
            });
        }
        Ok(Self {
            state: State::at_rest(slave_position),
            ratio: i64::from(ratio.to_bits()) << 16,
            master,
            mode: Mode::Engaged,
            deceleration: i64::from(deceleration.to_bits()) << 16,
            braking: 0,
            until_rest: Countdown::new(u64::MAX),
        })
    }

    /// The ratio in force.
    pub fn ratio(&self) -> GearRatio {
        // Built from a register's raw value, so it converts back.
        GearRatio::from_bits((self.ratio >> 16) as i32).unwrap_or(GearRatio::ZERO)
    }

    /// Whether the gear follows its master (not stopped, nor stopping).
    pub fn is_engaged(&self) -> bool {
        self.mode == Mode::Engaged
    }

    /// A new ratio, from the next cycle on: the follower goes on from where it is at the new
    /// ratio of the master's travel from where it is (the velocity jumps). Re-engages a stopped
    /// or stopping gear.
    pub fn set_ratio(&mut self, ratio: GearRatio) {
        self.ratio = i64::from(ratio.to_bits()) << 16;
        if self.mode != Mode::AbruptPending {
            self.mode = Mode::Engaged;
        }
    }

    /// Works out the disengaged cycles for the mode in force: a smooth stop's braking and its
    /// count, ⌈|v| / D⌉ cycles (the last the one that reaches or would pass zero: it rests);
    /// an abrupt stop's one cycle; nothing at rest.
    fn brake(&mut self) {
        let velocity = self.state.velocity.to_bits();
        (self.braking, self.until_rest) = match self.mode {
            Mode::Stopping => (
                if velocity > 0 {
                    -self.deceleration
                } else {
                    self.deceleration
                },
                // D ≥ 2^16: one division, when the stop is given.
                Countdown::new(velocity.unsigned_abs().div_ceil(self.deceleration as u64)),
            ),
            Mode::AbruptPending | Mode::AbruptStopped => (0, Countdown::new(1)),
            Mode::Engaged | Mode::Stopped => (0, Countdown::new(u64::MAX)),
        };
    }

    /// A new smooth-stop deceleration.
    ///
    /// # Errors
    /// [`Error::Zero`] for zero (nothing changes).
    pub fn set_deceleration(&mut self, deceleration: TrapezoidalAcceleration) -> Result<(), Error> {
        if deceleration.is_zero() {
            return Err(Error::Zero {
                parameter: "deceleration",
                range: TrapezoidalAcceleration::RANGE,
            });
        }
        self.deceleration = i64::from(deceleration.to_bits()) << 16;
        if self.mode == Mode::Stopping {
            // From the present velocity at the new deceleration.
            self.brake();
        }
        Ok(())
    }

    /// The present state.
    pub fn state(&self) -> State {
        self.state
    }

    /// One cycle with the master's count `master` (it may wrap: each cycle's change is taken
    /// modulo 2³², so it must be below 2³¹ counts). Returns the follower's new state.
    pub fn follow(&mut self, master: i32) -> State {
        // Engaged or not: one comparison (a jump table over the modes takes four instructions),
        // and disengaged, one countdown: every decision was made when the stop was given.
        let velocity = if self.mode == Mode::Engaged {
            // The change modulo 2^32, as a signed count: the wrap undone.
            let change = i64::from(master.wrapping_sub(self.master));
            self.master = master;
            // The ratio times the change: a whole number of raw units, modulo 2^64 as the
            // position register wraps (exact below the speed limit of the module docs).
            self.ratio.wrapping_mul(change)
        } else {
            self.master = master;
            match self.until_rest.tick() {
                End::Run => {
                    self.rest();
                    0
                }
                end => {
                    if end == End::Lap {
                        self.until_rest.lap();
                    }
                    // Toward zero, before the cycle that rests. (At rest: zero plus zero, for
                    // 2^64 − 1 cycles before the count's end rests it again.)
                    self.state.velocity.to_bits() + self.braking
                }
            }
        };
        // The state built in place and returned from locals (a store and a copy back would
        // cost a pass through memory).
        advance(&mut self.state, I32F32::from_bits(velocity))
    }

    /// The cycle that comes to rest (a smooth stop's last, an abrupt stop's): from then on,
    /// at rest — for one cycle marked as the abrupt stop's, whose drop is exempt. Out of line:
    /// a stop's last cycle, taken once.
    fn rest(&mut self) {
        self.mode = if self.mode == Mode::AbruptPending {
            Mode::AbruptStopped
        } else {
            Mode::Stopped
        };
        self.brake();
    }

    /// Whether the follower is at rest and disengaged.
    pub fn is_complete(&self) -> bool {
        matches!(self.mode, Mode::Stopped | Mode::AbruptStopped)
            && self.state.velocity == I32F32::ZERO
    }

    /// A stop (SPEC §14): abrupt, velocity zero on the next cycle; smooth, decelerate at the
    /// follower's deceleration. Either disengages the gear ([`Self::set_ratio`] re-engages).
    pub fn stop(&mut self, kind: StopKind) {
        self.mode = match (kind, self.mode) {
            (_, mode @ (Mode::Stopped | Mode::AbruptStopped)) => mode,
            (StopKind::Abrupt, _) | (StopKind::Smooth, Mode::AbruptPending) => Mode::AbruptPending,
            (StopKind::Smooth, _) if self.state.velocity == I32F32::ZERO => Mode::Stopped,
            (StopKind::Smooth, _) => Mode::Stopping,
        };
        self.brake();
    }

    /// The limits of the last cycle: none while engaged (the follower follows, whatever the
    /// master does); the deceleration while stopping; nothing moves once stopped.
    pub fn limits(&self) -> Limits {
        let deceleration = Some(I32F32::from_bits(self.deceleration));
        match self.mode {
            Mode::Engaged | Mode::AbruptPending => Limits::default(),
            Mode::Stopping | Mode::Stopped => Limits {
                max_speed_up: Some(I32F32::ZERO),
                max_slow_down: deceleration,
                ..Limits::default()
            },
            // The drop to rest: exempt from every limit.
            Mode::AbruptStopped => Limits {
                max_speed_up: Some(I32F32::ZERO),
                exempt: true,
                ..Limits::default()
            },
        }
    }
}

/// The integer part (floor) of a generator's position: the count its position register shows.
fn count(state: State) -> i32 {
    (state.position.to_bits() >> 32) as i32
}

/// A follower geared to another generator (the master): each step steps the master, then the
/// follower follows the master's count. Stops apply to the follower alone (the master goes on).
///
/// ```
/// use profilegen::fixed::types::I32F32;
/// use profilegen::format::juno::{Acceleration, TargetVelocity};
/// use profilegen::format::mc1451a::{GearRatio, TrapezoidalAcceleration};
/// use profilegen::gearing::Follower;
/// use profilegen::{ProfileGenerator, Trapezoidal, TrapezoidalParameters};
///
/// let master = Trapezoidal::new(TrapezoidalParameters {
///     destination: 1_000,
///     max_velocity: TargetVelocity::from_num(20.0)?,
///     acceleration: Acceleration::from_num(0.5)?,
///     deceleration: Acceleration::ZERO,
///     start_velocity: TargetVelocity::ZERO,
/// })?;
/// let ratio = GearRatio::from_num(-11.39)?; // −746,455 / 2^16
/// let mut axis = Follower::new(master, ratio, I32F32::ZERO, TrapezoidalAcceleration::from_num(1.0)?)?;
/// axis.states().take(200).for_each(drop);
/// // 1,000 counts of master: exactly −746,455 · 1,000 / 2^16 counts.
/// assert_eq!(axis.state().position, I32F32::from_bits((-746_455 * 1_000) << 16));
/// # Ok::<(), profilegen::Error>(())
/// ```
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Follower<M> {
    master: M,
    gear: ElectronicGear,
}

impl<M: ProfileGenerator> Follower<M> {
    /// A follower at rest at `slave_position`, geared to `master` from its present count.
    ///
    /// # Errors
    /// As [`ElectronicGear::new`].
    pub fn new(
        master: M,
        ratio: GearRatio,
        slave_position: I32F32,
        deceleration: TrapezoidalAcceleration,
    ) -> Result<Self, Error> {
        let gear = ElectronicGear::new(ratio, count(master.state()), slave_position, deceleration)?;
        Ok(Self { master, gear })
    }

    /// The master.
    pub fn master(&self) -> &M {
        &self.master
    }

    /// The master, to command it.
    pub fn master_mut(&mut self) -> &mut M {
        &mut self.master
    }

    /// The gear, to change its ratio or deceleration.
    pub fn gear_mut(&mut self) -> &mut ElectronicGear {
        &mut self.gear
    }

    /// The gear.
    pub fn gear(&self) -> &ElectronicGear {
        &self.gear
    }
}

impl<M: ProfileGenerator> ProfileGenerator for Follower<M> {
    fn step(&mut self) -> State {
        let master = self.master.step();
        self.gear.follow(count(master))
    }

    fn state(&self) -> State {
        self.gear.state()
    }

    fn is_complete(&self) -> bool {
        self.gear.is_complete()
    }

    fn stop(&mut self, kind: StopKind) {
        self.gear.stop(kind);
    }

    fn limits(&self) -> Limits {
        self.gear.limits()
    }
}

/// A follower geared to an encoder: each step takes the next count from `counts` (a master that
/// runs out stands still).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct EncoderFollower<I> {
    counts: I,
    gear: ElectronicGear,
}

impl<I: Iterator<Item = i32>> EncoderFollower<I> {
    /// A follower at rest at `slave_position`, geared to an encoder whose count is `master` now
    /// and `counts` on the coming cycles.
    ///
    /// # Errors
    /// As [`ElectronicGear::new`].
    pub fn new(
        counts: I,
        master: i32,
        ratio: GearRatio,
        slave_position: I32F32,
        deceleration: TrapezoidalAcceleration,
    ) -> Result<Self, Error> {
        let gear = ElectronicGear::new(ratio, master, slave_position, deceleration)?;
        Ok(Self { counts, gear })
    }

    /// The gear, to change its ratio or deceleration.
    pub fn gear_mut(&mut self) -> &mut ElectronicGear {
        &mut self.gear
    }

    /// The gear (its ratio, whether it is engaged).
    pub fn gear(&self) -> &ElectronicGear {
        &self.gear
    }
}

impl<I: Iterator<Item = i32>> ProfileGenerator for EncoderFollower<I> {
    fn step(&mut self) -> State {
        let master = self.counts.next().unwrap_or(self.gear.master);
        self.gear.follow(master)
    }

    fn state(&self) -> State {
        self.gear.state()
    }

    fn is_complete(&self) -> bool {
        self.gear.is_complete()
    }

    fn stop(&mut self, kind: StopKind) {
        self.gear.stop(kind);
    }

    fn limits(&self) -> Limits {
        self.gear.limits()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// The gear as it decided every cycle before its stops were worked out at the command: the
    /// yardstick, commands included.
    struct Decided {
        state: State,
        ratio: i64,
        master: i32,
        mode: Mode,
        deceleration: i64,
        braking: i64,
        exempt: bool,
    }

    impl Decided {
        fn braking_now(&self) -> i64 {
            if self.state.velocity > I32F32::ZERO {
                -self.deceleration
            } else {
                self.deceleration
            }
        }

        fn follow(&mut self, master: i32) -> State {
            let change = i64::from(master.wrapping_sub(self.master));
            self.master = master;
            self.exempt = false;
            let velocity = match self.mode {
                Mode::Engaged => self.ratio.wrapping_mul(change),
                Mode::Stopping => {
                    let velocity = self.state.velocity.to_bits();
                    let next = velocity + self.braking;
                    if next == 0 || (next ^ velocity) < 0 {
                        self.mode = Mode::Stopped;
                        0
                    } else {
                        next
                    }
                }
                Mode::AbruptPending => {
                    self.mode = Mode::Stopped;
                    self.exempt = true;
                    0
                }
                Mode::Stopped | Mode::AbruptStopped => 0,
            };
            self.state = self.state.advanced(I32F32::from_bits(velocity));
            self.state
        }

        fn command(&mut self, command: Command) {
            match command {
                Command::Ratio(ratio) => {
                    self.ratio = i64::from(ratio.to_bits()) << 16;
                    if self.mode != Mode::AbruptPending {
                        self.mode = Mode::Engaged;
                    }
                }
                Command::Deceleration(deceleration) => {
                    self.deceleration = i64::from(deceleration.to_bits()) << 16;
                    self.braking = self.braking_now();
                }
                Command::Stop(kind) => {
                    self.mode = match (kind, self.mode) {
                        (_, Mode::Stopped) => Mode::Stopped,
                        (StopKind::Abrupt, _) | (StopKind::Smooth, Mode::AbruptPending) => {
                            Mode::AbruptPending
                        }
                        (StopKind::Smooth, _) if self.state.velocity == I32F32::ZERO => {
                            Mode::Stopped
                        }
                        (StopKind::Smooth, _) => Mode::Stopping,
                    };
                    self.braking = self.braking_now();
                }
            }
        }
    }

    #[derive(Debug, Clone, Copy)]
    enum Command {
        Ratio(GearRatio),
        Deceleration(TrapezoidalAcceleration),
        Stop(StopKind),
    }

    fn ratio() -> impl Strategy<Value = GearRatio> {
        (-(1i32 << 30)..(1 << 30)).prop_map(|bits| GearRatio::from_bits(bits).unwrap())
    }

    fn deceleration() -> impl Strategy<Value = TrapezoidalAcceleration> {
        prop_oneof![1u32..(1 << 30), 1u32..1_000_000]
            .prop_map(|bits| TrapezoidalAcceleration::from_bits(bits).unwrap())
    }

    fn command() -> impl Strategy<Value = Command> {
        prop_oneof![
            2 => ratio().prop_map(Command::Ratio),
            1 => deceleration().prop_map(Command::Deceleration),
            2 => Just(Command::Stop(StopKind::Smooth)),
            1 => Just(Command::Stop(StopKind::Abrupt)),
        ]
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(2_000))]

        /// Random masters (steady and jumping counts) and commands at random cycles: every
        /// cycle's state and completion the same as the gear that decided every cycle, and its
        /// exemption after every cycle.
        #[test]
        fn the_stops_worked_out_are_the_rule_cycle_by_cycle(
            start in (ratio(), deceleration(), any::<i32>()),
            speed in prop_oneof![-2_000i32..2_000, any::<i32>().prop_map(|s| s >> 8)],
            commands in prop::collection::vec((0u32..200, command()), 0..10),
        ) {
            let (ratio, deceleration, master) = start;
            let mut gear = ElectronicGear::new(ratio, master, I32F32::ZERO, deceleration).unwrap();
            let mut decided = Decided {
                state: State::default(),
                ratio: i64::from(ratio.to_bits()) << 16,
                master,
                mode: Mode::Engaged,
                deceleration: i64::from(deceleration.to_bits()) << 16,
                braking: 0,
                exempt: false,
            };
            let mut count = master;
            for (gap, command) in commands.into_iter().chain([(300, Command::Stop(StopKind::Smooth))]) {
                for cycle in 0..gap {
                    count = count.wrapping_add(speed);
                    prop_assert_eq!(gear.follow(count), decided.follow(count), "cycle {}", cycle);
                    prop_assert_eq!(gear.limits().exempt, decided.exempt);
                    prop_assert_eq!(
                        gear.is_complete(),
                        decided.mode == Mode::Stopped && decided.state.velocity == I32F32::ZERO
                    );
                }
                match command {
                    Command::Ratio(ratio) => gear.set_ratio(ratio),
                    Command::Deceleration(deceleration) => gear.set_deceleration(deceleration).unwrap(),
                    Command::Stop(kind) => gear.stop(kind),
                }
                decided.command(command);
            }
        }
    }
}
