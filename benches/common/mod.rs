//! The moves the benches and the `cycle_budget` example measure, built once here so both time
//! the same thing: a 1,000,000-count move at 100 counts/cycle for every generator and peer.
#![allow(dead_code)] // each user takes what it measures

use profilegen::format::juno::{Acceleration, TargetVelocity};
use profilegen::format::mc1451a::{GearRatio, TrapezoidalAcceleration};
use profilegen::format::mc1451a::{Jerk, MaxVelocity, ScurveAcceleration};
use profilegen::format::CycleTime;
use profilegen::gearing::ElectronicGear;
use profilegen::interpolation::Line;
use profilegen::waveform::{MicrostepTable, Phases};
use profilegen::{
    DecelerationMode, Mcx514Parameters, Mcx514SCurve, Mcx514ScurveParameters, Mcx514Trapezoidal,
    ProfileGenerator, SCurve, ScurveParameters, Trapezoidal, TrapezoidalParameters,
    VelocityContouring, VelocityParameters,
};

/// Distance, counts.
pub const DISTANCE: i32 = 1_000_000;
/// Maximum velocity, counts/cycle.
pub const VELOCITY: f64 = 100.0;
/// Acceleration, counts/cycle² (trapezoid and velocity modes; S-curve maximum).
pub const ACCELERATION: f64 = 0.25;
/// S-curve maximum acceleration (16-bit register: < 0.5), counts/cycle².
pub const SCURVE_ACCELERATION: f64 = 0.4;
/// S-curve jerk, counts/cycle³.
pub const JERK: f64 = 0.001;

pub fn velocity() -> VelocityContouring {
    VelocityContouring::new(VelocityParameters {
        velocity: TargetVelocity::from_num(VELOCITY).unwrap(),
        acceleration: Acceleration::from_num(ACCELERATION).unwrap(),
        deceleration: Acceleration::ZERO,
    })
    .unwrap()
}

pub fn trapezoidal_parameters() -> TrapezoidalParameters {
    TrapezoidalParameters {
        destination: DISTANCE,
        max_velocity: TargetVelocity::from_num(VELOCITY).unwrap(),
        acceleration: Acceleration::from_num(ACCELERATION).unwrap(),
        deceleration: Acceleration::ZERO,
        start_velocity: TargetVelocity::ZERO,
    }
}

pub fn trapezoidal() -> Trapezoidal {
    Trapezoidal::new(trapezoidal_parameters()).unwrap()
}

pub fn scurve_parameters() -> ScurveParameters {
    ScurveParameters {
        destination: DISTANCE,
        max_velocity: MaxVelocity::from_num(VELOCITY).unwrap(),
        max_acceleration: ScurveAcceleration::from_num(SCURVE_ACCELERATION).unwrap(),
        jerk: Jerk::from_num(JERK).unwrap(),
    }
}

pub fn scurve() -> SCurve {
    SCurve::new(scurve_parameters()).unwrap()
}

pub fn microstep_table() -> MicrostepTable {
    MicrostepTable::new(256, Phases::Three)
        .unwrap()
        .with_current(20_000)
        .unwrap()
}

/// Reference 003's 3-axis line: finish (−20000, 30000, −50000), 50,000 steps.
pub fn manual_line() -> Line<3> {
    Line::from_pulses([-20_000, 30_000, -50_000]).unwrap()
}

/// Its MCX514 registers: SV 500 pps, DV 20,000 pps, AC = DC = 65,000 pps/s (at a 1 ms cycle 0.5
/// and 20 steps/cycle, 0.065 steps/cycle²), automatic deceleration.
fn manual_line_mcx514_parameters() -> Mcx514Parameters {
    use profilegen::format::mcx514::{Acceleration, Deceleration, DriveSpeed, InitialSpeed};
    Mcx514Parameters {
        pulses: manual_line().steps(),
        initial_speed: InitialSpeed::from_bits(500).unwrap(),
        drive_speed: DriveSpeed::from_bits(20_000).unwrap(),
        acceleration: Acceleration::from_bits(65_000).unwrap(),
        deceleration: Deceleration::from_bits(65_000).unwrap(),
        deceleration_mode: DecelerationMode::Automatic,
    }
}

