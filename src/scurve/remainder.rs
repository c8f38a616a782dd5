//! The remainder: what whole cycles of cruise and whole units cannot take off the distance, taken
//! off exactly by *notch pairs* placed where the main move has room for them.
//!
//! A notch pair of width `w` and span `k` from cycle `s` lowers the acceleration by one raw unit
//! for `w` cycles from `s` and raises it by one unit for `w` cycles from `s + k`. Its jerk is −1
//! on cycle `s`, +1 on `s + w` and `s + k`, −1 on `s + k + w`; its velocity is
//! `−(box(w) ∗ box(k))`, a dip at most `min(w, k)` deep that ends on cycle `s + k + w − 2`; it
//! covers exactly `w·k` less and leaves the end of the move unchanged.
//!
//! Where a pair fits is decided by O(1) inequalities on the main move's [`Bounds`] (the lowered
//! window where the acceleration is ≥ 0, the raised one where it is ≤ 0, the velocity at the first
//! and last cycle of each dip) and by the exact jerk where the main move's jerk leaves no room
//! ([`Placement::fits`]). Two pairs of widths `w` and `w + 1` take any
//! remainder `E` in their range: `w·k₁ + (w + 1)·k₂ = E` is solved by
//! `k₁ ≡ −E (mod w + 1)` ([`solve_spans`]), because `w ≡ −1` is its own inverse modulo `w + 1`.

use super::products::{product, saturating_product};
use super::shape::{Bounds, MainMove};
use crate::division::{ceil_div, div, div_ceil, floor_div};

/// One notch pair: see the module docs.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub(super) struct Notch {
    /// The cycle of its first jerk change (−1).
    pub start: u64,
    /// Cycles the acceleration is one unit lower, and later one unit higher.
    pub width: u64,
    /// Cycles from the first lowered cycle to the first raised one.
    pub span: u64,
}

impl Notch {
    /// Its jerk impulses `(cycle, ±1)`.
    pub fn impulses(&self) -> [(u64, i64); 4] {
        let (s, w, k) = (self.start, self.width, self.span);
        [(s, -1), (s + w, 1), (s + k, 1), (s + k + w, -1)]
    }

    /// The last cycle on which it lowers the velocity.
    fn last_dip(&self) -> u64 {
        self.start + self.span + self.width - 2
    }

    /// How much it lowers the velocity on cycle `n`: `(box(w) ∗ box(k))(n − s)`.
    fn depth_at(&self, n: u64) -> u64 {
        let Some(m) = n.checked_sub(self.start) else {
            return 0;
        };
        let (w, k) = (self.width, self.span);
        let after = (w + k).saturating_sub(1 + m);
        (m + 1).min(w).min(k).min(after)
    }
}

/// At most this many notch pairs: the velocity notch and two for the remainder.
pub(super) const MAX_NOTCHES: usize = 3;

/// The notch pairs of a plan.
#[derive(Debug, Clone, Copy, Default)]
pub(super) struct Placement {
    /// The pairs in `[0, len)`; those after them are not the placement's (one cleared,
    /// [`Self::clear`], leaves them as they were).
    notches: [Notch; MAX_NOTCHES],
    len: usize,
}

/// Placements are equal when their pairs are.
impl PartialEq for Placement {
    fn eq(&self, other: &Self) -> bool {
        self.notches() == other.notches()
    }
}

impl Eq for Placement {}

impl Placement {
    /// No pairs, as [`Self::default`] without writing the array over (the search places pairs
    /// attempt after attempt into one placement).
    pub fn clear(&mut self) {
        self.len = 0;
    }

    /// The pairs placed.
    pub fn notches(&self) -> &[Notch] {
        &self.notches[..self.len]
    }

    /// With one more pair.
    #[cfg(test)]
    pub fn with(mut self, notch: Notch) -> Self {
        self.push(notch);
        self
    }

    /// Adds a pair (in place: a placement is 80 bytes, and a copy costs about an instruction a
    /// byte on a Cortex-M4).
    pub fn push(&mut self, notch: Notch) {
        if self.len < MAX_NOTCHES {
            self.notches[self.len] = notch;
            self.len += 1;
        }
    }

    /// Adds `pairs` if they fit with those placed already ([`Self::fits`]); else leaves the
    /// placement as it was.
    fn try_add(
        &mut self,
        pairs: &[Notch],
        main: &MainMove,
        bounds: &Bounds,
        jerk_limit: u64,
    ) -> bool {
        let placed = self.len;
        for &pair in pairs {
            self.push(pair);
        }
        let fits = self.fits(placed, main, bounds, jerk_limit);
        if !fits {
            self.len = placed;
        }
        fits
    }

