//! The trapezoid's plan when it may stop from its starting velocity (SPEC §7, issue #12): the
//! last moving cycle may drop to rest from any velocity up to the starting velocity S. With
//! S ≤ D that drop is an ordinary deceleration and the per-cycle rule of [`super::Trapezoidal`]
//! plans the move; with S > D it is not, and the largest velocity each cycle can leave a distance
//! no landing covers (the stopping distance jumps at S), so the landing is planned with the rest.
//!
//! A plan of n moving cycles has velocities w_1 … w_n with w_1 ≤ w0 + A (w0 the present velocity,
//! or S from rest: the first cycle's jump), speed-ups ≤ A, slow-downs ≤ D, every w ≤ V, and
//! w_n ≤ S (the drop). So w_i ≤ E_i = min(w0 + i·A, S + (n − i)·D, V), and E itself keeps every
//! rate: it is the fastest n-cycle move, and n is taken as small as lets Σ E_i reach the
//! distance d (no plan is shorter). Then the velocities are E cut at a level c, the largest with
//! Σ min(E_i, c) ≤ d, and the units of 2^-32 counts still missing, fewer than the cycles with
//! E_i ≥ c + 1, go one each to the first of those cycles: every rate still holds (the cut
//! changes a velocity by at most what E does, the extra unit by one unit), and the sum is d.
//! The result is at most six runs: rising by A, one cycle at c, the extra units at c + 1, c,
//! falling by D to the landing, rest.

use super::bisect::last_true;

/// A run in the frame where the destination lies ahead: `(first velocity, change per cycle,
/// cycles)`, I32F32 bits.
pub(super) type Run = (i64, i64, u64);

/// The envelope of the fastest n-cycle plan.
#[derive(Debug, Clone, Copy)]
struct Envelope {
    first: i128,
    acceleration: i128,
    deceleration: i128,
    landing: i128,
    cycles: i128,
}

/// The three parts of the envelope cut at a level: `rising` cycles below it on the way up,
/// `falling` below it on the way down, the rest at it; and the sum.
#[derive(Debug, Clone, Copy)]
struct Cut {
    rising: i128,
    falling: i128,
    sum: i128,
}

impl Envelope {
    /// The envelope cut at `cap` (1 ≤ cap ≤ V): Σ_{i=1}^{n} min(w0 + i·A, S + (n − i)·D, cap).
    ///
    /// The rising line is below the falling one for i ≤ p = ⌊(S + n·D − w0) / (A + D)⌋ (both
    /// lines integer, so the floor is exact); on that side, the cycles below the cap are
    /// those with w0 + i·A < cap, i ≤ ⌊(cap − w0 − 1) / A⌋; on the other, with j = n − i, those
    /// with S + j·D < cap. Every value is below 2^48 and n below 2^56: i128 throughout.
    fn cut(&self, cap: i128) -> Cut {
        self.cut_counting(cap, self.below(cap))
    }

    /// How many rising cycles at most (⌊(cap − w0 − 1) / A⌋ + 1 counting i = 0) and falling ones
    /// (⌊(cap − S − 1) / D⌋ + 1) lie below `cap`, before the lines' own extent limits them: the
    /// divisions of [`Self::cut`] that do not depend on n, so a search over n does them once.
    fn below(&self, cap: i128) -> (i128, i128) {
        (
            if cap > self.first {
                divide(cap - self.first - 1, self.acceleration)
            } else {
                0
            },
            if cap > self.landing {
                divide(cap - self.landing - 1, self.deceleration) + 1
            } else {
                0
            },
        )
    }

    /// [`Self::cut`] with [`Self::below`]'s counts for `cap` given.
    fn cut_counting(&self, cap: i128, (rising_below, falling_below): (i128, i128)) -> Cut {
        let Self {
            first,
            acceleration,
            deceleration,
            landing,
            cycles,
        } = *self;
        let reach = landing + cycles * deceleration - first;
        let up = if reach < 0 {
            0
        } else {
            divide(reach, acceleration + deceleration).min(cycles)
        };
        let down = cycles - up;
        let rising = rising_below.min(up);
        let falling = falling_below.min(down);
        let sum = rising * first
            + acceleration * (rising * (rising + 1) / 2)
            + falling * landing
            + deceleration * (falling * (falling - 1) / 2)
            + (cycles - rising - falling) * cap;
        Cut {
            rising,
            falling,
            sum,
        }
    }
}

