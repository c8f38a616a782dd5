//! Circular interpolation (SPEC §12.4) scripts: an arc (a full circle or to a finish point on
//! it, either direction, radii from 1 pulse to 2³⁰) driven by a trapezoidal profile (its whole
//! command surface in motion, destinations past either end of the arc included) or by the MCX514
//! trapezoid (runs and stops). Every cycle: the driving profile's own checks, every point within
//! ±1 LSB of the true circle (exact, i128), at most one pulse per axis per step, and on the arc's
//! end once the profile is there. With the MCX514 driver, `Arc::mcx514_profile` is asked for
//! the arc's profile first, with or without jerks: refused for a jerk (S-curve driving),
//! automatic deceleration or an arc of more than 2³⁰ − 1 steps, naming the parameter; else the
//! trapezoid over the arc's steps.

use profilegen::format::mcx514::{DecelerationJerk, FinishPoint, Jerk};
use profilegen::interpolation::{Arc, CircleState, CircularDriving, Direction};
use profilegen::{
    DecelerationMode, Error, Limits, Mcx514Parameters, Mcx514Trapezoidal, ProfileGenerator, State,
    StopKind,
};

use super::{mcx514, trapezoidal, Bytes, Scripted, Step};

/// A generator driving an arc: stepped the way `Arc::drive` steps it (a drive made afresh each
/// cycle, so both of the walk's paths run).
#[derive(Debug, Clone, PartialEq)]
pub struct Driven<G> {
    arc: Arc,
    generator: G,
    /// The interpolation's state before the last cycle and after it.
    previous: CircleState,
    last: CircleState,
}

impl<G: Scripted> Driven<G> {
    /// `generator` driving `arc` from where it stands.
    pub fn new(arc: Arc, mut generator: G) -> Self {
        let last = arc.drive(&mut generator).state();
        Self {
            arc,
            generator,
            previous: last,
            last,
        }
    }
}

impl<G: Scripted> ProfileGenerator for Driven<G> {
    fn step(&mut self) -> State {
        self.previous = self.last;
        self.last = self.arc.drive(&mut self.generator).step();
        self.last.driving
    }
    fn state(&self) -> State {
        self.generator.state()
    }
    fn is_complete(&self) -> bool {
        self.generator.is_complete()
    }
    fn stop(&mut self, kind: StopKind) {
        self.arc.drive(&mut self.generator).stop(kind);
    }
    fn limits(&self) -> Limits {
        self.generator.limits()
    }
}

/// Whether `point` (relative to the start) lies within ±1 pulse of the circle around `centre`
/// through the start: (r − 1)² ≤ d² ≤ (r + 1)², r = √R², squared out to integers (i128).
fn on_circle(centre: [i32; 2], point: [i32; 2]) -> bool {
    let [cx, cy] = centre.map(i128::from);
    let [px, py] = point.map(i128::from);
    let r2 = cx * cx + cy * cy;
    let d2 = (px - cx) * (px - cx) + (py - cy) * (py - cy);
    // d² ≤ r² + 2r + 1 ⇔ d² − r² − 1 ≤ 2r; d² ≥ r² − 2r + 1 ⇔ r² + 1 − d² ≤ 2r.
    let within = |lhs: i128| lhs <= 0 || lhs * lhs <= 4 * r2;
    within(d2 - r2 - 1) && within(r2 + 1 - d2)
}

impl<G: Scripted> Scripted for Driven<G> {
    type Command = G::Command;

    scripted_as_its_generator!(generator);

    fn check_cycle(&self, previous: &State, commanded: bool) -> Result<(), String> {
        self.generator.check_cycle(previous, commanded)?;
        let (before, after) = (&self.previous, &self.last);
        if after.driving != self.generator.state() {
            return Err("the interpolation's driving state is not the profile's".into());
        }
        let steps = self.arc.steps();
        // The step is the driving position's integer part (a floor), held within 0 … steps.
        let step = (after.driving.position.to_bits() >> 32).clamp(0, steps as i64) as u64;
        if after.step != step {
            return Err(format!(
                "step {} at position {}",
                after.step, after.driving.position
            ));
        }
        if !on_circle(self.arc.centre(), after.axes) {
            return Err(format!(
                "{:?} over 1 pulse off the circle around {:?} at step {step}",
                after.axes,
                self.arc.centre()
            ));
        }
        let moved = step.abs_diff(before.step);
        for axis in 0..2 {
            let change = i64::from(after.axes[axis]) - i64::from(before.axes[axis]);
            if change.unsigned_abs() > moved {
                return Err(format!("axis {axis} moved {change} over {moved} steps"));
            }
        }
        if step == steps && after.axes != self.arc.end() {
            return Err(format!(
                "at step {steps} (the end) with the axes at {:?}, not {:?}",
                after.axes,
                self.arc.end()
            ));
        }
        if step == 0 && after.axes != [0, 0] {
            return Err(format!("at step 0 with the axes at {:?}", after.axes));
        }
        Ok(())
    }

