//! The MCX514's S-curve acceleration/deceleration on the driving axis (SPEC §12.2); see
//! [`Mcx514SCurve`].

use fixed::types::I32F32;

use super::trapezoidal::{DecelerationMode, Mcx514Parameters, Mcx514Trapezoidal};
use crate::format::mcx514::{DecelerationJerk, Jerk};
use crate::format::CycleTime;
use crate::state::{advance, Limits, ProfileGenerator, State, StopKind};
use crate::Error;

/// The parameters of an MCX514 S-curve move of the driving axis: those of the trapezoid, whose
/// acceleration and deceleration are now the limits AC and DC of the S-curve's rate, plus the
/// jerks.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Mcx514ScurveParameters {
    /// Pulses, speeds, AC, DC and the deceleration mode, as for the trapezoid.
    pub trapezoid: Mcx514Parameters,
    /// Jerk JK, the acceleration increasing rate, pps/s².
    pub jerk: Jerk,
    /// DJ, the deceleration increasing rate, pps/s².
    pub deceleration_jerk: DecelerationJerk,
}

/// One side of the S-curve (the speed-up or the slow-down) in raw I32F32 per-cycle bits: how the
/// rate may change per cycle (the jerk), its cap (AC or DC), and the speed a ramp-down from the
/// cap adds (see [`Ramp::tail`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
struct Ramp {
    jerk: i64,
    cap: i64,
    /// cap − jerk: a rate at or above it steps up to the cap itself (no overflow, unlike
    /// rate + jerk at the largest registers).
    cap_less_jerk: i64,
    /// [`Ramp::tail`] of the cap, saturated at `i64::MAX` (then never affordable).
    cap_tail: i64,
    /// min(jerk, cap): the rate a ramp from zero steps to first. A gap below it is closed in one
    /// cycle by [`Mcx514SCurve::land`] ([`Ramp::next`] would stay at zero for ever).
    first: i64,
}

impl Ramp {
    /// S(r) = Σ_{i ≥ 1} max(r − i·J, 0): the speed the cycles after one at rate r add while the
    /// rate falls by J per cycle to zero (the last step from below J to 0). Computed once per move
    /// (for the cap); on the per-cycle path it follows the rate by the exact identities
    /// S(r + J) = S(r) + max(r, 0) and S(r − J) = S(r) − max(r − J, 0), with no division.
    fn tail(rate: i64, jerk: i64) -> i64 {
        if rate <= jerk {
            return 0;
        }
        // i128: n < 2⁶³ terms of at most 2⁶³: the sum n·r − J·n(n+1)/2 < 2¹²⁶.
        let (rate, jerk) = (i128::from(rate), i128::from(jerk));
        let n = (rate - 1) / jerk; // the terms with r − i·J > 0: i < r/J
        let sum = n * rate - jerk * n * (n + 1) / 2;
        i64::try_from(sum).unwrap_or(i64::MAX)
    }

    /// This cycle's speed change, from the ramp's rate and tail with `gap` of speed still to
    /// gain (or shed), updating them: the largest of rate + J (capped) whose rate plus tail fits
    /// the gap; else, with the slack (the gap less the tail) above rate − J, the slack itself
    /// (at most the rate: the rate held), the ramp's rate kept so that rate − J follows; else
    /// rate − J. So the rate stays within J of the last change, and the descent from the top
    /// takes in one cycle what the tail leaves over (the slack is constant while the rate falls
    /// by J, so it fits between two of its steps): the speed lands on its target with the rate
    /// at zero, with no cycles crept at a rate below one jerk step.
    ///
    /// Invariant: tail ≤ gap (the rate chosen last fitted the gap then). No overflow: the rate
    /// and tail in hand were chosen with rate + tail ≤ the gap then (< 2⁶³), so tail + rate is
    /// in range; a sum with the gap is compared as a difference.
    #[inline]
    fn next(&self, rate: &mut i64, tail: &mut i64, gap: i64) -> i64 {
        let (up, up_tail) = if *rate >= self.cap_less_jerk {
            (self.cap, self.cap_tail)
        } else {
            (*rate + self.jerk, *tail + *rate)
        };
        if up <= gap && up_tail <= gap - up {
            (*rate, *tail) = (up, up_tail);
            return up;
        }
        // ≥ 0 by the invariant; rate − J, held at zero (the last step from below J).
        let slack = gap - *tail;
        let down = (*rate - self.jerk).max(0);
        if slack > down {
            // Within [rate − J, rate]: the rate held (slack ≥ rate), or the slack once, after
            // which the gap is the tail and the descent goes on from the rate.
            return slack.min(*rate);
        }
        // S(r − J) = S(r) − (r − J); from r ≤ J both are 0.
        (*rate, *tail) = (down, *tail - down);
        down
    }
}

