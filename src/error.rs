//! The one error type of the crate, and the legal range its messages report.

use core::fmt;

/// Everything that can go wrong in `profilegen`: a bad parameter, or a command the chip would refuse.
///
/// Every variant names the parameter and, where there is one, the value given and the legal
/// range in the caller's own units (counts/s for a conversion from counts/s), so a user reading
/// the message knows what to change. The type is `Copy` and works without `std`.
///
/// ```
/// use profilegen::format::juno::TargetVelocity;
/// use profilegen::format::CycleTime;
///
/// let error = TargetVelocity::from_physical(5e9, CycleTime::JUNO).unwrap_err();
/// assert_eq!(
///     error.to_string(),
///     "velocity 5000000000 counts/s is out of range: the legal range is -320000000 … \
///      319999999.85 counts/s"
/// );
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub enum Error {
    /// The value, rounded to the register, lies outside the register's range (this includes a
    /// negative value for an unsigned register).
    OutOfRange {
        /// The parameter (register) that was being set.
        parameter: &'static str,
        /// The value given, in the caller's units.
        value: f64,
        /// The legal range, in the caller's units.
        range: Range,
    },
    /// The value was NaN or infinite.
    NotFinite {
        /// The parameter (register) that was being set.
        parameter: &'static str,
        /// The value given (NaN or ±∞).
        value: f64,
        /// The legal range, in the caller's units.
        range: Range,
    },
    /// A non-zero value so small that it rounds to a zero register: zero would silently stand in
    /// for what was asked (a zero rate that means "use the acceleration", a move that can't
    /// start), so it is refused instead.
    Underflow {
        /// The parameter (register) that was being set.
        parameter: &'static str,
        /// The value given, in the caller's units.
        value: f64,
        /// The legal range and resolution, in the caller's units.
        range: Range,
    },
    /// Zero is a legal register value but not a legal profile parameter (SPEC §3): a move needs a
    /// non-zero maximum velocity, acceleration and jerk.
    Zero {
        /// The parameter that was zero.
        parameter: &'static str,
        /// The register's range and resolution: a usable value lies between one raw unit
        /// (`range.resolution`) and `range.max`.
        range: Range,
    },
    /// The generator refused the command in its present state, as the chip would (for example an
    /// S-curve parameter change while the axis is moving: the MC1451A "command error").
    Refused {
        /// The parameter whose change was refused.
        parameter: &'static str,
        /// Why, e.g. "while an S-curve move is in motion".
        reason: &'static str,
    },
    /// No move within the limits reaches the target (for example a destination one raw unit
    /// away with a jerk of one raw unit, which would need a jerk of two).
    Unreachable {
        /// The parameter whose value cannot be reached.
        parameter: &'static str,
        /// Why, and what to change.
        reason: &'static str,
    },
    /// A microstep resolution that the waveform table does not support.
    Microsteps {
        /// The value that was given.
        value: u32,
    },
    /// A motor phase count that the waveform table does not support.
    Phases {
        /// The value that was given.
        value: u32,
    },
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            Error::OutOfRange {
                parameter,
                value,
                range,
            } => write!(
                f,
                "{parameter} {} is out of range: the legal range is {range}",
                Given(value, range.unit)
            ),
            Error::NotFinite {
                parameter,
                value,
                range,
            } => write!(
                f,
                "{parameter} {value} is not a finite number: the legal range is {range}"
            ),
            Error::Underflow {
                parameter,
                value,
                range,
            } => write!(
                f,
                "{parameter} {} rounds to 0 in the register, whose resolution is {}{}: give 0 \
                 itself or a magnitude above half the resolution (the legal range is {range})",
                Given(value, range.unit),
                Bound(range.resolution),
                Unit(range.unit)
            ),
            Error::Zero { parameter, range } => write!(
                f,
                "{parameter} is 0, and a move needs a non-zero one: from {} to {}{}",
                Bound(range.resolution),
                Bound(range.max),
                Unit(range.unit)
            ),
            Error::Refused { parameter, reason } => {
                write!(f, "command error: {parameter} cannot be changed {reason}")
            }
            Error::Unreachable { parameter, reason } => {
                write!(f, "{parameter} cannot be reached: {reason}")
            }
            Error::Microsteps { value } => write!(
                f,
                "microsteps per full step is {value}: the legal values are 1, 2, 4, 8, 16, 32, \
                 64, 128, 256"
            ),
            Error::Phases { value } => {
                write!(f, "phase count is {value}: the legal values are 2 and 3")
            }
        }
    }
}

