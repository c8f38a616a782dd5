//! The generators as they stepped before issue #12 (and the trapezoid as its first part left it,
//! `planned`), the yardsticks of `tests/same_states.rs`.
pub mod planned;
pub mod trapezoidal;
pub mod velocity;
