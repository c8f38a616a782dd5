//! The MCX514's trapezoidal acceleration/deceleration on the driving axis (SPEC §12.2); see
//! [`Mcx514Trapezoidal`]. The rule of one cycle is [`rule`]; the cycles laid out ahead with
//! it, so that stepping replays them, [`plan`].

mod plan;
mod rule;

use fixed::types::I32F32;

use crate::format::mcx514::{
    Acceleration, Deceleration, DriveSpeed, FinishPoint, InitialSpeed, ManualDecelerationPoint,
};
use crate::format::CycleTime;
use crate::replay::End;
use crate::state::{advance, Limits, ProfileGenerator, State, StopKind};
use crate::Error;
use plan::{Layout, ELSEWHERE, RUNS};
use rule::{Phase, Rule};

/// When the driving axis starts to decelerate (SPEC §12.2).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum DecelerationMode {
    /// When the pulses left are ≤ the pulses output while accelerating; needs AC = DC.
    Automatic,
    /// When the output count reaches the manual deceleration point.
    Manual(ManualDecelerationPoint),
    /// Deceleration disabled (the chip's state at reset): constant speed DV, no ramps.
    Disabled,
}

/// The parameters of an MCX514 trapezoidal move of the driving axis, in the chip's registers.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Mcx514Parameters {
    /// Pulses the driving axis outputs: for a linear interpolation, the long axis's
    /// ([`Line::steps`](crate::interpolation::Line::steps)); 0 … 1,073,741,823.
    pub pulses: u32,
    /// Initial speed SV, pps: the start, and the floor of the deceleration.
    pub initial_speed: InitialSpeed,
    /// Drive speed DV, pps, ≥ SV.
    pub drive_speed: DriveSpeed,
    /// Acceleration AC, pps/s.
    pub acceleration: Acceleration,
    /// Deceleration DC, pps/s.
    pub deceleration: Deceleration,
    /// When deceleration starts.
    pub deceleration_mode: DecelerationMode,
}

/// The parameters converted to per-cycle raw I32F32 bits.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) struct PerCycle {
    /// The finish point, raw I32F32 pulses.
    pub(in crate::mcx514) finish: i64,
    pub(in crate::mcx514) initial: i64,
    pub(in crate::mcx514) drive: i64,
    pub(in crate::mcx514) acceleration: i64,
    pub(in crate::mcx514) deceleration: i64,
    /// DV − AC (may be negative): a cycle that begins below it speeds up by AC and stays below
    /// DV, so the sum is never formed where it could pass i64 (AC alone can come near 2⁶³ raw).
    below_last_speed_up: i64,
    /// The manual deceleration point, raw I32F32 whole pulses, held below 2³¹ pulses (every
    /// point from 2³⁰ on is past every finish point, so never reached); `i64::MAX` unless manual.
    pub(in crate::mcx514) manual_point: i64,
    pub(in crate::mcx514) automatic: bool,
    pub(in crate::mcx514) disabled: bool,
    /// max(DC, SV): a larger drop in one cycle is exempt (a late finish, an abrupt stop).
    largest_drop: i64,
}