/// The highest level c ≤ V whose cut fits in `distance`: Σ min(E_i, c) ≤ distance.
///
/// The cut's sum is piecewise linear in c, with a kink at every value of E: the rising values
/// w0 + i·A and the falling ones S + j·D below V. So bisect over each progression's index for
/// the highest value whose cut fits (at a rising value the count of rising cycles below it is
/// known, i − 1, and only the falling one takes a division; and the other way round), then
/// solve the line that runs from the higher of the two to the next kink: a few dozen cuts at
/// most where bisecting c itself would take 48.
fn highest_level(envelope: &Envelope, distance: i128, max: i128, below_max: (i128, i128)) -> i128 {
    let n = envelope.cycles;
    // The rising side (i ≤ up) does not depend on the level: one division.
    let reach = envelope.landing + n * envelope.deceleration - envelope.first;
    let up = if reach < 0 {
        0
    } else {
        divide(reach, envelope.acceleration + envelope.deceleration).min(n)
    };
    let down = n - up;
    // The cut at `cap` from the counts of rising and falling values below it.
    let sum = |cap: i128, rising: i128, falling: i128| {
        rising * envelope.first
            + envelope.acceleration * (rising * (rising + 1) / 2)
            + falling * envelope.landing
            + envelope.deceleration * (falling * (falling - 1) / 2)
            + (n - rising - falling) * cap
    };
    let rising_below = |cap: i128| {
        if cap > envelope.first {
            divide(cap - envelope.first - 1, envelope.acceleration).min(up)
        } else {
            0
        }
    };
    let falling_below = |cap: i128| {
        if cap > envelope.landing {
            (divide(cap - envelope.landing - 1, envelope.deceleration) + 1).min(down)
        } else {
            0
        }
    };
    // The largest k in 1 ..= count with fits(k), or 0 (fits is monotone, true then false).
    let last_fitting = |count: i128, fits: &dyn Fn(i128) -> bool| last_true(0, count + 1, fits);
    let rise = |i: i128| envelope.first + i * envelope.acceleration;
    let fall = |j: i128| envelope.landing + j * envelope.deceleration;
    let i = last_fitting(below_max.0.min(up), &|i| {
        let cap = rise(i);
        sum(cap, i - 1, falling_below(cap)) <= distance
    });
    let j = last_fitting(below_max.1.min(down), &|j| {
        let cap = fall(j - 1);
        sum(cap, rising_below(cap), j - 1) <= distance
    });
    // The cut at 1 is n units ≤ distance (every E_i ≥ 2^8, so n ≤ distance / 2^8).
    let mut start = 1;
    if i > 0 {
        start = start.max(rise(i));
    }
    if j > 0 {
        start = start.max(fall(j - 1));
    }
    // From `start` to the next kink the cut rises by the cycles above `start` per unit.
    let (rising, falling) = (rising_below(start + 1), falling_below(start + 1));
    let slope = n - rising - falling;
    if slope == 0 {
        return max;
    }
    (start + (distance - sum(start, rising, falling)) / slope).min(max)
}

/// ⌊a / b⌋ for 0 ≤ a and 0 < b, in 64 bits when both fit (a 32-bit core divides those several
/// times faster than 128-bit ones).
fn divide(a: i128, b: i128) -> i128 {
    match (u64::try_from(a), u64::try_from(b)) {
        (Ok(a), Ok(b)) => i128::from(a / b),
        _ => a / b,
    }
}

/// The runs that cover `distance` (> 0, I32F32 bits) from `velocity` (0 … V) and land with a
/// drop from at most S, per the module's documentation; `None` when the plan would slow down by
/// more than D on its first cycle (a move under way too fast for it: the caller plans the other
/// way).
pub(super) fn plan(
    distance: i128,
    velocity: i64,
    max_velocity: i64,
    acceleration: i64,
    deceleration: i64,
    start_velocity: i64,
) -> Option<[Run; 5]> {
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
        cycles: 1,
    };
    let below_max = envelope.below(max);
    let reaches = |envelope: &mut Envelope, cycles: i128| {
        envelope.cycles = cycles;
        envelope.cut_counting(max, below_max).sum >= distance
    };
    // The fewest cycles. From n1 = (cycles below V rising) + (below V falling) + 1 on, both
    // lines reach V before they meet, so every further cycle adds V: one division. Below n1,
    // bisect (Σ E grows with n).
    let plateau_from = below_max.0 + below_max.1 + 1;
    let high = if reaches(&mut envelope, plateau_from) {
        let mut low = 0; // does not reach
        let mut high = plateau_from;
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
    envelope.cycles = high;
    let level = highest_level(&envelope, distance, max, below_max);
    let cut = envelope.cut(level);
    let extra = distance - cut.sum;
    debug_assert!(
        cut.sum <= distance && (level == max || envelope.cut(level + 1).sum > distance),
        "the highest level that fits"
    );
    let at_level = envelope.cycles - cut.rising - cut.falling;
    // The cycles at the level whose envelope is exactly the level (the rest have E_i ≥ level + 1
    // and may take an extra unit): at most the first (where the rising line meets it) and the
    // last (the falling one). The extra units go right after the first, so they never end the
    // plateau: fewer than the cycles with E_i ≥ level + 1, they leave one at the level after.
    let above = envelope.cut(level + 1);
    let lead = i128::from(above.rising > cut.rising);
    // (At the level V the envelope's own cap binds and nothing is extra.)
    debug_assert!(extra >= 0 && (extra == 0 || extra < above.sum - cut.sum));
    let runs = [
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
    // The first cycle's velocity, against the present one: a slow-down of at most D.
    let opening = runs.iter().find(|run| run.2 > 0)?.0;
    if velocity != 0 && opening < first - envelope.deceleration {
        return None;
    }
    // Every value fits: velocities ≤ V < 2^48, counts < 2^56.
    Some(runs.map(|(next, increment, count)| (next as i64, increment as i64, count as u64)))
}