    /// Whether the pairs from the `checked`-th on fit the main move within `jerk_limit` (raw
    /// units), together with those before (which fit already), by O(1) inequalities per pair:
    ///
    /// - each lowered window `[s, s + w)` ends by `first_deceleration` (the acceleration is ≥ 0
    ///   there, so at most three units lower is far within the limit, which is ≥ 2^16), each
    ///   raised window starts from `rise_end − 1` on (the acceleration is ≤ 0 there);
    /// - on each cycle where a new pair changes the jerk, the main move's jerk plus every pair's
    ///   change on that cycle is within the limit — decided by the [`Bounds`] where the main
    ///   move's jerk has the sign that makes room (≥ 0 for a lower jerk, ≤ 0 for a higher), and
    ///   by the main move's exact jerk elsewhere;
    /// - every dip ends by the move's third-last cycle, and the main move's velocity at the first
    ///   and at the last cycle of each new dip is at least the dips' combined depth there.
    pub fn fits(&self, checked: usize, main: &MainMove, bounds: &Bounds, jerk_limit: u64) -> bool {
        let notches = self.notches();
        let new = &notches[checked.min(notches.len())..];
        let windows = new.iter().all(|n| {
            n.width > 0
                && n.span > n.width
                && n.start + n.width <= bounds.first_deceleration
                && n.start + n.span + 1 >= bounds.rise_end
                && n.start + n.span + n.width < bounds.total
        });
        if !windows {
            return false;
        }
        let limit = jerk_limit as i64;
        let lower_fits = |n: u64| {
            n < bounds.first_fall_end
                || (bounds.rise_end..bounds.first_deceleration).contains(&n)
                || n >= bounds.deceleration_jerked
        };
        let higher_fits = |n: u64| (bounds.last_rise_start..bounds.first_landing).contains(&n);
        let first_new = notches.len() - new.len();
        // Where the main move's jerk is known to leave room, |added| ≤ 3 ≤ … is enough (a main
        // jerk in [0, J] less up to J, or in [−J, 0] plus up to J).
        let jerk_fits_at = |cycle: u64, added: i64| {
            let room = (added <= 0 && lower_fits(cycle)) || (added >= 0 && higher_fits(cycle));
            (room && added.abs() <= limit) || (main.jerk_at(cycle) + added).abs() <= limit
        };
        // A pair's four impulses fall on four cycles (0 < w < k, checked above), so on one of
        // them it adds its own ±1 alone: a plan of one pair has no other to look up.
        let jerk_fits = if let ([pair], [_]) = (notches, new) {
            pair.impulses()
                .iter()
                .all(|&(cycle, amount)| jerk_fits_at(cycle, amount))
        } else {
            // Every pair's impulses, found once, not once for each impulse of the others they
            // are compared with (on a Cortex-M4 that took a third of a check of three pairs).
            // Written once each (a cleared table filled in wrote them twice).
            let impulses: [[(u64, i64); 4]; MAX_NOTCHES] =
                core::array::from_fn(|i| notches.get(i).map_or([(0, 0); 4], Notch::impulses));
            let impulses = &impulses[..notches.len()];
            impulses[first_new..]
                .iter()
                .enumerate()
                .all(|(index, own)| {
                    own.iter().all(|&(cycle, amount)| {
                        let mut added = amount;
                        for (other, pair) in impulses.iter().enumerate() {
                            if other != first_new + index {
                                for &(at, other_amount) in pair {
                                    if at == cycle {
                                        added += other_amount;
                                    }
                                }
                            }
                        }
                        jerk_fits_at(cycle, added)
                    })
                })
        };
        // The dips: at the first and last cycle of each, the main move's velocity covers them
        // all. Inside, the main move's velocity rises (falls) faster than the dips deepen, on
        // every cycle where the acceleration is at least their number (the tests replay every
        // plan they make and check it: [`super::schedule::Schedule::replay`]). The velocity is
        // first bounded below by [`Bounds::floor`] (one closed form instead of one per group);
        // the exact sum is taken only where that floor is not enough.
        // A pair's own dip is one unit deep on its first and its last cycle (0 < w < k), so
        // only the other pairs' depths are summed there.
        let covered = |own: usize, n: u64| {
            let mut depth = 1;
            for (other, pair) in notches.iter().enumerate() {
                if other != own {
                    depth += pair.depth_at(n);
                }
            }
            bounds.floor.velocity_at(n) >= depth || main.velocity_at(n) >= depth
        };
        jerk_fits
            && new.iter().enumerate().all(|(index, notch)| {
                covered(first_new + index, notch.start)
                    && covered(first_new + index, notch.last_dip())
            })
    }
}

