//! Continuous interpolation (SPEC §12.5): linear and circular segments on the X and Y axes,
//! driven back to back by one MCX514 trapezoid that accelerates at the start of the first
//! segment and decelerates only in the last, from a manual deceleration point counted from that
//! segment's start. The segments wait in a fixed-capacity queue, the chip's pre-buffer of
//! [`CAPACITY`] (no allocation), which may be refilled while the move runs.
//!
//! ```
//! use profilegen::format::mcx514::{Acceleration, Deceleration, DriveSpeed, InitialSpeed};
//! use profilegen::format::mcx514::ManualDecelerationPoint;
//! use profilegen::format::CycleTime;
//! use profilegen::interpolation::{Arc, ContinuousDriving, ContinuousInterpolation, Direction};
//! use profilegen::interpolation::{Line, Segment};
//!
//! let mut run = ContinuousInterpolation::new(
//!     ContinuousDriving {
//!         initial_speed: InitialSpeed::from_bits(1_000)?,
//!         drive_speed: DriveSpeed::from_bits(10_000)?,
//!         acceleration: Acceleration::from_bits(200_000)?,
//!         deceleration: Deceleration::from_bits(200_000)?,
//!     },
//!     CycleTime::from_seconds(1e-3)?,
//! )?;
//! // 1,000 pulses along X, a half circle of radius 500 back over the top, 1,000 back along X.
//! run.push(Segment::Line(Line::from_pulses([1_000, 0])?))?;
//! run.push(Segment::Arc(Arc::from_pulses([0, 500], [0, 1_000], Direction::CounterClockwise)?))?;
//! let point = ManualDecelerationPoint::from_bits(1_000 - 250)?; // 250 pulses to slow down
//! run.push_last(Segment::Line(Line::from_pulses([-1_000, 0])?), point)?;
//! while !run.is_complete() {
//!     run.step();
//! }
//! assert_eq!(run.state().axes, [0, 1_000]);
//! # Ok::<(), profilegen::Error>(())
//! ```

use super::drive::steps_of;
use super::{Arc, ArcWalk, Line, Walk};
use crate::format::mcx514::{
    Acceleration, Deceleration, DriveSpeed, FinishPoint, InitialSpeed, ManualDecelerationPoint,
};
use crate::format::CycleTime;
use crate::{
    DecelerationMode, Error, Mcx514Parameters, Mcx514Trapezoidal, ProfileGenerator, Range, State,
    StopKind,
};

/// The segments the queue holds besides the one being driven: the MCX514's pre-buffer.
pub const CAPACITY: usize = 8;

/// The pulses a whole continuous run may take: the MCX514 trapezoid's finish point range.
const MAX_STEPS: u64 = FinishPoint::MAX_BITS as u64;

/// One segment of a continuous interpolation, relative to where the previous one ends.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Segment {
    /// A straight line (SPEC §12.3).
    Line(Line<2>),
    /// A circular arc (SPEC §12.4).
    Arc(Arc),
}

impl Segment {
    /// The segment's steps: the long axis's pulses of a line, the short-axis pulses of an arc.
    pub fn steps(&self) -> u64 {
        match self {
            Segment::Line(line) => u64::from(line.steps()),
            Segment::Arc(arc) => arc.steps(),
        }
    }

    /// Where the segment ends, pulses relative to its start.
    pub fn end(&self) -> [i32; 2] {
        match self {
            Segment::Line(line) => line.finish(),
            Segment::Arc(arc) => arc.end(),
        }
    }

    fn cursor(&self) -> Cursor {
        match self {
            Segment::Line(line) => Cursor::Line(line.walk()),
            Segment::Arc(arc) => Cursor::Arc(arc.walk()),
        }
    }
}

/// A walk along the segment being driven.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
enum Cursor {
    Line(Walk<2>),
    Arc(ArcWalk),
}

impl Cursor {
    /// Both axes after `step` steps of the segment (clamped to its end).
    fn advance_to(&mut self, step: u64) -> [i32; 2] {
        match self {
            // A line has at most 2³⁰ − 1 steps: the clamp keeps the cast exact.
            Cursor::Line(walk) => walk.advance_to(step.min(u64::from(u32::MAX)) as u32),
            Cursor::Arc(walk) => walk.advance_to(step),
        }
    }

    fn position(&self) -> [i32; 2] {
        match self {
            Cursor::Line(walk) => walk.current_position(),
            Cursor::Arc(walk) => walk.current_position(),
        }
    }
}

/// The driving registers of a continuous interpolation (trapezoidal, as the MCX514 drives
/// circles); the manual deceleration point comes with the last segment
/// ([`ContinuousInterpolation::push_last`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct ContinuousDriving {
    /// Initial speed SV, pps.
    pub initial_speed: InitialSpeed,
    /// Drive speed DV, pps, ≥ SV.
    pub drive_speed: DriveSpeed,
    /// Acceleration AC, pps/s.
    pub acceleration: Acceleration,
    /// Deceleration DC, pps/s.
    pub deceleration: Deceleration,
}

