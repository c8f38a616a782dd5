//! Microstep waveform (SPEC §10) scripts: a table driven by a velocity-contouring script
//! (positions anywhere, across the ±2^31 wrap), its current and resolution changed on the way.
//! Every cycle: the outputs are the table's at the position's whole microstep, within ± the
//! current, and on the circle (2 phases: a² + b² = current², within the roundings) or summing
//! to zero (3 phases).

use profilegen::waveform::{MicrostepTable, PhaseOutputs, Phases};
use profilegen::{Error, Limits, ProfileGenerator, State, StopKind, VelocityContouring};

use super::{velocity, Bytes, Scripted, Step};

/// A command of a microstep script.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Command {
    /// A command to the velocity profile that drives the table.
    Profile(velocity::Command),
    /// A new current (refused above 32767).
    Current(u16),
    /// A new table: microsteps per full step (refused unless a power of two ≤ 256), phases
    /// (refused unless 2 or 3), at the present current.
    Table(u32, u32),
}

/// A table driven by a velocity profile, as `MicrostepTable::drive` drives it.
#[derive(Debug, Clone, PartialEq)]
pub struct Driven {
    table: MicrostepTable,
    generator: VelocityContouring,
    last: Option<PhaseOutputs>,
}

impl ProfileGenerator for Driven {
    fn step(&mut self) -> State {
        let (state, outputs) = self
            .table
            .drive(&mut self.generator)
            .next()
            .unwrap_or((self.generator.state(), self.table.outputs(0)));
        self.last = Some(outputs);
        state
    }
    fn state(&self) -> State {
        self.generator.state()
    }
    fn is_complete(&self) -> bool {
        self.generator.is_complete()
    }
    fn stop(&mut self, kind: StopKind) {
        self.generator.stop(kind);
    }
    fn limits(&self) -> Limits {
        self.generator.limits()
    }
}

impl Scripted for Driven {
    type Command = Command;

    fn apply(&mut self, command: &Command) -> Result<(), Error> {
        match *command {
            Command::Profile(command) => self.generator.apply(&command),
            Command::Current(current) => {
                self.table = self.table.with_current(current)?;
                Ok(())
            }
            Command::Table(microsteps, phases) => {
                self.table = MicrostepTable::new(microsteps, Phases::from_count(phases)?)?
                    .with_current(self.table.current())?;
                Ok(())
            }
        }
    }
    fn settle_bound(&self, stopped: bool) -> f64 {
        self.generator.settle_bound(stopped)
    }
    fn settled(&self) -> bool {
        self.generator.settled()
    }
    fn velocity_register(&self) -> Option<i64> {
        self.generator.velocity_register()
    }
    fn predict(&self, cycles: u64) -> Option<State> {
        Scripted::predict(&self.generator, cycles)
    }

    fn check_cycle(&self, previous: &State, commanded: bool) -> Result<(), String> {
        self.generator.check_cycle(previous, commanded)?;
        let Some(outputs) = self.last else {
            return Err("no outputs".into());
        };
        // The whole microstep: the integer part of the position (a floor), 32 bits.
        let microstep = (self.generator.state().position.to_bits() >> 32) as i32;
        if outputs != self.table.outputs(microstep) {
            return Err(format!(
                "outputs {outputs:?} are not the table's at {microstep}"
            ));
        }
        let current = f64::from(self.table.current());
        let values: Vec<f64> = outputs.as_slice().iter().map(|&v| f64::from(v)).collect();
        if values.iter().any(|v| v.abs() > current) {
            return Err(format!("outputs {values:?} above the current {current}"));
        }
        // Each value is within 1 of current·cos(…) (two roundings of ½): the 2-phase radius
        // within √2, the 3-phase sum (exactly 0 for the cosines) within 3.
        let off = match self.table.phases() {
            Phases::Two => (values[0].hypot(values[1]) - current).abs() > 1.5,
            Phases::Three => values.iter().sum::<f64>().abs() > 3.0,
        };
        if off {
            return Err(format!(
                "outputs {values:?} off the waveform of current {current}"
            ));
        }
        Ok(())
    }
}

/// A velocity script's generator driving a table.
#[derive(Debug, Clone)]
pub struct Script {
    /// Microsteps per full step, phases, current (a valid table).
    pub table: (u32, u32, u16),
    /// The profile and its start.
    pub profile: velocity::Script,
    /// The steps.
    pub steps: Vec<Step<Command>>,
}

impl Script {
    /// Builds the table and its driver and runs the script.
    ///
    /// # Errors
    /// The first check that failed.
    pub fn run(&self, budget: u64) -> Result<u64, String> {
        let (microsteps, phases, current) = self.table;
        let table = MicrostepTable::new(
            microsteps,
            Phases::from_count(phases).map_err(|e| e.to_string())?,
        )
        .and_then(|table| table.with_current(current))
        .map_err(|e| e.to_string())?;
        match self.profile.build()? {
            Some(generator) => super::run(
                Driven {
                    table,
                    generator,
                    last: None,
                },
                &self.steps,
                budget,
            ),
            None => Ok(0),
        }
    }

    /// Decodes a script from raw bytes (the fuzz target).
    pub fn decode(bytes: &mut Bytes) -> Self {
        let table = (
            1 << (bytes.byte() % 9),
            2 + u32::from(bytes.byte() & 1),
            bytes.boosted(32_767) as u16,
        );
        let profile = velocity::Script::decode(bytes);
        let steps = profile
            .steps
            .iter()
            .map(|step| match step {
                Step::Command(command) => Step::Command(Command::Profile(*command)),
                Step::Run(n) => Step::Run(*n),
                Step::RunFraction(f) => Step::RunFraction(*f),
                Step::Stop(kind) => Step::Stop(*kind),
                Step::Finish => Step::Finish,
            })
            .chain([
                Step::Command(Command::Current(bytes.boosted(u16::MAX.into()) as u16)),
                Step::Command(Command::Table(
                    bytes.boosted(512) as u32,
                    u32::from(bytes.byte() % 5),
                )),
                Step::Run(u32::from(bytes.byte())),
            ])
            .collect();
        Self {
            table,
            profile,
            steps,
        }
    }
}

/// The proptest strategy.
#[cfg(test)]
pub fn script() -> impl proptest::strategy::Strategy<Value = Script> {
    use super::{boosted, steps};
    use proptest::prelude::*;
    let command = prop_oneof![
        3 => velocity::command().prop_map(Command::Profile),
        1 => boosted(0, u16::MAX.into()).prop_map(|current| Command::Current(current as u16)),
        1 => (boosted(0, 512), 0u32..5).prop_map(|(microsteps, phases)| Command::Table(microsteps as u32, phases)),
    ];
    (
        (0u32..9, 2u32..4, boosted(0, 32_767)),
        velocity::script(),
        steps(command, 12),
    )
        .prop_map(|((shift, phases, current), profile, steps)| Script {
            table: (1 << shift, phases, current as u16),
            profile,
            steps,
        })
}
