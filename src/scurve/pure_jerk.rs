//! Moves where only the jerk binds: a few dozen cycles with a jerk of a few raw units, the
//! acceleration and velocity limits far above anything the move reaches (most often the last
//! fraction of a count left after a stop).
//!
//! There the continuous optimum is `4·∛(D/2J)` cycles, and the search's shapes can leave it
//! several cycles behind: they aim at the acceleration and velocity limits, and place notch pairs
//! only where the acceleration's sign lets O(1) inequalities keep those limits, which a move of
//! a few dozen cycles and one unit of jerk rarely has room for (101 raw units with a jerk of 1
//! raw unit: 18 cycles where 16 do). With the limits far away the pairs may go wherever the jerk
//! has room, so this module tries them there, on every cycle count from the optimum's floor up,
//! and checks each candidate exactly before it keeps one.
//!
//! A candidate is `J − e` units of `tb(a, b, c)` and `e` of `tb(a, b, c − 1)` (their cruise one
//! cycle shorter, `a·b` less each), less at most two notch pairs of widths up to [`WIDEST`]:
//! `J·a·b·c − e·a·b − w₁·k₁ − w₂·k₂` is the distance. A pair's four impulses need room in the
//! jerk where they fall — a lowering impulse where the main move's jerk is above `−J`, a raising
//! one where it is below `J` — and the cycles with room are a few intervals (the phases), so for
//! each choice of intervals the spans that fit form an interval too ([`Fit`]), found in O(1).
//! A candidate is then checked exactly by a fixed number of comparisons ([`Profile::fits`]: the
//! jerk on the cycles of their impulses, the velocity on the few slow cycles at the move's ends
//! that a dip could take below zero; the class's limits leave the acceleration and velocity
//! limits out of reach); the schedule is built once, for the plan found.
//!
//! Where a cycle count's candidates all fail, its main moves whose rest is `w·k` for a width
//! `w` from 4 to [`WIDEST_ALONE`] are tried with that one wide pair ([`Tries::wide_pairs`]):
//! a rest beyond two narrow pairs' reach, or in a gap of their spans, may be a single wide
//! pair's (119,285 raw units with a jerk of 7 from a fractional position: none of four cycle
//! counts had a main move narrow pairs finish, one of 83 cycles leaves `259 = 7·37`).
//!
//! The search calls it after its shapes, where their plan is more than three cycles over the
//! optimum or missing ([`improve`]), or before them where the jerk is at most 15 raw units
//! ([`FIRST_JERK`], [`first`]: the pass with the pairs' impulses apart — no cycle with two of
//! one sign, unless the main move has room for two wherever it has room for one — and for the
//! shortest moves the other as well; [`improve`] makes the other if the search's plan then
//! needs it). Where both passes run, each main move is tried with both, its room found once.
//!
//! Its cost is bounded: at most [`COUNTS`] cycle counts, for each a few main moves per first ramp
//! (the second ramps whose distance is just above the move's), at most [`MAX_CHECKS`] candidates
//! checked per pass and two passes, and at most [`MAX_WIDE`] main moves a count and
//! [`MAX_WIDE_CHECKS`] candidates in all with a wide pair.

use super::products::product;
use super::remainder::{self, Notch, Placement};
use super::roots::cube_root;
use super::schedule::{Limits64, Schedule};
use super::shape::{Group, MainMove};
use crate::bisect::last_true;
use crate::division::{div, div_ceil};
use num_traits::PrimInt;

/// Moves whose continuous optimum is under this many cycles are tried here: the cost of a try
/// grows with the square of the length, and longer moves have room for the search's own pairs.
/// 260 takes every distance under 2^19 raw units with a jerk of one raw unit (`∛(32·2^19) =
/// 256` cycles): at 128, moves of over 130 cycles with that jerk were planned up to 4.71
/// cycles over the optimum (2 of 300,000 random ones under 2^17 raw units, a case the property
/// tests found, and the seeded scan of `tests/scurve.rs`), and at 162 moves of 171 to 255 cycles
/// up to 3.41 (5 of 200,000 from 2^17 to 2^19 raw units); at 260 none (and none of 200,000 from 2^19 to 2^22, where the
/// search's own pairs have room: worst +2.13). Such a move costs less here than the search
/// spends failing on it (Cortex-M4: 51,000–64,000 instructions in all for the six moves of
/// `tests/scurve.rs`, most of it the search's failed attempts before this module, against up
/// to 146,000 without it); the bound costs no stack ([`Profile::fits`] keeps no table of the
/// move's cycles).
const LONGEST: u64 = 260;

/// Cycle counts tried: the optimum's floor and the next three (the bound is the optimum + 3).
const COUNTS: u64 = 4;

/// The widest notch pair tried: with widths up to 3, a survey of 3,000,000 random moves of this
/// kind (a jerk of 1 to 15 raw units, under 2^17 raw units) found none over the bound (README).
const WIDEST: u64 = 3;

/// A main move is tried only if its rest is under this fraction `(p, q)` = p/q of the pairs'
/// reach (not merely within it): such a rest needs the pairs at nearly their widest spans,
/// where the room is scarcest, and a try costs 3,500–5,000 Cortex-M4 instructions. Measured
/// over the `pure_jerk` tries of moves of 40 cycles or more in four samples of moves from
/// fractional positions: a rest of at least 0.8 of the reach fitted in 47 of 177 tries, under it
/// in 50–90 % (by tenths of the reach and jerks of 1 to 3 raw units). Over
/// those samples (seeds 17, 99, 5, 1234) moves over SPEC §16's 20,000 went 9, 12, 13, 13 → 3,
/// 8, 12, 9, the worst of the first 30,327 → 23,970 (0.7: 3, 8, 12, 9 with more cycles; 0.86:
/// 4, 8, 12, 9; 0.9: 5, 9, 13, 10). Of `tools/ab_plans.sh`'s 200,000 moves 322 plans differ, 165
/// a cycle or so longer (+168 cycles in all), every one still within the bound (a plan here is
/// at most `⌊∛(32D/J)⌋ + 3` cycles by construction).
const NEAR_REACH: (u64, u64) = (4, 5);

/// Candidates checked per pass at most (two passes): the cost stays bounded whatever the move.
const MAX_CHECKS: u32 = 64;

/// The jerk (raw units) up to which a move of this module's class is planned here before the
/// search ([`first`]): with a few units of jerk the search's shapes mostly leave remainders
/// that its pairs, placed where O(1) inequalities keep the limits, cannot take — attempt after
/// attempt, each a few thousand Cortex-M4 instructions — where pairs anywhere the jerk has
/// room can (README, "Planning from fractional positions"). 15, the most of the moves a stop
/// leaves in that sample: with more units the rest a main move leaves is up to a unit's area
/// (`a·b`), which the pairs' reach (`≈ 6·(N − 2a)`) seldom covers. It was 3 until main moves
/// whose jerk has room for two impulses of a sign wherever it has for one ([`Profile`]'s
/// `doubles`) stopped keeping their pairs' impulses apart and their fits came in closed form
/// ([`Fits::fill`]); 3 → 15 then, on the Cortex-M4 probe over five samples of moves from
/// fractional positions (seeds 17, 99, 5, 1234: 3,000 and 5,000 each; 2026: 20,000): over
/// SPEC §16's 20,000 0, 0, 0, 0, 3 → 0, 0, 0, 0, 1, worst 18,207 / 18,008 / 18,201 / 17,875 /
/// 24,663 → 16,366 / 17,526 / 16,179 / 16,403 / 20,983, p99 16,748 → 12,131 (CI's sample),
/// sums −12 to −13 %; plans (`tools/ab_plans.sh`) 2,210 of 200,000 shorter, 1,018 longer
/// (−1,379 cycles, all within `⌊∛(32·D/J)⌋ + 3` by construction); random moves unchanged
/// (worst 19,985 over the first 100,000, a search move of a jerk of 1 raw unit). (Once 3: up
/// to 4 had taken one tiny move, both of whose passes here failed before the search, 39,523
/// → 63,508, before such moves were tabled, [`super::tiny`].)
const FIRST_JERK: u64 = 15;

/// Moves whose continuous optimum is under this many cycles (its floor) and whose jerk is at
/// most [`FIRST_JERK`] are tried with both passes here, before the search ([`first`]), each
/// main move's room found once for both: the search's shapes seldom have room for their pairs
/// in so few cycles, and a plan missed by the first pass was then looked for again after them,
/// its main moves' room found a second time. Measured on the Cortex-M4 probe over four samples
/// of moves from fractional positions (seeds 17, 99, 5, 1234), moves over SPEC §16's 20,000:
/// 57, 107, 119, 87 → 53, 98, 115, 86, the worst 39,523, 47,662, 42,544, 34,038 → 39,517,
/// 41,611, 42,531, 34,032 (10: 55, 99, 116; 14: 53, 97, 116; 16: 54, 96, 114 but 44,161 at
/// worst; every move, both passes first: 60, 102, 128).
const SHORTEST: u64 = 12;

/// Plans a move of this module's class with a jerk of at most [`FIRST_JERK`] here, before the
/// search, with the pairs' impulses apart ([`first_apart`]) — and, for a move under [`SHORTEST`]
/// cycles, also at the ends of their ranges ([`improve`] tries those for the others if the
/// search's plan is then too long): `false`, and `out` unusable, if no plan was found or the
/// move is not one of them.
pub(super) fn first(distance: u64, direction: i64, limits: Limits64, out: &mut Schedule) -> bool {
    // The jerk first: most moves leave here, before the class test's cube root.
    limits.jerk <= FIRST_JERK
        && floor_if_planned_here(distance, limits).is_some_and(|floor| {
            let passes = first_passes(limits.jerk, floor);
            plan(
                distance,
                direction,
                limits,
                floor.max(3)..=floor + COUNTS - 1,
                passes,
                out,
            )
        })
}

/// The passes [`first`] makes for a move of this module's class with `jerk` and the optimum's
/// floor `floor` (`true`: the pairs' impulses apart, [`first_apart`]; `false`: at the ends of
/// their ranges), none above [`FIRST_JERK`]: [`improve`] makes the others.
fn first_passes(jerk: u64, floor: u64) -> &'static [bool] {
    if jerk > FIRST_JERK {
        &[]
    } else if floor < SHORTEST {
        &[true, false]
    } else {
        &[true]
    }
}

/// Replaces `out` (the search's plan, if `planned`) with a faster plan if the move is one where
/// only the jerk binds and the search's plan is more than three cycles over the continuous
/// optimum, or missing, and a faster one is found (with the passes [`first`] did not make,
/// [`first_passes`]). Returns whether `out` holds a plan.
pub(super) fn improve(
    distance: u64,
    direction: i64,
    limits: Limits64,
    planned: bool,
    out: &mut Schedule,
) -> bool {
    // By multiplications alone: most moves leave here.
    let Some(scaled) = scaled_distance(distance, limits.jerk) else {
        return planned;
    };
    if planned && within_bound(out.plan.total, scaled, limits.jerk) {
        return true;
    }
    let Some(floor) = optimum_floor(scaled, distance, limits) else {
        return planned;
    };
    // Only plans faster than the one there is (over `floor + 3` cycles, see above).
    let longest = if planned {
        out.plan.total - 1
    } else {
        u64::MAX
    };
    let last = longest.min(floor + COUNTS - 1);
    // With the pairs' impulses apart (each candidate then mostly fits), then with
    // them at the ends of their ranges, where they may meet: those `first` did not try. `out`
    // is written only with a plan found.
    let passes: &[bool] = match first_passes(limits.jerk, floor) {
        [] => &[true, false],
        [true] => &[false],
        _ => return planned,
    };
    plan(
        distance,
        direction,
        limits,
        floor.max(3)..=last,
        passes,
        out,
    ) || planned
}

/// Whether a plan of `total` cycles is within three of the continuous optimum of a move where
/// only the jerk binds, `scaled` = `32·D` ([`scaled_distance`]), by multiplications (no cube
/// root): `total ≤ ⌊∛(32·D/J)⌋ + 3`, and the optimum is at least that floor (the limits can
/// only lengthen it), exactly when `(total − 3)³·J ≤ 32·D`.
#[inline]
fn within_bound(total: u64, scaled: u64, jerk: u64) -> bool {
    let least = total.saturating_sub(3);
    product(least, least)
        .and_then(|square| product(square, least))
        .and_then(|cube| product(cube, jerk))
        .is_some_and(|needed| needed <= scaled)
}

/// `⌊∛(32·D/J)⌋` ([`optimum_floor`]) if the move is one of this module's class.
pub(super) fn floor_if_planned_here(distance: u64, limits: Limits64) -> Option<u64> {
    optimum_floor(scaled_distance(distance, limits.jerk)?, distance, limits)
}

/// Whether a move of `distance` raw units with `jerk` may be one where only the jerk binds of
/// under [`LONGEST`] cycles (`32·D < LONGEST³·J`): the moves [`first`], `volumes` and `tiny`
/// plan are all such, and most moves are not — one product and a comparison
/// ([`scaled_distance`]), where each of the three tested its own class first. With both, the
/// costliest of the first 100,000 random moves (206,948 cycles with a jerk of one raw unit,
/// planned by the search) went 20,004 → 19,982 Cortex-M4 instructions: the tiny table's test
/// had taken it 11 over its 19,993.
pub(super) fn is_short(distance: u64, jerk: u64) -> bool {
    scaled_distance(distance, jerk).is_some()
}

/// `32·D`, if below `LONGEST³·J`: the continuous optimum when only the jerk binds,
/// `4·∛(D/2J) = ∛(32·D/J)` cycles, is then under [`LONGEST`].
fn scaled_distance(distance: u64, jerk: u64) -> Option<u64> {
    // `32·D < LONGEST³·J` exactly when `D < J·LONGEST³/32` (`LONGEST³` is a multiple of 32):
    // one product to test, and `32·D < 2^64` after it (`J < 2^32`, so `D < 2^52`).
    const _: () = assert!(LONGEST * LONGEST * LONGEST % 32 == 0);
    let most = product(jerk, LONGEST * LONGEST * LONGEST / 32)?;
    (distance < most).then(|| distance * 32)
}

