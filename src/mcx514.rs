//! The MCX514's trapezoidal acceleration/deceleration on the driving axis (SPEC §12.2); see
//! [`Mcx514Trapezoidal`].

use fixed::types::I32F32;

use crate::format::mcx514::{
    Acceleration, Deceleration, DriveSpeed, FinishPoint, InitialSpeed, ManualDecelerationPoint,
};
use crate::format::CycleTime;
use crate::state::{advance, Limits, ProfileGenerator, State, StopKind};
use crate::Error;

/// When the driving axis starts to decelerate (SPEC §12.2).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum DecelerationMode {
    /// When the pulses left are ≤ the pulses output while accelerating; needs AC = DC.
    Automatic,
    /// When the output count reaches the manual deceleration point.
    Manual(ManualDecelerationPoint),
    /// Deceleration disabled (the chip's state at reset): constant speed DV, no ramps.
    Disabled,
}

/// The parameters of an MCX514 trapezoidal move of the driving axis, in the chip's registers.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Mcx514Parameters {
    /// Pulses the driving axis outputs: for a linear interpolation, the long axis's
    /// ([`Line::steps`](crate::interpolation::Line::steps)); 0 … 1,073,741,823.
    pub pulses: u32,
    /// Initial speed SV, pps: the start, and the floor of the deceleration.
    pub initial_speed: InitialSpeed,
    /// Drive speed DV, pps, ≥ SV.
    pub drive_speed: DriveSpeed,
    /// Acceleration AC, pps/s.
    pub acceleration: Acceleration,
    /// Deceleration DC, pps/s.
    pub deceleration: Deceleration,
    /// When deceleration starts.
    pub deceleration_mode: DecelerationMode,
}

/// The parameters converted to per-cycle raw I32F32 bits.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
struct PerCycle {
    /// The finish point, raw I32F32 pulses.
    finish: i64,
    initial: i64,
    drive: i64,
    acceleration: i64,
    deceleration: i64,
    /// The manual deceleration point, raw I32F32 pulses (`i64::MAX`, never reached, unless
    /// manual).
    trigger: i64,
    /// DV − AC, raw: a velocity at or above it reaches DV on the next speed-up (the sum itself
    /// could pass i64 at a cycle of seconds).
    drive_less_acceleration: i64,
    automatic: bool,
    disabled: bool,
}

/// The MCX514's trapezoidal acceleration/deceleration on the driving axis (SPEC §12.2), cycle by
/// cycle: start at the initial speed SV, accelerate by AC up to the drive speed DV, cruise,
/// decelerate by DC down to SV, keep outputting at SV until the finish point, stop.
///
/// The position counts interpolation steps (the driving axis's output pulses), so the generator
/// drives a geometry ([`Line::drive`](crate::interpolation::Line::drive)).
///
/// When deceleration starts:
/// - **automatic** (AC = DC, as on the chip): on the first cycle on which the pulses still to
///   output are ≤ the pulses output while accelerating (the start at SV included);
/// - **manual**: on the first cycle that begins with the output count (the integer part of the
///   position) at or past the manual deceleration point DP. A DP too early leaves a stretch at SV
///   (the chip's creep); one too late reaches the finish point above SV and stops there at once —
///   a drop exempt from the rate limits, like an abrupt stop (SPEC §9);
/// - **disabled** (the chip's default, command 6Eh): no acceleration either; the move runs at DV
///   from the first cycle to the finish point and stops there (exempt, as above).
///
/// Every cycle's velocity is at most the pulses left, so the move lands exactly on the finish
/// point; the cycle after, the velocity drops to zero. A smooth stop decelerates by DC to SV and
/// stops from there (the chip's decelerating stop); an abrupt stop drops to zero on the next
/// cycle. S-curve driving is not modelled yet.
///
/// ```
/// use profilegen::format::mcx514::{Acceleration, Deceleration, DriveSpeed, InitialSpeed};
/// use profilegen::format::CycleTime;
/// use profilegen::{DecelerationMode, Mcx514Parameters, Mcx514Trapezoidal, ProfileGenerator};
///
/// // At 1 ms: SV 2 pulses/cycle, DV 10, AC = DC = 2 pulses/cycle², 100 pulses.
/// let mut axis = Mcx514Trapezoidal::new(
///     Mcx514Parameters {
///         pulses: 100,
///         initial_speed: InitialSpeed::from_bits(2_000)?,
///         drive_speed: DriveSpeed::from_bits(10_000)?,
///         acceleration: Acceleration::from_bits(2_000_000)?,
///         deceleration: Deceleration::from_bits(2_000_000)?,
///         deceleration_mode: DecelerationMode::Automatic,
///     },
///     CycleTime::from_seconds(1e-3)?,
/// )?;
/// let last = axis.states_until_complete().last().unwrap();
/// assert_eq!(last.position, 100);
/// # Ok::<(), profilegen::Error>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Mcx514Trapezoidal {
    profile: PerCycle,
    state: State,
    /// Raw I32F32 pulses output up to the end of the last cycle that sped up.
    accelerated: i64,
    /// Deceleration has started (it never stops once started).
    decelerating: bool,
    /// A smooth stop was commanded: decelerate to SV, then stop.
    stopping: bool,
    complete: bool,
    /// The last cycle's velocity was cut to the pulses left, or was the stop to zero: the ends of
    /// the move, where the drop may be up to SV (or, above that, exempt).
    cut: bool,
}