/// Where the move is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Phase {
    /// At rest before the first cycle.
    Start,
    /// Speeding up toward DV (the rate ramps by JK within AC).
    Accelerating,
    /// At DV with the rate at zero (until deceleration starts).
    Cruising,
    /// Deceleration has started while the rate was still positive: it falls by JK to zero first.
    Easing,
    /// Slowing down toward SV (the rate ramps by DJ within DC).
    Decelerating,
    /// At SV with the rate at zero, to the finish point (a smooth stop makes it
    /// [`Phase::Decelerating`] again, which ends it).
    Creeping,
}

/// The MCX514's S-curve acceleration/deceleration on the driving axis (SPEC §12.2), cycle by
/// cycle: start at the initial speed SV; the rate of speed-up rises by the jerk JK per cycle up to
/// AC (if reached), holds, and falls so that the speed reaches DV with the rate at zero; cruise;
/// the slow-down mirrors it with DJ and DC down to SV; creep at SV to the finish point; stop.
///
/// Integer and division-free per cycle (I32F32 raw bits): each cycle takes the largest rate,
/// within one jerk of the last, from which a ramp-down at the jerk still lands on the target
/// speed, and once the ramp-down has begun, the slack it leaves in one cycle between two of its
/// steps (see `Ramp::next`); so the speed reaches DV (and SV) exactly, with the rate at zero,
/// and no cycles creep at a rate below one jerk step.
///
/// When deceleration starts, as for [`Mcx514Trapezoidal`]: **automatic** (AC = DC and JK = DJ)
/// on the first cycle on which the pulses left are ≤ the pulses output while speeding up;
/// **manual** at the output count DP; **disabled**: DV from the first cycle to the finish point.
/// If it starts while the rate is still rising, the rate first falls to zero by JK, then the
/// slow-down begins (the speed never passes DV). A move too short to reach DV decelerates from
/// where it is; the automatic point is the chip's rule, so such a move can arrive above SV and
/// stops there, as a late manual point does — exempt from the limits, like an abrupt stop.
///
/// Every cycle's velocity is at most the pulses left, so the move lands exactly on the finish
/// point. Between the documented events (the start at SV, the cycles cut to the pulses left and
/// the stop at the end) speed-ups stay within AC, slow-downs within DC, the rate changes within
/// JK (speeding up) or DJ (slowing down), and the speed within DV; [`limits`](Self::limits)
/// reports the events as exempt.
///
/// ```
/// use profilegen::format::mcx514::{
///     Acceleration, Deceleration, DecelerationJerk, DriveSpeed, InitialSpeed, Jerk,
/// };
/// use profilegen::format::CycleTime;
/// use profilegen::{
///     DecelerationMode, Mcx514Parameters, Mcx514SCurve, Mcx514ScurveParameters, ProfileGenerator,
/// };
///
/// // At 1 ms: SV 1 pulse/cycle, DV 10, AC = DC = 1 pulse/cycle², JK = DJ = 0.25 pulse/cycle³.
/// let mut axis = Mcx514SCurve::new(
///     Mcx514ScurveParameters {
///         trapezoid: Mcx514Parameters {
///             pulses: 500,
///             initial_speed: InitialSpeed::from_bits(1_000)?,
///             drive_speed: DriveSpeed::from_bits(10_000)?,
///             acceleration: Acceleration::from_bits(1_000_000)?,
///             deceleration: Deceleration::from_bits(1_000_000)?,
///             deceleration_mode: DecelerationMode::Automatic,
///         },
///         jerk: Jerk::from_bits(250_000_000)?,
///         deceleration_jerk: DecelerationJerk::from_bits(250_000_000)?,
///     },
///     CycleTime::from_seconds(1e-3)?,
/// )?;
/// let states: Vec<_> = axis.states_until_complete().collect();
/// assert_eq!(states.last().unwrap().position, 500);
/// assert!(states.iter().any(|s| s.velocity == 10)); // DV reached
/// # Ok::<(), profilegen::Error>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Mcx514SCurve {
    /// The finish point, raw I32F32 pulses.
    finish: i64,
    initial: i64,
    drive: i64,
    /// The manual deceleration point, raw I32F32 whole pulses, held below 2³¹ pulses (every
    /// point from 2³⁰ on is past every finish point); `i64::MAX` unless manual.
    manual_point: i64,
    automatic: bool,
    /// The position (raw I32F32) at or past which a cycle that begins there, speeding up or at
    /// DV, starts to decelerate: the manual point; with automatic deceleration, while speeding
    /// up, half the finish point (rounded up: the pulses left, finish − p, are then ≤ those
    /// output while speeding up, p), and at DV the finish point less those. `i64::MAX`: never.
    trigger: i64,
    disabled: bool,
    speed_up: Ramp,
    slow_down: Ramp,
    state: State,
    phase: Phase,
    /// The rate of the present ramp (speed-up while accelerating or easing, slow-down while
    /// decelerating), ≥ 0, raw bits per cycle², and its tail S(rate).
    rate: i64,
    tail: i64,
    /// A smooth stop was commanded: decelerate to SV, then stop.
    stopping: bool,
    complete: bool,
    /// The velocity the last cycle wanted (raw I32F32) before the cut to the pulses left: what
    /// [`limits`](ProfileGenerator::limits) tells the ends of the move by, off the per-cycle path.
    wanted: i64,
}

