//! Continuous interpolation (SPEC §12.5) scripts: lines and arcs queued before the run and
//! refilled while it runs (a ninth waiting segment refused), a last segment with its manual
//! deceleration point, stops. Every cycle: the driving MCX514 trapezoid's checks, both axes
//! where the test's own account of the queue puts them (the ends of the segments passed plus the
//! present segment's point at its own step), the segment number the first whose end the step has
//! not passed; an accepted segment only when the queue had room and was open; after a stop the
//! queue empty and the run within the segment it was driving.

use profilegen::format::mcx514::{
    Acceleration, Deceleration, DriveSpeed, InitialSpeed, ManualDecelerationPoint,
};
use profilegen::format::CycleTime;
use profilegen::interpolation::continuous::CAPACITY;
use profilegen::interpolation::{
    Arc, ContinuousDriving, ContinuousInterpolation, Direction, Line, Segment,
};
use profilegen::{Error, Limits, ProfileGenerator, State, StopKind};

use super::{counts, Bytes, Scripted, Step};

/// Cycle times, seconds.
const CYCLES: [f64; 3] = [2.5e-4, 1e-3, 4e-3];

/// A segment in pulses: a line (dx, dy), or an arc around (cx, cy) to a point at an angle
/// (2^-16 turns; `None`: a full circle), counter-clockwise or not.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Spec {
    /// A line.
    Line(i32, i32),
    /// An arc.
    Arc([i32; 2], Option<u16>, bool),
}

impl Spec {
    fn segment(self) -> Result<Segment, Error> {
        Ok(match self {
            Spec::Line(x, y) => Segment::Line(Line::from_pulses([x, y])?),
            Spec::Arc(centre, angle, counter_clockwise) => {
                let [cx, cy] = centre.map(f64::from);
                let finish = angle.map_or([0, 0], |angle| {
                    let turn = f64::from(angle) / 65_536.0 * core::f64::consts::TAU;
                    let (sin, cos) = turn.sin_cos();
                    [
                        (cx - cx * cos + cy * sin).round() as i32,
                        (cy - cx * sin - cy * cos).round() as i32,
                    ]
                });
                let direction = if counter_clockwise {
                    Direction::CounterClockwise
                } else {
                    Direction::Clockwise
                };
                Segment::Arc(Arc::from_pulses(centre, finish, direction)?)
            }
        })
    }

    fn decode(bytes: &mut Bytes) -> Self {
        if bytes.byte() & 1 == 0 {
            Spec::Line(
                bytes.boosted_signed(1 << 14) as i32,
                bytes.boosted_signed(1 << 14) as i32,
            )
        } else {
            Spec::Arc(
                [0, 1].map(|_| bytes.boosted_signed(1 << 12) as i32),
                (bytes.byte() % 3 != 0).then(|| bytes.bits(2) as u16),
                bytes.byte() & 1 == 0,
            )
        }
    }
}

/// A command: queue a segment, or the last one with its deceleration point (pulses from its
/// start).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Command {
    /// `push`.
    Push(Spec),
    /// `push_last`.
    PushLast(Spec, u32),
}

/// The run, and the test's account of its queue.
#[derive(Debug, Clone, PartialEq)]
pub struct Run {
    run: ContinuousInterpolation,
    /// Every segment accepted and not abandoned, in order.
    segments: Vec<Segment>,
    /// The last accepted command was legal (room, open, not stopped).
    legal: bool,
    closed: bool,
    /// After a stop: the step the run may not pass (the end of the segment it was driving).
    stop_limit: Option<u64>,
    /// Per-cycle SV and DC, pulses, for the bounds.
    initial: f64,
    deceleration: f64,
}

impl ProfileGenerator for Run {
    fn step(&mut self) -> State {
        self.run.step().driving
    }
    fn state(&self) -> State {
        self.run.profile().state()
    }
    fn is_complete(&self) -> bool {
        self.run.is_complete()
    }
    fn stop(&mut self, kind: StopKind) {
        // The segments not yet started (still waiting) are abandoned.
        let started = self.segments.len() - self.run.waiting();
        self.segments.truncate(started);
        self.stop_limit = Some(self.ends().last().copied().unwrap_or(0));
        self.run.stop(kind);
    }
    fn limits(&self) -> Limits {
        self.run.profile().limits()
    }
}

