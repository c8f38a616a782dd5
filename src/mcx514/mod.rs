//! The MCX514's acceleration/deceleration on the driving axis of an interpolation (SPEC §12.2):
//! the trapezoid ([`Mcx514Trapezoidal`]) and the S-curve ([`Mcx514SCurve`]), each a
//! [`ProfileGenerator`](crate::ProfileGenerator) whose position counts interpolation steps.

mod scurve;
mod trapezoidal;

pub use scurve::{Mcx514SCurve, Mcx514ScurveParameters};
pub use trapezoidal::{DecelerationMode, Mcx514Parameters, Mcx514Trapezoidal};
