//! MCX514 trapezoidal driving-axis profile (SPEC §12.2) scripts: every register across its
//! range, automatic, manual and disabled deceleration, cycle times from 0.1 to 4 ms, smooth and
//! abrupt stops from every phase. The profile takes no command in motion but stops (the chip's
//! registers are written before a drive starts), and has no restart: a new drive is a new
//! generator.

use profilegen::format::mcx514::{
    Acceleration, Deceleration, DriveSpeed, FinishPoint, InitialSpeed, ManualDecelerationPoint,
};
use profilegen::format::CycleTime;
use profilegen::reference::trapezoidal_duration;
use profilegen::{
    DecelerationMode, Error, Limits, Mcx514Parameters, Mcx514Trapezoidal, ProfileGenerator, State,
    StopKind,
};

use super::{counts, Bytes, NoCommand, Scripted, Step};

/// Cycle times, seconds: the per-cycle registers from fine to coarse.
pub const CYCLES: [f64; 5] = [1e-4, 2.5e-4, 1e-3, 2e-3, 4e-3];

/// The deceleration mode, raw.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Mode {
    /// Automatic (the deceleration is the acceleration).
    Automatic,
    /// Manual, at this point (pulses).
    Manual(u32),
    /// Deceleration disabled.
    Disabled,
}

/// An MCX514 drive's registers: pulses, initial speed, drive speed, acceleration, deceleration
/// (raw), deceleration mode, index into the cycle times.
pub type Parameters = (u32, u32, u32, u32, u32, Mode, usize);

/// The generator's registers and its script.
#[derive(Debug, Clone)]
pub struct Script {
    /// The registers.
    pub parameters: Parameters,
    /// The steps.
    pub steps: Vec<Step<NoCommand>>,
}

/// The generator, and what a script needs to know of its drive: how long it may take, and how
/// many cycles have passed.
#[derive(Debug, Clone, PartialEq)]
pub struct Drive {
    generator: Mcx514Trapezoidal,
    /// Pulses to the finish point, I32F32 bits.
    finish: i64,
    /// The bound on the whole drive's cycles, from the float reference.
    bound: f64,
    /// Per-cycle deceleration (pulses/cycle²), for a stop's bound.
    deceleration: f64,
    elapsed: u64,
}

