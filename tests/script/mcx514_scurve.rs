//! MCX514 S-curve driving-axis profile (SPEC §12.2) scripts, driven like the trapezoid
//! (`mcx514.rs`): every register across its range (the jerks JK and DJ too), automatic, manual
//! and disabled deceleration, cycle times from 0.1 to 4 ms, smooth and abrupt stops from every
//! phase, then finish. The profile takes no command in motion but stops and has no restart.

use profilegen::format::mcx514::{
    Acceleration, Deceleration, DecelerationJerk, DriveSpeed, FinishPoint, InitialSpeed, Jerk,
};
use profilegen::reference::scurve_duration;
use profilegen::{
    Error, Limits, Mcx514SCurve, Mcx514ScurveParameters, ProfileGenerator, State, StopKind,
};

use super::mcx514::{
    accepted, between_start_and_finish, registers, settled, with_mode_and_cycle, Mode, Parameters,
};
use super::{counts, Bytes, NoCommand, Scripted, Step};

/// The generator's registers and its script.
#[derive(Debug, Clone)]
pub struct Script {
    /// The registers of the trapezoid underneath (`mcx514.rs`).
    pub parameters: Parameters,
    /// Jerk JK and deceleration jerk DJ (raw; DJ is JK with automatic deceleration).
    pub jerks: (u32, u32),
    /// The steps.
    pub steps: Vec<Step<NoCommand>>,
}

/// The generator, and what a script needs to know of its drive.
#[derive(Debug, Clone, PartialEq)]
pub struct Drive {
    generator: Mcx514SCurve,
    /// Pulses to the finish point, I32F32 bits.
    finish: i64,
    /// The bound on the whole drive's cycles, from the float reference.
    bound: f64,
    /// Automatic deceleration: the continuous S-curve's duration with slack for whole cycles
    /// and the creep the chip's rule leaves (see `build`).
    tight: f64,
    /// Per-cycle AC, DC, JK, DJ, SV (pulses/cycle^k), for a stop's bound.
    rates: (f64, f64, f64, f64, f64),
    elapsed: u64,
}

