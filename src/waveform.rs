//! Microstep waveform tables for 2- and 3-phase step motors (SPEC §10): the last stage of the
//! Juno step-motor IC, from commanded position in microsteps to phase currents.
//!
//! Phase `i` at microstep `k` is `round(32767 · cos(2πk/M − i·φ))`, correctly rounded (ties away
//! from zero), with `M = 4N` microsteps per electrical cycle and φ = 90° for 2-phase motors,
//! `M = 6N` and φ = 120° for 3-phase motors. A 16-bit motor command (power level) scales the
//! outputs. No floating point at run time: one quarter-wave table, generated at build time, serves
//! every resolution; each [`MicrostepTable`] keeps its electrical cycle's outputs, scaled, so a
//! lookup is three loads.

use crate::{Error, ProfileGenerator, State, States};

include!(concat!(env!("OUT_DIR"), "/quarter_cosine.rs"));

/// Steps per electrical cycle of the generated table (`QUARTER_COSINE` holds a quarter of them).
const TABLE_STEPS: u32 = 3072;
const TABLE_QUARTER: u32 = TABLE_STEPS / 4;

/// The entries a table holds: an electrical cycle of M microsteps and the lead of phase A over
/// the last phase, (phases − 1)·M/phase-count more, at most 6·256 + 2·512 = 2560 (3 phases, 256
/// microsteps per full step); for 2 phases also M zeros, which its phase "C" reads (at most
/// 4·256 + 256 + 1024). Rounded up to a power of two, so that masking an index with
/// `ENTRIES − 1` is what proves it in bounds (one instruction, where a bounds check takes three).
const ENTRIES: usize = 4096;

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
///
/// The table holds the outputs of one electrical cycle at its motor command (8 KB, no
/// allocation), built by [`MicrostepTable::new`] and [`MicrostepTable::with_current`], so
/// [`MicrostepTable::outputs`] only reduces the position and loads.
#[derive(Clone, Copy, PartialEq, Eq, Hash)]
pub struct MicrostepTable {
    microsteps: u32,
    phases: Phases,
    current: u16,
    /// Microsteps per electrical cycle, M.
    cycle: u32,
    /// Microsteps between phases: M/4 (90°) or M/3 (120°).
    phase_shift: u32,
    /// M · 2^31: added to a position, makes it non-negative (below 2^42) with the same residue
    /// modulo M.
    bias: u64,
    /// ⌊2^64 / M⌋ + 1: `(x · reciprocal) >> 64` is ⌊x / M⌋ for every x < 2^42, so `outputs`
    /// reduces a position modulo M without a division.
    reciprocal: u64,
    /// Where phase i's outputs begin in `entries`: phase i at microstep k (reduced, k < M) is
    /// `entries[k + offsets[i]]`. Phase A leads by the most, so it starts furthest in; a
    /// 2-phase table's third offset points at zeros.
    offsets: [u32; 3],
    /// The outputs of phase A, scaled by the motor command, from `lead` microsteps before the
    /// cycle's start: `entries[j]` is phase A at microstep `(j − lead) mod M`, for
    /// j < M + lead, where lead = (phases − 1)·phase_shift; zero beyond. Every phase lags A by a
    /// multiple of the phase shift, so every phase reads M consecutive entries here, and a
    /// lookup needs no wrap-around.
    entries: [i16; ENTRIES],
}

