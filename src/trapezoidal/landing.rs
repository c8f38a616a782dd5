//! The trapezoid's plan when it may stop from its starting velocity (SPEC §7, issue #12): the
//! last moving cycle may drop to rest from any velocity up to the starting velocity S. With
//! S ≤ D that drop is an ordinary deceleration and the per-cycle rule of [`super::Trapezoidal`]
//! plans the move; with S > D it is not, and the largest velocity each cycle can leave a distance
//! no landing covers (the stopping distance jumps at S), so the landing is planned with the rest.
//!
//! A plan of n moving cycles has velocities w_1 … w_n with w_1 ≤ w0 + A (w0 the present velocity,
//! or S from rest: the first cycle's jump), speed-ups ≤ A, slow-downs ≤ D, every w ≤ V, and
//! w_n ≤ S (the drop). So w_i ≤ E_i = min(w0 + i·A, S + (n − i)·D, V), and E itself keeps every
//! rate: it is the fastest n-cycle move. In motion the slow-downs also bound the velocities from
//! below, w_i ≥ L_i = w0 − i·D (from rest nothing does), and every moving cycle goes forward,
//! w_i ≥ 1 unit. So an n-cycle plan exists exactly when L_n ≤ S (n ≥ k = ⌈(w0 − S) / D⌉) and
//! Σ max(L_i, 1) ≤ d ≤ Σ E_i, d the distance; both sums grow with n, so the fewest cycles is
//! n = max(k, the least n with Σ E_i ≥ d), and no plan exists (the axis is too fast to land
//! before the destination: it passes it) when Σ max(L_i, 1) > d there.
//!
//! The velocities are then E and L clamped to a level c, w_i = max(L_i, min(E_i, c)), with c the
//! highest level whose sum fits in d, and the units of 2^-32 counts still missing, fewer than
//! the cycles with L_i ≤ c < E_i, go one each to the first of those cycles: every rate still
//! holds (the clamp of sequences that keep the rates keeps them, the extra unit changes a
//! velocity by one unit where both neighbours allow it), and the sum is d. The result is at most
//! six runs: slowing by D (in motion, above the level) or rising by A, one cycle at c, the extra
//! units at c + 1, c, falling by D to the landing, rest.
//!
//! The plan is its own per-cycle decision: from the state its first cycle leaves, the plan of
//! the cycles left is the rest of this one (L and E of the new state bound the same velocities
//! on the side that binds), so stepping it is what deciding every cycle afresh would do
//! (`tests/trapezoidal.rs`).

use crate::bisect::last_true;
use crate::division::Reciprocal;

/// A run in the frame where the destination lies ahead: `(first velocity, change per cycle,
/// cycles)`, I32F32 bits.
pub(super) type Run = (i64, i64, u64);

/// The envelope of the fastest n-cycle plan, and the line of the slowest.
#[derive(Debug, Clone, Copy)]
struct Envelope {
    first: i128,
    acceleration: i128,
    deceleration: i128,
    landing: i128,
    cycles: i128,
    /// w0, the present velocity (the slowest plan's L_i = w0 − i·D), or 0 from rest (no bound:
    /// then no L_i is ever above a level ≥ 1).
    lower: i128,
    rates: Rates,
}

/// The parts of the plan clamped at a level: `slowing` cycles above it on the slowest line,
/// `rising` cycles below it on the way up, `falling` below it on the way down, the rest at it;
/// and the sum.
#[derive(Debug, Clone, Copy)]
struct Cut {
    slowing: i128,
    rising: i128,
    falling: i128,
    sum: i128,
}

impl Envelope {
    /// The plan clamped at `cap` (1 ≤ cap ≤ V): Σ_{i=1}^{n} max(L_i, min(w0 + i·A, S + (n − i)·D,
    /// cap)).
    ///
    /// The rising line is below the falling one for i ≤ p = ⌊(S + n·D − w0) / (A + D)⌋ (both
    /// lines integer, so the floor is exact); on that side, the cycles below the cap are
    /// those with w0 + i·A < cap, i ≤ ⌊(cap − w0 − 1) / A⌋; on the other, with j = n − i, those
    /// with S + j·D < cap. Above the cap on the slowest line: w0 − i·D > cap, that is
    /// i ≤ ⌊(w0 − cap − 1) / D⌋, the first cycles (where E_i ≥ L_i > cap, so neither line of E
    /// is below the cap there). Every value is below 2^48 and n below 2^56: i128 throughout.
    fn cut(&self, cap: i128) -> Cut {
        self.cut_counting(cap, self.below(cap))
    }