impl Mcx514SCurve {
    /// A move from rest at position 0, with the registers converted to per-cycle values of
    /// `cycle`.
    ///
    /// # Errors
    /// As [`Mcx514Trapezoidal::new`] (pulses, SV above DV, the conversions); [`Error::Refused`]
    /// for automatic deceleration with AC ≠ DC or JK ≠ DJ (the chip needs a manual point then);
    /// [`Error::Underflow`] or [`Error::OutOfRange`] when `cycle` makes a jerk vanish or
    /// overflow.
    pub fn new(parameters: Mcx514ScurveParameters, cycle: CycleTime) -> Result<Self, Error> {
        let p = parameters.trapezoid;
        // The trapezoid checks everything the two share.
        Mcx514Trapezoidal::new(p, cycle)?;
        let automatic = p.deceleration_mode == DecelerationMode::Automatic;
        if automatic && parameters.jerk.to_bits() != parameters.deceleration_jerk.to_bits() {
            return Err(Error::Refused {
                parameter: DecelerationJerk::PARAMETER,
                reason: "to differ from the jerk with automatic deceleration (the chip needs a \
                         manual deceleration point for that)",
            });
        }
        let ramp = |jerk: I32F32, cap: I32F32| {
            let (jerk, cap) = (jerk.to_bits(), cap.to_bits());
            Ramp {
                jerk,
                cap,
                cap_less_jerk: cap - jerk,
                cap_tail: Ramp::tail(cap, jerk),
                first: jerk.min(cap),
            }
        };
        let speed_up = ramp(
            parameters.jerk.per_cycle(cycle)?,
            p.acceleration.per_cycle(cycle)?,
        );
        let slow_down = ramp(
            parameters.deceleration_jerk.per_cycle(cycle)?,
            p.deceleration.per_cycle(cycle)?,
        );
        let finish = i64::from(p.pulses) << 32;
        Ok(Self {
            finish,
            initial: p.initial_speed.per_cycle(cycle)?.to_bits(),
            drive: p.drive_speed.per_cycle(cycle)?.to_bits(),
            manual_point: match p.deceleration_mode {
                // Past 2³¹ − 1 pulses the shift would leave i64; such a point is never reached.
                DecelerationMode::Manual(point) => {
                    i64::from(point.to_bits().min(i32::MAX as u32)) << 32
                }
                _ => i64::MAX,
            },
            automatic,
            disabled: p.deceleration_mode == DecelerationMode::Disabled,
            speed_up,
            slow_down,
            state: State::default(),
            phase: Phase::Start,
            rate: 0,
            tail: 0,
            trigger: i64::MAX, // set by the first cycle
            stopping: false,
            complete: finish == 0,
            wanted: 0,
        })
    }

