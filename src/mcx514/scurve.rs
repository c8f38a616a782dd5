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
    /// [`Ramp::tail`] of the cap, saturated at `i64::MAX` (then never affordable).
    cap_tail: i64,
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

    /// The next rate and its tail, from the present ones with `gap` of speed still to gain (or
    /// shed): the largest of rate + J (capped), rate, rate − J whose rate plus tail fits the gap,
    /// so the speed lands on its target with the rate at zero, every change within J. The
    /// invariant (rate + tail ≤ gap after the previous choice) makes rate − J always fit; the
    /// last resort, a rate ≤ J equal to the gap, lands exactly.
    #[inline]
    fn next(&self, rate: i64, tail: i64, gap: i64) -> (i64, i64) {
        let up = rate.saturating_add(self.jerk);
        let (up, up_tail) = if up >= self.cap {
            (self.cap, self.cap_tail)
        } else {
            (up, tail.saturating_add(rate.max(0)))
        };
        if up.saturating_add(up_tail) <= gap {
            return (up, up_tail);
        }
        if rate.saturating_add(tail) <= gap {
            return (rate, tail);
        }
        let down = rate - self.jerk;
        if down > 0 {
            return (down, tail - down);
        }
        // rate ≤ J and its tail is 0, yet rate > gap: the gap itself (0 ≤ gap < rate ≤ J).
        (gap.max(0), 0)
    }
}

/// Where the move is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Phase {
    /// At rest before the first cycle.
    Start,
    /// Speeding up toward DV (the rate ramps by JK within AC), then cruising at DV.
    Accelerating,
    /// Deceleration has started while the rate was still positive: it falls by JK to zero first.
    Easing,
    /// Slowing down toward SV (the rate ramps by DJ within DC), then creeping at SV.
    Decelerating,
}

/// The MCX514's S-curve acceleration/deceleration on the driving axis (SPEC §12.2), cycle by
/// cycle: start at the initial speed SV; the rate of speed-up rises by the jerk JK per cycle up to
/// AC (if reached), holds, and falls so that the speed reaches DV with the rate at zero; cruise;
/// the slow-down mirrors it with DJ and DC down to SV; creep at SV to the finish point; stop.
///
/// Integer and division-free per cycle (I32F32 raw bits): each cycle takes the largest rate,
/// within one jerk of the last, from which a ramp-down at the jerk still lands on the target
/// speed (see `Ramp::next`); so the speed reaches DV (and SV) exactly, with the rate at zero.
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
    /// The manual deceleration point, raw I32F32 whole pulses (`None` unless manual).
    manual_point: Option<i64>,
    automatic: bool,
    disabled: bool,
    speed_up: Ramp,
    slow_down: Ramp,
    state: State,
    phase: Phase,
    /// The rate of the present ramp (speed-up while accelerating or easing, slow-down while
    /// decelerating), ≥ 0, raw bits per cycle², and its tail S(rate).
    rate: i64,
    tail: i64,
    /// Raw I32F32 pulses output up to the end of the last cycle that sped up.
    accelerated: i64,
    /// A smooth stop was commanded: decelerate to SV, then stop.
    stopping: bool,
    complete: bool,
    /// The last cycle was an event exempt from the limits (the start, a cut, the stop).
    exempt: bool,
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
                cap_tail: Ramp::tail(cap, jerk),
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
                    Some(i64::from(point.to_bits().min(i32::MAX as u32)) << 32)
                }
                _ => None,
            },
            automatic,
            disabled: p.deceleration_mode == DecelerationMode::Disabled,
            speed_up,
            slow_down,
            state: State::default(),
            phase: Phase::Start,
            rate: 0,
            tail: 0,
            accelerated: 0,
            stopping: false,
            complete: finish == 0,
            exempt: false,
        })
    }

    /// The velocity of the next cycle before the cut to the pulses left (raw I32F32), and the
    /// phase it belongs to.
    fn next_velocity(&mut self) -> i64 {
        let (position, velocity) = (self.state.position.to_bits(), self.state.velocity.to_bits());
        if self.disabled && !self.stopping {
            // DV from the first cycle (the start, an event, is the only one that jumps).
            self.phase = Phase::Accelerating;
            return self.drive;
        }
        if self.phase == Phase::Start {
            self.phase = Phase::Accelerating;
            return self.initial; // SV at once
        }
        if self.phase == Phase::Accelerating {
            let left = self.finish - position;
            let decelerate = self.stopping
                || (self.automatic && left <= self.accelerated)
                // The output count is the position's integer part: compare whole pulses.
                || self.manual_point.is_some_and(|point| position >> 32 << 32 >= point);
            if decelerate {
                self.phase = Phase::Easing;
            }
        }
        if self.phase == Phase::Easing {
            if self.rate > 0 {
                // Down by JK toward zero; the speed-up's tail kept the speed within DV.
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
        }
        match self.phase {
            Phase::Decelerating => {
                if self.stopping && velocity <= self.initial {
                    return 0; // a smooth stop ends at SV, as the chip's decelerating stop does
                }
                // Excess over SV ≥ 0: the slow-down never goes below SV.
                let excess = velocity - self.initial;
                (self.rate, self.tail) = self.slow_down.next(self.rate, self.tail, excess);
                velocity - self.rate
            }
            _ => {
                let gap = self.drive - velocity;
                (self.rate, self.tail) = self.speed_up.next(self.rate, self.tail, gap);
                velocity + self.rate
            }
        }
    }
}

impl ProfileGenerator for Mcx514SCurve {
    fn step(&mut self) -> State {
        let before = self.state.velocity.to_bits();
        let starting = self.phase == Phase::Start;
        // (Deceleration disabled: the first cycle jumps to DV; later ones hold it.)
        let velocity = if self.complete {
            0
        } else {
            let left = self.finish - self.state.position.to_bits();
            let wanted = self.next_velocity();
            // At most the pulses left: the move lands exactly on the finish point. i64: both
            // below 2³¹ pulses in raw I32F32.
            let velocity = wanted.min(left);
            if velocity > before && self.phase == Phase::Accelerating {
                self.accelerated = self.state.position.to_bits() + velocity;
            }
            self.exempt = starting || velocity < wanted || velocity == 0;
            velocity
        };
        if self.complete {
            self.exempt = before != 0;
        }
        let state = advance(&mut self.state, I32F32::from_bits(velocity));
        if velocity == 0 || state.position.to_bits() == self.finish {
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
        let (jerk, max_acceleration) = match self.phase {
            Phase::Decelerating => (self.slow_down.jerk, self.slow_down.cap),
            _ => (self.speed_up.jerk, self.speed_up.cap),
        };
        Limits {
            max_velocity: Some(I32F32::from_bits(self.drive)),
            max_speed_up: Some(I32F32::from_bits(self.speed_up.cap)),
            max_slow_down: Some(I32F32::from_bits(self.slow_down.cap)),
            max_acceleration: Some(I32F32::from_bits(max_acceleration)),
            max_jerk: Some(I32F32::from_bits(jerk)),
            exempt: self.exempt,
        }
    }
}
