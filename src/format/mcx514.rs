//! NOVA MCX514 registers (SPEC §12.1): the chip's own integer units, and their per-cycle values.
//!
//! Unlike the PMD chips, the MCX514 takes its speeds and rates in physical units: pulses per
//! second (pps), pps/s and pps/s², as integers (16 MHz reference clock). Each register here holds
//! that integer, checked against the range of the chip's command table, and converts to the
//! per-cycle value a cycle-based generator steps with ([`CycleTime`], SPEC §4): `v·T`, `a·T²`,
//! `j·T³`, rounded to nearest (ties to even) into an [`I32F32`], the format of
//! [`State`](crate::State).
//!
//! Speeds, rates and jerks start at **1**, not 0: the chip's command table has no zero for them,
//! so zero (or a value that rounds to zero) is [`Error::OutOfRange`], whose message shows the
//! range `1 … max`. Points (the manual deceleration point, finish point and centre) do include 0.
//!
//! ```
//! use profilegen::format::mcx514::Acceleration;
//! use profilegen::format::CycleTime;
//! // Reference 003: 65,000 pps/s is written as 0xFDE8.
//! let acceleration = Acceleration::from_num(65_000.0)?;
//! assert_eq!(acceleration.to_bits(), 0xFDE8);
//! // At a 1 ms cycle: 65,000 · 0.001² = 0.065 pulses/cycle².
//! let per_cycle = acceleration.per_cycle(CycleTime::from_seconds(1e-3)?)?;
//! assert!((per_cycle.to_num::<f64>() - 0.065).abs() < 1e-9);
//! # Ok::<(), profilegen::Error>(())
//! ```

use fixed::types::I32F32;

use super::CycleTime;
use crate::{Error, Range};

/// The largest per-cycle value, in raw I32F32 bits, that a conversion accepts: `2^63 − 1024`, the
/// largest `f64` below `2^63`, so the range check in `f64` and the cast to `i64` agree exactly
/// (`i64::MAX` itself is not an `f64`; it would round up to `2^63`).
const PER_CYCLE_MAX_BITS: i64 = i64::MAX - 1023;

