//! Microstep waveform tables for 2- and 3-phase step motors (SPEC §10): the last stage of the
//! Juno step-motor IC, from commanded position in microsteps to phase currents.
//!
//! Phase `i` at microstep `k` is `round(32767 · cos(2πk/M − i·φ))`, correctly rounded (ties away
//! from zero), with `M = 4N` microsteps per electrical cycle and φ = 90° for 2-phase motors,
//! `M = 6N` and φ = 120° for 3-phase motors. A 16-bit motor command (power level) scales the
//! outputs. No floating point at run time: one quarter-wave table, generated at build time, serves
//! every resolution.

use crate::{Error, ProfileGenerator, State};

include!(concat!(env!("OUT_DIR"), "/quarter_cosine.rs"));

/// Steps per electrical cycle of the generated table (`QUARTER_COSINE` holds a quarter of them).
const TABLE_STEPS: u32 = 3072;
const TABLE_QUARTER: u32 = TABLE_STEPS / 4;

/// Full scale of a phase output and of the motor command.
pub const FULL_SCALE: i16 = 32767;

/// The number of motor phases.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Phases {
    /// Two phases, 90° apart; an electrical cycle is 4 full steps.
    Two,
    /// Three phases, 120° apart; an electrical cycle is 6 full steps.
    Three,
}

impl Phases {
    /// From a phase count.
    ///
    /// # Errors
    /// [`Error::Phases`] unless the count is 2 or 3.
    pub const fn from_count(count: u32) -> Result<Self, Error> {
        match count {
            2 => Ok(Phases::Two),
            3 => Ok(Phases::Three),
            value => Err(Error::Phases { value }),
        }
    }

    /// The phase count, 2 or 3.
    pub const fn count(self) -> usize {
        match self {
            Phases::Two => 2,
            Phases::Three => 3,
        }
    }

    /// Full steps per electrical cycle: 4 or 6.
    const fn full_steps_per_cycle(self) -> u32 {
        match self {
            Phases::Two => 4,
            Phases::Three => 6,
        }
    }
}

/// The phase outputs of one microstep: `values[..phases]` are phases A, B (and C), signed 16-bit,
/// full scale ±32767.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct PhaseOutputs {
    values: [i16; 3],
    phases: Phases,
}

impl PhaseOutputs {
    /// The outputs of the motor's phases, A first.
    pub fn as_slice(&self) -> &[i16] {
        &self.values[..self.phases.count()]
    }
}

/// A validated microstep table: resolution, phase count and motor command.
///
/// ```
/// use profilegen::waveform::{MicrostepTable, Phases};
/// let table = MicrostepTable::new(64, Phases::Two)?;
/// assert_eq!(table.microsteps_per_cycle(), 256);
/// assert_eq!(table.outputs(0).as_slice(), [32767, 0]);   // A at cos 0, B at cos −90°
/// assert_eq!(table.outputs(64).as_slice(), [0, 32767]);  // one full step on
/// assert_eq!(table.outputs(-64).as_slice(), [0, -32767]);
/// # Ok::<(), profilegen::Error>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct MicrostepTable {
    microsteps: u32,
    phases: Phases,
    current: u16,
    /// Microsteps per electrical cycle, M.
    cycle: u32,
    /// Table steps per microstep: 3072 / M.
    stride: u32,
    /// Microsteps between phases: M/4 (90°) or M/3 (120°).
    phase_shift: u32,
}

impl MicrostepTable {
    /// A table at full current (motor command 32767).
    ///
    /// # Errors
    /// [`Error::Microsteps`] unless `microsteps_per_full_step` is a power of two from 1 to 256.
    pub fn new(microsteps_per_full_step: u32, phases: Phases) -> Result<Self, Error> {
        if !microsteps_per_full_step.is_power_of_two() || microsteps_per_full_step > 256 {
            return Err(Error::Microsteps {
                value: microsteps_per_full_step,
            });
        }
        let cycle = microsteps_per_full_step * phases.full_steps_per_cycle();
        let phase_shift = match phases {
            Phases::Two => cycle / 4,
            Phases::Three => cycle / 3,
        };
        Ok(Self {
            microsteps: microsteps_per_full_step,
            phases,
            current: FULL_SCALE as u16,
            cycle,
            stride: TABLE_STEPS / cycle,
            phase_shift,
        })
    }

    /// The same table with a motor command (power level) `current`.
    ///
    /// # Errors
    /// [`Error::OutOfRange`] (parameter `current`) above 32767.
    pub fn with_current(self, current: u16) -> Result<Self, Error> {
        if current > FULL_SCALE as u16 {
            return Err(Error::out_of_range_bits(
                "current",
                i64::from(current),
                0,
                crate::Range::of_register(0, FULL_SCALE as i64, 0, ""),
            ));
        }
        Ok(Self { current, ..self })
    }