/// Places the velocity notch of width `width` as the placement's first pair (`placement` is
/// empty), if one fits: it lowers the acceleration for `width` cycles ending in phase III and
/// raises it `c − 1` cycles later, so the whole cruise is `width` lower, and takes
/// `width · (c − 1)` off (the earliest start of phase V is `c − 1` or `c`). `false` (and the
/// placement empty) if neither of two ends fits.
///
/// The first end is where phase III starts earliest. The raise then ends `c − 1` cycles later:
/// inside phase V when every unit starts phase V on cycle `c` and some unit's first ramp is as
/// long as the shortest second ramp — there the jerk is −J already, and the raise's −1 has no
/// room. The second (tried only if it differs) is the earliest that ends the raise after every
/// unit's phase V; its lowered window's last jerk change then falls in phase III, whose jerk ≤ 0
/// has room for the +1. Without it, a move of 2 counts with a jerk of 2 raw units, whose two
/// units meet the maximum velocity only from above, cruised 56 raw units under it instead: 8
/// cycles over the optimum.
pub(super) fn place_velocity_notch(
    placement: &mut Placement,
    width: u64,
    c: u64,
    main: &MainMove,
    bounds: &Bounds,
    jerk_limit: u64,
) -> bool {
    let Some(span) = c.checked_sub(1) else {
        return false;
    };
    let mut ending_on = |end: u64| {
        end.checked_sub(width).is_some_and(|start| {
            placement.try_add(&[Notch { start, width, span }], main, bounds, jerk_limit)
        })
    };
    let first_end = bounds.first_fall_end;
    // The raise's last jerk change, on `end + span`, at or after the latest end of phase V.
    let later_end = bounds.deceleration_jerked.saturating_sub(span);
    ending_on(first_end) || (later_end > first_end && ending_on(later_end))
}

/// A cycle number in the width the search for a placement works in: 32 bits for a move shorter
/// than 2^31 cycles (nearly every move; a Cortex-M4 then compares, subtracts and clamps two
/// cycles in one instruction each, not three), 64 otherwise. Sums of two cycles of the move
/// (`s + k`, `w + 1`) stay below 2^32 in the narrow width.
trait Cycle: Copy + Ord + core::ops::Add<Output = Self> + core::ops::Sub<Output = Self> {
    const ZERO: Self;
    const ONE: Self;
    /// The cycle in this width; a value past it (only [`u64::MAX`], the unbounded cap) becomes
    /// the width's largest.
    fn narrow(cycle: u64) -> Self;
    /// Back to 64 bits.
    fn widen(self) -> u64;
    fn saturating_sub(self, other: Self) -> Self;
}

impl Cycle for u32 {
    const ZERO: Self = 0;
    const ONE: Self = 1;
    fn narrow(cycle: u64) -> Self {
        u32::try_from(cycle).unwrap_or(u32::MAX)
    }
    fn widen(self) -> u64 {
        u64::from(self)
    }
    fn saturating_sub(self, other: Self) -> Self {
        u32::saturating_sub(self, other)
    }
}

impl Cycle for u64 {
    const ZERO: Self = 0;
    const ONE: Self = 1;
    fn narrow(cycle: u64) -> Self {
        cycle
    }
    fn widen(self) -> u64 {
        self
    }
    fn saturating_sub(self, other: Self) -> Self {
        u64::saturating_sub(self, other)
    }
}

/// Cycles `[low, high]` (empty when `low > high`).
type Interval<C> = (C, C);

/// Where a pair of some width can go: its first notch's cycles, its second's, and its spans.
type Region<C> = (Interval<C>, Interval<C>, Interval<C>);

/// Where one notch of a pair of width `w` can start, as a function of `w`:
/// `[max(low_floor, low_base − w), min(high_cap, high_base − w)]`, the subtractions saturating.
#[derive(Debug, Clone, Copy)]
struct Edges<C> {
    low_floor: C,
    low_base: C,
    high_cap: C,
    high_base: C,
}

impl<C: Cycle> Edges<C> {
    fn at(&self, w: C) -> Interval<C> {
        (
            self.low_floor.max(self.low_base.saturating_sub(w)),
            self.high_cap.min(self.high_base.saturating_sub(w)),
        )
    }

    /// The widest `w` whose interval ([`Self::at`]) can be non-empty: past it the high end,
    /// at most `high_base − w`, falls below the low end, at least `low_floor` (no limit where
    /// the floor is 0; none fits where `high_base < low_floor`).
    fn widest(&self) -> u64 {
        if self.low_floor == C::ZERO {
            u64::MAX
        } else {
            self.high_base
                .widen()
                .saturating_sub(self.low_floor.widen())
        }
    }
}

