//! One side of the MCX514 S-curve (the speed-up or the slow-down): how its rate of speed change
//! rises by the jerk within its cap and falls back to zero as the speed lands on its target.

/// One side of the S-curve (the speed-up or the slow-down) in raw I32F32 per-cycle bits: how the
/// rate may change per cycle (the jerk), its cap (AC or DC), and the speed a ramp-down from the
/// cap adds (see [`Ramp::tail`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) struct Ramp {
    pub(super) jerk: i64,
    pub(super) cap: i64,
    /// cap − jerk: a rate at or above it steps up to the cap itself (no overflow, unlike
    /// rate + jerk at the largest registers).
    pub(super) cap_less_jerk: i64,
    /// [`Ramp::tail`] of the cap, saturated at `i64::MAX` (then never affordable).
    pub(super) cap_tail: i64,
    /// min(jerk, cap): the rate a ramp from zero steps to first. A gap below it is closed in one
    /// cycle by the rule's landing (`Ramp::next` would stay at zero for ever).
    pub(super) first: i64,
}

impl Ramp {
    /// The ramp of `jerk` within `cap` (raw I32F32 bits per cycle³ and per cycle², both > 0).
    pub(super) fn new(jerk: i64, cap: i64) -> Self {
        Self {
            jerk,
            cap,
            cap_less_jerk: cap - jerk,
            cap_tail: Self::tail(cap, jerk),
            first: jerk.min(cap),
        }
    }

    /// S(r) = Σ_{i ≥ 1} max(r − i·J, 0): the speed the cycles after one at rate r add while the
    /// rate falls by J per cycle to zero (the last step from below J to 0). Computed once per move
    /// (for the cap) and at a command; on the way it follows the rate by the exact identities
    /// S(r + J) = S(r) + max(r, 0) and S(r − J) = S(r) − max(r − J, 0), with no division.
    pub(super) fn tail(rate: i64, jerk: i64) -> i64 {
        if rate <= jerk {
            return 0;
        }
        // n terms, those with r − i·J > 0 (i < r/J); their sum n·r − J·n(n+1)/2 is
        // n·(2r − J·(n+1))/2, the factor in 64 bits (J·(n+1) lies within r … r + J − 1, so the
        // factor within r − J + 1 … r) and the product checked: past 2^64 the tail is past
        // i64::MAX too. (64-bit: a 32-bit core divides and multiplies those in a few dozen
        // instructions, 128-bit ones in hundreds.)
        let (rate, jerk) = (rate as u64, jerk as u64);
        let n = (rate - 1) / jerk;
        let factor = 2 * rate - jerk * (n + 1);
        n.checked_mul(factor).map_or(i64::MAX, |twice| {
            i64::try_from(twice / 2).unwrap_or(i64::MAX)
        })
    }

    /// This cycle's speed change, from the ramp's rate and tail with `gap` of speed still to
    /// gain (or shed), updating them: the largest of rate + J (capped) whose rate plus tail fits
    /// the gap; else, with the slack (the gap less the tail) above rate − J, the slack itself
    /// (at most the rate: the rate held), the ramp's rate kept so that rate − J follows; else
    /// rate − J. So the rate stays within J of the last change, and the descent from the top
    /// takes in one cycle what the tail leaves over (the slack is constant while the rate falls
    /// by J, so it fits between two of its steps): the speed lands on its target with the rate
    /// at zero, with no cycles crept at a rate below one jerk step.
    ///
    /// Invariant: tail ≤ gap (the rate chosen last fitted the gap then). No overflow: the rate
    /// and tail in hand were chosen with rate + tail ≤ the gap then (< 2⁶³), so tail + rate is
    /// in range; a sum with the gap is compared as a difference.
    pub(super) fn next(&self, rate: &mut i64, tail: &mut i64, gap: i64) -> i64 {
        let (up, up_tail) = if *rate >= self.cap_less_jerk {
            (self.cap, self.cap_tail)
        } else {
            (*rate + self.jerk, *tail + *rate)
        };
        if up <= gap && up_tail <= gap - up {
            (*rate, *tail) = (up, up_tail);
            return up;
        }
        // ≥ 0 by the invariant; rate − J, held at zero (the last step from below J).
        let slack = gap - *tail;
        let down = (*rate - self.jerk).max(0);
        if slack > down {
            // Within [rate − J, rate]: the rate held (slack ≥ rate), or the slack once, after
            // which the gap is the tail and the descent goes on from the rate.
            return slack.min(*rate);
        }
        // S(r − J) = S(r) − (r − J); from r ≤ J both are 0.
        (*rate, *tail) = (down, *tail - down);
        down
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The tail against its sum term by term (small rates) and against the 128-bit closed form
    /// (large ones, saturated past i64::MAX).
    #[test]
    fn the_tail_is_the_sum_of_the_descent() {
        for jerk in 1..20i64 {
            for rate in 0..400i64 {
                let sum: i64 = (1..).map(|i| rate - i * jerk).take_while(|&t| t > 0).sum();
                assert_eq!(Ramp::tail(rate, jerk), sum, "rate {rate} jerk {jerk}");
            }
        }
        let wide = |rate: i64, jerk: i64| -> i64 {
            let (r, j) = (i128::from(rate), i128::from(jerk));
            let n = (r - 1) / j;
            i64::try_from(n * r - j * n * (n + 1) / 2).unwrap_or(i64::MAX)
        };
        for (rate, jerk) in [
            (i64::MAX, 1),
            (i64::MAX, 3),
            (1 << 40, 1),
            (1 << 33, 1),
            (3_037_000_499, 1), // near where the tail passes 2^62
            (6_074_000_999, 1),
            (i64::MAX, 1 << 40),
            (i64::MAX - 5, i64::MAX - 6),
            (1 << 62, (1 << 31) + 7),
        ] {
            assert_eq!(
                Ramp::tail(rate, jerk),
                wide(rate, jerk),
                "rate {rate} jerk {jerk}"
            );
        }
    }
}