    /// How many rising cycles at most (⌊(cap − w0 − 1) / A⌋ + 1 counting i = 0) and falling ones
    /// (⌊(cap − S − 1) / D⌋ + 1) lie below `cap`, before the lines' own extent limits them: the
    /// divisions of [`Self::cut`] that do not depend on n, so a search over n does them once.
    fn below(&self, cap: i128) -> (i128, i128) {
        (
            if cap > self.first {
                self.rates.per_acceleration.of(cap - self.first - 1)
            } else {
                0
            },
            if cap > self.landing {
                self.rates.per_deceleration.of(cap - self.landing - 1) + 1
            } else {
                0
            },
        )
    }

    /// The cycles whose slowest velocity is above `cap`: i ≥ 1 with w0 − i·D > cap, at most n.
    fn above(&self, cap: i128) -> i128 {
        if self.lower > cap {
            self.rates
                .per_deceleration
                .of(self.lower - cap - 1)
                .min(self.cycles)
        } else {
            0
        }
    }

    /// The first cycle on the rising side of E: the cycles i ≤ up rise (see [`Self::cut`]).
    fn up(&self) -> i128 {
        let reach = self.landing + self.cycles * self.deceleration - self.first;
        if reach < 0 {
            0
        } else {
            self.rates.per_both.of(reach).min(self.cycles)
        }
    }

    /// The clamped sum from the counts of the cycles on each line: `slowing` above the level on
    /// L, `rising` and `falling` below it on E, the rest at `cap`. (A value equal to the cap
    /// may be counted on its line or at the level: the sum is the same.)
    ///
    /// In 64 bits, saturating at 2^64 − 1 (a 32-bit core multiplies 64-bit words several times
    /// faster than 128-bit ones): the sum is only ever compared with a distance below 2^64, or
    /// subtracted from one it does not exceed, so a saturated sum answers every comparison as
    /// the exact one would. Every part is a sum of positive terms (the lines are disjoint: see
    /// [`Self::cut`]), each an arithmetic progression.
    fn sum(&self, cap: i128, slowing: i128, rising: i128, falling: i128) -> i128 {
        // Counts below 2^56, values below 2^49: the casts are exact.
        let level = (self.cycles - slowing - rising - falling) as u64;
        let (lower, first, landing) = (self.lower as u64, self.first as u64, self.landing as u64);
        let (acceleration, deceleration) = (self.acceleration as u64, self.deceleration as u64);
        let (slowing, rising, falling) = (slowing as u64, rising as u64, falling as u64);
        let sum = progression(rising, first + acceleration, first + rising * acceleration)
            .saturating_add(progression(
                falling,
                landing,
                landing + falling.saturating_sub(1) * deceleration,
            ))
            .saturating_add(saturating_product(level, cap as u64))
            .saturating_add(progression(
                slowing,
                lower.saturating_sub(deceleration),
                lower.saturating_sub(slowing * deceleration),
            ));
        i128::from(sum)
    }
    /// [`Self::cut`] with [`Self::below`]'s counts for `cap` given.
    fn cut_counting(&self, cap: i128, (rising_below, falling_below): (i128, i128)) -> Cut {
        let up = self.up();
        let slowing = self.above(cap);
        let rising = rising_below.min(up);
        let falling = falling_below.min(self.cycles - up);
        Cut {
            slowing,
            rising,
            falling,
            sum: self.sum(cap, slowing, rising, falling),
        }
    }
}

