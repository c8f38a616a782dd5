//! The MCX514's S-curve acceleration/deceleration on the driving axis (SPEC §12.2); see
//! [`Mcx514SCurve`]. The ramp of each side is [`ramp`]; the rule of one cycle, [`rule`]; the
//! cycles laid out ahead with it, so that stepping replays them, [`plan`].

mod plan;
mod ramp;
mod rule;

use fixed::types::I32F32;

use super::trapezoidal::{Mcx514Parameters, PerCycle as TrapezoidPerCycle};
use crate::format::mcx514::{DecelerationJerk, Jerk};
use crate::format::CycleTime;
use crate::replay::End;
use crate::state::{Limits, ProfileGenerator, State, StopKind};
use crate::Error;
use plan::{Layout, Motion, ELSEWHERE, SLOTS};
use ramp::Ramp;
use rule::{Phase, Rule};

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

/// The MCX514's S-curve acceleration/deceleration on the driving axis (SPEC §12.2), cycle by
/// cycle: start at the initial speed SV; the rate of speed-up rises by the jerk JK per cycle up to
/// AC (if reached), holds, and falls so that the speed reaches DV with the rate at zero; cruise;
/// the slow-down mirrors it with DJ and DC down to SV; creep at SV to the finish point; stop.
///
/// Integer throughout (I32F32 raw bits): each cycle takes the largest rate, within one jerk of
/// the last, from which a ramp-down at the jerk still lands on the target speed, and once the
/// ramp-down has begun, the slack it leaves in one cycle between two of its steps (the ramp's
/// rule); so the speed reaches DV (and SV) exactly, with the rate at zero, and no cycles creep
/// at a rate below one jerk step. The move and every stop lay the cycles out ahead, as runs of
/// constant jerk (about 25 for a move), and a step replays them: three additions and a
/// countdown (SPEC §16).
///
/// When deceleration starts, as for [`Mcx514Trapezoidal`](crate::Mcx514Trapezoidal):
/// **automatic** (AC = DC and JK = DJ) on the first cycle on which the pulses left are ≤ the
/// pulses output while speeding up; **manual** at the output count DP; **disabled**: DV from
/// the first cycle to the finish point.
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
    // The per-cycle fields first.
    /// The run under way: an index into `plan.runs` (always below [`SLOTS`]).
    current: usize,
    state: State,
    /// The cycles until the next command, and the rule's state before each run.
    plan: Layout,
    profile: PerCycle,
}

/// The parameters converted to per-cycle raw I32F32 bits.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) struct PerCycle {
    /// The finish point, raw I32F32 pulses.
    finish: i64,
    initial: i64,
    drive: i64,
    /// The manual deceleration point, raw I32F32 whole pulses, held below 2³¹ pulses (every
    /// point from 2³⁰ on is past every finish point); `i64::MAX` unless manual.
    manual_point: i64,
    automatic: bool,
    disabled: bool,
    speed_up: Ramp,
    slow_down: Ramp,
}

impl Mcx514SCurve {
    /// A move from rest at position 0, with the registers converted to per-cycle values of
    /// `cycle`.
    ///
    /// # Errors
    /// As [`Mcx514Trapezoidal::new`](crate::Mcx514Trapezoidal::new) (pulses, SV above DV, the conversions); [`Error::Refused`]
    /// for automatic deceleration with AC ≠ DC or JK ≠ DJ (the chip needs a manual point then);
    /// [`Error::Underflow`] or [`Error::OutOfRange`] when `cycle` makes a jerk vanish or
    /// overflow.
    pub fn new(parameters: Mcx514ScurveParameters, cycle: CycleTime) -> Result<Self, Error> {
        // Checked and converted as the trapezoid's (everything the two share).
        let trapezoid = TrapezoidPerCycle::new(parameters.trapezoid, cycle)?;
        if trapezoid.automatic
            && parameters.jerk.to_bits() != parameters.deceleration_jerk.to_bits()
        {
            return Err(Error::Refused {
                parameter: DecelerationJerk::PARAMETER,
                reason: "to differ from the jerk with automatic deceleration (the chip needs a \
                         manual deceleration point for that)",
            });
        }
        let speed_up = Ramp::new(
            parameters.jerk.per_cycle(cycle)?.to_bits(),
            trapezoid.acceleration,
        );
        let slow_down = Ramp::new(
            parameters.deceleration_jerk.per_cycle(cycle)?.to_bits(),
            trapezoid.deceleration,
        );
        let finish = trapezoid.finish;
        let profile = PerCycle {
            finish,
            initial: trapezoid.initial,
            drive: trapezoid.drive,
            manual_point: trapezoid.manual_point,
            automatic: trapezoid.automatic,
            disabled: trapezoid.disabled,
            speed_up,
            slow_down,
        };
        let at_rest = Motion {
            position: 0,
            velocity: 0,
            acceleration: 0,
        };
        let rule = Rule::new(finish);
        let mut generator = Self {
            current: 0,
            state: State::default(),
            plan: Layout::empty(rule),
            profile,
        };
        generator.plan.lay_out(&profile, rule, at_rest);
        Ok(generator)
    }