/// Its MCX514 trapezoid at a 1 ms cycle ([`manual_line_mcx514_parameters`]).
pub fn manual_line_mcx514() -> Mcx514Trapezoidal {
    Mcx514Trapezoidal::new(
        manual_line_mcx514_parameters(),
        CycleTime::from_seconds(1e-3).unwrap(),
    )
    .unwrap()
}

/// The MCX514 S-curve on the same line: the same registers, JK = DJ = 650,000 pps/s² (the rate
/// reaches AC in 0.1 s).
pub fn manual_line_mcx514_scurve() -> Mcx514SCurve {
    use profilegen::format::mcx514::{DecelerationJerk, Jerk};
    Mcx514SCurve::new(
        Mcx514ScurveParameters {
            trapezoid: manual_line_mcx514_parameters(),
            jerk: Jerk::from_bits(650_000).unwrap(),
            deceleration_jerk: DecelerationJerk::from_bits(650_000).unwrap(),
        },
        CycleTime::from_seconds(1e-3).unwrap(),
    )
    .unwrap()
}

/// An MC1451A electronic gear following at 1.5 (the master's count times 3/2), decelerating at
/// 0.25 counts/cycle² when stopped, from rest at 0.
pub fn gear() -> ElectronicGear {
    ElectronicGear::new(
        GearRatio::from_num(1.5).unwrap(),
        0,
        fixed::types::I32F32::ZERO,
        TrapezoidalAcceleration::from_num(ACCELERATION).unwrap(),
    )
    .unwrap()
}

/// A copy of `generator` advanced by `cycles`.
pub fn advanced<G: ProfileGenerator + Clone>(generator: &G, cycles: u64) -> G {
    let mut copy = generator.clone();
    for _ in 0..cycles {
        copy.step();
    }
    copy
}

/// A phase of a move, told from the sign of a cycle's velocity change.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Phase {
    /// The velocity rises.
    Accelerate,
    /// The velocity stays, away from zero.
    Cruise,
    /// The velocity falls.
    Decelerate,
}

impl Phase {
    /// The phase of a cycle whose velocity changed from `before` to `after` (`None`: at rest).
    pub fn of<T: PartialOrd + Default>(before: T, after: T) -> Option<Self> {
        if after > before {
            Some(Self::Accelerate)
        } else if after < before {
            Some(Self::Decelerate)
        } else if after != T::default() {
            Some(Self::Cruise)
        } else {
            None
        }
    }
}

/// The longest run of consecutive cycles (or steps) in `phase`, given the phase of each in
/// order: `(first, length)`, first counted from 0, length capped at `cap`.
pub fn window(phases: impl Iterator<Item = Option<Phase>>, phase: Phase, cap: u64) -> (u64, u64) {
    let (mut best, mut run_start, mut run) = ((0, 0), 0, 0);
    for (i, p) in phases.enumerate() {
        if p == Some(phase) {
            if run == 0 {
                run_start = i as u64;
            }
            run += 1;
            if run > best.1 {
                best = (run_start, run);
            }
        } else {
            run = 0;
        }
    }
    (best.0, best.1.min(cap))
}

/// The window of `phase` in the move `generator` makes from its present state to completion
/// (cycle `first` is the first step taken from that state).
pub fn generator_window<G: ProfileGenerator + Clone>(
    generator: &G,
    phase: Phase,
    cap: u64,
) -> (u64, u64) {
    let mut axis = generator.clone();
    let mut before = axis.state().velocity;
    // At most 100,000 cycles: velocity contouring cruises for ever.
    let phases = (0..100_000).map_while(|_| {
        if axis.is_complete() {
            return None;
        }
        let after = axis.step().velocity;
        let p = Phase::of(before, after);
        before = after;
        Some(p)
    });
    window(phases, phase, cap)
}

