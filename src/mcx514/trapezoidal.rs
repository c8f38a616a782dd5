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
    /// DV − AC (may be negative): a cycle that begins below it speeds up by AC and stays below
    /// DV, so the sum is never formed where it could pass i64 (AC alone can come near 2⁶³ raw).
    below_last_speed_up: i64,
    /// The manual deceleration point, raw I32F32 whole pulses, held below 2³¹ pulses (every
    /// point from 2³⁰ on is past every finish point, so never reached); `i64::MAX` unless manual.
    manual_point: i64,
    automatic: bool,
    disabled: bool,
    /// max(DC, SV): a larger drop in one cycle is exempt (a late finish, an abrupt stop).
    largest_drop: i64,
}

/// Where the move is; each phase has its own one-comparison test for what ends it. The trigger
/// is `i64::MAX` while decelerating, so the test for deceleration needs no phase.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Phase {
    /// At rest before the first cycle.
    Start,
    /// Speeding up by AC toward DV.
    Accelerating,
    /// At DV (deceleration disabled: from the first cycle).
    Cruising,
    /// Slowing down by DC toward SV.
    Decelerating,
    /// At SV after the deceleration (the chip's creep), until the finish point or a stop.
    Creeping,
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
/// cycle. The S-curve is [`Mcx514SCurve`](crate::Mcx514SCurve).
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
    phase: Phase,
    /// The position (raw I32F32) at or past which a cycle that begins there starts to
    /// decelerate: the manual point; with automatic deceleration, while speeding up, half the
    /// finish point (rounded up: the pulses left, finish − p, are then ≤ the pulses output while
    /// speeding up, p), and once at DV, the finish point less those pulses. `i64::MAX`: never,
    /// and while decelerating (nothing to start then).
    trigger: i64,
    /// A smooth stop was commanded: decelerate to SV, then stop.
    stopping: bool,
    complete: bool,
    /// The velocity the last cycle wanted (raw I32F32) before the cut to the pulses left: what
    /// [`limits`](ProfileGenerator::limits) tells the ends of the move by, off the per-cycle path.
    wanted: i64,
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
        let manual_point = match parameters.deceleration_mode {
            // Past 2³¹ − 1 pulses the shift would leave i64; such a point is never reached.
            DecelerationMode::Manual(point) => {
                i64::from(point.to_bits().min(i32::MAX as u32)) << 32
            }
            _ => i64::MAX,
        };
        let finish = i64::from(finish.to_bits()) << 32;
        // Converted in the registers' order, so the first bad one is the one reported.
        let initial = initial.per_cycle(cycle)?.to_bits();
        let drive = drive.per_cycle(cycle)?.to_bits();
        let acceleration = parameters.acceleration.per_cycle(cycle)?.to_bits();
        let deceleration = parameters.deceleration.per_cycle(cycle)?.to_bits();
        let profile = PerCycle {
            finish,
            initial,
            drive,
            acceleration,
            deceleration,
            below_last_speed_up: drive - acceleration,
            manual_point,
            automatic,
            disabled: parameters.deceleration_mode == DecelerationMode::Disabled,
            largest_drop: deceleration.max(initial),
        };
        Ok(Self {
            profile,
            state: State::default(),
            phase: Phase::Start,
            // While speeding up (automatic): 2p ≥ finish, i.e. p ≥ ⌈finish/2⌉.
            trigger: if automatic {
                (finish + 1) >> 1
            } else {
                manual_point
            },
            stopping: false,
            complete: finish == 0,
            wanted: 0,
        })
    }

    /// Continuous interpolation (SPEC §12.5): moves the finish point to `pulses` (≥ the pulses
    /// output so far) and the manual deceleration point to `manual_point` (`None`: none yet, so
    /// no deceleration until one is given), while the move runs. Returns `false`, changing
    /// nothing, once the move has ended (it reached its finish point, or was stopped after it
    /// started), or for a move with automatic deceleration or deceleration disabled (continuous
    /// runs are built with a manual point); a move that has not started yet may be given its
    /// first finish point.
    pub(crate) fn continue_to(&mut self, pulses: u32, manual_point: Option<u32>) -> bool {
        let finish = i64::from(pulses) << 32;
        let position = self.state.position.to_bits();
        let moved = position != 0 || self.state.velocity != I32F32::ZERO;
        if (self.complete && moved)
            || self.stopping
            || finish < position
            || self.profile.automatic
            || self.profile.disabled
        {
            return false;
        }
        // As in `new`: a point past 2³¹ − 1 pulses is never reached.
        let point = manual_point.map_or(i64::MAX, |point| {
            i64::from(point.min(i32::MAX as u32)) << 32
        });
        self.profile.finish = finish;
        self.profile.manual_point = point;
        // Decelerating or creeping, the trigger stays i64::MAX.
        if !matches!(self.phase, Phase::Decelerating | Phase::Creeping) {
            self.trigger = point;
        }
        self.complete = finish == position;
        true
    }

    /// The velocity of the next cycle, before the cut to the pulses left (raw I32F32), with the
    /// phase it leaves the move in. The rules (SPEC §12.2): SV at once; up by AC to DV; down by
    /// DC to SV from the cycle that begins at or past the trigger; a smooth stop decelerates at
    /// once and stops from SV.
    #[inline]
    fn next_velocity(&mut self, position: i64, velocity: i64) -> i64 {
        if position >= self.trigger {
            self.decelerate();
        }
        match self.phase {
            Phase::Cruising => velocity,
            Phase::Accelerating => {
                // velocity + AC < DV exactly when velocity < DV − AC (0 ≤ velocity): the sum is
                // formed only below DV, so it never passes i64 (AC alone can near 2⁶³ raw).
                if velocity < self.profile.below_last_speed_up {
                    return velocity + self.profile.acceleration;
                }
                let drive = self.profile.drive;
                self.cruise(position + drive);
                drive
            }
            Phase::Decelerating => {
                // Down by DC. No overflow: 0 ≤ velocity and DC < 2⁶³ in raw bits.
                let next = velocity - self.profile.deceleration;
                if next > self.profile.initial {
                    // Above SV + DC before: on the ramp (a smooth stop has nothing to end yet).
                    return next;
                }
                self.reach_initial(velocity)
            }
            // max(SV − DC, SV) = SV, cycle after cycle.
            Phase::Creeping => velocity,
            Phase::Start => self.start(),
        }
    }

    /// The deceleration's last step, down to SV (never below: the creep), or, with a smooth stop,
    /// the stop from at or below SV, as the chip's decelerating stop ends.
    #[cold]
    fn reach_initial(&mut self, velocity: i64) -> i64 {
        let initial = self.profile.initial;
        if self.stopping && velocity <= initial {
            self.complete = true;
            return 0;
        }
        if !self.stopping {
            self.phase = Phase::Creeping;
        }
        initial
    }

    /// The cycle that begins at or past the trigger starts the deceleration; nothing triggers
    /// again.
    #[cold]
    fn decelerate(&mut self) {
        self.phase = Phase::Decelerating;
        self.trigger = i64::MAX;
    }

    /// The first cycle: SV at once (DV with deceleration disabled).
    #[cold]
    fn start(&mut self) -> i64 {
        let p = self.profile;
        if p.disabled {
            self.phase = Phase::Cruising;
            self.trigger = i64::MAX;
            return p.drive;
        }
        if p.initial < p.drive {
            self.phase = Phase::Accelerating;
        } else {
            self.cruise(p.initial);
        }
        p.initial
    }

    /// At DV after a cycle that sped up to `reached` (raw I32F32 pulses): with automatic
    /// deceleration, the trigger becomes the finish point less the pulses output while speeding
    /// up.
    #[cold]
    fn cruise(&mut self, reached: i64) {
        self.phase = Phase::Cruising;
        if self.profile.automatic {
            self.trigger = self.profile.finish - reached;
        }
    }
}