/// Where a pair can go in one placement, for any width: found once per placement from the
/// main move's [`Bounds`], then a few subtractions per width.
#[derive(Debug, Clone, Copy)]
struct Room<C> {
    first: Edges<C>,
    second: Edges<C>,
}

impl<C: Cycle> Room<C> {
    /// The first notch (−1 where the jerk is ≥ 0, +1 `w` later where it is ≤ 0, the window
    /// before phase V) in phases I–II, or in the cruise (`first_in_cruise`); the second (+1
    /// where the jerk is ≤ 0, from the end of phase III on; −1 `w` later where the jerk is ≥ 0,
    /// before the last cycle) ending in the cruise (`second_in_cruise`), or after phase V.
    fn new(bounds: &Bounds, (first_in_cruise, second_in_cruise): (bool, bool)) -> Self {
        let deceleration = bounds.first_deceleration;
        let first = if first_in_cruise {
            Edges {
                low_floor: bounds.rise_end,
                low_base: 0,
                high_cap: u64::MAX,
                high_base: deceleration,
            }
        } else {
            Edges {
                low_floor: 0,
                low_base: bounds.last_rise_start,
                high_cap: bounds.first_fall_end.saturating_sub(1),
                high_base: deceleration,
            }
        };
        let from = bounds.rise_end.saturating_sub(1);
        let second = if second_in_cruise {
            Edges {
                low_floor: from,
                low_base: bounds.rise_end,
                high_cap: u64::MAX,
                high_base: deceleration.saturating_sub(1),
            }
        } else {
            Edges {
                low_floor: from,
                low_base: bounds.deceleration_jerked,
                high_cap: bounds.first_landing.saturating_sub(1),
                high_base: bounds.total.saturating_sub(1),
            }
        };
        let narrow = |edges: Edges<u64>| Edges {
            low_floor: C::narrow(edges.low_floor),
            low_base: C::narrow(edges.low_base),
            high_cap: C::narrow(edges.high_cap),
            high_base: C::narrow(edges.high_base),
        };
        Self {
            first: narrow(first),
            second: narrow(second),
        }
    }

    /// The widest notch either notch of a pair can have here ([`Edges::widest`]).
    fn widest(&self) -> u64 {
        self.first.widest().min(self.second.widest())
    }

    /// For width `w`: the first notch's cycles, the second's, and the spans between them (a
    /// pair's span exceeds its width).
    fn at(&self, w: C) -> Region<C> {
        let (first, second) = (self.first.at(w), self.second.at(w));
        let (low, high) = spans(first, second);
        (first, second, (low.max(w + C::ONE), high))
    }
}

/// The spans a pair of width `w` can have with its first notch in `first` and its second in
/// `second`: the differences of the two intervals.
fn spans<C: Cycle>(first: Interval<C>, second: Interval<C>) -> Interval<C> {
    if first.0 > first.1 || second.0 > second.1 {
        return (C::ONE, C::ONE.saturating_sub(C::ONE));
    }
    (
        second.0.saturating_sub(first.1),
        second.1.saturating_sub(first.0),
    )
}

/// The pair of width `w` and span `k` with its notches in `first` and `second`: the start in
/// the middle of where both fit (`None` if `k` is out of reach).
fn place<C: Cycle>(first: Interval<C>, second: Interval<C>, width: C, span: C) -> Option<Notch> {
    let low = first.0.max(second.0.saturating_sub(span));
    if second.1 < span {
        return None;
    }
    let high = first.1.min(second.1 - span);
    (low <= high).then(|| Notch {
        start: (low.widen() + (high.widen() - low.widen()) / 2),
        width: width.widen(),
        span: span.widen(),
    })
}

/// An interval in 64 bits.
fn widened<C: Cycle>((low, high): Interval<C>) -> (u64, u64) {
    (low.widen(), high.widen())
}

/// Two notch pairs, of widths `w` and `w + 1`, with spans in `range`, taking exactly `left`:
/// `w·k₁ + (w + 1)·k₂ = left`. `w ≡ −1 (mod w + 1)`, so `k₁ ≡ −left (mod w + 1)`; the solutions
/// are `k₁ = r + (w + 1)·t`, `k₂ = q − w·t`, and the inequalities of `range` bound `t`.
fn solve_spans(left: u64, width: u64, range: (u64, u64)) -> Option<(u64, u64)> {
    // No span is longer than left / w, so clamping the range there keeps every value below
    // `left` (a few areas, < 2^50): 64-bit arithmetic, 32-bit divisions where they fit.
    let high = range.1.min(div(left, width));
    let (w, left, low, high) = (
        i64::try_from(width).ok()?,
        i64::try_from(left).ok()?,
        i64::try_from(range.0).ok()?,
        i64::try_from(high).ok()?,
    );
    // r = (−left) mod (w + 1) = w − ((left + w) mod (w + 1)).
    let r = w - (left + w - (w + 1) * floor_div(left + w, w + 1));
    let q = floor_div(left - w * r, w + 1);
    let t_low = ceil_div(low - r, w + 1).max(ceil_div(q - high, w));
    let t_high = floor_div(high - r, w + 1).min(floor_div(q - low, w));
    if t_low > t_high {
        return None;
    }
    // The middle solution: spans near each other, away from the ends of the range.
    let t = t_low + (t_high - t_low) / 2;
    Some((
        u64::try_from(r + (w + 1) * t).ok()?,
        u64::try_from(q - w * t).ok()?,
    ))
}

