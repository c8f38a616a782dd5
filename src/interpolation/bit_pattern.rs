//! Bit-pattern interpolation (SPEC §12.5): each axis gets its pulses 16 steps at a time as a
//! "+" word and a "−" word (bit k set: one pulse in that direction on step k of the word, LSB
//! first); both bits set on any axis is the end of the data. One MCX514 trapezoid paces the
//! steps (trapezoidal with a manual deceleration point only, as the chip drives bit patterns,
//! reference 003 §3.8.2), however many a cycle takes: a word is counted with `count_ones`, not
//! walked bit by bit.
//!
//! ```
//! use profilegen::format::mcx514::{Acceleration, Deceleration, DriveSpeed, InitialSpeed};
//! use profilegen::format::CycleTime;
//! use profilegen::interpolation::{BitPatternInterpolation, BitWord, ContinuousDriving};
//!
//! let mut run = BitPatternInterpolation::<2>::new(
//!     ContinuousDriving {
//!         initial_speed: InitialSpeed::from_bits(4_000)?,
//!         drive_speed: DriveSpeed::from_bits(4_000)?,
//!         acceleration: Acceleration::from_bits(1)?,
//!         deceleration: Deceleration::from_bits(1)?,
//!     },
//!     None, // no deceleration
//!     CycleTime::from_seconds(1e-3)?,
//! )?;
//! // X: 16 steps forward; Y: every other step forward, then the end of data after 12 steps.
//! run.push([BitWord::new(0xFFFF, 0), BitWord::new(0x5555, 0)])?;
//! run.push([BitWord::new(0x1FFF, 0x1000), BitWord::new(0, 0x0FFF)])?; // X's bit 12: both
//! while !run.is_complete() {
//!     run.step();
//! }
//! assert_eq!(run.state().axes, [16 + 12, 8 - 12]);
//! assert_eq!(run.state().step, 28);
//! # Ok::<(), profilegen::Error>(())
//! ```

use super::continuous::ContinuousDriving;
use super::drive::steps_of;
use crate::format::mcx514::{FinishPoint, ManualDecelerationPoint};
use crate::format::CycleTime;
use crate::{
    DecelerationMode, Error, Mcx514Parameters, Mcx514Trapezoidal, ProfileGenerator, Range, State,
    StopKind,
};

/// Words per axis the buffer holds (our choice, as the continuous pre-buffer's 8).
pub const WORDS: usize = 8;

/// Steps in a word.
const STEPS_PER_WORD: u64 = 16;

/// One axis's 16 steps: bit k of `plus` pulses forward on step k, of `minus` backward; both:
/// the end of the data.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub struct BitWord {
    /// "+" direction pulses, LSB first.
    pub plus: u16,
    /// "−" direction pulses, LSB first.
    pub minus: u16,
}

impl BitWord {
    /// A word from its "+" and "−" halves.
    pub const fn new(plus: u16, minus: u16) -> Self {
        Self { plus, minus }
    }

    /// The net pulses of the first `steps` (0 … 16) steps of the word.
    fn net(self, steps: u32) -> i32 {
        // steps ≤ 16: the mask fits u32 (1 << 16 at most).
        let mask = ((1u32 << steps) - 1) as u16;
        (self.plus & mask).count_ones() as i32 - (self.minus & mask).count_ones() as i32
    }
}

/// One cycle of a bit-pattern interpolation.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct BitPatternState<const N: usize> {
    /// The speed profile's state: position in steps since the start.
    pub driving: State,
    /// Steps since the start.
    pub step: u64,
    /// Every axis, pulses relative to the start.
    pub axes: [i32; N],
}

/// A bit-pattern interpolation of N axes: a buffer of [`WORDS`] words per axis, refilled while
/// running, paced by one MCX514 trapezoid; see the [module docs](self).
#[derive(Debug, Clone)]
pub struct BitPatternInterpolation<const N: usize> {
    profile: Mcx514Trapezoidal,
    /// A ring of word groups: `words[(head + i) % WORDS]` for i < `waiting`.
    words: [[BitWord; N]; WORDS],
    head: usize,
    waiting: usize,
    /// The step at which the word at `head` begins.
    word_start: u64,
    /// Every axis at `word_start`.
    base: [i32; N],
    /// Steps the buffered words provide (to the end of the data, once it is in).
    available: u64,
    /// The end of the data is in the buffer.
    ended: bool,
    /// The absolute manual deceleration point, if any.
    point: Option<u32>,
    stopped: bool,
    axes: [i32; N],
}