impl PerCycle {
    /// The registers checked and converted to per-cycle values of `cycle` (shared with the
    /// S-curve, which adds its jerks). Errors as [`Mcx514Trapezoidal::new`].
    pub(super) fn new(parameters: Mcx514Parameters, cycle: CycleTime) -> Result<Self, Error> {
        if parameters.pulses > FinishPoint::MAX_BITS as u32 {
            return Err(Error::out_of_range_bits(
                FinishPoint::PARAMETER,
                i64::from(parameters.pulses),
                0,
                FinishPoint::RANGE,
            ));
        }
        // In range, so the cast is exact.
        let finish = FinishPoint::from_bits(parameters.pulses as i32)?;
        let (initial, drive) = (parameters.initial_speed, parameters.drive_speed);
        if initial.to_bits() > drive.to_bits() {
            return Err(Error::out_of_range_bits(
                InitialSpeed::PARAMETER,
                i64::from(initial.to_bits()),
                0,
                InitialSpeed::RANGE.up_to_bits(i64::from(drive.to_bits()), 0),
            ));
        }
        let automatic = parameters.deceleration_mode == DecelerationMode::Automatic;
        if automatic && parameters.acceleration.to_bits() != parameters.deceleration.to_bits() {
            return Err(Error::Refused {
                parameter: Deceleration::PARAMETER,
                reason: "to differ from the acceleration with automatic deceleration (the chip \
                         needs a manual deceleration point for that)",
            });
        }
        let manual_point = match parameters.deceleration_mode {
            // Past 2³¹ − 1 pulses the shift would leave i64; such a point is never reached.
            DecelerationMode::Manual(point) => {
                i64::from(point.to_bits().min(i32::MAX as u32)) << 32
            }
            _ => i64::MAX,
        };
        let finish = i64::from(finish.to_bits()) << 32;
        // Converted in the registers' order, so the first bad one is the one reported.
        let initial = initial.per_cycle(cycle)?.to_bits();
        let drive = drive.per_cycle(cycle)?.to_bits();
        let acceleration = parameters.acceleration.per_cycle(cycle)?.to_bits();
        let deceleration = parameters.deceleration.per_cycle(cycle)?.to_bits();
        Ok(PerCycle {
            finish,
            initial,
            drive,
            acceleration,
            deceleration,
            below_last_speed_up: drive - acceleration,
            manual_point,
            automatic,
            disabled: parameters.deceleration_mode == DecelerationMode::Disabled,
            largest_drop: deceleration.max(initial),
        })
    }
}

/// The MCX514's trapezoidal acceleration/deceleration on the driving axis (SPEC §12.2), cycle by
/// cycle: start at the initial speed SV, accelerate by AC up to the drive speed DV, cruise,
/// decelerate by DC down to SV, keep outputting at SV until the finish point, stop.
///
/// The position counts interpolation steps (the driving axis's output pulses), so the generator
/// drives a geometry ([`Line::drive`](crate::interpolation::Line::drive)).
///
/// When deceleration starts:
/// - **automatic** (AC = DC, as on the chip): on the first cycle on which the pulses still to
///   output are ≤ the pulses output while accelerating (the start at SV included);
/// - **manual**: on the first cycle that begins with the output count (the integer part of the
///   position) at or past the manual deceleration point DP. A DP too early leaves a stretch at SV
///   (the chip's creep); one too late reaches the finish point above SV and stops there at once —
///   a drop exempt from the rate limits, like an abrupt stop (SPEC §9);
/// - **disabled** (the chip's default, command 6Eh): no acceleration either; the move runs at DV
///   from the first cycle to the finish point and stops there (exempt, as above).
///
/// Every cycle's velocity is at most the pulses left, so the move lands exactly on the finish
/// point; the cycle after, the velocity drops to zero. A smooth stop decelerates by DC to SV and
/// stops from there (the chip's decelerating stop); an abrupt stop drops to zero on the next
/// cycle. The S-curve is [`Mcx514SCurve`](crate::Mcx514SCurve).
///
/// The move and every command (a stop, a new finish point of a continuous interpolation) lay
/// the cycles out ahead, as at most 13 runs of constant velocity change, and a step replays
/// them: one addition and a countdown (SPEC §16).
///
/// ```
/// use profilegen::format::mcx514::{Acceleration, Deceleration, DriveSpeed, InitialSpeed};
/// use profilegen::format::CycleTime;
/// use profilegen::{DecelerationMode, Mcx514Parameters, Mcx514Trapezoidal, ProfileGenerator};
///
/// // At 1 ms: SV 2 pulses/cycle, DV 10, AC = DC = 2 pulses/cycle², 100 pulses.
/// let mut axis = Mcx514Trapezoidal::new(
///     Mcx514Parameters {
///         pulses: 100,
///         initial_speed: InitialSpeed::from_bits(2_000)?,
///         drive_speed: DriveSpeed::from_bits(10_000)?,
///         acceleration: Acceleration::from_bits(2_000_000)?,
///         deceleration: Deceleration::from_bits(2_000_000)?,
///         deceleration_mode: DecelerationMode::Automatic,
///     },
///     CycleTime::from_seconds(1e-3)?,
/// )?;
/// let last = axis.states_until_complete().last().unwrap();
/// assert_eq!(last.position, 100);
/// # Ok::<(), profilegen::Error>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Mcx514Trapezoidal {
    // The per-cycle fields first.
    /// The run under way: an index into `plan.runs` (always below [`RUNS`]).
    current: usize,
    state: State,
    /// The cycles until the next command, and the rule's state before each run.
    plan: Layout,
    profile: PerCycle,
}