impl ProfileGenerator for Drive {
    fn step(&mut self) -> State {
        self.elapsed += 1;
        self.generator.step()
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

impl Script {
    /// Builds the drive and runs the script.
    ///
    /// # Errors
    /// The first check that failed.
    pub fn run(&self, budget: u64) -> Result<u64, String> {
        match self.build()? {
            Some(drive) => super::run(drive, &self.steps, budget),
            None => Ok(0),
        }
    }

    /// The registers and the cycle time: `None` for a register out of its range (the
    /// strategy's extremes, refused).
    ///
    /// # Errors
    /// A cycle time refused.
    pub fn registers(&self) -> Result<Option<(Mcx514Parameters, CycleTime)>, String> {
        registers(self.parameters)
    }

    /// Builds the drive: `None` if the registers are refused, as they must be then.
    ///
    /// # Errors
    /// Valid registers refused.
    pub fn build(&self) -> Result<Option<Drive>, String> {
        let (pulses, initial, drive, acceleration, _, mode, _) = self.parameters;
        let registers = registers(self.parameters)?;
        let Some((registers, cycle)) = registers else {
            return Ok(None); // a register out of its range: the strategy's extremes, refused
        };
        let Some(generator) = accepted(Mcx514Trapezoidal::new(registers, cycle), self.parameters)?
        else {
            return Ok(None);
        };
        let per_cycle = |value: f64, power: i32| value * cycle.seconds().powi(power);
        let (s, v) = (
            per_cycle(f64::from(initial), 1),
            per_cycle(f64::from(drive), 1),
        );
        let (a, d) = (
            per_cycle(f64::from(acceleration), 2),
            per_cycle(f64::from(registers.deceleration.to_bits()), 2),
        );
        let p = f64::from(pulses);
        // Every moving cycle but the last runs at SV or faster (the profile never slows below
        // SV before the finish point): at most P / SV cycles, whatever the mode. Disabled: at DV
        // all the way. Automatic: the continuous trapezoid from SV to SV, and a creep at SV over
        // at most two cycles' distance at the peak (the deceleration point is decided on whole
        // cycles, and the discrete ramps' areas differ from the continuous ones by about a
        // cycle's distance each).
        let bound = match mode {
            Mode::Disabled => p / v,
            Mode::Automatic => {
                (p / s).min(trapezoidal_duration(p, v, a, d, s) + 2.0 * (v + a) / s + 4.0)
            }
            Mode::Manual(_) => p / s,
        } + 3.0;
        Ok(Some(Drive {
            generator,
            finish: i64::from(pulses) << 32,
            bound,
            deceleration: d,
            elapsed: 0,
        }))
    }

    /// Decodes a script from raw bytes (the fuzz target).
    pub fn decode(bytes: &mut Bytes) -> Self {
        let pulses = bytes.boosted(FinishPoint::MAX_BITS as u64) as u32;
        let initial = bytes.boosted(InitialSpeed::MAX_BITS.into()) as u32;
        let drive = bytes.boosted(DriveSpeed::MAX_BITS.into()) as u32;
        let acceleration = bytes.boosted(Acceleration::MAX_BITS.into()) as u32;
        let deceleration = bytes.boosted(Deceleration::MAX_BITS.into()) as u32;
        let parameters =
            with_mode_and_cycle(bytes, [pulses, initial, drive, acceleration, deceleration]);
        let steps = bytes.steps(|_| None);
        Self { parameters, steps }
    }
}

/// The registers `[pulses, initial, drive, acceleration, deceleration]` decoded already, with
/// the deceleration mode and the cycle time decoded next (the fuzz targets).
pub fn with_mode_and_cycle(bytes: &mut Bytes, registers: [u32; 5]) -> Parameters {
    let mode = match bytes.byte() % 4 {
        0 | 1 => Mode::Automatic,
        2 => Mode::Manual(bytes.boosted(ManualDecelerationPoint::MAX_BITS.into()) as u32),
        _ => Mode::Disabled,
    };
    parameters_of(registers, mode, usize::from(bytes.byte()))
}

/// The registers `[pulses, initial, drive, acceleration, deceleration]`, mode and cycle time.
fn parameters_of(registers: [u32; 5], mode: Mode, cycle: usize) -> Parameters {
    let [pulses, initial, drive, acceleration, deceleration] = registers;
    (
        pulses,
        initial,
        drive,
        acceleration,
        deceleration,
        mode,
        cycle,
    )
}

impl Scripted for Drive {
    type Command = NoCommand;

    fn apply(&mut self, command: &NoCommand) -> Result<(), Error> {
        match *command {}
    }

    /// The drive's bound less the cycles run; after a stop: down at DC to SV, then rest (which
    /// may take longer than the rest of the drive would have: it is a bound of its own).
    fn settle_bound(&self, stopped: bool) -> f64 {
        if stopped {
            let velocity = counts(self.state().velocity.to_bits());
            return velocity / self.deceleration + 3.0;
        }
        (self.bound - self.elapsed as f64).max(1.0)
    }

    fn velocity_register(&self) -> Option<i64> {
        None
    }

    fn check_cycle(&self, previous: &State, _commanded: bool) -> Result<(), String> {
        between_start_and_finish(&self.state(), previous, self.finish)
    }

    fn check_settled(&self, stopped: bool) -> Result<(), String> {
        settled(&self.state(), stopped, self.finish)
    }
}

/// The registers of an MCX514 drive and the cycle time: `None` for a register out of its range
/// (the strategy's extremes, refused). With automatic deceleration DC is AC.
///
/// # Errors
/// A cycle time refused.
pub fn registers(parameters: Parameters) -> Result<Option<(Mcx514Parameters, CycleTime)>, String> {
    let (pulses, initial, drive, acceleration, deceleration, mode, cycle) = parameters;
    let cycle = CycleTime::from_seconds(CYCLES[cycle % CYCLES.len()]).map_err(|e| e.to_string())?;
    let registers = (|| -> Result<Mcx514Parameters, Error> {
        Ok(Mcx514Parameters {
            pulses,
            initial_speed: InitialSpeed::from_bits(initial)?,
            drive_speed: DriveSpeed::from_bits(drive)?,
            acceleration: Acceleration::from_bits(acceleration)?,
            deceleration: Deceleration::from_bits(match mode {
                Mode::Automatic => acceleration,
                _ => deceleration,
            })?,
            deceleration_mode: match mode {
                Mode::Automatic => DecelerationMode::Automatic,
                Mode::Manual(point) => {
                    DecelerationMode::Manual(ManualDecelerationPoint::from_bits(point)?)
                }
                Mode::Disabled => DecelerationMode::Disabled,
            },
        })
    })();
    Ok(registers.ok().map(|registers| (registers, cycle)))
}

/// The generator an MCX514 drive's registers made; `None` where refusing them is right: SV
/// above DV, pulses past the finish point's range, or a register that rounds to zero (or
/// overflows) per cycle — the errors the docs name.
///
/// # Errors
/// Valid registers refused.
pub fn accepted<G>(made: Result<G, Error>, parameters: Parameters) -> Result<Option<G>, String> {
    let (pulses, initial, drive, ..) = parameters;
    match made {
        Ok(generator) => Ok(Some(generator)),
        Err(_) if initial > drive || pulses > FinishPoint::MAX_BITS as u32 => Ok(None),
        Err(Error::Underflow { .. } | Error::OutOfRange { .. }) => Ok(None),
        Err(error) => Err(format!("valid registers refused: {error}")),
    }
}

/// The position never passes the finish point (I32F32 bits), nor goes back.
///
/// # Errors
/// Where it does.
pub fn between_start_and_finish(
    state: &State,
    previous: &State,
    finish: i64,
) -> Result<(), String> {
    let position = state.position.to_bits();
    if position > finish || position < previous.position.to_bits() {
        return Err(format!("left 0 … the finish point {finish} (bits)"));
    }
    Ok(())
}

/// At rest; exactly on the finish point (I32F32 bits) unless stopped.
///
/// # Errors
/// Where it is not.
pub fn settled(state: &State, stopped: bool, finish: i64) -> Result<(), String> {
    if state.velocity != 0 || (!stopped && state.position.to_bits() != finish) {
        return Err(format!("settled off the finish point: {state:?}"));
    }
    Ok(())
}

/// The strategy for an MCX514 drive's registers.
#[cfg(test)]
pub fn parameters() -> impl proptest::strategy::Strategy<Value = Parameters> {
    use super::boosted;
    use proptest::prelude::*;
    let pulses = boosted(0, FinishPoint::MAX_BITS as u64).prop_map(|bits| bits as u32);
    let speed = || boosted(1, DriveSpeed::MAX_BITS.into()).prop_map(|bits| bits as u32);
    let rate = || boosted(1, Acceleration::MAX_BITS.into()).prop_map(|bits| bits as u32);
    let mode = prop_oneof![
        2 => Just(Mode::Automatic),
        2 => boosted(0, ManualDecelerationPoint::MAX_BITS.into()).prop_map(|point| Mode::Manual(point as u32)),
        1 => Just(Mode::Disabled),
    ];
    // The initial speed at or below the drive speed three times in four (above it is refused).
    let speeds = (speed(), speed(), 0u8..4).prop_map(|(x, y, order)| {
        if order == 0 {
            (x, y)
        } else {
            (x.min(y), x.max(y))
        }
    });
    (pulses, speeds, rate(), rate(), mode, 0..CYCLES.len()).prop_map(
        |(pulses, (initial, drive), acceleration, deceleration, mode, cycle)| {
            parameters_of(
                [pulses, initial, drive, acceleration, deceleration],
                mode,
                cycle,
            )
        },
    )
}

/// The proptest strategy.
#[cfg(test)]
pub fn script() -> impl proptest::strategy::Strategy<Value = Script> {
    use super::plain_steps;
    use proptest::prelude::*;
    (parameters(), plain_steps(12)).prop_map(|(parameters, steps)| Script { parameters, steps })
}
