//! The exact integer square root the circle needs once per cycle, in 32-bit operations only.
//!
//! `u64::isqrt` of `core` finishes with a 64-bit division, which a 32-bit Cortex-M4 has no
//! instruction for (a library call of a hundred-odd instructions). Here the input is below 2⁶²
//! (a radius² is below 2⁶¹), so one Karatsuba step (Zimmermann, "Karatsuba Square Root", 1999)
//! in base b = 2¹⁵ keeps every quantity of the last stage inside 32 bits:
//!
//! ```text
//! n shifted by an even amount into [2⁵⁸, 2⁶²):  n = h·b² + a₁·b + a₀,  h = ⌊n / 2³⁰⌋ ∈ [2²⁸, 2³²)
//! s₁ = ⌊√h⌋ ∈ [2¹⁴, 2¹⁶) (a table and one Newton step),  r₁ = h − s₁² ≤ 2·s₁ < 2¹⁷
//! (q, u) = divmod(r₁·b + a₁, 2·s₁)     r₁·b + a₁ < 2¹⁷·2¹⁵ = 2³²; q ≤ b
//! s = s₁·b + q,  r = u·b + a₀ − q²;    if r < 0 { s −= 1 }   (at most once: s₁ ≥ b/2)
//! ```
//!
//! and `u·b + a₀ < 2³²`, `q² ≤ 2³⁰`, so the sign test is a 32-bit comparison too. Undoing the
//! normalization (a shift of the root by half the shift) keeps the floor: ⌊⌊2ʲ·x⌋ / 2ʲ⌋ = ⌊x⌋.

use core::num::NonZeroU32;

/// ⌊√n⌋ for n < 2⁶², exactly; see the [module docs](self).
pub(crate) fn isqrt(n: u64) -> u32 {
    debug_assert!(n < 1 << 62, "isqrt: the input must be below 2^62");
    if n == 0 {
        return 0;
    }
    isqrt_shifted(n, shift_for(n))
}

/// The even shift that puts `top` (0 < top < 2⁶²) into [2⁶⁰, 2⁶²): every n in [top/4, top]
/// then lands in [2⁵⁸, 2⁶²), the domain of [`isqrt_shifted`]. A circle computes it once for R²
/// (the long axis's radicand R² − s² never falls below R²/4), so a cycle needs no `clz`.
pub(crate) fn shift_for(top: u64) -> u32 {
    top.leading_zeros().saturating_sub(2) & !1
}

/// ⌊√n⌋ for n·2^shift in [2⁵⁸, 2⁶²) (shift even): one Karatsuba step (module docs), with
/// h = ⌊n·2^shift / 2³⁰⌋ in [2²⁸, 2³²), so s₁ = ⌊√h⌋ ≥ 2¹⁴ = b/2, Zimmermann's normalization,
/// and every quantity of the step below 2³².
#[inline(always)]
pub(crate) fn isqrt_shifted(n: u64, shift: u32) -> u32 {
    isqrt_wide(n << shift) >> (shift / 2)
}

/// ⌊√n⌋ for n in [2⁵⁸, 2⁶²): the Karatsuba step of the [module docs](self), h = ⌊n / 2³⁰⌋ in
/// [2²⁸, 2³²), so s₁ = ⌊√h⌋ ≥ 2¹⁴ = b/2, Zimmermann's normalization, and every quantity of the
/// step below 2³². A circle hands it R²·2^shift − (s·2^(shift/2))², already in range, so a
/// cycle shifts no 64-bit value by a variable amount.
#[inline(always)]
pub(crate) fn isqrt_wide(n: u64) -> u32 {
    // h < 2³²: the cast keeps every bit.
    let high = (n >> 30) as u32;
    let low = (n as u32) & ((1 << 30) - 1);
    let (digit_1, digit_0) = (low >> 15, low & 0x7fff);
    let root_high = isqrt_normalized(high);
    // r₁ ≤ 2·s₁ < 2¹⁷, so r₁·2¹⁵ + a₁ < 2³²: one 32-bit division. The divisor 2·s₁ ≥ 2¹⁵ is
    // never zero; built as a `NonZeroU32` so the division needs no check.
    let remainder_high = high.wrapping_sub(root_high.wrapping_mul(root_high));
    let numerator = (remainder_high << 15) | digit_1;
    let divisor = NonZeroU32::MIN.saturating_add((root_high << 1).wrapping_sub(1));
    let quotient = numerator / divisor;
    let rest = numerator.wrapping_sub(quotient.wrapping_mul(divisor.get()));
    // s < 2¹⁶·2¹⁵ + 2¹⁵ < 2³²; the remainder u·b + a₀ < 2³², and q ≤ 2¹⁵, so q² ≤ 2³⁰.
    let root = (root_high << 15).wrapping_add(quotient);
    root.wrapping_sub(u32::from(
        (rest << 15).wrapping_add(digit_0) < quotient.wrapping_mul(quotient),
    ))
}