    fn check_settled(&self, stopped: bool) -> Result<(), String> {
        self.generator.check_settled(stopped)
    }
}

/// The profile driving the arc, with its own script.
#[derive(Debug, Clone)]
pub enum Driver {
    /// A trapezoidal move (its destination: the arc's steps plus the overshoot).
    Trapezoidal(trapezoidal::Script),
    /// An MCX514 drive (its pulses are the arc's steps).
    Mcx514(mcx514::Script),
}

/// An arc and the script of the profile that drives it.
#[derive(Debug, Clone)]
pub struct Script {
    /// The centre relative to the start, pulses.
    pub centre: [i32; 2],
    /// The finish point: `None` for a full circle, else the angle (of 2^16 turns from the start)
    /// of a point on the circle, rounded.
    pub finish: Option<u16>,
    /// Counter-clockwise.
    pub counter_clockwise: bool,
    /// Counts past the arc's end (or before it, negative) for a trapezoid's destination.
    pub overshoot: i64,
    /// The driver.
    pub driver: Driver,
    /// JK and DJ (raw) asked of `Arc::mcx514_profile` with the MCX514 driver (refused if any).
    pub jerks: (Option<u32>, Option<u32>),
}

/// `Arc::mcx514_profile` with `driving`: refused for a jerk (JK named first), automatic
/// deceleration or more than 2³⁰ − 1 steps, each naming its parameter; else exactly the
/// trapezoid of `registers` over the arc's steps.
fn check_profile(
    arc: &Arc,
    registers: Mcx514Parameters,
    jerks: (Option<u32>, Option<u32>),
    cycle: profilegen::format::CycleTime,
) -> Result<(), String> {
    let (Ok(jerk), Ok(deceleration_jerk)) = (
        jerks.0.map(Jerk::from_bits).transpose(),
        jerks.1.map(DecelerationJerk::from_bits).transpose(),
    ) else {
        return Ok(()); // a jerk out of its range: not a register
    };
    let driving = CircularDriving {
        initial_speed: registers.initial_speed,
        drive_speed: registers.drive_speed,
        acceleration: registers.acceleration,
        deceleration: registers.deceleration,
        jerk,
        deceleration_jerk,
        deceleration_mode: registers.deceleration_mode,
    };
    // `&self` on a `Copy` arc: a refusal cannot change it (nothing else is given).
    let result = arc.mcx514_profile(driving, cycle);
    let refused = if jerk.is_some() {
        Some(Jerk::PARAMETER)
    } else if deceleration_jerk.is_some() {
        Some(DecelerationJerk::PARAMETER)
    } else if registers.deceleration_mode == DecelerationMode::Automatic {
        Some("deceleration point")
    } else if arc.steps() > u64::from(FinishPoint::MAX_BITS as u32) {
        Some("arc steps")
    } else {
        None
    };
    match (refused, result) {
        (Some(expected), Err(Error::Refused { parameter, .. }))
            if parameter == expected && expected != "arc steps" =>
        {
            Ok(())
        }
        (
            Some("arc steps"),
            Err(Error::OutOfRange {
                parameter: "arc steps",
                ..
            }),
        ) => Ok(()),
        (None, result) => {
            let pulses = arc.steps() as u32;
            let expected = Mcx514Trapezoidal::new(
                Mcx514Parameters {
                    pulses,
                    ..registers
                },
                cycle,
            );
            if result == expected {
                Ok(())
            } else {
                Err(format!(
                    "mcx514_profile gave {result:?}, expected {expected:?}"
                ))
            }
        }
        (expected, result) => Err(format!(
            "mcx514_profile gave {result:?}, expected a refusal naming {expected:?}"
        )),
    }
}

impl Script {
    /// The arc: `None` when refused (a radius past the position range, a rounded finish point
    /// off the path), as documented.
    fn arc(&self) -> Option<Arc> {
        let [cx, cy] = self.centre.map(f64::from);
        let finish = match self.finish {
            None => [0, 0],
            Some(angle) => {
                // The start is at angle φ0 around the centre; the finish φ0 ± the fraction.
                let turn = f64::from(angle) / 65_536.0 * core::f64::consts::TAU;
                let (sin, cos) = turn.sin_cos();
                // Rotate the start (−c) about the centre by the angle, counter-clockwise.
                let (sx, sy) = (-cx, -cy);
                [
                    (cx + sx * cos - sy * sin).round() as i32,
                    (cy + sx * sin + sy * cos).round() as i32,
                ]
            }
        };
        let direction = if self.counter_clockwise {
            Direction::CounterClockwise
        } else {
            Direction::Clockwise
        };
        Arc::from_pulses(self.centre, finish, direction).ok()
    }