/// The cycle on which the trapezoid starts to decelerate (velocity first drops).
pub fn trapezoidal_deceleration_start() -> u64 {
    let mut axis = trapezoidal();
    let mut cycle = 0;
    let mut peak = axis.state().velocity;
    while !axis.is_complete() {
        let state = axis.step();
        cycle += 1;
        if state.velocity < peak {
            return cycle - 1;
        }
        peak = state.velocity;
    }
    cycle
}

/// Peers, in per-cycle units (time unit = one cycle).
pub mod peers {
    use rsruckig::prelude::*;

    pub fn ruckig_input() -> InputParameter<1> {
        let mut input = InputParameter::new(None);
        input.current_position[0] = 0.0;
        input.target_position[0] = f64::from(super::DISTANCE);
        input.max_velocity[0] = super::VELOCITY;
        input.max_acceleration[0] = super::SCURVE_ACCELERATION;
        input.max_jerk[0] = super::JERK;
        input
    }

    pub fn ruckig() -> Ruckig<1, ThrowErrorHandler> {
        Ruckig::<1, ThrowErrorHandler>::new(None, 1.0)
    }

    /// Ruckig's whole-trajectory calculation; returns the duration.
    pub fn ruckig_plan(input: &InputParameter<1>) -> f64 {
        let mut trajectory = Trajectory::new(None);
        ruckig().calculate(input, &mut trajectory).unwrap();
        trajectory.get_duration()
    }

    pub fn s_curve_input() -> s_curve::SCurveInput {
        s_curve::SCurveInput {
            constraints: s_curve::SCurveConstraints {
                max_jerk: super::JERK,
                max_acceleration: super::SCURVE_ACCELERATION,
                max_velocity: super::VELOCITY,
            },
            start_conditions: s_curve::SCurveStartConditions {
                q0: 0.0,
                q1: f64::from(super::DISTANCE),
                v0: 0.0,
                v1: 0.0,
            },
        }
    }

    /// Steps of the peers' per-step move: 5,000 steps with ramps of 2,000 (100 steps/cycle
    /// reached at 2.5 steps/cycle²), short so that a window near its end is quick to reach.
    pub const STEPS: u32 = 5_000;
    /// The per-step move's acceleration, steps/cycle².
    pub const STEP_ACCELERATION: f64 = 2.5;

    /// stepgen's ramp for the same move in steps: a 1 MHz tick, 10,000 steps/s reached at
    /// 25,000 steps/s² (2,000 steps), stop at step 5,000. Its delays are 24.8 ticks per step.
    pub fn stepgen() -> stepgen::Stepgen {
        let mut stepgen = stepgen::Stepgen::new(1_000_000);
        stepgen.set_acceleration(25_000 << 8).unwrap();
        stepgen.set_target_speed(10_000 << 8).unwrap();
        stepgen.set_target_step(STEPS).unwrap();
        stepgen
    }

    /// ramp-maker's trapezoid in its default number type (U32F32 fixed point), steps per cycle.
    pub fn ramp_maker() -> ramp_maker::Trapezoidal<fixed::types::U32F32> {
        use fixed::types::U32F32;
        use ramp_maker::MotionProfile as _;
        let mut profile = ramp_maker::Trapezoidal::new(U32F32::from_num(super::ACCELERATION));
        profile.enter_position_mode(U32F32::from_num(super::VELOCITY), super::DISTANCE as u32);
        profile
    }

    /// ramp-maker's trapezoid for the peers' per-step move (`STEPS` steps, ramps of 2,000).
    pub fn ramp_maker_steps() -> ramp_maker::Trapezoidal<fixed::types::U32F32> {
        use fixed::types::U32F32;
        use ramp_maker::MotionProfile as _;
        let mut profile = ramp_maker::Trapezoidal::new(U32F32::from_num(STEP_ACCELERATION));
        profile.enter_position_mode(U32F32::from_num(super::VELOCITY), STEPS);
        profile
    }
}
