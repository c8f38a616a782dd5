//! Integer square and cube roots for the search: exact floors, no floating point, so every
//! target computes the same plan.

/// `⌊√n⌋`.
///
/// On a 64-bit target, by multiplications alone ([`square_root_by_products`]): the library's
/// `isqrt` there takes three divisions one after the other, the longest chain of waits in the
/// search's first step (two roots a plan; `SCurve::new` about 1.5 % faster without them,
/// `tools/ab_planning.sh`). On a 32-bit core the library's 32-bit root where `n` fits 32 bits
/// (its divisions are `udiv` instructions), else by products too: the library's 64-bit root
/// calls the 64-bit division routine (about 100 Cortex-M4 instructions a root; the first 400
/// random moves' sum −0.66 %, none more). All are the exact floor, so the plans are the same.
#[inline]
pub(super) fn square_root(n: u64) -> u64 {
    if cfg!(target_pointer_width = "64") {
        square_root_by_products(n)
    } else if let Ok(narrow) = u32::try_from(n) {
        u64::from(narrow.isqrt())
    } else {
        square_root_by_products(n)
    }
}

/// `⌊√n⌋` without a division: `n` scaled by `4^s` into `m ∈ [2^62, 2^64)`, the reciprocal root
/// `y ≈ 2^30/√u` of `u = m/2^64` from a table on its top 8 bits (8 bits right), two Newton
/// steps `y ← y·(3 − u·y²)/2` (16, then about 28 bits), the root `√m ≈ u·y·2^32`, one correction
/// `(m − r²)/(2r)` with `1/(2r) ≈ y/2^63` (then within a unit or two), scaled back by `2^s`,
/// and the last unit settled exactly by comparing squares.
///
/// Widths: `y ≤ 2^31` (a Newton step never overshoots `1/√u` but for its truncations, which
/// stay far below `2^31`), so `y² < 2^62`, `high·y²/2^30 < 2^64` and `y·(3·2^30 − …) < 2^63`;
/// the estimate is within about 2^5 of `√m < 2^32`, so `m − r²` is below 2^38 in magnitude (its
/// top 31 bits times `y` fit 63).
fn square_root_by_products(n: u64) -> u64 {
    if n < 4 {
        return u64::from(n > 0);
    }
    let half_shift = n.leading_zeros() / 2;
    let m = n << (2 * half_shift);
    // u = m/2^64 ∈ [1/4, 1) to 32 bits.
    let high = m >> 32;
    let mut y = u64::from(RECIPROCAL_ROOTS[(m >> 56) as usize - 64]);
    for _ in 0..2 {
        let square = (y * y) >> 30;
        let product = (high * square) >> 32;
        y = (y * ((3 << 30) - product)) >> 31;
    }
    let estimate = (high * y) >> 30;
    // m − estimate², exact (the true difference is far inside ±2^63; the estimate may be 2^32).
    let difference = m.wrapping_sub(estimate.wrapping_mul(estimate)) as i64;
    let correction = ((difference >> 7) * y as i64) >> 56;
    let root = estimate
        .wrapping_add_signed(correction)
        .min(u64::from(u32::MAX));
    let mut root = root >> half_shift;
    // Off by at most one here (a survey of 300,000 values: 1 % one too low); settled exactly.
    while root * root > n {
        root -= 1;
    }
    let mut rest = n - root * root;
    // (root + 1)² ≤ n ⇔ 2·root + 1 ≤ n − root².
    while rest > 2 * root {
        rest -= 2 * root + 1;
        root += 1;
    }
    root
}

/// `⌊2^30/√((i + ½)/256)⌋` for the top byte `i` (64 to 255) of a scaled `m` (see
/// [`square_root_by_products`]): at the middle of its interval, so within 2^-8 of the
/// reciprocal root anywhere in it; at most `2^30·√(512/129) < 2^31`.
const RECIPROCAL_ROOTS: [u32; 192] = {
    let mut table = [0u32; 192];
    let mut i = 0;
    while i < 192 {
        // 2^60·256/(i + 64 + ½) = 2^69/(2·(i + 64) + 1).
        table[i] = ((1u128 << 69) / (2 * (i as u128 + 64) + 1)).isqrt() as u32;
        i += 1;
    }
    table
};