/// `⌊4·∛(D/2J)⌋ = ⌊∛(32·D/J)⌋` from `scaled` = [`scaled_distance`], the floor of the continuous
/// optimum when only the jerk binds, if the move is one this module plans: every candidate's
/// peaks (at most `J·⌊N/4⌋ + 2` acceleration and `J·⌊N²/16⌋` velocity for `N` cycles, as
/// `a ≤ N/4` and `a + b ≤ N/2`) within the limits.
fn optimum_floor(scaled: u64, distance: u64, limits: Limits64) -> Option<u64> {
    let jerk = limits.jerk;
    // First, before the cube root, a necessary condition by multiplications: the peak
    // acceleration required below exceeds `J·∛(32·D/J)/4 = ∛(D·J²/2)`, so `2·A³ > D·J²` (most
    // moves whose plan is long for their distance leave here: they reach the acceleration limit).
    let acceleration = limits.acceleration;
    if let Some(cube) = product(acceleration, acceleration)
        .and_then(|square| product(square, acceleration))
        .and_then(|cube| cube.checked_mul(2))
    {
        let needed = product(distance, jerk).and_then(|d| product(d, jerk));
        if needed.is_none_or(|needed| needed >= cube) {
            return None;
        }
    } else {
        // A ≥ 2^21: in 128 bits (A < 2^32, D < 2^64, J < 2^32), so that a large jerk that
        // reaches even a large acceleration leaves here too, not after the cube root (a move
        // of one count with a jerk of 0.04 counts/cycle³ spent 174 Cortex-M4 instructions
        // more there once [`super::volumes`] tested the class first).
        let cube = 2 * u128::from(acceleration).pow(3);
        let needed = u128::from(distance) * u128::from(jerk) * u128::from(jerk);
        if needed >= cube {
            return None;
        }
    }
    let floor = cube_root(div(scaled, jerk));
    let cycles = floor + COUNTS;
    let peak_acceleration = product(jerk, cycles / 4)?.checked_add(2)?;
    let peak_velocity = product(jerk, cycles * cycles / 16)?;
    (peak_acceleration <= limits.acceleration && peak_velocity <= limits.velocity).then_some(floor)
}

/// The first plan found, fewest cycles first, with a cycle count in `counts`, into `out`: for
/// each main move, its pairs placed as each of `passes` has them (`true`: their impulses
/// apart, [`first_apart`]; `false`: at the ends of their ranges), each pass with its own
/// [`MAX_CHECKS`]. (The passes once ran one after the other over every main move: a main move
/// both tried had its room found twice, and a plan the first pass found on a later cycle count
/// was kept over one the second would have found on an earlier one.)
fn plan(
    distance: u64,
    direction: i64,
    limits: Limits64,
    counts: core::ops::RangeInclusive<u64>,
    passes: &[bool],
    out: &mut Schedule,
) -> bool {
    // In 32 bits where every product of the search for main moves fits (`J·a·b·c ≤ J·N³/27`,
    // `D < 2^32`): a 64-bit product or quotient is several Cortex-M4 instructions, and this
    // search is a large part of a plan's cost where its main moves fail (95,747 raw units with a
    // jerk of 3, four cycle counts of nine first ramps each, one main move tried: 20,983 →
    // 19,709 instructions in all, the last of a sample of 20,000 moves from fractional positions
    // over SPEC §16's 20,000). The 64-bit search is for the jerks of hundreds of raw units or
    // more that [`improve`] plans.
    let most = *counts.end();
    let narrow = u32::try_from(distance).is_ok()
        && most
            .checked_mul(most * most)
            .and_then(|cube| product(cube, limits.jerk))
            .is_some_and(|most_product| most_product <= u64::from(u32::MAX));
    let mut tries = Tries {
        distance,
        direction,
        limits,
        passes,
        checks: [0; 2],
        profile: Profile::new(limits),
        fits: Fits::EMPTY,
        wide: [(0, 0, 0, 0, 0); MAX_WIDE],
        wides: 0,
        wide_checks: 0,
        far: [(0, 0, 0, 0, 0); MAX_FAR],
        fars: 0,
        out,
    };
    let planned = if narrow {
        plan_in::<u32>(&mut tries, counts)
    } else {
        plan_in::<u64>(&mut tries, counts)
    };
    planned || tries.far_rests()
}

/// [`plan`] with the search for main moves in `W`: each main move whose rest the pairs may take
/// is handed to [`Tries::main_move`] (one function for both widths: most main moves of a first
/// ramp are passed by here, and this search is the part that takes the width).
fn plan_in<W: Word>(tries: &mut Tries, counts: core::ops::RangeInclusive<u64>) -> bool {
    let (distance, jerk) = (tries.distance, tries.limits.jerk);
    let (distance_w, jerk_w) = (W::of(distance), W::of(jerk));
    let (one, two) = (W::one(), W::of(2));
    for total in counts {
        tries.wides = 0;
        // Every first ramp from the first that covers the distance on: the later ones cover more.
        for a in first_ramp(distance, jerk, total)..=total / 4 {
            let reach = reach(total, a);
            let (total_w, a_w, reach_w) = (W::of(total), W::of(a), W::of(reach));
            // a·b·(s − b)·J ≥ D with s = N − a: b(s − b) ≥ ⌈D/(J·a)⌉ from the root's floor up.
            let s = total_w - a_w;
            let need = distance_w.quotient_up(jerk_w * a_w);
            // `4·need ≤ s² + 4` for the first ramps [`first_ramp`] lets through
            // (`J·a·(s/2)² ≥ D`); s < 2^10 (the moves here are under `LONGEST + COUNTS`
            // cycles), so the square is under 2^20.
            let Some(square) = (s * s).checked_sub(&(W::of(4) * need)) else {
                continue;
            };
            let mut b_w = ((s - square.root()) / two).max(a_w);
            while b_w * (s - b_w) < need {
                b_w = b_w + one;
            }
            // c = N − a − b ≥ a + b.
            while two * (a_w + b_w) <= total_w {
                let c_w = total_w - a_w - b_w;
                let (full, area) = (jerk_w * a_w * b_w * c_w, a_w * b_w);
                // `full − D − (J − 1)·a·b` grows with b (a·b·(J·(c − 1) + 1) does while
                // 2b < N − a), and no later b leaves less than it.
                if full - distance_w > (jerk_w - one) * area + reach_w {
                    break;
                }
                // Units whose cruise ends a cycle early take whole areas; e ≤ J − 1 keeps one
                // unit whole (and only a move with a cruise has a cycle to give).
                let early = if c_w > a_w + b_w {
                    (full - distance_w).quotient(area).min(jerk_w - one)
                } else {
                    W::zero()
                };
                let rest = (full - early * area - distance_w).wide();
                let (b, c, early) = (b_w.wide(), c_w.wide(), early.wide());
                if let Some(planned) = tries.main_move(total, (a, b, c), early, (rest, reach)) {
                    return planned;
                }
                b_w = b_w + one;
            }
        }
        if let Some(planned) = tries.wide_pairs(total) {
            return planned;
        }
    }
    false
}

/// What [`plan`] carries from one main move tried to the next: the move, where its plan goes,
/// the candidates checked so far, and one profile and one table of fits, rewritten for each
/// main move tried (a few hundred bytes each, which a fresh pair per main move cleared and
/// copied: about an instruction a byte on a Cortex-M4).
struct Tries<'s> {
    distance: u64,
    direction: i64,
    limits: Limits64,
    passes: &'s [bool],
    checks: [u32; 2],
    profile: Profile,
    fits: Fits,
    /// The present cycle count's main moves, `(a, b, c, e, rest)`, whose rest one wide pair
    /// may take ([`wide_may_take`]), the first [`MAX_WIDE`]: tried once the count's other
    /// candidates have failed ([`Tries::wide_pairs`]).
    wide: [(u64, u64, u64, u64, u64); MAX_WIDE],
    wides: usize,
    /// Wide pairs checked so far (at most [`MAX_WIDE_CHECKS`]).
    wide_checks: u32,
    /// The first [`MAX_FAR`] main moves, `(a, b, c, e, rest)`, whose rest is beyond what
    /// narrow pairs are tried for ([`NEAR_REACH`]): tried with the search's pairs once every
    /// cycle count has failed ([`Tries::far_rests`]).
    far: [(u64, u64, u64, u64, u64); MAX_FAR],
    fars: usize,
    out: &'s mut Schedule,
}

impl Tries<'_> {
    /// Tries `J − e` units of `tb(a, b, c)` and `e` of `tb(a, b, c − 1)`, `total` cycles, `rest`
    /// over the distance, the pairs' `reach` ([`reach`]): `Some(planned)` where the search ends
    /// (a plan built into `out`, or the candidates to check used up), `None` to go on.
    fn main_move(
        &mut self,
        total: u64,
        (a, b, c): (u64, u64, u64),
        early: u64,
        (rest, reach): (u64, u64),
    ) -> Option<bool> {
        // A rest near the reach needs pairs at their widest spans, where the room is
        // scarcest ([`NEAR_REACH`]); a small rest, pairs of small spans, which units all
        // alike may have no room for ([`small_rest_may_fit`]); a rest between the bands of
        // spans the main move has room for, none ([`bands_may_take`]).
        let near = NEAR_REACH.1 * rest < NEAR_REACH.0 * reach;
        if !near && self.fars < MAX_FAR {
            self.far[self.fars] = (a, b, c, early, rest);
            self.fars += 1;
        }
        if near
            && (early > 0 || small_rest_may_fit(rest, a, b, c))
            && bands_may_take(rest, (a, b, c), early > 0)
        {
            let groups = self.groups((a, b, c), early);
            self.profile.set(&groups, total);
            if rest > 0 {
                self.fits.fill(&self.profile);
            }
            let placement = self.passes.iter().find_map(|&apart| {
                let checks = &mut self.checks[usize::from(apart)];
                (*checks < MAX_CHECKS)
                    .then(|| self.profile.take(rest, apart, checks, &self.fits))
                    .flatten()
            });
            if let Some(placement) = placement {
                return Some(self.build(&groups, &placement));
            }
            if self
                .passes
                .iter()
                .all(|&apart| self.checks[usize::from(apart)] >= MAX_CHECKS)
            {
                return Some(false);
            }
        }
        // Not with one unit of jerk ([`WIDEST_ALONE`]).
        if self.limits.jerk >= 2
            && rest > 0
            && a >= 2
            && self.wides < MAX_WIDE
            && wide_may_take(rest, total, a, b)
        {
            self.wide[self.wides] = (a, b, c, early, rest);
            self.wides += 1;
        }
        None
    }

    /// Tries one wide pair ([`wide_may_take`]) on the main moves of `total` cycles kept for it,
    /// in their order: `Some(planned)` where a plan was built into `out`, `None` to go on.
    ///
    /// A single pair of width `w` and span `k > w` dips the velocity by
    /// `min(m + 1, w, w + k − 1 − m)` on its `m`-th cycle, from its start `s`: at most `n + 1`
    /// on cycle `n = s + m`, and at most `total − 2 − n` (its last impulse, on `s + k + w`, is
    /// before the move's last cycle), and at most `w ≤ a·b`. The main move is at least that fast
    /// there ([`Profile::set_pieces`]: `min(n + 1, total − 2 − n, a·b)`), so the velocity stays
    /// at least zero wherever the pair sits, as [`Profile::fits`] assumes on its fast cycles
    /// (where it assumes dips of at most [`SLOW`]); the jerk is checked as for any pair.
    #[inline(never)]
    fn wide_pairs(&mut self, total: u64) -> Option<bool> {
        for i in 0..self.wides {
            let (a, b, c, early, rest) = self.wide[i];
            // Cycles in 32 bits, as [`Profile::set`] has them; the rest is at most
            // `max(a·b, reach) < 2^15` (the moves here are under 2^9 cycles): unsigned 32-bit
            // divisions, one instruction each on a Cortex-M4.
            let shape = (a as i32, b as i32, c as i32, i32::from(early > 0));
            let (rest, most) = (rest as u32, (a * b).min(WIDEST_ALONE as u64) as u32);
            // Spans `k < total − 2a + w` ([`reach`]).
            let longest = (total - 2 * a) as u32;
            let mut set = false;
            let mut width = WIDEST as u32 + 1;
            while width <= most {
                let (w, k) = (width, rest / width);
                width += 1;
                if k * w != rest || k <= w || k >= longest + w {
                    continue;
                }
                let (w, k) = (w as i32, k as i32);
                self.fits.fill_closed_width(shape, total as i32, w, 0);
                for &fit in &self.fits.fits[0][..self.fits.lens[0]] {
                    let (lo, hi) = fit.spans();
                    if k < lo || k > hi {
                        continue;
                    }
                    let groups = self.groups((a, b, c), early);
                    if !set {
                        self.profile.set(&groups, total);
                        set = true;
                    }
                    let (first, last) = fit.range(k);
                    for start in [first, last] {
                        if self.wide_checks >= MAX_WIDE_CHECKS {
                            return None;
                        }
                        self.wide_checks += 1;
                        self.profile.ready();
                        if self.profile.fits(&[(start, w, k)]) {
                            return Some(self.build(&groups, &placement(&[(start, w, k)])));
                        }
                    }
                }
            }
        }
        None
    }

    /// Tries the main moves kept for it ([`Self::far`]) with the search's notch pairs
    /// ([`remainder::take_exactly`]: one pair, or two of consecutive widths `w` and `w + 1` of
    /// any width, placed where [`Placement::fits`]' O(1) inequalities keep the limits), those
    /// whose rest they likely take first ([`far_rest_likely`]), the others in their order:
    /// whether a plan was built into `out`. [`plan`] calls it once every cycle count's
    /// candidates have failed, so no plan found before changes.
    ///
    /// Narrow pairs are tried for rests under [`NEAR_REACH`] of their reach; a rest beyond it
    /// needs wider ones. Where every cycle count's candidates failed, the move went to the
    /// search, which found plans with pairs of widths up to 26 — after this module's own
    /// attempts, 10,000 to 20,000 Cortex-M4 instructions more: over a survey of 1,000,000 moves
    /// from fractional positions (seeds 121–140), 5 moves, 4 of them over SPEC §16's 20,000
    /// (up to 29,518). The search's pairs take a kept main move's rest in each of them, the
    /// first or the second tried, in as many cycles as the search's plan or fewer (120,075 raw
    /// units with a jerk of 7: 82, where the search's took 84).
    #[inline(never)]
    fn far_rests(&mut self) -> bool {
        // Those whose rest is likely taken first ([`far_rest_likely`]), then the others.
        let likely = (0..self.fars).fold(0u8, |likely, i| {
            let (a, b, c, _, rest) = self.far[i];
            let total = a + b + c;
            likely | u8::from(far_rest_likely(rest, total, reach(total, a))) << i
        });
        for order in [likely, !likely] {
            for i in (0..self.fars).filter(|&i| order >> i & 1 != 0) {
                let (a, b, c, early, rest) = self.far[i];
                let groups = self.groups((a, b, c), early);
                let main = MainMove::of_groups(&groups);
                let bounds = main.bounds();
                let mut placement = Placement::default();
                // No units given back: the main move is the one the rest is of.
                if remainder::take_exactly(rest, &main, &bounds, &mut placement, self.limits.jerk) {
                    return self.build_main(&main, &placement, (a, b));
                }
            }
        }
        false
    }

    /// `J − e` units of `tb(a, b, c)` and `e` of `tb(a, b, c − 1)`.
    fn groups(&self, (a, b, c): (u64, u64, u64), early: u64) -> [Group; 2] {
        [
            Group {
                count: self.limits.jerk - early,
                a,
                b,
                c,
            },
            Group {
                count: early,
                a,
                b,
                c: c - 1,
            },
        ]
    }

    /// Builds the plan of `groups` less `placement` into `out` (whether it was built).
    fn build(&mut self, groups: &[Group; 2], placement: &Placement) -> bool {
        // The main move only for the plan found (most candidates fail): a [`MainMove`] is a
        // few hundred bytes to clear and fill.
        self.build_main(
            &MainMove::of_groups(groups),
            placement,
            (groups[0].a, groups[0].b),
        )
    }

    /// Builds the plan of `main`, whose units' ramps are `(a, b)`, less `placement` into `out`
    /// (whether it was built).
    fn build_main(&mut self, main: &MainMove, placement: &Placement, (a, b): (u64, u64)) -> bool {
        let built = self.out.build(main, placement, self.direction, (a, b));
        // Checked by `Profile::fits` (the search's pairs by `Placement::fits`); the tests run
        // with debug assertions, and every plan made here is replayed as well.
        debug_assert!(
            self.out.lands(self.direction, self.limits, self.distance),
            "a plan that breaks a limit or misses the distance: {:?}",
            (main, placement, self.distance, self.limits)
        );
        built
    }
}

