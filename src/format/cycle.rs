//! The cycle time and the conversions between per-second and per-cycle units (SPEC §4).

use crate::{Error, Range, State};

/// A profile generator's cycle time (its sample time), in seconds.
///
/// The chips' registers are in per-cycle units: a velocity in counts/cycle is `v·T`, an
/// acceleration in counts/cycle² is `a·T²`, a jerk in counts/cycle³ is `j·T³`.
///
/// ```
/// use profilegen::format::CycleTime;
/// // 135,000 counts/s on a Juno is 13.824 counts/cycle.
/// let v = CycleTime::JUNO.per_cycle(135_000.0, 1);
/// assert!((v - 13.824).abs() < 1e-12);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, PartialOrd)]
pub struct CycleTime {
    seconds: f64,
}

/// The parameter name and range that cycle-time errors report.
const CYCLE_TIME: (&str, Range) = ("cycle time", Range::positive("s"));

impl CycleTime {
    /// The Juno cycle time: 102.4 µs nominal (±0.5 % over temperature).
    pub const JUNO: Self = Self { seconds: 102.4e-6 };
    /// The MC1451A cycle time: 330 µs, fixed ("not adjustable").
    pub const MC1451A: Self = Self { seconds: 330e-6 };

    /// A custom cycle time in seconds.
    ///
    /// # Errors
    /// [`Error::NotFinite`] for NaN or ±∞, [`Error::OutOfRange`] for zero or a negative time.
    pub fn from_seconds(seconds: f64) -> Result<Self, Error> {
        let (parameter, range) = CYCLE_TIME;
        let value = seconds;
        if !seconds.is_finite() {
            return Err(Error::NotFinite {
                parameter,
                value,
                range,
            });
        }
        if seconds <= 0.0 {
            return Err(Error::OutOfRange {
                parameter,
                value,
                range,
            });
        }
        Ok(Self { seconds })
    }

    /// A custom cycle time from a cycle rate in cycles per second (the Juno manual's worked
    /// example uses 9,765 cycles/s).
    ///
    /// # Errors
    /// [`Error::NotFinite`] or [`Error::OutOfRange`] (parameter `cycle rate`, in cycles/s) unless
    /// the rate is finite and positive with a finite period.
    pub fn from_hertz(hertz: f64) -> Result<Self, Error> {
        let (parameter, range) = ("cycle rate", Range::positive("cycles/s"));
        if !hertz.is_finite() {
            return Err(Error::NotFinite {
                parameter,
                value: hertz,
                range,
            });
        }
        if hertz <= 0.0 {
            return Err(Error::OutOfRange {
                parameter,
                value: hertz,
                range,
            });
        }
        Self::from_seconds(1.0 / hertz).map_err(|_| Error::OutOfRange {
            // Finite and positive, yet 1/hertz is not (a subnormal rate): too slow to represent.
            parameter,
            value: hertz,
            range,
        })
    }

    /// The cycle time in seconds.
    pub const fn seconds(self) -> f64 {
        self.seconds
    }

    /// `T^power` (power 0 … 3), by repeated multiplication so no `std` math is needed.
    fn power_of(self, power: u32) -> f64 {
        (0..power).fold(1.0, |product, _| product * self.seconds)
    }

    /// A per-second quantity to per-cycle units: `value · T^power` (power 1 for velocity, 2 for
    /// acceleration, 3 for jerk). Round it to a register with that register's `from_num`.
    pub fn per_cycle(self, value: f64, power: u32) -> f64 {
        value * self.power_of(power)
    }

    /// A per-cycle quantity to per-second units: `value / T^power`.
    pub fn per_second(self, value: f64, power: u32) -> f64 {
        value / self.power_of(power)
    }

    /// How many cycles a duration in seconds spans (not rounded: the caller decides).
    ///
    /// # Errors
    /// [`Error::NotFinite`] or [`Error::OutOfRange`] (parameter `duration`) unless the duration is
    /// finite and positive.
    pub fn cycles_in(self, seconds: f64) -> Result<f64, Error> {
        check_duration(seconds)?;
        Ok(seconds / self.seconds)
    }

