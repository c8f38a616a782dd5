//! An [`Arc`] driven by a speed profile (SPEC §12), as [`Line::drive`](super::super::Line::drive)
//! does for a line, and the MCX514's own driving profile for an arc, with the chip's refusals.

use super::{Arc, ArcWalk, Octant};
use crate::format::mcx514::{
    Acceleration, Deceleration, DecelerationJerk, DriveSpeed, FinishPoint, InitialSpeed, Jerk,
};
use crate::format::CycleTime;
use crate::interpolation::drive::steps_of;
use crate::{
    DecelerationMode, Error, Mcx514Parameters, Mcx514Trapezoidal, ProfileGenerator, Range, State,
    StopKind,
};

/// One cycle of a circular interpolation: the driving profile's exact state, the step count,
/// where it puts both axes and the octant of the last step.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct CircleState {
    /// The speed profile's state (SPEC §5): position in interpolation steps, exact I32F32.
    pub driving: State,
    /// Interpolation steps (short-axis pulses) taken: the integer part of the driving position,
    /// held within 0 … [`Arc::steps`].
    pub step: u64,
    /// Both axes' positions, pulses relative to the start.
    pub axes: [i32; 2],
    /// The octant of the last step (the chip's status register).
    pub octant: Octant,
}

/// An [`Arc`] driven by a speed profile; see [`Arc::drive`]. As an [`Iterator`] it steps the
/// profile once per item, without end (use [`Self::is_complete`] or `take` to stop).
#[derive(Debug)]
pub struct CircularInterpolation<'a, G: ProfileGenerator + ?Sized> {
    walk: ArcWalk,
    generator: &'a mut G,
}

impl Arc {
    /// Drives this arc with `generator`, whose position (in steps) should run from 0 to
    /// [`Self::steps`]: e.g. [`Self::mcx514_profile`], or any of the crate's point-to-point
    /// generators to that destination. Each cycle both axes jump to the step the profile
    /// reached, O(1) however many steps the cycle takes; a driving position outside the arc
    /// holds the axes at the nearer end.
    ///
    /// ```
    /// use profilegen::format::mcx514::{Acceleration, Deceleration, DriveSpeed, InitialSpeed};
    /// use profilegen::format::CycleTime;
    /// use profilegen::interpolation::{Arc, CircularDriving, Direction};
    /// use profilegen::DecelerationMode;
    ///
    /// // A half circle of radius 1,000 at 1 ms: SV 2,000 pps, DV 50,000 pps.
    /// let arc = Arc::from_pulses([1_000, 0], [2_000, 0], Direction::Clockwise)?;
    /// let mut profile = arc.mcx514_profile(
    ///     CircularDriving {
    ///         initial_speed: InitialSpeed::from_bits(2_000)?,
    ///         drive_speed: DriveSpeed::from_bits(50_000)?,
    ///         acceleration: Acceleration::from_bits(1_000_000)?,
    ///         deceleration: Deceleration::from_bits(1_000_000)?,
    ///         jerk: None,
    ///         deceleration_jerk: None,
    ///         deceleration_mode: DecelerationMode::Disabled,
    ///     },
    ///     CycleTime::from_seconds(1e-3)?,
    /// )?;
    /// let mut interpolation = arc.drive(&mut profile);
    /// while !interpolation.is_complete() {
    ///     interpolation.step();
    /// }
    /// assert_eq!(interpolation.state().axes, [2_000, 0]);
    /// # Ok::<(), profilegen::Error>(())
    /// ```
    pub fn drive<'a, G: ProfileGenerator + ?Sized>(
        &self,
        generator: &'a mut G,
    ) -> CircularInterpolation<'a, G> {
        let mut walk = self.walk();
        walk.advance_to(u64::from(steps_of(&generator.state())));
        CircularInterpolation { walk, generator }
    }

    /// The MCX514's driving profile for this arc: an [`Mcx514Trapezoidal`] over [`Self::steps`]
    /// pulses. Circular interpolation drives trapezoidally with a manual deceleration point (or
    /// deceleration disabled) only, as on the chip (reference 003 §3.8.2).
    ///
    /// # Errors
    /// [`Error::Refused`] for a jerk (S-curve driving, parameter `jerk`) or automatic
    /// deceleration (parameter `deceleration point`); [`Error::OutOfRange`] (parameter `arc
    /// steps`) for an arc of more than 1,073,741,823 steps; those of [`Mcx514Trapezoidal::new`].
    pub fn mcx514_profile(
        &self,
        driving: CircularDriving,
        cycle: CycleTime,
    ) -> Result<Mcx514Trapezoidal, Error> {
        if driving.jerk.is_some() || driving.deceleration_jerk.is_some() {
            return Err(Error::Refused {
                parameter: if driving.jerk.is_some() {
                    Jerk::PARAMETER
                } else {
                    DecelerationJerk::PARAMETER
                },
                reason: "in circular interpolation: the MCX514 drives an arc trapezoidally only \
                         (S-curve driving is for linear interpolation, reference 003 §3.8.2)",
            });
        }
        if driving.deceleration_mode == DecelerationMode::Automatic {
            return Err(Error::Refused {
                parameter: "deceleration point",
                reason: "to automatic in circular interpolation: the MCX514 needs a manual \
                         deceleration point there (reference 003 §3.8.2)",
            });
        }
        let pulses = u32::try_from(self.steps)
            .ok()
            .filter(|&steps| steps <= FinishPoint::MAX_BITS as u32)
            .ok_or(Error::OutOfRange {
                parameter: "arc steps",
                value: self.steps as f64,
                range: Range::of_register(0, i64::from(FinishPoint::MAX_BITS), 0, "pulses"),
            })?;
        Mcx514Trapezoidal::new(
            Mcx514Parameters {
                pulses,
                initial_speed: driving.initial_speed,
                drive_speed: driving.drive_speed,
                acceleration: driving.acceleration,
                deceleration: driving.deceleration,
                deceleration_mode: driving.deceleration_mode,
            },
            cycle,
        )
    }
}

