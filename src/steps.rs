//! Step timing for step/direction drivers: any generator's motion as the sequence of step
//! events — for each whole count crossed, its direction and its time, exact as a fraction of a
//! cycle (no floating point), so a driver can time its step pulses from this crate.
//!
//! Within a cycle the position is taken to move linearly, at that cycle's velocity `v(n)`, from
//! the last state's position `p(n−1)` to `p(n)` (the identities of SPEC §5 say the two ends are
//! `v(n)` apart). The count the position register shows is the floor of the position, so moving
//! up a step happens when the position reaches a whole count `k`, at the fraction
//! `(k − p(n−1)) / v(n)` of the cycle (in `(0, 1]`), and moving down when it falls below one, at
//! `(p(n−1) − k) / |v(n)|` (in `[0, 1)`). Numerators and denominators are raw I32F32 units
//! (velocities below 2^47), so every instant is an exact rational; the interval between two
//! steps is one too, in whole cycles plus a fraction with a 128-bit numerator and denominator.
//!
//! For a timer, [`StepTime::ticks`] rounds each step's instant (not each interval) down to
//! whole ticks: the delay between two pulses is the difference of two such values, so the
//! roundings never add up.

use crate::state::{ProfileGenerator, State};

/// Which way a step goes.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Direction {
    /// The count goes up by one.
    Forward,
    /// The count goes down by one.
    Backward,
}

/// An instant: `cycle + numerator / denominator` cycles after the timer started (`cycle` whole
/// cycles, then a fraction `0 ≤ numerator ≤ denominator` of the next).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct StepTime {
    /// Whole cycles before the one the step falls in.
    pub cycle: u64,
    /// The fraction of that cycle: numerator (raw units, 2^-32 counts) …
    pub numerator: u64,
    /// … over denominator (the cycle's |velocity|, raw units; never zero).
    pub denominator: u64,
}

impl StepTime {
    /// The instant in whole ticks of a timer running `ticks_per_cycle` ticks per cycle,
    /// rounded down: `cycle·t + ⌊numerator·t / denominator⌋` (exact in 128 bits: the
    /// numerator is below 2^47).
    pub fn ticks(self, ticks_per_cycle: u64) -> u128 {
        let per = u128::from(ticks_per_cycle);
        u128::from(self.cycle) * per
            + u128::from(self.numerator) * per / u128::from(self.denominator.max(1))
    }

    /// The time from `earlier` to this instant (this one not earlier), exactly.
    pub fn since(self, earlier: StepTime) -> Interval {
        let (d1, d2) = (
            u128::from(earlier.denominator.max(1)),
            u128::from(self.denominator.max(1)),
        );
        // The fractions' difference over d1·d2 (< 2^94): n2·d1 − n1·d2, borrowing a whole cycle
        // when it is negative.
        let (mine, theirs) = (
            u128::from(self.numerator) * d1,
            u128::from(earlier.numerator) * d2,
        );
        let denominator = d1 * d2;
        let mut cycles = self.cycle.saturating_sub(earlier.cycle);
        let numerator = if mine >= theirs {
            mine - theirs
        } else {
            cycles = cycles.saturating_sub(1);
            denominator - (theirs - mine)
        };
        // A fraction of a whole cycle (n ≤ d): carried into the cycles.
        if numerator == denominator {
            return Interval {
                cycles: cycles + 1,
                numerator: 0,
                denominator: 1,
            };
        }
        Interval {
            cycles,
            numerator,
            denominator,
        }
    }
}

/// A time between two steps, exactly: `cycles + numerator / denominator` cycles, with
/// `0 ≤ numerator < denominator`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Interval {
    /// Whole cycles.
    pub cycles: u64,
    /// The fraction's numerator …
    pub numerator: u128,
    /// … and denominator (never zero).
    pub denominator: u128,
}

/// One step: a whole count crossed.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct StepEvent {
    /// Up or down.
    pub direction: Direction,
    /// The count the position register shows after the step (it wraps with the register).
    pub count: i32,
    /// When it happens.
    pub at: StepTime,
    /// The time since the previous step; `None` for the first.
    pub since_previous: Option<Interval>,
}