/// One pair of width `width` ∈ {1, 2} taking exactly `left + q·area` with its span in `range`,
/// for a small remainder: `(span, q)` with the least `q ≤ available`. Widths of one and two
/// divide by a shift (no division but the one for `q`, and that only when `left` falls short).
fn one_pair(
    left: u64,
    width: u64,
    range: (u64, u64),
    (area, available): (u64, u64),
) -> Option<(u64, u64)> {
    debug_assert!(width == 1 || width == 2);
    // Times the width by a shift: the spans are cycles of the move, far below 2^63.
    let shift = (width - 1) as u32;
    if range.0 > range.1 || range.1 << shift < left {
        return None; // no span in range, or the remainder is past the widest
    }
    let least = range.0.max(width + 1) << shift;
    let mut q = match least.checked_sub(left) {
        Some(short) if short > 0 => {
            if area == 0 || available == 0 {
                return None;
            }
            div_ceil(short, area)
        }
        _ => 0,
    };
    // An even width needs an even distance: one more unit of an odd area fixes the parity
    // (read from the last bits, before any product).
    let odd = |q: u64| width == 2 && (left ^ (q & area)) & 1 != 0;
    if odd(q) {
        q += 1;
    }
    if odd(q) || q > available {
        return None;
    }
    let target = left.checked_add(product(q, area)?)?;
    let span = target >> shift;
    (span <= range.1 && span > width).then_some((span, q))
}

/// How many widths from one below the estimate [`take`] tries: the estimate and the one below.
/// Over 200,000 random moves, the widths one and two above the estimate took 66 of the 62,550
/// remainders that two pairs near the estimate took; without them no plan of the `planning`
/// bench's 100,000 moves got longer (the mean and worst over the optimum stayed +0.927 and
/// +2.891), and the worst plan's Cortex-M4 count fell by a tenth.
const WIDTH_TRIES: u64 = 1;

/// Notch pairs that take exactly `left + q·area` off `main` together with the pairs already in
/// `placed` (added to it), for the least `q ≤ available` that makes the remainder fit
/// ([`Placement::fits`]): `Some(q)`, and `q` units of that area then keep their whole cruise;
/// `None` (and `placed` as it was) if no candidate fits. A fixed, small number of candidates:
/// for each of three ways to place a pair (first notch in phases I–II, second in the cruise or
/// after phase V; both in the cruise), one pair of width 1 or 2 for a small remainder, else (not
/// in the cruise alone) two pairs of widths `w` and `w + 1` for a few `w`: the estimate
/// `left / (2·span + 1)` and one below it, and half and all of the first ramp (where short moves
/// have room). With `with_unit`, the widths are estimated for `left + area` instead (a second
/// search's, after the first found nothing).
///
/// `UNITS` false gives no units back (`q` is 0, `units` and `with_unit` unread):
/// [`take_exactly`]. The search calls `take::<true>` alone, `super::pure_jerk` the other copy
/// alone: with one copy for both, the compiler inlined it into neither, and the search's
/// `complete` paid for the call (about 40 Cortex-M4 instructions more a random move, up to 280
/// on the costliest).
pub(super) fn take<const UNITS: bool>(
    left: u64,
    main: &MainMove,
    bounds: &Bounds,
    placed: &mut Placement,
    jerk_limit: u64,
    units: (u64, u64),
    with_unit: bool,
) -> Option<u64> {
    let (area, available) = if UNITS { units } else { (0, 0) };
    if left == 0 {
        return Some(0);
    }
    if left == 1 && (area == 0 || available == 0) {
        return None; // no pair takes less than 2 (a width of 1, a span of 2)
    }
    // A pair takes w·k with w + k < total (both notches inside the move), so less than
    // total²/4, and two pairs less than total²/2; q units only add to the remainder.
    if left >= saturating_product(bounds.total, bounds.total) / 2 {
        return None;
    }
    // With no unit to give back, the second search's call is the first search's, which failed.
    if with_unit && (area == 0 || available == 0) {
        return None;
    }
    let remainder = Remainder {
        left,
        main,
        bounds,
        jerk_limit,
        area,
        available,
        estimated: estimated(left, area, with_unit),
    };
    if bounds.total < 1 << 31 {
        remainder.take_in::<u32, UNITS>(placed)
    } else {
        remainder.take_in::<u64, UNITS>(placed)
    }
}

