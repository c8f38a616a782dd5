//! The MCX514 trapezoid as it stepped before its per-cycle path was laid out again (commit
//! 59fa77c, `src/mcx514/trapezoidal.rs`): the yardstick `tests/mcx514_same_states.rs` steps the
//! library's `Mcx514Trapezoidal` beside, requiring the same state on every cycle.

use fixed::types::I32F32;

use profilegen::format::mcx514::{Deceleration, FinishPoint, InitialSpeed};
use profilegen::format::CycleTime;
use profilegen::{
    DecelerationMode, Error, Limits, Mcx514Parameters, ProfileGenerator, State, StopKind,
};

/// `State::advanced`, stored and returned (the library's crate-internal `advance`).
fn advance(state: &mut State, velocity: I32F32) -> State {
    *state = state.advanced(velocity);
    *state
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
    /// The manual deceleration point, raw I32F32 whole pulses, held below 2³¹ pulses (every
    /// point from 2³⁰ on is past every finish point, so never reached); `i64::MAX` unless manual.
    manual_point: i64,
    automatic: bool,
    disabled: bool,
    /// max(DC, SV): a larger drop in one cycle is exempt (a late finish, an abrupt stop).
    largest_drop: i64,
}

/// Where the move is; each phase has its own one-comparison test for what ends it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Phase {
    /// At rest before the first cycle.
    Start,
    /// Speeding up by AC toward DV.
    Accelerating,
    /// At DV (deceleration disabled: from the first cycle).
    Cruising,
    /// Slowing down by DC to SV, then creeping at SV.
    Decelerating,
}

/// `Mcx514Trapezoidal` as it stepped at commit 59fa77c (the yardstick of
/// `tests/mcx514_same_states.rs`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct PreviousMcx514Trapezoidal {
    profile: PerCycle,
    state: State,
    phase: Phase,
    /// The position (raw I32F32) at or past which a cycle that begins there starts to
    /// decelerate: the manual point; with automatic deceleration, while speeding up, half the
    /// finish point (rounded up: the pulses left, finish − p, are then ≤ the pulses output while
    /// speeding up, p), and once at DV, the finish point less those pulses. `i64::MAX`: never.
    trigger: i64,
    /// A smooth stop was commanded: decelerate to SV, then stop.
    stopping: bool,
    complete: bool,
    /// The velocity the last cycle wanted (raw I32F32) before the cut to the pulses left: what
    /// [`limits`](ProfileGenerator::limits) tells the ends of the move by, off the per-cycle path.
    wanted: i64,
}

impl PreviousMcx514Trapezoidal {
    /// A move from rest at position 0, with the registers converted to per-cycle values of
    /// `cycle` ([`per_cycle`](profilegen::format::mcx514::DriveSpeed::per_cycle)).
    ///
    /// # Errors
    /// [`Error::OutOfRange`] for `pulses` beyond 1,073,741,823 (parameter `finish point`) or an
    /// initial speed above the drive speed; [`Error::Refused`] for automatic deceleration with
    /// AC ≠ DC (the chip needs a manual deceleration point then); the conversions' errors
    /// ([`Error::Underflow`], [`Error::OutOfRange`]) when `cycle` makes a register vanish or
    /// overflow.
    pub fn new(parameters: Mcx514Parameters, cycle: CycleTime) -> Result<Self, Error> {
        if parameters.pulses > FinishPoint::MAX_BITS as u32 {
            return Err(Error::Refused {
                parameter: FinishPoint::PARAMETER,
                reason: "out of range (the snapshot keeps no range)",
            });
        }
        // In range, so the cast is exact.
        let finish = FinishPoint::from_bits(parameters.pulses as i32)?;
        let (initial, drive) = (parameters.initial_speed, parameters.drive_speed);
        if initial.to_bits() > drive.to_bits() {
            return Err(Error::Refused {
                parameter: InitialSpeed::PARAMETER,
                reason: "out of range (the snapshot keeps no range)",
            });
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

    /// The velocity of the next cycle, before the cut to the pulses left (raw I32F32), with the
    /// phase it leaves the move in. The rules (SPEC §12.2): SV at once; up by AC to DV; down by
    /// DC to SV from the cycle that begins at or past the trigger; a smooth stop decelerates at
    /// once and stops from SV.
    #[inline]
    fn next_velocity(&mut self, position: i64, velocity: i64) -> i64 {
        if self.phase != Phase::Decelerating && position >= self.trigger {
            self.phase = Phase::Decelerating;
        }
        match self.phase {
            Phase::Cruising => velocity,
            Phase::Accelerating => {
                // Saturating: at a cycle of seconds AC alone is near 2³¹ pulses/cycle², and with
                // the velocity it can pass i64 in raw bits; DV caps the sum anyway.
                let next = velocity.saturating_add(self.profile.acceleration);
                let drive = self.profile.drive;
                if next < drive {
                    return next;
                }
                self.cruise(position + drive);
                drive
            }
            Phase::Decelerating => {
                let initial = self.profile.initial;
                if self.stopping && velocity <= initial {
                    // A smooth stop ends at SV, as the chip's decelerating stop does.
                    self.complete = true;
                    return 0;
                }
                // Down by DC, never below SV (the creep). No overflow: 0 ≤ velocity and
                // DC < 2⁶³ in raw bits.
                (velocity - self.profile.deceleration).max(initial)
            }
            Phase::Start => self.start(),
        }
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

impl ProfileGenerator for PreviousMcx514Trapezoidal {
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
                self.phase = Phase::Decelerating;
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