/// ⌊√h⌋ for h ∈ [2²⁸, 2³²): a table of the top ten bits, one Newton step, one correction.
///
/// For h in the table's bucket i (i·2²² ≤ h < (i + 1)·2²², 64 ≤ i < 1024) the start
/// x₀ = ⌊√((i + 1)·2²² − 1)⌋ + 1 lies above √h by at most 2¹¹·(√(i + 1) − √i) + 1 < 129; one
/// Newton step x₁ = ⌊(x₀ + ⌊h / x₀⌋) / 2⌋ stays at or above ⌊√h⌋ (the integer Newton step never
/// undershoots) and less than (x₀ − √h)² / (2·√h) < 129² / 2¹⁵ < 0.51 above √h, so x₁ is ⌊√h⌋
/// or one more, which x₁² > h tells.
#[inline(always)]
fn isqrt_normalized(high: u32) -> u32 {
    // high >> 22 < 1024: always inside the table, no bounds check.
    let start = NonZeroU32::MIN.saturating_add(u32::from(ROOTS[(high >> 22) as usize]));
    let root = (start.get() + high / start) >> 1;
    // 2¹⁴ ≤ x₁ ≤ 2¹⁶. Below 2¹⁶, x₁² > h ⇔ x₁² − 1 ≥ h in 32 bits; at 2¹⁶, x₁² − 1 wraps to
    // 2³² − 1 ≥ h, which is right too (2³² > h). One `mla` and a comparison, no 64-bit square.
    root - u32::from(root.wrapping_mul(root).wrapping_sub(1) >= high)
}

/// ⌊√((i + 1)·2²² − 1)⌋ for i = 0 … 1023 (the first 64 unused), computed when compiling.
static ROOTS: [u16; 1024] = {
    let mut roots = [0u16; 1024];
    let mut i = 0;
    while i < 1024 {
        let top = ((i as u64 + 1) << 22) - 1;
        // Below 2¹⁶: the cast is exact.
        roots[i] = top.isqrt() as u16;
        i += 1;
    }
    roots
};

/// √n rounded to the nearest integer (there are no ties: (q + ½)² is never an integer), for
/// n < 2⁶²: ⌊√n⌋ plus one when n − q² > q, i.e. n ≥ q² + q + ¼.
pub(crate) fn round_sqrt(n: u64) -> u32 {
    round_root(n, isqrt(n))
}

/// As [`round_sqrt`] for n·2^shift in [2⁵⁸, 2⁶²) (see [`shift_for`]); the tests' check of the
/// shifted root.
#[cfg(test)]
pub(crate) fn round_sqrt_shifted(n: u64, shift: u32) -> u32 {
    round_root(n, isqrt_shifted(n, shift))
}

/// ⌊√n⌋ = `root` rounded to nearest: one more when n − q² > q.
#[inline(always)]
fn round_root(n: u64, root: u32) -> u32 {
    round_with_low_word(n as u32, root)
}