    /// The velocity of the next cycle before the cut to the pulses left (raw I32F32), with the
    /// phase it leaves the move in. Inlined into [`step`](ProfileGenerator::step) with the two
    /// ramps; the events (the start, the trigger, easing, landing) are calls off that path.
    #[inline(always)]
    fn next_velocity(&mut self, position: i64, velocity: i64) -> i64 {
        match self.phase {
            Phase::Cruising if position < self.trigger => velocity,
            Phase::Creeping => velocity,
            Phase::Accelerating if position < self.trigger => self.accelerate(position, velocity),
            Phase::Decelerating => self.decelerate(position, velocity),
            _ => self.event(position, velocity),
        }
    }

    /// Speeding up toward DV, or cruising there.
    #[inline(always)]
    fn accelerate(&mut self, position: i64, velocity: i64) -> i64 {
        let gap = self.drive - velocity;
        if self.rate == 0 && gap < self.speed_up.first {
            if gap <= 0 {
                // At DV: cruise (what the ramp would choose, sooner).
                self.phase = Phase::Cruising;
                return velocity;
            }
            return self.land(position, velocity, gap);
        }
        let change = self.speed_up.next(&mut self.rate, &mut self.tail, gap);
        // (Gap 0 with the rate still above zero: at DV already, the trigger set.)
        if change == gap && gap != 0 {
            // At DV this cycle: with automatic deceleration the trigger becomes the finish
            // point less the pulses output while speeding up.
            self.at_drive_speed(position + gap + velocity);
        }
        velocity + change
    }

    /// Slowing down toward SV, or creeping there; a smooth stop ends at SV.
    #[inline(always)]
    fn decelerate(&mut self, position: i64, velocity: i64) -> i64 {
        let initial = self.initial;
        if self.stopping && velocity <= initial {
            // A smooth stop ends at SV, as the chip's decelerating stop does.
            self.complete = true;
            return 0;
        }
        // Excess over SV ≥ 0: the slow-down never goes below SV.
        let excess = velocity - initial;
        if self.rate == 0 && excess < self.slow_down.first {
            if excess <= 0 {
                // At SV: creep (what the ramp would choose, sooner).
                self.phase = Phase::Creeping;
                return velocity;
            }
            return self.land(position, velocity, -excess);
        }
        velocity - self.slow_down.next(&mut self.rate, &mut self.tail, excess)
    }

    /// The first cycle, the trigger reached while speeding up or at DV, and easing.
    #[cold]
    #[inline(never)]
    fn event(&mut self, position: i64, velocity: i64) -> i64 {
        match self.phase {
            Phase::Start => self.start(),
            Phase::Accelerating | Phase::Cruising | Phase::Easing => {
                self.phase = Phase::Easing;
                self.ease(position, velocity)
            }
            // Not reached (no event while slowing down or creeping); as on the path.
            Phase::Decelerating | Phase::Creeping => self.decelerate(position, velocity),
        }
    }

