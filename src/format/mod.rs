//! Register formats and unit scaling (SPEC §3, §4), one file per chip family.
//!
//! Every register is a newtype over a [`fixed`] number, so a value of one register can't be passed
//! where another is expected. Each is built from a real number (rounded to nearest, ties to even,
//! as the manuals' worked examples do) or from raw bits (checked), and out-of-range input is an
//! [`Error`](crate::Error) naming the register and its legal range.

mod cycle;
pub mod juno;
pub mod mc1451a;
pub mod mcx514;

pub use cycle::{CycleTime, PhysicalState};

/// `2^52`: at and above this magnitude every `f64` is an integer.
const TWO_POW_52: f64 = 4_503_599_627_370_496.0;

/// Rounds to the nearest integer, ties to even, without `std` (`f64::round_ties_even` lives in
/// `std`). Adding and subtracting 2^52 forces the FPU's own round-to-nearest-even at the units
/// place; the operations are exact otherwise, and Rust never reassociates float arithmetic.
fn round_ties_even(x: f64) -> f64 {
    let magnitude = if x < 0.0 { -x } else { x };
    if magnitude >= TWO_POW_52 {
        x
    } else if x < 0.0 {
        -((magnitude + TWO_POW_52) - TWO_POW_52)
    } else {
        (magnitude + TWO_POW_52) - TWO_POW_52
    }
}

/// Converts a real value to raw register bits: scale by `2^frac_bits`, round to nearest (ties to
/// even), check `range` (in raw units: `range.min · 2^frac_bits ..= range.max · 2^frac_bits`).
/// Negative input to an unsigned register (`range.min == 0`) is out of range even when it would
/// round to zero: the manuals call such registers positive. Non-zero input that rounds to zero
/// in a register with fractional bits is [`Error::Underflow`](crate::Error::Underflow): zero would
/// silently mean something else (no motion, "use the acceleration").
fn real_to_bits(
    value: f64,
    frac_bits: u32,
    parameter: &'static str,
    range: crate::Range,
) -> Result<i64, crate::Error> {
    if !value.is_finite() {
        return Err(crate::Error::NotFinite {
            parameter,
            value,
            range,
        });
    }
    let out_of_range = crate::Error::OutOfRange {
        parameter,
        value,
        range,
    };
    if range.min == 0.0 && value < 0.0 {
        return Err(out_of_range);
    }
    // Multiplying by a power of two is exact for every finite value that stays finite; values that
    // overflow to infinity fail the range check below all the same.
    let scale = (1u64 << frac_bits) as f64;
    let rounded = round_ties_even(value * scale);
    // The bounds times the scale are the raw bounds again, exactly (powers of two).
    if rounded < range.min * scale || rounded > range.max * scale {
        return Err(out_of_range);
    }
    if rounded == 0.0 && value != 0.0 && frac_bits > 0 {
        return Err(crate::Error::Underflow {
            parameter,
            value,
            range,
        });
    }
    Ok(rounded as i64)
}