impl<const N: usize> BitPatternInterpolation<N> {
    /// An empty run with these driving registers at `cycle` and an optional manual deceleration
    /// point (steps from the start; `None`: no deceleration, the run stops at once at the end of
    /// the data).
    ///
    /// # Errors
    /// Those of [`Mcx514Trapezoidal::new`].
    pub fn new(
        driving: ContinuousDriving,
        deceleration_point: Option<ManualDecelerationPoint>,
        cycle: CycleTime,
    ) -> Result<Self, Error> {
        let profile = Mcx514Trapezoidal::new(
            Mcx514Parameters {
                pulses: 0,
                initial_speed: driving.initial_speed,
                drive_speed: driving.drive_speed,
                acceleration: driving.acceleration,
                deceleration: driving.deceleration,
                deceleration_mode: DecelerationMode::Manual(ManualDecelerationPoint::MAX),
            },
            cycle,
        )?;
        Ok(Self {
            profile,
            words: [[BitWord::default(); N]; WORDS],
            head: 0,
            waiting: 0,
            word_start: 0,
            base: [0; N],
            available: 0,
            ended: false,
            point: deceleration_point.map(ManualDecelerationPoint::to_bits),
            stopped: false,
            axes: [0; N],
        })
    }

    /// Buffers the next 16 steps of every axis.
    ///
    /// # Errors
    /// [`Error::Refused`] (parameter `bit pattern`), changing nothing, when the buffer holds
    /// [`WORDS`] words, after the end of the data, after a stop or once the run has ended;
    /// [`Error::OutOfRange`] (parameter `bit pattern steps`) past 1,073,741,823 steps.
    pub fn push(&mut self, words: [BitWord; N]) -> Result<(), Error> {
        let refused = |reason| Error::Refused {
            parameter: "bit pattern",
            reason,
        };
        if self.waiting == WORDS {
            return Err(refused("while the buffer is full (8 words per axis)"));
        }
        if self.ended {
            return Err(refused("after the end of the data"));
        }
        if self.stopped {
            return Err(refused("after a stop"));
        }
        // The end of the data: the first step on which any axis has both bits set.
        let both = words
            .iter()
            .fold(0u16, |both, word| both | (word.plus & word.minus));
        let steps = if both == 0 {
            STEPS_PER_WORD
        } else {
            u64::from(both.trailing_zeros())
        };
        let available = self.available + steps;
        if available > FinishPoint::MAX_BITS as u64 {
            return Err(Error::OutOfRange {
                parameter: "bit pattern steps",
                value: available as f64,
                range: Range::of_register(0, i64::from(FinishPoint::MAX_BITS), 0, "pulses"),
            });
        }
        // Below 2³⁰: exact.
        if !self.profile.continue_to(available as u32, self.point) {
            return Err(refused("after the run has ended (the buffer ran dry)"));
        }
        self.words[(self.head + self.waiting) % WORDS] = words;
        self.waiting += 1;
        self.available = available;
        self.ended = both != 0;
        Ok(())
    }

    /// Advances the profile one cycle and every axis by the pulses of the steps it took: one
    /// `count_ones` per word it crosses (at most [`WORDS`]), never a loop over the steps.
    pub fn step(&mut self) -> BitPatternState<N> {
        let driving = self.profile.step();
        let step = u64::from(steps_of(&driving)).min(self.available);
        // Whole words behind the step: add them to the base and free their room.
        while self.waiting > 0 && step >= self.word_start + STEPS_PER_WORD {
            let words = self.words[self.head];
            for (base, word) in self.base.iter_mut().zip(words) {
                *base = base.wrapping_add(word.net(16));
            }
            self.head = (self.head + 1) % WORDS;
            self.waiting -= 1;
            self.word_start += STEPS_PER_WORD;
        }
        // Within the word at the head: 0 … 15 steps (16 only past the end of a dry buffer).
        let within = (step - self.word_start).min(STEPS_PER_WORD) as u32;
        let words = self.words[self.head];
        for ((axis, base), word) in self.axes.iter_mut().zip(self.base).zip(words) {
            *axis = if self.waiting > 0 {
                base.wrapping_add(word.net(within))
            } else {
                base
            };
        }
        BitPatternState {
            driving,
            step,
            axes: self.axes,
        }
    }

    /// The present state.
    pub fn state(&self) -> BitPatternState<N> {
        let driving = self.profile.state();
        BitPatternState {
            driving,
            step: u64::from(steps_of(&driving)).min(self.available),
            axes: self.axes,
        }
    }

    /// Whether the run has ended (at rest after the end of the data, a dry buffer or a stop).
    pub fn is_complete(&self) -> bool {
        self.profile.is_complete()
    }

    /// Room left in the buffer, in words per axis.
    pub const fn free(&self) -> usize {
        WORDS - self.waiting
    }

    /// The driving profile (its limits, for checking a cycle from outside).
    pub const fn profile(&self) -> &Mcx514Trapezoidal {
        &self.profile
    }

    /// Stops the run (SPEC §9): a smooth stop decelerates through the buffered steps (ending at
    /// their end at the latest), an abrupt stop holds in place; nothing can be buffered after.
    pub fn stop(&mut self, kind: StopKind) {
        self.stopped = true;
        self.profile.stop(kind);
    }
}