/// The highest level c ≤ V whose clamped plan fits in `distance`: Σ max(L_i, min(E_i, c)) ≤
/// distance (the clamp at 1 fits: the caller checked).
///
/// The sum is piecewise linear in c, with a kink at every value of E and L: the rising values
/// w0 + i·A and the falling ones S + j·D below V, and the slowest line's w0 − i·D. So bisect over
/// each progression's index for the highest value whose sum fits (at a value of one line its
/// own count is known, and the others take a division each), then solve the line that runs from
/// the highest of the three to the next kink: a few dozen sums at most where bisecting c itself
/// would take 48.
fn highest_level(envelope: &Envelope, distance: i128, max: i128, below_max: (i128, i128)) -> i128 {
    let n = envelope.cycles;
    // The rising side (i ≤ up) does not depend on the level: one division.
    let up = envelope.up();
    let down = n - up;
    let rising_below = |cap: i128| {
        if cap > envelope.first {
            envelope
                .rates
                .per_acceleration
                .of(cap - envelope.first - 1)
                .min(up)
        } else {
            0
        }
    };
    let falling_below = |cap: i128| {
        if cap > envelope.landing {
            (envelope
                .rates
                .per_deceleration
                .of(cap - envelope.landing - 1)
                + 1)
            .min(down)
        } else {
            0
        }
    };
    let fits = |cap: i128, slowing: i128, rising: i128, falling: i128| {
        envelope.sum(cap, slowing, rising, falling) <= distance
    };
    // The largest k in 1 ..= count with fits(k), or 0 (fits is monotone, true then false).
    let last_fitting = |count: i128, fits: &dyn Fn(i128) -> bool| last_true(0, count + 1, fits);
    let rise = |i: i128| envelope.first + i * envelope.acceleration;
    let fall = |j: i128| envelope.landing + j * envelope.deceleration;
    let slow = |i: i128| envelope.lower - i * envelope.deceleration;
    // Above every value of L (w0 − D < w0 + A): none of the rising values is on L's side.
    let i = last_fitting(below_max.0.min(up), &|i| {
        let cap = rise(i);
        fits(cap, 0, i - 1, falling_below(cap))
    });
    let j = last_fitting(below_max.1.min(down), &|j| {
        let cap = fall(j - 1);
        fits(cap, envelope.above(cap), rising_below(cap), j - 1)
    });
    // L's values from the top, w0 − D, w0 − 2D, …, while ≥ 1 and within the n cycles; the sum
    // falls along them, so the first that fits is the highest: the last that does not, plus one.
    // (Below every rising value: none is below them.)
    let slowing = if envelope.lower > envelope.deceleration {
        envelope
            .rates
            .per_deceleration
            .of(envelope.lower - 1)
            .min(n)
    } else {
        0
    };
    let misses = last_true(0, slowing + 1, |k| {
        let cap = slow(k);
        !fits(cap, k - 1, 0, falling_below(cap))
    });
    // The cut at 1 fits (the caller's check).
    let mut start = 1;
    if i > 0 {
        start = start.max(rise(i));
    }
    if j > 0 {
        start = start.max(fall(j - 1));
    }
    if misses < slowing {
        start = start.max(slow(misses + 1));
    }
    // From `start` to the next kink the sum rises by the cycles at the level per unit.
    let (slowing, rising, falling) = (
        envelope.above(start),
        rising_below(start + 1),
        falling_below(start + 1),
    );
    let slope = n - slowing - rising - falling;
    if slope == 0 {
        return max;
    }
    (start + (distance - envelope.sum(start, slowing, rising, falling)) / slope).min(max)
}

/// The sum of `count` terms of an arithmetic progression from `first` to `last` (both below
/// 2^62), saturating at 2^64 − 1: count·(first + last) / 2, halved where it divides exactly
/// (count even, or else first + last, the progression's terms being integers).
fn progression(count: u64, first: u64, last: u64) -> u64 {
    if count == 0 {
        return 0;
    }
    let ends = first + last;
    let (factor, other) = if count % 2 == 0 {
        (count / 2, ends)
    } else {
        (count, ends / 2)
    };
    saturating_product(factor, other)
}

