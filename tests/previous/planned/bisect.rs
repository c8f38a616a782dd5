//! Bisection over integers: the one search the trapezoid's and the S-curve's planners share
//! wherever a condition is monotone in a cycle count or a rate.

use num_traits::PrimInt;

/// The last value in `low ..= high − 1` for which `holds` is true, when `holds` is true from
/// `low` on up to some point and false from there to `high` (`holds(low)` is taken as true and
/// `holds(high)` as false; neither is asked). ⌈log₂(high − low)⌉ calls.
pub(crate) fn last_true<T: PrimInt>(mut low: T, mut high: T, holds: impl Fn(T) -> bool) -> T {
    while high - low > T::one() {
        let middle = low + ((high - low) >> 1);
        if holds(middle) {
            low = middle;
        } else {
            high = middle;
        }
    }
    low
}