impl Run {
    /// The cumulative ends (steps) of the segments.
    fn ends(&self) -> Vec<u64> {
        self.segments
            .iter()
            .scan(0, |end, segment| {
                *end += segment.steps();
                Some(*end)
            })
            .collect()
    }

    /// The axes by the test's account at `step`: the segment is the first whose end `step` has
    /// not passed (or the last), its origin the sum of the ends before it.
    fn expected(&self, step: u64) -> (usize, [i32; 2]) {
        let ends = self.ends();
        if self.segments.is_empty() {
            return (0, [0, 0]);
        }
        let k = ends
            .iter()
            .position(|&end| step <= end)
            .unwrap_or(self.segments.len() - 1);
        let mut origin = [0i32; 2];
        for segment in &self.segments[..k] {
            let end = segment.end();
            origin = [
                origin[0].wrapping_add(end[0]),
                origin[1].wrapping_add(end[1]),
            ];
        }
        let start = if k == 0 { 0 } else { ends[k - 1] };
        let local = step.saturating_sub(start);
        let point = match self.segments[k] {
            Segment::Line(line) => line.position_at(local.min(u64::from(u32::MAX)) as u32),
            Segment::Arc(arc) => arc.position_at(local),
        };
        (
            k,
            [
                origin[0].wrapping_add(point[0]),
                origin[1].wrapping_add(point[1]),
            ],
        )
    }
}

impl Scripted for Run {
    type Command = Command;

    fn apply(&mut self, command: &Command) -> Result<(), Error> {
        let (spec, point) = match *command {
            Command::Push(spec) => (spec, None),
            Command::PushLast(spec, point) => (spec, Some(point)),
        };
        let segment = spec.segment()?;
        let waiting = self.run.waiting();
        match point {
            None => self.run.push(segment)?,
            Some(point) => self
                .run
                .push_last(segment, ManualDecelerationPoint::from_bits(point)?)?,
        }
        self.legal = waiting < CAPACITY && !self.closed && self.stop_limit.is_none();
        self.closed |= point.is_some();
        self.segments.push(segment);
        Ok(())
    }

    /// The steps left at SV or faster; after a stop, down from the velocity at DC.
    fn settle_bound(&self, stopped: bool) -> f64 {
        let velocity = counts(self.state().velocity.to_bits());
        if stopped {
            return velocity / self.deceleration + 3.0;
        }
        let total = self.ends().last().copied().unwrap_or(0) as f64;
        let left = total - counts(self.state().position.to_bits());
        left.max(0.0) / self.initial + 3.0
    }

    fn velocity_register(&self) -> Option<i64> {
        None
    }

    fn check_command(&self) -> Result<(), String> {
        if !self.legal {
            return Err("a segment was accepted into a full, closed or stopped queue".into());
        }
        Ok(())
    }

    fn check_cycle(&self, previous: &State, _commanded: bool) -> Result<(), String> {
        let state = self.run.state();
        if state.driving.position < previous.position {
            return Err("the run went backwards".into());
        }
        let (k, axes) = self.expected(state.step);
        if !self.segments.is_empty() && (state.segment as usize != k || state.axes != axes) {
            return Err(format!(
                "segment {} at {:?}, expected segment {k} at {axes:?} (step {})",
                state.segment, state.axes, state.step
            ));
        }
        if let Some(limit) = self.stop_limit {
            if self.run.waiting() != 0 || state.step > limit {
                return Err(format!(
                    "after a stop: {} waiting, step {} past the limit {limit}",
                    self.run.waiting(),
                    state.step
                ));
            }
        }
        Ok(())
    }

    fn check_settled(&self, stopped: bool) -> Result<(), String> {
        let state = self.run.state();
        let total = self.ends().last().copied().unwrap_or(0);
        if !stopped && self.closed && state.step != total {
            return Err(format!(
                "settled at step {}, not the end {total}",
                state.step
            ));
        }
        Ok(())
    }
}

/// The run's registers, the segments queued before it starts, and the script.
#[derive(Debug, Clone)]
pub struct Script {
    /// SV, DV, AC, DC (raw), index into the cycle times.
    pub registers: (u32, u32, u32, u32, usize),
    /// Queued before the first cycle (a ninth is refused).
    pub initial: Vec<Command>,
    /// The steps.
    pub steps: Vec<Step<Command>>,
}

