//! The common exact state model (SPEC §5), the stop kinds (SPEC §9), the [`ProfileGenerator`]
//! trait every generator implements, and the iterator adapter over its states.

use fixed::types::I32F32;

/// One cycle's commanded values, in the one exact format every generator shares.
///
/// On every cycle `n`, for every generator, exactly:
///
/// ```text
/// acceleration(n) = velocity(n) − velocity(n−1)
/// position(n)     = position(n−1) + velocity(n)      (wrapping at 32 integer bits)
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub struct State {
    /// Commanded position, counts (32 integer bits that wrap like the chip's register, 32
    /// fractional bits).
    pub position: I32F32,
    /// Commanded velocity, counts/cycle.
    pub velocity: I32F32,
    /// The velocity change applied on this cycle, counts/cycle².
    pub acceleration: I32F32,
}

impl State {
    /// At rest at `position`.
    pub const fn at_rest(position: I32F32) -> Self {
        Self {
            position,
            velocity: I32F32::ZERO,
            acceleration: I32F32::ZERO,
        }
    }

    /// The state after one cycle that applies `velocity`: the acceleration is the velocity change
    /// and the position advances by the new velocity, wrapping like the chip's register. Every
    /// generator builds its next state with this, so the identities of SPEC §5 hold by
    /// construction.
    #[inline]
    pub fn advanced(self, velocity: I32F32) -> Self {
        Self {
            position: self.position.wrapping_add(velocity),
            // Velocities are bounded by their registers (|v| < 2^31 counts/cycle), so the
            // difference cannot overflow; wrapping keeps the hot path free of a panic branch.
            acceleration: velocity.wrapping_sub(self.velocity),
            velocity,
        }
    }
}

/// Advances `state` by one cycle at `velocity` (as [`State::advanced`]) and returns the new
/// state, written field by field to both places: storing a whole `State` and returning a copy
/// of it makes the compiler write the return slot and copy it over, or reload what it just
/// stored (a store-forwarding stall on x86). The generators' `step` ends with this.
#[inline(always)]
pub(crate) fn advance(state: &mut State, velocity: I32F32) -> State {
    let position = state.position.wrapping_add(velocity);
    // As in `advanced`: velocities are bounded by their registers, no overflow.
    let acceleration = velocity.wrapping_sub(state.velocity);
    state.position = position;
    state.velocity = velocity;
    state.acceleration = acceleration;
    State {
        position,
        velocity,
        acceleration,
    }
}

/// How to stop (SPEC §9).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum StopKind {
    /// Decelerate to rest at the generator's deceleration (jerk-limited for the S-curve).
    Smooth,
    /// Velocity zero on the next cycle, position held; exempt from every rate limit.
    Abrupt,
}

/// The limits that governed a generator's most recent cycle, for checking it from outside (see
/// the `conformance` module). Magnitudes in counts/cycle, counts/cycle², counts/cycle³; `None`
/// means the generator has no such limit.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Limits {
    /// |velocity| may not exceed this.
    pub max_velocity: Option<I32F32>,
    /// A cycle that raises |velocity| (without crossing zero) may raise it by at most this.
    pub max_speed_up: Option<I32F32>,
    /// A cycle that lowers |velocity|, or crosses zero, may change the velocity by at most this.
    pub max_slow_down: Option<I32F32>,
    /// |acceleration| may not exceed this.
    pub max_acceleration: Option<I32F32>,
    /// |acceleration(n) − acceleration(n−1)| may not exceed this.
    pub max_jerk: Option<I32F32>,
    /// The cycle was an abrupt stop, exempt from every rate and jerk limit (SPEC §9).
    pub exempt: bool,
}

/// The one interface every profile generator implements. Object-safe, so a multi-axis
/// controller can hold `&mut dyn ProfileGenerator`.
///
/// Stepping never fails and never allocates; commands that can fail live on the generators.
pub trait ProfileGenerator: AsDynGenerator {
    /// Advances one cycle and returns the new state.
    fn step(&mut self) -> State;

    /// The present state (the last one [`step`](Self::step) returned, or the initial state).
    fn state(&self) -> State;