/// [`take`] with no units to give back: whether pairs take exactly `left` off `main` (added to
/// `placed`). For `super::pure_jerk`, whose main moves' rests are their own.
pub(super) fn take_exactly(
    left: u64,
    main: &MainMove,
    bounds: &Bounds,
    placed: &mut Placement,
    jerk_limit: u64,
) -> bool {
    take::<false>(left, main, bounds, placed, jerk_limit, (0, 0), false).is_some()
}

/// What [`take`] estimates the widths of two pairs for: `left`, or with `with_unit` one unit's
/// `area` more. Where the remainder alone is small beside the spans, the sums of two pairs near
/// the estimate, (2w + 1)·[K − w, K + w] for spans around K, leave gaps between consecutive w
/// that no cruise length closes (with a jerk of one raw unit there is one unit, and no other way
/// to change the remainder); one unit's area more lands it where they overlap.
fn estimated(left: u64, area: u64, with_unit: bool) -> u64 {
    if with_unit {
        left.saturating_add(area)
    } else {
        left
    }
}

/// What [`take`] places pairs for: the remainder `left`, the main move and its bounds, the jerk
/// limit, and the units of `area` (at most `available`) that may keep their cruise.
struct Remainder<'a> {
    left: u64,
    main: &'a MainMove,
    bounds: &'a Bounds,
    jerk_limit: u64,
    area: u64,
    available: u64,
    /// What the widths of two pairs are estimated for ([`estimated`]).
    estimated: u64,
}