impl Mcx514Trapezoidal {
    /// A move from rest at position 0, with the registers converted to per-cycle values of
    /// `cycle` ([`per_cycle`](crate::format::mcx514::DriveSpeed::per_cycle)).
    ///
    /// # Errors
    /// [`Error::OutOfRange`] for `pulses` beyond 1,073,741,823 (parameter `finish point`) or an
    /// initial speed above the drive speed; [`Error::Refused`] for automatic deceleration with
    /// AC ≠ DC (the chip needs a manual deceleration point then); the conversions' errors
    /// ([`Error::Underflow`], [`Error::OutOfRange`]) when `cycle` makes a register vanish or
    /// overflow.
    pub fn new(parameters: Mcx514Parameters, cycle: CycleTime) -> Result<Self, Error> {
        if parameters.pulses > FinishPoint::MAX_BITS as u32 {
            return Err(Error::out_of_range_bits(
                FinishPoint::PARAMETER,
                i64::from(parameters.pulses),
                0,
                FinishPoint::RANGE,
            ));
        }
        // In range, so the cast is exact.
        let finish = FinishPoint::from_bits(parameters.pulses as i32)?;
        let (initial, drive) = (parameters.initial_speed, parameters.drive_speed);
        if initial.to_bits() > drive.to_bits() {
            return Err(Error::out_of_range_bits(
                InitialSpeed::PARAMETER,
                i64::from(initial.to_bits()),
                0,
                InitialSpeed::RANGE.up_to_bits(i64::from(drive.to_bits()), 0),
            ));
        }
        let automatic = parameters.deceleration_mode == DecelerationMode::Automatic;
        if automatic && parameters.acceleration.to_bits() != parameters.deceleration.to_bits() {
            return Err(Error::Refused {
                parameter: Deceleration::PARAMETER,
                reason: "to differ from the acceleration with automatic deceleration (the chip \
                         needs a manual deceleration point for that)",
            });
        }
        let trigger = match parameters.deceleration_mode {
            DecelerationMode::Manual(point) => i64::from(point.to_bits()) << 32,
            _ => i64::MAX,
        };
        let profile = PerCycle {
            finish: i64::from(finish.to_bits()) << 32,
            initial: initial.per_cycle(cycle)?.to_bits(),
            drive: drive.per_cycle(cycle)?.to_bits(),
            acceleration: parameters.acceleration.per_cycle(cycle)?.to_bits(),
            deceleration: parameters.deceleration.per_cycle(cycle)?.to_bits(),
            trigger,
            drive_less_acceleration: 0,
            automatic,
            disabled: parameters.deceleration_mode == DecelerationMode::Disabled,
        };
        let profile = PerCycle {
            // Both in 0 … 2⁶³ − 1024: the difference cannot overflow.
            drive_less_acceleration: profile.drive - profile.acceleration,
            ..profile
        };
        Ok(Self {
            profile,
            state: State::default(),
            accelerated: 0,
            decelerating: false,
            stopping: false,
            complete: profile.finish == 0,
            cut: false,
        })
    }