    /// Whether the motion is complete: at rest with nothing left to do. A complete generator
    /// stays put — stepping returns the same state — until it gets a new command.
    fn is_complete(&self) -> bool;

    /// Applies a stop (SPEC §9); it takes effect on the next [`step`](Self::step).
    fn stop(&mut self, kind: StopKind);

    /// The limits that governed the most recent cycle.
    fn limits(&self) -> Limits;

    /// An iterator over the states of the coming cycles, without end. Works on a
    /// `&mut dyn ProfileGenerator` too.
    ///
    /// ```
    /// use profilegen::format::juno::{Acceleration, TargetVelocity};
    /// use profilegen::{ProfileGenerator, StopKind, VelocityContouring, VelocityParameters};
    ///
    /// let mut axis = VelocityContouring::new(VelocityParameters {
    ///     velocity: TargetVelocity::from_num(1.0)?,
    ///     acceleration: Acceleration::from_num(0.25)?,
    ///     deceleration: Acceleration::ZERO,
    /// })?;
    /// let axis: &mut dyn ProfileGenerator = &mut axis;
    /// assert_eq!(axis.states().take(3).count(), 3);
    /// axis.stop(StopKind::Smooth);
    /// assert_eq!(axis.states_until_complete().last().unwrap().velocity, 0);
    /// # Ok::<(), profilegen::Error>(())
    /// ```
    fn states(&mut self) -> States<'_, dyn ProfileGenerator + '_> {
        States::new(self.as_dyn(), false)
    }

    /// An iterator over the states of the coming cycles that ends with the cycle on which the
    /// generator is complete (yielding nothing if it is complete already). Works on a
    /// `&mut dyn ProfileGenerator` too.
    fn states_until_complete(&mut self) -> States<'_, dyn ProfileGenerator + '_> {
        States::new(self.as_dyn(), true)
    }
}

/// A borrowed generator is a generator: adapters that own theirs (a [`crate::steps::StepTimer`],
/// a [`crate::gearing::Follower`]'s master) can borrow one instead, a trait object included.
impl<G: ProfileGenerator + ?Sized> ProfileGenerator for &mut G {
    #[inline]
    fn step(&mut self) -> State {
        (**self).step()
    }

    fn state(&self) -> State {
        (**self).state()
    }

    fn is_complete(&self) -> bool {
        (**self).is_complete()
    }

    fn stop(&mut self, kind: StopKind) {
        (**self).stop(kind);
    }

    fn limits(&self) -> Limits {
        (**self).limits()
    }
}

/// The generator as a trait object: what lets [`ProfileGenerator::states`] and
/// [`ProfileGenerator::states_until_complete`] be called on a `&mut dyn ProfileGenerator` as on a
/// concrete generator (a method that returned a type naming `Self` would need `Self: Sized`,
/// and could not be called on a trait object). Implemented for every sized generator; nothing
/// to implement by hand.
pub trait AsDynGenerator {
    /// `self` as a `&mut dyn ProfileGenerator`.
    fn as_dyn(&mut self) -> &mut dyn ProfileGenerator;
}

impl<G: ProfileGenerator> AsDynGenerator for G {
    #[inline]
    fn as_dyn(&mut self) -> &mut dyn ProfileGenerator {
        self
    }
}

/// Iterator over a generator's states, one per cycle; see [`ProfileGenerator::states`], or
/// [`States::new`] for one over a concrete generator.
#[derive(Debug)]
pub struct States<'a, G: ProfileGenerator + ?Sized> {
    generator: &'a mut G,
    until_complete: bool,
    done: bool,
}

impl<'a, G: ProfileGenerator + ?Sized> States<'a, G> {
    /// States of `generator`, without end (`until_complete == false`) or up to and including the
    /// cycle on which it is complete.
    pub fn new(generator: &'a mut G, until_complete: bool) -> Self {
        let done = until_complete && generator.is_complete();
        Self {
            generator,
            until_complete,
            done,
        }
    }
}

impl<G: ProfileGenerator + ?Sized> Iterator for States<'_, G> {
    type Item = State;

    fn next(&mut self) -> Option<State> {
        if self.done {
            return None;
        }
        let state = self.generator.step();
        self.done = self.until_complete && self.generator.is_complete();
        Some(state)
    }
}
