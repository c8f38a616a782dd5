//! Trapezoidal point-to-point (SPEC §7): accelerate at A (from an optional starting velocity),
//! cruise at the maximum velocity, decelerate at D and arrive exactly, deciding every cycle from
//! the present state so that every parameter can change in motion.

mod landing;
mod predict;

use fixed::types::I32F32;

use crate::bisect::last_true;
use crate::format::juno::{Acceleration, TargetVelocity};
use crate::replay::{End, Replay};
use crate::state::{advance, Limits, ProfileGenerator, State, StopKind};
use crate::Error;

/// The parameters of a trapezoidal move, in Juno register formats.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct TrapezoidalParameters {
    /// Destination, counts.
    pub destination: i32,
    /// Maximum velocity, counts/cycle (16.16), positive.
    pub max_velocity: TargetVelocity,
    /// Acceleration, counts/cycle² (8.24), non-zero.
    pub acceleration: Acceleration,
    /// Deceleration, counts/cycle² (8.24); zero means "use the acceleration".
    pub deceleration: Acceleration,
    /// Starting velocity, counts/cycle (16.16), 0 … the maximum velocity (MC1x51A): a move from
    /// rest begins at it, so its first cycle may jump to the starting velocity plus one cycle's
    /// acceleration.
    pub start_velocity: TargetVelocity,
}

/// A maximum velocity: the positive half of the 16.16 register.
const MAX_VELOCITY_RANGE: crate::Range = crate::Range {
    min: 0.0,
    ..TargetVelocity::RANGE
};

/// The limits, validated, as I32F32 bits (a separate value from the per-cycle state).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
struct Profile {
    max_velocity: i64,
    acceleration: i64,
    /// Resolved: a zero register means the acceleration.
    deceleration: i64,
    start_velocity: i64,
}

impl TrapezoidalParameters {
    /// Checks every parameter.
    ///
    /// # Errors
    /// [`Error::Zero`] for a zero maximum velocity or acceleration; [`Error::OutOfRange`] for a
    /// negative maximum velocity, or a starting velocity outside 0 … the maximum velocity.
    pub fn validate(&self) -> Result<(), Error> {
        self.profile().map(|_| ())
    }

    fn profile(&self) -> Result<Profile, Error> {
        let max_velocity = i64::from(self.max_velocity.to_bits());
        if max_velocity == 0 {
            return Err(Error::Zero {
                parameter: "velocity",
                range: MAX_VELOCITY_RANGE,
            });
        }
        if max_velocity < 0 {
            return Err(Error::out_of_range_bits(
                "velocity",
                max_velocity,
                16,
                MAX_VELOCITY_RANGE,
            ));
        }
        if self.acceleration.is_zero() {
            return Err(Error::Zero {
                parameter: "acceleration",
                range: Acceleration::RANGE,
            });
        }
        let start_velocity = i64::from(self.start_velocity.to_bits());
        if !(0..=max_velocity).contains(&start_velocity) {
            // 0 … the maximum velocity (16.16 bits, like the starting velocity).
            return Err(Error::out_of_range_bits(
                "start velocity",
                start_velocity,
                16,
                MAX_VELOCITY_RANGE.up_to_bits(max_velocity, 16),
            ));
        }
        let acceleration = i64::from(self.acceleration.to_bits()) << 8;
        let deceleration = match self.deceleration.to_bits() {
            0 => acceleration,
            bits => i64::from(bits) << 8,
        };
        // 16.16 → I32F32: shift left 16; 8.24 → I32F32: shift left 8. Both exact.
        Ok(Profile {
            max_velocity: max_velocity << 16,
            acceleration,
            deceleration,
            start_velocity: start_velocity << 16,
        })
    }
}

/// What the next cycle does.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Phase {
    /// Heading for the destination along a plan: stepping replays its runs.
    Run,
    /// Heading for the destination from a state no plan covers: each cycle decides from
    /// scratch, then plans again. One kind is left: moving away so far that the distance passes
    /// 2^31 counts. (A plan that ends in such a state runs as `Decide` from the start: its runs
    /// lead to [`ELSEWHERE`].)
    Decide,
    /// Smooth stop: decelerating to rest, destination abandoned.
    Stopping,
    /// Abrupt stop: its cycle is the run in slot `stop_slot`, and after it the axis heads for the
    /// destination if a new maximum velocity came in the meantime (`resume`), else it is
    /// stopped ([`Trapezoidal::phase`] reads it so once the cycle is stepped).
    AbruptPending { resume: bool },
    /// Stopped: the velocity register is zero; a new maximum velocity restarts.
    Stopped,
}

/// One run of the plan: `count` cycles whose velocities (on the axis, signed) are `next`,
/// `next + increment`, … (a velocity change that is constant over the run).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
struct Run {
    /// The velocity of the run's next cycle, I32F32 bits.
    next: i64,
    /// Its change per cycle.
    increment: i64,
    /// Cycles left in the run (≥ 1 while it is the current run).
    count: u64,
}

impl Run {
    /// The run as it is replayed ([`Replay`]: the same cycles).
    const fn replay(&self) -> Replay {
        Replay::new(self.next, self.increment, self.count)
    }

    /// An empty run, left out of a plan.
    const NONE: Self = Self {
        next: 0,
        increment: 0,
        count: 0,
    };
    /// At rest: velocity zero for 2^64 − 1 cycles (for ever, in practice), so resting cycles
    /// take the common path too. A plan's arriving cycle is its first.
    const REST: Self = Self {
        next: 0,
        increment: 0,
        count: u64::MAX,
    };
}

/// The smallest non-zero 8.24 rate as I32F32 bits (1 << 8): the least deceleration a validated
/// profile has.
const MIN_DECELERATION: i64 = 1 << 8;
/// Above the largest 8.24 rate as I32F32 bits ((2^31 − 1) << 8 < 2^39).
const MAX_DECELERATION: i64 = 1 << 40;