impl Remainder<'_> {
    /// [`take`] with cycles of type `C`, wide enough for every cycle of the move (and the sum
    /// of two).
    fn take_in<C: Cycle, const UNITS: bool>(&self, placed: &mut Placement) -> Option<u64> {
        let (left, bounds, area, available) = (self.left, self.bounds, self.area, self.available);
        let estimated = self.estimated;
        let (main, jerk_limit) = (self.main, self.jerk_limit);
        let mut try_fit = |pairs: &[Notch]| placed.try_add(pairs, main, bounds, jerk_limit);
        // The three placements that take remainders (measured over 100,000 random moves: first
        // notch in phases I–II with the second in the cruise or after phase V, and both in the
        // cruise for single pairs; first in the cruise, second after phase V, never did).
        const PLACEMENTS: [(bool, bool); 3] = [(false, true), (false, false), (true, true)];
        // The most any q ≤ available can make of the remainder.
        let reach = saturating_product(area, available).saturating_add(left);
        for &placement in &PLACEMENTS {
            let room = Room::<C>::new(bounds, placement);
            // A single pair takes w·span ≤ 2·total, and q units only add to the remainder: a
            // larger one needs two pairs.
            let widest = if left <= bounds.total.saturating_mul(2) {
                2
            } else {
                0
            };
            for width in 1..=widest {
                let (first, second, range) = room.at(C::narrow(width));
                if range.0 > range.1 {
                    continue; // no span: one comparison in the narrow width
                }
                let Some((span, q)) = one_pair(left, width, widened(range), (area, available))
                else {
                    continue;
                };
                // span ≤ range.1, a cycle of the move: it narrows exactly.
                if place(first, second, C::narrow(width), C::narrow(span))
                    .is_some_and(|n| try_fit(&[n]))
                {
                    return Some(q);
                }
            }
            // Two pairs only with the first notch in phases I–II (see above).
            if placement.0 {
                continue;
            }
            // No notch wider than either room's widest fits ([`Room::widest`]), and two pairs
            // have widths `w` and `w + 1 ≥ 2`. The second notch in the cruise, say, starts at
            // `rise_end − 1` whatever the width and ends `w` before phase V: the moves with a
            // single unit and no cruise (a jerk of one raw unit, most often) leave here, before
            // the widths' estimates and rooms. Past the widest, the widths below are skipped
            // before their rooms are worked out (each would be empty: the same pairs are
            // found); random moves 1022796 and 1077553, three attempts each with a cruise of a
            // cycle or two, 20,360 → 19,992 and 20,213 → 19,844 Cortex-M4 instructions.
            let widest = room.widest();
            if widest < 2 {
                continue;
            }
            // No pair as wide as the move fits in it (a notch's window ends before phase V):
            // the widths below are cycles of the move, and so is one more. `None` also past
            // the widest (as if its room were worked out: empty).
            let limit = bounds.total.min(widest.saturating_add(1));
            let region = |w: u64| (w < limit).then(|| room.at(C::narrow(w)));
            // The widths whose spans land in the middle of their range: from spans of half
            // the move, refined twice (the range depends a little on the width).
            let refine = |width: u64| {
                let Some((_, _, range)) = region(width) else {
                    return width;
                };
                let range = widened(range);
                if range.0 > range.1 {
                    return width;
                }
                let middle = (range.0 / 2 + range.1 / 2).max(1);
                div(estimated, middle.saturating_mul(2).saturating_add(1)).max(1)
            };
            let guess = refine(refine(div(estimated, bounds.total.max(1)).max(1)));
            // And half and all of the first ramp, where short moves have room.
            let ramp = bounds.last_rise_start;
            // (Every width around the guess is at least 1; the ramp's, read from a slice, not
            // moved out of an array: fewer instructions a width on a Cortex-M4.)
            let around = guess.saturating_sub(1).max(1)..guess + WIDTH_TRIES;
            let ramp_widths = [ramp / 2, ramp];
            let widths = around.clone().chain(
                ramp_widths
                    .iter()
                    .copied()
                    .filter(move |&w| w > 0 && !around.contains(&w)),
            );
            // The widths around the guess are consecutive: one's wider pair is the next one's.
            let mut wider: Option<(u64, Region<C>)> = None;
            for width in widths {
                let known = match wider {
                    Some((w, known)) if w == width => Some(known),
                    _ => region(width),
                };
                let Some((first1, second1, narrow)) = known else {
                    continue;
                };
                let narrow = widened(narrow);
                // Every sum w·k₁ + (w + 1)·k₂ with both spans in the narrower pair's range lies
                // in [(2w + 1)·low, (2w + 1)·high]: outside, no q can help (a quick, exact
                // rejection before the wider pair's room or any division).
                let odd = (2 * width).saturating_add(1);
                if narrow.0 > narrow.1
                    || left > saturating_product(odd, narrow.1)
                    || reach < saturating_product(odd, narrow.0)
                {
                    continue;
                }
                let Some((first2, second2, wide)) = region(width + 1) else {
                    continue;
                };
                wider = Some((width + 1, (first2, second2, wide)));
                let wide = widened(wide);
                let (low, high) = (narrow.0.max(wide.0), narrow.1.min(wide.1));
                if low > high {
                    continue;
                }
                // w·k₁ + (w + 1)·k₂ with k₁, k₂ in [low, high] has a solution for every value
                // between these (k₁ moves in steps of w + 1, k₂ of w).
                let (w, l, h) = (width, low, high);
                // The same with both ranges.
                let (lowest, highest) = (saturating_product(odd, l), saturating_product(odd, h));
                if left > highest || reach < lowest {
                    continue;
                }
                let both_ends = saturating_product(w, w + 1);
                let least = lowest.saturating_add(both_ends);
                let most = highest.saturating_sub(both_ends);
                let q = if left < least && area > 0 {
                    div_ceil(least - left, area)
                } else {
                    0
                };
                let Some(target) = product(q, area).and_then(|t| t.checked_add(left)) else {
                    continue;
                };
                if q > available || target > most.max(left) || target < lowest || target > highest {
                    continue;
                }
                let Some((k1, k2)) = solve_spans(target, width, (low, high)) else {
                    continue;
                };
                // Both spans lie in [low, high], cycles of the move: they narrow exactly.
                let (Some(one), Some(two)) = (
                    place(first1, second1, C::narrow(width), C::narrow(k1)),
                    place(first2, second2, C::narrow(width + 1), C::narrow(k2)),
                ) else {
                    continue;
                };
                let (first2, second2) = (widened(first2), widened(second2));
                // Their notches may meet where the jerk has no unit to spare: then move the
                // wider pair by a cycle, within its room.
                let moved = |by: i64| {
                    let start = two.start.checked_add_signed(by)?;
                    let fits_first = (first2.0..=first2.1).contains(&start);
                    let fits_second = (second2.0..=second2.1).contains(&(start + k2));
                    (fits_first && fits_second).then_some(Notch { start, ..two })
                };
                if [Some(two), moved(-1), moved(1)]
                    .into_iter()
                    .flatten()
                    .any(|two| try_fit(&[one, two]))
                {
                    return Some(q);
                }
            }
        }
        None
    }
}