impl ProfileGenerator for Mcx514Trapezoidal {
    // Inlined into each caller: called from several interpolations, it would otherwise stay an
    // out-of-line call returning the whole state through memory.
    #[inline]
    fn step(&mut self) -> State {
        let (position, before) = (self.state.position.to_bits(), self.state.velocity.to_bits());
        let velocity = if self.complete {
            self.wanted = 0;
            0
        } else {
            let wanted = self.next_velocity(position, before);
            self.wanted = wanted;
            // At most the pulses left: the move lands exactly on the finish point, complete
            // there (the next cycle drops to zero). i64: both below 2³¹ pulses in raw I32F32.
            let left = self.profile.finish - position;
            if wanted >= left {
                self.complete = true;
                left
            } else {
                wanted
            }
        };
        advance(&mut self.state, I32F32::from_bits(velocity))
    }

    fn state(&self) -> State {
        self.state
    }

    fn is_complete(&self) -> bool {
        self.complete && self.state.velocity == I32F32::ZERO
    }

    fn stop(&mut self, kind: StopKind) {
        match kind {
            StopKind::Smooth => {
                self.stopping = true;
                self.decelerate();
            }
            StopKind::Abrupt => self.complete = true,
        }
    }

    fn limits(&self) -> Limits {
        let p = &self.profile;
        let (velocity, acceleration) = (
            self.state.velocity.to_bits(),
            self.state.acceleration.to_bits(),
        );
        let before = velocity - acceleration;
        // The ends of the move: the cycle cut to the pulses left, and the stop to zero.
        let cut = velocity < self.wanted || velocity == 0;
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
            max_slow_down: Some(I32F32::from_bits(if cut {
                p.deceleration.max(p.initial)
            } else {
                p.deceleration
            })),
            max_acceleration: None,
            max_jerk: None,
            // A drop beyond both DC and SV only happens at a late finish or an abrupt stop.
            exempt: -acceleration > p.largest_drop,
        }
    }
}