/// The slots of [`Trapezoidal::runs`]: a plan has at most nine runs (moving away from the
/// destination and the cycle that turns, then accelerate, cruise, brake, bump, rest; or the six
/// of a `landing` plan and rest), and slot [`ELSEWHERE`] stands for the phases that are not a
/// plan. A power of two, so that `% RUNS` is a mask.
const RUNS: usize = 16;
/// The slot that sends the next step to [`Trapezoidal::step_otherwise`]: a one-cycle run, so the
/// common path needs no test of the phase (its count running out is the test).
const ELSEWHERE: usize = RUNS - 1;

/// A run of the per-cycle rule laid out for another generator ([`Trapezoidal::rule_runs`]):
/// `(first velocity, change per cycle, cycles)`, I32F32 bits.
pub(crate) type RuleRun = (i64, i64, u64);

/// The runs of a plan while it is worked out, in order, empty ones left out. At most 13 (an
/// abrupt stop's cycle, three slowing stages, two turning runs, the six of a plan and rest),
/// below [`ELSEWHERE`].
#[derive(Debug, Clone, Copy)]
struct Layout {
    runs: [Run; ELSEWHERE],
    len: usize,
}

impl Layout {
    const fn new() -> Self {
        Self {
            runs: [Run::NONE; ELSEWHERE],
            len: 0,
        }
    }

    /// Appends `run` unless it is empty.
    fn push(&mut self, run: Run) {
        if run.count != 0 {
            if let Some(slot) = self.runs.get_mut(self.len) {
                *slot = run;
                self.len += 1;
            }
        }
    }

    fn runs(&self) -> &[Run] {
        &self.runs[..self.len]
    }
}

/// The trapezoidal point-to-point generator.
///
/// Every cycle takes the largest velocity that (a) speeds up by at most A (or jumps to the
/// starting velocity from rest), (b) stays within the maximum velocity, and (c) still lets the
/// axis stop exactly on the destination decelerating by at most D per cycle — see
/// [`Trapezoidal::braking_velocity`] for how (c) is exact. So it arrives exactly, with no
/// precomputed deceleration point, and any parameter can change in motion.
///
/// Those decisions are taken ahead: every command works out, from the present state, on which
/// cycle (c) will first bind and what the braking velocities will be, as at most six runs of
/// constant velocity change laid out in a table (after the cycles that slow down by D from above
/// a lowered maximum velocity, or from too fast for a nearer destination, and after an abrupt
/// stop's own cycle, which are runs too), and stepping replays them: one addition and a countdown per cycle, and the cycle that ends a run
/// moves on to the next in the table (nothing is worked out while stepping). Until the next
/// command, each cycle's velocity is exactly the one a decision from that cycle's state
/// would take (tested against the per-cycle decision, `tests/same_states.rs`); any command
/// drops the plan and works it out again.
///
/// The last moving cycle may drop to rest from up to the starting velocity S (SPEC §7), as the
/// first may jump from rest to it. While S ≤ D that drop is an ordinary deceleration and the rule
/// above is the whole story. With S > D the largest velocity each cycle can leave a distance that
/// no landing covers, so the move is planned whole instead (the `landing` module): the fewest
/// cycles the limits allow, at the highest velocities that cover the distance exactly. That plan
/// is at most 2 cycles over the continuous-time optimum with both jumps
/// ([`crate::reference::trapezoidal_duration`]) on most moves; on the rest (about 2 % of random
/// moves with a starting velocity) no plan can be, as the discrete limits cost up to half a cycle
/// more, and it is within 2.5 (`tests/trapezoidal.rs`, `fewest_moving_cycles`). A command in
/// motion plans that way again from the present state, the fewest cycles from it (its first
/// slowing down by at most D); when the axis is too fast for any plan to land, it slows down by
/// D until it has passed the destination, then turns back.
///
/// ```
/// use profilegen::format::juno::{Acceleration, TargetVelocity};
/// use profilegen::{ProfileGenerator, Trapezoidal, TrapezoidalParameters};
///
/// let mut axis = Trapezoidal::new(TrapezoidalParameters {
///     destination: 1_000,
///     max_velocity: TargetVelocity::from_num(20.0)?,
///     acceleration: Acceleration::from_num(0.5)?,
///     deceleration: Acceleration::ZERO,
///     start_velocity: TargetVelocity::ZERO,
/// })?;
/// let last = axis.states_until_complete().last().unwrap();
/// assert_eq!((last.position, last.velocity), (1_000.into(), 0.into()));
/// # Ok::<(), profilegen::Error>(())
/// ```
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Trapezoidal {
    // The per-cycle fields first.
    /// The run under way: an index into `runs` (always below [`RUNS`]).
    current: usize,
    /// The plan's runs in order, worked out when the plan is made, so the cycle that ends one
    /// run only moves on to the next (the last run, at rest, never ends), and [`ELSEWHERE`].
    runs: [Replay; RUNS],
    state: State,
    phase: Phase,
    parameters: TrapezoidalParameters,
    profile: Profile,
    /// The destination as I32F32 bits.
    destination: i64,
    /// The state the last abrupt stop produced, until a command: while the generator still
    /// shows it, its last cycle was that stop (for [`ProfileGenerator::limits`]).
    abrupt_state: Option<State>,
    /// The state a pending abrupt stop's cycle produces, worked out when the stop is given
    /// (that cycle is a run of the plan, [`Self::lay_out_abrupt`]).
    abrupt_next: State,
    /// While an abrupt stop is pending, the slot of its cycle: it is pending until that run has
    /// been stepped (see [`Self::phase`]).
    stop_slot: usize,
    /// During a smooth stop, the slot of the rest run that ends it: the stop is over once that
    /// run is under way.
    rest_slot: usize,
}

impl Trapezoidal {
    /// A generator at rest at position 0 that starts the move on its first step.
    ///
    /// # Errors
    /// As [`TrapezoidalParameters::validate`].
    pub fn new(parameters: TrapezoidalParameters) -> Result<Self, Error> {
        Self::with_position(parameters, I32F32::ZERO)
    }

