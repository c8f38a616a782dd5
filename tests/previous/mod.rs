//! The generators as they stepped before issue #12, the yardstick of `tests/same_states.rs`.
pub mod trapezoidal;
pub mod velocity;