/// Turns a generator's cycles into step events: [`Self::step`] advances the generator one cycle
/// and returns that cycle's steps, in order, each with its exact time.
///
/// ```
/// use profilegen::format::juno::{Acceleration, TargetVelocity};
/// use profilegen::steps::{Direction, StepTimer};
/// use profilegen::{VelocityContouring, VelocityParameters};
///
/// let axis = VelocityContouring::new(VelocityParameters {
///     velocity: TargetVelocity::from_num(2.5)?,
///     acceleration: Acceleration::from_num(2.5)?,
///     deceleration: Acceleration::ZERO,
/// })?;
/// let mut timer = StepTimer::new(axis);
/// // The first cycle moves 0 → 2.5: counts 1 and 2, at 1/2.5 and 2/2.5 of the cycle.
/// let steps: Vec<_> = timer.step().collect();
/// assert_eq!(steps.len(), 2);
/// assert_eq!(steps[1].direction, Direction::Forward);
/// assert_eq!(steps[1].count, 2);
/// let at = steps[1].at;
/// assert_eq!((at.cycle, at.numerator * 5), (0, at.denominator * 4)); // 0.8 of the first cycle
/// // 0.4 cycles after the first; on a 1,000-tick cycle, step pulses at ticks 400 and 800.
/// let since = steps[1].since_previous.unwrap();
/// assert_eq!((since.cycles, since.numerator * 5), (0, since.denominator * 2));
/// assert_eq!((steps[0].at.ticks(1_000), at.ticks(1_000)), (400, 800));
/// # Ok::<(), profilegen::Error>(())
/// ```
#[derive(Debug, Clone)]
pub struct StepTimer<G> {
    generator: G,
    /// Cycles stepped so far.
    cycles: u64,
    /// The last step's time, if any.
    last: Option<StepTime>,
}

impl<G: ProfileGenerator> StepTimer<G> {
    /// A timer over `generator`, from its present state; time 0 is now.
    pub fn new(generator: G) -> Self {
        Self {
            generator,
            cycles: 0,
            last: None,
        }
    }

    /// The generator.
    pub fn generator(&self) -> &G {
        &self.generator
    }

    /// The generator, to command it.
    pub fn generator_mut(&mut self) -> &mut G {
        &mut self.generator
    }

    /// Advances the generator one cycle; its steps, in order (none if the count did not change).
    pub fn step(&mut self) -> CycleSteps {
        let before = self.generator.state();
        let after = self.generator.step();
        let steps = CycleSteps::new(before, after, self.cycles, self.last);
        self.cycles += 1;
        if let Some(last) = steps.last_time() {
            self.last = Some(last);
        }
        steps
    }
}

/// The steps of one cycle ([`StepTimer::step`]), computed one by one (no allocation).
#[derive(Debug, Clone)]
pub struct CycleSteps {
    /// The position before the cycle, raw, not wrapped (i128 so the crossing never wraps).
    from: i128,
    /// The cycle's velocity, raw.
    velocity: i128,
    /// The next count boundary to cross (whole counts).
    next: i128,
    /// Steps left.
    remaining: u64,
    cycle: u64,
    previous: Option<StepTime>,
}

impl CycleSteps {
    fn new(before: State, after: State, cycle: u64, previous: Option<StepTime>) -> Self {
        let from = i128::from(before.position.to_bits());
        // The identities make the cycle's velocity the positions' difference (mod the register).
        let velocity = i128::from(after.velocity.to_bits());
        let to = from + velocity;
        // Whole counts below the ends (floor: the arithmetic shift).
        let (low, high) = (from >> 32, to >> 32);
        let (next, remaining) = if velocity >= 0 {
            (low + 1, high - low)
        } else {
            // Moving down, the step to k − 1 happens below k: the first boundary is floor(from).
            (low, low - high)
        };
        Self {
            from,
            velocity,
            next,
            remaining: remaining as u64,
            cycle,
            previous,
        }
    }

    /// The time of the step at boundary `k` (whole counts).
    fn time_at(&self, k: i128) -> StepTime {
        let distance = ((k << 32) - self.from).unsigned_abs();
        StepTime {
            cycle: self.cycle,
            // Both below 2^47 (a cycle moves less than 2^15 counts).
            numerator: distance as u64,
            denominator: self.velocity.unsigned_abs() as u64,
        }
    }

    /// The time of this cycle's last step, if it has any.
    fn last_time(&self) -> Option<StepTime> {
        let count = i128::from(self.remaining);
        (count > 0).then(|| {
            let last = if self.velocity >= 0 {
                self.next + count - 1
            } else {
                self.next - count + 1
            };
            self.time_at(last)
        })
    }
}

impl Iterator for CycleSteps {
    type Item = StepEvent;

    fn next(&mut self) -> Option<StepEvent> {
        if self.remaining == 0 {
            return None;
        }
        self.remaining -= 1;
        let k = self.next;
        let at = self.time_at(k);
        let (direction, count) = if self.velocity >= 0 {
            self.next += 1;
            (Direction::Forward, k)
        } else {
            self.next -= 1;
            (Direction::Backward, k - 1)
        };
        let since_previous = self.previous.map(|previous| at.since(previous));
        self.previous = Some(at);
        Some(StepEvent {
            direction,
            // The register's count: the low 32 bits of the whole count.
            count: count as i32,
            at,
            since_previous,
        })
    }

    fn size_hint(&self) -> (usize, Option<usize>) {
        let left = usize::try_from(self.remaining).unwrap_or(usize::MAX);
        (left, Some(left))
    }
}