    /// As [`Self::new`], starting at rest at `position`.
    ///
    /// # Errors
    /// As [`TrapezoidalParameters::validate`].
    pub fn with_position(
        parameters: TrapezoidalParameters,
        position: I32F32,
    ) -> Result<Self, Error> {
        let profile = parameters.profile()?;
        let mut generator = Self {
            current: 0,
            runs: [Replay::new(0, 0, 0); RUNS],
            state: State::at_rest(position),
            phase: Phase::Run,
            parameters,
            profile,
            destination: i64::from(parameters.destination) << 32,
            abrupt_state: None,
            abrupt_next: State::at_rest(position),
            stop_slot: 0,
            rest_slot: 0,
        };
        generator.plan();
        Ok(generator)
    }

    /// The parameters in force (after a stop the maximum velocity reads zero, as the chip's
    /// register does).
    pub fn parameters(&self) -> TrapezoidalParameters {
        let mut parameters = self.parameters;
        if matches!(
            self.phase(),
            Phase::Stopped | Phase::Stopping | Phase::AbruptPending { resume: false }
        ) {
            parameters.max_velocity = TargetVelocity::ZERO;
        }
        parameters
    }

    /// Replaces all parameters at once, in motion or at rest; they apply from the next cycle.
    /// During or after a stop this restarts motion (after the abrupt stop's cycle, for that kind).
    ///
    /// # Errors
    /// As [`TrapezoidalParameters::validate`]; on error nothing changes.
    pub fn set_parameters(&mut self, parameters: TrapezoidalParameters) -> Result<(), Error> {
        self.profile = parameters.profile()?;
        self.parameters = parameters;
        self.destination = i64::from(parameters.destination) << 32;
        self.settle();
        self.abrupt_state = None;
        // A new velocity restarts a stopped or stopping axis (the abrupt stop still happens).
        match self.phase {
            Phase::AbruptPending { .. } => self.lay_out_abrupt(true),
            _ => self.plan(),
        }
        Ok(())
    }

    /// Sets a new destination; applies from the next cycle (a destination behind the axis means
    /// decelerate, reverse and arrive). After a stop, motion restarts only with a new maximum
    /// velocity.
    pub fn set_destination(&mut self, destination: i32) {
        self.parameters.destination = destination;
        self.destination = i64::from(destination) << 32;
        self.replan();
    }

    /// Sets a new maximum velocity; applies from the next cycle (a lower one means decelerate at
    /// D down to it). After a stop this restarts motion.
    ///
    /// # Errors
    /// As [`TrapezoidalParameters::validate`]; on error nothing changes.
    pub fn set_max_velocity(&mut self, max_velocity: TargetVelocity) -> Result<(), Error> {
        self.set_parameters(TrapezoidalParameters {
            max_velocity,
            ..self.parameters
        })
    }

    /// Sets a new acceleration; applies from the next cycle.
    ///
    /// # Errors
    /// [`Error::Zero`] if it is zero; on error nothing changes.
    pub fn set_acceleration(&mut self, acceleration: Acceleration) -> Result<(), Error> {
        self.change(TrapezoidalParameters {
            acceleration,
            ..self.parameters
        })
    }

    /// Sets a new deceleration (zero: use the acceleration); applies from the next cycle.
    pub fn set_deceleration(&mut self, deceleration: Acceleration) {
        // Only the deceleration changes, and any deceleration register is valid.
        let _ = self.change(TrapezoidalParameters {
            deceleration,
            ..self.parameters
        });
    }

    /// Sets a new starting velocity; applies to the next cycle that starts from rest.
    ///
    /// # Errors
    /// [`Error::OutOfRange`] unless 0 ≤ it ≤ the maximum velocity; on error nothing changes.
    pub fn set_start_velocity(&mut self, start_velocity: TargetVelocity) -> Result<(), Error> {
        self.change(TrapezoidalParameters {
            start_velocity,
            ..self.parameters
        })
    }

    /// A change that, unlike a new maximum velocity, does not restart a stopped axis.
    fn change(&mut self, parameters: TrapezoidalParameters) -> Result<(), Error> {
        self.profile = parameters.profile()?;
        self.parameters = parameters;
        self.replan();
        Ok(())
    }

    /// After a command: plans again if the axis is heading for the destination; a stopping axis
    /// keeps stopping, at the deceleration now in force; a stopped one stays put.
    fn replan(&mut self) {
        self.settle();
        self.abrupt_state = None;
        match self.phase {
            Phase::Run | Phase::Decide => self.plan(),
            Phase::Stopping if !self.stop_over() => self.plan_stop(),
            // The plan after a pending abrupt stop uses what is in force at its cycle.
            Phase::AbruptPending { resume: true } => self.lay_out_abrupt(true),
            _ => {}
        }
    }

    /// An abrupt stop from the present state: its cycle (velocity zero, the whole drop) as a
    /// one-cycle run, then rest, or, with `resume` (a new maximum velocity came after the stop),
    /// the plan from rest where it stops. The state it produces is worked out now, so its cycle
    /// is an ordinary step.
    fn lay_out_abrupt(&mut self, resume: bool) {
        const STOP: Run = Run {
            next: 0,
            increment: 0,
            count: 1,
        };
        self.abrupt_next = self.state.advanced(I32F32::ZERO);
        if resume {
            self.plan_after(STOP);
        } else {
            self.set_runs(0, &[STOP, Run::REST]);
        }
        self.phase = Phase::AbruptPending { resume };
        self.stop_slot = self.current;
    }

    /// Whether an abrupt stop's cycle is still to come.
    fn abrupt_pending(&self) -> bool {
        matches!(self.phase, Phase::AbruptPending { .. }) && self.current == self.stop_slot
    }

    /// The phase, with an abrupt stop whose cycle has been stepped read as what follows it:
    /// stopped, or heading for the destination after a resume (stepping does not update
    /// `phase`; [`Self::settle`] does at the next command).
    fn phase(&self) -> Phase {
        match self.phase {
            Phase::AbruptPending { resume } if !self.abrupt_pending() => {
                if resume {
                    Phase::Run
                } else {
                    Phase::Stopped
                }
            }
            phase => phase,
        }
    }

    /// The state the last abrupt stop's cycle produced (None after a command).
    fn last_abrupt(&self) -> Option<State> {
        match self.phase {
            Phase::AbruptPending { .. } if !self.abrupt_pending() => Some(self.abrupt_next),
            _ => self.abrupt_state,
        }
    }