#[cfg(test)]
mod tests {
    use super::super::shape::Mix;
    use super::*;
    use proptest::prelude::*;

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(4_000))]

        /// What `Placement::fits` relies on to skip a pair's own part: its four impulses fall on
        /// four cycles, and its dip is one unit deep on its first and its last cycle — checked
        /// against the pair's velocity summed from its jerk, cycle by cycle.
        #[test]
        fn a_pair_is_one_unit_deep_at_both_ends(start in 0u64..50, width in 1u64..40, extra in 1u64..40) {
            let notch = Notch { start, width, span: width + extra };
            let cycles: Vec<u64> = notch.impulses().iter().map(|&(at, _)| at).collect();
            prop_assert!(cycles.windows(2).all(|pair| pair[0] < pair[1]));
            let (mut acceleration, mut velocity) = (0i64, 0i64);
            for n in 0..notch.last_dip() + 3 {
                acceleration += notch.impulses().iter().filter(|&&(at, _)| at == n).map(|&(_, j)| j).sum::<i64>();
                velocity += acceleration;
                prop_assert_eq!(notch.depth_at(n) as i64, -velocity, "cycle {}", n);
            }
            prop_assert_eq!(notch.depth_at(notch.start), 1);
            prop_assert_eq!(notch.depth_at(notch.last_dip()), 1);
        }

        /// What [`Room::widest`] skips is empty: past an edge's widest, its interval is empty
        /// (for any edges, in both widths of cycle).
        #[test]
        fn no_notch_fits_past_the_widest(
            low_floor in 0u64..300,
            low_base in 0u64..300,
            high_cap in 0u64..300,
            high_base in 0u64..300,
            past in 1u64..300,
        ) {
            let edges = Edges { low_floor, low_base, high_cap, high_base };
            let widest = edges.widest();
            prop_assume!(widest < u64::MAX);
            let (low, high) = edges.at(widest + past);
            prop_assert!(low > high, "width {} past {}: {:?}", widest + past, widest, (low, high));
            let narrow = Edges {
                low_floor: low_floor as u32,
                low_base: low_base as u32,
                high_cap: high_cap as u32,
                high_base: high_base as u32,
            };
            prop_assert_eq!(narrow.widest(), widest);
        }

        /// Any solution found solves the equation within the range; none found means none
        /// exists (brute force over the range).
        #[test]
        fn solve_spans_solves(left in 1u64..200_000, width in 1u64..200, low in 1u64..2_000, extent in 0u64..2_000) {
            let range = (low, low + extent);
            match solve_spans(left, width, range) {
                Some((k1, k2)) => {
                    prop_assert_eq!(width * k1 + (width + 1) * k2, left);
                    prop_assert!((low..=low + extent).contains(&k1) && (low..=low + extent).contains(&k2));
                }
                None => {
                    for k1 in low..=low + extent {
                        let Some(rest) = left.checked_sub(width * k1) else { break };
                        let w2 = width + 1;
                        let ok = rest % w2 == 0 && (low..=low + extent).contains(&(rest / w2));
                        prop_assert!(!ok, "missed k1 = {}", k1);
                    }
                }
            }
        }

        /// The search in 32-bit cycles (moves shorter than 2^31 cycles) places exactly the
        /// pairs the 64-bit one does, or fails where it fails.
        #[test]
        fn cycles_in_32_bits_place_the_same_pairs(
            a in 1u64..400,
            longer in 0u64..400,
            cruise in 0u64..800,
            counts in proptest::array::uniform4(0u64..4),
            early in proptest::array::uniform4(0u64..2),
            share in 0u64..1_000_000,
            (area, available) in (0u64..5_000, 0u64..4),
            with_unit in any::<bool>(),
        ) {
            prop_assume!(counts.iter().sum::<u64>() > 0 && a > 1);
            let b = a + longer;
            let c = a + b + cruise + 1;
            let mix = Mix {
                a,
                b,
                counts,
                acceleration: 0,
                velocity: 0,
            };
            let early = core::array::from_fn(|k| early[k].min(counts[k]));
            let main = mix.main_move(c, early);
            let bounds = main.bounds();
            // Remainders across what two pairs can take (< total²/2), more of them small:
            // the share squared, in millionths.
            let most = u128::from(bounds.total * bounds.total / 2);
            let share = u128::from(share);
            let left = u64::try_from(most * share * share / 1_000_000_000_000).unwrap_or(2).max(2);
            let remainder = Remainder {
                left,
                main: &main,
                bounds: &bounds,
                jerk_limit: 4,
                area,
                available,
                estimated: estimated(left, area, with_unit),
            };
            let (mut narrow, mut wide) = (Placement::default(), Placement::default());
            prop_assert_eq!(
                remainder.take_in::<u32, true>(&mut narrow),
                remainder.take_in::<u64, true>(&mut wide)
            );
            prop_assert_eq!(narrow, wide);
        }
    }
}