    /// The acceleration in counts/cycle² that goes from `from_counts_per_second` to
    /// `to_counts_per_second` in `seconds` (the Juno manual's "135,000 counts/s after 120 ms"):
    /// `|Δv|·T / (t/T) = |Δv|·T²/t`. Round it to a register with that register's `from_num`.
    ///
    /// # Errors
    /// [`Error::NotFinite`] or [`Error::OutOfRange`] (parameter `duration`) unless `seconds` is
    /// finite and positive; [`Error::NotFinite`] (parameter `velocity`) for non-finite velocities.
    pub fn acceleration_for_change(
        self,
        from_counts_per_second: f64,
        to_counts_per_second: f64,
        seconds: f64,
    ) -> Result<f64, Error> {
        check_duration(seconds)?;
        let change = to_counts_per_second - from_counts_per_second;
        if !change.is_finite() {
            return Err(Error::NotFinite {
                parameter: "velocity change",
                value: change,
                range: Range::finite("counts/s"),
            });
        }
        let magnitude = if change < 0.0 { -change } else { change };
        Ok(magnitude * self.seconds * self.seconds / seconds)
    }
}

/// A [`State`] in physical units, for display and for users' own planning (floats at the edge
/// only: the state itself stays exact).
#[derive(Debug, Clone, Copy, PartialEq, PartialOrd, Default)]
pub struct PhysicalState {
    /// Position, counts (the nearest `f64` to the exact I32F32).
    pub position: f64,
    /// Velocity, counts/s.
    pub counts_per_second: f64,
    /// Acceleration, counts/s².
    pub counts_per_second_squared: f64,
}

impl CycleTime {
    /// The duration of `cycles` cycles, in seconds (e.g. a plan's `total`).
    ///
    /// ```
    /// use profilegen::format::CycleTime;
    /// assert!((CycleTime::MC1451A.seconds_for(1_000) - 0.33).abs() < 1e-12);
    /// ```
    pub fn seconds_for(self, cycles: u64) -> f64 {
        cycles as f64 * self.seconds
    }

    /// The number of whole cycles stepped by `seconds` after the start, `⌊t / T⌋`: the `n` to
    /// give `state_at(n)` for the state at time `t` (the state holds from cycle `n` until cycle
    /// `n + 1`).
    ///
    /// # Errors
    /// [`Error::NotFinite`] or [`Error::OutOfRange`] (parameter `time`, 0 … 2⁶⁴ cycles) unless
    /// the time is finite, not negative, and under 2⁶⁴ cycles.
    pub fn cycles_at(self, seconds: f64) -> Result<u64, Error> {
        // 2^64 as an f64 is exact; every f64 below it converts to u64 by truncation (floor
        // for non-negative values).
        const CYCLES_LIMIT: f64 = 18_446_744_073_709_551_616.0;
        let range = Range {
            min: 0.0,
            max: CYCLES_LIMIT * self.seconds,
            resolution: self.seconds,
            unit: "s",
        };
        let parameter = "time";
        if !seconds.is_finite() {
            return Err(Error::NotFinite {
                parameter,
                value: seconds,
                range,
            });
        }
        let cycles = seconds / self.seconds;
        if !(0.0..CYCLES_LIMIT).contains(&cycles) {
            return Err(Error::OutOfRange {
                parameter,
                value: seconds,
                range,
            });
        }
        Ok(cycles as u64)
    }

    /// A state in physical units: counts, counts/s (`v / T`), counts/s² (`a / T²`).
    ///
    /// ```
    /// use profilegen::fixed::types::I32F32;
    /// use profilegen::format::CycleTime;
    /// use profilegen::State;
    ///
    /// let state = State { position: I32F32::from_num(10), velocity: I32F32::from_num(0.5),
    ///     acceleration: I32F32::from_num(0.25) };
    /// let physical = CycleTime::from_seconds(0.5)?.physical(state);
    /// assert_eq!((physical.position, physical.counts_per_second), (10.0, 1.0));
    /// assert_eq!(physical.counts_per_second_squared, 1.0);
    /// # Ok::<(), profilegen::Error>(())
    /// ```
    pub fn physical(self, state: State) -> PhysicalState {
        PhysicalState {
            position: state.position.to_num(),
            counts_per_second: self.per_second(state.velocity.to_num(), 1),
            counts_per_second_squared: self.per_second(state.acceleration.to_num(), 2),
        }
    }
}

/// A duration must be finite and positive (parameter `duration`, in s).
pub(super) fn check_duration(seconds: f64) -> Result<(), Error> {
    let (parameter, value, range) = ("duration", seconds, Range::positive("s"));
    if !seconds.is_finite() {
        return Err(Error::NotFinite {
            parameter,
            value,
            range,
        });
    }
    if seconds <= 0.0 {
        return Err(Error::OutOfRange {
            parameter,
            value,
            range,
        });
    }
    Ok(())
}
