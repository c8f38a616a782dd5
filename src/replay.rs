//! The per-cycle form of a plan laid out ahead: runs of cycles whose velocity changes by a
//! constant, replayed one cycle per step (the trapezoid's and the MCX514 trapezoid's). A run
//! counts its cycles in 32 bits, with the laps of 2^32 cycles beyond them apart: a 32-bit core
//! counts down and tests a 32-bit word in two instructions where a 64-bit one takes five, and
//! the laps are looked at only on the cycle the word reaches zero.

/// `cycles` (≥ 1) as a 32-bit count in 1 … 2^32 (2^32 kept as 0: a countdown subtracts before it
/// tests) and the laps of 2^32 cycles after it: `cycles = count + laps·2^32`. The S-curve's runs
/// count the same way (their laps on the slow path).
pub(crate) const fn count_and_laps(cycles: u64) -> (u32, u64) {
    let below = cycles - 1;
    ((below as u32).wrapping_add(1), below >> 32)
}

/// The cycles a count and its laps stand for ([`count_and_laps`] undone).
pub(crate) const fn cycles_of(count: u32, laps: u64) -> u64 {
    let count = if count == 0 { 1 << 32 } else { count as u64 };
    count + (laps << 32)
}

/// A run's cycles left, counted down in 32 bits ([`count_and_laps`]). Shared by both kinds of
/// run.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Countdown {
    count: u32,
    laps: u32,
}

impl Countdown {
    /// `cycles` cycles (≥ 1; 0 makes an empty run, never replayed).
    pub(crate) const fn new(cycles: u64) -> Self {
        if cycles == 0 {
            return Self { count: 0, laps: 0 };
        }
        let (count, laps) = count_and_laps(cycles);
        Self {
            count,
            laps: laps as u32,
        }
    }

    /// The cycles left (≥ 1 while the run is replayed).
    pub(crate) const fn cycles(&self) -> u64 {
        cycles_of(self.count, self.laps as u64)
    }

    /// The slow path's marker: one cycle, whose end [`Self::tick`] reports as [`End::Lap`] (its
    /// laps are never counted).
    const fn elsewhere() -> Self {
        Self {
            count: 1,
            laps: u32::MAX,
        }
    }

    /// One cycle taken: what the count reaching zero means.
    #[inline(always)]
    pub(crate) fn tick(&mut self) -> End {
        self.count = self.count.wrapping_sub(1);
        if self.count != 0 {
            End::No
        } else if self.laps == 0 {
            End::Run
        } else {
            End::Lap
        }
    }

    /// After [`End::Lap`] on a run that is not the slow path's: 2^32 cycles more (the count
    /// wraps on the next).
    #[inline(always)]
    pub(crate) fn lap(&mut self) {
        self.laps -= 1;
    }
}

/// One run being replayed: `cycles` cycles at velocities `next`, `next + increment`, … (I32F32
/// bits).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Replay {
    next: i64,
    increment: i64,
    countdown: Countdown,
}

impl Replay {
    /// The run of `cycles` (≥ 1; 0 makes an empty run, never replayed) from `next` by
    /// `increment` per cycle.
    pub(crate) const fn new(next: i64, increment: i64, cycles: u64) -> Self {
        Self {
            next,
            increment,
            countdown: Countdown::new(cycles),
        }
    }

    /// The next cycle's velocity (I32F32 bits).
    pub(crate) const fn next(&self) -> i64 {
        self.next
    }

    /// The change per cycle.
    pub(crate) const fn increment(&self) -> i64 {
        self.increment
    }

    /// The cycles left in the run (≥ 1 while it is replayed).
    pub(crate) const fn cycles(&self) -> u64 {
        self.countdown.cycles()
    }

    /// The run that stands for the slow path (the slot of a plan that leads to it): one cycle,
    /// whose end [`Self::take`] reports as [`End::Lap`] (its laps are a marker, never counted).
    pub(crate) const fn elsewhere() -> Self {
        Self {
            next: 0,
            increment: 0,
            countdown: Countdown::elsewhere(),
        }
    }

    /// Takes the run's next cycle: its velocity, and what its count reaching zero means.
    #[inline(always)]
    pub(crate) fn take(&mut self) -> (i64, End) {
        let velocity = self.next;
        // Past the run's last cycle the sum is never used: wrapping (a rate can near 2⁶³).
        self.next = velocity.wrapping_add(self.increment);
        (velocity, self.countdown.tick())
    }

