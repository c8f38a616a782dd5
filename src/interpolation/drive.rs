//! A geometry driven by a speed profile (SPEC §12, #14 item 3): any [`ProfileGenerator`] whose
//! position counts interpolation steps moves every axis of a [`Line`], one O(1) jump per cycle.
//! The generator stays one-dimensional; this composes it with the geometry, as
//! [`MicrostepTable::drive`](crate::waveform::MicrostepTable::drive) does with a waveform.

use super::linear::{Line, Walk};
use crate::{ProfileGenerator, State, StopKind};

/// One cycle of a multi-axis interpolation: the driving profile's exact state and where it puts
/// every axis.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct InterpolationState<const N: usize> {
    /// The speed profile's state (SPEC §5): position in interpolation steps, exact I32F32.
    pub driving: State,
    /// Interpolation steps taken: the integer part of the driving position (floor, like the
    /// chip's output counter), held within 0 … [`Line::steps`].
    pub step: u32,
    /// Every axis's position, pulses relative to the start.
    pub axes: [i32; N],
}

/// A [`Line`] driven by a speed profile; see [`Line::drive`]. As an [`Iterator`] it steps the
/// profile once per item, without end (use [`Self::is_complete`] or `take` to stop).
#[derive(Debug)]
pub struct LinearInterpolation<'a, G: ProfileGenerator + ?Sized, const N: usize> {
    walk: Walk<N>,
    generator: &'a mut G,
}

impl<const N: usize> Line<N> {
    /// Drives this line with `generator`, whose position (in steps) should run from 0 to
    /// [`Self::steps`]: e.g. a trapezoidal or S-curve move to that destination. Each cycle the
    /// axes jump to the step the profile reached, O(1) per axis however many steps the cycle
    /// takes. A driving position outside 0 … L holds the axes at the nearer end: the geometry
    /// never leaves its segment.
    ///
    /// ```
    /// use profilegen::format::juno::{Acceleration, TargetVelocity};
    /// use profilegen::interpolation::Line;
    /// use profilegen::{Trapezoidal, TrapezoidalParameters};
    ///
    /// let line = Line::from_pulses([-20_000, 30_000, -50_000])?;
    /// let mut profile = Trapezoidal::new(TrapezoidalParameters {
    ///     destination: line.steps() as i32,
    ///     max_velocity: TargetVelocity::from_num(250.0)?, // steps per cycle
    ///     acceleration: Acceleration::from_num(2.0)?,
    ///     deceleration: Acceleration::ZERO, // as the acceleration
    ///     start_velocity: TargetVelocity::ZERO,
    /// })?;
    /// let mut interpolation = line.drive(&mut profile);
    /// while !interpolation.is_complete() {
    ///     interpolation.step();
    /// }
    /// assert_eq!(interpolation.state().axes, [-20_000, 30_000, -50_000]);
    /// # Ok::<(), profilegen::Error>(())
    /// ```
    pub fn drive<'a, G: ProfileGenerator + ?Sized>(
        &self,
        generator: &'a mut G,
    ) -> LinearInterpolation<'a, G, N> {
        let mut walk = self.walk();
        walk.advance_to(steps_of(&generator.state()));
        LinearInterpolation { walk, generator }
    }
}

/// The whole steps of a driving position: its integer part (I32F32 bits shifted right by 32, a
/// floor), clamped to 0 … u32::MAX (the walk clamps to its own end).
pub(super) fn steps_of(state: &State) -> u32 {
    let whole = state.position.to_bits() >> 32;
    // i64 → u32: negative positions are step 0; the integer part is < 2³¹ so the cast is exact.
    whole.max(0) as u32
}

impl<G: ProfileGenerator + ?Sized, const N: usize> LinearInterpolation<'_, G, N> {
    /// Advances the profile one cycle and moves every axis to where it leads.
    pub fn step(&mut self) -> InterpolationState<N> {
        let driving = self.generator.step();
        // The integer part of an I32F32 (a floor) is an i32: the cast keeps every bit.
        let axes = self
            .walk
            .advance_to_whole((driving.position.to_bits() >> 32) as i32);
        InterpolationState {
            driving,
            step: self.walk.step(),
            axes,
        }
    }

    /// The present state (after the last [`step`](Self::step), or the start).
    pub fn state(&self) -> InterpolationState<N> {
        InterpolationState {
            driving: self.generator.state(),
            step: self.walk.step(),
            axes: self.walk.current_position(),
        }
    }

    /// Whether the driving profile is complete.
    pub fn is_complete(&self) -> bool {
        self.generator.is_complete()
    }

    /// Stops the whole interpolation (SPEC §9) by stopping the driving profile: a smooth stop
    /// decelerates along the line (the axes follow the step count, so they stay on it); an abrupt
    /// stop holds the step count, so every axis holds.
    pub fn stop(&mut self, kind: StopKind) {
        self.generator.stop(kind);
    }

    /// The line being followed.
    pub fn line(&self) -> &Line<N> {
        self.walk.line()
    }
}

impl<G: ProfileGenerator + ?Sized, const N: usize> Iterator for LinearInterpolation<'_, G, N> {
    type Item = InterpolationState<N>;

    fn next(&mut self) -> Option<Self::Item> {
        Some(self.step())
    }
}