/// The widest single notch pair tried where pairs of widths up to [`WIDEST`] cannot take a
/// main move's rest ([`Tries::wide_pairs`]), with a jerk of 2 raw units or more. Before it,
/// moves whose every main move left a rest beyond those pairs' reach or between their spans
/// went to the search, which planned them at 18,000–23,000 Cortex-M4 instructions; the widths
/// that took them, found by hand over those moves, were 7 to 11. On the probe, over a survey of
/// 500,000 moves from fractional positions (seeds 101–110, 50,000 each): over SPEC §16's
/// 20,000 6 → 3 (119,285 raw units with a jerk of 7: 22,821 → 11,299; 75,614 / 6: 21,814 →
/// 6,637), over 18,000 35 → 21, sums +0.23 %; `tools/ab_plans.sh`: 1,764 of 200,000 plans
/// differ, 1,762 shorter, none longer (−1,800 cycles). The three left over have a jerk of one
/// raw unit. With one unit the wide pairs seldom fit (no early units: the rest is the main
/// move's alone, and its spans fall between the fits'), and where they failed they cost up to
/// 2,100 more (27,445 raw units: 18,797 → 20,926; 129,425: 19,866 → 21,664, seed 7777),
/// where the moves they planned were under 20,000 already (79,403: 19,057 → 12,160): so not
/// with one unit. (Tried last, after every cycle count's narrow pairs, they cost the moves that
/// need them 2,000 to 7,000 more and planned fewer: 15,095 / J 1 12,386 → 19,833.)
const WIDEST_ALONE: i32 = 12;

/// Main moves kept for the search's pairs ([`Tries::far_rests`]): the cost of a move whose
/// every candidate fails stays bounded (a try that fails is 1,500 to 4,000 Cortex-M4
/// instructions: the main move and its bounds written, then `remainder::take`'s placements).
const MAX_FAR: usize = 4;

/// Whether the search's pairs likely take `rest` off a main move of `total` cycles whose narrow
/// pairs' [`reach`] is `reach`: a rest at least nine tenths of that reach (from 0.8 to 0.9 of
/// it they took half) and under a third of `total²` (two pairs take less than `total²/2`, and
/// from about 0.35 of it on seldom fit). Of the 4,116 main moves kept over CI's sample of moves
/// from fractional positions and the 20,000 seeded 2026, the pairs took 2,815 of the 2,974
/// likely ones and 410 of the 1,142 others.
fn far_rest_likely(rest: u64, total: u64, reach: u64) -> bool {
    10 * rest >= 9 * reach && 3 * rest < total * total
}

/// Main moves kept per cycle count for a wide pair ([`Tries::wide_pairs`]): the cost of a count
/// whose wide pairs fail stays bounded (each main move costs its fits of each width that
/// divides its rest, about 100 Cortex-M4 instructions a width).
const MAX_WIDE: usize = 4;

/// Candidates with a wide pair checked per plan at most (each about 600 Cortex-M4 instructions
/// for the main move's pieces and the check).
const MAX_WIDE_CHECKS: u32 = 8;

/// Whether one notch pair wider than [`WIDEST`] may take `rest` off a main move of `total`
/// cycles whose ramps are `a` and `b`: `rest = w·k` with `k > w`, the span within the reach
/// of [`reach`] (`k ≤ total − 2a − 1 + w`), and `w ≤ a·b` (see [`Tries::wide_pairs`]).
fn wide_may_take(rest: u64, total: u64, a: u64, b: u64) -> bool {
    // In 32 bits: the rest is at most `max(a·b, reach) < 2^15` and `total < 2^9` (see
    // [`plan`]); a 64-bit division is a library call on a Cortex-M4, a 32-bit one an
    // instruction. (The same test as [`Tries::wide_pairs`]' for each width: a function both
    // call measured up to +1,000 Cortex-M4 instructions on moves from fractional positions,
    // through `main_move`'s code.)
    let (rest, longest, area) = (rest as u32, (total - 2 * a) as u32, (a * b) as u32);
    (WIDEST as u32 + 1..=WIDEST_ALONE as u32).any(|w| {
        let k = rest / w;
        k * w == rest && k > w && k < longest + w && w <= area
    })
}

/// The integers [`plan_in`] searches for main moves in: `u32` where its products fit
/// ([`plan`]), else `u64`.
trait Word: PrimInt {
    /// `value`, which the caller knows fits.
    fn of(value: u64) -> Self;
    /// As `u64`.
    fn wide(self) -> u64;
    /// `⌊√self⌋` of a value under 2^32.
    fn root(self) -> Self;
    /// `⌊self / divisor⌋`.
    fn quotient(self, divisor: Self) -> Self;
    /// `⌈self / divisor⌉`.
    fn quotient_up(self, divisor: Self) -> Self;
}

impl Word for u32 {
    fn of(value: u64) -> Self {
        value as u32
    }
    fn wide(self) -> u64 {
        u64::from(self)
    }
    fn root(self) -> Self {
        self.isqrt()
    }
    fn quotient(self, divisor: Self) -> Self {
        self / divisor
    }
    fn quotient_up(self, divisor: Self) -> Self {
        self.div_ceil(divisor)
    }
}

impl Word for u64 {
    fn of(value: u64) -> Self {
        value
    }
    fn wide(self) -> u64 {
        self
    }
    fn root(self) -> Self {
        // The library's 32-bit root, a fraction of the 64-bit one's cost on a 32-bit core.
        u64::from(u32::try_from(self).map_or(u32::MAX, u32::isqrt))
    }
    // The crate's divisions, which take the 32-bit instruction where the operands fit.
    fn quotient(self, divisor: Self) -> Self {
        div(self, divisor)
    }
    fn quotient_up(self, divisor: Self) -> Self {
        div_ceil(self, divisor)
    }
}

/// What two notch pairs can take at most off a main move of `total` cycles whose ramps are `a`
/// cycles (with widths up to [`WIDEST`]): each `w·k` with a span `k ≤ total − 2a − 1 + w`. Both
/// raising impulses of a pair, on `s + w` and `s + k`, need room, which is on `[a, c + b)`
/// alone: before it every unit's jerk is +1 (the two groups share their ramps), from it on +1
/// again (or, on the last cycle only, where a raise has no cycle left for the lowering impulse
/// after it, all but the early units'). So `s ≥ a − w`, `s + k < c + b`, and
/// `c + b − a = total − 2a` for every `b`. (The span bounded by `total` alone let through main
/// moves no pairs can finish: about half of [`Profile::set`]'s and [`Fits::fill`]'s work, a
/// thousand Cortex-M4 instructions or more each.)
fn reach(total: u64, a: u64) -> u64 {
    2 * WIDEST * (total - 2 * a - 1 + WIDEST)
}

/// Whether notch pairs may take `rest` off `J` units of `tb(a, b, c)` (all alike, no early
/// units): `false` only where they surely cannot, so that the main move is not tried — its
/// room found and its fits filled for nothing (161 of 748 failed tries over four samples of
/// moves from fractional positions, about 2,500 Cortex-M4 instructions each; the plans are
/// the same).
///
/// Of such a main move's fits ([`Fits::fill`], the room in closed form as [`Profile::set`] has
/// it), those whose spans start at 1 are a pair within phase II (or VI: spans up to
/// `b − a − 1`, where the width fits there, `b − a > w`) or within the cruise (up to
/// `c − a − b − 1 − w`); every other fit's spans start at `a − w + 1` or more, so it takes at
/// least `w·(a − w + 1) ≥ a`. So a rest under `a` is one or two of the first kind, `w·k` with
/// `k ≠ w` (a pair of span `w` is not tried): a sum looked up in a mask of those amounts.
/// `true` (no answer) for a rest of `a` or more, or too large for the mask.
fn small_rest_may_fit(rest: u64, a: u64, b: u64, c: u64) -> bool {
    if rest == 0 || rest >= a || rest >= 64 {
        return true;
    }
    let (within_ramps, cruise) = (b - a, c - a - b);
    // Bit x: one pair takes x (x ≤ rest < 64).
    let mut amounts = 0u64;
    for w in 1..=WIDEST {
        let in_ramps = if within_ramps > w {
            within_ramps - 1
        } else {
            0
        };
        let longest = in_ramps.max(cruise.saturating_sub(w + 1)).min(rest / w);
        for k in (1..=longest).filter(|&k| k != w) {
            amounts |= 1 << (w * k);
        }
    }
    if amounts >> rest & 1 != 0 {
        return true;
    }
    // Two pairs: rest = x + (rest − x).
    let mut firsts = amounts;
    while firsts != 0 {
        let x = u64::from(firsts.trailing_zeros());
        firsts &= firsts - 1;
        if x < rest && amounts >> (rest - x) & 1 != 0 {
            return true;
        }
    }
    false
}

/// Whether one or two notch pairs may take `rest` off a main move of units of `tb(a, b, c)`
/// (with early units: `late`), by the bands its fits' spans fall in: `false` only where
/// [`Profile::take`] surely finds nothing, so that the main move's room and fits are not worked
/// out for nothing (about 2,000 Cortex-M4 instructions a main move, most of it
/// [`Fits::fill_closed`] and `take`'s loops over pairs of fits: every failed try of the
/// costliest moves from fractional positions failed there, before a candidate was checked).
///
/// From [`Fits::fill_closed`]'s intervals, with `d = b − a` and the cruise `C = c − a − b`, a
/// pair of width `w` has its spans in three bands (each a superset of the fits' spans there):
/// - small, `[1, σ_w]`: within phase II (`S₁U₁`, up to `d − 1`), the cruise (`S₂U₂`, up to
///   `C − 1 − w`) or phase VI (`S₃U₃`, up to `d − 1 + late`, where that is at least `w`), less
///   the width itself where it is an end of the band (a pair's span is not its width, [`notch`]);
/// - middle, with a cruise: `[a − late − w + 1, c − a − 1]` (`S₁U₂`, `S₂U₃`);
/// - large: `[2a + C − late − w + 1, 2b + C − 1 + w]` (`S₁U₃`).
///
/// A rest is then one pair's `w·k` or two pairs' `w₁·k₁ + w₂·k₂` with each span in a band: for
/// each pair of bands, within the sum of their amounts' hulls (and, for two pairs of one width,
/// a multiple of it). With nearly equal ramps and a short cruise the small bands hold a few
/// spans and the others start near `a`: rests between them fit nothing. A second ramp more
/// than 4 cycles longer than the first is let through unlooked-at: its small bands are wide
/// enough to fill most gaps (over CI's sample of moves from fractional positions and the
/// 20,000 seeded 2026, 25 of the 698 main moves ruled out had one, against 1,642 of the 5,611
/// let through, at 100–250 Cortex-M4 instructions each).
fn bands_may_take(rest: u64, (a, b, c): (u64, u64, u64), late: bool) -> bool {
    // `Fits::fill_closed` is for `a ≥ 2` only.
    if rest == 0 || a < 2 || b - a > 4 {
        return true;
    }
    // An empty band: its sums with any other stay empty.
    const NONE: Interval = (1 << 20, -(1 << 20));
    // Spans and amounts in 32 bits: the moves here are under 2^9 cycles.
    let (rest, a, b, c, late) = (rest as i32, a as i32, b as i32, c as i32, i32::from(late));
    let (d, cruise) = (b - a, c - a - b);
    // The amounts `w·k` of each band of width `w`.
    let small = |w: i32| {
        let phase_six = if d - 1 + late >= w { d - 1 + late } else { 0 };
        let small = phase_six.max(cruise - 1 - w);
        // Spans `k ≠ w`: 1 and `w` dropped where they are the band's ends.
        let (first, last) = (
            if w == 1 { 2 } else { 1 },
            if small == w { w - 1 } else { small },
        );
        if first <= last {
            (w * first, w * last)
        } else {
            NONE
        }
    };
    let middle = |w: i32| {
        if cruise > 0 {
            (w * (a - late - w + 1), w * (c - a - 1))
        } else {
            NONE
        }
    };
    let large = |w: i32| {
        (
            w * (2 * a + cruise - late - w + 1),
            w * (2 * b + cruise - 1 + w),
        )
    };
    let within = |(lo, hi): Interval| lo <= rest && rest <= hi;
    // One pair's first, in the large and middle bands (where about half the rests of main
    // moves tried are found), before the table for two pairs is written.
    if (1..=WIDEST as i32).any(|w| within(large(w)) || within(middle(w))) {
        return true;
    }
    // `bands[3·(w − 1) + i]`: band `i` (small, middle, large) of width `w`.
    let bands: [Interval; 3 * WIDEST as usize] = core::array::from_fn(|i| {
        let w = i as i32 / 3 + 1;
        match i % 3 {
            0 => small(w),
            1 => middle(w),
            _ => large(w),
        }
    });
    if bands.iter().step_by(3).any(|&band| within(band)) {
        return true;
    }
    // Two pairs: each pair of bands once, the second from the widest amounts down (most rests
    // two pairs take have one pair in a large band); of one width only where the rest is a
    // multiple of it.
    for (j, &(lo2, hi2)) in bands.iter().enumerate().rev() {
        // Past the rest (or empty): no pair with it can take the rest.
        if lo2 > rest {
            continue;
        }
        let w2 = j as i32 / 3 + 1;
        let end = if rest % w2 == 0 { j + 1 } else { j - j % 3 };
        // What the first pair must take.
        let (least, most) = (rest - hi2, rest - lo2);
        if bands[..end]
            .iter()
            .any(|&(lo1, hi1)| lo1 <= most && hi1 >= least)
        {
            return true;
        }
    }
    false
}