    /// After [`End::Lap`] on a run that is not [`Self::elsewhere`]: 2^32 cycles more (the count
    /// wraps on the next).
    #[inline(always)]
    pub(crate) fn lap(&mut self) {
        self.countdown.lap();
    }
}

/// One run of constant jerk being replayed (the MCX514 S-curve's): `cycles` cycles on each of
/// which the acceleration changes by `jerk` (I32F32 bits), the velocity by the acceleration. The
/// state itself carries the acceleration and the velocity, so a cycle is three additions.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct JerkRun {
    jerk: i64,
    countdown: Countdown,
}

impl JerkRun {
    /// The run of `cycles` (≥ 1; 0 makes an empty run, never replayed) at `jerk` per cycle.
    pub(crate) const fn new(jerk: i64, cycles: u64) -> Self {
        Self {
            jerk,
            countdown: Countdown::new(cycles),
        }
    }

    /// The run that stands for the slow path: see [`Replay::elsewhere`].
    pub(crate) const fn elsewhere() -> Self {
        Self {
            jerk: 0,
            countdown: Countdown::elsewhere(),
        }
    }

    /// Takes the run's next cycle: its jerk, and what its count reaching zero means.
    #[inline(always)]
    pub(crate) fn take(&mut self) -> (i64, End) {
        (self.jerk, self.countdown.tick())
    }

    /// After [`End::Lap`] on a run that is not [`Self::elsewhere`]: 2^32 cycles more.
    #[inline(always)]
    pub(crate) fn lap(&mut self) {
        self.countdown.lap();
    }
}

/// What the cycle [`Replay::take`] took ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum End {
    /// Nothing: the run goes on.
    No,
    /// The run: the next cycle is the next run's.
    Run,
    /// A lap of 2^32 cycles of a longer run ([`Replay::lap`] takes it), or the slow path's
    /// cycle ([`Replay::elsewhere`]). Both rare, so the common end of a run is one test.
    Lap,
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A run takes exactly its cycles, at the velocities of its progression, across the 32-bit
    /// count's ends (counted in laps of 2^32 without stepping them all: `cycles` after each).
    #[test]
    fn a_run_takes_its_cycles_exactly() {
        for cycles in [
            1u64,
            2,
            3,
            1000,
            (1 << 32) - 1,
            1 << 32,
            (1 << 32) + 1,
            3 << 32,
            u64::MAX,
        ] {
            let mut run = Replay::new(5, -2, cycles);
            assert_eq!(run.cycles(), cycles);
            let mut taken = 0u64;
            let mut velocity = 5i64;
            // Step the first few and the last few cycles; skip the middle by laps.
            loop {
                let left = run.cycles();
                if left > 10 && taken >= 5 {
                    // Jump to 5 cycles before the end, as if stepped.
                    let skip = left - 5;
                    run = Replay::new(
                        run.next()
                            .wrapping_add(run.increment().wrapping_mul(skip as i64)),
                        -2,
                        5,
                    );
                    taken += skip;
                    velocity = velocity.wrapping_add((-2i64).wrapping_mul(skip as i64));
                }
                let (got, end) = run.take();
                assert_eq!(got, velocity);
                velocity = velocity.wrapping_sub(2);
                taken += 1;
                match end {
                    End::Run => break,
                    End::Lap => run.lap(),
                    End::No => {}
                }
                assert_eq!(run.cycles(), cycles - taken, "after {taken} of {cycles}");
            }
            assert_eq!(taken, cycles);
        }
    }

    /// Across a lap: the count's wrap and the lap taken keep the cycles left right.
    #[test]
    fn laps_are_taken_where_the_count_runs_out() {
        let mut run = Replay::new(0, 0, (1 << 32) + 2);
        assert_eq!(run.take(), (0, End::No));
        assert_eq!(run.cycles(), (1 << 32) + 1);
        // The count reaches zero with a lap left: 2^32 cycles more.
        assert_eq!(run.take(), (0, End::Lap));
        run.lap();
        assert_eq!(run.cycles(), 1 << 32);
        for _ in 0..3 {
            assert_eq!(run.take(), (0, End::No));
        }
        assert_eq!(run.cycles(), (1 << 32) - 3);
        // The slow path's run ends at once, as a lap.
        assert_eq!(Replay::elsewhere().take(), (0, End::Lap));
    }
}
