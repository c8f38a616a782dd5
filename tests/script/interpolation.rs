//! Linear interpolation (SPEC §12.3) scripts: a 2–4 axis line driven by a trapezoidal, S-curve
//! or MCX514 profile whose whole command surface runs in motion (destinations past either end of
//! the line included: the axes hold at the nearer end). Every cycle: the driving profile's own
//! checks, and every axis within ±½ pulse of the ideal line at the step reached (exact, i128),
//! never more than one pulse per step, never backwards.

use profilegen::interpolation::{InterpolationState, Line};
use profilegen::{Error, Limits, ProfileGenerator, State, StopKind};

use super::{mcx514, scurve, trapezoidal, Bytes, Scripted, Step};

/// A generator driving a line: stepped the way `Line::drive` steps it.
#[derive(Debug, Clone, PartialEq)]
pub struct Driven<G, const N: usize> {
    line: Line<N>,
    generator: G,
    /// The interpolation's state before the last cycle and after it.
    previous: InterpolationState<N>,
    last: InterpolationState<N>,
}

impl<G: Scripted, const N: usize> Driven<G, N> {
    /// `generator` driving `line` from where it stands.
    pub fn new(line: Line<N>, mut generator: G) -> Self {
        let last = line.drive(&mut generator).state();
        Self {
            line,
            generator,
            previous: last,
            last,
        }
    }
}

impl<G: Scripted, const N: usize> ProfileGenerator for Driven<G, N> {
    fn step(&mut self) -> State {
        // A drive made afresh each cycle jumps its walk to the present step, then steps: both
        // of `Walk::advance_to`'s paths, every cycle (the walk is a function of the step).
        self.previous = self.last;
        self.last = self.line.drive(&mut self.generator).step();
        self.last.driving
    }
    fn state(&self) -> State {
        self.generator.state()
    }
    fn is_complete(&self) -> bool {
        self.generator.is_complete()
    }
    fn stop(&mut self, kind: StopKind) {
        self.line.drive(&mut self.generator).stop(kind);
    }
    fn limits(&self) -> Limits {
        self.generator.limits()
    }
}

impl<G: Scripted, const N: usize> Scripted for Driven<G, N> {
    type Command = G::Command;

    scripted_as_its_generator!(generator);

    fn check_cycle(&self, previous: &State, commanded: bool) -> Result<(), String> {
        self.generator.check_cycle(previous, commanded)?;
        let (before, after) = (&self.previous, &self.last);
        if after.driving != self.generator.state() {
            return Err("the interpolation's driving state is not the profile's".into());
        }
        let steps = i64::from(self.line.steps());
        // The step is the driving position's integer part (a floor), held within 0 … L.
        let step = (after.driving.position.to_bits() >> 32).clamp(0, steps);
        if i64::from(after.step) != step {
            return Err(format!(
                "step {} at position {}",
                after.step, after.driving.position
            ));
        }
        let moved = i128::from(step) - i128::from(before.step);
        for (axis, &delta) in self.line.finish().iter().enumerate() {
            let (position, delta) = (i128::from(after.axes[axis]), i128::from(delta));
            // |position − step·Δ/L| ≤ ½, times 2L; a line of no steps stays at 0.
            let off = (2 * position * i128::from(steps) - 2 * i128::from(step) * delta).abs();
            if off > i128::from(steps) || (steps == 0 && position != 0) {
                return Err(format!(
                    "axis {axis} at {position}, over ½ pulse off the line at step {step}"
                ));
            }
            let change = position - i128::from(before.axes[axis]);
            if change.abs() > moved.abs() || change * delta * moved < 0 {
                return Err(format!(
                    "axis {axis} moved {change} over {moved} steps (Δ {delta})"
                ));
            }
        }
        Ok(())
    }

    fn check_settled(&self, stopped: bool) -> Result<(), String> {
        self.generator.check_settled(stopped)?;
        let steps = i64::from(self.line.steps());
        if self.generator.state().position.to_bits() == steps << 32
            && self.last.axes != self.line.finish()
        {
            return Err(format!(
                "arrived at step {steps} with the axes at {:?}",
                self.last.axes
            ));
        }
        Ok(())
    }
}

/// The profile driving the line, with its own script (its destination is replaced by the line's
/// length plus `overshoot`).
#[derive(Debug, Clone)]
pub enum Driver {
    /// A trapezoidal move.
    Trapezoidal(trapezoidal::Script),
    /// An S-curve move.
    SCurve(scurve::Script),
    /// An MCX514 drive (its pulses are the line's length: it cannot overshoot).
    Mcx514(mcx514::Script),
}