/// Defines one register: a newtype over a `fixed` number with a checked raw range.
macro_rules! register {
    (
        $(#[$meta:meta])*
        $name:ident($fixed:ty, $bits:ty, frac = $frac:expr, min = $min:expr, max = $max:expr),
        parameter = $parameter:expr,
        unit = $unit:expr
        $(, per_second = $power:expr, physical_unit = $physical:expr)?
    ) => {
        $(#[$meta])*
        #[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, Default)]
        pub struct $name($fixed);

        impl $name {
            /// The register's name, as errors report it.
            pub const PARAMETER: &'static str = $parameter;
            /// The register's legal range and resolution, in its own (per-cycle) units, as errors
            /// report it.
            pub const RANGE: $crate::Range =
                $crate::Range::of_register($min as i64, $max as i64, $frac, $unit);
            /// The smallest raw value the register accepts.
            pub const MIN_BITS: $bits = $min;
            /// The largest raw value the register accepts.
            pub const MAX_BITS: $bits = $max;
            /// The smallest legal value.
            pub const MIN: Self = Self(<$fixed>::from_bits($min));
            /// The largest legal value.
            pub const MAX: Self = Self(<$fixed>::from_bits($max));
            /// Zero.
            pub const ZERO: Self = Self(<$fixed>::ZERO);

            /// The register from its raw bits, as sent to the chip.
            ///
            /// # Errors
            /// [`Error::OutOfRange`](crate::Error::OutOfRange) when `bits` lies outside
            #[doc = concat!("`", stringify!($min), " ..= ", stringify!($max), "`.")]
            #[allow(unused_comparisons)] // min is 0 for the unsigned registers
            pub const fn from_bits(bits: $bits) -> Result<Self, crate::Error> {
                if bits < $min || bits > $max {
                    return Err(crate::Error::OutOfRange {
                        parameter: $parameter,
                        value: bits as f64 / (1u64 << $frac) as f64,
                        range: Self::RANGE,
                    });
                }
                Ok(Self(<$fixed>::from_bits(bits)))
            }

            /// The register from a real value in its units, rounded to the nearest raw value
            /// (ties to even) as the manuals' worked examples do.
            ///
            /// # Errors
            /// [`Error::NotFinite`](crate::Error::NotFinite) for NaN or ±∞;
            /// [`Error::OutOfRange`](crate::Error::OutOfRange) when the rounded value lies outside
            /// the register's range, or the value is negative and the register unsigned;
            /// [`Error::Underflow`](crate::Error::Underflow) when a non-zero value rounds to zero
            /// (registers with fractional bits).
            pub fn from_num(value: f64) -> Result<Self, crate::Error> {
                let bits = $crate::format::real_to_bits(value, $frac, $parameter, Self::RANGE)?;
                // In range, so the narrowing cast is exact.
                Ok(Self(<$fixed>::from_bits(bits as $bits)))
            }

            /// The register from a `fixed` value of its own format.
            ///
            /// # Errors
            /// [`Error::OutOfRange`](crate::Error::OutOfRange) outside the register's range.
            pub const fn from_fixed(value: $fixed) -> Result<Self, crate::Error> {
                Self::from_bits(value.to_bits())
            }

            /// The raw bits, as sent to the chip.
            pub const fn to_bits(self) -> $bits {
                self.0.to_bits()
            }

            /// The value in its `fixed` format.
            pub const fn to_fixed(self) -> $fixed {
                self.0
            }

            /// The real value in the register's units (exact: every raw value is an `f64`).
            pub fn to_f64(self) -> f64 {
                self.0.to_num::<f64>()
            }

            /// Whether the register holds zero.
            pub const fn is_zero(self) -> bool {
                self.0.to_bits() == 0
            }

            $(
            #[doc = concat!("The register from a physical value in ", $physical, ": multiplied by the")]
            #[doc = concat!("cycle time to the power ", stringify!($power), ", then rounded as [`Self::from_num`].")]
            ///
            /// # Errors
            /// As [`Self::from_num`], for the scaled value; the error reports `value` and the
            #[doc = concat!("legal range in ", $physical, " at this cycle time.")]
            pub fn from_physical(value: f64, cycle: $crate::format::CycleTime) -> Result<Self, crate::Error> {
                Self::from_num(cycle.per_cycle(value, $power))
                    .map_err(|error| error.in_units(value, cycle.per_second(1.0, $power), $physical))
            }

            #[doc = concat!("The register's value as a physical value in ", $physical, ".")]
            pub fn to_physical(self, cycle: $crate::format::CycleTime) -> f64 {
                cycle.per_second(self.to_f64(), $power)
            }
            )?
        }

        impl core::fmt::Display for $name {
            fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
                core::fmt::Display::fmt(&self.0, f)
            }
        }
    };
}
pub(crate) use register;