impl Script {
    /// Builds the run and runs the script.
    ///
    /// # Errors
    /// The first check that failed.
    pub fn run(&self, budget: u64) -> Result<u64, String> {
        let (initial, drive, acceleration, deceleration, cycle) = self.registers;
        let cycle =
            CycleTime::from_seconds(CYCLES[cycle % CYCLES.len()]).map_err(|e| e.to_string())?;
        let driving = (|| -> Result<ContinuousDriving, Error> {
            Ok(ContinuousDriving {
                initial_speed: InitialSpeed::from_bits(initial)?,
                drive_speed: DriveSpeed::from_bits(drive)?,
                acceleration: Acceleration::from_bits(acceleration)?,
                deceleration: Deceleration::from_bits(deceleration)?,
            })
        })();
        let Ok(driving) = driving else {
            return Ok(0);
        };
        let Ok(run) = ContinuousInterpolation::new(driving, cycle) else {
            return Ok(0); // SV above DV, or a register that vanishes at this cycle: documented
        };
        let per_cycle = |value: u32, power: i32| f64::from(value) * cycle.seconds().powi(power);
        let mut run = Run {
            run,
            segments: Vec::new(),
            legal: true,
            closed: false,
            stop_limit: None,
            initial: per_cycle(initial, 1),
            deceleration: per_cycle(deceleration, 2),
        };
        for command in &self.initial {
            let before = run.clone();
            if run.apply(command).is_err() && run != before {
                return Err(format!("a refused {command:?} changed the run"));
            }
            run.check_command()?;
        }
        super::run(run, &self.steps, budget)
    }

    /// Decodes a script from raw bytes (the fuzz target).
    pub fn decode(bytes: &mut Bytes) -> Self {
        let initial = bytes.boosted(DriveSpeed::MAX_BITS.into()) as u32;
        let drive = bytes.boosted(DriveSpeed::MAX_BITS.into()) as u32;
        let acceleration = bytes.boosted(Acceleration::MAX_BITS.into()) as u32;
        let deceleration = bytes.boosted(Acceleration::MAX_BITS.into()) as u32;
        let cycle = usize::from(bytes.byte());
        let command = |bytes: &mut Bytes| {
            if bytes.byte() % 4 == 0 {
                Command::PushLast(Spec::decode(bytes), bytes.bits(2) as u32)
            } else {
                Command::Push(Spec::decode(bytes))
            }
        };
        let queued = usize::from(bytes.byte() % 11);
        let initial_commands = (0..queued).map(|_| command(bytes)).collect();
        let steps = bytes.steps(|bytes| Some(command(bytes)));
        Self {
            registers: (initial, drive, acceleration, deceleration, cycle),
            initial: initial_commands,
            steps,
        }
    }
}

/// The proptest strategy: SV at or below DV mostly, short segments (runs that end within a
/// script), up to ten queued before the start.
#[cfg(test)]
pub fn script() -> impl proptest::strategy::Strategy<Value = Script> {
    use super::{boosted, boosted_signed, steps};
    use proptest::prelude::*;
    let speed = || boosted(1, DriveSpeed::MAX_BITS.into()).prop_map(|bits| bits as u32);
    let rate = || boosted(1, Acceleration::MAX_BITS.into()).prop_map(|bits| bits as u32);
    let spec = prop_oneof![
        2 => (boosted_signed(1 << 14), boosted_signed(1 << 14))
            .prop_map(|(x, y)| Spec::Line(x as i32, y as i32)),
        1 => (
            [boosted_signed(1 << 12), boosted_signed(1 << 12)],
            prop_oneof![Just(None), any::<u16>().prop_map(Some)],
            any::<bool>()
        )
            .prop_map(|(centre, angle, ccw)| Spec::Arc(centre.map(|c| c as i32), angle, ccw)),
    ];
    let command = prop_oneof![
        4 => spec.clone().prop_map(Command::Push),
        1 => (spec, boosted(0, 1 << 16)).prop_map(|(spec, point)| Command::PushLast(spec, point as u32)),
    ];
    (
        (speed(), speed(), rate(), rate(), 0..CYCLES.len()),
        prop::collection::vec(command.clone(), 0..=10),
        steps(command, 12),
    )
        .prop_map(
            |((x, y, acceleration, deceleration, cycle), initial, steps)| Script {
                registers: (x.min(y), x.max(y), acceleration, deceleration, cycle),
                initial,
                steps,
            },
        )
}