    /// Brings `phase` up to date after an abrupt stop's cycle (see [`Self::phase`]).
    fn settle(&mut self) {
        self.abrupt_state = self.last_abrupt();
        self.phase = self.phase();
    }

    /// A smooth stop as runs, from the present state: the velocity falls by D every cycle while
    /// it stays on its side of zero (⌈|v| / D⌉ − 1 cycles, a division once), then one cycle at
    /// zero (the stop's last, before which the axis is not at rest yet), then rest: the
    /// deceleration of SPEC §9 without a decision per cycle.
    fn plan_stop(&mut self) {
        let velocity = self.state.velocity.to_bits();
        let deceleration = self.profile.deceleration;
        // 0 when moving forwards (or at rest), −1 backwards: the run turned round by mask.
        let sign = velocity >> 63;
        let magnitude = velocity.unsigned_abs();
        let slowing = magnitude.saturating_sub(1) / deceleration as u64;
        let turn = |v: i64| (v ^ sign) - sign;
        let runs = [
            Run {
                next: turn(magnitude as i64 - deceleration),
                increment: turn(-deceleration),
                count: slowing,
            },
            Run {
                next: 0,
                increment: 0,
                count: 1,
            },
            Run::REST,
        ];
        self.set_runs(0, &runs);
        self.rest_slot = usize::from(slowing != 0) + 1;
    }

    /// Whether a smooth stop has come to rest (its rest run under way).
    fn stop_over(&self) -> bool {
        self.state.velocity == I32F32::ZERO && self.current == self.rest_slot
    }

    /// The distance (I32F32 bits) travelled from a cycle at `velocity` ≥ 0 (that cycle
    /// included) until rest, slowing down by the full deceleration D every cycle:
    /// `T(v) = v + (v − D) + (v − 2D) + … ` over the positive terms, then 0 (the last positive
    /// term is ≤ D, so that drop is allowed). With `q = ⌊v / D⌋`:
    /// `T(v) = (q + 1)·v − D·q(q + 1)/2`. Exact: v < 2^48 and D ≥ 2^8, so q < 2^40 and the
    /// products stay below 2^89.
    fn stopping_distance(velocity: i64, deceleration: i64) -> i128 {
        // Floor division of non-negative values below 2^48: u64 is enough.
        let q = (velocity as u64 / deceleration as u64) as i128;
        let (velocity, deceleration) = (i128::from(velocity), i128::from(deceleration));
        (q + 1) * velocity - deceleration * (q * (q + 1) / 2)
    }

    /// The largest velocity `v` (I32F32 bits) with `T(v) ≤ distance`: the fastest this cycle may
    /// go and still stop exactly on the destination, decelerating by at most D per cycle.
    ///
    /// `T` is increasing and piecewise linear: on `q·D ≤ v < (q + 1)·D` it is
    /// `(q + 1)·v − D·q(q + 1)/2`, and `T(q·D) = D·q(q + 1)/2`. So find the segment, the largest
    /// `q` with `D·q(q + 1)/2 ≤ distance` (`q(q + 1) ≤ m = ⌊2·distance / D⌋` ⇔
    /// `2q + 1 ≤ ⌊√(4m + 1)⌋`, an exact integer square root), then solve the segment's line and
    /// round down: `v = ⌊(distance + D·q(q + 1)/2) / (q + 1)⌋`. Any distance left over,
    /// `distance − T(v) < q + 1` units of 2^-32 counts, is absorbed on later cycles, because the
    /// velocity can take any 2^-32 value: the axis lands exactly.
    ///
    /// Defined for every input (it never panics): a deceleration outside 2^8 … 2^40 (the 8.24
    /// rates, 2^8 … 2^39, with room) counts as the nearer end, and a distance beyond 2^64 − 1
    /// (farther than any two positions of the 32-bit register) as 2^64 − 1. (Found by the audit
    /// of issue #17: a zero or negative deceleration divided by zero or overflowed, and one
    /// near 2^63 made a velocity past `i64`.)
    pub fn braking_velocity(distance: i128, deceleration: i64) -> i64 {
        Self::braking(
            distance.min(i128::from(u64::MAX)),
            deceleration.clamp(MIN_DECELERATION, MAX_DECELERATION),
        )
    }

    /// [`Self::braking_velocity`] within its domain: `distance` < 2^64, `deceleration` within
    /// 1 … 2^40 (the generator's own calls, on every plan: a validated rate and a position
    /// difference; and the S-curve's smooth stop, one derivative up, with its jerk of 1 raw unit
    /// and more and a velocity below 2^60), so the velocity is below √(2·2^40·2^64) + 2^40 < 2^53.
    pub(crate) fn braking(distance: i128, deceleration: i64) -> i64 {
        if distance <= 0 {
            return 0;
        }
        // Distances up to 2^62 (2^30 counts) take 64-bit divisions, several times cheaper than
        // 128-bit ones: 2·distance < 2^63, and the numerator below is < 2·distance + D·(q+1)
        // < 2^64. Longer distances take the same arithmetic in 128 bits.
        if let (Ok(distance), Ok(deceleration)) =
            (u64::try_from(distance), u64::try_from(deceleration))
        {
            if distance < 1 << 62 {
                let m = 2 * distance / deceleration;
                let q = ((4 * m + 1).isqrt() - 1) / 2;
                // D·q(q+1)/2 ≤ distance (that is how q was chosen), so no overflow.
                let numerator = distance + deceleration * (q * (q + 1) / 2);
                return (numerator / (q + 1)) as i64;
            }
        }
        let deceleration = i128::from(deceleration);
        // distance < 2^64 and D ≥ 2^8, so m < 2^57 and 4m + 1 < 2^59: u64 throughout.
        let m = (2 * distance / deceleration) as u64;
        let q = i128::from(((4 * m + 1).isqrt() - 1) / 2);
        let numerator = distance + deceleration * q * (q + 1) / 2;
        (numerator / (q + 1)) as i64
    }