/// `a·b`, saturating at 2^64 − 1. Written as a checked product: `u64::saturating_mul` compiles
/// to longer code for a Cortex-M4 (measured: the worst whole-range set-up 30,317 instructions
/// this way, 30,891 with it).
#[allow(clippy::manual_saturating_arithmetic)]
fn saturating_product(a: u64, b: u64) -> u64 {
    a.checked_mul(b).unwrap_or(u64::MAX)
}

/// ⌊a / b⌋ for 0 ≤ a and 0 < b, in 64 bits when both fit (a 32-bit core divides those several
/// times faster than 128-bit ones).
fn divide(a: i128, b: i128) -> i128 {
    match (u64::try_from(a), u64::try_from(b)) {
        (Ok(a), Ok(b)) => i128::from(a / b),
        _ => a / b,
    }
}

/// A rate of the plan as a divisor: its reciprocal, for the searches' many quotients by it.
#[derive(Debug, Clone, Copy)]
struct Per {
    divisor: i128,
    reciprocal: Reciprocal,
}

impl Per {
    /// `rate` ≥ 1 (a rate of the profile, below 2^41).
    fn new(rate: i128) -> Self {
        Self {
            divisor: rate,
            reciprocal: Reciprocal::new(rate as u64),
        }
    }

    /// ⌊a / rate⌋ for 0 ≤ a: by the reciprocal below 2^64, as a 128-bit division above.
    fn of(self, a: i128) -> i128 {
        match u64::try_from(a) {
            Ok(a) => i128::from(self.reciprocal.divide(a)),
            Err(_) => a / self.divisor,
        }
    }
}

/// The divisors of the searches: A, D and A + D.
#[derive(Debug, Clone, Copy)]
struct Rates {
    per_acceleration: Per,
    per_deceleration: Per,
    per_both: Per,
}