/// Without the entries, which the other fields determine.
impl core::fmt::Debug for MicrostepTable {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.debug_struct("MicrostepTable")
            .field("microsteps", &self.microsteps)
            .field("phases", &self.phases)
            .field("current", &self.current)
            .finish_non_exhaustive()
    }
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
        let lead = match phases {
            Phases::Two => phase_shift,
            Phases::Three => 2 * phase_shift,
        };
        let offsets = match phases {
            Phases::Two => [lead, 0, cycle + lead],
            Phases::Three => [lead, lead - phase_shift, 0],
        };
        Ok(Self {
            microsteps: microsteps_per_full_step,
            phases,
            current: 0,
            cycle,
            phase_shift,
            bias: u64::from(cycle) << 31,
            reciprocal: u64::MAX / u64::from(cycle) + 1,
            offsets,
            entries: [0; ENTRIES],
        }
        .scaled_to(FULL_SCALE as u16))
    }

    /// The table at motor command `current`: phase A at microstep k is
    /// `round(C · cos(2πk/M) / 32767)`, from the correctly rounded full-scale entry at table step
    /// k · 3072/M.
    fn scaled_to(mut self, current: u16) -> Self {
        self.current = current;
        let stride = TABLE_STEPS / self.cycle;
        // Phase A's offset is the lead; j − lead + M ≥ 0 is the microstep modulo M.
        let lead = self.offsets[0];
        let span = (self.cycle + lead) as usize;
        for (j, entry) in self.entries[..span].iter_mut().enumerate() {
            let k = (j as u32 + self.cycle - lead) % self.cycle;
            *entry = Self::scaled(current, Self::full_scale(k * stride));
        }
        self
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
        Ok(self.scaled_to(current))
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
    /// by quarter-wave symmetry from the quarter table: exact, so the symmetry is too.
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
    /// rounding.
    fn scaled(current: u16, entry: i16) -> i16 {
        let product = i32::from(current) * i32::from(entry);
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
    // Not inlined: one copy serves every caller (25 x86 instructions), and it stays the function
    // that `tools/instruction_counts.sh` counts.
    #[inline(never)]
    pub fn outputs(&self, microstep: i32) -> PhaseOutputs {
        // microstep mod M = x − M·⌊x / M⌋ for x = microstep + M·2^31, which lies in
        // 0 … 2^42 (M ≤ 1536). The floor is the high half of x·r, r = ⌊2^64/M⌋ + 1, exactly:
        // x·r / 2^64 = x/M + x·e/(M·2^64) with 0 < e ≤ M, an excess below 2^−22 < 1/M, too
        // little to reach the next integer (x/M lies at most 1 − 1/M past its floor). Checked
        // against `rem_euclid` for every resolution (tests/waveform.rs).
        let x = (i64::from(microstep) as u64).wrapping_add(self.bias);
        let quotient = ((u128::from(x) * u128::from(self.reciprocal)) >> 64) as u64;
        let index = (x - quotient * u64::from(self.cycle)) as usize;
        // index < M and every offset ≤ M + lead, so the sum is below ENTRIES and the mask
        // changes nothing; it only spares the bounds check.
        let at = |i: usize| self.entries[(index + self.offsets[i] as usize) & (ENTRIES - 1)];
        let (a, b, c) = (at(0), at(1), at(2));
        PhaseOutputs {
            values: [a, b, c],
            phases: self.phases,
        }
    }

    /// Drives the table from a profile generator: an iterator over the phase outputs of each
    /// coming cycle, from the integer part (floor) of the commanded position, as the chip's
    /// position register holds it. Without end; see [`Self::drive_until_complete`].
    pub fn drive<'a, G: ProfileGenerator + ?Sized>(
        &'a self,
        generator: &'a mut G,
    ) -> Microstepper<'a, G> {
        Microstepper {
            table: self,
            states: States::new(generator, false),
        }
    }

    /// As [`Self::drive`], ending with the cycle on which the generator is complete (nothing if
    /// it is complete already), as [`ProfileGenerator::states_until_complete`] does.
    pub fn drive_until_complete<'a, G: ProfileGenerator + ?Sized>(
        &'a self,
        generator: &'a mut G,
    ) -> Microstepper<'a, G> {
        Microstepper {
            table: self,
            states: States::new(generator, true),
        }
    }
}

/// Phase outputs per cycle of a generator; see [`MicrostepTable::drive`].
#[derive(Debug)]
pub struct Microstepper<'a, G: ProfileGenerator + ?Sized> {
    table: &'a MicrostepTable,
    states: States<'a, G>,
}

impl<G: ProfileGenerator + ?Sized> Iterator for Microstepper<'_, G> {
    type Item = (State, PhaseOutputs);

    fn next(&mut self) -> Option<Self::Item> {
        let state = self.states.next()?;
        // The integer part: I32F32 bits shifted right 32 (floor, like the chip's register).
        let microstep = (state.position.to_bits() >> 32) as i32;
        Some((state, self.table.outputs(microstep)))
    }
}