/// ⌊√n⌋ = `root` rounded to nearest from n's low word `low` (n mod 2³²): q² ≤ n and
/// n − q² ≤ 2q < 2³², so the low words give n − q² exactly (one `mls`).
#[inline(always)]
pub(crate) fn round_with_low_word(low: u32, root: u32) -> u32 {
    let excess = low.wrapping_sub(root.wrapping_mul(root));
    root + u32::from(excess > root)
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::{isqrt, round_sqrt};

    /// The definition, checked in u128: q² ≤ n < (q + 1)².
    fn is_floor_root(n: u64, root: u32) -> bool {
        let (n, q) = (u128::from(n), u128::from(root));
        q * q <= n && n < (q + 1) * (q + 1)
    }

    #[test]
    fn exact_near_every_square_and_at_the_ends() {
        let mut cases = std::vec![0u64, 1, 2, 3, 4, (1 << 62) - 1, 1 << 60, (1 << 60) - 1];
        // Around q² for q spread over the whole range (q < 2³¹): q² − 1, q², q² + q, q² + q + 1, …
        let mut q: u64 = 1;
        while q < 1 << 31 {
            for root in [q, q + 1, (1 << 31) - q] {
                let square = root * root;
                for n in [
                    square - 1,
                    square,
                    square + 1,
                    square + root,
                    square + root + 1,
                ] {
                    if n < 1 << 62 {
                        cases.push(n);
                    }
                }
            }
            q = q * 3 / 2 + 1;
        }
        for n in cases {
            assert!(is_floor_root(n, isqrt(n)), "isqrt({n}) = {}", isqrt(n));
        }
    }

    #[test]
    fn the_normalized_root_is_exact_at_every_bucket_edge_and_square() {
        // Every square k² and its neighbours in [2²⁸, 2³²), and every bucket's ends.
        for k in 16_384u64..=65_536 {
            for n in [k * k - 1, k * k, k * k + k, k * k + 2 * k] {
                if (1 << 28..1 << 32).contains(&n) {
                    let n = n as u32;
                    assert!(
                        is_floor_root(u64::from(n), super::isqrt_normalized(n)),
                        "{n}"
                    );
                }
            }
        }
        for bucket in 64u64..1024 {
            for n in [bucket << 22, ((bucket + 1) << 22) - 1] {
                let n = n as u32;
                assert!(
                    is_floor_root(u64::from(n), super::isqrt_normalized(n)),
                    "{n}"
                );
            }
        }
    }

    #[test]
    fn exact_with_a_circles_shift_over_a_quarter_of_its_range() {
        // n in [top/4, top] with the shift of top, for tops of every size.
        let mut state: u64 = 0x2545_f491_4f6c_dd1d;
        for _ in 0..100_000 {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            let top = (state >> (2 + state % 61)).max(1);
            let shift = super::shift_for(top);
            let n = top - (state >> 7) % (top - top / 4 + 1);
            let root = super::isqrt_shifted(n, shift);
            assert!(
                is_floor_root(n, root),
                "isqrt_shifted({n}, {shift}) = {root}"
            );
            let nearest = super::round_sqrt_shifted(n, shift);
            assert_eq!(nearest, round_sqrt(n), "{n}");
        }
    }

    #[test]
    fn exact_on_pseudo_random_inputs_of_every_size() {
        // A fixed xorshift sequence, every bit length from 1 to 62.
        let mut state: u64 = 0x9e37_79b9_7f4a_7c15;
        for _ in 0..200_000 {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            let n = state >> (2 + state % 62);
            assert!(is_floor_root(n, isqrt(n)), "isqrt({n}) = {}", isqrt(n));
            let nearest = round_sqrt(n);
            // |nearest − √n| < ½  ⇔  (2q − 1)² < 4n < (2q + 1)², in u128.
            let (four_n, twice) = (4 * u128::from(n), 2 * u128::from(nearest));
            assert!(
                (twice.saturating_sub(1)).pow(2) < four_n || n == 0,
                "round_sqrt({n})"
            );
            assert!(four_n < (twice + 1).pow(2), "round_sqrt({n}) = {nearest}");
        }
    }
}