/// One cycle of a continuous interpolation.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct ContinuousState {
    /// The speed profile's state (SPEC §5): position in steps since the run began.
    pub driving: State,
    /// Steps since the run began (the integer part of the driving position).
    pub step: u64,
    /// The number of the segment being driven, counted from 0 since the run began.
    pub segment: u32,
    /// Both axes, pulses relative to where the run began (wrapping at 32 bits, like the chip's
    /// counters).
    pub axes: [i32; 2],
}

/// A continuous interpolation: a queue of up to [`CAPACITY`] waiting segments and the one being
/// driven, one MCX514 trapezoid across all of them; see the [module docs](self).
///
/// The trapezoid's finish point is the end of the last segment queued so far: if the queue runs
/// dry before a last segment ([`Self::push_last`]) arrives, the move stops at the end of what it
/// has, at speed (as the chip does at a late finish point, exempt from the rate limits).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ContinuousInterpolation {
    profile: Mcx514Trapezoidal,
    /// The waiting segments, a ring: `queue[(head + i) % CAPACITY]` for i < `waiting`.
    queue: [Option<Segment>; CAPACITY],
    head: usize,
    waiting: usize,
    /// The segment being driven, if any yet.
    current: Option<Cursor>,
    /// Its number since the run began.
    segment: u32,
    /// The run's step at which it begins.
    current_start: u64,
    /// Where it begins, relative to the run's start.
    origin: [i32; 2],
    /// Steps of the segment being driven and every waiting one: the trapezoid's finish point.
    queued_steps: u64,
    /// A last segment has been queued (the deceleration point is set): nothing may follow it.
    closed: bool,
    /// A stop abandoned the queue.
    stopped: bool,
}

impl ContinuousInterpolation {
    /// An empty run with these driving registers at `cycle`; it starts moving on the first
    /// [`step`](Self::step) after a segment is queued.
    ///
    /// # Errors
    /// Those of [`Mcx514Trapezoidal::new`] (an initial speed above the drive speed, a register
    /// that vanishes or overflows at this cycle time).
    pub fn new(driving: ContinuousDriving, cycle: CycleTime) -> Result<Self, Error> {
        let profile = Mcx514Trapezoidal::new(
            Mcx514Parameters {
                pulses: 0,
                initial_speed: driving.initial_speed,
                drive_speed: driving.drive_speed,
                acceleration: driving.acceleration,
                deceleration: driving.deceleration,
                // No point until the last segment sets one.
                deceleration_mode: DecelerationMode::Manual(ManualDecelerationPoint::MAX),
            },
            cycle,
        )?;
        Ok(Self {
            profile,
            queue: [None; CAPACITY],
            head: 0,
            waiting: 0,
            current: None,
            segment: 0,
            current_start: 0,
            origin: [0, 0],
            queued_steps: 0,
            closed: false,
            stopped: false,
        })
    }

    /// Queues `segment` to follow the others without stopping.
    ///
    /// # Errors
    /// [`Error::Refused`] (parameter `segment`), changing nothing, when the queue already holds
    /// [`CAPACITY`] waiting segments, after the last segment ([`Self::push_last`]), after a stop,
    /// or once the run has ended; [`Error::OutOfRange`] (parameter `continuous steps`) when the
    /// run would exceed 1,073,741,823 steps.
    pub fn push(&mut self, segment: Segment) -> Result<(), Error> {
        self.enqueue(segment, None)
    }

    /// Queues the last segment, with the manual deceleration point counted from its start (in
    /// its own steps: `segment.steps() − deceleration pulses`, as for a single segment). The run
    /// decelerates there only, and ends at this segment's end.
    ///
    /// # Errors
    /// As [`Self::push`].
    pub fn push_last(
        &mut self,
        segment: Segment,
        deceleration_point: ManualDecelerationPoint,
    ) -> Result<(), Error> {
        self.enqueue(segment, Some(deceleration_point))
    }

    fn enqueue(
        &mut self,
        segment: Segment,
        point: Option<ManualDecelerationPoint>,
    ) -> Result<(), Error> {
        let refused = |reason| Error::Refused {
            parameter: "segment",
            reason,
        };
        if self.waiting == CAPACITY {
            return Err(refused(
                "while the pre-buffer is full (8 segments waiting): wait for one to start",
            ));
        }
        if self.closed {
            return Err(refused("after the last segment"));
        }
        if self.stopped {
            return Err(refused("after a stop (the stop abandoned the queue)"));
        }
        let start = self.queued_steps;
        let total = start + segment.steps();
        if total > MAX_STEPS {
            return Err(Error::OutOfRange {
                parameter: "continuous steps",
                value: total as f64,
                range: Range::of_register(0, MAX_STEPS as i64, 0, "pulses"),
            });
        }
        // The deceleration point, counted from this segment's start; past the register's top
        // means never (the chip's largest point, 4,294,967,292, is beyond any run).
        let global_point = point.map(|point| {
            u32::try_from(start + u64::from(point.to_bits()))
                .unwrap_or(ManualDecelerationPoint::MAX_BITS)
        });
        // Both below 2³⁰: the cast is exact.
        if !self.profile.continue_to(total as u32, global_point) {
            return Err(refused("after the run has ended (the queue ran dry)"));
        }
        self.queue[(self.head + self.waiting) % CAPACITY] = Some(segment);
        self.waiting += 1;
        self.queued_steps = total;
        self.closed = point.is_some();
        Ok(())
    }

