//! Bisection over integers: the one search the trapezoid's and the S-curve's planners and the
//! predictions share wherever a condition is monotone in a cycle count or a rate.

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

#[cfg(test)]
mod tests {
    use super::*;

    /// Against a linear scan, for every threshold in a small range and both ends.
    #[test]
    fn finds_the_last_value_that_holds() {
        for low in -5i64..5 {
            for high in low + 1..low + 12 {
                for threshold in low..high {
                    let found = last_true(low, high, |x| x <= threshold);
                    assert_eq!(found, threshold, "{low}..{high} threshold {threshold}");
                }
            }
        }
        assert_eq!(last_true(0u64, 1, |_| unreachable!()), 0);
        assert_eq!(
            last_true(0i128, i128::MAX, |x| x < 1 << 100),
            (1 << 100) - 1
        );
    }
}