/// `core::error::Error`, so `?` turns an `Error` into a `Box<dyn Error>` (with or without `std`).
impl core::error::Error for Error {}

/// A unit after a number: a space and the unit, or nothing for a ratio.
struct Unit(&'static str);

impl fmt::Display for Unit {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.0 {
            "" => Ok(()),
            unit => write!(f, " {unit}"),
        }
    }
}

impl Error {
    /// [`Error::OutOfRange`] for a register value given as raw bits with `frac_bits` fractional
    /// bits. The conversion to a real number happens here, at the edge, so the generators that
    /// report such errors stay free of floating point (SPEC §16).
    pub(crate) fn out_of_range_bits(
        parameter: &'static str,
        bits: i64,
        frac_bits: u32,
        range: Range,
    ) -> Self {
        Error::OutOfRange {
            parameter,
            value: Range::real(bits, frac_bits),
            range,
        }
    }

    /// The same error for a value the caller gave in other units: `value` as given, and the range
    /// multiplied by `factor` (caller's units per register unit) in `unit`. Physical-unit
    /// conversions use it so an input in counts/s is answered in counts/s.
    pub(crate) fn in_units(self, value: f64, factor: f64, unit: &'static str) -> Self {
        match self {
            Error::OutOfRange {
                parameter, range, ..
            } => Error::OutOfRange {
                parameter,
                value,
                range: range.scaled(factor, unit),
            },
            Error::NotFinite {
                parameter, range, ..
            } => Error::NotFinite {
                parameter,
                value,
                range: range.scaled(factor, unit),
            },
            Error::Underflow {
                parameter, range, ..
            } => Error::Underflow {
                parameter,
                value,
                range: range.scaled(factor, unit),
            },
            other => other,
        }
    }
}

/// A parameter's legal values, in some unit: what errors report.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Range {
    /// The smallest legal value (`-∞` for no bound).
    pub min: f64,
    /// The largest legal value (`+∞` for no bound).
    pub max: f64,
    /// One raw unit of the register (the smallest non-zero magnitude it holds), or 0 for a
    /// quantity that is not a register.
    pub resolution: f64,
    /// The unit, e.g. `"counts/cycle"`; empty for a ratio.
    pub unit: &'static str,
}

impl Range {
    /// Any value above zero (a time): `min` 0, no upper bound.
    pub const fn positive(unit: &'static str) -> Self {
        Self {
            min: 0.0,
            max: f64::INFINITY,
            resolution: 0.0,
            unit,
        }
    }

    /// Any finite value.
    pub const fn finite(unit: &'static str) -> Self {
        Self {
            min: f64::NEG_INFINITY,
            max: f64::INFINITY,
            resolution: 0.0,
            unit,
        }
    }

    /// The range of a register with raw values `min_bits ..= max_bits` and `frac_bits` fractional
    /// bits, in `unit`.
    pub const fn of_register(
        min_bits: i64,
        max_bits: i64,
        frac_bits: u32,
        unit: &'static str,
    ) -> Self {
        // Exact: the bounds have at most 32 significant bits and the scale is a power of two.
        let resolution = 1.0 / (1u64 << frac_bits) as f64;
        Self {
            min: min_bits as f64 * resolution,
            max: max_bits as f64 * resolution,
            resolution,
            unit,
        }
    }

    /// The same range up to a register value given as raw bits with `frac_bits` fractional bits
    /// (e.g. a starting velocity's limit, the maximum velocity); see
    /// [`Error::out_of_range_bits`] for why raw.
    pub(crate) fn up_to_bits(self, bits: i64, frac_bits: u32) -> Self {
        Self {
            max: Self::real(bits, frac_bits),
            ..self
        }
    }

    /// Raw bits as a real number (exact for the registers' at most 32 significant bits).
    const fn real(bits: i64, frac_bits: u32) -> f64 {
        bits as f64 / (1u64 << frac_bits) as f64
    }

    /// The same range with every bound multiplied by `factor` (> 0), in `unit`.
    pub fn scaled(self, factor: f64, unit: &'static str) -> Self {
        Self {
            min: self.min * factor,
            max: self.max * factor,
            resolution: self.resolution * factor,
            unit,
        }
    }
}

impl fmt::Display for Range {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let unit = Unit(self.unit);
        match (self.min.is_finite(), self.max.is_finite()) {
            (false, false) => write!(f, "any finite value{unit}"),
            (true, false) => write!(f, "above {}{unit}", Bound(self.min)),
            _ => write!(f, "{} … {}{unit}", Bound(self.min), Bound(self.max)),
        }
    }
}

