//! Division of 64-bit integers that takes the 32-bit instruction where the operands fit.
//!
//! On a Cortex-M4 a 64-bit division is a library call of about 80 instructions, a 32-bit one a
//! single `udiv`/`sdiv`; most of the S-curve planner's quotients (ramp lengths, unit counts,
//! spans) have both operands under 2^32, so checking costs a few instructions and saves the
//! call, and the trapezoid's landing divides by its rates in every step of its searches. The
//! results are the same as the 64-bit operators', panics on a zero divisor included. A 64-bit
//! dividend by a 32-bit divisor takes a long division in 32-bit steps, and a divisor of 64 bits
//! one such step on its top half, each about half the library's cost.

/// `(⌊n / d⌋, n mod d)`: the hardware's own division on a 64-bit target.
#[cfg(target_pointer_width = "64")]
#[inline]
pub(crate) fn div_rem(n: u64, d: u64) -> (u64, u64) {
    (n / d, n % d)
}

/// `(⌊n / d⌋, n mod d)`.
#[cfg(not(target_pointer_width = "64"))]
#[inline]
pub(crate) fn div_rem(n: u64, d: u64) -> (u64, u64) {
    match (u32::try_from(n), u32::try_from(d)) {
        (Ok(n), Ok(d)) => (u64::from(n / d), u64::from(n % d)),
        (Err(_), Ok(d)) if d != 0 => by_narrow(n, d),
        (_, Ok(_)) => (n / d, n % d),
        (_, Err(_)) => by_wide(n, d),
    }
}

/// `⌊n / d⌋`.
#[inline]
pub(crate) fn div(n: u64, d: u64) -> u64 {
    div_rem(n, d).0
}

/// `⌈n / d⌉`.
#[inline]
pub(crate) fn div_ceil(n: u64, d: u64) -> u64 {
    let (quotient, remainder) = div_rem(n, d);
    quotient + u64::from(remainder != 0)
}

/// `n mod d`.
#[inline]
pub(crate) fn rem(n: u64, d: u64) -> u64 {
    div_rem(n, d).1
}

/// A 64-bit `n` by a 32-bit `d > 0`: long division in base 2^32, the high word first; the low
/// word's step divides a 64-bit value by `d` knowing the quotient fits 32 bits
/// ([`narrow_step`]).
// On a 64-bit target only the tests call it (they check it there too).
#[cfg_attr(target_pointer_width = "64", allow(dead_code))]
#[inline(never)]
fn by_narrow(n: u64, d: u32) -> (u64, u64) {
    let (high, low) = ((n >> 32) as u32, n as u32);
    let (quotient_high, carried) = (high / d, high % d);
    let (quotient_low, remainder) = if d < 1 << 16 {
        half_steps(carried, low, d)
    } else {
        narrow_step(carried, low, d)
    };
    (
        u64::from(quotient_high) << 32 | u64::from(quotient_low),
        u64::from(remainder),
    )
}

/// `(high·2^32 + low) / d` and its remainder, for `high < d < 2^16`: two 32-bit divisions, one
/// for each half of `low`, as each partial dividend (what is carried, then 16 bits) stays below
/// `d·2^16 ≤ 2^32` — about a fifth of [`narrow_step`]'s cost on a Cortex-M4, for the divisors
/// the planner mostly has (a ramp's cycles, a jerk, a peak acceleration of a few thousand raw
/// units) under a large distance.
#[cfg_attr(target_pointer_width = "64", allow(dead_code))]
fn half_steps(high: u32, low: u32, d: u32) -> (u32, u32) {
    let upper = (high << 16) | (low >> 16);
    let (quotient_upper, carried) = (upper / d, upper % d);
    let lower = (carried << 16) | (low & 0xFFFF);
    ((quotient_upper << 16) | (lower / d), lower % d)
}

/// A 64-bit `n` by a `d ≥ 2^32` (so the quotient fits 32 bits): the quotient of `n/2` by the
/// divisor's top 32 bits (normalized), scaled back, is the quotient or one more; one less is
/// at most one short, which one comparison puts right (*Hacker's Delight*, §9-5, `divDU`).
#[cfg_attr(target_pointer_width = "64", allow(dead_code))]
#[inline(never)]
fn by_wide(n: u64, d: u64) -> (u64, u64) {
    let shift = d.leading_zeros();
    let top = ((d << shift) >> 32) as u32;
    let half = n >> 1;
    // half < 2^63, so its high word is below top ≥ 2^31: the quotient fits 32 bits.
    let (estimate, _) = narrow_step((half >> 32) as u32, half as u32, top);
    let mut quotient = (u64::from(estimate) << shift) >> 31;
    quotient = quotient.saturating_sub(1);
    // quotient ≤ the true quotient, so quotient·d ≤ n.
    let mut remainder = n - quotient * d;
    if remainder >= d {
        quotient += 1;
        remainder -= d;
    }
    (quotient, remainder)
}

