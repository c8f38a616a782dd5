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
use crate::state::{Limits, ProfileGenerator, State, StopKind};
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
    /// While stopping: the deceleration against the velocity's sign (added each cycle), worked
    /// out when the stop is given, so a cycle does not decide the sign again.
    braking: i64,
    /// The last cycle was an abrupt stop (exempt from the limits).
    exempt: bool,
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
            exempt: false,
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
        self.braking = self.braking_now();
        Ok(())
    }

    /// The present state.
    pub fn state(&self) -> State {
        self.state
    }

    /// One cycle with the master's count `master` (it may wrap: each cycle's change is taken
    /// modulo 2³², so it must be below 2³¹ counts). Returns the follower's new state.
    pub fn follow(&mut self, master: i32) -> State {
        // The change modulo 2^32, as a signed count: the wrap undone.
        let change = i64::from(master.wrapping_sub(self.master));
        self.master = master;
        self.exempt = false;
        let velocity = match self.mode {
            Mode::Engaged => {
                // The ratio times the change: a whole number of raw units, modulo 2^64 as the
                // position register wraps (exact below the speed limit of the module docs).
                self.ratio.wrapping_mul(change)
            }
            Mode::Stopping => {
                let velocity = self.state.velocity.to_bits();
                // Toward zero by the deceleration, never past it: on zero or past it (the sign
                // turned), at rest. The two have opposite signs, so the sum does not overflow.
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
            Mode::Stopped => 0,
        };
        self.state = self.state.advanced(I32F32::from_bits(velocity));
        self.state
    }

    /// Whether the follower is at rest and disengaged.
    pub fn is_complete(&self) -> bool {
        self.mode == Mode::Stopped && self.state.velocity == I32F32::ZERO
    }

    /// A stop (SPEC §14): abrupt, velocity zero on the next cycle; smooth, decelerate at the
    /// follower's deceleration. Either disengages the gear ([`Self::set_ratio`] re-engages).
    pub fn stop(&mut self, kind: StopKind) {
        self.mode = match (kind, self.mode) {
            (_, Mode::Stopped) => Mode::Stopped,
            (StopKind::Abrupt, _) | (StopKind::Smooth, Mode::AbruptPending) => Mode::AbruptPending,
            (StopKind::Smooth, _) if self.state.velocity == I32F32::ZERO => Mode::Stopped,
            (StopKind::Smooth, _) => Mode::Stopping,
        };
        self.braking = self.braking_now();
    }

    /// The deceleration against the present velocity's sign.
    fn braking_now(&self) -> i64 {
        if self.state.velocity > I32F32::ZERO {
            -self.deceleration
        } else {
            self.deceleration
        }
    }

    /// The limits of the last cycle: none while engaged (the follower follows, whatever the
    /// master does); the deceleration while stopping; nothing moves once stopped.
    pub fn limits(&self) -> Limits {
        let deceleration = Some(I32F32::from_bits(self.deceleration));
        match self.mode {
            Mode::Engaged | Mode::AbruptPending => Limits {
                exempt: self.exempt,
                ..Limits::default()
            },
            Mode::Stopping | Mode::Stopped => Limits {
                max_speed_up: Some(I32F32::ZERO),
                max_slow_down: if self.exempt { None } else { deceleration },
                exempt: self.exempt,
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