/// A line and the script of the profile that drives it.
#[derive(Debug, Clone)]
pub struct Script {
    /// The relative finish point of each axis, 2 to 4 of them.
    pub finish: Vec<i32>,
    /// Counts past the line's end (or before it, negative) for the driver's destination.
    pub overshoot: i64,
    /// The driver.
    pub driver: Driver,
}

impl Script {
    /// Builds the line and its driver and runs the script.
    ///
    /// # Errors
    /// The first check that failed.
    pub fn run(&self, budget: u64) -> Result<u64, String> {
        match self.finish.len() {
            2 => self.run_axes::<2>(budget),
            3 => self.run_axes::<3>(budget),
            _ => self.run_axes::<4>(budget),
        }
    }

    fn run_axes<const N: usize>(&self, budget: u64) -> Result<u64, String> {
        let mut finish = [0; N];
        for (axis, &delta) in finish.iter_mut().zip(&self.finish) {
            *axis = delta;
        }
        let line = Line::from_pulses(finish).map_err(|e| e.to_string())?;
        let steps = i64::from(line.steps());
        let destination = steps + self.overshoot;
        match &self.driver {
            Driver::Trapezoidal(script) => {
                let mut script = script.clone();
                let target = destination.clamp(i32::MIN.into(), i32::MAX.into()) as i32;
                script.parameters.0 = trapezoidal::Target::Absolute(target);
                drive(line, script.build()?, &script.steps, budget)
            }
            Driver::SCurve(script) => {
                let mut script = script.clone();
                let target = destination.clamp(-(1 << 30), (1 << 30) - 1) as i32;
                script.parameters.0 = scurve::Target::Absolute(target);
                drive(line, script.build()?, &script.steps, budget)
            }
            Driver::Mcx514(script) => {
                let mut script = script.clone();
                script.parameters.0 = line.steps();
                drive(line, script.build()?, &script.steps, budget)
            }
        }
    }

    /// Decodes a script from raw bytes (the fuzz target).
    pub fn decode(bytes: &mut Bytes) -> Self {
        let axes = 2 + usize::from(bytes.byte() % 3);
        let finish = (0..axes)
            .map(|_| bytes.boosted_signed((1 << 30) - 1) as i32)
            .collect();
        let overshoot = if bytes.byte() & 3 == 0 {
            bytes.boosted_signed(1 << 12)
        } else {
            0
        };
        let driver = match bytes.byte() % 3 {
            0 => Driver::Trapezoidal(trapezoidal::Script::decode(bytes)),
            1 => Driver::SCurve(scurve::Script::decode(bytes)),
            _ => Driver::Mcx514(mcx514::Script::decode(bytes)),
        };
        Self {
            finish,
            overshoot,
            driver,
        }
    }
}

fn drive<G: Scripted, const N: usize>(
    line: Line<N>,
    generator: Option<G>,
    steps: &[Step<G::Command>],
    budget: u64,
) -> Result<u64, String> {
    match generator {
        Some(generator) => super::run(Driven::new(line, generator), steps, budget),
        None => Ok(0),
    }
}

/// The proptest strategy: the drivers' own strategies, their start positions near the line's
/// start (a fraction either side of it, or exactly on it).
#[cfg(test)]
pub fn script() -> impl proptest::strategy::Strategy<Value = Script> {
    use super::boosted_signed;
    use fixed::types::I32F32;
    use proptest::prelude::*;
    let near_start =
        prop_oneof![Just(0i64), -(1i64 << 33)..(1i64 << 33)].prop_map(I32F32::from_bits);
    let driver = prop_oneof![
        (trapezoidal::script(), near_start.clone()).prop_map(|(mut script, position)| {
            script.position = position;
            Driver::Trapezoidal(script)
        }),
        (scurve::script(), near_start).prop_map(|(mut script, position)| {
            script.position = position;
            Driver::SCurve(script)
        }),
        mcx514::script().prop_map(Driver::Mcx514),
    ];
    (
        prop::collection::vec(
            boosted_signed((1 << 30) - 1).prop_map(|delta| delta as i32),
            2..=4,
        ),
        prop_oneof![3 => Just(0i64), 1 => boosted_signed(1 << 12)],
        driver,
    )
        .prop_map(|(finish, overshoot, driver)| Script {
            finish,
            overshoot,
            driver,
        })
}