impl ProfileGenerator for Drive {
    fn step(&mut self) -> State {
        // The move's own cycles: a script's runs may go on past its end.
        self.elapsed += u64::from(!self.generator.is_complete());
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

    /// Builds the drive: `None` if the registers are refused, as they must be then.
    ///
    /// # Errors
    /// Valid registers refused.
    pub fn build(&self) -> Result<Option<Drive>, String> {
        let (pulses, initial, drive, acceleration, _, mode, _) = self.parameters;
        let (jerk, deceleration_jerk) = match mode {
            Mode::Automatic => (self.jerks.0, self.jerks.0),
            _ => self.jerks,
        };
        let Some((trapezoid, cycle)) = registers(self.parameters)? else {
            return Ok(None); // a register out of its range: the strategy's extremes, refused
        };
        let (Ok(jerk_register), Ok(deceleration_jerk_register)) = (
            Jerk::from_bits(jerk),
            DecelerationJerk::from_bits(deceleration_jerk),
        ) else {
            return Ok(None);
        };
        let registers = Mcx514ScurveParameters {
            trapezoid,
            jerk: jerk_register,
            deceleration_jerk: deceleration_jerk_register,
        };
        let Some(generator) = accepted(Mcx514SCurve::new(registers, cycle), self.parameters)?
        else {
            return Ok(None);
        };
        let per_cycle = |value: u32, power: i32| f64::from(value) * cycle.seconds().powi(power);
        let (s, v) = (per_cycle(initial, 1), per_cycle(drive, 1));
        let (a, d) = (
            per_cycle(acceleration, 2),
            per_cycle(registers.trapezoid.deceleration.to_bits(), 2),
        );
        let (j, dj) = (per_cycle(jerk, 3), per_cycle(deceleration_jerk, 3));
        let p = f64::from(pulses);
        // Every moving cycle but the last runs at SV or faster (the profile never slows below
        // SV before the finish point): at most P / SV cycles, whatever the mode. Disabled: at DV
        // all the way. Automatic (AC = DC, JK = DJ), at most:
        // - the continuous S-curve from rest to rest (which the one from SV never trails), with
        //   8 cycles for the whole cycles of the two ramps (each: the rate's steps rounded, at
        //   most two cycles held below the cap, one that takes the slack between two steps of
        //   the descent, the start cycle);
        // - a creep at SV over what the slow-down leaves: the deceleration is decided on whole
        //   cycles (at most DV + SV pulses), and the discrete slow-down's speeds are not exactly
        //   the mirror of the speed-up's: pairing the i-th cycle of one with the i-th from the
        //   end of the other, the rates differ by a few J only over the ramps' rate-building
        //   cycles (R ≤ min(AC/JK, √(G/JK)) + 4, G = DV − SV) and each difference weighs at most
        //   the speed-up's N cycles (≤ G/AC + AC/JK + 2√(G/JK) + 3): at most JK·R·N pulses
        //   (measured: ≤ 0.32 of it over 20,000 random moves; before the ramp could take the
        //   slack between two steps it was up to 69 times it).
        let tight = match mode {
            Mode::Automatic => {
                let gain = (v - s).max(0.0);
                let ramp = (a / j).min((gain / j).sqrt()) + 4.0;
                let speed_up = gain / a + a / j + 2.0 * (gain / j).sqrt() + 3.0;
                let creep = (v + s + j * ramp * speed_up) / s;
                (p / s).min(scurve_duration(p, v, a, j) + 8.0 + creep)
            }
            _ => p / s,
        } + 3.0;
        let bound = match mode {
            Mode::Disabled => p / v,
            _ => p / s,
        } + 3.0;
        Ok(Some(Drive {
            generator,
            finish: i64::from(pulses) << 32,
            bound,
            tight,
            rates: (a, d, j, dj, s),
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
        let jerk = bytes.boosted(Jerk::MAX_BITS.into()) as u32;
        let deceleration_jerk = bytes.boosted(DecelerationJerk::MAX_BITS.into()) as u32;
        let parameters =
            with_mode_and_cycle(bytes, [pulses, initial, drive, acceleration, deceleration]);
        let steps = bytes.steps(|_| None);
        Self {
            parameters,
            jerks: (jerk, deceleration_jerk),
            steps,
        }
    }
}

impl Scripted for Drive {
    type Command = NoCommand;

    fn apply(&mut self, command: &NoCommand) -> Result<(), Error> {
        match *command {}
    }

    /// The drive's bound less the cycles run; after a smooth stop: a rising rate eases off at JK
    /// (AC/JK cycles, adding at most AC²/JK to the speed), then the speed falls at DC, with
    /// DC/DJ cycles for the rate to build, to SV, then rest (a bound of its own: it may exceed
    /// the rest of the drive).
    fn settle_bound(&self, stopped: bool) -> f64 {
        if stopped {
            let (a, d, j, dj, s) = self.rates;
            let velocity = counts(self.state().velocity.to_bits());
            return ((velocity - s).max(0.0) + a * a / j) / d + a / j + 2.0 * d / dj + 6.0;
        }
        (self.bound - self.elapsed as f64).max(1.0)
    }

    fn velocity_register(&self) -> Option<i64> {
        None
    }

    fn check_cycle(&self, previous: &State, _commanded: bool) -> Result<(), String> {
        between_start_and_finish(&self.state(), previous, self.finish)
    }

    /// At rest; exactly on the finish point unless stopped; a move that was not stopped took at
    /// most the tight bound's cycles.
    fn check_settled(&self, stopped: bool) -> Result<(), String> {
        if !stopped && self.elapsed as f64 > self.tight {
            return Err(format!(
                "{} cycles, past the S-curve bound of {:.1}",
                self.elapsed, self.tight
            ));
        }
        settled(&self.state(), stopped, self.finish)
    }
}

/// The proptest strategy.
#[cfg(test)]
pub fn script() -> impl proptest::strategy::Strategy<Value = Script> {
    use super::mcx514::parameters;
    use super::{boosted, plain_steps};
    use proptest::prelude::*;
    let jerk = || boosted(1, Jerk::MAX_BITS.into()).prop_map(|bits| bits as u32);
    (parameters(), (jerk(), jerk()), plain_steps(12)).prop_map(|(parameters, jerks, steps)| {
        Script {
            parameters,
            jerks,
            steps,
        }
    })
}