/// The driving registers of an MCX514 circular interpolation, as the chip takes them; see
/// [`Arc::mcx514_profile`]. The S-curve registers are here so that asking for an S-curve circle
/// is refused as the chip refuses it, not silently ignored.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct CircularDriving {
    /// Initial speed SV, pps.
    pub initial_speed: InitialSpeed,
    /// Drive speed DV, pps, ≥ SV.
    pub drive_speed: DriveSpeed,
    /// Acceleration AC, pps/s.
    pub acceleration: Acceleration,
    /// Deceleration DC, pps/s.
    pub deceleration: Deceleration,
    /// Jerk JK for S-curve driving: must be `None` (refused in circular interpolation).
    pub jerk: Option<Jerk>,
    /// Deceleration jerk DJ for S-curve driving: must be `None` (refused likewise).
    pub deceleration_jerk: Option<DecelerationJerk>,
    /// Manual (with the point, in short-axis pulses) or disabled; automatic is refused.
    pub deceleration_mode: DecelerationMode,
}

impl<G: ProfileGenerator + ?Sized> CircularInterpolation<'_, G> {
    /// Advances the profile one cycle and moves both axes to where it leads.
    pub fn step(&mut self) -> CircleState {
        let driving = self.generator.step();
        // The integer part of an I32F32 (a floor) is an i32: the cast keeps every bit.
        let axes = self
            .walk
            .advance_to_whole((driving.position.to_bits() >> 32) as i32);
        CircleState {
            driving,
            step: self.walk.step(),
            axes,
            octant: self.walk.octant(),
        }
    }

    /// The present state (after the last [`step`](Self::step), or the start).
    pub fn state(&self) -> CircleState {
        CircleState {
            driving: self.generator.state(),
            step: self.walk.step(),
            axes: self.walk.current_position(),
            octant: self.walk.octant(),
        }
    }

    /// Whether the driving profile is complete.
    pub fn is_complete(&self) -> bool {
        self.generator.is_complete()
    }

    /// Stops the interpolation (SPEC §9) by stopping the driving profile: smooth along the
    /// arc, abrupt in place.
    pub fn stop(&mut self, kind: StopKind) {
        self.generator.stop(kind);
    }

    /// The arc being followed.
    pub fn arc(&self) -> &Arc {
        self.walk.arc()
    }
}

impl<G: ProfileGenerator + ?Sized> Iterator for CircularInterpolation<'_, G> {
    type Item = CircleState;

    fn next(&mut self) -> Option<Self::Item> {
        Some(self.step())
    }
}
