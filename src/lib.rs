#![doc = include_str!("../README.md")]
#![cfg_attr(not(feature = "std"), no_std)]

mod bisect;
#[cfg(feature = "conformance")]
pub mod conformance;
mod error;
pub mod format;
pub mod interpolation;
mod mcx514;
pub mod reference;
mod scurve;
mod state;
mod trapezoidal;
mod velocity;
pub mod waveform;

pub use error::{Error, Range};
pub use mcx514::{
    DecelerationMode, Mcx514Parameters, Mcx514SCurve, Mcx514ScurveParameters, Mcx514Trapezoidal,
};
pub use scurve::{SCurve, ScurveParameters, ScurvePlan};
pub use state::{Limits, ProfileGenerator, State, States, StopKind};
pub use trapezoidal::{Trapezoidal, TrapezoidalParameters};
pub use velocity::{VelocityContouring, VelocityParameters};