/// The shortest first ramp `a` of a main move of `total` cycles that can cover `distance`.
///
/// Of `tb(a, b, c)` with `c ≥ a + b`, the longest second ramp, `b = h − a` with `h = ⌊N/2⌋`,
/// covers the most: `a·b·c = a·b·(N − a − b)` grows with `b` up to `(N − a)/2` (a test holds
/// it). So `J` units need `J·a·(h − a)·(N − h) ≥ D`, which grows with `a` up to `N/4` (from `a`
/// to `a + 1` by `(N − h)·(h − 2a − 1) ≥ 0`, as `2a + 2 ≤ h` there), and a binary search finds
/// the first `a` that does: none before it covers the distance and every one after it does.
/// (It once bounded `b` by the cycles alone, `J·a·⌊(N − a)²/4⌋ ≥ D`, and [`plan`] passed by
/// the ramps that bound let through one by one — a quarter of a long move's cycles, about
/// 1,300 Cortex-M4 instructions on the costliest moves from fractional positions.)
fn first_ramp(distance: u64, jerk: u64, total: u64) -> u64 {
    // `J·a·b·c` < 2^32·2^7·2^8·2^9 (moves here are under 2^9 cycles): no overflow.
    let half = total / 2;
    let covers = |a: u64| jerk * a * (half - a) * (total - half) >= distance;
    // The last ramp that does not cover it (0 does not; `total/4 + 1`, past the ramps, is taken
    // to), and the next.
    last_true(0, total / 4 + 1, |a| !covers(a)) + 1
}

/// A notch pair as `(start, width, span)`, cycles.
type Pair = (i32, i32, i32);

/// Cycles `[lo, hi]` (inclusive, signed so that bounds below 0 need no care).
type Interval = (i32, i32);

/// At most this many intervals of room for a lowering or a raising impulse: the main move's
/// jerk takes at most 13 levels (12 corners), so room comes and goes at most 6 times.
const MAX_INTERVALS: usize = 7;

/// The most the pairs' dips lower the velocity on any cycle: two pairs, each at most
/// `min(w, k) ≤` [`WIDEST`] deep. Where the main move is at least this fast, no placement of
/// pairs can take its velocity below zero.
const SLOW: i64 = 2 * WIDEST as i64;

/// At most this many pieces of constant jerk in a main move: its two groups share their ramps
/// and differ by a cycle of cruise, so their corners fall on at most 12 cycles.
const MAX_LEVELS: usize = 16;

/// A main move's jerk by pieces, the cycles where its velocity is surely at least [`SLOW`],
/// and the cycles where its jerk has room for one impulse of each sign:
/// what decides whether notch pairs fit it ([`Self::fits`]).
#[derive(Debug)]
struct Profile {
    /// The main move's jerk by pieces, `(first cycle, level)`, from cycle 0 on: each lasts until the next
    /// one's first cycle, the last until the end of the move.
    levels: [(i32, i64); MAX_LEVELS],
    level_count: usize,
    /// Cycles `[first, last]` on which its velocity is at least [`SLOW`] (see [`Self::set`];
    /// empty when `first > last`): no dip there needs a look.
    fast: Interval,
    total: u64,
    limits: Limits64,
    /// Where the jerk is above `−J`: a lowering impulse fits.
    lower: [Interval; MAX_INTERVALS],
    lowers: usize,
    /// Where the jerk is below `J`: a raising impulse fits.
    raise: [Interval; MAX_INTERVALS],
    raises: usize,
    /// The main move whose pieces and fast cycles are still to be found ([`Self::ready`]):
    /// for units all alike, [`Self::set`] writes the room alone.
    pending: Option<[Group; 2]>,
    /// `(a, b, c, 1)` for units of `tb(a, b, c)` with early units, `(a, b, c, 0)` without, where
    /// [`Self::set`] wrote the room in closed form (every main move [`plan`] makes): what
    /// [`Fits::fill`] finds the fits from.
    shape: Option<(i32, i32, i32, i32)>,
    /// Whether every cycle with room for an impulse of a sign has room for two: a lowering
    /// impulse has room where the jerk is above `−J`, two where it is `2 − J` or more, so
    /// exactly where no cycle's jerk is `1 − J` (and, raising, `J − 1`) and `J ≥ 2` (a jerk of
    /// 0). For `J` units all alike the jerk is `J`, 0 or `−J`; with `e` early units (a cycle
    /// ahead from phase V on) also `±e`, `±(J − e)` and, where phase VI is empty, `±(J − 2e)`:
    /// `1 − J` only for `e = 1` or `e = J − 1`. So two or more early units and two or more
    /// others also have room for two (a test holds it exactly). Then two pairs need not keep
    /// their impulses apart ([`first_apart`]).
    doubles: bool,
}

impl Profile {
    /// No main move yet ([`Self::set`] gives it one), within `limits`.
    fn new(limits: Limits64) -> Self {
        Self {
            levels: [(0, 0); MAX_LEVELS],
            level_count: 0,
            fast: (1, 0),
            total: 0,
            limits,
            lower: [(0, 0); MAX_INTERVALS],
            lowers: 0,
            raise: [(0, 0); MAX_INTERVALS],
            raises: 0,
            pending: None,
            shape: None,
            doubles: false,
        }
    }

    /// The main move of `groups` — units of `tb(a, b, c)` (at least one) and units of
    /// `tb(a, b, c − 1)` (any, none included), as [`plan`] makes them — of `total` cycles: its
    /// room, by pieces of constant jerk. Only the entries it counts are written (and read).
    #[cfg(test)]
    fn of(groups: &[Group; 2], limits: Limits64, total: u64) -> Self {
        let mut profile = Self::new(limits);
        profile.set(groups, total);
        profile.ready();
        profile
    }

    /// As `Profile::of` (the tests' constructor), in place — but only the room: most main moves
    /// tried fail before a candidate is checked, on the room and the spans alone (every one of
    /// 748 that failed over four samples of moves from fractional positions), so their pieces
    /// wait for a candidate to check ([`Self::ready`]).
    fn set(&mut self, groups: &[Group; 2], total: u64) {
        let [full, early] = groups;
        if full.count + early.count != self.limits.jerk || full.a + full.b + full.c != total {
            // Not a main move [`plan`] makes (the tests' own): the room from the pieces.
            self.set_pieces(groups, total);
            self.pending = None;
            self.shape = None;
            self.doubles = false;
            return;
        }
        // `J` units of `tb(a, b, c)`: the jerk is `+J` in phases I and VII, `−J` in III and V,
        // zero in II, IV and VI (phases of no cycles dropped): a lowering impulse has room
        // but in III and V, a raising one from II to VI. Early units (`tb(a, b, c − 1)`, only
        // with a cruise) share the ramps and start phases V to VII a cycle early: the jerk is
        // above `−J` from the first cycle of the full units' phase V on (the early units are in
        // VI there), so a lowering impulse has room from `c + a − 1`; below `J` on the last
        // cycle, where the early units have ended, so a raising one has room there too. (The
        // pieces cost about 650 Cortex-M4 instructions a main move with early units, most of
        // which fail before a candidate is checked; a test and a debug assertion in
        // [`Self::ready`] hold the two equal.)
        self.total = total;
        let (a, b, c, end) = (full.a as i32, full.b as i32, full.c as i32, total as i32);
        let late = i32::from(early.count > 0);
        self.lowers = 0;
        push(&mut self.lower, &mut self.lowers, (0, b - 1));
        if c > a + b {
            push(&mut self.lower, &mut self.lowers, (a + b, c - 1));
        }
        push(&mut self.lower, &mut self.lowers, (c + a - late, end - 1));
        self.raises = 0;
        push(&mut self.raise, &mut self.raises, (a, c + b - 1));
        if late > 0 {
            push(&mut self.raise, &mut self.raises, (end - 1, end - 1));
        }
        self.pending = Some(*groups);
        self.shape = Some((a, b, c, late));
        let early_units = early.count;
        self.doubles = self.limits.jerk >= 2
            && (early_units == 0 || (early_units >= 2 && early_units + 2 <= self.limits.jerk));
    }

    /// Finds the pieces and fast cycles [`Self::set`] left for later, if it did: what
    /// [`Self::fits`] reads.
    fn ready(&mut self) {
        if let Some(groups) = self.pending.take() {
            let (lower, lowers, raise, raises) = (self.lower, self.lowers, self.raise, self.raises);
            self.set_pieces(&groups, self.total);
            // The room in closed form is the room the pieces give.
            debug_assert_eq!(
                (&lower[..lowers], &raise[..raises]),
                (self.lower(), self.raise()),
                "{groups:?}"
            );
        }
    }

    /// The main move's pieces, room and fast cycles ([`Self::set`] for any main move).
    fn set_pieces(&mut self, groups: &[Group; 2], total: u64) {
        self.total = total;
        // Cycles in 32 bits: the moves here are under 2^9 cycles.
        let end = total as i32;
        let [full, early] = groups;
        debug_assert!(
            early.count == 0 || (early.a, early.b, early.c + 1) == (full.a, full.b, full.c),
            "{groups:?}"
        );
        let (a, b, c) = (full.a as i32, full.b as i32, full.c as i32);
        let (units, early_units) = (full.count as i64, early.count as i64);
        let jerk = units + early_units;
        // The corners of both groups in the order of their cycles, written down rather than
        // merged (a merge of two lists of eight cost about 1,300 Cortex-M4 instructions a main
        // move): the ramps' four, shared, then the last four of each group, the early group's
        // one cycle before the full group's. Those interleave, `E₀ M₀ E₁ M₁ E₂ M₂ E₃ M₃`, as
        // `Mᵢ₊₁ − Mᵢ ≥ 1` puts `Eᵢ₊₁ = Mᵢ₊₁ − 1` at or after `Mᵢ` — but for `a = b`, where
        // `M₁ = M₂` and `E₁ = E₂`: then both early corners come first.
        let mut corners = [
            (0, jerk),
            (a, -jerk),
            (b, -jerk),
            (a + b, jerk),
            (c - 1, -early_units),
            (c, -units),
            (c - 1 + a, early_units),
            (c + a, units),
            (c - 1 + b, early_units),
            (c + b, units),
            (c - 1 + a + b, -early_units),
            (c + a + b, -units),
        ];
        if a == b {
            corners.swap(7, 8);
        }
        // (With no early unit there may be no cruise either: its corners are no changes.)
        debug_assert!(corners
            .windows(2)
            .all(|pair| pair[0].0 <= pair[1].0 || pair[0].1 == 0 || pair[1].1 == 0));
        // Each cycle with a change starts a piece; changes on one cycle add up (the early
        // group's, when it has no unit, are none).
        let (mut count, mut level, mut from) = (0, 0i64, 0i32);
        for (cycle, change) in corners {
            if cycle >= end {
                break;
            }
            if change == 0 {
                continue;
            }
            if cycle > from {
                self.levels[count] = (from, level);
                count += 1;
                from = cycle;
            }
            level += change;
        }
        self.levels[count] = (from, level);
        count += 1;
        self.level_count = count;
        // The room for each sign of impulse, piece by piece.
        let limit = self.limits.jerk as i64;
        self.lowers = 0;
        self.raises = 0;
        for k in 0..count {
            let (start, level) = self.levels[k];
            let last = if k + 1 < count {
                self.levels[k + 1].0 - 1
            } else {
                end - 1
            };
            if level > -limit {
                push(&mut self.lower, &mut self.lowers, (start, last));
            }
            if level < limit {
                push(&mut self.raise, &mut self.raises, (start, last));
            }
        }
        // Each unit's velocity is at least `min(n + 1, total − 2 − n, a·b)` on cycle `n`: it
        // rises by at least one raw unit a cycle from 1 on cycle 0 to `a·b`, and falls likewise
        // to 1 on cycle `total − 3` (`box(a) ∗ box(b) ∗ box(c)` is symmetric). The first group
        // has a unit (`J − e ≥ 1`), the other's add to it: so from cycle `SLOW − 1` to cycle
        // `total − 2 − SLOW` the velocity is at least `SLOW` if `a·b` is.
        self.fast = if full.count > 0 && full.a + full.b + full.c == total {
            let slow = SLOW as i32;
            let plateau = i64::try_from(full.a * full.b).unwrap_or(i64::MAX);
            if plateau >= SLOW {
                (slow - 1, end - 2 - slow)
            } else {
                (1, 0)
            }
        } else {
            (1, 0)
        };
    }