impl Mcx514Trapezoidal {
    /// A move from rest at position 0, with the registers converted to per-cycle values of
    /// `cycle` ([`per_cycle`](crate::format::mcx514::DriveSpeed::per_cycle)).
    ///
    /// # Errors
    /// [`Error::OutOfRange`] for `pulses` beyond 1,073,741,823 (parameter `finish point`) or an
    /// initial speed above the drive speed; [`Error::Refused`] for automatic deceleration with
    /// AC ≠ DC (the chip needs a manual deceleration point then); the conversions' errors
    /// ([`Error::Underflow`], [`Error::OutOfRange`]) when `cycle` makes a register vanish or
    /// overflow.
    pub fn new(parameters: Mcx514Parameters, cycle: CycleTime) -> Result<Self, Error> {
        let profile = PerCycle::new(parameters, cycle)?;
        let (finish, automatic) = (profile.finish, profile.automatic);
        let rule = Rule {
            phase: Phase::Start,
            // While speeding up (automatic): 2p ≥ finish, i.e. p ≥ ⌈finish/2⌉.
            trigger: if automatic {
                (finish + 1) >> 1
            } else {
                profile.manual_point
            },
            stopping: false,
            complete: finish == 0,
        };
        Ok(Self {
            current: 0,
            state: State::default(),
            plan: Layout::new(&profile, rule, 0, 0),
            profile,
        })
    }

    /// Continuous interpolation (SPEC §12.5): moves the finish point to `pulses` (≥ the pulses
    /// output so far) and the manual deceleration point to `manual_point` (`None`: none yet, so
    /// no deceleration until one is given), while the move runs. Returns `false`, changing
    /// nothing, once the move has ended (it reached its finish point, or was stopped after it
    /// started), or for a move with automatic deceleration or deceleration disabled (continuous
    /// runs are built with a manual point); a move that has not started yet may be given its
    /// first finish point.
    pub(crate) fn continue_to(&mut self, pulses: u32, manual_point: Option<u32>) -> bool {
        let finish = i64::from(pulses) << 32;
        let position = self.state.position.to_bits();
        let moved = position != 0 || self.state.velocity != I32F32::ZERO;
        let mut rule = self.rule();
        if (rule.complete && moved)
            || rule.stopping
            || finish < position
            || self.profile.automatic
            || self.profile.disabled
        {
            return false;
        }
        // As in `new`: a point past 2³¹ − 1 pulses is never reached.
        let point = manual_point.map_or(i64::MAX, |point| {
            i64::from(point.min(i32::MAX as u32)) << 32
        });
        self.profile.finish = finish;
        self.profile.manual_point = point;
        // Decelerating or creeping, the trigger stays i64::MAX.
        if !matches!(rule.phase, Phase::Decelerating | Phase::Creeping) {
            rule.trigger = point;
        }
        rule.complete = finish == position;
        self.replan(rule);
        true
    }

    /// The rule's state now, between two cycles: the one before the current run's first cycle,
    /// which a run's cycles leave as it was.
    fn rule(&self) -> Rule {
        self.plan.rules[self.current % RUNS]
    }

    /// The move is over: the cycle that lands (or the stop) has been stepped.
    fn complete(&self) -> bool {
        self.current >= self.plan.rest_slot
    }

    /// Lays the cycles out again from the present state, with the rule in the state `rule`.
    fn replan(&mut self, rule: Rule) {
        // A move already over keeps telling its last cycle as it was (for `limits`).
        let shown_short = self.complete() && self.plan.cut_short;
        let (position, velocity) = (self.state.position.to_bits(), self.state.velocity.to_bits());
        self.plan = Layout::new(&self.profile, rule, position, velocity);
        if self.plan.rest_slot == 0 {
            self.plan.cut_short = shown_short;
        }
        self.current = 0;
    }

