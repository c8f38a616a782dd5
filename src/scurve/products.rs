//! Products of 64-bit integers that take the 32-bit multiplication where both factors fit.
//!
//! On a Cortex-M4, `u64::checked_mul` forms and checks the whole 128-bit product; most of the
//! S-curve planner's products (cycles, spans, widths, ramps by the jerk, most remainders) have
//! both factors under 2^32, where one `umull` gives the exact product and it cannot overflow.
//! The results are `checked_mul`'s and `saturating_mul`'s on every target. Used by the
//! notch pairs' placements ([`super::remainder`]), the shapes and the continuous optimum's
//! ramps ([`super::search`]), the unit mix ([`super::shape::Mix::solve`]) and the class tests
//! of [`super::pure_jerk`]: random moves 100,000–100,999 sum −2.6 % on a Cortex-M4 when the last
//! four took them.

/// `a·b`, or `None` past 2^64 (`u64::checked_mul`); on a 32-bit core [`narrow_product`].
#[inline(always)]
pub(super) fn product(a: u64, b: u64) -> Option<u64> {
    if cfg!(target_pointer_width = "64") {
        a.checked_mul(b)
    } else {
        narrow_product(a, b)
    }
}

/// [`product`] on a 32-bit core: one `umull` where both fit 32 bits (cycles, spans, widths and
/// most remainders), where `u64::checked_mul` forms and checks the whole 128-bit product (a few
/// dozen instructions on a Cortex-M4, in the remainder's innermost loops: 79 → 74 of CI's
/// 3,000 moves from fractional positions over SPEC §16's 20,000, the same plans). Not shared
/// with the trapezoid's landing, whose `saturating_product` is the plain checked product: its
/// factors mostly pass 2^32, and this test cost its worst set-up 17,177 → 18,052.
#[inline(always)]
fn narrow_product(a: u64, b: u64) -> Option<u64> {
    if (a | b) >> 32 == 0 {
        Some(a * b)
    } else {
        a.checked_mul(b)
    }
}

/// `a·b`, or `u64::MAX` past it ([`product`]).
#[inline(always)]
pub(super) fn saturating_product(a: u64, b: u64) -> u64 {
    product(a, b).unwrap_or(u64::MAX)
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(4_000))]

        /// The 32-bit core's product is `checked_mul`'s, on both sides of 2^32 and of overflow.
        #[test]
        fn the_narrow_product_is_the_checked_product(
            a_bits in 0u32..64, a_low in any::<u64>(), b_bits in 0u32..64, b_low in any::<u64>(),
        ) {
            let (a, b) = (a_low >> a_bits, b_low >> b_bits);
            prop_assert_eq!(narrow_product(a, b), a.checked_mul(b));
            prop_assert_eq!(saturating_product(a, b), a.saturating_mul(b));
        }
    }
}
