//! The cycle time and the conversions between per-second and per-cycle units (SPEC §4).

use crate::{Error, Range};

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