/// `(high·2^32 + low) / d` and its remainder, for `high < d` (so the quotient fits 32 bits), with
/// 32-bit divisions only: Knuth's algorithm D in base 2^16 with the divisor normalized (its top
/// bit set), each quotient digit estimated from the divisor's top half and corrected at most
/// twice (H. S. Warren, *Hacker's Delight*, 2nd ed., §9-4, `divlu`).
#[cfg_attr(target_pointer_width = "64", allow(dead_code))]
fn narrow_step(high: u32, low: u32, d: u32) -> (u32, u32) {
    const BASE: u32 = 1 << 16;
    let shift = d.leading_zeros();
    let d = d << shift;
    let (d_high, d_low) = (d >> 16, d & 0xFFFF);
    // The dividend shifted as the divisor was: three digits and a half (high < d, so no bit is
    // lost off the top).
    let top = if shift == 0 {
        high
    } else {
        high << shift | low >> (32 - shift)
    };
    let bottom = low << shift;
    let (digit1, digit0) = (bottom >> 16, bottom & 0xFFFF);
    // One quotient digit of `top·BASE + next` by d, and what remains (< d).
    let digit = |top: u32, next: u32| {
        let mut q = top / d_high;
        let mut r = top - q * d_high;
        // q ≥ BASE is tested first, so q·d_low is only formed below 2^32; r < BASE there too.
        while q >= BASE || q * d_low > BASE * r + next {
            q -= 1;
            r += d_high;
            if r >= BASE {
                break;
            }
        }
        // Exact modulo 2^32, and the true value is below d.
        let remaining = top
            .wrapping_mul(BASE)
            .wrapping_add(next)
            .wrapping_sub(q.wrapping_mul(d));
        (q, remaining)
    };
    let (q1, middle) = digit(top, digit1);
    let (q0, remaining) = digit(middle, digit0);
    (q1 * BASE + q0, remaining >> shift)
}

/// `⌊n / d⌋` for signed `n` and `d > 0`.
#[inline]
pub(crate) fn floor_div(n: i64, d: i64) -> i64 {
    match (i32::try_from(n), i32::try_from(d)) {
        (Ok(n), Ok(d)) => i64::from(n.div_euclid(d)),
        _ => n.div_euclid(d),
    }
}

/// `⌈n / d⌉` for signed `n` and `d > 0`.
#[inline]
pub(crate) fn ceil_div(n: i64, d: i64) -> i64 {
    -floor_div(-n, d)
}

/// Division by a divisor fixed for many quotients (a rate of the plan, while its searches run):
/// one multiplication by a precomputed reciprocal and at most two corrections, where a 64-bit
/// division is a library call of a few hundred instructions on a 32-bit core.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Reciprocal {
    divisor: u64,
    /// ⌊(2^64 − 1) / divisor⌋.
    inverse: u64,
}

impl Reciprocal {
    /// The reciprocal of `divisor` (≥ 1): one 64-bit division.
    pub(crate) fn new(divisor: u64) -> Self {
        Self {
            divisor,
            inverse: u64::MAX / divisor,
        }
    }

    /// `⌊n / divisor⌋`, for every `n`.
    ///
    /// With r = ⌊(2^64 − 1) / d⌋ > (2^64 − 1) / d − 1, the estimate q = ⌊n·r / 2^64⌋ is at most
    /// ⌊n / d⌋ (n·r < n·2^64 / d) and more than n / d − (n + n / d) / 2^64 − 1 ≥ n / d − 3, so
    /// it is short by at most two: the remainder n − q·d (exact in 64 bits, as q·d ≤ n) says
    /// how many.
    #[inline]
    pub(crate) fn divide(self, n: u64) -> u64 {
        let mut quotient = ((u128::from(n) * u128::from(self.inverse)) >> 64) as u64;
        let mut remainder = n - quotient * self.divisor;
        while remainder >= self.divisor {
            quotient += 1;
            remainder -= self.divisor;
        }
        quotient
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// Values of every width, the 32-bit boundary and zero most of all.
    fn operand() -> impl Strategy<Value = u64> {
        prop_oneof![
            (0u32..=64).prop_flat_map(|bits| 0..=u64::MAX >> (64 - bits.max(1))),
            Just(u64::from(u32::MAX)),
            Just(1u64 << 32),
        ]
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(20_000))]

        #[test]
        fn a_reciprocal_divides_as_the_operator(n in operand(), d in operand().prop_map(|d| d.max(1))) {
            prop_assert_eq!(Reciprocal::new(d).divide(n), n / d);
        }

        #[test]
        fn the_same_as_the_64_bit_operators(n in operand(), d in operand().prop_map(|d| d.max(1))) {
            prop_assert_eq!(div_rem(n, d), (n / d, n % d));
            // The 32-bit target's paths, checked on every target.
            if n >> 32 != 0 && d >> 32 == 0 {
                prop_assert_eq!(by_narrow(n, d as u32), (n / d, n % d));
            }
            if d >> 32 != 0 {
                prop_assert_eq!(by_wide(n, d), (n / d, n % d));
            }
            prop_assert_eq!(div(n, d), n / d);
            prop_assert_eq!(div_ceil(n, d), n.div_ceil(d));
            prop_assert_eq!(rem(n, d), n % d);
            let (sn, sd) = (n as i64, (d >> 1).max(1) as i64);
            prop_assert_eq!(floor_div(sn, sd), sn.div_euclid(sd));
            prop_assert_eq!(ceil_div(sn, sd), -((-(sn as i128)).div_euclid(sd as i128)) as i64);
        }
    }
}