    /// Microsteps per full step, N.
    pub const fn microsteps_per_full_step(&self) -> u32 {
        self.microsteps
    }

    /// Microsteps per electrical cycle, M = 4N or 6N.
    pub const fn microsteps_per_cycle(&self) -> u32 {
        self.cycle
    }

    /// The phase count.
    pub const fn phases(&self) -> Phases {
        self.phases
    }

    /// The motor command.
    pub const fn current(&self) -> u16 {
        self.current
    }

    /// The full-scale entry `round(32767 · cos(2π·index/3072))` for a table index below 2·3072,
    /// by quarter-wave symmetry from the quarter table: exact, so the symmetry is too. The
    /// divisors are constants (the compiler multiplies by their reciprocals): no division.
    #[inline(always)]
    fn full_scale(index: u32) -> i16 {
        let index = if index >= TABLE_STEPS {
            index - TABLE_STEPS
        } else {
            index
        };
        let quadrant = index / TABLE_QUARTER;
        let offset = index - quadrant * TABLE_QUARTER;
        // Quadrants 1 and 3 run the quarter backwards; 1 and 2 are negative.
        let entry = if quadrant & 1 == 0 {
            QUARTER_COSINE[offset as usize]
        } else {
            QUARTER_COSINE[(TABLE_QUARTER - offset) as usize]
        };
        if (quadrant + 1) & 2 == 0 {
            entry
        } else {
            -entry
        }
    }

    /// Scales a full-scale entry by the motor command: `round(C · entry / 32767)`, ties away from
    /// zero, in integers (|C · entry| < 2^30, so i32 holds it). Each scaled output is within
    /// 1 LSB of `C · cos(…)`: the entry errs by ≤ 0.5, scaled by C/32767 ≤ 1, plus ≤ 0.5 of
    /// rounding. The divisor is a constant: a multiplication by its reciprocal, not a division.
    #[inline(always)]
    fn scaled(&self, entry: i16) -> i16 {
        let product = i32::from(self.current) * i32::from(entry);
        let full = i32::from(FULL_SCALE);
        // Round half away from zero: (2|x| + d) / 2d, truncating, then the sign back.
        let magnitude = (2 * product.unsigned_abs() + full as u32) / (2 * full as u32);
        if product < 0 {
            -(magnitude as i16)
        } else {
            magnitude as i16
        }
    }

    /// The phase outputs at a signed microstep position (any i32: negative and wrapping
    /// positions are reduced modulo the electrical cycle). Constant time, no allocation, no
    /// division.
    ///
    /// A 3-phase cycle (6N) does not divide 2^32, so a position register that wraps jumps in
    /// electrical angle at the wrap; 2-phase cycles (4N, a power of two) wrap seamlessly.
    pub fn outputs(&self, microstep: i32) -> PhaseOutputs {
        // The position in table steps modulo the 3072 of an electrical cycle: (microstep mod M)
        // · stride = (microstep · stride) mod (M · stride), M · stride = 3072, a constant
        // divisor. |microstep · stride| < 2^31 · 3072 < 2^43: i64.
        let index = (i64::from(microstep) * i64::from(self.stride)).rem_euclid(3072) as u32;
        // Phase i lags by i·φ: cos(2π(k − i·shift)/M); in table steps, k·stride − i·φ_t, kept
        // non-negative by adding one cycle (φ_t ≤ 1024, i ≤ 2), and below 2·3072.
        let lag = self.phase_shift * self.stride;
        let a = self.scaled(Self::full_scale(index));
        let b = self.scaled(Self::full_scale(index + TABLE_STEPS - lag));
        let c = match self.phases {
            Phases::Two => 0,
            Phases::Three => self.scaled(Self::full_scale(index + TABLE_STEPS - 2 * lag)),
        };
        PhaseOutputs {
            values: [a, b, c],
            phases: self.phases,
        }
    }

    /// Drives the table from a profile generator: an iterator over the phase outputs of each
    /// coming cycle, from the integer part (floor) of the commanded position, as the chip's
    /// position register holds it.
    pub fn drive<'a, G: ProfileGenerator + ?Sized>(
        &'a self,
        generator: &'a mut G,
    ) -> Microstepper<'a, G> {
        Microstepper {
            table: self,
            generator,
        }
    }
}

/// Phase outputs per cycle of a generator; see [`MicrostepTable::drive`].
#[derive(Debug)]
pub struct Microstepper<'a, G: ProfileGenerator + ?Sized> {
    table: &'a MicrostepTable,
    generator: &'a mut G,
}

impl<G: ProfileGenerator + ?Sized> Iterator for Microstepper<'_, G> {
    type Item = (State, PhaseOutputs);

    fn next(&mut self) -> Option<Self::Item> {
        let state = self.generator.step();
        // The integer part: I32F32 bits shifted right 32 (floor, like the chip's register).
        let microstep = (state.position.to_bits() >> 32) as i32;
        Some((state, self.table.outputs(microstep)))
    }
}