    /// The main move's jerk on cycle `n` (`0 ≤ n < total`).
    #[cfg(test)]
    fn jerk_at(&self, n: i32) -> i64 {
        self.levels[..self.level_count]
            .iter()
            .take_while(|&&(from, _)| from <= n)
            .last()
            .map_or(0, |&(_, level)| level)
    }

    fn lower(&self) -> &[Interval] {
        &self.lower[..self.lowers]
    }

    fn raise(&self) -> &[Interval] {
        &self.raise[..self.raises]
    }

    /// Whether `pairs` (`(start, width, span)`, each placed by a [`Fit`]) fit the main move:
    /// the jerk on every cycle with an impulse, and the velocity under every dip, within the
    /// limits. A fixed number of comparisons, whatever the move's length:
    ///
    /// - the jerk changes only on the impulses' cycles (at most 8), where the main move's
    ///   level is looked up in its pieces;
    /// - the acceleration and the velocity cannot leave their limits: the class of moves
    ///   planned here keeps the main move's peaks `J·⌊N/4⌋ + 2` and `J·⌊N²/16⌋` within them
    ///   ([`optimum_floor`]), and the pairs add at most 2 to the one and only lower the other;
    /// - the velocity stays at least zero where the main move is at least [`SLOW`] (the pairs'
    ///   dips are never deeper), so only the cycles under a dip outside [`Self::fast`] are
    ///   checked, with the main move's velocity summed from its first cycle or back from its
    ///   last (a few cycles, unless the move is tiny).
    ///
    /// The distance is right by construction, and the move ends as the main move does: every
    /// dip ends by its third-last cycle. (This replaced a walk over every cycle the pairs span,
    /// a few dozen 64-bit operations a cycle on a Cortex-M4.)
    fn fits(&self, pairs: &[Pair]) -> bool {
        let jerk_limit = self.limits.jerk as i64;
        // The impulses in order of their cycles (at most 8: an insertion sort).
        let mut impulses = [(0i32, 0i64); 8];
        let mut len = 0;
        for &pair in pairs {
            for impulse in impulses_of(pair) {
                let mut k = len;
                while k > 0 && impulses[k - 1].0 > impulse.0 {
                    impulses[k] = impulses[k - 1];
                    k -= 1;
                }
                impulses[k] = impulse;
                len += 1;
            }
        }
        if len == 0 {
            return true;
        }
        // The jerk on each impulse's cycle: the main move's level plus every impulse there (a
        // pair's may meet another's), the pieces walked once alongside the sorted impulses.
        let levels = &self.levels[..self.level_count];
        let (mut piece, mut i) = (0, 0);
        while i < len {
            let cycle = impulses[i].0;
            let mut on_cycle = 0;
            while i < len && impulses[i].0 == cycle {
                on_cycle += impulses[i].1;
                i += 1;
            }
            piece = piece_holding(levels, piece, cycle);
            let level = levels.get(piece).map_or(0, |&(_, level)| level);
            if (level + on_cycle).abs() > jerk_limit {
                return false;
            }
        }
        // The velocity under the dips, from the first impulse to the last (on which every
        // dip has ended), where the main move may be slower than `SLOW`: the cycles before
        // `fast` summed from cycle 0, those after it back from rest after the last cycle.
        let (from, to) = (impulses[0].0, impulses[len - 1].0);
        let dips = |n: i32| -> i64 { pairs.iter().map(|&pair| depth(pair, n)).sum() };
        let head_end = to.min(self.fast.0.max(from));
        if from < head_end {
            let (mut acceleration, mut velocity, mut piece) = (0i64, 0i64, 0);
            for n in 0..head_end {
                piece = piece_holding(levels, piece, n);
                acceleration += levels[piece].1;
                velocity += acceleration;
                if n >= from && velocity < dips(n) {
                    return false;
                }
            }
        }
        let tail_start = head_end.max(self.fast.1 + 1);
        if tail_start < to {
            // The state after cycle `n − 1` is `v − a`, `a − j` of the one after `n`; after the
            // last cycle the move is at rest, its jerk 0 (every change made).
            let (mut jerk, mut acceleration, mut velocity) = (0i64, 0i64, 0i64);
            let mut piece = levels.len();
            for n in (tail_start..self.total as i32).rev() {
                velocity -= acceleration;
                acceleration -= jerk;
                while piece > 0 && levels[piece - 1].0 > n {
                    piece -= 1;
                }
                jerk = if piece > 0 { levels[piece - 1].1 } else { 0 };
                if n < to && velocity < dips(n) {
                    return false;
                }
            }
        }
        true
    }
}

/// The piece of `levels` (`(first cycle, level)`, in order) that holds cycle `n`, looked for
/// from `piece` on (`n` at or past that piece's first cycle).
fn piece_holding(levels: &[(i32, i64)], mut piece: usize, n: i32) -> usize {
    while piece + 1 < levels.len() && levels[piece + 1].0 <= n {
        piece += 1;
    }
    piece
}

/// How much the pair `(s, w, k)` lowers the velocity on cycle `n`: `(box(w) ∗ box(k))(n − s)`,
/// the running sum of its acceleration (−1 under its first notch, +1 under its second).
fn depth((s, w, k): Pair, n: i32) -> i64 {
    let m = n - s;
    if m < 0 {
        return 0;
    }
    i64::from((m + 1).min(w).min(k).min(w + k - 1 - m).max(0))
}

/// Appends `piece` to the intervals, merged with the last one if it continues it.
fn push(intervals: &mut [Interval; MAX_INTERVALS], len: &mut usize, piece: Interval) {
    if *len > 0 && intervals[*len - 1].1 + 1 == piece.0 {
        intervals[*len - 1].1 = piece.1;
    } else if *len < MAX_INTERVALS {
        intervals[*len] = piece;
        *len += 1;
    }
}

/// Where a notch pair of width `w` fits: its starts `s` in `starts` (`[A₁, B₁]`: a lowering
/// impulse fits on `s`, a raising one on `s + w`) and its raises `s + k` in `raises` (`[A₂, B₂]`:
/// a raising impulse on `s + k`, a lowering one on `s + k + w`, before the move's last cycle).
/// For a span `k` the starts are `[max(A₁, A₂ − k), min(B₁, B₂ − k)]`, not empty exactly for
/// `k ∈ [A₂ − B₁, B₂ − A₁]`.
#[derive(Debug, Clone, Copy)]
struct Fit {
    starts: Interval,
    raises: Interval,
    /// `w·` [`Self::spans`]: what one pair of the width takes, found once per main move (the
    /// search for two pairs compares it for every pair of fits: most cannot take the rest).
    reach: Interval,
}

impl Fit {
    /// No room: a table's entry before it is written.
    const EMPTY: Self = Self {
        starts: (0, 0),
        raises: (0, 0),
        reach: (0, 0),
    };

    /// The fit of a pair of width `w` with its starts in `starts` and its raises in `raises`,
    /// its reach found, if it has spans at all.
    fn of(starts: Interval, raises: Interval, w: i32) -> Option<Self> {
        let fit = Self {
            starts,
            raises,
            reach: (0, 0),
        };
        let (lo, hi) = fit.spans();
        (lo <= hi).then_some(Self {
            reach: (w * lo, w * hi),
            ..fit
        })
    }

    /// The spans the pair can take (not the width itself: see [`notch`]).
    fn spans(&self) -> Interval {
        (
            (self.raises.0 - self.starts.1).max(1),
            self.raises.1 - self.starts.0,
        )
    }

    /// The first and the last start of a pair of span `k` (within [`Self::spans`]).
    fn range(&self, k: i32) -> Interval {
        (
            self.starts.0.max(self.raises.0 - k),
            self.starts.1.min(self.raises.1 - k),
        )
    }
}

/// At most this many [`Fit`]s of one width are kept: a main move [`plan`] makes has no more (six
/// in closed form, [`Fits::fill_closed`]; with a first ramp of one cycle, whose fits
/// [`Fits::fill_from_room`] finds, a test holds it for every main move of up to
/// [`LONGEST`] + [`COUNTS`] cycles). The table is cleared once a plan: 12 a width cleared 432
/// bytes more, 162 Cortex-M4 instructions.
const MAX_FITS: usize = 6;

/// The [`Fit`]s of a pair of each width from 1 to [`WIDEST`] in a main move (only the first
/// `lens[w − 1]` of each width are its: the table is rewritten for each main move).
struct Fits {
    fits: [[Fit; MAX_FITS]; WIDEST as usize],
    lens: [usize; WIDEST as usize],
    /// For each width, the least and the most one pair takes over all its fits (`reach`).
    reach: [Interval; WIDEST as usize],
    /// Scratch for [`Self::fill`]: a width's intervals of starts and of raises (each written
    /// before it is read; kept here, written once per plan, not cleared for every main move).
    starts: [Interval; MAX_INTERVALS * 2],
    raises: [Interval; MAX_INTERVALS * 2],
}

impl Fits {
    /// No fits yet ([`Self::fill`] finds them).
    const EMPTY: Self = Self {
        fits: [[Fit::EMPTY; MAX_FITS]; WIDEST as usize],
        lens: [0; WIDEST as usize],
        reach: [(0, 0); WIDEST as usize],
        starts: [(0, 0); MAX_INTERVALS * 2],
        raises: [(0, 0); MAX_INTERVALS * 2],
    };

    /// For each width: the intervals of starts (a lowering impulse's room, and a raising one's
    /// `w` later) and of raises (a raising impulse's room, and a lowering one's `w` later,
    /// before the last cycle), each pair of them whose spans are not empty.
    fn fill(&mut self, profile: &Profile) {
        match profile.shape {
            Some(shape) if shape.0 >= 2 => self.fill_closed(shape, profile.total as i32),
            _ => self.fill_from_room(profile),
        }
    }

    /// [`Self::fill`] for units of `tb(a, b, c)`, `a ≥ 2`, with early units (`late` = 1) or
    /// without (0), from the room in closed form ([`Profile::set`]): the same fits in the same
    /// order as [`Self::fill_from_room`] finds from its intervals (a test compares them over
    /// every such main move of up to 48 cycles), without intersecting every pair of intervals
    /// of room and every pair of starts and raises: about 380 Cortex-M4 instructions a main move
    /// where that took about 760 (85,418 raw units with a jerk of 1, seven main moves tried,
    /// six of them failing).
    ///
    /// The room: lowering `L₁ = [0, b)`, `L₂ = [a + b, c)` (a cruise), `L₃ = [c + a − late, N)`;
    /// raising `[a, c + b)` (and, with early units, the last cycle: its starts, `N − 1 − w`,
    /// have no raise after them, and its raises none of their own). A pair's starts from `Lᵢ`
    /// and raises before `Lⱼ` (`Sᵢ`, `Uⱼ`) have spans only for `i ≤ j` (each `Uⱼ` ends before
    /// `Lⱼ`, each `Sᵢ` starts in `Lᵢ`): six fits a width at most, in the order
    /// `S₁U₁ S₁U₂ S₁U₃ S₂U₂ S₂U₃ S₃U₃`. (With `a = 1` intervals meet and merge.)
    fn fill_closed(&mut self, shape: (i32, i32, i32, i32), total: i32) {
        for w in 1..=WIDEST as i32 {
            self.fill_closed_width(shape, total, w, w as usize - 1);
        }
    }

    /// The fits of a pair of width `w` in closed form ([`Self::fill_closed`]) as the table's
    /// `row`: its own for `w` up to [`WIDEST`]; row 0 for a wider pair
    /// ([`Tries::wide_pairs`], once the table's main moves are tried: the next main move
    /// fills the table again).
    #[inline(always)]
    fn fill_closed_width(
        &mut self,
        (a, b, c, late): (i32, i32, i32, i32),
        total: i32,
        w: i32,
        i: usize,
    ) {
        let last = total - 1;
        // No cruise: `S₂` and `U₂` empty (`lo > hi`).
        let cruise = c > a + b;
        // As `fill_from_room`'s intersections with the raising room `[a, c + b − 1]`.
        let s1 = ((a - w).max(0), (b - 1).min(c + b - 1 - w));
        let s2 = if cruise {
            (a + b, (c - 1).min(c + b - 1 - w))
        } else {
            (1, 0)
        };
        let s3 = (c + a - late, c + b - 1 - w);
        let u1 = (a, b - 1 - w);
        let u2 = if cruise {
            (a.max(a + b - w), c - 1 - w)
        } else {
            (1, 0)
        };
        let u3 = (a.max(c + a - late - w), (c + b - 1).min(last - w));
        let (mut len, mut reach) = (0, (i32::MAX, i32::MIN));
        let width_fits = &mut self.fits[i];
        let mut add = |starts: Interval, raises: Interval| {
            // `fill_from_room` keeps only intervals that are not empty.
            let kept = (starts.0 <= starts.1 && raises.0 <= raises.1)
                .then(|| Fit::of(starts, raises, w))
                .flatten();
            if let Some(fit) = kept {
                width_fits[len] = fit;
                len += 1;
                reach = (reach.0.min(fit.reach.0), reach.1.max(fit.reach.1));
            }
        };
        add(s1, u1);
        add(s1, u2);
        add(s1, u3);
        add(s2, u2);
        add(s2, u3);
        add(s3, u3);
        self.lens[i] = len;
        self.reach[i] = reach;
    }