    /// The cycle of slot [`ELSEWHERE`] (a plan out of slots): taken by the rule, then a new plan.
    #[cold]
    #[inline(never)]
    fn step_otherwise(&mut self) {
        let mut rule = self.plan.rules[ELSEWHERE];
        let (position, velocity) = (self.state.position.to_bits(), self.state.velocity.to_bits());
        let (next, wanted) = rule.cycle(&self.profile, position, velocity);
        advance(&mut self.state, I32F32::from_bits(next));
        self.replan(rule);
        if rule.complete {
            self.plan.cut_short = wanted > next;
        }
    }
}

impl ProfileGenerator for Mcx514Trapezoidal {
    // Inlined into each caller: called from several interpolations, it would otherwise stay an
    // out-of-line call returning the whole state through memory.
    #[inline]
    fn step(&mut self) -> State {
        // `% RUNS` is free (`current` < RUNS) and spares the bounds check.
        let current = self.current % RUNS;
        let (velocity, end) = self.plan.runs[current].take();
        match end {
            End::No => {}
            // The run's last cycle: the next run is already laid out.
            End::Run => self.current = current + 1,
            End::Lap if current == ELSEWHERE => {
                // Returns nothing: a state returned from a call out of line needs a stack slot
                // in every caller, set up on every cycle.
                self.step_otherwise();
                return self.state;
            }
            End::Lap => self.plan.runs[current].lap(),
        }
        advance(&mut self.state, I32F32::from_bits(velocity))
    }

    fn state(&self) -> State {
        self.state
    }

    fn is_complete(&self) -> bool {
        self.complete() && self.state.velocity == I32F32::ZERO
    }

    fn stop(&mut self, kind: StopKind) {
        let mut rule = self.rule();
        match kind {
            StopKind::Smooth => {
                rule.stopping = true;
                rule.decelerate();
            }
            StopKind::Abrupt => rule.complete = true,
        }
        self.replan(rule);
    }

