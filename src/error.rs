//! The one error type of the crate.

/// Everything that can go wrong in `profilegen`: a bad parameter, or a command the chip would refuse.
///
/// Every variant names the parameter and, where there is one, its legal range, so a user reading the
/// message knows what to change. The type is `Copy` and works without `std`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, thiserror::Error)]
#[non_exhaustive]
pub enum Error {
    /// The value, rounded to the register, lies outside the register's range (this includes a
    /// negative value for an unsigned register).
    #[error("{parameter} is out of range: the legal range is {range}")]
    OutOfRange {
        /// The parameter (register) that was being set.
        parameter: &'static str,
        /// The legal range, with units.
        range: &'static str,
    },
    /// The value was NaN or infinite.
    #[error("{parameter} is not a finite number: the legal range is {range}")]
    NotFinite {
        /// The parameter (register) that was being set.
        parameter: &'static str,
        /// The legal range, with units.
        range: &'static str,
    },
    /// Zero is a legal register value but not a legal profile parameter (SPEC §3): a move needs a
    /// non-zero maximum velocity, acceleration and jerk.
    #[error("{parameter} must be non-zero to set up a move: the legal range is {range}")]
    Zero {
        /// The parameter that was zero.
        parameter: &'static str,
        /// The legal range of a usable value, with units.
        range: &'static str,
    },
    /// The generator refused the command in its present state, as the chip would (for example an
    /// S-curve parameter change while the axis is moving: the MC1451A "command error").
    #[error("command error: {parameter} cannot be changed {reason}")]
    Refused {
        /// The parameter whose change was refused.
        parameter: &'static str,
        /// Why, e.g. "while an S-curve move is in motion".
        reason: &'static str,
    },
    /// No move within the limits reaches the target (for example a destination one raw unit
    /// away with a jerk of one raw unit, which would need a jerk of two).
    #[error("{parameter} cannot be reached: {reason}")]
    Unreachable {
        /// The parameter whose value cannot be reached.
        parameter: &'static str,
        /// Why, and what to change.
        reason: &'static str,
    },
    /// A microstep resolution that the waveform table does not support.
    #[error("microsteps per full step is {value}: the legal values are 1, 2, 4, 8, 16, 32, 64, 128, 256")]
    Microsteps {
        /// The value that was given.
        value: u32,
    },
    /// A motor phase count that the waveform table does not support.
    #[error("phase count is {value}: the legal values are 2 and 3")]
    Phases {
        /// The value that was given.
        value: u32,
    },
}
