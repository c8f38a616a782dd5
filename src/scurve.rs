//! MC1451A seven-phase S-curve point-to-point (SPEC §8): jerk-limited, planned before the first
//! step, exact on arrival.
//!
//! # How the profile is built, and why it lands exactly
//!
//! A *triple box* `h·tb(a, b, c)` is the velocity profile `h · box(a) ∗ box(b) ∗ box(c)` (discrete
//! convolution of three runs of ones, `a ≤ b`, `c ≥ a + b`). Its jerk is `+h` for `a` cycles
//! (phase I), 0 for `b − a` (II), `−h` for `a` (III), 0 for `c − a − b` (IV, cruise), `−h`, 0,
//! `+h` (V–VII, the mirror image); its peak acceleration is `h·a`, its peak velocity `h·a·b`, and
//! the distance it covers is exactly `h·a·b·c` — all integers in units of 2^-32 counts.
//!
//! Profiles add, and so do their jerks: a sum of triple boxes whose heights add up to at most J
//! never jerks harder than J. The plan is therefore:
//!
//! 1. the **main move**: units of three kinds, `tb(a, b, c)`, `tb(a, b − 1, c)` and
//!    `tb(a − 1, b, c)`, mixed so that the peak acceleration is exactly the maximum (where the
//!    ramps reach it) and the peak velocity within a few units of the maximum velocity; a
//!    *velocity notch* (below) brings the cruise to the maximum velocity to the raw unit. Ending
//!    `e` units' cruise one cycle early (`c − 1`) takes `e·a·b` off the distance, so every
//!    multiple of `a·b` is reachable with the same seven phases;
//! 2. the **remainder** `E < a·b` (the main move is planned to overshoot by it) is taken out by
//!    *dips* in the cruise — small negative triple boxes placed one after another where the main
//!    move's jerk is zero, so each may use the whole jerk budget — or, where the cruise is too
//!    short for them (small jerks, moves that never cruise), by **notch pairs**.
//!
//! A *notch pair* of width `w` and span `k` lowers the acceleration by one unit for `w` cycles
//! and raises it by one unit for `w` cycles `k` cycles later: the velocity dips by at most
//! `min(w, k)` in between and is unchanged after, so the move keeps its length and its end and
//! covers exactly `w·k` less. Its jerk is ±1 on four single cycles, which fits wherever the main
//! move has one unit of jerk to spare — at the ends of the ramps (phase I ends on +J and III
//! begins on −J), and everywhere in phases of zero jerk — so notch pairs fit inside moves that
//! use the full jerk on every cycle. Two of them take any remainder: with spans in the intervals
//! the spare jerk allows, `w₁·k₁ + w₂·k₂ = E` is a linear Diophantine equation, solved exactly.
//!
//! Every plan is checked against the limits before it is used ([`within_limits`]: per run of
//! constant jerk the acceleration is linear and the velocity quadratic, so a few cycles per jerk
//! change decide it), and dips and notches only lower the velocity, so the velocity limit holds
//! and the position never moves backwards.
//!
//! The plan is a short list of jerk changes (cycle, amount); stepping adds the due changes to the
//! jerk, the jerk to the acceleration, the acceleration to the velocity and the velocity to the
//! position: four integer additions and a comparison per cycle. The sum of the profile is the
//! distance by construction, so the last state is exactly the destination with velocity and
//! acceleration zero.
//!
//! # Duration
//!
//! The planner searches shapes near the continuous-time optimum
//! ([`crate::reference::scurve_duration`]) and keeps the one with the fewest cycles; every move
//! takes at most 4 cycles over that optimum (asserted by the property tests over the whole
//! register ranges; over 240,000 random moves measured, the worst was +2.9 cycles). Planning
//! takes about 10 µs (9 µs on average over those moves, 0.4 ms at worst): shapes that cannot beat
//! the best plan so far are not built.
//!
//! The integer plan may keep a cycle or two of constant acceleration *below* the maximum (phases
//! II/VI) where the continuous optimum has none, and always keeps at least one cycle at zero
//! acceleration between phases III and V (the acceleration has to pass through zero within the
//! jerk limit); [`ScurvePlan::phases`] reports them as they are.

use fixed::types::I32F32;
use num_traits::Float;

use crate::format::mc1451a::{Destination, Jerk, MaxVelocity, ScurveAcceleration};
use crate::state::{Limits, ProfileGenerator, State, StopKind};
use crate::Error;
/// The parameters of an S-curve move, in MC1451A register formats.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct ScurveParameters {
    /// Destination, counts (±2³⁰).
    pub destination: Destination,
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
    /// Cycles in phases I–VII (II/VI are zero when the maximum acceleration is not reached, IV when
    /// the maximum velocity is not).
    pub phases: [u64; 7],
    /// Cycles from the first step to the last state (at the destination with velocity and
    /// acceleration zero), inclusive: the move is complete after this many steps.
    pub total: u64,
    /// The largest acceleration magnitude on any cycle of the move (speeding up or slowing
    /// down), I32F32 bits: exactly what stepping the move shows.
    pub peak_acceleration: i64,
    /// The largest velocity magnitude on any cycle of the move, I32F32 bits: exactly what
    /// stepping the move shows.
    pub peak_velocity: i64,
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
/// use profilegen::format::mc1451a::{Destination, Jerk, MaxVelocity, ScurveAcceleration};
/// use profilegen::{ProfileGenerator, SCurve, ScurveParameters};
///
/// // The datasheet's numbers: velocity 2.75, acceleration 0.175, jerk 0.0075.
/// let mut axis = SCurve::new(ScurveParameters {
///     destination: Destination::from_num(1_000.0)?,
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
#[derive(Debug, Clone)]
pub struct SCurve {
    parameters: ScurveParameters,
    limits: Limits64,
    schedule: Schedule,
    /// Index of the next jerk change due.
    next_change: usize,
    /// Cycles stepped since the move started.
    cycle: u64,
    /// +1 or −1: the direction of the move.
    direction: i64,
    /// Jerk, acceleration and velocity magnitudes along the direction, I32F32 bits.
    jerk: i64,
    acceleration: i64,
    velocity: i64,
    state: State,
    motion: Motion,
    last_was_abrupt: bool,
    /// After a stop the velocity register reads zero (SPEC §9).
    velocity_cleared: bool,
}

const REFUSED_IN_MOTION: &str = "while an S-curve move is in motion (MC1451A command error)";