    /// Builds the arc and its driver and runs the script.
    ///
    /// # Errors
    /// The first check that failed.
    pub fn run(&self, budget: u64) -> Result<u64, String> {
        let Some(arc) = self.arc() else {
            return Ok(0);
        };
        let steps = arc.steps() as i64;
        match &self.driver {
            Driver::Trapezoidal(script) => {
                let mut script = script.clone();
                let target =
                    (steps + self.overshoot).clamp(i32::MIN.into(), i32::MAX.into()) as i32;
                script.parameters.0 = trapezoidal::Target::Absolute(target);
                drive(arc, script.build()?, &script.steps, budget)
            }
            Driver::Mcx514(script) => {
                if let Some((registers, cycle)) = script.registers()? {
                    check_profile(&arc, registers, self.jerks, cycle)?;
                }
                let mut script = script.clone();
                let Ok(pulses) = u32::try_from(steps) else {
                    return Ok(0);
                };
                script.parameters.0 = pulses;
                drive(arc, script.build()?, &script.steps, budget)
            }
        }
    }

    /// Decodes a script from raw bytes (the fuzz target).
    pub fn decode(bytes: &mut Bytes) -> Self {
        let centre = [0, 1].map(|_| bytes.boosted_signed((1 << 30) - 1) as i32);
        let finish = match bytes.byte() % 3 {
            0 => None,
            _ => Some(bytes.bits(2) as u16),
        };
        let counter_clockwise = bytes.byte() & 1 == 0;
        let overshoot = if bytes.byte() & 3 == 0 {
            bytes.boosted_signed(1 << 12)
        } else {
            0
        };
        let driver = match bytes.byte() % 2 {
            0 => Driver::Trapezoidal(trapezoidal::Script::decode(bytes)),
            _ => Driver::Mcx514(mcx514::Script::decode(bytes)),
        };
        let mut jerk =
            || (bytes.byte() % 4 == 0).then(|| bytes.boosted(Jerk::MAX_BITS.into()) as u32);
        let jerks = (jerk(), jerk());
        Self {
            centre,
            finish,
            counter_clockwise,
            overshoot,
            driver,
            jerks,
        }
    }
}

fn drive<G: Scripted>(
    arc: Arc,
    generator: Option<G>,
    steps: &[Step<G::Command>],
    budget: u64,
) -> Result<u64, String> {
    match generator {
        Some(generator) => super::run(Driven::new(arc, generator), steps, budget),
        None => Ok(0),
    }
}

/// The proptest strategy: small radii mostly (whole circles within a script's budget), any up
/// to 2³⁰; the trapezoid starting near the arc's start.
#[cfg(test)]
pub fn script() -> impl proptest::strategy::Strategy<Value = Script> {
    use super::{boosted, boosted_signed};
    use fixed::types::I32F32;
    use proptest::prelude::*;
    let near_start =
        prop_oneof![Just(0i64), -(1i64 << 33)..(1i64 << 33)].prop_map(I32F32::from_bits);
    let driver = prop_oneof![
        (trapezoidal::script(), near_start).prop_map(|(mut script, position)| {
            script.position = position;
            Driver::Trapezoidal(script)
        }),
        mcx514::script().prop_map(Driver::Mcx514),
    ];
    let coordinate = prop_oneof![
        3 => boosted_signed(1 << 10),
        2 => boosted_signed(1 << 16),
        1 => boosted_signed((1 << 30) - 1),
    ]
    .prop_map(|c| c as i32);
    let jerk = || prop_oneof![3 => Just(None), 1 => boosted(0, Jerk::MAX_BITS.into()).prop_map(|bits| Some(bits as u32))];
    (
        [coordinate.clone(), coordinate],
        prop_oneof![1 => Just(None), 2 => any::<u16>().prop_map(Some)],
        any::<bool>(),
        prop_oneof![3 => Just(0i64), 1 => boosted_signed(1 << 12)],
        driver,
        (jerk(), jerk()),
    )
        .prop_map(
            |(centre, finish, counter_clockwise, overshoot, driver, jerks)| Script {
                centre,
                finish,
                counter_clockwise,
                overshoot,
                driver,
                jerks,
            },
        )
}