/// Defines one MCX514 register: a newtype over the chip's integer with a checked range.
macro_rules! mcx514_register {
    (
        $(#[$meta:meta])*
        $name:ident($bits:ty, min = $min:expr, max = $max:expr),
        parameter = $parameter:expr,
        unit = $unit:expr
        $(, per_cycle = $power:expr, per_cycle_unit = $per_cycle_unit:expr)?
    ) => {
        $(#[$meta])*
        #[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
        pub struct $name($bits);

        impl $name {
            /// The register's name, as errors report it.
            pub const PARAMETER: &'static str = $parameter;
            /// The register's legal range, in the chip's units, as errors report it.
            pub const RANGE: Range = Range::of_register($min as i64, $max as i64, 0, $unit);
            /// The smallest value the register accepts.
            pub const MIN_BITS: $bits = $min;
            /// The largest value the register accepts.
            pub const MAX_BITS: $bits = $max;
            /// The smallest legal value.
            pub const MIN: Self = Self($min);
            /// The largest legal value.
            pub const MAX: Self = Self($max);

            /// The register from the integer written to the chip, in its units.
            ///
            /// # Errors
            /// [`Error::OutOfRange`] when `bits` lies outside
            #[doc = concat!("`", stringify!($min), " ..= ", stringify!($max), "`.")]
            #[allow(unused_comparisons)] // min is 0 for the unsigned points
            pub const fn from_bits(bits: $bits) -> Result<Self, Error> {
                if bits < $min || bits > $max {
                    return Err(Error::OutOfRange {
                        parameter: $parameter,
                        value: bits as f64,
                        range: Self::RANGE,
                    });
                }
                Ok(Self(bits))
            }

            /// The register from a real value in its units, rounded to the nearest integer (ties
            /// to even).
            ///
            /// # Errors
            /// [`Error::NotFinite`] for NaN or ±∞; [`Error::OutOfRange`] when the rounded value
            /// lies outside the register's range.
            pub fn from_num(value: f64) -> Result<Self, Error> {
                let bits = super::real_to_bits(value, 0, $parameter, Self::RANGE)?;
                // In range, so the narrowing cast is exact.
                Ok(Self(bits as $bits))
            }

            /// The integer written to the chip.
            pub const fn to_bits(self) -> $bits {
                self.0
            }

            /// The value as a real number in the register's units (exact).
            pub fn to_f64(self) -> f64 {
                self.0 as f64
            }

            $(
            #[doc = concat!("The value per cycle of `cycle`, in ", $per_cycle_unit, ": the")]
            #[doc = concat!("register times `T^", stringify!($power), "`, rounded to nearest (ties")]
            /// to even) to 2⁻³² — the resolution of [`State`](crate::State).
            ///
            /// # Errors
            /// [`Error::Underflow`] when the per-cycle value rounds to zero (a cycle so short
            /// that the register is below half of 2⁻³² per cycle), [`Error::OutOfRange`] when it
            /// exceeds the I32F32 range (a cycle of seconds); both report the register's value
            /// and the I32F32 range in the register's units at this cycle time.
            pub fn per_cycle(self, cycle: CycleTime) -> Result<I32F32, Error> {
                per_cycle(self.to_f64(), $power, cycle, $parameter, $unit)
            }
            )?
        }

        impl core::fmt::Display for $name {
            fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
                write!(f, "{} {}", self.0, $unit)
            }
        }
    };
}

/// `value · T^power` rounded into an I32F32; errors in the register's own units.
fn per_cycle(
    value: f64,
    power: u32,
    cycle: CycleTime,
    parameter: &'static str,
    unit: &'static str,
) -> Result<I32F32, Error> {
    // Non-negative range: the registers are positive. Resolution 2^-32 per cycle.
    let range = Range::of_register(0, PER_CYCLE_MAX_BITS, 32, "per cycle");
    super::real_to_bits(cycle.per_cycle(value, power), 32, parameter, range)
        .map(I32F32::from_bits)
        .map_err(|error| error.in_units(value, cycle.per_second(1.0, power), unit))
}

mcx514_register! {
    /// Initial speed SV: the speed the driving axis starts at and decelerates down to,
    /// 1 … 8,000,000 pps.
    InitialSpeed(u32, min = 1, max = 8_000_000),
    parameter = "initial speed",
    unit = "pps",
    per_cycle = 1, per_cycle_unit = "pulses/cycle"
}

mcx514_register! {
    /// Drive speed DV: the speed the driving axis accelerates to and cruises at,
    /// 1 … 8,000,000 pps.
    ///
    /// ```
    /// use profilegen::format::mcx514::DriveSpeed;
    /// use profilegen::format::CycleTime;
    /// let speed = DriveSpeed::from_bits(20_000)?;
    /// // 20,000 pps · 1 ms = 20 pulses/cycle, exactly.
    /// let per_cycle = speed.per_cycle(CycleTime::from_seconds(1e-3)?)?;
    /// assert_eq!(per_cycle, 20);
    /// # Ok::<(), profilegen::Error>(())
    /// ```
    DriveSpeed(u32, min = 1, max = 8_000_000),
    parameter = "drive speed",
    unit = "pps",
    per_cycle = 1, per_cycle_unit = "pulses/cycle"
}

mcx514_register! {
    /// Acceleration AC: 1 … 536,870,911 pps/s (2²⁹ − 1).
    Acceleration(u32, min = 1, max = 536_870_911),
    parameter = "acceleration",
    unit = "pps/s",
    per_cycle = 2, per_cycle_unit = "pulses/cycle²"
}

mcx514_register! {
    /// Deceleration DC: 1 … 536,870,911 pps/s (2²⁹ − 1).
    Deceleration(u32, min = 1, max = 536_870_911),
    parameter = "deceleration",
    unit = "pps/s",
    per_cycle = 2, per_cycle_unit = "pulses/cycle²"
}

mcx514_register! {
    /// Jerk JK, the chip's "acceleration increasing rate": 1 … 1,073,741,823 pps/s² (2³⁰ − 1).
    Jerk(u32, min = 1, max = 1_073_741_823),
    parameter = "jerk",
    unit = "pps/s²",
    per_cycle = 3, per_cycle_unit = "pulses/cycle³"
}

mcx514_register! {
    /// Deceleration jerk DJ, the chip's "deceleration increasing rate":
    /// 1 … 1,073,741,823 pps/s² (2³⁰ − 1).
    DecelerationJerk(u32, min = 1, max = 1_073_741_823),
    parameter = "deceleration increasing rate",
    unit = "pps/s²",
    per_cycle = 3, per_cycle_unit = "pulses/cycle³"
}

mcx514_register! {
    /// Manual deceleration point DP: the driving axis's output count (in interpolation, the
    /// long axis's pulses) at which deceleration starts, 0 … 4,294,967,292 pulses.
    ManualDecelerationPoint(u32, min = 0, max = 4_294_967_292),
    parameter = "manual deceleration point",
    unit = "pulses"
}

mcx514_register! {
    /// One axis's finish point in interpolation, relative to the start:
    /// −1,073,741,823 … 1,073,741,823 pulses (symmetric: ±(2³⁰ − 1)).
    FinishPoint(i32, min = -1_073_741_823, max = 1_073_741_823),
    parameter = "finish point",
    unit = "pulses"
}

mcx514_register! {
    /// One coordinate of a circle's centre, relative to the start:
    /// −1,073,741,823 … 1,073,741,823 pulses.
    Centre(i32, min = -1_073_741_823, max = 1_073_741_823),
    parameter = "centre",
    unit = "pulses"
}

/// The manual deceleration point of a move of `total_pulses` driving-axis pulses that needs
/// `deceleration_pulses` to slow down: `total − deceleration` (reference 003; for a circle, the
/// total is the short-axis pulse count: 56,568 − 3,075 = 53,493 for r = 10,000).
///
/// # Errors
/// [`Error::OutOfRange`] (parameter `manual deceleration point`) when the deceleration needs more
/// pulses than the move has (the point would be negative), or the point exceeds the register.
pub fn manual_deceleration_point(
    total_pulses: u64,
    deceleration_pulses: u64,
) -> Result<ManualDecelerationPoint, Error> {
    // i128: both u64, so the difference is exact whatever its sign.
    let point = i128::from(total_pulses) - i128::from(deceleration_pulses);
    match u32::try_from(point) {
        Ok(point) => ManualDecelerationPoint::from_bits(point),
        Err(_) => Err(Error::OutOfRange {
            parameter: ManualDecelerationPoint::PARAMETER,
            value: point as f64,
            range: ManualDecelerationPoint::RANGE,
        }),
    }
}

/// The manual deceleration point of a linear interpolation to `finish` (2–4 axes, relative):
/// counted in long-axis pulses, `max|Δᵢ| − deceleration_pulses` (reference 003: "set the maximum
/// absolute value among the finish points of each axis coordinates as the manual deceleration
/// point of the main axis").
///
/// ```
/// use profilegen::format::mcx514::{linear_manual_deceleration_point, FinishPoint};
/// // Reference 003: finish (−20000, 30000, −50000), 5,000 pulses to decelerate → 45,000.
/// let finish = [-20_000, 30_000, -50_000].map(|p| FinishPoint::from_bits(p).unwrap());
/// assert_eq!(linear_manual_deceleration_point(&finish, 5_000)?.to_bits(), 45_000);
/// # Ok::<(), profilegen::Error>(())
/// ```
///
/// # Errors
/// As [`manual_deceleration_point`]: the deceleration needs more pulses than the long axis has.
pub fn linear_manual_deceleration_point<const N: usize>(
    finish: &[FinishPoint; N],
    deceleration_pulses: u64,
) -> Result<ManualDecelerationPoint, Error> {
    let long_axis = finish
        .iter()
        .map(|point| point.to_bits().unsigned_abs())
        .max()
        .unwrap_or(0);
    manual_deceleration_point(u64::from(long_axis), deceleration_pulses)
}

/// The pulses a trapezoid outputs while it slows from the drive speed DV to the initial speed SV
/// at the deceleration DC: `(DV² − SV²) / (2·DC)`, the area under the speed ramp — the manual's
/// `(SV + DV)·t/2` with `t = (DV − SV)/DC` — rounded **up**, so a deceleration point computed
/// from it errs early (a short creep at SV) rather than late (a stop above SV). Zero when
/// DV ≤ SV (no ramp). The same formula with the acceleration gives the pulses of the speed-up.
///
/// This is the continuous-time count the manual's examples use; a cycle-based profile's own
/// count can differ by the pulses of a cycle or two.
///
/// ```
/// use profilegen::format::mcx514::{deceleration_pulses, Deceleration, DriveSpeed, InitialSpeed};
/// // Reference 003: (500 + 20,000) · 0.3 / 2 = 3,075 pulses at 65,000 pps/s.
/// let pulses = deceleration_pulses(
///     InitialSpeed::from_bits(500)?,
///     DriveSpeed::from_bits(20_000)?,
///     Deceleration::from_bits(65_000)?,
/// );
/// assert_eq!(pulses, 3_075);
/// # Ok::<(), profilegen::Error>(())
/// ```
pub fn deceleration_pulses(
    initial: InitialSpeed,
    drive: DriveSpeed,
    deceleration: Deceleration,
) -> u64 {
    let (initial, drive) = (u64::from(initial.to_bits()), u64::from(drive.to_bits()));
    if drive <= initial {
        return 0;
    }
    // u64: DV² ≤ (8·10⁶)² = 6.4·10¹³ and 2·DC < 2³⁰, far inside 2⁶⁴.
    let area_twice = drive * drive - initial * initial;
    area_twice.div_ceil(2 * u64::from(deceleration.to_bits()))
}

/// The acceleration that takes the speed from `initial` to `drive` in `seconds`:
/// `|DV − SV| / t` pps/s, rounded to the nearest integer (reference 003: 500 → 20,000 pps in
/// 0.3 s is 65,000 pps/s, 0xFDE8). For the deceleration register, the same value:
/// `Deceleration::from_bits(acceleration.to_bits())`.
///
/// ```
/// use profilegen::format::mcx514::{acceleration_for_change, DriveSpeed, InitialSpeed};
/// let acceleration =
///     acceleration_for_change(InitialSpeed::from_bits(500)?, DriveSpeed::from_bits(20_000)?, 0.3)?;
/// assert_eq!(acceleration.to_bits(), 0xFDE8);
/// # Ok::<(), profilegen::Error>(())
/// ```
///
/// # Errors
/// [`Error::NotFinite`] or [`Error::OutOfRange`] (parameter `duration`, in s) unless `seconds` is
/// finite and positive; [`Error::OutOfRange`] (parameter `acceleration`, in pps/s) when the rate
/// rounds outside 1 … 536,870,911 pps/s (equal speeds, or a change too slow or too fast).
pub fn acceleration_for_change(
    initial: InitialSpeed,
    drive: DriveSpeed,
    seconds: f64,
) -> Result<Acceleration, Error> {
    super::cycle::check_duration(seconds)?;
    let change = drive.to_f64() - initial.to_f64();
    let magnitude = if change < 0.0 { -change } else { change };
    Acceleration::from_num(magnitude / seconds)
}