    /// Continuous interpolation (SPEC §12.5): moves the finish point to `pulses` (≥ the pulses
    /// output so far) and the manual deceleration point to `manual_point` (`None`: none yet, so
    /// no deceleration until one is given), while the move runs. Returns `false`, changing
    /// nothing, once the move has ended (it reached its finish point or was stopped after it
    /// started); a move that has not started yet may be given its first finish point.
    pub(crate) fn continue_to(&mut self, pulses: u32, manual_point: Option<u32>) -> bool {
        let finish = i64::from(pulses) << 32;
        let moved = self.state.position.to_bits() != 0 || self.state.velocity != I32F32::ZERO;
        if (self.complete && moved) || self.stopping || finish < self.state.position.to_bits() {
            return false;
        }
        self.profile.finish = finish;
        self.profile.trigger = manual_point.map_or(i64::MAX, |point| i64::from(point) << 32);
        self.complete = finish == self.state.position.to_bits();
        true
    }

    /// The velocity of the next cycle, before the cut to the pulses left (raw I32F32), from the
    /// velocity `before` at `position` with `left` pulses to the finish point.
    #[inline(always)]
    fn next_velocity(&mut self, position: i64, before: i64, left: i64) -> i64 {
        let p = &self.profile;
        if p.disabled && !self.stopping {
            return p.drive;
        }
        if !self.decelerating {
            self.decelerating = self.stopping
                // The output count is the position's integer part: compare whole pulses.
                || position >> 32 << 32 >= p.trigger
                || (p.automatic && before != 0 && left <= self.accelerated);
        }
        if self.decelerating {
            if self.stopping && before <= p.initial {
                return 0; // a smooth stop ends at SV, as the chip's decelerating stop does
            }
            // Down by DC, never below SV (the creep). No overflow: 0 ≤ velocity and
            // DC < 2⁶³ in raw bits.
            return (before - p.deceleration).max(p.initial);
        }
        if before == 0 {
            p.initial // the start: SV at once
        } else if before >= p.drive_less_acceleration {
            // DV caps the speed-up; comparing with DV − AC avoids the sum, which at a cycle of
            // seconds (AC near 2³¹ pulses/cycle²) can pass i64 in raw bits.
            p.drive
        } else {
            before + p.acceleration
        }
    }
}

impl ProfileGenerator for Mcx514Trapezoidal {
    #[inline]
    fn step(&mut self) -> State {
        let before = self.state.velocity.to_bits();
        let position = self.state.position.to_bits();
        let (mut velocity, mut cut) = (0, true);
        if !self.complete {
            // At most the pulses left: the move lands exactly on the finish point. i64: both
            // below 2³¹ pulses in raw I32F32.
            let left = self.profile.finish - position;
            let wanted = self.next_velocity(position, before, left);
            velocity = wanted.min(left);
            // The ends of the move: cut to the pulses left, or the stop to zero.
            cut = velocity < wanted || velocity == 0;
            if velocity > before && !self.decelerating {
                self.accelerated = position + velocity;
            }
        }
        self.cut = cut;
        let state = advance(&mut self.state, I32F32::from_bits(velocity));
        if velocity == 0 || state.position.to_bits() == self.profile.finish {
            // Complete at rest; on the finish point the next cycle drops to zero.
            self.complete = true;
        }
        state
    }

    fn state(&self) -> State {
        self.state
    }

    fn is_complete(&self) -> bool {
        self.complete && self.state.velocity == I32F32::ZERO
    }

    fn stop(&mut self, kind: StopKind) {
        match kind {
            StopKind::Smooth => self.stopping = true,
            StopKind::Abrupt => self.complete = true,
        }
    }

    fn limits(&self) -> Limits {
        let p = &self.profile;
        let before = self.state.velocity.to_bits() - self.state.acceleration.to_bits();
        // From rest the first cycle jumps to SV (to DV with deceleration disabled).
        let speed_up = if before == 0 {
            if p.disabled {
                p.drive
            } else {
                p.initial
            }
        } else {
            p.acceleration
        };
        Limits {
            max_velocity: Some(I32F32::from_bits(p.drive)),
            max_speed_up: Some(I32F32::from_bits(speed_up)),
            // DC on the ramp; at the ends (the cut to the pulses left, the stop) up to SV.
            max_slow_down: Some(I32F32::from_bits(if self.cut {
                p.deceleration.max(p.initial)
            } else {
                p.deceleration
            })),
            max_acceleration: None,
            max_jerk: None,
            // A drop beyond both DC and SV only happens at a late finish or after an abrupt
            // stop: the last cycle's velocity change is −drop.
            exempt: self.state.acceleration.to_bits().wrapping_neg()
                > p.deceleration.max(p.initial),
        }
    }
}