/// A value as the caller gave it (shortest form that reads back the same), with its unit.
struct Given(f64, &'static str);

impl fmt::Display for Given {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let Given(value, unit) = *self;
        let magnitude = if value < 0.0 { -value } else { value };
        // Plain decimals for everyday magnitudes; `1e-300` rather than three hundred zeros.
        if value == 0.0 || (1e-6..1e16).contains(&magnitude) {
            write!(f, "{value}{}", Unit(unit))
        } else {
            write!(f, "{value:e}{}", Unit(unit))
        }
    }
}

/// A range's bound: eleven significant digits, cut toward zero (so the printed bound is itself a
/// legal value), trailing zeros dropped; scientific notation outside 1e-5 … 1e10.
pub(crate) struct Bound(pub(crate) f64);

/// Significant digits of a printed bound.
const DIGITS: i32 = 11;

impl fmt::Display for Bound {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let value = self.0;
        if value == 0.0 || !value.is_finite() {
            return write!(f, "{value}");
        }
        let magnitude = if value < 0.0 { -value } else { value };
        // The decimal exponent of the leading digit, by scaling (no `std` logarithm).
        let mut exponent = 0i32;
        let mut scaled = magnitude;
        while scaled >= 10.0 {
            scaled /= 10.0;
            exponent += 1;
        }
        while scaled < 1.0 {
            scaled *= 10.0;
            exponent -= 1;
        }
        // The leading digits as an integer, cut toward zero: 11 digits fit a u64 exactly enough
        // (the digits come from an f64, itself good to about 16).
        let mut digits = truncate(scaled * pow10(DIGITS - 1));
        let mut decimals = DIGITS - 1; // digits after the leading one
        while decimals > 0 && digits % 10 == 0 {
            digits /= 10;
            decimals -= 1;
        }
        let sign = if value < 0.0 { "-" } else { "" };
        let unit = pow10_u64(decimals);
        let (whole, fraction) = (digits / unit, digits % unit);
        if !(-5..10).contains(&exponent) {
            // d.ddd…e±x
            return match decimals {
                0 => write!(f, "{sign}{whole}e{exponent}"),
                _ => write!(
                    f,
                    "{sign}{whole}.{fraction:0width$}e{exponent}",
                    width = decimals as usize
                ),
            };
        }
        // Positional: the digits with the decimal point moved by the exponent.
        let point = exponent + 1; // digits before the point (≤ 0: leading zeros after it)
        let all = digits;
        let count = decimals + 1; // significant digits kept
        if point >= count {
            write!(f, "{sign}{all}")?;
            return zeros(f, point - count);
        }
        if point <= 0 {
            write!(f, "{sign}0.")?;
            zeros(f, -point)?;
            return write!(f, "{all}");
        }
        let unit = pow10_u64(count - point);
        write!(
            f,
            "{sign}{}.{:0width$}",
            all / unit,
            all % unit,
            width = (count - point) as usize
        )
    }
}

/// `count` zeros (the `0` flag pads numbers, not strings).
fn zeros(f: &mut fmt::Formatter<'_>, count: i32) -> fmt::Result {
    (0..count).try_for_each(|_| f.write_str("0"))
}

fn pow10(power: i32) -> f64 {
    (0..power).fold(1.0, |product, _| product * 10.0)
}

fn pow10_u64(power: i32) -> u64 {
    (0..power).fold(1, |product, _| product * 10)
}

/// `x` (0 ≤ x < 2^53) cut to an integer, allowing for the rounding of the scaling by powers of
/// ten: a value a hair below an integer (…99999.99999999) is that integer.
fn truncate(x: f64) -> u64 {
    let nearest = (x + 0.5) as u64;
    let difference = nearest as f64 - x;
    if -1e-4 < difference && difference < 1e-4 {
        nearest
    } else {
        x as u64
    }
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::Bound;

    #[test]
    fn bounds_print_eleven_digits_cut_toward_zero() {
        let cases: [(f64, &str); 9] = [
            (0.5, "0.5"),
            (100.0, "100"),
            (-0.001, "-0.001"),
            (1e-10, "1e-10"),
            (12_345_678_901_234.0, "1.2345678901e13"),
            // 2/3 = 0.666…: cut, not rounded up to …667.
            (2.0 / 3.0, "0.66666666666"),
            (-32_768.0, "-32768"),
            (4_294_967_295.0, "4294967295"),
            (0.000_015_258_789_062_5, "0.000015258789062"),
        ];
        for (value, expected) in cases {
            let mut text = std::string::String::new();
            core::fmt::write(&mut text, format_args!("{}", Bound(value))).unwrap();
            assert_eq!(text, expected, "{value}");
        }
    }
}