    /// The state as the plan reads it.
    fn motion(&self) -> Motion {
        Motion {
            position: self.state.position.to_bits(),
            velocity: self.state.velocity.to_bits(),
            acceleration: self.state.acceleration.to_bits(),
        }
    }

    /// The rule's state now, between two cycles.
    fn rule(&self) -> Rule {
        self.plan
            .rule_within(&self.profile, self.current % SLOTS, self.motion())
    }

    /// The move is over: the cycle that lands (or the stop) has been stepped.
    fn complete(&self) -> bool {
        self.current >= self.plan.rest_slot
    }

    /// Lays the cycles out again from the present state, with the rule in the state `rule`.
    fn replan(&mut self, rule: Rule) {
        // A move already over keeps telling its last cycle as it was (for `limits`).
        let shown_short = self.complete() && self.plan.cut_short;
        let motion = self.motion();
        self.plan.lay_out(&self.profile, rule, motion);
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
        let landing = !rule.complete;
        let motion = self.motion();
        let (next, wanted) = rule.cycle(&self.profile, motion.position, motion.velocity);
        crate::state::advance(&mut self.state, I32F32::from_bits(next));
        self.replan(rule);
        if landing && rule.complete {
            self.plan.cut_short = wanted > next;
        }
    }
}

impl ProfileGenerator for Mcx514SCurve {
    // Inlined into each caller, as the trapezoid's.
    #[inline]
    fn step(&mut self) -> State {
        // `% SLOTS` is free (`current` < SLOTS) and spares the bounds check.
        let current = self.current % SLOTS;
        let (jerk, end) = self.plan.runs[current].take();
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
        // The identities of SPEC §5 by construction; wrapping, as the plan's sums (the values
        // reached are the rule's, in range).
        // Each field stored as it is formed and the state returned from the locals: storing a
        // built state and returning a copy of it costs a pass through the stack.
        let acceleration = I32F32::from_bits(self.state.acceleration.to_bits().wrapping_add(jerk));
        self.state.acceleration = acceleration;
        let velocity = self.state.velocity.wrapping_add(acceleration);
        self.state.velocity = velocity;
        let position = self.state.position.wrapping_add(velocity);
        self.state.position = position;
        State {
            position,
            velocity,
            acceleration,
        }
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
            StopKind::Smooth => rule.stop_smoothly(),
            StopKind::Abrupt => rule.complete = true,
        }
        self.replan(rule);
    }

    fn limits(&self) -> Limits {
        let velocity = self.state.velocity.to_bits();
        let before = velocity - self.state.acceleration.to_bits();
        // The events: the start (from rest to moving), the cut to the pulses left (the last
        // cycle stepped was the plan's last before the rest), the stop (from moving to rest).
        let cut = self.current % SLOTS == self.plan.rest_slot && self.plan.cut_short;
        let exempt = (before == 0) != (velocity == 0) || (cut && velocity != 0);
        let p = &self.profile;
        let (jerk, max_acceleration) = match self.plan.rules[self.current % SLOTS].phase {
            Phase::Decelerating | Phase::Creeping => (p.slow_down.jerk, p.slow_down.cap),
            _ => (p.speed_up.jerk, p.speed_up.cap),
        };
        Limits {
            max_velocity: Some(I32F32::from_bits(p.drive)),
            max_speed_up: Some(I32F32::from_bits(p.speed_up.cap)),
            max_slow_down: Some(I32F32::from_bits(p.slow_down.cap)),
            max_acceleration: Some(I32F32::from_bits(max_acceleration)),
            max_jerk: Some(I32F32::from_bits(jerk)),
            exempt,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::format::mcx514::{
        Acceleration, Deceleration, DriveSpeed, InitialSpeed, ManualDecelerationPoint,
    };
    use crate::replay::JerkRun;
    use crate::state::advance;
    use crate::DecelerationMode;
    use proptest::prelude::*;

    /// The rule stepped cycle by cycle, as the generator did before its cycles were laid out:
    /// the yardstick for the plan, stops included.
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

        fn stop(&mut self, kind: StopKind) {
            match kind {
                StopKind::Smooth => self.rule.stop_smoothly(),
                StopKind::Abrupt => self.rule.complete = true,
            }
        }
    }

    /// Whether the plan ran out of slots (its last leads to the slow path).
    fn out_of_slots(axis: &Mcx514SCurve) -> bool {
        axis.plan.runs[ELSEWHERE] == JerkRun::elsewhere()
    }

    /// A register drawn log-uniformly (a binary order, then a value within it) from
    /// `low ..= high` (integers: the module holds no floating point, tests included).
    fn log_uniform(low: u32, high: u32) -> impl Strategy<Value = u32> {
        (low.ilog2()..=high.ilog2())
            .prop_flat_map(move |order| (1u32 << order)..=((1u64 << (order + 1)) - 1) as u32)
            .prop_map(move |value| value.clamp(low, high))
    }

    fn stop() -> impl Strategy<Value = StopKind> {
        prop_oneof![Just(StopKind::Smooth), Just(StopKind::Abrupt)]
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(3_000))]

        /// Moves over the registers' ranges in every deceleration mode, with stops at random
        /// cycles: every cycle's state and completion the same as the rule's cycle by cycle, and
        /// every plan within its slots.
        #[test]
        fn the_plan_is_the_rule_cycle_by_cycle(
            pulses in prop_oneof![0u32..200, log_uniform(1, 1 << 30)],
            speeds in (log_uniform(1, 8_000_000), log_uniform(1, 8_000_000)),
            rates in (log_uniform(1, 536_870_911), log_uniform(1, 536_870_911)),
            jerks in (log_uniform(1, 1_073_741_823), log_uniform(1, 1_073_741_823)),
            point in log_uniform(1, 1 << 30),
            mode in 0..3u8,
            cycle in prop_oneof![Just(1e-4), Just(1e-3), Just(4e-3)],
            stops in prop::collection::vec((0u32..400, stop()), 0..3),
        ) {
            let deceleration_mode = match mode {
                0 => DecelerationMode::Automatic,
                1 => DecelerationMode::Manual(ManualDecelerationPoint::from_bits(point.min(pulses)).unwrap()),
                _ => DecelerationMode::Disabled,
            };
            let automatic = deceleration_mode == DecelerationMode::Automatic;
            let rates = if automatic { (rates.0, rates.0) } else { rates };
            let jerks = if automatic { (jerks.0, jerks.0) } else { jerks };
            let parameters = Mcx514ScurveParameters {
                trapezoid: Mcx514Parameters {
                    pulses,
                    initial_speed: InitialSpeed::from_bits(speeds.0.min(speeds.1)).unwrap(),
                    drive_speed: DriveSpeed::from_bits(speeds.0.max(speeds.1)).unwrap(),
                    acceleration: Acceleration::from_bits(rates.0).unwrap(),
                    deceleration: Deceleration::from_bits(rates.1).unwrap(),
                    deceleration_mode,
                },
                jerk: Jerk::from_bits(jerks.0).unwrap(),
                deceleration_jerk: DecelerationJerk::from_bits(jerks.1).unwrap(),
            };
            let Ok(mut axis) = Mcx514SCurve::new(parameters, CycleTime::from_seconds(cycle).unwrap()) else {
                return Ok(()); // a register that vanishes per cycle
            };
            let mut decided = Decided { profile: axis.profile, rule: Rule::new(axis.profile.finish), state: axis.state };
            prop_assert!(!out_of_slots(&axis));
            // The stops, then the move to its end (or 20,000 cycles).
            for (gap, kind) in stops.into_iter().map(|(gap, kind)| (gap, Some(kind))).chain([(20_000, None)]) {
                for cycle in 0..gap {
                    prop_assert_eq!(axis.step(), decided.step(), "cycle {}", cycle);
                    let complete = decided.rule.complete && decided.state.velocity == I32F32::ZERO;
                    prop_assert_eq!(axis.is_complete(), complete);
                    if complete {
                        break;
                    }
                }
                if let Some(kind) = kind {
                    axis.stop(kind);
                    decided.stop(kind);
                    prop_assert!(!out_of_slots(&axis));
                }
            }
        }
    }
}