    /// Takes the next waiting segment, if any, as the one being driven.
    fn start_next(&mut self) -> bool {
        if self.waiting == 0 {
            return false;
        }
        let Some(segment) = self.queue[self.head].take() else {
            return false;
        };
        self.head = (self.head + 1) % CAPACITY;
        self.waiting -= 1;
        if let Some(current) = &self.current {
            let end = current.position();
            self.origin = [
                self.origin[0].wrapping_add(end[0]),
                self.origin[1].wrapping_add(end[1]),
            ];
            self.segment += 1;
        }
        self.current = Some(segment.cursor());
        true
    }

    /// Advances the profile one cycle and moves both axes along the segments to the step it
    /// reached: O(1) per segment it finishes (at most [`CAPACITY`] + 1 per cycle), O(1) within
    /// one.
    pub fn step(&mut self) -> ContinuousState {
        if self.current.is_none() {
            self.start_next();
        }
        let driving = self.profile.step();
        let step = u64::from(steps_of(&driving));
        // Past the end of the segment being driven: on to the next ones (the end of one is the
        // start of the next, so an exact end stays on the segment being driven).
        while let Some(current) = &self.current {
            let steps = match current {
                Cursor::Line(walk) => u64::from(walk.line().steps()),
                Cursor::Arc(walk) => walk.arc().steps(),
            };
            if step <= self.current_start + steps || self.waiting == 0 {
                break;
            }
            // Finish this one where it ends, then start the next.
            if let Some(current) = &mut self.current {
                current.advance_to(steps);
            }
            self.current_start += steps;
            self.start_next();
        }
        self.state_with(driving, step)
    }

    fn state_with(&mut self, driving: State, step: u64) -> ContinuousState {
        let local = step.saturating_sub(self.current_start);
        let position = match &mut self.current {
            Some(current) => current.advance_to(local),
            None => [0, 0],
        };
        ContinuousState {
            driving,
            step,
            segment: self.segment,
            axes: [
                self.origin[0].wrapping_add(position[0]),
                self.origin[1].wrapping_add(position[1]),
            ],
        }
    }

    /// The present state (after the last [`step`](Self::step), or the start).
    pub fn state(&self) -> ContinuousState {
        let driving = self.profile.state();
        let position = self.current.as_ref().map_or([0, 0], Cursor::position);
        ContinuousState {
            driving,
            step: u64::from(steps_of(&driving)),
            segment: self.segment,
            axes: [
                self.origin[0].wrapping_add(position[0]),
                self.origin[1].wrapping_add(position[1]),
            ],
        }
    }

    /// Whether the run has ended: the profile is at rest at its finish point (or stopped).
    pub fn is_complete(&self) -> bool {
        self.profile.is_complete()
    }

    /// The segments waiting (not counting the one being driven).
    pub const fn waiting(&self) -> usize {
        self.waiting
    }

    /// Room left in the queue.
    pub const fn free(&self) -> usize {
        CAPACITY - self.waiting
    }

    /// The driving profile (its limits, for checking a cycle from outside).
    pub const fn profile(&self) -> &Mcx514Trapezoidal {
        &self.profile
    }

    /// Stops the run (SPEC §9) and abandons the waiting segments: a smooth stop decelerates
    /// along the segment being driven, whose end becomes the finish point (if it comes first,
    /// the run stops there at once, as at a late finish point; if the position is already a
    /// fraction past it, the stop is abrupt); an abrupt stop holds in place.
    /// Nothing can be queued afterwards.
    pub fn stop(&mut self, kind: StopKind) {
        let end_of_current = match &self.current {
            Some(Cursor::Line(walk)) => self.current_start + u64::from(walk.line().steps()),
            Some(Cursor::Arc(walk)) => self.current_start + walk.arc().steps(),
            None => 0,
        };
        self.queue = [None; CAPACITY];
        self.waiting = 0;
        self.queued_steps = end_of_current;
        // Below the previous finish point, within 2³⁰: exact. A finish already behind the
        // position (the run has ended) is refused and changes nothing.
        let moved_on = self.profile.continue_to(end_of_current as u32, None);
        // The position already a fraction past the segment's end (its step still the end's): the
        // end cannot be the finish point any more, and the old one lies in the abandoned
        // segments. The end came first: stop at once, within the segment's last step.
        let passed = !moved_on
            && !self.stopped
            && self.profile.state().position.to_bits() > (end_of_current as i64) << 32;
        self.stopped = true;
        self.profile
            .stop(if passed { StopKind::Abrupt } else { kind });
    }
}