    /// The first cycle: SV at once (DV with deceleration disabled, for good).
    #[cold]
    fn start(&mut self) -> i64 {
        self.phase = Phase::Accelerating;
        if self.disabled && !self.stopping {
            self.trigger = i64::MAX;
            (self.rate, self.tail) = (0, 0);
            return self.drive;
        }
        self.trigger = if self.automatic {
            // While speeding up: 2p ≥ finish, i.e. p ≥ ⌈finish/2⌉.
            (self.finish + 1) >> 1
        } else {
            self.manual_point
        };
        if self.initial == self.drive {
            self.at_drive_speed(self.initial);
        }
        if self.stopping {
            // Stopped before the first cycle: SV once (the start), then the stop from there.
            self.phase = Phase::Easing;
        }
        self.initial
    }

    /// The rate at zero and the speed `change` (raw I32F32 per cycle; |change| below the ramp's
    /// first step) from its target (DV speeding up, SV slowing down): there at once, the rate
    /// the change itself (within the jerk and the cap from zero, and back to zero on the next
    /// cycle). The ramp's own choice from zero would be to stay (+J overshoots): the speed would
    /// never reach DV, and a smooth stop that had to come down to SV would never end.
    #[cold]
    #[inline(never)]
    fn land(&mut self, position: i64, velocity: i64, change: i64) -> i64 {
        (self.rate, self.tail) = (change.abs(), 0);
        if change > 0 {
            self.at_drive_speed(position + change + velocity);
        }
        velocity + change
    }

    /// At DV after a cycle that ended at `reached` (raw I32F32 pulses).
    #[inline]
    fn at_drive_speed(&mut self, reached: i64) {
        if self.automatic {
            self.trigger = self.finish - reached;
        }
    }

    /// Deceleration has started: a rate still rising the speed falls by JK to zero first (the
    /// speed-up's tail kept the speed within DV), then the slow-down begins.
    fn ease(&mut self, position: i64, velocity: i64) -> i64 {
        if self.rate > 0 {
            let down = self.rate - self.speed_up.jerk;
            (self.rate, self.tail) = if down > 0 {
                (down, self.tail - down)
            } else {
                (0, 0)
            };
            return velocity + self.rate;
        }
        self.phase = Phase::Decelerating;
        (self.rate, self.tail) = (0, 0);
        self.decelerate(position, velocity)
    }
}

impl ProfileGenerator for Mcx514SCurve {
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
            let left = self.finish - position;
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
                self.phase = match self.phase {
                    Phase::Accelerating | Phase::Cruising => Phase::Easing,
                    // Creeping: SV reached, the stop ends it (`decelerate`).
                    Phase::Creeping => Phase::Decelerating,
                    phase => phase,
                };
            }
            StopKind::Abrupt => self.complete = true,
        }
    }

    fn limits(&self) -> Limits {
        let velocity = self.state.velocity.to_bits();
        let before = velocity - self.state.acceleration.to_bits();
        // The events: the start (from rest to moving), the cut to the pulses left, the stop
        // (from moving to rest).
        let exempt = (before == 0) != (velocity == 0) || velocity < self.wanted;
        let (jerk, max_acceleration) = match self.phase {
            Phase::Decelerating | Phase::Creeping => (self.slow_down.jerk, self.slow_down.cap),
            _ => (self.speed_up.jerk, self.speed_up.cap),
        };
        Limits {
            max_velocity: Some(I32F32::from_bits(self.drive)),
            max_speed_up: Some(I32F32::from_bits(self.speed_up.cap)),
            max_slow_down: Some(I32F32::from_bits(self.slow_down.cap)),
            max_acceleration: Some(I32F32::from_bits(max_acceleration)),
            max_jerk: Some(I32F32::from_bits(jerk)),
            exempt,
        }
    }
}