/// The runs that cover `distance` (≥ 0, I32F32 bits) from `velocity` (0 … V) and land with a
/// drop from at most S, per the module's documentation: the fewest cycles any plan takes; `None`
/// when no plan lands (the axis is too fast to stop before the destination, even slowing down
/// by D on every cycle: it passes it).
pub(super) fn plan(
    distance: i128,
    velocity: i64,
    max_velocity: i64,
    acceleration: i64,
    deceleration: i64,
    start_velocity: i64,
) -> Option<[Run; 6]> {
    let first = i128::from(if velocity == 0 {
        start_velocity
    } else {
        velocity
    });
    let max = i128::from(max_velocity);
    let mut envelope = Envelope {
        first,
        acceleration: i128::from(acceleration),
        deceleration: i128::from(deceleration),
        landing: i128::from(start_velocity),
        cycles: 0,
        lower: i128::from(velocity),
        rates: Rates {
            per_acceleration: Per::new(i128::from(acceleration)),
            per_deceleration: Per::new(i128::from(deceleration)),
            per_both: Per::new(i128::from(acceleration) + i128::from(deceleration)),
        },
    };
    // k: the fewest cycles that slow down to S from the present velocity.
    let landing_cycles = if envelope.lower > envelope.landing {
        divide(
            envelope.lower - envelope.landing + envelope.deceleration - 1,
            envelope.deceleration,
        )
    } else {
        0
    };
    let below_max = envelope.below(max);
    let reaches = |envelope: &mut Envelope, cycles: i128| {
        envelope.cycles = cycles;
        envelope.cut_counting(max, below_max).sum >= distance
    };
    // The fewest cycles whose fastest plan reaches the distance. From n1 = (cycles below V
    // rising) + (below V falling) + 1 on, both lines reach V before they meet, so every further
    // cycle adds V: one division. Below n1, bisect (Σ E grows with n), between bounds that
    // every E_i lies within: m = min(w0, S) ≤ E_i ≤ V (the rising line starts at w0, the
    // falling one ends at S), so n·V < d does not reach and n·m ≥ d does. (Often a few cycles
    // apart where n1 is 2^40: the bisection's steps are 128-bit sums and a 64-bit division.)
    let plateau_from = below_max.0 + below_max.1 + 1;
    let least = first.min(envelope.landing);
    let enough = divide(distance + least - 1, least);
    let fastest = if distance == 0 {
        0
    } else if enough < plateau_from || reaches(&mut envelope, plateau_from) {
        let mut low = divide(distance - 1, max); // n·V < d: does not reach
        let mut high = enough.min(plateau_from);
        // Secant steps from above first: Σ E gains at least as much per cycle at n as at any
        // fewer cycles (the envelope's peak only rises with n), so from a reaching n, with g the
        // last cycle's gain, n − ⌊(Σ E − d) / g⌋ still reaches — and a step of zero means n − 1
        // does not. Each step is checked (a step that does not reach is undone, and the
        // bisection below finishes), so the result never rests on that argument; on the long
        // moves (n up to 2^40) they take a few steps where the bisection takes 30 and more
        // (measured on the Cortex-M4 probe: the worst whole-range set-up 30,317 → 24,856).
        let total = |envelope: &mut Envelope, cycles: i128| {
            envelope.cycles = cycles;
            envelope.cut_counting(max, below_max).sum
        };
        for _ in 0..8 {
            // (Where the bracket is already narrow, bisecting it is cheaper: two sums a step.)
            if high - low <= 1 << 10 {
                break;
            }
            let at_high = total(&mut envelope, high);
            let gain = at_high - total(&mut envelope, high - 1);
            let step = if gain > 0 {
                divide(at_high - distance, gain)
            } else {
                0
            };
            if step == 0 {
                if gain > 0 {
                    // n − 1 falls short (its sum is below the distance).
                    low = high - 1;
                }
                break;
            }
            let next = (high - step).max(low + 1);
            if total(&mut envelope, next) < distance {
                low = next;
                break;
            }
            high = next;
        }
        while high - low > 1 {
            let middle = low + (high - low) / 2;
            if reaches(&mut envelope, middle) {
                high = middle;
            } else {
                low = middle;
            }
        }
        high
    } else {
        envelope.cycles = plateau_from;
        let short = distance - envelope.cut_counting(max, below_max).sum;
        plateau_from + (short + max - 1) / max
    };
    envelope.cycles = fastest.max(landing_cycles);
    // The slowest plan of those cycles, every velocity at least 1 unit: if it passes the
    // distance, so does every plan of as many cycles or more (its sum grows with n).
    if envelope.cut(1).sum > distance {
        return None;
    }
    if envelope.cycles == 0 {
        // On the destination at up to S: the drop is the landing.
        return Some([(0, 0, 0); 6]);
    }
    let level = highest_level(&envelope, distance, max, below_max);
    let cut = envelope.cut(level);
    let extra = distance - cut.sum;
    debug_assert!(
        cut.sum <= distance && (level == max || envelope.cut(level + 1).sum > distance),
        "the highest level that fits"
    );
    let at_level = envelope.cycles - cut.slowing - cut.rising - cut.falling;
    // The cycles at the level that cannot take an extra unit: where E_i is exactly the level
    // (L_i ≤ c on every cycle at it) — at most the first (where the rising line meets it) and
    // the last (the falling one). The extra units go right after the first, so they never end
    // the plateau: fewer than the cycles with E_i ≥ level + 1, they leave one at the level after.
    let above = envelope.cut(level + 1);
    let lead = i128::from(above.rising > cut.rising);
    // (At the level V the envelope's own cap binds and nothing is extra.)
    debug_assert!(extra >= 0 && (extra == 0 || extra < above.sum - cut.sum));
    let runs = [
        (
            envelope.lower - envelope.deceleration,
            -envelope.deceleration,
            cut.slowing,
        ),
        (
            first + envelope.acceleration,
            envelope.acceleration,
            cut.rising,
        ),
        (level, 0, lead),
        (level + 1, 0, extra),
        (level, 0, at_level - lead - extra),
        (
            envelope.landing + (cut.falling - 1) * envelope.deceleration,
            -envelope.deceleration,
            cut.falling,
        ),
    ];
    // Every value fits: velocities ≤ V < 2^48, counts < 2^56.
    Some(runs.map(|(next, increment, count)| (next as i64, increment as i64, count as u64)))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A move's limits in plain integers (the plan's arithmetic does not care about the unit).
    #[derive(Debug, Clone, Copy)]
    struct Limits {
        max_velocity: i64,
        acceleration: i64,
        deceleration: i64,
        start_velocity: i64,
    }

    /// The fewest cycles of any plan from `velocity` (0: from rest) that covers `distance`
    /// exactly, by breadth-first search over (distance covered, last velocity): every velocity
    /// 1 … V, the first ≤ (velocity, or S from rest) + A and, in motion, ≥ velocity − D, then
    /// changes within −D … +A, the last ≤ S. `None` when no plan lands.
    fn fewest_cycles(distance: i64, velocity: i64, limits: Limits) -> Option<u64> {
        let Limits {
            max_velocity,
            acceleration,
            deceleration,
            start_velocity,
        } = limits;
        if distance == 0 && velocity <= start_velocity {
            return Some(0);
        }
        let top = if velocity == 0 {
            start_velocity
        } else {
            velocity
        };
        let mut frontier: Vec<(i64, i64)> = (1..=max_velocity)
            .filter(|&w| w <= top + acceleration && (velocity == 0 || w >= velocity - deceleration))
            .filter(|&w| w <= distance)
            .map(|w| (w, w))
            .collect();
        let mut seen = std::collections::HashSet::new();
        for cycles in 1.. {
            if frontier.is_empty() {
                return None;
            }
            if frontier
                .iter()
                .any(|&(covered, last)| covered == distance && last <= start_velocity)
            {
                return Some(cycles);
            }
            let mut next = Vec::new();
            for &(covered, last) in &frontier {
                for w in (last - deceleration).max(1)..=(last + acceleration).min(max_velocity) {
                    if covered + w <= distance && seen.insert((covered + w, w)) {
                        next.push((covered + w, w));
                    }
                }
            }
            frontier = next;
        }
        unreachable!()
    }

    /// Checks the runs against the limits and the distance; returns their cycles.
    fn check(runs: &[Run; 6], distance: i64, velocity: i64, limits: Limits) -> u64 {
        let velocities: Vec<i64> = runs
            .iter()
            .flat_map(|&(next, increment, count)| {
                (0..count as i64).map(move |k| next + k * increment)
            })
            .collect();
        assert_eq!(
            velocities.iter().sum::<i64>(),
            distance,
            "exact: {velocities:?}"
        );
        let mut last = velocity;
        for (i, &w) in velocities.iter().enumerate() {
            assert!(
                (1..=limits.max_velocity).contains(&w),
                "cycle {i}: {velocities:?}"
            );
            let top = if i == 0 && velocity == 0 {
                limits.start_velocity
            } else {
                last
            };
            assert!(
                w <= top + limits.acceleration,
                "speed-up, cycle {i}: {velocities:?}"
            );
            if i > 0 || velocity != 0 {
                assert!(
                    w >= last - limits.deceleration,
                    "slow-down, cycle {i}: {velocities:?}"
                );
            }
            last = w;
        }
        assert!(last <= limits.start_velocity, "the drop: {velocities:?}");
        velocities.len() as u64
    }

    /// Long moves from rest (where the search for the fewest cycles takes its secant steps):
    /// the plan's cycles are the fewest whose fastest envelope reaches the distance — one cycle
    /// fewer does not — and its velocities sum to the distance, over the rates' whole range.
    #[test]
    fn long_moves_take_the_fewest_cycles() {
        let mut seed = 0x2545_f491_4f6c_dd1du64;
        let mut next = |bits: u32| {
            // xorshift: any value of `bits` bits, log-uniform in its width.
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            let width = (seed % u64::from(bits)) as u32 + 1;
            (seed >> 11) % (1 << width) + 1
        };
        let mut secant = 0;
        for _ in 0..3_000 {
            let max_velocity = (next(31) as i64) << 16;
            let acceleration = (next(31) as i64) << 8;
            let deceleration = (next(31) as i64) << 8;
            let start_velocity = (next(31) as i64) << 16;
            if start_velocity <= deceleration || start_velocity > max_velocity {
                continue;
            }
            let distance = i128::from(next(31)) << 32;
            let Some(runs) = plan(
                distance,
                0,
                max_velocity,
                acceleration,
                deceleration,
                start_velocity,
            ) else {
                panic!("from rest every distance lands");
            };
            let cycles: i128 = runs.iter().map(|run| i128::from(run.2)).sum();
            let sum: i128 = runs
                .iter()
                .map(|&(next, increment, count)| {
                    let count = i128::from(count);
                    count * i128::from(next) + i128::from(increment) * (count * (count - 1) / 2)
                })
                .sum();
            assert_eq!(sum, distance);
            let mut envelope = Envelope {
                first: i128::from(start_velocity),
                acceleration: i128::from(acceleration),
                deceleration: i128::from(deceleration),
                landing: i128::from(start_velocity),
                cycles,
                lower: 0,
                rates: Rates {
                    per_acceleration: Per::new(i128::from(acceleration)),
                    per_deceleration: Per::new(i128::from(deceleration)),
                    per_both: Per::new(i128::from(acceleration) + i128::from(deceleration)),
                },
            };
            let max = i128::from(max_velocity);
            assert!(envelope.cut(max).sum >= distance);
            envelope.cycles = cycles - 1;
            assert!(
                envelope.cut(max).sum < distance,
                "{cycles} cycles is not the fewest"
            );
            let least = i128::from(start_velocity);
            secant += usize::from((distance + least - 1) / least - distance / max > 1 << 10);
        }
        assert!(secant > 100, "only {secant} moves with a wide bracket");
    }

    /// A progression's sum against u128 arithmetic, saturated, across the widths.
    #[test]
    fn a_progressions_sum_saturates_exactly() {
        let values = [
            0u64,
            1,
            2,
            3,
            255,
            1 << 20,
            (1 << 32) + 7,
            (1 << 48) - 1,
            (1 << 56) + 3,
        ];
        for count in values {
            for first in values.iter().map(|v| v >> 2) {
                for step in [0u64, 1, 2, 1 << 8, 1 << 30] {
                    let last = first + count.saturating_sub(1).min(1 << 20) * step;
                    if count > 1 << 20 && step != 0 {
                        continue;
                    }
                    let exact = u128::from(count) * u128::from(first + last) / 2;
                    let expected = u64::try_from(exact).unwrap_or(u64::MAX);
                    assert_eq!(
                        progression(count, first, last),
                        expected,
                        "{count} {first} {last}"
                    );
                }
            }
        }
    }

    /// Every small move with S > D, from rest and in motion at every velocity: a plan exactly
    /// when the search finds one, of its fewest cycles, keeping every limit and the distance.
    #[test]
    fn the_fewest_cycles_of_any_plan_or_none() {
        let mut planned = 0;
        let mut none = 0;
        for max_velocity in 2..=9 {
            for acceleration in 1..=4 {
                for deceleration in 1..=3 {
                    for start_velocity in deceleration + 1..=max_velocity {
                        let limits = Limits {
                            max_velocity,
                            acceleration,
                            deceleration,
                            start_velocity,
                        };
                        for velocity in 0..=max_velocity {
                            for distance in 0..=40 {
                                let expected = fewest_cycles(distance, velocity, limits);
                                let got = plan(
                                    i128::from(distance),
                                    velocity,
                                    max_velocity,
                                    acceleration,
                                    deceleration,
                                    start_velocity,
                                );
                                let context = (distance, velocity, limits);
                                match (expected, got) {
                                    (None, None) => none += 1,
                                    (Some(cycles), Some(runs)) => {
                                        let got = check(&runs, distance, velocity, limits);
                                        assert_eq!(got, cycles, "{context:?}: {runs:?}");
                                        planned += 1;
                                    }
                                    _ => panic!("{context:?}: {expected:?} vs {got:?}"),
                                }
                            }
                        }
                    }
                }
            }
        }
        // Both kinds occur, many times.
        assert!(
            planned > 10_000 && none > 1_000,
            "{planned} planned, {none} none"
        );
    }
}
