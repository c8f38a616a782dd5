//! Interpolation geometries (SPEC §12): pure functions from the number of interpolation steps
//! taken to the integer position of every axis, in O(1) per evaluation however many steps lie
//! between two evaluations. A speed profile decides how many steps a cycle takes; a geometry
//! decides where those steps put the axes.

pub mod bit_pattern;
pub mod circular;
pub mod continuous;
mod drive;
pub mod linear;

pub use bit_pattern::{BitPatternInterpolation, BitPatternState, BitWord};
pub use circular::{
    Arc, ArcWalk, CircleState, CircularDriving, CircularInterpolation, Direction, Octant,
};
pub use continuous::{ContinuousDriving, ContinuousInterpolation, ContinuousState, Segment};
pub use drive::{InterpolationState, LinearInterpolation};
pub use linear::{Line, Walk};