    /// [`Self::fill`] from the room's intervals, whatever they are.
    fn fill_from_room(&mut self, profile: &Profile) {
        let fits = self;
        let last = profile.total as i32 - 1;
        let (starts, raises) = (&mut fits.starts, &mut fits.raises);
        for w in 1..=WIDEST as i32 {
            let (mut n_starts, mut n_raises) = (0, 0);
            for &lower in profile.lower() {
                for &raise in profile.raise() {
                    let start = (lower.0.max(raise.0 - w).max(0), lower.1.min(raise.1 - w));
                    if start.0 <= start.1 && n_starts < starts.len() {
                        starts[n_starts] = start;
                        n_starts += 1;
                    }
                    let up = (
                        raise.0.max(lower.0 - w),
                        raise.1.min(lower.1 - w).min(last - w),
                    );
                    if up.0 <= up.1 && n_raises < raises.len() {
                        raises[n_raises] = up;
                        n_raises += 1;
                    }
                }
            }
            let i = w as usize - 1;
            // The count and the reach in locals, written back once (kept in the table, they
            // were loaded and stored for every fit).
            let (mut len, mut reach) = (0, (i32::MAX, i32::MIN));
            let width_fits = &mut fits.fits[i];
            // The first `MAX_FITS` pairs of intervals whose spans are not empty: once that many
            // are kept, the rest would be passed over, so they are not looked at.
            'pairs: for &starts in &starts[..n_starts] {
                for &raises in &raises[..n_raises] {
                    if len == MAX_FITS {
                        break 'pairs;
                    }
                    if let Some(fit) = Fit::of(starts, raises, w) {
                        width_fits[len] = fit;
                        len += 1;
                        reach = (reach.0.min(fit.reach.0), reach.1.max(fit.reach.1));
                    }
                }
            }
            // None passed over in the main moves `plan` makes (see [`MAX_FITS`]).
            debug_assert!(
                len < MAX_FITS
                    || starts[..n_starts]
                        .iter()
                        .flat_map(|&s| raises[..n_raises].iter().map(move |&r| (s, r)))
                        .filter(|&(s, r)| Fit::of(s, r, w).is_some())
                        .count()
                        == MAX_FITS,
                "more than {MAX_FITS} fits of width {w}"
            );
            fits.lens[i] = len;
            fits.reach[i] = reach;
        }
    }

    /// The fits of width `w` (1 to [`WIDEST`]).
    fn of_width(&self, w: i32) -> &[Fit] {
        let i = w as usize - 1;
        &self.fits[i][..self.lens[i]]
    }
}

/// A notch pair of width `w` and span `k` from `start`, written with the shorter of the two as
/// its width: `box(w) ∗ box(k)` is the same either way, and the schedule's merge reads a pair's
/// changes in order, which needs `span > width` (a pair with `k = w` is not tried).
fn notch(start: i32, w: i32, k: i32) -> Notch {
    Notch {
        start: start as u64,
        width: w.min(k) as u64,
        span: w.max(k) as u64,
    }
}

impl Profile {
    /// The notch pairs, one or two, that take `rest` off the main move and fit it
    /// ([`Self::fits`]), in the room `fits` found for it ([`Fits::fill`]); counts the candidates
    /// checked in `checks`. With `apart`, only pairs whose impulses are apart ([`first_apart`]:
    /// each cycle's then has the room its interval gives it); else the ends of the start
    /// ranges, where impulses of a sign may meet in room for both.
    fn take(&mut self, rest: u64, apart: bool, checks: &mut u32, fits: &Fits) -> Option<Placement> {
        if rest == 0 {
            return Some(Placement::default());
        }
        // Under 6·131 (see `plan`): 32-bit divisions, one instruction each on a Cortex-M4.
        let rest = rest as i32;
        // One pair: w·k = rest.
        for width in 1..=WIDEST {
            let w = width as i32;
            if rest % w != 0 || rest / w == w {
                continue;
            }
            let k = rest / w;
            for &fit in fits.of_width(w) {
                let (lo, hi) = fit.spans();
                if k < lo || k > hi {
                    continue;
                }
                let (first, last) = fit.range(k);
                for start in [first, last] {
                    if *checks >= MAX_CHECKS {
                        return None;
                    }
                    *checks += 1;
                    self.ready();
                    if self.fits(&[(start, w, k)]) {
                        return Some(placement(&[(start, w, k)]));
                    }
                }
            }
        }
        // Two pairs: w₁·k₁ + w₂·k₂ = rest, k₁ the first two of its interval with the right
        // residue modulo w₂ (at most 2·w₂ values to look at): the first alone missed pairs
        // where it was the width itself or had no starts apart (`tools/ab_plans.sh`: 81 of
        // 200,000 plans a cycle shorter; moves from fractional positions 102,941 and 80,549
        // with a jerk of 1, which found no pairs here and went on to the search, 21,730 and
        // 21,242 → 8,871 and 8,215 Cortex-M4 instructions; up to +350 where every candidate
        // fails: 127,623, six main moves tried, 19,890 → 20,044).
        // Most pairs of fits cannot take `rest` at all: w₁·k₁ + w₂·k₂ lies in [w₁·lo₁ + w₂·lo₂,
        // w₁·hi₁ + w₂·hi₂]. Rejected by comparisons — all the fits of two widths at once, then
        // all the second width's with one of the first, then one pair of fits — before the
        // divisions below (whose range would be empty: the same result).
        let passes = |(low, high): Interval, (least, most): Interval| {
            low.saturating_add(least) <= rest && high.saturating_add(most) >= rest
        };
        for w1 in 1..=WIDEST as i32 {
            for w2 in w1..=WIDEST as i32 {
                // Two pairs of one width take only multiples of it (of widths up to 3, only
                // equal ones share a factor): their fits are passed by without a look. Most
                // failed tries look at every pair of fits (80,549 raw units with a jerk of 1,
                // four failed tries: 24,511 → 21,554 Cortex-M4 instructions).
                let seconds = fits.reach[w2 as usize - 1];
                if (w1 == w2 && rest % w1 != 0) || !passes(fits.reach[w1 as usize - 1], seconds) {
                    continue;
                }
                for &first in fits.of_width(w1) {
                    if !passes(first.reach, seconds) {
                        continue;
                    }
                    // The second pair must take from `rest − w₁·hi₁` to `rest − w₁·lo₁`:
                    // `passes` with the first fit's part taken out of the loop (calling
                    // `passes` there measured +160 Cortex-M4 instructions on the worst move).
                    let (needed_low, needed_high) = (rest - first.reach.1, rest - first.reach.0);
                    for &second in fits.of_width(w2) {
                        if second.reach.0 > needed_high || second.reach.1 < needed_low {
                            continue;
                        }
                        let (lo1, hi1) = first.spans();
                        let (lo2, hi2) = second.spans();
                        let from = lo1.max(ceil(rest - w2 * hi2, w1));
                        let to = hi1.min((rest - w2 * lo2).div_euclid(w1));
                        for k1 in from..=to.min(from + 2 * w2 - 1) {
                            let left = rest - w1 * k1;
                            if left % w2 != 0 || k1 == w1 || left / w2 == w2 {
                                continue;
                            }
                            let k2 = left / w2;
                            let (from1, to1) = first.range(k1);
                            let (from2, to2) = second.range(k2);
                            let (starts, count) = if apart {
                                // Starts whose impulses are apart: each cycle's has the room
                                // its interval gives it.
                                let found = first_apart(
                                    (from1, to1),
                                    (from2, to2),
                                    (w1, k1),
                                    (w2, k2),
                                    self.doubles,
                                );
                                let Some(found) = found else {
                                    continue;
                                };
                                ([found; 4], 1)
                            } else {
                                ([(from1, to2), (from1, from2), (to1, to2), (to1, from2)], 4)
                            };
                            for &(s1, s2) in &starts[..count] {
                                if *checks >= MAX_CHECKS {
                                    return None;
                                }
                                *checks += 1;
                                let pairs = [(s1, w1, k1), (s2, w2, k2)];
                                self.ready();
                                if self.fits(&pairs) {
                                    return Some(placement(&pairs));
                                }
                            }
                        }
                    }
                }
            }
        }
        None
    }
}

/// The placement of `pairs` (`(start, width, span)`).
fn placement(pairs: &[Pair]) -> Placement {
    let mut placement = Placement::default();
    for &(start, w, k) in pairs {
        placement.push(notch(start, w, k));
    }
    placement
}

/// A pair's jerk impulses `(cycle, ±1)` (as [`Notch::impulses`], in this module's cycles).
fn impulses_of((s, w, k): Pair) -> [(i32, i64); 4] {
    [(s, -1), (s + w, 1), (s + k, 1), (s + k + w, -1)]
}

/// The first starts `(s₁, s₂)` — `s₁` from the first four of `from1 ..= to1`, then `s₂` from
/// the first 21 of `from2 ..= to2` — that put two pairs of widths and spans `(w1, k1)` and
/// `(w2, k2)` apart: no cycle with two impulses of one sign. Each cycle's impulses then have
/// the room their intervals give them: a pair's four fall on four cycles (`w ≠ k`), so a cycle
/// has one impulse, or one of each pair — of one sign (kept apart), or of opposite signs, which
/// cancel and leave the main move's jerk. With `doubles` (the main move has room for two
/// impulses of a sign wherever it has for one, [`Profile`]) the first starts of each: nothing
/// needs keeping apart. (Impulses were once kept on distinct cycles, opposite signs too, and
/// always: 30 of 80 main moves that failed over the costliest moves of a sample from fractional
/// positions had pairs that took their rest, all kept apart by that.)
///
/// The pairs meet with one sign exactly when `s₂ − s₁` is one of the 8 differences between an
/// impulse of the first and one of the second of the same sign, the same for every start: those
/// within reach are marked once in a mask of differences, and each `s₁` reads its first free
/// `s₂` off it. (A walk over the starts compared the pairs of impulses for each: cheap when the
/// first start is free, but hundreds of Cortex-M4 instructions where the starts are few and all
/// taken, as in the shortest moves.)
fn first_apart(
    (from1, to1): Interval,
    (from2, to2): Interval,
    (w1, k1): (i32, i32),
    (w2, k2): (i32, i32),
    doubles: bool,
) -> Option<(i32, i32)> {
    let (last1, last2) = (to1.min(from1 + 3), to2.min(from2 + 20));
    if from1 > last1 || from2 > last2 {
        return None;
    }
    if doubles {
        return Some((from1, from2));
    }
    // One start each (most calls, in short moves: 28 of 30 for 438 raw units with a jerk of 1):
    // the 8 differences compared with theirs, no mask (about 130 Cortex-M4 instructions a call
    // with it). A pair's lowering impulses are on `s` and `s + k + w`, its raising ones on
    // `s + w` and `s + k`.
    if from1 == last1 && from2 == last2 {
        let apart = from2 - from1;
        let meet = [0, k1 + w1]
            .into_iter()
            .any(|one| [0, k2 + w2].contains(&(one - apart)))
            || [w1, k1]
                .into_iter()
                .any(|one| [w2, k2].contains(&(one - apart)));
        return (!meet).then_some((from1, from2));
    }
    // Differences `s₂ − s₁` from `from2 − last1` (bit 0) on: 24 of them cover every pair of
    // starts looked at. Lowering impulses with lowering ones, raising with raising.
    let base = from2 - last1;
    let mut taken = 0u32;
    for (ones, others) in [([0, k1 + w1], [0, k2 + w2]), ([w1, k1], [w2, k2])] {
        for one in ones {
            for other in others {
                let bit = one - other - base;
                if (0..32).contains(&bit) {
                    taken |= 1 << bit;
                }
            }
        }
    }
    // The starts `from2 ..= last2` (at most 21) as bits from 0.
    let starts = (1u32 << (last2 - from2 + 1)) - 1;
    (from1..=last1).find_map(|s1| {
        // `s₂ = from2 + i` has the difference `from2 + i − s1`: bit `i + (last1 − s1)`.
        let free = !(taken >> (last1 - s1)) & starts;
        (free != 0).then(|| (s1, from2 + free.trailing_zeros() as i32))
    })
}