/// `⌊∛n⌋`, digit by digit in base 8 (at most 22 steps): each step brings the next three bits
/// of `n` down into the remainder and tries the next bit of the root.
///
/// The digits come off the top of `n`, shifted left three bits at a time, not out of `n`
/// shifted right by an amount that changes with each step: on a Cortex-M4 a 64-bit shift by a
/// constant is two or three instructions, by a variable amount a branch and six.
pub(super) fn cube_root(n: u64) -> u64 {
    if n == 0 {
        return 0;
    }
    // Base-8 digits of `n`: ⌈bits/3⌉.
    let digits = (66 - n.leading_zeros()) / 3;
    // The root (below 2^22: 32 bits hold it, and its product with the next is one 32 × 32 →
    // 64-bit multiplication, on a Cortex-M4 one instruction, not three) and the digits still
    // to bring down, the next at the top.
    let (mut root, mut bits, steps) = if digits == 22 {
        // 64 bits: the first digit is the top bit alone, and it is 1 (1 ≥ 1³): root 1, nothing
        // left over.
        (1u32, n << 1, 21)
    } else {
        (0, n << (64 - 3 * digits), digits)
    };
    // The first twelve steps in 32 bits: the root stays under 2^13 (it starts at 0 or 1), so
    // `next` under 3·2^26 + 1 and the remainder brought down under 8·next < 2^32.
    let narrow = steps.min(12);
    let mut narrow_rest = 0u32;
    for _ in 0..narrow {
        root *= 2;
        narrow_rest = (narrow_rest << 3) | (bits >> 61) as u32;
        bits <<= 3;
        let next = 3 * (root * (root + 1)) + 1;
        if narrow_rest >= next {
            narrow_rest -= next;
            root += 1;
        }
    }
    // Then in 64 bits: what is left stays below 3·(2r)·(2r + 1) + 1 < 2^46 after each step,
    // so three bits more still fit.
    let mut rest = u64::from(narrow_rest);
    for _ in narrow..steps {
        root *= 2;
        rest = (rest << 3) | (bits >> 61);
        bits <<= 3;
        // (2r + 1)³ − (2r)³ = 3·2r·(2r + 1) + 1.
        let next = 3 * (u64::from(root) * u64::from(root + 1)) + 1;
        if rest >= next {
            rest -= next;
            root += 1;
        }
    }
    u64::from(root)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Against the library's `isqrt`: every value under 10^6, squares and their neighbours up to
    /// the largest, powers of two and their neighbours, and 4,000,000 pseudo-random values of
    /// every magnitude. Both roots, whichever target runs the tests.
    #[test]
    fn square_root_is_exact() {
        let mut x = 0x1234_5678_9abc_def1u64;
        let check = |n: u64| {
            assert_eq!(square_root_by_products(n), n.isqrt(), "{n}");
            assert_eq!(square_root(n), n.isqrt(), "{n}");
        };
        for n in 0..1_000_000u64 {
            check(n);
        }
        for k in (0..=u64::from(u32::MAX))
            .step_by(65_537)
            .chain([u64::from(u32::MAX)])
        {
            for n in [k * k, (k * k).saturating_sub(1), k * k + 1, k * k + 2 * k] {
                check(n);
            }
        }
        for shift in 0..64 {
            check(1 << shift);
            check((1u64 << shift) - 1);
            check((1u64 << shift) + 1);
            check(u64::MAX >> shift);
        }
        for _ in 0..2_000_000 {
            // xorshift64
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            check(x);
            check(x >> (x % 64));
        }
    }

    #[test]
    fn cube_root_is_exact() {
        let check = |n: u64| {
            let r = cube_root(n);
            assert!(u128::from(r).pow(3) <= u128::from(n), "{n}");
            assert!(u128::from(r + 1).pow(3) > u128::from(n), "{n}");
        };
        for n in (0..5_000u64).chain([
            u64::MAX,
            u64::MAX - 1,
            1 << 63,
            (1 << 21) * (1 << 21) * (1 << 21) - 1,
        ]) {
            check(n);
        }
        // Every 97th cube up to the largest below 2^64 (and that one) with its neighbours, and
        // 1,000,000 pseudo-random values of every magnitude, each also shifted right.
        for k in (1..=2_642_245u64).step_by(97).chain([2_642_245]) {
            let cube = k * k * k;
            check(cube);
            check(cube - 1);
            check(cube.saturating_add(1));
        }
        let mut x = 0x9e37_79b9_7f4a_7c15u64;
        for _ in 0..1_000_000 {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            check(x);
            check(x >> (x % 64));
        }
    }
}
