#![doc = include_str!("../README.md")]
#![cfg_attr(not(feature = "std"), no_std)]

mod bisect;
#[cfg(feature = "conformance")]
pub mod conformance;
mod division;
mod error;
pub mod format;
pub mod gearing;
pub mod interpolation;
mod mcx514;
pub mod predict;
pub mod reference;
mod replay;
mod scurve;
mod state;
pub mod steps;
mod trapezoidal;
mod velocity;
pub mod waveform;

/// The `fixed` crate, re-exported: the state's [`I32F32`](fixed::types::I32F32) and the registers'
/// formats, without a dependency of your own (and always the version this crate uses).
pub use fixed;

pub use error::{Error, Range};
pub use mcx514::{
    DecelerationMode, Mcx514Parameters, Mcx514SCurve, Mcx514ScurveParameters, Mcx514Trapezoidal,
};
pub use predict::Prediction;
pub use scurve::{SCurve, ScurveParameters, ScurvePlan};
pub use state::{AsDynGenerator, Limits, ProfileGenerator, State, States, StopKind};
pub use trapezoidal::{Trapezoidal, TrapezoidalParameters};
pub use velocity::{VelocityContouring, VelocityParameters};