/// `⌈n/d⌉` for `d > 0`.
fn ceil(n: i32, d: i32) -> i32 {
    -(-n).div_euclid(d)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Limits far above what these moves reach: only the jerk binds.
    fn wide(jerk: u64) -> Limits64 {
        Limits64 {
            jerk,
            acceleration: 1 << 30,
            velocity: 1 << 46,
        }
    }

    /// The plan of `distance` raw units with `jerk`, from this module alone: [`first`] where
    /// the search would call it, then [`improve`] as if the search had found nothing.
    fn planned(distance: u64, jerk: u64) -> Schedule {
        let mut out = Schedule::EMPTY;
        assert!(
            first(distance, 1, wide(jerk), &mut out)
                || improve(distance, 1, wide(jerk), false, &mut out),
            "{distance}, J {jerk}"
        );
        let replay = out.replay(1, wide(jerk));
        assert!(replay.within_limits, "{distance}, J {jerk}");
        assert_eq!(replay.distance, i128::from(distance));
        out
    }

    /// By hand: 101 raw units with a jerk of 1 in 16 cycles, `tb(3, 4, 9)` (108) less pairs of
    /// width 1 and spans 3 and 4 (the exhaustive search of tests/scurve_exhaustive.rs finds no
    /// plan shorter; the search alone took 18). 192 raw units with a jerk of 3: `3·tb(2, 4, 8)`
    /// exactly, 14 cycles.
    #[test]
    fn moves_by_hand() {
        assert_eq!(planned(101, 1).plan.total, 16);
        assert_eq!(planned(192, 3).plan.total, 14);
    }

    /// The main move's jerk, acceleration and velocity on every cycle, summed cycle by cycle
    /// from its groups' changes.
    fn summed(groups: &[Group; 2], total: u64) -> Vec<(i64, i64, i64)> {
        let (mut jerk, mut acceleration, mut velocity) = (0i64, 0i64, 0i64);
        (0..total + 2)
            .map(|n| {
                jerk += groups
                    .iter()
                    .flat_map(|g| {
                        crate::scurve::shape::corners(g.a, g.b, g.c).map(|(at, sign)| {
                            if at == n {
                                sign * g.count as i64
                            } else {
                                0
                            }
                        })
                    })
                    .sum::<i64>();
                acceleration += jerk;
                velocity += acceleration;
                (jerk, acceleration, velocity)
            })
            .collect()
    }

    /// Main moves of two groups (one a cycle of cruise shorter), small and large.
    fn main_moves() -> Vec<([Group; 2], u64)> {
        let mut moves = Vec::new();
        for (a, b) in [(1, 1), (1, 2), (2, 2), (2, 3), (3, 5), (1, 4)] {
            for extra in 0..3 {
                let c = a + b + 1 + extra;
                for (count, early) in [(1, 0), (1, 1), (3, 0), (2, 2), (4, 3), (7, 0), (5, 2)] {
                    let group = |count, c| Group { count, a, b, c };
                    moves.push(([group(count, c), group(early, c - 1)], a + b + c));
                }
            }
        }
        moves
    }

    /// Whether two pairs have their impulses apart: no cycle with two of one sign.
    fn apart(first: Pair, second: Pair) -> bool {
        let first = impulses_of(first);
        impulses_of(second)
            .iter()
            .all(|impulse| first.iter().all(|other| other != impulse))
    }

    proptest::proptest! {
        #![proptest_config(proptest::prelude::ProptestConfig::with_cases(20_000))]

        /// [`first_apart`]'s mask of differences finds the starts a walk over them, comparing
        /// every pair of impulses, finds first (or none, as it does); with `doubles`, the first
        /// starts of each.
        #[test]
        fn the_first_starts_apart_are_the_walks(
            from1 in 0i32..30, len1 in -2i32..8, from2 in 0i32..30, len2 in -2i32..30,
            w1 in 1i32..=3, k1 in 1i32..20, w2 in 1i32..=3, k2 in 1i32..20,
        ) {
            let (to1, to2) = (from1 + len1, from2 + len2);
            let walked = (from1..=to1.min(from1 + 3)).find_map(|s1| {
                (from2..=to2.min(from2 + 20))
                    .find(|&s2| apart((s1, w1, k1), (s2, w2, k2)))
                    .map(|s2| (s1, s2))
            });
            proptest::prop_assert_eq!(
                first_apart((from1, to1), (from2, to2), (w1, k1), (w2, k2), false),
                walked
            );
            let first = (from1 <= to1 && from2 <= to2).then_some((from1, from2));
            proptest::prop_assert_eq!(
                first_apart((from1, to1), (from2, to2), (w1, k1), (w2, k2), true),
                first
            );
        }
    }

    /// One start each, [`first_apart`]'s comparisons without a mask: the walk's answer for
    /// every pair of starts apart by −6 to 11 cycles, widths up to 3 and spans up to 11.
    #[test]
    fn one_start_each_is_the_walk() {
        for s1 in 0..6 {
            for s2 in 0..12 {
                for (w1, k1, w2, k2) in (1..=3).flat_map(|w1| {
                    (1..12).flat_map(move |k1| {
                        (1..=3).flat_map(move |w2| (1..12).map(move |k2| (w1, k1, w2, k2)))
                    })
                }) {
                    let walked = apart((s1, w1, k1), (s2, w2, k2)).then_some((s1, s2));
                    let found = first_apart((s1, s1), (s2, s2), (w1, k1), (w2, k2), false);
                    assert_eq!(found, walked, "{:?}", (s1, s2, w1, k1, w2, k2));
                }
            }
        }
    }

    /// [`reach`]'s bound, against every pair whose four impulses each have room in the main
    /// move's jerk summed cycle by cycle (what a [`Fit`] places), widths up to [`WIDEST`]:
    /// its span is at most `total − 2a − 1 + w`, and that bound is met.
    #[test]
    fn no_pair_spans_past_the_reach() {
        let mut met = 0;
        for (groups, total) in main_moves() {
            let jerk = (groups[0].count + groups[1].count) as i64;
            let main = summed(&groups, total);
            let level = |n: i32| main[n as usize].0;
            let (t, a) = (total as i32, groups[0].a as i32);
            let bound = |w: i32| t - 2 * a - 1 + w;
            let mut longest = i32::MIN;
            for s in 0..t {
                for w in 1..=WIDEST as i32 {
                    for k in 1..t {
                        let end = s + k + w;
                        let room = k != w
                            && end < t
                            && level(s) > -jerk
                            && level(s + w) < jerk
                            && level(s + k) < jerk
                            && level(end) > -jerk;
                        if room {
                            assert!(k <= bound(w), "{groups:?}: {:?}", (s, w, k));
                            longest = longest.max(k - bound(w));
                            assert!(2 * i64::from(w * k) <= reach(total, groups[0].a) as i64);
                        }
                    }
                }
            }
            met += usize::from(longest == 0);
        }
        assert!(met > 10, "{met}");
    }

    /// The widest second ramp `⌊N/2⌋ − a` covers the most of any with the first ramp `a` (by
    /// brute force over every second ramp, `c ≥ a + b`): where it does not cover a distance,
    /// [`plan`] passes the first ramp by, and none would have.
    #[test]
    fn the_widest_second_ramp_covers_the_most() {
        for total in 4..=120u64 {
            for a in 1..=total / 4 {
                let widest = total / 2 - a;
                let most = (a..=widest).map(|b| a * b * (total - a - b)).max().unwrap();
                assert_eq!(most, a * widest * (total - a - widest), "{total} {a}");
            }
        }
    }

    /// Where [`small_rest_may_fit`] says no, no pairs are tried at all: for every main move of
    /// `J` units all alike of up to 48 cycles with a jerk of 1 to 3 raw units, and every rest
    /// under its first ramp, the fits are filled and both passes of [`Profile::take`] run,
    /// and those it rules out find nothing and check no candidate.
    #[test]
    fn small_rests_ruled_out_take_nothing() {
        let (mut ruled_out, mut kept) = (0, 0);
        for (jerk, groups, total) in units_all_alike(48) {
            let Group { a, b, c, .. } = groups[0];
            let (mut profile, fits) = filled(jerk, &groups, total);
            for rest in 1..a {
                if small_rest_may_fit(rest, a, b, c) {
                    kept += 1;
                    continue;
                }
                ruled_out += 1;
                assert_takes_nothing(&mut profile, &fits, rest, &groups);
            }
        }
        assert!(ruled_out > 1_000 && kept > 1_000, "{ruled_out} {kept}");
    }

    /// The room of `J` = `jerk` units as `groups`, `total` cycles, and its fits.
    fn filled(jerk: u64, groups: &[Group; 2], total: u64) -> (Profile, Fits) {
        let mut profile = Profile::new(wide(jerk));
        profile.set(groups, total);
        let mut fits = Fits::EMPTY;
        fits.fill(&profile);
        (profile, fits)
    }

    /// Neither pass of [`Profile::take`] finds pairs for `rest` in `fits`, or checks a candidate.
    fn assert_takes_nothing(profile: &mut Profile, fits: &Fits, rest: u64, groups: &[Group; 2]) {
        for apart in [true, false] {
            let mut checks = 0;
            let taken = profile.take(rest, apart, &mut checks, fits);
            assert!(taken.is_none(), "{groups:?} {rest}");
            assert_eq!(checks, 0, "{groups:?} {rest}");
        }
    }

    /// Where [`bands_may_take`] rules a rest out, [`Profile::take`] finds no candidate for it,
    /// in either pass: every main move of up to 48 cycles with a first ramp of 2 cycles or more
    /// and a jerk of 1 to 3 raw units, with early units and without, every rest up to the
    /// pairs' reach.
    #[test]
    fn rests_the_bands_rule_out_take_nothing() {
        let (mut ruled_out, mut kept) = (0, 0);
        for (jerk, groups, total) in with_early_units(48, 3) {
            let [Group { a, b, c, .. }, early] = groups;
            if a < 2 {
                continue;
            }
            let (mut profile, fits) = filled(jerk, &groups, total);
            for rest in 1..=reach(total, a) {
                if bands_may_take(rest, (a, b, c), early.count > 0) {
                    kept += 1;
                    continue;
                }
                ruled_out += 1;
                assert_takes_nothing(&mut profile, &fits, rest, &groups);
            }
        }
        assert!(ruled_out > 100_000 && kept > 100_000, "{ruled_out} {kept}");
    }

    /// No main move [`plan`] makes with a first ramp of one cycle has more than [`MAX_FITS`]
    /// fits of a width (the debug assertion in [`Fits::fill_from_room`]): every one of up to
    /// [`LONGEST`] + [`COUNTS`] cycles, with early units and without.
    #[test]
    fn no_main_move_has_more_fits_than_the_table_holds() {
        let mut most = [0; WIDEST as usize];
        for (jerk, groups, total) in with_early_units(LONGEST + COUNTS, 2) {
            if groups[0].a == 1 {
                let (_, fits) = filled(jerk, &groups, total);
                for (most, &len) in most.iter_mut().zip(&fits.lens) {
                    *most = (*most).max(len);
                }
            }
        }
        // The table is full for some: the assertion had something to check.
        assert_eq!(most, [MAX_FITS; WIDEST as usize]);
    }

    /// Every main move of `J` units all alike (no early units) of 4 to `most` cycles with a
    /// jerk of 1 to 3 raw units: `(J, groups, cycles)`.
    fn units_all_alike(most: u64) -> impl Iterator<Item = (u64, [Group; 2], u64)> {
        units_all_alike_up_to(most, 3)
    }

    /// As [`units_all_alike`], with a jerk of 1 to `most_jerk` raw units.
    fn units_all_alike_up_to(
        most: u64,
        most_jerk: u64,
    ) -> impl Iterator<Item = (u64, [Group; 2], u64)> {
        (1..=most_jerk).flat_map(move |jerk| {
            (4..=most).flat_map(move |total| {
                (1..=total / 4).flat_map(move |a| {
                    (a..=total / 2 - a).map(move |b| {
                        let c = total - a - b;
                        let group = |count, c| Group { count, a, b, c };
                        (jerk, [group(jerk, c), group(0, c - 1)], total)
                    })
                })
            })
        })
    }

    /// [`Fits::fill_closed`] finds the fits [`Fits::fill_from_room`] finds from the room, in the
    /// same order, with the same reach: every main move of up to 48 cycles with a first ramp of
    /// 2 cycles or more and a jerk of 1 to 3 raw units, with early units and without.
    #[test]
    fn the_fits_in_closed_form_are_the_rooms() {
        let mut compared = [0; 2];
        for (jerk, groups, total) in with_early_units(48, 3) {
            let mut profile = Profile::new(wide(jerk));
            profile.set(&groups, total);
            let Some(shape) = profile.shape.filter(|shape| shape.0 >= 2) else {
                continue;
            };
            let (mut closed, mut from_room) = (Fits::EMPTY, Fits::EMPTY);
            closed.fill_closed(shape, total as i32);
            from_room.fill_from_room(&profile);
            for w in 1..=WIDEST as i32 {
                let found = |fits: &Fits| {
                    let of_width = fits.of_width(w).iter();
                    let found: Vec<_> = of_width
                        .map(|fit| (fit.starts, fit.raises, fit.reach))
                        .collect();
                    (found, fits.reach[w as usize - 1])
                };
                assert_eq!(found(&closed), found(&from_room), "{groups:?}, w {w}");
            }
            compared[usize::from(groups[1].count > 0)] += 1;
        }
        assert!(compared[0] > 1_000 && compared[1] > 1_000, "{compared:?}");
    }

    /// [`Profile`]'s `doubles` is set exactly where the jerk has room for two impulses of a
    /// sign on every cycle with room for one (with a jerk of 1 raw unit, never: only the tiniest
    /// main moves, with no phase of zero jerk, have that room, and they are left out): every
    /// main move of up to 32 cycles with a jerk of 1 to 7 raw units, with and without early
    /// units.
    #[test]
    fn room_for_two_where_doubles_says() {
        let mut set = [0; 2];
        for (jerk, groups, total) in with_early_units(32, 7) {
            let mut profile = Profile::new(wide(jerk));
            profile.set(&groups, total);
            let doubles = profile.doubles;
            profile.ready();
            let limit = jerk as i64;
            let mut lowering = profile.lower().iter().flat_map(|&(from, to)| from..=to);
            let mut raising = profile.raise().iter().flat_map(|&(from, to)| from..=to);
            let room_for_two = lowering.all(|n| profile.jerk_at(n) - 2 >= -limit)
                && raising.all(|n| profile.jerk_at(n) + 2 <= limit);
            assert!(!doubles || room_for_two, "{groups:?}");
            if jerk >= 2 {
                assert_eq!(doubles, room_for_two, "{groups:?}");
            }
            set[usize::from(groups[1].count > 0)] += usize::from(doubles);
        }
        assert!(set[0] > 1_000 && set[1] > 1_000, "{set:?}");
    }

    /// Every main move [`plan`] makes of 4 to `most` cycles with a jerk of 1 to `most_jerk` raw
    /// units: [`units_all_alike_up_to`], and with each count of early units they can have
    /// (`1 ..= J − 1`, where there is a cruise).
    fn with_early_units(most: u64, most_jerk: u64) -> impl Iterator<Item = (u64, [Group; 2], u64)> {
        units_all_alike_up_to(most, most_jerk).flat_map(|(jerk, [full, _], total)| {
            (0..jerk)
                .filter(move |&early| early == 0 || full.c > full.a + full.b)
                .map(move |early| {
                    let groups = [
                        Group {
                            count: jerk - early,
                            ..full
                        },
                        Group {
                            count: early,
                            c: full.c - 1,
                            ..full
                        },
                    ];
                    (jerk, groups, total)
                })
        })
    }

    /// [`Profile::set`]'s room in closed form is the room the pieces give ([`Profile::ready`]):
    /// every main move of up to 40 cycles with a jerk of 1 to 3 raw units, with early units and
    /// without.
    #[test]
    fn the_room_in_closed_form_is_the_pieces_room() {
        let mut compared = [0; 2];
        for (jerk, groups, total) in with_early_units(40, 3) {
            let mut profile = Profile::new(wide(jerk));
            profile.set(&groups, total);
            assert!(profile.pending.is_some());
            let room = (profile.lower().to_vec(), profile.raise().to_vec());
            profile.ready();
            assert_eq!(
                room,
                (profile.lower().to_vec(), profile.raise().to_vec()),
                "{groups:?}"
            );
            compared[usize::from(groups[1].count > 0)] += 1;
        }
        assert!(compared[0] > 1_000 && compared[1] > 1_000, "{compared:?}");
    }

    /// The jerk by pieces, against the jerk summed cycle by cycle, and the velocity at least
    /// [`SLOW`] on every cycle of `fast` (not empty for most of these moves); and the groups
    /// end at rest with their distance.
    #[test]
    fn the_pieces_and_the_fast_cycles_are_the_summed_jerks() {
        let mut fast_cycles = 0;
        let longer = [(3, 5), (4, 6), (2, 9)].into_iter().flat_map(|(a, b)| {
            [(1, 0), (2, 1)].map(|(count, early)| {
                let c = a + b + 12;
                let group = |count, c| Group { count, a, b, c };
                ([group(count, c), group(early, c - 1)], a + b + c)
            })
        });
        for (groups, total) in main_moves().into_iter().chain(longer) {
            let profile = Profile::of(&groups, wide(7), total);
            let states = summed(&groups, total);
            for (n, &(jerk, _, velocity)) in states.iter().enumerate().take(total as usize) {
                let n = n as i32;
                assert_eq!(profile.jerk_at(n), jerk, "{groups:?}, cycle {n}");
                if (profile.fast.0..=profile.fast.1).contains(&n) {
                    assert!(velocity >= SLOW, "{groups:?}, cycle {n}: {velocity}");
                    fast_cycles += 1;
                }
            }
            // At rest after the last cycle.
            assert_eq!(states[total as usize], (0, 0, 0), "{groups:?}");
            assert_eq!(states[total as usize + 1], (0, 0, 0), "{groups:?}");
        }
        // By hand: 4·tb(3, 5, 11) + 3·tb(3, 5, 10) covers 4·3·5·11 + 3·3·5·10 = 1,110.
        let group = |count, c| Group {
            count,
            a: 3,
            b: 5,
            c,
        };
        let states = summed(&[group(4, 11), group(3, 10)], 19);
        assert_eq!(states.iter().map(|s| s.2).sum::<i64>(), 1_110);
        assert!(fast_cycles > 200, "{fast_cycles}");
    }

    /// [`Profile::fits`] against the pairs' jerk, acceleration and velocity summed cycle by
    /// cycle over the whole move, for every placement of one pair and a sample of two: the
    /// same answer each time.
    #[test]
    fn fits_is_the_cycle_by_cycle_check() {
        let jerk_limit = 7;
        let limits = wide(jerk_limit);
        // Placements checked (one pair, two), and of them those that fit.
        let mut checked = [0usize; 2];
        let mut fitting = [0usize; 2];
        for (groups, total) in main_moves() {
            if groups[0].count + groups[1].count > jerk_limit {
                continue;
            }
            let profile = Profile::of(&groups, limits, total);
            let main = summed(&groups, total);
            let exact = |pairs: &[Pair]| fits_exactly(&main, pairs, limits);
            let t = total as i32;
            // Pairs as a Fit places them: inside the move, ending before its last cycle.
            let placed: Vec<Pair> = (0..t)
                .flat_map(|s| (1..=WIDEST as i32).map(move |w| (s, w)))
                .flat_map(|(s, w)| ((w + 1)..t).map(move |k| (s, w, k)))
                .filter(|&(s, w, k)| s + k + w < t)
                .collect();
            for &pair in &placed {
                let fits = profile.fits(&[pair]);
                assert_eq!(fits, exact(&[pair]), "{groups:?}: {pair:?}");
                checked[0] += 1;
                fitting[0] += usize::from(fits);
            }
            for (i, &first) in placed.iter().enumerate().step_by(5) {
                for &second in placed[i..].iter().step_by(7) {
                    let pairs = [first, second];
                    let fits = profile.fits(&pairs);
                    assert_eq!(fits, exact(&pairs), "{groups:?}: {pairs:?}");
                    checked[1] += 1;
                    fitting[1] += usize::from(fits);
                }
            }
        }
        // Both answers, often: the comparison is not of two constants.
        for (checked, fitting) in checked.into_iter().zip(fitting) {
            assert!(
                fitting > checked / 10 && fitting < checked * 9 / 10,
                "{fitting} of {checked}"
            );
        }
        assert!(checked[0] > 1_000 && checked[1] > 10_000, "{checked:?}");
    }

    /// Whether `pairs` taken off the main move `main` ([`summed`]) keep its jerk and
    /// acceleration within `limits` and its velocity at least zero, cycle by cycle.
    fn fits_exactly(main: &[(i64, i64, i64)], pairs: &[Pair], limits: Limits64) -> bool {
        let (mut acceleration, mut velocity) = (0i64, 0i64);
        main.iter().enumerate().all(|(n, &(main_jerk, _, _))| {
            let jerk = main_jerk
                + pairs
                    .iter()
                    .flat_map(|&pair| impulses_of(pair))
                    .filter(|&(at, _)| at == n as i32)
                    .map(|(_, change)| change)
                    .sum::<i64>();
            acceleration += jerk;
            velocity += acceleration;
            jerk.abs() <= limits.jerk as i64
                && acceleration.abs() <= limits.acceleration as i64
                && velocity >= 0
        })
    }

    /// One pair wider than [`WIDEST`] ([`Tries::wide_pairs`]), of a width up to the main
    /// move's plateau `a·b`, fits exactly where [`Profile::fits`] says it does, its velocity
    /// never looked at on the main move's fast cycles: a single pair's dip is never deeper
    /// than the main move is fast.
    #[test]
    fn a_wide_pair_fits_where_fits_says() {
        let mut checked = 0usize;
        let mut fitting = 0usize;
        for (a, b) in [(2, 2), (2, 3), (3, 5), (4, 6), (5, 5), (4, 9), (6, 7)] {
            for extra in [0, 1, 3, 20] {
                let c = a + b + 1 + extra;
                let total = a + b + c;
                for (count, early) in [(1, 0), (1, 1), (3, 0), (2, 2), (4, 3), (5, 2)] {
                    let group = |count, c| Group { count, a, b, c };
                    let groups = [group(count, c), group(early, c - 1)];
                    let limits = wide(count + early);
                    let profile = Profile::of(&groups, limits, total);
                    let main = summed(&groups, total);
                    let t = total as i32;
                    for w in WIDEST as i32 + 1..=WIDEST_ALONE.min((a * b) as i32) {
                        for s in 0..t {
                            for k in (w + 1..t).filter(|&k| s + k + w < t) {
                                let fits = profile.fits(&[(s, w, k)]);
                                assert_eq!(
                                    fits,
                                    fits_exactly(&main, &[(s, w, k)], limits),
                                    "{groups:?}: {:?}",
                                    (s, w, k)
                                );
                                checked += 1;
                                fitting += usize::from(fits);
                            }
                        }
                    }
                }
            }
        }
        assert!(
            checked > 10_000 && fitting > checked / 20 && fitting < checked * 19 / 20,
            "{fitting} of {checked}"
        );
    }

    /// Moves from fractional positions whose main moves leave rests that no two pairs of
    /// widths up to [`WIDEST`] take on any of the four cycle counts (the search planned them,
    /// at 18,000–22,000 Cortex-M4 instructions), and one wide pair does. By hand, 119,285 raw
    /// units with a jerk of 7: six units of `tb(17, 24, 42)` and one of `tb(17, 24, 41)` are
    /// `102,816 + 16,728 = 119,544`, a pair of width 7 and span 37 takes the 259 over (83
    /// cycles; `⌊∛(32·119,285/7)⌋ = 81`).
    #[test]
    fn one_wide_pair_takes_what_two_narrow_ones_cannot() {
        for (distance, jerk) in [
            (119_285, 7),
            (120_066, 7),
            (75_614, 6),
            (75_608, 6),
            (120_811, 4),
        ] {
            let floor = cube_root(32 * distance / jerk);
            let total = planned(distance, jerk).plan.total;
            assert!(
                total <= floor + 3,
                "{distance}, J {jerk}: {total} > {floor} + 3"
            );
        }
        assert_eq!(6 * 17 * 24 * 42 + 17 * 24 * 41 - 7 * 37, 119_285);
    }

    /// Moves from fractional positions whose every main move's rest is beyond what narrow and
    /// single wide pairs take, on all four cycle counts (they went on to the search, 20,608 to
    /// 29,518 Cortex-M4 instructions for the first four): the search's pairs of consecutive
    /// widths take a kept main move's ([`Tries::far_rests`]), within `⌊∛(32·D/J)⌋ + 3` cycles
    /// and replayed exactly (the search had planned 120,075 raw units in 84 cycles; here 82).
    #[test]
    fn far_rests_take_the_search_pairs() {
        for (distance, jerk) in [
            (82_837, 2),
            (124_655, 3),
            (121_941, 1),
            (120_075, 7),
            (120_093, 7),
        ] {
            let mut out = Schedule::EMPTY;
            assert!(
                first(distance, 1, wide(jerk), &mut out),
                "{distance}, J {jerk}"
            );
            let replay = out.replay(1, wide(jerk));
            assert!(replay.within_limits, "{distance}, J {jerk}");
            assert_eq!(replay.distance, i128::from(distance));
            let floor = cube_root(32 * distance / jerk);
            let total = out.plan.total;
            assert!(
                total <= floor + 3,
                "{distance}, J {jerk}: {total} > {floor} + 3"
            );
        }
    }

    /// Where the first span of the right residue cannot be used — a pair as wide as its span,
    /// or no starts that keep the pairs' impulses apart — the next of that residue is: these
    /// moves from fractional positions, each with a jerk of one raw unit, found no pairs for
    /// any main move that way and went on to the search (21,730 and 21,242 Cortex-M4
    /// instructions for the first two; 102,941 raw units takes `tb(32, 43, 75)` less pairs of
    /// widths 1 and 3, spans 4 and 85, where the first span of its residue, 1, is the width).
    #[test]
    fn the_next_span_of_a_residue_where_the_first_cannot_be_used() {
        for distance in [102_941, 80_549, 56_433, 129_425] {
            let mut out = Schedule::EMPTY;
            assert!(first(distance, 1, wide(1), &mut out), "{distance}");
            let replay = out.replay(1, wide(1));
            assert!(replay.within_limits, "{distance}");
            assert_eq!(replay.distance, i128::from(distance));
            let floor = cube_root(32 * distance);
            assert!(
                out.plan.total <= floor + 3,
                "{distance}: {}",
                out.plan.total
            );
        }
    }

    /// The first ramp that can cover the distance is the first of `1..=total/4` with a main
    /// move `tb(a, b, c)`, `a ≤ b`, `c ≥ a + b`, `a + b + c = total`, of `J·a·b·c ≥ D`, found by
    /// looking at each in turn, and every later one has such a main move too.
    #[test]
    fn the_shortest_first_ramp_is_the_first_that_covers() {
        for jerk in [1u64, 2, 7, 1 << 20] {
            for total in 1..70u64 {
                let most = jerk * total.pow(3) / 16 + 2;
                for distance in (1..=most).step_by((most / 500).max(1) as usize) {
                    let covers = |a: u64| {
                        (a..=total)
                            .filter(|&b| total >= 2 * (a + b))
                            .any(|b| jerk * a * b * (total - a - b) >= distance)
                    };
                    let first = (1..=total / 4).find(|&a| covers(a));
                    if let Some(first) = first {
                        assert!((first..=total / 4).all(covers), "{distance} in {total}");
                    }
                    let expected = first.unwrap_or(total / 4 + 1);
                    assert_eq!(
                        first_ramp(distance, jerk, total),
                        expected,
                        "{distance} in {total}, J {jerk}"
                    );
                }
            }
        }
    }

    /// `⌊∛(32·D/J)⌋` against its definition, and `None` where the move leaves the class.
    #[test]
    fn the_floor_of_the_optimum() {
        let floor = |distance: u64, limits: Limits64| {
            optimum_floor(scaled_distance(distance, limits.jerk)?, distance, limits)
        };
        for jerk in [1u64, 2, 3, 7, 15] {
            for distance in (2..3_000u64).step_by(7) {
                let floor = floor(distance, wide(jerk)).unwrap();
                let x = 32 * distance / jerk;
                assert!(
                    floor.pow(3) <= x && (floor + 1).pow(3) > x,
                    "{distance}, J {jerk}"
                );
            }
        }
        // 32·D ≥ 260³·J = 17,576,000·J: too long for this module (17,576,000 / 32 = 549,250).
        assert_eq!(scaled_distance(549_250, 1), None);
        assert_eq!(scaled_distance(549_249, 1), Some(32 * 549_249));
        assert_eq!(scaled_distance(2 * 549_250, 2), None);
        // The acceleration limit binds (2·A³ ≤ D·J²).
        let binding = Limits64 {
            acceleration: 3,
            ..wide(1)
        };
        assert_eq!(floor(1_000, binding), None);
    }

    /// Every distance from 4 to 3,000 raw units with a jerk of 1 (and a sample with 2 to 5):
    /// planned here within `⌊∛(32·D/J)⌋ + 3` cycles, exactly and within the limits (checked
    /// by the replay, independently of `Profile::fits`).
    #[test]
    fn every_small_distance_within_the_bound() {
        for (jerk, step) in [(1u64, 1usize), (2, 5), (3, 7), (5, 11)] {
            // From 4J: shorter moves are a pulse of one cycle (`plan_move`), or have no room.
            for distance in (4 * jerk..3_000u64).step_by(step) {
                let scaled = scaled_distance(distance, jerk).unwrap();
                let floor = optimum_floor(scaled, distance, wide(jerk)).unwrap();
                let total = planned(distance, jerk).plan.total;
                assert!(total <= floor.max(3) + 3, "{distance}, J {jerk}: {total}");
            }
        }
    }
}