    fn limits(&self) -> Limits {
        let p = &self.profile;
        let (velocity, acceleration) = (
            self.state.velocity.to_bits(),
            self.state.acceleration.to_bits(),
        );
        let before = velocity - acceleration;
        // The ends of the move: the cycle cut to the pulses left (below the velocity the rule
        // wanted: the last cycle stepped was the plan's last before rest), and the stop to zero.
        let cut =
            velocity == 0 || (self.current % RUNS == self.plan.rest_slot && self.plan.cut_short);
        // From rest the first cycle jumps to SV (to DV with deceleration disabled).
        let speed_up = if before == 0 {
            if p.disabled {
                p.drive
            } else {
                p.initial
            }
        } else {
            p.acceleration
        };
        Limits {
            max_velocity: Some(I32F32::from_bits(p.drive)),
            max_speed_up: Some(I32F32::from_bits(speed_up)),
            // DC on the ramp; at the ends (the cut to the pulses left, the stop) up to SV.
            max_slow_down: Some(I32F32::from_bits(if cut {
                p.deceleration.max(p.initial)
            } else {
                p.deceleration
            })),
            max_acceleration: None,
            max_jerk: None,
            // A drop beyond both DC and SV only happens at a late finish or an abrupt stop.
            exempt: -acceleration > p.largest_drop,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::format::mcx514::ManualDecelerationPoint;
    use proptest::prelude::*;

    /// The rule stepped cycle by cycle, as the generator did before its cycles were laid out:
    /// the yardstick for the plan, commands included.
    struct Decided {
        profile: PerCycle,
        rule: Rule,
        state: State,
    }

    impl Decided {
        fn step(&mut self) -> State {
            let (position, velocity) =
                (self.state.position.to_bits(), self.state.velocity.to_bits());
            let (next, _) = self.rule.cycle(&self.profile, position, velocity);
            advance(&mut self.state, I32F32::from_bits(next))
        }

        /// As `continue_to` was.
        fn continue_to(&mut self, pulses: u32, manual_point: Option<u32>) -> bool {
            let finish = i64::from(pulses) << 32;
            let position = self.state.position.to_bits();
            let moved = position != 0 || self.state.velocity != I32F32::ZERO;
            if (self.rule.complete && moved)
                || self.rule.stopping
                || finish < position
                || self.profile.automatic
                || self.profile.disabled
            {
                return false;
            }
            let point = manual_point.map_or(i64::MAX, |point| {
                i64::from(point.min(i32::MAX as u32)) << 32
            });
            self.profile.finish = finish;
            self.profile.manual_point = point;
            if !matches!(self.rule.phase, Phase::Decelerating | Phase::Creeping) {
                self.rule.trigger = point;
            }
            self.rule.complete = finish == position;
            true
        }

        fn stop(&mut self, kind: StopKind) {
            match kind {
                StopKind::Smooth => {
                    self.rule.stopping = true;
                    self.rule.decelerate();
                }
                StopKind::Abrupt => self.rule.complete = true,
            }
        }
    }

    /// A command between two cycles.
    #[derive(Debug, Clone, Copy)]
    enum Command {
        /// More pulses (a fraction of what was given so far, or a few) and a new point.
        Continue {
            more: u32,
            point: Option<u32>,
        },
        Stop(StopKind),
    }

    fn command() -> impl Strategy<Value = Command> {
        prop_oneof![
            4 => (prop_oneof![0u32..10, 0u32..100_000], prop::option::of(0u32..200_000))
                .prop_map(|(more, point)| Command::Continue { more, point }),
            1 => Just(Command::Stop(StopKind::Smooth)),
            1 => Just(Command::Stop(StopKind::Abrupt)),
        ]
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(3_000))]

        /// Runs of a continuous interpolation (manual deceleration, finish points moved on in
        /// motion) and stops, at whole and fractional speeds: every cycle's state and completion
        /// the same as the rule's cycle by cycle.
        #[test]
        fn the_plan_is_the_rule_cycle_by_cycle(
            pulses in 0u32..50_000,
            speeds in (1u32..100_000, 1u32..100_000),
            rates in (1u32..5_000_000, 1u32..5_000_000),
            point in prop::option::of(0u32..60_000),
            mode in 0..3u8,
            commands in prop::collection::vec((0u32..300, command()), 0..6),
        ) {
            let deceleration_mode = match (mode, point) {
                (0, _) => DecelerationMode::Automatic,
                (1, Some(point)) => DecelerationMode::Manual(ManualDecelerationPoint::from_bits(point).unwrap()),
                _ => DecelerationMode::Disabled,
            };
            let rates = if deceleration_mode == DecelerationMode::Automatic { (rates.0, rates.0) } else { rates };
            let parameters = Mcx514Parameters {
                pulses,
                initial_speed: InitialSpeed::from_bits(speeds.0.min(speeds.1)).unwrap(),
                drive_speed: DriveSpeed::from_bits(speeds.0.max(speeds.1)).unwrap(),
                acceleration: Acceleration::from_bits(rates.0).unwrap(),
                deceleration: Deceleration::from_bits(rates.1).unwrap(),
                deceleration_mode,
            };
            let cycle = CycleTime::from_seconds(1e-3).unwrap();
            let mut axis = Mcx514Trapezoidal::new(parameters, cycle).unwrap();
            let mut decided = Decided { profile: axis.profile, rule: axis.rule(), state: axis.state };
            let mut given = pulses;
            for (gap, command) in commands.into_iter().chain([(20_000, Command::Stop(StopKind::Smooth))]) {
                for cycle in 0..gap {
                    prop_assert_eq!(axis.step(), decided.step(), "cycle {}", cycle);
                    prop_assert_eq!(axis.is_complete(), decided.rule.complete && decided.state.velocity == I32F32::ZERO);
                }
                match command {
                    Command::Continue { more, point } => {
                        let pulses = given.saturating_add(more).min(1_000_000);
                        let continued = axis.continue_to(pulses, point);
                        prop_assert_eq!(continued, decided.continue_to(pulses, point));
                        if continued {
                            given = pulses;
                        }
                    }
                    Command::Stop(kind) => {
                        axis.stop(kind);
                        decided.stop(kind);
                    }
                }
            }
        }
    }
}