    /// The runs the per-cycle rule takes from a state `distance` ahead (≥ 0, I32F32 bits)
    /// moving at `velocity` (signed, positive toward the destination) to rest on the
    /// destination, with the maximum velocity `max_velocity`, A = D = `rate` (≥ 1, any
    /// integer: no 8.24 register behind it) and no starting velocity, as `(first velocity,
    /// change per cycle, cycles)`, the last the rest run (`u64::MAX` cycles, its first the
    /// cycle that arrives) — or `None` when no plan covers the state (see `Phase::Decide`).
    ///
    /// For the S-curve's smooth stop, which is this rule one derivative up: the distance is the
    /// velocity left, the velocity the deceleration. The plan is worked out by a generator
    /// standing for that profile, never stepped (the planning reads only its profile and
    /// destination). Bounds: `distance` < 2^62, `velocity` and `max_velocity` < 2^33, `rate`
    /// ≤ 2^31, so every product of the planning stays within its i128 (and 64-bit) width.
    pub(crate) fn rule_runs(
        distance: i64,
        velocity: i64,
        max_velocity: i64,
        rate: i64,
    ) -> Option<([RuleRun; ELSEWHERE], usize)> {
        let parameters = TrapezoidalParameters {
            destination: 0,
            max_velocity: TargetVelocity::ZERO,
            acceleration: Acceleration::ZERO,
            deceleration: Acceleration::ZERO,
            start_velocity: TargetVelocity::ZERO,
        };
        let planner = Self {
            current: 0,
            runs: [Replay::new(0, 0, 0); RUNS],
            state: State::at_rest(I32F32::ZERO),
            phase: Phase::Run,
            parameters,
            profile: Profile {
                max_velocity,
                acceleration: rate,
                deceleration: rate,
                start_velocity: 0,
            },
            destination: 0,
            abrupt_state: None,
            abrupt_next: State::at_rest(I32F32::ZERO),
            stop_slot: 0,
            rest_slot: 0,
        };
        let mut layout = Layout::new();
        if !planner.plan_into(&mut layout, distance.wrapping_neg(), velocity) {
            return None;
        }
        let mut runs = [(0, 0, 0); ELSEWHERE];
        for (to, run) in runs.iter_mut().zip(layout.runs()) {
            *to = (run.next, run.increment, run.count);
        }
        Some((runs, layout.len))
    }

    /// The per-cycle decision from scratch, in the frame where the destination lies ahead
    /// (`distance ≥ 0`): the velocity rule of the type's documentation, for any state.
    fn decide_ahead(&self, distance: i128, velocity: i64) -> i64 {
        let Profile {
            max_velocity,
            acceleration,
            deceleration,
            start_velocity,
        } = self.profile;
        // From rest the first cycle may jump to the starting velocity and accelerate from there:
        // "accelerating at the commanded acceleration, beginning at the starting velocity".
        let speed_up = if velocity == 0 {
            acceleration + start_velocity
        } else {
            acceleration
        };
        if velocity < 0 {
            // Moving away from the destination: slow down by D; the cycle that crosses zero
            // changes the velocity by at most D in all and speeds up by at most A.
            let slowed = velocity + deceleration;
            if slowed <= 0 {
                return slowed;
            }
            let braking = Self::braking(distance, deceleration);
            return slowed.min(acceleration).min(max_velocity).min(braking);
        }
        let upper = if velocity > max_velocity {
            // A lower maximum velocity: decelerate at D down to it.
            (velocity - deceleration).max(max_velocity)
        } else {
            (velocity + speed_up).min(max_velocity)
        };
        if Self::stopping_distance(upper, deceleration) <= distance {
            return upper;
        }
        // Braking is due. From any state reached under constant parameters the braking velocity
        // is at least velocity − D (the previous cycle checked T(velocity) ≤ distance before it);
        // after a change of destination or D it may not be, and then the axis slows by D and
        // overshoots as little as it can.
        Self::braking(distance, deceleration).max(velocity - deceleration)
    }

    /// The signed distance to go and the direction mask of the frame where it lies ahead
    /// (the destination's side, or the velocity's when on it).
    fn ahead(&self) -> (i64, i64) {
        // Modulo the 32-bit position register: the move goes the short way round, as on the
        // chip (exact for every |distance| < 2^31 counts).
        let distance = self.destination.wrapping_sub(self.state.position.to_bits());
        let toward = if distance != 0 {
            distance
        } else {
            self.state.velocity.to_bits()
        };
        (distance, toward >> 63)
    }

    /// Works out, from the present state and parameters, the cycles to the destination: the
    /// decisions of [`Self::decide_ahead`] for every cycle until the next command, taken at once.
    ///
    /// In the frame where the destination lies ahead, with `d` the distance and `v` the velocity
    /// (0 ≤ v ≤ the maximum V): cycle `i` would go at `u_i = min(w + i·A, V)` (`w` = v, or the
    /// starting velocity from rest), and it may as long as `T(u_i)` fits in what is left,
    /// `d − (u_1 + … + u_{i−1})`. Both sides are monotone in `i` (the velocities rise, the
    /// distance left falls), so the first cycle that must brake is found by bisection over the
    /// accelerating cycles, or by one division over the cruising ones. From there the braking
    /// velocity `b` = [`Self::braking_velocity`] of the distance left, which leaves
    /// `L = distance − T(b) ≤ q = ⌊b / D⌋` over. Each later cycle's distance left is
    /// `T(b − k·D) + L` (`T(x) = x + T(x − D)`), whose braking velocity is `b − k·D` while
    /// `L` is less than the segment's slope, one unit more on the cycle it equals it (`L` is
    /// then spent), and zero once in segment 0: so the braking cycles are runs too, and the
    /// decision of every cycle is known without a division.
    fn plan(&mut self) {
        self.plan_after(Run::NONE);
    }

    /// [`Self::plan`] after `opening` (an abrupt stop's cycle, or [`Run::NONE`]): the plan from
    /// the state that run leaves, laid out behind it.
    fn plan_after(&mut self, opening: Run) {
        let mut layout = Layout::new();
        layout.push(opening);
        let mut position = self.state.position.to_bits();
        let mut velocity = self.state.velocity.to_bits();
        if opening.count != 0 {
            // The opening keeps its velocity for its cycles (an abrupt stop: one, at zero).
            velocity = opening.next;
            position = position.wrapping_add(velocity.wrapping_mul(opening.count as i64));
        }
        if self.plan_into(&mut layout, position, velocity) {
            self.phase = Phase::Run;
            self.set_runs(0, layout.runs());
        } else {
            self.phase = Phase::Decide;
            self.set_runs(ELSEWHERE, layout.runs());
        }
    }