fn check(parameters: &ScurveParameters) -> Result<Limits64, Error> {
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

impl SCurve {
    /// A generator at rest at position 0, with the move to `parameters.destination` planned; it
    /// starts on the first step.
    ///
    /// # Errors
    /// [`Error::Zero`] for a zero maximum velocity, maximum acceleration or jerk.
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
            parameters,
            limits,
            schedule: Schedule::EMPTY,
            next_change: 0,
            cycle: 0,
            direction: 1,
            jerk: 0,
            acceleration: 0,
            velocity: 0,
            state: State::at_rest(position),
            motion: Motion::Rest,
            last_was_abrupt: false,
            velocity_cleared: false,
        };
        generator.start_move();
        Ok(generator)
    }

    /// The plan of the present move (all zero when at rest with nothing to do).
    pub fn plan(&self) -> ScurvePlan {
        self.schedule.plan
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
    /// [`Error::Zero`] for a zero maximum velocity, acceleration or jerk.
    pub fn set_parameters(&mut self, parameters: ScurveParameters) -> Result<(), Error> {
        if self.motion != Motion::Rest {
            return Err(Error::Refused {
                parameter: "S-curve parameters",
                reason: REFUSED_IN_MOTION,
            });
        }
        self.limits = check(&parameters)?;
        self.parameters = parameters;
        self.velocity_cleared = false;
        self.start_move();
        Ok(())
    }

    /// A new destination, keeping the other parameters; as [`Self::set_parameters`].
    ///
    /// # Errors
    /// As [`Self::set_parameters`] (after a stop the velocity register is zero: set a velocity).
    pub fn set_destination(&mut self, destination: Destination) -> Result<(), Error> {
        self.set_parameters(ScurveParameters {
            destination,
            ..self.parameters()
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

    /// Plans the move from the present position (at rest) to the destination.
    fn start_move(&mut self) {
        let target = i64::from(self.parameters.destination.to_bits()) << 32;
        // The signed distance modulo the 32-bit position register: the short way round.
        let distance = target.wrapping_sub(self.state.position.to_bits());
        self.direction = if distance < 0 { -1 } else { 1 };
        self.next_change = 0;
        self.cycle = 0;
        self.jerk = 0;
        self.acceleration = 0;
        self.velocity = 0;
        if distance == 0 {
            self.schedule = Schedule::EMPTY;
            self.motion = Motion::Rest;
            return;
        }
        self.schedule = plan(u128::from(distance.unsigned_abs()), self.limits);
        self.motion = Motion::Planned;
    }

    /// The velocity (2^-32 units) still shed while raising a negative acceleration `-magnitude`
    /// to zero in jerk steps: `Σ (magnitude − k·J)` over the positive terms.
    fn velocity_to_level_off(&self, magnitude: i64) -> i128 {
        if magnitude <= 0 {
            return 0;
        }
        let jerk = self.limits.jerk as i128;
        let magnitude = i128::from(magnitude);
        let steps = (magnitude - 1) / jerk;
        steps * magnitude - jerk * steps * (steps + 1) / 2
    }

    /// One cycle of a smooth stop: the most negative acceleration (within the jerk and the
    /// maximum acceleration) from which the axis can still level off at velocity zero, found by
    /// bisection on a monotone condition. Up to three phases emerge: the acceleration falls to its
    /// floor, holds, and rises back to zero as the velocity reaches zero.
    fn stopping_acceleration(&self) -> i64 {
        let jerk = self.limits.jerk as i64;
        let floor = -(self.limits.acceleration as i64);
        let feasible = |next: i64| {
            let velocity = i128::from(self.velocity) + i128::from(next);
            velocity >= 0 && velocity >= self.velocity_to_level_off(-next)
        };
        let mut low = (self.acceleration - jerk).max(floor);
        let mut high = self.acceleration + jerk;
        if feasible(low) {
            return low;
        }
        // feasible(high) holds (see the module tests); find the smallest feasible value.
        while high - low > 1 {
            let middle = low + (high - low) / 2;
            if feasible(middle) {
                high = middle;
            } else {
                low = middle;
            }
        }
        high
    }
}

impl ProfileGenerator for SCurve {
    #[inline]
    fn step(&mut self) -> State {
        self.last_was_abrupt = false;
        match self.motion {
            Motion::Rest => {
                self.state = State::at_rest(self.state.position);
                return self.state;
            }
            Motion::Planned => {
                let changes = &self.schedule.changes[..self.schedule.count];
                while let Some(change) = changes
                    .get(self.next_change)
                    .filter(|c| c.cycle == self.cycle)
                {
                    self.jerk += change.amount;
                    self.next_change += 1;
                }
                self.acceleration += self.jerk;
                self.velocity += self.acceleration;
                self.cycle += 1;
                if self.cycle >= self.schedule.plan.total {
                    self.motion = Motion::Rest;
                }
            }
            Motion::Stopping => {
                let next = self.stopping_acceleration();
                self.acceleration = next;
                self.velocity += next;
                if self.velocity == 0 && self.acceleration == 0 {
                    self.motion = Motion::Rest;
                }
            }
            Motion::AbruptPending => {
                self.last_was_abrupt = true;
                self.acceleration = -self.velocity;
                self.velocity = 0;
                self.motion = Motion::Rest;
            }
        }
        self.state = self
            .state
            .advanced(I32F32::from_bits(self.direction * self.velocity));
        self.state
    }

    fn state(&self) -> State {
        self.state
    }

    fn is_complete(&self) -> bool {
        self.motion == Motion::Rest
    }

    fn stop(&mut self, kind: StopKind) {
        // Either stop clears the velocity register, moving or not (SPEC §9).
        self.velocity_cleared = true;
        self.motion = match (kind, self.motion) {
            (_, Motion::Rest) => Motion::Rest,
            (StopKind::Smooth, Motion::Planned | Motion::Stopping) => Motion::Stopping,
            _ => Motion::AbruptPending,
        };
    }

    fn limits(&self) -> Limits {
        let acceleration = Some(I32F32::from_bits(self.limits.acceleration as i64));
        Limits {
            max_velocity: Some(I32F32::from_bits(self.limits.velocity as i64)),
            max_speed_up: acceleration,
            max_slow_down: acceleration,
            max_acceleration: acceleration,
            max_jerk: Some(I32F32::from_bits(self.limits.jerk as i64)),
            exempt: self.last_was_abrupt,
        }
    }
}

// Planning: the search for the fastest shape, and the main move of each shape.

/// Plans a move of `distance` (> 0, 2^-32 counts) within the limits: shapes near the
/// continuous-time optimum first, the one with the fewest cycles wins.
fn plan(distance: u128, limits: Limits64) -> Schedule {
    let to_real = |bits: u64| bits as f64 / 4_294_967_296.0;
    // The continuous optimum only guides the search; every candidate is checked in integers.
    let (jerk_time, constant_time, _) = crate::reference::scurve_phases(
        distance as f64 / 4_294_967_296.0,
        to_real(limits.velocity),
        to_real(limits.acceleration),
        to_real(limits.jerk),
    );
    let a0 = (Float::round(jerk_time) as u64).max(1);
    let b0 = (Float::round(jerk_time + constant_time) as u64).max(a0);
    let mut best: Option<Schedule> = None;
    for a in [a0 + 1, a0, a0.saturating_sub(1)] {
        if a > 0 {
            let start = (b0 + 1).max(integer_ramp(distance, a, limits));
            scan_shapes(distance, a, start, limits, &mut best);
        }
    }
    // Polish: the neighbours of the best shape, larger ones included.
    if let Some((a1, b1)) = best
        .as_ref()
        .map(|s| (s.plan.phases[0], s.plan.phases[0] + s.plan.phases[1]))
    {
        for a in a1.saturating_sub(1).max(1)..=a1 + 1 {
            for b in b1.saturating_sub(2).max(a)..=b1 + 2 {
                if let Built::Plan(candidate) = try_shape(distance, a, b, limits, bound(&best)) {
                    keep_faster(&mut best, candidate);
                }
            }
        }
    }
    best.unwrap_or_else(|| {
        // Ramps of one cycle always fit: the height is at most min(J, A) < 2^31 while a move is at
        // least 2^32 units, so c ≥ 3 = a + b + 1, and with a·b = 1 the early units take the whole
        // overshoot (no dips). The empty plan is never reached.
        match try_shape(distance, 1, 1, limits, u64::MAX) {
            Built::Plan(schedule) => schedule,
            _ => Schedule::EMPTY,
        }
    })
}

/// The longest second ramp `b` worth trying with first ramps of `a` cycles: the integer plan's
/// peak acceleration `min(J·a, A)` can fall short of the maximum that the continuous optimum
/// uses (the ramps are whole cycles), so its ramps may need to be longer — up to where the peak
/// velocity reaches the maximum velocity, or the move needs no cruise.
fn integer_ramp(distance: u128, a: u64, limits: Limits64) -> u64 {
    let a_ = u128::from(a);
    let peak = (u128::from(limits.jerk) * a_).min(u128::from(limits.acceleration));
    let by_velocity = u128::from(limits.velocity) / peak + 1;
    let covers = |b: u128| peak * b * (a_ + b) >= distance;
    // b² + a·b ≥ distance/peak: a float guess, then exact steps.
    let guess =
        (-(a as f64) + Float::sqrt((a as f64).powi(2) + 4.0 * distance as f64 / peak as f64)) / 2.0;
    let mut b = (guess.max(1.0) as u128).min(by_velocity);
    while b < by_velocity && !covers(b) {
        b += 1;
    }
    while b > 1 && covers(b - 1) {
        b -= 1;
    }
    u64::try_from(b.min(by_velocity)).unwrap_or(u64::MAX).max(a)
}

/// The cycles a new plan must beat: the best plan's, if any.
fn bound(best: &Option<Schedule>) -> u64 {
    best.as_ref()
        .map_or(u64::MAX, |schedule| schedule.plan.total)
}

/// Keeps `candidate` if it takes fewer cycles than the best plan so far.
fn keep_faster(best: &mut Option<Schedule>, candidate: Schedule) {
    if best
        .as_ref()
        .is_none_or(|current| candidate.plan.total < current.plan.total)
    {
        *best = Some(candidate);
    }
}

/// How many shapes past the largest that fits [`scan_shapes`] also tries.
const NEIGHBOURS: u64 = 8;

/// Searches shapes from ramps `(a, start)` toward shorter ones — `b` down to `a`, then both
/// together — and keeps the plan with the fewest cycles. Shorter ramps lower the peak velocity and
/// so lengthen the cruise, which is where a remainder too large for a short cruise goes; whether a
/// shape fits is (nearly) monotone along that path, so: step down in doubling steps until one
/// fits, bisect back to the largest shape that fits, then try its neighbours.
fn scan_shapes(distance: u128, a: u64, start: u64, limits: Limits64, best: &mut Option<Schedule>) {
    let start = start.max(a);
    let last = (start - a) + (a - 1);
    // Position p along the path ↦ ramps.
    let shape = |p: u64| {
        if p <= start - a {
            (a, start - p)
        } else {
            let x = a - (p - (start - a));
            (x, x)
        }
    };
    let attempt = |p: u64, best: &mut Option<Schedule>| -> bool {
        let (a, b) = shape(p);
        match try_shape(distance, a, b, limits, bound(best)) {
            Built::Plan(candidate) => {
                keep_faster(best, candidate);
                true
            }
            Built::Slower => true,
            Built::Unfit => false,
        }
    };
    // Doubling steps from the start until a shape fits.
    let mut fails = None;
    let mut p = 0u64;
    let mut step = 1u64;
    let mut good = loop {
        if attempt(p, best) {
            break p;
        }
        fails = Some(p);
        if p == last {
            return;
        }
        p = (p + step).min(last);
        step = step.saturating_mul(2);
    };
    // Bisect between the last shape that failed and the first that fits.
    while let Some(bad) = fails.filter(|&bad| good - bad > 1) {
        let middle = bad + (good - bad) / 2;
        if attempt(middle, best) {
            good = middle;
        } else {
            fails = Some(middle);
        }
    }
    // Neighbours: divisibility makes fitting not quite monotone, and the fastest may be nearby.
    for p in good + 1..=(good + NEIGHBOURS).min(last) {
        attempt(p, best);
    }
}

/// How many counts of third-kind units [`try_shape`] tries when lowering the peak velocity.
const LOWERING_TRIES: u128 = 48;

/// The main move's kinds of unit: `(ramp a, ramp b, area a·b)`; see [`try_shape`].
type Kinds = [(u64, u64, u128); 3];

/// Tries one shape of the main move, ramps `a ≤ b`: its fastest plan, or [`Built::Slower`] if
/// it cannot take fewer than `bound` cycles, or [`Built::Unfit`] if the distance is too short for
/// it, its peak velocity cannot be brought within the maximum, or the remainder does not fit.
///
/// The main move is a sum of triple boxes whose heights add up to `h` (the jerk of phase I):
/// `h₀·tb(a, b, ·) + h₁·tb(a, b−1, ·) + h₂·tb(a−1, b, ·)`. Each unit moved from the first kind to
/// the second lowers the peak velocity by `a`, to the third by `b` and the peak acceleration by
/// one, so the peak acceleration comes to the maximum exactly (`h` is chosen so that `h·a`
/// reaches it), and the peak velocity within a few units of the maximum velocity — or, with a
/// *velocity notch* (a notch pair of width `w` ending with phase II and with phase VI, see
/// [`push_notch_pair`]), exactly to it: `w` takes the last units off the whole cruise. Both
/// are tried; the faster is kept. Each kind then ends its cruise on cycle `c` or, for `eᵢ` of its
/// units, one cycle early, which takes `eᵢ·aᵢ·bᵢ` off the distance; what is left (less than
/// `a·b`) goes to dips in the cruise or to notch pairs.
fn try_shape(distance: u128, a: u64, b: u64, limits: Limits64, bound: u64) -> Built {
    let (a_, b_) = (u128::from(a), u128::from(b));
    let acceleration_limit = u128::from(limits.acceleration);
    // The jerk of phase I: as much as the jerk limit allows, and enough that `h·a` reaches the
    // maximum acceleration — units of the third kind (one cycle shorter ramp) then lower the peak
    // acceleration to it exactly, one unit each, where `⌊A/a⌋·a` could fall short by up to `a`
    // units (and the move lose time in proportion on a long constant-acceleration phase).
    let h = u128::from(limits.jerk).min(acceleration_limit.div_ceil(a_));
    if h == 0 {
        return Built::Unfit;
    }
    let kinds: Kinds = [
        (a, b, a_ * b_),
        (a, b.saturating_sub(1), a_ * (b_ - 1)),
        (a.saturating_sub(1), b, (a_ - 1) * b_),
    ];
    let usable = |kind: usize| kinds[kind].0 > 0 && kinds[kind].1 > 0;
    let velocity_limit = u128::from(limits.velocity);
    let acceleration_over = (h * a_).saturating_sub(acceleration_limit);
    let over = (h * a_ * b_).saturating_sub(velocity_limit);
    // Lowerings `h₁·a + h₂·b` with at least `acceleration_over` units of the third kind: the
    // least one that brings the peak velocity within the limit, and the greatest one that does
    // not go below it (the velocity notch takes the rest).
    let mut at_least: Option<(u128, u128, u128)> = None;
    let mut at_most: Option<(u128, u128, u128)> = None;
    // Units of the third kind lower more each (b ≥ a), so a large `over` needs at least
    // `(over − h·a)/(b − a)` of them. A few dozen counts of them are tried: the lowering comes
    // within `a` of `over` with any of them, and the velocity notch takes the rest exactly.
    let fewest = match (over.checked_sub(h * a_), b_ - a_) {
        (Some(excess), spread) if spread > 0 => excess.div_ceil(spread),
        _ => 0,
    };
    // (One fewer can still give the greatest lowering below `over`.)
    let least_h2 = acceleration_over.max(fewest.saturating_sub(1));
    let tries = if over == 0 { 0 } else { LOWERING_TRIES };
    for h2 in least_h2..=h.min(least_h2 + tries) {
        if h2 > 0 && !usable(2) {
            break;
        }
        let rest = over.saturating_sub(h2 * b_);
        // Just enough of the second kind, just too few, and as many as there are units left.
        for h1 in [rest / a_, rest.div_ceil(a_), (rest / a_).min(h - h2)] {
            if (h1 > 0 && !usable(1)) || h1 + h2 > h {
                continue;
            }
            let lowered = h1 * a_ + h2 * b_;
            if lowered >= over && at_least.is_none_or(|(least, _, _)| lowered < least) {
                at_least = Some((lowered, h1, h2));
            }
            if lowered <= over && at_most.is_none_or(|(most, _, _)| lowered > most) {
                at_most = Some((lowered, h1, h2));
            }
        }
    }
    let heights_of = |(_, h1, h2): (u128, u128, u128)| [h - h1 - h2, h1, h2];
    let mut built = Built::Unfit;
    match at_least {
        Some(choice) => {
            built = built.or(build_shape(
                distance,
                kinds,
                heights_of(choice),
                0,
                limits,
                bound,
            ));
        }
        None => {
            // The other kinds cannot lower it enough (tiny ramps): a lower jerk height instead.
            let h = h
                .min(acceleration_limit / a_)
                .min(velocity_limit / (a_ * b_));
            if h > 0 {
                built = built.or(build_shape(distance, kinds, [h, 0, 0], 0, limits, bound));
            }
        }
    }
    if let Some(choice @ (lowered, _, _)) = at_most {
        let notch = u64::try_from(over - lowered).unwrap_or(u64::MAX);
        if notch > 0 && notch <= b {
            let bound = match &built {
                Built::Plan(schedule) => schedule.plan.total,
                _ => bound,
            };
            built = built.or(build_shape(
                distance,
                kinds,
                heights_of(choice),
                notch,
                limits,
                bound,
            ));
        }
    }
    built
}

/// What came of one shape: a plan, a plan that could not be faster than `bound` (so was not
/// built), or none (the shape is too large for the distance, or the remainder fits nowhere).
// The plan is held inline: the library does not allocate, and an outcome is moved only a few
// times per shape tried.
#[allow(clippy::large_enum_variant)]
#[derive(Debug, Clone, Copy)]
enum Built {
    Plan(Schedule),
    Slower,
    Unfit,
}

impl Built {
    /// The better of two outcomes: the faster plan, else `Slower`, else `Unfit`.
    fn or(self, other: Built) -> Built {
        match (self, other) {
            (Built::Plan(mine), Built::Plan(theirs)) => {
                if theirs.plan.total < mine.plan.total {
                    Built::Plan(theirs)
                } else {
                    Built::Plan(mine)
                }
            }
            (Built::Plan(plan), _) | (_, Built::Plan(plan)) => Built::Plan(plan),
            (Built::Slower, _) | (_, Built::Slower) => Built::Slower,
            _ => Built::Unfit,
        }
    }
}

/// Builds the main move of `heights` units of `kinds`, with a velocity notch of `notch` units
/// (0: none), and takes the remainder off; see [`try_shape`]. Every plan it returns has been
/// checked against the limits on every cycle ([`within_limits`]).
fn build_shape(
    distance: u128,
    kinds: Kinds,
    heights: [u128; 3],
    notch: u64,
    limits: Limits64,
    bound: u64,
) -> Built {
    let (a, b, _) = kinds[0];
    let peak_velocity: u128 = (0..3).map(|k| heights[k] * kinds[k].2).sum();
    // The velocity notch runs from cycle b − w to b (the end of phase II, or of I without a
    // phase II) and from c + b − w to c + b (the end of VI or V): it lowers the
    // whole cruise by w and takes w·c off the distance.
    let Some(cruise_velocity) = peak_velocity
        .checked_sub(u128::from(notch))
        .filter(|&v| v > 0)
    else {
        return Built::Unfit;
    };
    // Overshoot with whole cycles of cruise, then take off eᵢ·areaᵢ by ending eᵢ units early
    // (one unit fewer where what is left is too small for the notch pairs), and the rest with
    // dips or notch pairs.
    let Ok(shortest) = u64::try_from(distance.div_ceil(cruise_velocity)) else {
        return Built::Unfit;
    };
    if shortest < a + b + 1 {
        return Built::Unfit;
    }
    if a + b + shortest >= bound {
        return Built::Slower;
    }
    // A cycle more of cruise where the remainder of the shortest fits nowhere: it is then at
    // least a whole cruise cycle's worth, which notch pairs can always take.
    (shortest..=shortest + 1)
        .find_map(|c| {
            build_with_cruise(distance, kinds, heights, notch, cruise_velocity, c, limits)
        })
        .map_or(Built::Unfit, Built::Plan)
}

/// [`build_shape`] with the deceleration starting on cycle `c`, the cruise at `cruise_velocity`
/// (the main move's peak less the velocity notch).
fn build_with_cruise(
    distance: u128,
    kinds: Kinds,
    heights: [u128; 3],
    notch: u64,
    cruise_velocity: u128,
    c: u64,
    limits: Limits64,
) -> Option<Schedule> {
    let (a, b, _) = kinds[0];
    let total = a + b + c;
    let over = u128::from(c) * cruise_velocity - distance;
    let mut early = [0u128; 3];
    let mut left = over;
    for k in 0..3 {
        if let Some(units) = left.checked_div(kinds[k].2) {
            early[k] = heights[k].min(units);
            left -= early[k] * kinds[k].2;
        }
    }
    let main_move = |early: [u128; 3]| -> Option<Schedule> {
        let mut schedule = Schedule::EMPTY;
        for k in 0..3 {
            let (ka, kb, _) = kinds[k];
            let full = (heights[k] - early[k]) as i64;
            let short = early[k] as i64;
            if (full != 0 || short != 0)
                && !(schedule.push_triple_box(0, full, ka, kb, c)
                    && schedule.push_triple_box(0, short, ka, kb, c - 1))
            {
                return None;
            }
        }
        if notch > 0 && !push_notch_pair(&mut schedule, b - notch, notch, c) {
            return None;
        }
        schedule.sort();
        Some(schedule)
    };
    let cruise_velocity_bits = u64::try_from(cruise_velocity).ok()?;
    let finish = |mut schedule: Schedule| -> Option<Schedule> {
        schedule.sort();
        let peaks = peaks_within_limits(&schedule, total, limits)?;
        schedule.plan = ScurvePlan {
            phases: [a, b - a, a, c - a - b, a, b - a, a],
            total,
            peak_acceleration: peaks.acceleration as i64,
            peak_velocity: peaks.velocity as i64,
        };
        Some(schedule)
    };
    let schedule = main_move(early)?;
    // Dips in the cruise first: they fit by construction when the cruise is long enough.
    let mut dipped = schedule;
    if fill_dips(
        &mut dipped,
        left,
        a + b,
        c - 1,
        limits,
        cruise_velocity_bits,
    ) {
        if let Some(plan) = finish(dipped) {
            return Some(plan);
        }
    }
    // Notch pairs, with what is left or, if that fails, with one early unit fewer (a notch pair
    // takes at least about the distance between the ramps, so a small remainder may need more).
    let mut notched = schedule;
    if notch_pairs(&mut notched, left, total, limits) {
        if let Some(plan) = finish(notched) {
            return Some(plan);
        }
    }
    let k = (0..3).rev().find(|&k| early[k] > 0)?;
    let mut fewer_early = early;
    fewer_early[k] -= 1;
    let mut notched = main_move(fewer_early)?;
    if notch_pairs(&mut notched, left + kinds[k].2, total, limits) {
        return finish(notched);
    }
    None
}

// The schedule of jerk changes, and the closed-form check of a plan against the limits.

/// A jerk change: on cycle `cycle` (0 = the first step) the jerk changes by `amount` (2^-32
/// counts/cycle³).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
struct JerkChange {
    cycle: u64,
    amount: i64,
}

/// At most this many jerk changes: 48 for the main move, 8 for each notch pair and each dip.
const MAX_CHANGES: usize = 128;

/// The exact limits in I32F32 bits.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
struct Limits64 {
    jerk: u64,
    acceleration: u64,
    velocity: u64,
}

/// A plan under construction or in force: the sorted jerk changes and the summary.
#[derive(Debug, Clone, Copy)]
struct Schedule {
    changes: [JerkChange; MAX_CHANGES],
    count: usize,
    plan: ScurvePlan,
}

impl Schedule {
    const EMPTY: Self = Self {
        changes: [JerkChange {
            cycle: 0,
            amount: 0,
        }; MAX_CHANGES],
        count: 0,
        plan: ScurvePlan {
            phases: [0; 7],
            total: 0,
            peak_acceleration: 0,
            peak_velocity: 0,
        },
    };

    fn push(&mut self, cycle: u64, amount: i64) -> bool {
        if amount == 0 {
            return true;
        }
        if self.count == MAX_CHANGES {
            return false;
        }
        self.changes[self.count] = JerkChange { cycle, amount };
        self.count += 1;
        true
    }

    /// Adds `height · tb(a, b, c)` starting on cycle `start`; see the module docs.
    fn push_triple_box(&mut self, start: u64, height: i64, a: u64, b: u64, c: u64) -> bool {
        let s = start;
        self.push(s, height)
            && self.push(s + c, -height)
            && self.push(s + a, -height)
            && self.push(s + a + c, height)
            && self.push(s + b, -height)
            && self.push(s + b + c, height)
            && self.push(s + a + b, height)
            && self.push(s + a + b + c, -height)
    }

    fn sort(&mut self) {
        // Insertion sort: at most 96 entries, once per plan, no allocation.
        for i in 1..self.count {
            let mut k = i;
            while k > 0 && self.changes[k - 1].cycle > self.changes[k].cycle {
                self.changes.swap(k - 1, k);
                k -= 1;
            }
        }
    }
}

/// The jerk runs of a sorted schedule over cycles `0 .. total`: `visit(start, end, jerk)` for
/// each run of constant jerk, in order.
fn jerk_runs(
    schedule: &Schedule,
    total: u64,
    mut visit: impl FnMut(u64, u64, i64) -> bool,
) -> bool {
    let changes = &schedule.changes[..schedule.count];
    let (mut jerk, mut at, mut next) = (0i64, 0u64, 0usize);
    while at < total {
        while let Some(change) = changes.get(next).filter(|c| c.cycle <= at) {
            jerk += change.amount;
            next += 1;
        }
        let end = changes.get(next).map_or(total, |c| c.cycle.min(total));
        if !visit(at, end, jerk) {
            return false;
        }
        at = end;
    }
    true
}

/// `⌊n / d⌋` for `d ≠ 0`.
fn floor_div(n: i128, d: i128) -> i128 {
    let q = n / d;
    if (n % d != 0) && ((n < 0) != (d < 0)) {
        q - 1
    } else {
        q
    }
}

/// The largest acceleration magnitude and the largest velocity of a move, I32F32 bits.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
struct Peaks {
    acceleration: u64,
    velocity: u64,
}

/// The peaks of a sorted schedule of `total` cycles, if every cycle keeps |jerk| ≤ J,
/// |acceleration| ≤ A and 0 ≤ velocity ≤ V and the move ends at rest; `None` otherwise. Checked
/// per run of constant jerk in closed form — on a run the acceleration is linear and the
/// velocity quadratic, so the ends of the run and the velocity's turning point are the only
/// cycles that can break a limit or set a peak — which makes the check cost per jerk change, not
/// per cycle.
fn peaks_within_limits(schedule: &Schedule, total: u64, limits: Limits64) -> Option<Peaks> {
    let (j_max, a_max, v_max) = (
        i128::from(limits.jerk),
        i128::from(limits.acceleration),
        i128::from(limits.velocity),
    );
    let (mut acceleration, mut velocity) = (0i128, 0i128);
    let (mut peak_acceleration, mut peak_velocity) = (0i128, 0i128);
    let fits = jerk_runs(schedule, total, |start, end, jerk| {
        let (jerk, cycles) = (i128::from(jerk), i128::from(end - start));
        // After m cycles of the run (1 ≤ m ≤ cycles).
        let acceleration_after = |m: i128| acceleration + jerk * m;
        let velocity_after = |m: i128| velocity + acceleration * m + jerk * m * (m + 1) / 2;
        let steepest = acceleration_after(1)
            .abs()
            .max(acceleration_after(cycles).abs());
        if jerk.abs() > j_max || steepest > a_max {
            return false;
        }
        // The turning point of the velocity: m* = −acceleration/jerk − ½.
        let turn = if jerk == 0 {
            1
        } else {
            floor_div(-2 * acceleration - jerk, 2 * jerk)
        };
        let mut fastest = 0;
        for m in [1, cycles, turn, turn + 1] {
            if (1..=cycles).contains(&m) {
                let v = velocity_after(m);
                if !(0..=v_max).contains(&v) {
                    return false;
                }
                fastest = fastest.max(v);
            }
        }
        peak_acceleration = peak_acceleration.max(steepest);
        peak_velocity = peak_velocity.max(fastest);
        let (next_acceleration, next_velocity) =
            (acceleration_after(cycles), velocity_after(cycles));
        acceleration = next_acceleration;
        velocity = next_velocity;
        true
    });
    (fits && acceleration == 0 && velocity == 0).then_some(Peaks {
        // Within the limits, so within u64.
        acceleration: peak_acceleration as u64,
        velocity: peak_velocity as u64,
    })
}

/// Whether a sorted schedule of `total` cycles stays within the limits; see
/// [`peaks_within_limits`].
fn within_limits(schedule: &Schedule, total: u64, limits: Limits64) -> bool {
    peaks_within_limits(schedule, total, limits).is_some()
}

// Cruise dips: the remainder taken out of the cruise.

/// Takes `remainder` (2^-32 counts) out of the cruise `[start, end)` with dips, one after
/// another; `false` if they do not fit. Each dip is `g·tb(k, k, z)` (z ≥ 2k, taking `g·k²·z`),
/// sized to leave a remainder the following, smaller dips can take in the room left; the last
/// units go as a run of −1 in velocity (`tb(1; 1, 1, r)`, r ≥ 2, jerking by at most 1). No dip
/// leaves exactly 1, which nothing can take.
fn fill_dips(
    schedule: &mut Schedule,
    remainder: u128,
    start: u64,
    end: u64,
    limits: Limits64,
    cruise_velocity: u64,
) -> bool {
    let mut left = remainder;
    let mut at = start;
    while left > 0 {
        let room = end.saturating_sub(at);
        if let Some(length) = even_dip_length(left, room, limits, cruise_velocity) {
            return schedule.push_even_dip(at, left, length);
        }
        if left >= 2 && left + 3 <= u128::from(room) && cruise_velocity >= 1 {
            return schedule.push_triple_box(at, -1, 1, 1, left as u64);
        }
        let Some((height, side, length)) = next_dip(left, room, limits, cruise_velocity) else {
            return false;
        };
        if !schedule.push_triple_box(at, -(height as i64), side, side, length) {
            return false;
        }
        left -= u128::from(height) * u128::from(side) * u128::from(side) * u128::from(length);
        at += 2 * side + length;
    }
    true
}

/// The longest an even dip may be: each cycle is one jerk change.
const EVEN_DIP_CYCLES: u64 = 16;

/// The length (1 … 16 cycles) of an *even dip* taking `left` within `room`, if one fits: a dip
/// of `q` or `q + 1` on each cycle (Bresenham-spread), whose jerk is at most `q + 2` — so it needs
/// `q + 2 ≤ J`, `q + 1` within the maximum acceleration and the cruise velocity. A one-cycle dip
/// jerks by `2·left`.
fn even_dip_length(left: u128, room: u64, limits: Limits64, cruise_velocity: u64) -> Option<u64> {
    let height_cap = u128::from(limits.jerk.saturating_sub(2))
        .min(u128::from(limits.acceleration.saturating_sub(1)))
        .min(u128::from(cruise_velocity.saturating_sub(1)));
    // One cycle: the jerk goes −E, +2E, −E.
    let single_cap = u128::from(limits.jerk / 2)
        .min(u128::from(limits.acceleration))
        .min(u128::from(cruise_velocity));
    if left <= single_cap && room >= 3 {
        return Some(1);
    }
    if height_cap == 0 {
        return None;
    }
    let length = left.div_ceil(height_cap).max(2);
    (length <= u128::from(EVEN_DIP_CYCLES) && length + 2 <= u128::from(room))
        .then_some(length as u64)
}

impl Schedule {
    /// Adds a dip of `amount` spread evenly over `length` cycles from `start`: the velocity is
    /// lowered by `⌊(k+1)·amount/length⌋ − ⌊k·amount/length⌋` on cycle k. The jerk changes are the
    /// third differences of that sequence (zero outside it).
    fn push_even_dip(&mut self, start: u64, amount: u128, length: u64) -> bool {
        let depth = |k: i64| -> i128 {
            if k < 0 || k >= length as i64 {
                return 0;
            }
            let (k, n) = (k as u128, u128::from(length));
            -(((k + 1) * amount / n) as i128 - (k * amount / n) as i128)
        };
        let jerk = |k: i64| depth(k) - 2 * depth(k - 1) + depth(k - 2);
        (0..length as i64 + 3).all(|k| self.push(start + k as u64, (jerk(k) - jerk(k - 1)) as i64))
    }
}

/// Room (cycles) that dips need for `left` at height up to `height`: about `3·(left/height)^⅓`
/// for the first, plus the smaller ones after it (an estimate to compare dip sizes by).
fn room_estimate(left: u128, height: u64) -> u64 {
    if left == 0 {
        return 0;
    }
    let per = (left / u128::from(height.max(1))).max(1);
    let cube_root = integer_cube_root(per);
    4 * cube_root + 6
}

fn integer_cube_root(value: u128) -> u64 {
    // Float guess, then exact correction: planning only, never per cycle.
    let mut root = Float::cbrt(value as f64) as u64;
    while u128::from(root + 1).pow(3) <= value {
        root += 1;
    }
    while root > 0 && u128::from(root).pow(3) > value {
        root -= 1;
    }
    root
}

/// The next dip `(g, k, z)` for `left` in `room` cycles: among sides k (powers of two and the
/// cube-root size) the one whose own room plus the estimated room of what it leaves is least.
fn next_dip(
    left: u128,
    room: u64,
    limits: Limits64,
    cruise_velocity: u64,
) -> Option<(u64, u64, u64)> {
    let height_cap = limits.jerk.min(limits.acceleration);
    let guess = integer_cube_root(left / u128::from(height_cap.max(1))).max(1);
    let mut best: Option<(u64, (u64, u64, u64))> = None;
    let candidates = (0..40).map(|shift| 1u64 << shift).chain([
        guess,
        guess + 1,
        guess.saturating_sub(1).max(1),
    ]);
    for k in candidates {
        if 4 * k > room {
            continue;
        }
        let k2 = u128::from(k) * u128::from(k);
        let height = u128::from(height_cap)
            .min(u128::from(limits.acceleration) / u128::from(k))
            .min(u128::from(cruise_velocity) / k2);
        if height == 0 {
            continue;
        }
        let longest = u128::from(room - 2 * k);
        // As long as fits and takes no more than is left (z ≥ 2k).
        let mut z = (left / (height * k2)).min(longest);
        let mut g = height;
        if z < u128::from(2 * k) {
            // Too little left for this side at full height: a lower dip of the shortest length.
            z = u128::from(2 * k);
            g = left / (k2 * z);
            if g == 0 {
                continue;
            }
        }
        let mut taken = g * k2 * z;
        if left - taken == 1 {
            if z > u128::from(2 * k) {
                z -= 1;
            } else if g > 1 {
                g -= 1;
            } else {
                continue;
            }
            taken = g * k2 * z;
        }
        let used = 2 * k + z as u64;
        let cost = used + room_estimate(left - taken, height_cap);
        if best.is_none_or(|(least, _)| cost < least) {
            best = Some((cost, (g as u64, k, z as u64)));
        }
    }
    best.map(|(_, shape)| shape)
}

// Notch pairs: the remainder taken out inside the ramps.

/// A *notch pair* takes `width · span` off a move without changing its length or its end: the
/// acceleration is lowered by one unit for `width` cycles from `start` and raised by one unit for
/// `width` cycles from `start + span`, i.e. the jerk changes by −1, +1 at `start`,
/// `start + width` and by +1, −1 at `start + span`, `start + span + width`. The velocity dips
/// by at most `min(width, span)` in between and is unchanged outside.
///
/// It needs one unit of jerk to spare in the right direction at its four corners — which the
/// ramps have at their ends (phase I ends on +J followed by −J) and every phase of zero jerk has
/// everywhere — so it fits where cruise dips cannot: inside the ramps of a move with no cruise.
fn push_notch_pair(schedule: &mut Schedule, start: u64, width: u64, span: u64) -> bool {
    // The schedule holds changes of the jerk: a jerk of `amount` on one cycle only is a change
    // by `amount` on it and back on the next.
    let mut impulse =
        |cycle: u64, amount: i64| schedule.push(cycle, amount) && schedule.push(cycle + 1, -amount);
    impulse(start, -1)
        && impulse(start + width, 1)
        && impulse(start + span, 1)
        && impulse(start + span + width, -1)
}

/// At most this many runs of cycles in a [`Runs`]: the runs where a notch can go number a few
/// per phase; beyond this many the rest are left out (fewer places to try, never a wrong one).
const MAX_RUNS: usize = 24;

/// Runs of cycles `[start, end)`, sorted and disjoint, in a fixed-capacity array.
#[derive(Debug, Clone, Copy)]
struct Runs {
    runs: [(u64, u64); MAX_RUNS],
    count: usize,
}

impl Runs {
    const EMPTY: Self = Self {
        runs: [(0, 0); MAX_RUNS],
        count: 0,
    };

    /// Appends `[start, end)` (after every run so far), merging it with a run it touches.
    fn push(&mut self, start: u64, end: u64) {
        if start >= end {
            return;
        }
        if let Some(last) = self.count.checked_sub(1).map(|i| &mut self.runs[i]) {
            if last.1 == start {
                last.1 = end;
                return;
            }
        }
        if self.count < MAX_RUNS {
            self.runs[self.count] = (start, end);
            self.count += 1;
        }
    }

    fn as_slice(&self) -> &[(u64, u64)] {
        &self.runs[..self.count]
    }

    /// The cycles `n` of `self` with `n + shift` in `other`.
    fn meet_shifted(&self, other: &Runs, shift: u64) -> Runs {
        let mut met = Runs::EMPTY;
        let (mut i, mut k) = (0, 0);
        let (mine, theirs) = (self.as_slice(), other.as_slice());
        while i < mine.len() && k < theirs.len() {
            let (a_start, a_end) = mine[i];
            let (b_start, b_end) = (
                theirs[k].0.saturating_sub(shift),
                theirs[k].1.saturating_sub(shift),
            );
            met.push(a_start.max(b_start), a_end.min(b_end));
            if a_end < b_end {
                i += 1;
            } else {
                k += 1;
            }
        }
        met
    }
}

/// Where one notch pair of some width can go: the cycles its first notch can start on, those
/// its second can, and the spans (second start − first start) that allows.
#[derive(Debug, Clone, Copy)]
struct NotchRoom {
    firsts: (u64, u64),
    seconds: (u64, u64),
    spans: (u64, u64),
}

/// The cycles of a planned move on which its jerk can be lowered by one unit (`lower`) and
/// raised by one unit (`raise`) within the jerk limit.
struct Slack {
    lower: Runs,
    raise: Runs,
}

impl Slack {
    fn of(schedule: &Schedule, total: u64, limits: Limits64) -> Self {
        let jerk_limit = limits.jerk as i64;
        let mut slack = Self {
            lower: Runs::EMPTY,
            raise: Runs::EMPTY,
        };
        jerk_runs(schedule, total, |start, end, jerk| {
            if jerk > -jerk_limit {
                slack.lower.push(start, end);
            }
            if jerk < jerk_limit {
                slack.raise.push(start, end);
            }
            true
        });
        slack
    }

    /// Whether `found` holds for some room of a notch pair of `width` (it stops at the first).
    fn any_room(&self, width: u64, mut found: impl FnMut(NotchRoom) -> bool) -> bool {
        // The first notch lowers the jerk on its first cycle and raises it on the cycle `width`
        // later; the second raises, then lowers.
        let firsts = self.lower.meet_shifted(&self.raise, width);
        let seconds = self.raise.meet_shifted(&self.lower, width);
        for &first in firsts.as_slice() {
            for &second in seconds.as_slice() {
                if second.1 <= first.0 + 1 {
                    continue;
                }
                let shortest = second.0.saturating_sub(first.1 - 1).max(1);
                let longest = (second.1 - 1) - first.0;
                let room = NotchRoom {
                    firsts: first,
                    seconds: second,
                    spans: (shortest, longest),
                };
                if shortest <= longest && found(room) {
                    return true;
                }
            }
        }
        false
    }
}

/// Places a notch pair of `width` and `span` in `room`, keeping it if the whole schedule stays
/// within the limits ([`within_limits`]).
fn place_notch_pair(
    schedule: &mut Schedule,
    room: NotchRoom,
    width: u64,
    span: u64,
    total: u64,
    limits: Limits64,
) -> bool {
    let (first, second) = (room.firsts, room.seconds);
    let low = first.0.max(second.0.saturating_sub(span));
    let high = (first.1 - 1).min((second.1 - 1).saturating_sub(span));
    if low > high {
        return false;
    }
    // The middle first (away from the slow ends of the move), then either end.
    for start in [low + (high - low) / 2, high, low] {
        let mut candidate = *schedule;
        if push_notch_pair(&mut candidate, start, width, span) {
            candidate.sort();
            if within_limits(&candidate, total, limits) {
                *schedule = candidate;
                return true;
            }
        }
    }
    false
}

/// The modular inverse of `value` modulo `modulus` (coprime, modulus ≥ 1).
fn inverse_mod(value: i128, modulus: i128) -> i128 {
    let (mut old_r, mut r) = (value.rem_euclid(modulus), modulus);
    let (mut old_s, mut s) = (1i128, 0i128);
    while r != 0 {
        let q = old_r / r;
        (old_r, r) = (r, old_r - q * r);
        (old_s, s) = (s, old_s - q * s);
    }
    old_s.rem_euclid(modulus)
}

/// A solution of `w₁·k₁ + w₂·k₂ = left` with `k₁` and `k₂` in their (inclusive) ranges — the
/// middle one of the solutions there.
fn solve_two(
    left: u128,
    (w1, w2): (u64, u64),
    range1: (u64, u64),
    range2: (u64, u64),
) -> Option<(u64, u64)> {
    let (w1, w2, left) = (i128::from(w1), i128::from(w2), i128::try_from(left).ok()?);
    let g = {
        let (mut x, mut y) = (w1, w2);
        while y != 0 {
            (x, y) = (y, x % y);
        }
        x
    };
    if left % g != 0 {
        return None;
    }
    let (a, b, e) = (w1 / g, w2 / g, left / g);
    // k₁ ≡ e·a⁻¹ (mod b); then k₁ = k₁₀ + t·b, k₂ = k₂₀ − t·a for integer t.
    let k1_0 = (e % b) * inverse_mod(a, b) % b;
    let k2_0 = (e - a * k1_0) / b;
    let (l1, u1) = (i128::from(range1.0), i128::from(range1.1));
    let (l2, u2) = (i128::from(range2.0), i128::from(range2.1));
    let t_low = floor_div(l1 - k1_0 + b - 1, b).max(floor_div(k2_0 - u2 + a - 1, a));
    let t_high = floor_div(u1 - k1_0, b).min(floor_div(k2_0 - l2, a));
    if t_low > t_high {
        return None;
    }
    let t = t_low + (t_high - t_low) / 2;
    Some((
        u64::try_from(k1_0 + t * b).ok()?,
        u64::try_from(k2_0 - t * a).ok()?,
    ))
}

/// Takes exactly `left` off a sorted schedule of `total` cycles with one or two notch pairs, each
/// checked against the limits; `false` (and the schedule unchanged) if none fits.
///
/// A pair takes `width · span`, its spans ranging over intervals (the distances between places
/// with jerk to spare); with two pairs of widths `w₁, w₂`, `w₁·k₁ + w₂·k₂ = left` is a linear
/// Diophantine equation solved exactly over those intervals.
fn notch_pairs(schedule: &mut Schedule, left: u128, total: u64, limits: Limits64) -> bool {
    if left == 0 {
        return true;
    }
    let slack = Slack::of(schedule, total, limits);
    // One pair: a width dividing what is left (spans are shorter than the move).
    let narrowest = u64::try_from(left / u128::from(total.max(1)))
        .unwrap_or(u64::MAX)
        .max(1);
    for width in narrowest..narrowest.saturating_add(64) {
        let Ok(span) = u64::try_from(left / u128::from(width)) else {
            continue;
        };
        if left % u128::from(width) == 0
            && slack.any_room(width, |room| {
                (room.spans.0..=room.spans.1).contains(&span)
                    && place_notch_pair(schedule, room, width, span, total, limits)
            })
        {
            return true;
        }
    }
    // Two pairs. Their spans lie around the distance between the ramps (about half the move),
    // so widths near `left / total` each. For each first width and room, the second width is
    // what the rest needs at the spans a pair of the first width allows in each room (rooms of
    // neighbouring widths differ little), tried at a few points of its range.
    let guess = narrowest;
    for scale in [8u64, 6, 11, 4, 16, 2, 32, 1] {
        let w1 = (guess.saturating_mul(scale) / 8).max(1);
        let placed = slack.any_room(w1, |room1| {
            slack.any_room(w1, |estimate| {
                second_widths(left, w1, room1.spans, estimate.spans).any(|w2| {
                    slack.any_room(w2, |room2| {
                        let Some((span1, span2)) =
                            solve_two(left, (w1, w2), room1.spans, room2.spans)
                        else {
                            return false;
                        };
                        let mut candidate = *schedule;
                        let fits =
                            place_notch_pair(&mut candidate, room1, w1, span1, total, limits)
                                && place_notch_pair(
                                    &mut candidate,
                                    room2,
                                    w2,
                                    span2,
                                    total,
                                    limits,
                                );
                        if fits {
                            *schedule = candidate;
                        }
                        fits
                    })
                })
            })
        });
        if placed {
            return true;
        }
    }
    false
}

/// The widths worth trying for the second of two notch pairs: what is left after the first
/// (width `w1`, spans in `spans1`) divided by the spans `spans2`, at five points of that range.
fn second_widths(
    left: u128,
    w1: u64,
    spans1: (u64, u64),
    spans2: (u64, u64),
) -> impl Iterator<Item = u64> {
    let rest_low = left.saturating_sub(u128::from(w1) * u128::from(spans1.1));
    let rest_high = left.saturating_sub(u128::from(w1) * u128::from(spans1.0));
    let low = rest_low.div_ceil(u128::from(spans2.1)).max(1);
    let high = rest_high / u128::from(spans2.0);
    let step = (high.saturating_sub(low) / 4).max(1);
    (0..5u128)
        .map(move |k| low + k * step)
        .take_while(move |&w| w <= high)
        .filter_map(|w| u64::try_from(w).ok())
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// `(jerk, acceleration, velocity)` on each of `total` cycles, by stepping the schedule one
    /// cycle at a time (the plain way the closed forms are checked against).
    fn by_cycle(schedule: &Schedule, total: u64) -> Vec<(i128, i128, i128)> {
        let (mut jerk, mut acceleration, mut velocity) = (0i128, 0i128, 0i128);
        let changes = &schedule.changes[..schedule.count];
        (0..total)
            .map(|cycle| {
                jerk += changes
                    .iter()
                    .filter(|c| c.cycle == cycle)
                    .map(|c| i128::from(c.amount))
                    .sum::<i128>();
                acceleration += jerk;
                velocity += acceleration;
                (jerk, acceleration, velocity)
            })
            .collect()
    }

    /// The limits, cycle by cycle: the reference [`within_limits`] must agree with.
    fn within_limits_by_cycle(schedule: &Schedule, total: u64, limits: Limits64) -> bool {
        let cycles = by_cycle(schedule, total);
        cycles.iter().all(|&(jerk, acceleration, velocity)| {
            jerk.abs() <= i128::from(limits.jerk)
                && acceleration.abs() <= i128::from(limits.acceleration)
                && (0..=i128::from(limits.velocity)).contains(&velocity)
        }) && cycles.last().is_none_or(|&(_, a, v)| a == 0 && v == 0)
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(4_000))]

        /// The closed-form check agrees with stepping every cycle, on random schedules (a
        /// triple box and random jerk changes, so both verdicts occur).
        #[test]
        fn within_limits_agrees_with_stepping(
            (a, b, c) in (1u64..6, 0u64..6, 0u64..12),
            height in 1i64..4,
            extra in proptest::collection::vec((0u64..40, -3i64..=3), 0..6),
            (jerk, acceleration, velocity) in (1u64..8, 1u64..30, 1u64..200),
        ) {
            let (b, c) = (a + b, 2 * a + b + c);
            let mut schedule = Schedule::EMPTY;
            prop_assert!(schedule.push_triple_box(0, height, a, b, c));
            for (cycle, amount) in extra {
                prop_assert!(schedule.push(cycle, amount));
            }
            schedule.sort();
            let limits = Limits64 { jerk, acceleration, velocity };
            let total = a + b + c + 4;
            prop_assert_eq!(
                within_limits(&schedule, total, limits),
                within_limits_by_cycle(&schedule, total, limits)
            );
        }

        /// A notch pair takes exactly `width · span` off the distance and leaves the end at rest.
        #[test]
        fn a_notch_pair_takes_width_times_span(
            start in 0u64..20, width in 1u64..20, span in 1u64..40,
        ) {
            let mut schedule = Schedule::EMPTY;
            prop_assert!(push_notch_pair(&mut schedule, start, width, span));
            schedule.sort();
            let cycles = by_cycle(&schedule, start + span + width + 2);
            // ±1 on four cycles (two coincide, adding to 2, when the span equals the width).
            let most = if span == width { 2 } else { 1 };
            prop_assert!(cycles.iter().all(|&(jerk, _, _)| jerk.abs() <= most));
            let &(_, acceleration, velocity) = cycles.last().unwrap();
            prop_assert_eq!((acceleration, velocity), (0, 0));
            let distance: i128 = cycles.iter().map(|&(_, _, velocity)| velocity).sum();
            prop_assert_eq!(distance, -i128::from(width * span));
        }

        /// Two notch-pair widths and spans: any solution found solves the equation, in range.
        #[test]
        fn solve_two_solves(
            left in 1u128..1_000_000, w1 in 1u64..300, w2 in 1u64..300,
            (l1, n1, l2, n2) in (1u64..3_000, 0u64..3_000, 1u64..3_000, 0u64..3_000),
        ) {
            if let Some((k1, k2)) = solve_two(left, (w1, w2), (l1, l1 + n1), (l2, l2 + n2)) {
                prop_assert_eq!(u128::from(w1) * u128::from(k1) + u128::from(w2) * u128::from(k2), left);
                prop_assert!((l1..=l1 + n1).contains(&k1) && (l2..=l2 + n2).contains(&k2));
            } else {
                // No solution: check by brute force over the smaller range.
                for k1 in l1..=l1 + n1 {
                    let rest = left.checked_sub(u128::from(w1) * u128::from(k1));
                    if let Some(rest) = rest {
                        let ok = rest % u128::from(w2) == 0
                            && (u128::from(l2)..=u128::from(l2 + n2)).contains(&(rest / u128::from(w2)));
                        prop_assert!(!ok, "missed k1 = {}", k1);
                    }
                }
            }
        }
    }
}