    /// Appends to `layout` the runs from the state at `position` moving at `velocity` (I32F32
    /// bits) to the destination; `true` when they end at rest there, `false` when they end in
    /// a state no plan covers (the next step then goes to [`ELSEWHERE`]).
    ///
    /// States whose per-cycle decision is "slow down by D" whatever the distance (above a
    /// lowered maximum velocity; too fast to stop on the destination after a change) are runs
    /// too ([`Self::slowing_run`]): the plan follows them to the state where the rule decides
    /// otherwise (the maximum velocity reached, braking in reach, the destination passed) and
    /// goes on from there. A few such stages at most: the loop's bound is never reached.
    fn plan_into(&self, layout: &mut Layout, mut position: i64, mut velocity: i64) -> bool {
        for _ in 0..8 {
            let distance = self.destination.wrapping_sub(position);
            let toward = if distance != 0 { distance } else { velocity };
            let sign = toward >> 63;
            let ahead = (velocity ^ sign) - sign;
            if ahead < 0 {
                return self.plan_turn(layout, distance, ahead, sign);
            }
            // With a starting velocity above D the landing covers every state any plan lands
            // from; the rest pass the destination, slowing down by D (`slowing_run`).
            if self.profile.start_velocity > self.profile.deceleration
                && ahead <= self.profile.max_velocity
                && self.push_landing(layout, distance, ahead, sign)
            {
                return true;
            }
            let Some((next, increment, count)) = self.slowing_run(distance.unsigned_abs(), ahead)
            else {
                return self.plan_from(layout, distance, ahead, sign);
            };
            let run = Run {
                next: (next ^ sign) - sign,
                increment: (increment ^ sign) - sign,
                count,
            };
            layout.push(run);
            // The run's cycles cover count·next + increment·count(count − 1)/2 (within the
            // 64-bit position, which wraps like the register: the runs are at most 2^40 cycles
            // of velocities below 2^48, and the sum is the distance's, below 2^64 in magnitude).
            let count_wide = i128::from(count);
            let covered = count_wide * i128::from(run.next)
                + i128::from(run.increment) * (count_wide * (count_wide - 1) / 2);
            position = position.wrapping_add(covered as i64);
            velocity = run.next + (count as i64 - 1) * run.increment;
        }
        false
    }

    /// The run of cycles that slow down by D from a state the plans do not cover, in the frame
    /// where the destination lies ahead (`distance` ≥ 0, `velocity` ≥ 0, I32F32 bits), as
    /// `(first velocity, change per cycle, cycles)`; `None` when the state is one the plans
    /// cover ([`Self::plan_from`]).
    ///
    /// - Above the maximum V: the per-cycle rule takes `max(v − D, V)` when its stopping
    ///   distance fits and `max(braking velocity, v − D)` when not, so `v − D` while that is
    ///   ≥ V whatever the distance; the cycle that crosses V decides by the rule (one cycle).
    /// - At most V, but `T(v − D)` > the distance (a nearer destination or a smaller D): the rule
    ///   takes `v − D` (the braking velocity is below it), and that leaves the same situation
    ///   (`T(v − 2D) = T(v − D) − (v − D)`) while the velocity stays above D. With a starting
    ///   velocity above D the `landing` plan covers every state from which any plan lands
    ///   ([`Self::plan_into`] asks it first), and a state it does not cover is of this kind
    ///   (the rule's own plan, which lands with a drop ≤ D, would otherwise do); slowing down by
    ///   D leads to others of the same kind (a plan from the state after such a cycle would
    ///   land from this one too), so they pass the destination, as above.
    ///
    /// Either run also ends after the cycle that passes the destination (the frame turns
    /// round): distance left `d_j = d − j·v + D·j(j + 1)/2` after `j` cycles, decreasing while
    /// the velocities are positive, so the last `j` with `d_j ≥ 0` is a bisection.
    fn slowing_run(&self, distance: u64, velocity: i64) -> Option<(i64, i64, u64)> {
        let Profile {
            max_velocity,
            deceleration,
            ..
        } = self.profile;
        let cycles = if velocity > max_velocity {
            let cycles = (velocity - max_velocity) as u64 / deceleration as u64;
            if cycles == 0 {
                // The cycle that crosses V.
                let next = self.decide_ahead(i128::from(distance), velocity);
                return Some((next, 0, 1));
            }
            cycles
        } else {
            if velocity <= deceleration
                || Self::stopping_distance(velocity - deceleration, deceleration)
                    <= i128::from(distance)
            {
                return None;
            }
            // While the velocity before the cycle is above D: v − j·D > D ⇔ j < v / D.
            (velocity as u64 - 1) / deceleration as u64
        };
        let (distance_wide, velocity_wide, deceleration_wide) = (
            i128::from(distance),
            i128::from(velocity),
            i128::from(deceleration),
        );
        let left = |j: u64| {
            let j = i128::from(j);
            distance_wide - j * velocity_wide + deceleration_wide * (j * (j + 1) / 2)
        };
        // The last j ≤ cycles with d_j ≥ 0 (d_0 ≥ 0); the cycle after it, if within the run,
        // passes the destination and ends the run.
        let last = last_true(0, cycles + 1, |j| left(j) >= 0);
        Some((velocity - deceleration, -deceleration, cycles.min(last + 1)))
    }

    /// Moving away from the destination: the per-cycle rule slows down by D while the velocity
    /// stays on the far side of zero (or reaches it), ⌊|v| / D⌋ cycles, then turns with one cycle
    /// at `min(v + D, A, V, braking velocity)` ([`Self::decide_ahead`]), then goes on as from
    /// that state. All of that is worked out here, as two runs before the plan from the state
    /// after them ([`Self::plan_from`]). `None` (decide cycle by cycle) when moving away would
    /// take the distance past 2^31 counts, where the short way round turns the other way.
    fn plan_turn(&self, layout: &mut Layout, distance: i64, velocity: i64, sign: i64) -> bool {
        let deceleration = self.profile.deceleration;
        let away = velocity.unsigned_abs() / deceleration as u64;
        let (away_wide, velocity_wide, deceleration_wide) = (
            i128::from(away),
            i128::from(velocity),
            i128::from(deceleration),
        );
        // The distance once the away cycles are over: they cover k·v + D·k(k + 1)/2 ≤ 0.
        let moved =
            away_wide * velocity_wide + deceleration_wide * (away_wide * (away_wide + 1) / 2);
        let Ok(far) = i64::try_from(i128::from(distance.unsigned_abs()) - moved) else {
            return false;
        };
        let last = velocity + away as i64 * deceleration;
        let turn = |v: i64| (v ^ sign) - sign;
        let away_run = Run {
            next: turn(velocity + deceleration),
            increment: turn(deceleration),
            count: away,
        };
        layout.push(away_run);
        if last == 0 {
            // At rest after the away cycles: a plan from rest (with the starting velocity).
            return self.plan_from(layout, far, 0, sign);
        }
        let turning = self.decide_ahead(i128::from(far), last);
        let turn_run = Run {
            next: turn(turning),
            increment: 0,
            count: 1,
        };
        layout.push(turn_run);
        self.plan_from(layout, far - turning, turning, sign)
    }

    /// [`Self::plan_into`] from a state `distance` ahead (≥ 0, I32F32 bits) moving at
    /// `velocity` in that frame, `sign` the frame's direction mask: appends the runs, `true`
    /// when they end at rest on the destination.
    fn plan_from(&self, layout: &mut Layout, distance: i64, velocity: i64, sign: i64) -> bool {
        let Profile {
            max_velocity,
            acceleration,
            deceleration,
            start_velocity,
        } = self.profile;
        if distance == 0 && velocity == 0 {
            layout.push(Run::REST);
            return true;
        }
        if !(0..=max_velocity).contains(&velocity) {
            return false;
        }
        if start_velocity > deceleration && self.push_landing(layout, distance, velocity, sign) {
            // The drop from the starting velocity is more than D: the landing is planned with
            // the move (`landing`).
            return true;
        }
        // |distance| ≤ 2^63; in i128 throughout the search.
        let distance = i128::from(distance.unsigned_abs());
        // Turns a run of the frame where the destination lies ahead round to the axis.
        let ahead = |next: i64, increment: i64, count: u64| Run {
            next: (next ^ sign) - sign,
            increment: (increment ^ sign) - sign,
            count,
        };
        let base = if velocity == 0 {
            start_velocity
        } else {
            velocity
        };
        // Cycles that accelerate without reaching V: base + i·A < V ⇔ i ≤ (V − base − 1) / A.
        // `base` ≤ V (the starting velocity is at most V), so the numerator is ≥ −1.
        let rising = u64::try_from((max_velocity - base - 1) / acceleration).unwrap_or(0);
        let (base_wide, acceleration_wide, max_wide) = (
            i128::from(base),
            i128::from(acceleration),
            i128::from(max_velocity),
        );
        // u_i and u_1 + … + u_k (k < 2^56 and every velocity < 2^48: below 2^104).
        let velocity_of = |i: u64| -> i64 {
            if i <= rising {
                base + i as i64 * acceleration
            } else {
                max_velocity
            }
        };
        let covered = |k: u64| -> i128 {
            let rising_part = i128::from(k.min(rising));
            rising_part * base_wide
                + acceleration_wide * (rising_part * (rising_part + 1) / 2)
                + i128::from(k - k.min(rising)) * max_wide
        };
        let may = |i: u64| -> bool {
            Self::stopping_distance(velocity_of(i), deceleration) <= distance - covered(i - 1)
        };
        // m: the number of cycles before the first that brakes.
        let cycles = if rising == 0 || may(rising) {
            // Past the rising cycles, every cycle goes at V while T(V) fits.
            let room =
                distance - covered(rising) - Self::stopping_distance(max_velocity, deceleration);
            if room < 0 {
                rising
            } else {
                rising + 1 + (room / max_wide) as u64
            }
        } else {
            // may(0) holds by convention, may(rising) does not: bisect.
            last_true(0u64, rising, may)
        };
        let last = if cycles == 0 {
            velocity
        } else {
            velocity_of(cycles)
        };
        let left = distance - covered(cycles);
        let braking = Self::braking(left, deceleration);
        let accelerate = ahead(base + acceleration, acceleration, cycles.min(rising));
        let cruise = ahead(max_velocity, 0, cycles - cycles.min(rising));
        if braking < last - deceleration {
            // Too fast to stop on the destination within D after these runs (a change made it
            // so, with a starting velocity above D: `slowing_run` lays out the other cases):
            // then decide cycle by cycle. The runs go last before `ELSEWHERE`.
            layout.push(accelerate);
            layout.push(cruise);
            return false;
        }
        // < q + 1 ≤ 2^40 (the braking velocity is the largest that fits).
        let leftover = (left - Self::stopping_distance(braking, deceleration)) as u64;
        let segment = braking as u64 / deceleration as u64;
        // The first braking velocity, then D less for as long as the leftover is below the
        // segment's slope: segment − leftover cycles.
        let count = 1 + (segment - leftover);
        let brake = ahead(braking, -deceleration, count);
        let bump = if leftover == 0 {
            Run::NONE
        } else {
            // The brake run's last velocity lies in segment `leftover` (its segment fell by one
            // every cycle), whose slope from the next velocity down is `leftover`. The leftover
            // buys exactly one unit: the next velocity is one unit above last − D, in segment
            // leftover − 1, or in segment leftover if that unit reaches the segment's start
            // (last's offset in its segment is D − 1).
            let last = braking - (count - 1) as i64 * deceleration;
            let offset = last as u64 - leftover * deceleration as u64;
            let segment = leftover - 1 + u64::from(offset + 1 == deceleration as u64);
            ahead(last - deceleration + 1, -deceleration, 1 + segment)
        };
        // The cycle that arrives (velocity zero) is the rest run's first.
        for run in [accelerate, cruise, brake, bump, Run::REST] {
            layout.push(run);
        }
        true
    }

    /// Appends the runs of [`landing::plan`] with the profile in force, from a state `distance`
    /// ahead (I32F32 bits, signed as the axis) moving at `velocity` (0 … V) in the frame of
    /// `sign` (the direction mask), and rest: `true`, or `false` (nothing appended) when no plan
    /// lands.
    fn push_landing(&self, layout: &mut Layout, distance: i64, velocity: i64, sign: i64) -> bool {
        let Profile {
            max_velocity,
            acceleration,
            deceleration,
            start_velocity,
        } = self.profile;
        let Some(runs) = landing::plan(
            i128::from(distance.unsigned_abs()),
            velocity,
            max_velocity,
            acceleration,
            deceleration,
            start_velocity,
        ) else {
            return false;
        };
        for (next, increment, count) in runs {
            layout.push(Run {
                next: (next ^ sign) - sign,
                increment: (increment ^ sign) - sign,
                count,
            });
        }
        layout.push(Run::REST);
        true
    }

    /// Lays out the runs of a plan that are not empty, from slot `at` when it is 0, or so that
    /// the last ends just before slot `at` (then the step after them goes to `at`), and makes
    /// the first the current run.
    fn set_runs(&mut self, at: usize, runs: &[Run]) {
        let mut slot = 0;
        for (to, run) in self.runs[..ELSEWHERE]
            .iter_mut()
            .zip(runs.iter().filter(|run| run.count != 0))
        {
            *to = run.replay();
            slot += 1;
        }
        let first = at.saturating_sub(slot);
        if first != 0 {
            self.runs.copy_within(0..slot, first);
        }
        self.runs[ELSEWHERE] = Replay::elsewhere();
        self.current = first;
    }

    /// The next step goes to [`Self::step_otherwise`].
    fn elsewhere(&mut self) {
        self.runs[ELSEWHERE] = Replay::elsewhere();
        self.current = ELSEWHERE;
    }

    /// Every cycle that is not a run of the plan: deciding from scratch, stopping.
    #[cold]
    #[inline(never)]
    fn step_otherwise(&mut self) -> State {
        self.settle();
        let velocity = self.state.velocity.to_bits();
        let next = match self.phase {
            // A plan's runs never lead here; if one did, deciding from scratch takes the same
            // velocity its run would.
            Phase::Run | Phase::Decide => {
                let (distance, sign) = self.ahead();
                let ahead = i128::from(distance) * i128::from(sign | 1);
                let next = (self.decide_ahead(ahead, (velocity ^ sign) - sign) ^ sign) - sign;
                self.state = self.state.advanced(I32F32::from_bits(next));
                self.plan();
                return self.state;
            }
            // A pending abrupt stop's cycle is a run (its slot is never ELSEWHERE).
            Phase::Stopped | Phase::AbruptPending { .. } => {
                self.stopped();
                0
            }
            Phase::Stopping => {
                let deceleration = self.profile.deceleration;
                let next = if velocity > 0 {
                    (velocity - deceleration).max(0)
                } else {
                    (velocity + deceleration).min(0)
                };
                if next == 0 {
                    self.stopped();
                } else {
                    self.elsewhere();
                }
                next
            }
        };
        let state = self.state.advanced(I32F32::from_bits(next));
        self.state = state;
        state
    }

    /// Stopped (the next cycle is at rest): the rest run, so those cycles take the common path.
    fn stopped(&mut self) {
        self.phase = Phase::Stopped;
        self.set_runs(0, &[Run::REST]);
    }
}

impl ProfileGenerator for Trapezoidal {
    #[inline]
    fn step(&mut self) -> State {
        // `% RUNS` is free (`current` < RUNS) and spares the bounds check.
        let current = self.current % RUNS;
        let (velocity, end) = self.runs[current].take();
        match end {
            End::No => {}
            // The run's last cycle: the next run is already laid out.
            End::Run => self.current = current + 1,
            End::Lap if current == ELSEWHERE => return self.step_otherwise(),
            End::Lap => self.runs[current].lap(),
        }
        advance(&mut self.state, I32F32::from_bits(velocity))
    }

    fn state(&self) -> State {
        self.state
    }

    fn is_complete(&self) -> bool {
        self.state.velocity == I32F32::ZERO
            && match self.phase() {
                Phase::Run | Phase::Decide => self.destination == self.state.position.to_bits(),
                Phase::Stopped => true,
                Phase::Stopping => self.current == self.rest_slot,
                Phase::AbruptPending { .. } => false,
            }
    }

    fn stop(&mut self, kind: StopKind) {
        self.settle();
        match (kind, self.phase) {
            (StopKind::Smooth, Phase::AbruptPending { .. }) | (StopKind::Abrupt, _) => {
                self.lay_out_abrupt(false);
            }
            (StopKind::Smooth, _) => {
                self.phase = Phase::Stopping;
                self.plan_stop();
            }
        }
    }

    /// Derived from the present state, not kept by stepping: the velocity before the last cycle
    /// is `velocity − acceleration` (SPEC §5).
    fn limits(&self) -> Limits {
        let before = self.state.velocity.to_bits() - self.state.acceleration.to_bits();
        // From rest the speed-up may include the jump to the starting velocity.
        let speed_up = if before == 0 {
            self.profile.acceleration + self.profile.start_velocity
        } else {
            self.profile.acceleration
        };
        // The cycle that arrives may drop to rest from up to the starting velocity (SPEC §7).
        let arrived = self.phase() == Phase::Run
            && self.state.velocity == I32F32::ZERO
            && self.destination == self.state.position.to_bits();
        let slow_down = if arrived {
            self.profile.deceleration.max(self.profile.start_velocity)
        } else {
            self.profile.deceleration
        };
        Limits {
            // A lowered maximum is reached by decelerating at D, from the velocity before.
            max_velocity: Some(I32F32::from_bits(
                self.profile.max_velocity.max(before.abs()),
            )),
            max_speed_up: Some(I32F32::from_bits(speed_up)),
            max_slow_down: Some(I32F32::from_bits(slow_down)),
            max_acceleration: None,
            max_jerk: None,
            exempt: self.last_abrupt() == Some(self.state),
        }
    }
}
