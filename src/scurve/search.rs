//! The search for a plan: the continuous-time optimum in integers, a small fixed set of integer
//! shapes around it, and the first of them, fastest first, whose remainder fits.
//!
//! Short moves where only the jerk binds are planned before any of this, as sums of unit volumes
//! ([`super::volumes`]).
//!
//! Its cost is bounded whatever the move: integer square and cube roots (a fixed number of
//! steps), at most [`MAX_SHAPES`] shapes, each solved in closed form when it is tried (fastest
//! first, so usually one), two cruise lengths and two unit mixes per shape, for each a fixed
//! number of notch-pair placements ([`super::remainder::take`]); the schedule is built once, for
//! the plan that wins. A last resort (two *fine units*, then ramps of one cycle) covers the few
//! very short moves with a large jerk that notch pairs have no room in. Where only the jerk binds
//! and the plan is more than three cycles over the optimum, or missing, [`super::pure_jerk`]
//! places notch pairs wherever the jerk has room; with a jerk of up to 15 raw units it plans
//! such moves before the shapes are tried. Before the ramps of one cycle, the ramps around
//! the optimum ([`around`]), then the same shapes once more with the pairs' widths estimated for
//! the remainder plus one unit's area ([`Move::with_unit`]), which closes the gaps between what
//! two pairs take when the jerk leaves a single unit.

use super::products::{product, saturating_product};
use super::pure_jerk;
use super::remainder::{self, place_velocity_notch, Placement};
use super::roots::{cube_root, square_root};
use super::schedule::{Limits64, Schedule, LONGEST_RUN};
use super::shape::{MainMove, Mix};
use super::tiny;
use super::volumes;
use crate::division::{div, div_ceil, div_rem};

/// One shape: ramps `(a, b)`, a unit mix, a velocity notch of `notch` units, phase V from cycle
/// `c`; `total = a + b + c` cycles.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
struct Candidate {
    mix: Mix,
    notch: u64,
    c: u64,
}

/// A shape's two candidates ([`Shape::candidates`]).
struct Candidates {
    /// The mix that meets the shape's velocity exactly or from below.
    under: Option<Candidate>,
    /// The mix from above with a velocity notch (`None` where `under` meets it exactly).
    over: Option<Candidate>,
}

impl Candidates {
    /// Both, the faster (the earlier phase V) first: as references, so that ordering them
    /// copies nothing (an array of the two candidates by value cost two copies of ~200 bytes,
    /// ~450 Cortex-M4 instructions, each time a later shape was looked at).
    fn faster_first(&self) -> [&Option<Candidate>; 2] {
        match (&self.under, &self.over) {
            (Some(u), Some(o)) if o.c < u.c => [&self.over, &self.under],
            _ => [&self.under, &self.over],
        }
    }
}

/// What decides whether [`complete`] can fit a candidate's remainder: its units (as the ramps
/// `(a, b)` and counts of the mix written with the longest ramps its units have, so two mixes
/// of the same units compare equal), phase V's cycle `c` and the velocity notch. Adjacent
/// shapes often share their units — with one unit of jerk, shape `(a, b + 1)`'s only unit of
/// kind `(a, b)` is shape `(a, b)`'s — and a remainder that did not fit once does not fit again.
#[derive(Debug, Clone, Copy)]
struct Attempt {
    a: u64,
    b: u64,
    /// Units of kinds 0 and 1, and of kinds 2 and 3, 32 bits each (each count is at most the
    /// jerk, < 2^31): plain words, compared without a call to `memcmp`.
    counts: [u64; 2],
    c: u64,
    notch: u64,
}

impl Attempt {
    fn of(candidate: &Candidate, c: u64) -> Self {
        let mix = &candidate.mix;
        let (mut a, mut b, mut counts) = (mix.a, mix.b, mix.counts);
        // No unit of the longer second ramp: the kinds (a, b − 1), (a − 1, b − 1) are the
        // longest of the mix (a, b − 1); no unit of the longer first ramp: likewise (a − 1, b).
        // Until a unit has both (a few steps: the ramps only shorten).
        while counts[0] == 0 {
            if counts[2] == 0 && b > a {
                (b, counts) = (b - 1, [counts[1], 0, counts[3], 0]);
            } else if counts[1] == 0 && a > 1 {
                (a, counts) = (a - 1, [counts[2], counts[3], 0, 0]);
            } else {
                break;
            }
        }
        Self {
            a,
            b,
            counts: [counts[0] | counts[1] << 32, counts[2] | counts[3] << 32],
            c,
            notch: candidate.notch,
        }
    }

    fn is(&self, other: &Self) -> bool {
        // Phase V's cycle first: the attempts kept mostly differ there.
        self.c == other.c
            && self.a == other.a
            && self.b == other.b
            && self.counts[0] == other.counts[0]
            && self.counts[1] == other.counts[1]
            && self.notch == other.notch
    }
}

/// The last attempts whose remainder did not fit: the duplicates come from neighbouring
/// shapes, each tried at two cruise lengths in turn. Four: with one unit of jerk, the unit
/// `(a, b)` of the first shape comes back as the second ramp's shorter kind in the third
/// shape `(a + 1, b)`, two shapes later, after three attempts (random move 275055: its
/// remainder tried a second time, ~2,100 Cortex-M4 instructions, where two were kept).
#[derive(Debug, Default)]
struct Failed {
    /// `None` until written: only the tags are cleared when a search begins.
    attempts: [Option<Attempt>; FAILED_KEPT],
    next: usize,
}

/// How many failed attempts [`Failed`] keeps.
const FAILED_KEPT: usize = 4;

impl Failed {
    fn contains(&self, attempt: &Attempt) -> bool {
        self.attempts
            .iter()
            .flatten()
            .any(|known| known.is(attempt))
    }

    fn push(&mut self, attempt: Attempt) {
        self.attempts[self.next % FAILED_KEPT] = Some(attempt);
        self.next += 1;
    }
}

/// Ramps `(a, b)` and the cruise velocity they aim at; `cycles` is the move's length if the
/// unit mix meets that velocity exactly.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
struct Shape {
    a: u64,
    b: u64,
    target: u64,
    cycles: u64,
}

/// At most this many shapes: two first ramps × four second ramps.
const MAX_SHAPES: usize = 8;

/// The shapes worth trying for a move of `distance` (2^-32 counts) within `limits`, fastest
/// first, into `found`; returns how many (filled in place: the list is a quarter of a kilobyte,
/// and a copy costs about an instruction a byte on a Cortex-M4).
///
/// The continuous optimum has jerk phases of `a* = min(A/J, √(V/J), ∛(D/2J))` cycles; the first
/// ramp is its floor or ceiling. For each, the second ramp is the one that reaches the maximum
/// velocity (`⌈V/peak⌉`) or the ones the distance allows with no cruise (the floor and ceiling
/// of the root of `peak·b·(a + b) = D`, and one shorter), whichever is shorter.
fn shapes(distance: u64, limits: Limits64, found: &mut [Shape; MAX_SHAPES]) -> usize {
    let (jerk, acceleration, velocity) = (limits.jerk, limits.acceleration, limits.velocity);
    // a* = min(⌊A/J⌋, ⌊√⌊V/J⌋⌋, ⌊∛⌊D/2J⌋⌋); a root is taken only when it can be the least:
    // ⌊√⌊V/J⌋⌋ ≥ m ⇔ V ≥ m²·J and ⌊∛⌊D/2J⌋⌋ ≥ m ⇔ D ≥ 2J·m³, a multiplication each.
    let mut a0 = div(acceleration, jerk);
    if product(a0, a0)
        .and_then(|s| product(s, jerk))
        .is_none_or(|s| s > velocity)
    {
        a0 = a0.min(square_root(div(velocity, jerk)));
    }
    let cube = product(a0, a0).and_then(|s| product(s, a0));
    if cube
        .and_then(|c| product(c, 2 * jerk))
        .is_none_or(|c| c > distance)
    {
        a0 = a0.min(cube_root(div(distance, 2 * jerk)));
    }
    let mut len = 0;
    // Cycles at the maximum velocity, ⌈D/V⌉, the same for every shape that reaches it: found
    // once, when first needed.
    let mut at_velocity = None;
    // The floor and the ceiling of a* (both 1 when a* < 1).
    // (An exclusive range: an inclusive one's iteration costs a test more each step.)
    let firsts = if a0 == 0 { 1..2 } else { a0..a0 + 2 };
    for a in firsts {
        // a ≤ √(2^46) + 1, so jerk·a < 2^55.
        let peak = (jerk * a).min(acceleration);
        let to_velocity = div_ceil(velocity, peak).max(a);
        // peak·b·(a + b) ≤ D ⇔ b ≤ (√(a² + 4D/peak) − a)/2; D/peak < 2^63, a² < 2^47.
        let (quotient, remainder) = div_rem(distance, peak);
        // ⌈D/peak⌉: with ⌈⌈D/peak⌉/b⌉ = ⌈D/(peak·b)⌉, each uncapped second ramp's cruise is then a
        // division of this (often 32 bits) by b, not of D by peak·b.
        let quotient_up = quotient + u64::from(remainder != 0);
        let root = if quotient < 1 << 60 {
            square_root(a * a + 4 * quotient)
        } else {
            // Only with a peak below 8 raw units: rare enough for the 128-bit root.
            let square = u128::from(a * a) + 4 * u128::from(quotient);
            u64::try_from(square.isqrt()).unwrap_or(u64::MAX)
        };
        let no_cruise = (root - a) / 2;
        let seconds = [
            no_cruise,
            no_cruise + 1,
            to_velocity,
            no_cruise.saturating_sub(1),
        ];
        let mut tried = [0u64; 4];
        // Indexed: iterating the array (by value or by reference) cost ~110 more Cortex-M4
        // instructions a move, ~1 % of the mean plan (random moves 100,000–100,999).
        #[allow(clippy::needless_range_loop)]
        for i in 0..seconds.len() {
            let b = seconds[i].clamp(a, to_velocity);
            if tried[..i].contains(&b) {
                continue;
            }
            tried[i] = b;
            // Past the distance's own peak, ⌊D/(a + b)⌋, a faster cruise cannot shorten the move:
            // min(x, ⌊D/(a + b)⌋) is x exactly when x·(a + b) ≤ D, which a multiplication tells
            // (a division only when the cap applies).
            let aim = if b >= to_velocity {
                velocity
            } else {
                saturating_product(peak, b)
            };
            let ramps = a + b;
            let (target, cruise) = match product(aim, ramps) {
                Some(covered) if covered <= distance => {
                    let cruise = if aim == velocity {
                        *at_velocity.get_or_insert_with(|| div_ceil(distance, velocity))
                    } else {
                        // aim = peak·b: ⌈D/(peak·b)⌉ = ⌈⌈D/peak⌉/b⌉ (see `quotient_up`).
                        div_ceil(quotient_up, b)
                    };
                    (aim, cruise)
                }
                _ => {
                    // The cap t = ⌊D/(a + b)⌋: D = t·(a + b) + r with r < a + b, so ⌈D/t⌉ =
                    // (a + b) + ⌈r/t⌉, which is (a + b) + [r > 0] once t ≥ a + b (no second
                    // division).
                    let (target, rest) = div_rem(distance, ramps);
                    if target == 0 {
                        continue;
                    }
                    let cruise = if target >= ramps {
                        ramps + u64::from(rest != 0)
                    } else {
                        div_ceil(distance, target)
                    };
                    (target, cruise)
                }
            };
            let shape = Shape {
                a,
                b,
                target,
                cycles: ramps + cruise.max(ramps),
            };
            // Fastest first (an insertion sort of at most six).
            let mut k = len;
            while k > 0 && found[k - 1].cycles > shape.cycles {
                found[k] = found[k - 1];
                k -= 1;
            }
            found[k] = shape;
            len += 1;
        }
    }
    len
}

impl Shape {
    /// The mix that meets the velocity from below, and — unless it meets it exactly — the one
    /// from above with a velocity notch.
    fn candidates(&self, distance: u64, limits: Limits64) -> Candidates {
        // Each written where it is kept, not moved there (a move copies it).
        let mut candidates = Candidates {
            under: self.candidate(true, distance, limits),
            over: None,
        };
        if !matches!(&candidates.under, Some(c) if c.mix.velocity == self.target) {
            candidates.over = self.candidate(false, distance, limits);
        }
        candidates
    }

    /// The shape with the unit mix that meets its velocity exactly or from below (`under`), or
    /// from above with a velocity notch, and the shortest cruise that covers the distance.
    fn candidate(&self, under: bool, distance: u64, limits: Limits64) -> Option<Candidate> {
        let (a, b, target) = (self.a, self.b, self.target);
        let mix = Mix::solve(a, b, limits.jerk, limits.acceleration, target, under)?;
        let notch = mix.velocity.saturating_sub(target);
        if (!under && notch == 0) || notch > b {
            return None; // the same as the first, or a notch too wide to fit
        }
        let cruise = mix.velocity - notch;
        if cruise == 0 {
            return None;
        }
        // c·velocity − notch·(c − 1) ≥ distance.
        let c = div_ceil(distance.saturating_sub(notch), cruise).max(a + b);
        Some(Candidate { mix, notch, c })
    }
}

/// Plans a move of `distance` (> 1, 2^-32 counts) in `direction` (±1) within `limits` into
/// `out`: the fastest shape whose remainder fits, else the one-cycle ramps, which always do.
/// `false` (and `out` unusable) if nothing fits.
pub(super) fn search(distance: u64, direction: i64, limits: Limits64, out: &mut Schedule) -> bool {
    let move_ = Move {
        distance,
        direction,
        limits,
        with_unit: false,
    };
    // Moves where only the jerk may bind, under 260 cycles ([`pure_jerk::is_short`]), first
    // by the planners of such moves, in turn — one test for the three, which most moves fail:
    if pure_jerk::is_short(distance, limits.jerk)
        // tiny moves with a jerk of 1 or 2 raw units from the table of their fastest plans
        // ([`tiny`]): the shapes below have the least room for their pairs there;
        && (tiny::plan(distance, direction, limits, out)
        // short moves with a jerk of 3 raw units or more as a sum of unit volumes
        // ([`volumes`]): the shapes mostly leave them remainders their pairs have no room for;
            || volumes::plan(distance, direction, limits, out)
        // with a jerk of up to 15 raw units, notch pairs anywhere the jerk has room
        // ([`pure_jerk`]): the shapes mostly leave it remainders it cannot place.
            || pure_jerk::first(distance, direction, limits, out))
    {
        return true;
    }
    let mut found = [Shape::default(); MAX_SHAPES];
    let len = shapes(distance, limits, &mut found);
    let fastest = found[..len].first().map_or(u64::MAX, |shape| shape.cycles);
    // Moves of a few cycles with a large jerk can be too short for notch pairs: there, two
    // units of the jerk kept aside take the rest as fine units. In the shortest moves they are
    // tried first and kept unless a shape is faster: there the shapes' remainders mostly do not
    // fit, and each failed attempt costs thousands of Cortex-M4 instructions (a move of 15
    // cycles with a huge jerk took 28,756, now 11,606). In other short moves they are tried if
    // no shape fit, or if only a slower one did (the faster kept). Either way the fine units'
    // main move is found first and its schedule built only if it is kept: building the plan
    // that loses aside and copying the winner over cost a second build, a clear and a copy
    // (random move 881545, 19 cycles, whose shape beat its fine units: 22,632 → 19,813
    // Cortex-M4 instructions).
    let short = fastest < SHORT_MOVE;
    let planned = if limits.jerk >= FINE_FIRST_JERK
        && fastest < FINE_FIRST
        && fine_unless_faster_shape(&move_, &found[..len], fastest, out)
    {
        true
    } else if fastest_fit(&move_, &found[..len], out) {
        !(limits.jerk > 2 && short && out.plan.total > fastest + 1) || fine_if_faster(&move_, out)
    } else {
        // Nothing planned: the fine units straight into `out`.
        limits.jerk > 2 && with_fine_units(&move_, out)
    };
    // Where only the jerk binds and the plan is more than three cycles over the optimum, or
    // missing: notch pairs wherever the jerk has room ([`pure_jerk`]); it keeps a plan it cannot
    // better.
    if pure_jerk::improve(distance, direction, limits, planned, out) {
        return true;
    }
    // Then the same shapes with the notch pairs' widths for a remainder grown by a unit's area
    // too ([`Move::with_unit`]): only after the ramps around the optimum, so that every move
    // planned without them keeps its plan (and its cost), and before the one-cycle ramps —
    // and after a plan of those ramps more than three cycles over the fastest shape (a single
    // unit whose remainder is one raw unit, which no pair takes, at each cruise: its ramps of
    // 65,537 and 65,543 cycles took 33,682,440 cycles where the unit given back and its area
    // taken by two pairs takes 3,211,297), keeping the faster.
    let with_unit = Move {
        with_unit: true,
        ..move_
    };
    if around(&move_, &found[..len], out) {
        if out.plan.total > fastest.saturating_add(3) {
            keep_if_faster(out, |aside| fastest_fit(&with_unit, &found[..len], aside));
        }
        return true;
    }
    fastest_fit(&with_unit, &found[..len], out) || one_cycle_ramps(&move_, out)
}

/// Plans a second time, with `plan`, into a schedule aside (`out` holds a plan already), and
/// keeps that one if it is shorter.
fn keep_if_faster(out: &mut Schedule, plan: impl FnOnce(&mut Schedule) -> bool) {
    let mut aside = Schedule::EMPTY;
    if plan(&mut aside) && aside.plan.total < out.plan.total {
        *out = aside;
    }
}

/// The first of `found` (fastest first) whose remainder fits, into `out`: each shape's
/// candidates at their own cruise and one cycle more (`false` if none fits).
fn fastest_fit(move_: &Move, found: &[Shape], out: &mut Schedule) -> bool {
    let (distance, limits) = (move_.distance, move_.limits);
    let len = found.len();
    let mut planned = false;
    // Candidates tried at their own cruise already, ahead of their turn: bit 2·shape + index.
    let mut tried = 0u16;
    let mut failed = Failed::default();
    // Each attempt's main move and pairs, written over the last's.
    let mut scratch = Scratch::default();
    'shapes: for (i, shape) in found[..len].iter().enumerate() {
        // The mix that meets the velocity from below, and — unless it meets it exactly — the
        // one from above with a velocity notch; the faster first.
        let candidates = shape.candidates(distance, limits);
        let ordered = candidates.faster_first();
        for (k, candidate) in ordered.into_iter().enumerate() {
            let Some(candidate) = candidate else {
                continue;
            };
            if tried & (1 << (2 * i + k)) == 0
                && complete_once(
                    candidate,
                    candidate.c,
                    move_,
                    out,
                    &mut failed,
                    false,
                    &mut scratch,
                )
            {
                planned = true;
                break 'shapes;
            }
            // A single unit has no cruise to end early: one cycle more of cruise leaves the
            // notch pairs the same remainder (or that and the unit's whole area, which
            // [`complete`] does not try where it is all that is new). Before that,
            // the later shapes' candidates as fast as this one, at their own cruise (often the
            // next second ramp with a velocity notch, at the same length). None longer than
            // this one, and every candidate tried after it here is at least as long, so the
            // plan is never longer than without this.
            if candidate.mix.units() == 1 {
                let total = candidate.mix.a + candidate.mix.b + candidate.c;
                // A candidate as fast as this one at its own cruise, once (bit `2·shape + index`
                // of `tried`).
                let mut as_fast = |bit: u16, early: &Candidate| {
                    if tried & bit != 0 || early.mix.a + early.mix.b + early.c > total {
                        return false;
                    }
                    tried |= bit;
                    complete_once(early, early.c, move_, out, &mut failed, false, &mut scratch)
                };
                // First this shape's other candidate: with one unit of jerk, a first ramp's
                // unit under the velocity is often the shorter kind of the shape before (a
                // remainder that failed already), and its unit over it, with a velocity notch,
                // lands where a later shape's would — before that later shape's and its
                // neighbours' candidates are worked out and tried (random move 1449522, a jerk
                // of one raw unit: one failed attempt and three shapes' candidates, about 3,300
                // Cortex-M4 instructions).
                if let (0, Some(sibling)) = (k, ordered[1]) {
                    if as_fast(1 << (2 * i + 1), sibling) {
                        planned = true;
                        break 'shapes;
                    }
                }
                for (j, later) in found[..len].iter().enumerate().skip(i + 1) {
                    if later.cycles > total {
                        break;
                    }
                    let candidates = later.candidates(distance, limits);
                    for (m, early) in candidates.faster_first().into_iter().enumerate() {
                        let Some(early) = early else {
                            continue;
                        };
                        if as_fast(1 << (2 * j + m), early) {
                            planned = true;
                            break 'shapes;
                        }
                    }
                }
            }
            if complete_once(
                candidate,
                candidate.c + 1,
                move_,
                out,
                &mut failed,
                true,
                &mut scratch,
            ) {
                planned = true;
                break 'shapes;
            }
        }
    }
    planned
}

/// Plans a move whose maximum velocity is reached in one cycle (`V ≤ min(J, A)`) into `out`:
/// then ramps of one cycle ([`one_cycle_ramps`]) are the fastest plan there is. Every moving cycle
/// is at most `V`, and coming to rest takes two cycles more (the velocity to 0, then the
/// acceleration), so no plan is shorter than `⌈D/V⌉ + 2` cycles, which these ramps take (one
/// more only when two cycles of cruise would jerk past the limit). `false` otherwise.
pub(super) fn at_velocity_in_one_cycle(
    distance: u64,
    direction: i64,
    limits: Limits64,
    out: &mut Schedule,
) -> bool {
    limits.velocity <= limits.jerk.min(limits.acceleration)
        && one_cycle_ramps(
            &Move {
                distance,
                direction,
                limits,
                with_unit: false,
            },
            out,
        )
}

/// A move this many cycles long or more has room for notch pairs wherever a shape fits.
const SHORT_MOVE: u64 = 100;

/// Moves whose fastest shape is shorter than this are planned with fine units first
/// ([`search`]): measured on the Cortex-M4 probe, a bound of 24 took the first 5,000 random
/// moves' worst from 19,680 to 18,011 instructions and nine of the 39 over 20,000 among 100,000
/// under it, where 100 (every short move) cost moves of 30 to 100 cycles a failed or slower
/// fine plan first (worst 26,702).
const FINE_FIRST: u64 = 24;

/// ... and whose jerk is at least this (raw units): with a jerk of a few raw units (what a stop
/// leaves, [`super::pure_jerk`]'s moves) two units kept aside are most of it, and fine units
/// first there took the median of 3,000 such moves from 9,770 to 13,969 Cortex-M4 instructions.
const FINE_FIRST_JERK: u64 = 1 << 16;

/// The plan with two units of jerk, acceleration and velocity kept aside for two fine units,
/// fastest shape first ([`fine_main_move`]), into `out`.
fn with_fine_units(move_: &Move, out: &mut Schedule) -> bool {
    let mut scratch = Scratch::default();
    fine_main(move_, &mut scratch)
        .is_some_and(|ramps| finish(&scratch.main, &scratch.placement, ramps, move_, out))
}

/// The fine units' plan ([`with_fine_units`]) into `out` unless a shape's ([`fastest_fit`],
/// planned into `out` first where it may be faster: the fine units' main move is longer than
/// the `fastest` shape) is faster; `false` (`out` untouched) if the fine units have no plan.
/// Where the shape is faster, the fine units' schedule is never built.
fn fine_unless_faster_shape(
    move_: &Move,
    found: &[Shape],
    fastest: u64,
    out: &mut Schedule,
) -> bool {
    let mut scratch = Scratch::default();
    let Some(ramps) = fine_main(move_, &mut scratch) else {
        return false;
    };
    let total = scratch.main.total();
    if total > fastest && fastest_fit(move_, found, out) && out.plan.total < total {
        return true;
    }
    // `finish` cannot fail here: `fine_main` kept only a main move it can build.
    finish(&scratch.main, &scratch.placement, ramps, move_, out)
}

/// Replaces the plan in `out` with the fine units' ([`with_fine_units`]) if theirs is shorter;
/// their schedule is built only then, over the other (`fine_main` kept only a main move it can
/// build). Returns whether `out` holds a plan.
fn fine_if_faster(move_: &Move, out: &mut Schedule) -> bool {
    let mut scratch = Scratch::default();
    match fine_main(move_, &mut scratch) {
        Some(ramps) if scratch.main.total() < out.plan.total => {
            finish(&scratch.main, &scratch.placement, ramps, move_, out)
        }
        _ => true,
    }
}

/// The fine units' main move ([`with_fine_units`]), written into `scratch`: the ramps `(a, b)`
/// its schedule is built with, or `None` if no shape has one.
fn fine_main(move_: &Move, scratch: &mut Scratch) -> Option<(u64, u64)> {
    let limits = move_.limits;
    let spare = Limits64 {
        jerk: limits.jerk - 2,
        acceleration: limits.acceleration - 2,
        velocity: limits.velocity - 2,
    };
    let mut found = [Shape::default(); MAX_SHAPES];
    let len = shapes(move_.distance, spare, &mut found);
    // Each attempt's main move written over the last's, as [`complete`]'s (its placement
    // stays empty: fine units take the whole remainder).
    for shape in &found[..len] {
        // Looked at where it was returned, not moved out of the `Option` (a copy).
        let candidate = shape.candidate(true, move_.distance, spare);
        let Some(candidate) = &candidate else {
            continue;
        };
        for extra in 0..2 {
            if fine_main_move(candidate, candidate.c + extra, move_, scratch) {
                return Some((candidate.mix.a, candidate.mix.b));
            }
        }
    }
    None
}

/// What is being planned: the distance (2^-32 counts), the direction (±1), the limits.
#[derive(Debug, Clone, Copy)]
struct Move {
    distance: u64,
    direction: i64,
    limits: Limits64,
    /// Whether [`remainder::take`] estimates the widths of two pairs for the remainder with one
    /// unit given back (its cruise kept) instead of the remainder alone: the second search's.
    with_unit: bool,
}

/// The early units of `mix` with phase V from cycle `c` that take the most of `over` (2^-32
/// counts), largest area first, and what they leave.
#[inline]
fn early_units(mix: &Mix, c: u64, mut over: u64) -> ([u64; 4], u64) {
    let areas = mix.areas();
    let kinds = mix.kinds();
    let mut early = [0u64; 4];
    for k in 0..4 {
        // A unit can end its cruise early only if it still has a cruise (c − 1 ≥ aₖ + bₖ).
        if areas[k] > 0 && mix.counts[k] > 0 && over >= areas[k] && c > kinds[k].0 + kinds[k].1 {
            let units = div(over, areas[k]).min(mix.counts[k]);
            early[k] = units;
            over -= units * areas[k];
        }
    }
    (early, over)
}

/// The distance `mix` covers with phase V from cycle `c` and a velocity notch of `notch` units
/// (which takes `notch·(c − 1)`): `c·velocity − notch·(c − 1)`, or `None` past 64 bits.
fn covered(mix: &Mix, c: u64, notch: u64) -> Option<u64> {
    product(c, mix.velocity)?.checked_sub(product(notch, c - 1)?)
}

/// The plan of `candidate` with phase V from cycle `c`, into `out`, if its remainder fits.
///
/// **How a move lands exactly.** The main move with phase V from cycle `c` covers
/// `c·velocity` (less the velocity notch's share), at least the distance: every unit of area
/// `aₖ·bₖ` whose cruise ends one cycle early takes `aₖ·bₖ` off, so the early units, largest area
/// first, take all but a rest smaller than the smallest area. Notch pairs take that rest exactly
/// ([`remainder::take`]); if the rest is too small for them, some early units keep their cruise
/// and the rest grows by their areas until the pairs fit. The plan is then the main move less
/// the pairs: its distance is the distance, to the raw unit, by construction (in builds with
/// debug assertions [`Schedule::replay`] confirms it, with the limits).
///
/// `retried`: the same candidate with phase V one cycle earlier failed (see below for what that
/// spares).
fn complete(
    candidate: &Candidate,
    c: u64,
    move_: &Move,
    out: &mut Schedule,
    retried: bool,
    scratch: &mut Scratch,
) -> bool {
    let Scratch { main, placement } = scratch;
    let mix = &candidate.mix;
    let notch = candidate.notch;
    let Some(over) = covered(mix, c, notch).and_then(|d| d.checked_sub(move_.distance)) else {
        return false;
    };
    // A single unit whose cruise ends early here and did not one cycle earlier: the main move
    // and the remainder are that failed attempt's, and all that is new is giving the unit back
    // (a remainder grown by its whole area, which the pairs sized for the remainder rarely
    // take). Not tried: over 100,000 random moves no plan changed, and each such attempt cost a
    // few thousand Cortex-M4 instructions (17 of the 30 moves over 20,000 came under it). The
    // unit ends early, as [`early_units`] has it, where it has a cruise and `over` is at least
    // its area; the rest is then `over − area`. Decided before the early units are found.
    if retried && notch == 0 && !move_.with_unit && mix.units() == 1 {
        let kinds = mix.kinds();
        if let Some(&(a, b)) = (0..4).find(|&k| mix.counts[k] == 1).map(|k| &kinds[k]) {
            let area = a * b;
            if area > 0 && over >= area && over - area < area && c > a + b {
                return false;
            }
        }
    }
    let jerk = move_.limits.jerk;
    let areas = mix.areas();
    let (mut early, over) = early_units(mix, c, over);
    // Units given back (cruise restored) when the rest is too small for notch pairs: of the
    // kind with the most early units (the widest choice of sums).
    let give_back = (0..4).filter(|&k| early[k] > 0).max_by_key(|&k| early[k]);
    let (area, available) = give_back.map_or((0, 0), |k| (areas[k], early[k]));
    mix.write_main_move(c, early, main);
    let bounds = main.bounds();
    placement.clear();
    if notch > 0 && !place_velocity_notch(placement, notch, c, main, &bounds, jerk) {
        return false;
    }
    let Some(given) = remainder::take::<true>(
        over,
        main,
        &bounds,
        placement,
        jerk,
        (area, available),
        move_.with_unit,
    ) else {
        return false;
    };
    match give_back {
        Some(k) if given > 0 => {
            early[k] -= given;
            // Written over the first (not needed after this), not copied.
            mix.write_main_move(c, early, main);
            // Fewer early units can only move phase V later; the pairs must still fit.
            placement.fits(0, main, &main.bounds(), jerk)
                && finish(main, placement, (mix.a, mix.b), move_, out)
        }
        _ => finish(main, placement, (mix.a, mix.b), move_, out),
    }
}

/// What each attempt of [`complete`] (or [`fine_main_move`], which places no pairs) writes over
/// the last's: its main move and its notch pairs (408 bytes, which a fresh pair per attempt
/// cleared: about an instruction a byte on a Cortex-M4; 275055 of the random moves, five
/// attempts: 24,520 → 23,703 instructions).
#[derive(Default)]
struct Scratch {
    main: MainMove,
    placement: Placement,
}

/// [`complete`], unless the same units with the same `c` and notch failed already
/// ([`Attempt`]). Only a mix with a unit of its longest kind is remembered: then its ramps
/// `(a, b)` are its units' own, so nothing about it depends on how it was written — where a
/// mix without one may fail only because its nominal ramps are longer than its units' (the
/// schedule's check in [`finish`]). Only a mix without one is looked up: a mix with one is
/// written as every mix of the same units would be.
fn complete_once(
    candidate: &Candidate,
    c: u64,
    move_: &Move,
    out: &mut Schedule,
    failed: &mut Failed,
    retried: bool,
    scratch: &mut Scratch,
) -> bool {
    let longest_kind = candidate.mix.counts[0] > 0;
    if !longest_kind && failed.contains(&Attempt::of(candidate, c)) {
        return false;
    }
    if complete(candidate, c, move_, out, retried, scratch) {
        return true;
    }
    if longest_kind {
        failed.push(Attempt::of(candidate, c));
    }
    false
}

/// As [`complete`]'s main move, for a mix planned with two units of jerk to spare: one unit
/// more than fits ends its cruise early, and one or two fine units `tb(1, 1, x)` (`x` raw units
/// each, `2 ≤ x ≤ total − 2`) add back the difference. Writes that main move over `scratch`'s
/// (its placement, never written, stays empty); `false` if there is none, or none whose
/// schedule [`finish`] can build ([`Schedule::cruise`]), so that the fine units' main move is
/// known to land before it is built.
fn fine_main_move(candidate: &Candidate, c: u64, move_: &Move, scratch: &mut Scratch) -> bool {
    let main = &mut scratch.main;
    let mix = &candidate.mix;
    let Some(over) = covered(mix, c, 0).and_then(|d| d.checked_sub(move_.distance)) else {
        return false;
    };
    let (mut early, mut over) = early_units(mix, c, over);
    // Fine units add distance: one more early unit than fits (of the smallest kind that has
    // one to spare), and the fine units make up the difference — two more if that difference
    // is 1 (a fine unit of one cycle would jerk by 2).
    let mut left = 0;
    let kinds = mix.kinds();
    let areas = mix.areas();
    while over > 0 || left == 1 {
        let Some(k) = (0..4)
            .rev()
            .find(|&k| early[k] < mix.counts[k] && c > kinds[k].0 + kinds[k].1 && areas[k] > 0)
        else {
            return false;
        };
        early[k] += 1;
        left = (left + areas[k]).saturating_sub(over);
        over = over.saturating_sub(areas[k]);
    }
    mix.write_main_move(c, early, main);
    let longest = main.total().saturating_sub(2);
    match left {
        0 => {}
        x if x <= longest => main.add_fine_unit(x),
        x if x - longest >= 2 && x - longest <= longest => {
            main.add_fine_unit(longest);
            main.add_fine_unit(x - longest);
        }
        _ => return false,
    }
    // What [`Schedule::build`] requires of it.
    Schedule::cruise(main.total(), (mix.a, mix.b)).is_some()
}

/// Builds the schedule of `main` less `placement` into `out`, sealed (`false` if its phases do
/// not add up).
fn finish(
    main: &MainMove,
    placement: &Placement,
    (a, b): (u64, u64),
    move_: &Move,
    out: &mut Schedule,
) -> bool {
    if !out.build(main, placement, move_.direction, (a, b)) {
        return false;
    }
    // The planner's inequalities keep the limits and its arithmetic the distance; the tests run
    // with debug assertions, so every plan they make is replayed and checked here.
    debug_assert!(
        out.lands(move_.direction, move_.limits, move_.distance),
        "a plan that breaks a limit or misses the distance: {:?}",
        (main, placement, move_)
    );
    true
}

/// Ramps around the continuous optimum's (`a` within three of it, `b` up to six more), fastest
/// first, at most [`AROUND_TRIES`] of them: where the shapes of [`shapes`] leave a remainder no
/// notch pairs can take — mostly with a jerk of one or two raw units, where no fine units can be
/// kept aside — another pair of ramps often divides the distance better. Before the one-cycle
/// ramps, whose moves are exact but far longer. `found`: the move's [`shapes`], found by the
/// search already (their least first ramp is the optimum's, rounded down).
fn around(move_: &Move, found: &[Shape], out: &mut Schedule) -> bool {
    let (distance, limits) = (move_.distance, move_.limits);
    let a0 = found.iter().map(|s| s.a).min().unwrap_or(1);
    let mut wide = [Shape::default(); AROUND_SHAPES];
    let mut count = 0;
    for a in a0.saturating_sub(3).max(1)..=a0 + 3 {
        let Some(peak) = product(limits.jerk, a).map(|p| p.min(limits.acceleration)) else {
            continue;
        };
        for b in a..=a + 6 {
            let Some(aim) = product(peak, b).map(|v| v.min(limits.velocity)) else {
                continue;
            };
            let ramps = a + b;
            let target = aim.min(div(distance, ramps));
            if target == 0 || count == AROUND_SHAPES {
                continue;
            }
            let cruise = div_ceil(distance, target);
            wide[count] = Shape {
                a,
                b,
                target,
                cycles: ramps + cruise.max(ramps),
            };
            count += 1;
        }
    }
    let wide = &mut wide[..count];
    wide.sort_unstable_by_key(|shape| shape.cycles);
    let mut tries = 0;
    let mut failed = Failed::default();
    let mut scratch = Scratch::default();
    for shape in wide.iter() {
        let candidate = shape.candidate(true, distance, limits);
        let Some(candidate) = &candidate else {
            continue;
        };
        for extra in 0..2 {
            if tries == AROUND_TRIES {
                return false;
            }
            tries += 1;
            if complete_once(
                candidate,
                candidate.c + extra,
                move_,
                out,
                &mut failed,
                extra == 1,
                &mut scratch,
            ) {
                return true;
            }
        }
    }
    false
}

/// Shapes [`around`] lists: seven first ramps by seven second ramps.
const AROUND_SHAPES: usize = 49;

/// Attempts [`around`] makes at most (each a few thousand Cortex-M4 instructions).
const AROUND_TRIES: usize = 24;

/// The plan with ramps of one cycle: `tb(1, 1, c)` units, as many as the jerk, the
/// acceleration and the velocity allow, one early unit per raw unit of overshoot. It has no
/// remainder (its units' area is 1), so it fits every distance of at least 2 raw units: the
/// last resort.
fn one_cycle_ramps(move_: &Move, out: &mut Schedule) -> bool {
    let (distance, limits) = (move_.distance, move_.limits);
    let most = limits.jerk.min(limits.acceleration).min(limits.velocity);
    let first = distance.div_ceil(most).max(2);
    // A cruise too long for the schedule's runs (a velocity under 2^-16 counts/cycle, only
    // reached here when the jerk is below it and no other shape fit) is refused: the move then
    // gets a typed error, not a plan whose laps saturate and cut the cruise short.
    if first + 1 >= LONGEST_RUN {
        return false;
    }
    for c in first..first + 2 {
        let units = distance.div_ceil(c);
        let over = units * c - distance;
        // With c = 2 an early unit is tb(1, 1, 1), whose velocity of one cycle jerks by −2 on
        // cycle 1, where every other unit jerks by −1: `units + over` in all.
        if over > units || (c == 2 && units + over > limits.jerk) {
            continue;
        }
        let mix = Mix {
            a: 1,
            b: 1,
            counts: [units, 0, 0, 0],
            acceleration: units,
            velocity: units,
        };
        let main = mix.main_move(c, [over, 0, 0, 0]);
        if finish(&main, &Placement::default(), (1, 1), move_, out) {
            return true;
        }
    }
    false
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A mix without units of its longest kind is remembered as the mix of its units' own
    /// ramps: the same key, and the same main move (what [`complete`] decides on) at every
    /// cycle of phase V and every choice of early units.
    #[test]
    fn an_attempt_is_keyed_by_its_units() {
        for a in 2..7u64 {
            for b in a..a + 4 {
                for counts in (0..81u32).map(|n| [0, n % 3, n / 3 % 3, n / 9 % 3].map(u64::from)) {
                    if counts.iter().sum::<u64>() == 0 {
                        continue;
                    }
                    let mix = Mix {
                        a,
                        b,
                        counts,
                        acceleration: 0,
                        velocity: 0,
                    };
                    let c = 2 * (a + b) + 1;
                    let written = Candidate { mix, notch: 1, c };
                    let key = Attempt::of(&written, c);
                    let own = Mix {
                        a: key.a,
                        b: key.b,
                        counts: [
                            key.counts[0] & 0xFFFF_FFFF,
                            key.counts[0] >> 32,
                            key.counts[1] & 0xFFFF_FFFF,
                            key.counts[1] >> 32,
                        ],
                        ..mix
                    };
                    let as_own = Candidate {
                        mix: own,
                        ..written
                    };
                    assert!(Attempt::of(&as_own, c).is(&key), "{mix:?}");
                    // Early units of each kind, at that kind's place in the other writing.
                    let early = counts.map(|n| n.min(1));
                    let mut own_early = [0; 4];
                    for (k, kind) in mix.kinds().into_iter().enumerate() {
                        if counts[k] > 0 {
                            let at = own.kinds().iter().position(|&o| o == kind);
                            own_early[at.expect("a unit's kind is one of the own mix's")] =
                                early[k];
                        }
                    }
                    assert_eq!(
                        mix.main_move(c, early),
                        own.main_move(c, own_early),
                        "{mix:?} → {own:?}"
                    );
                    assert_eq!(
                        mix.main_move(c, [0; 4]),
                        own.main_move(c, [0; 4]),
                        "{mix:?} → {own:?}"
                    );
                }
            }
        }
    }

    /// Random move 275055's attempts (a jerk of one raw unit): its first shape's unit
    /// `(17439, 17440)` fails at phase V's cycle `c` and `c + 1`, the shape `(17439, 17439)`
    /// fails, and the third shape `(17440, 17440)` writes that first unit as its kind 2 — the
    /// same attempt, which [`Failed`] must still hold after the two in between (two slots had
    /// forgotten it, and its remainder was tried again), and forgets once four more failed.
    #[test]
    fn a_single_unit_met_again_two_shapes_later_is_known_to_fail() {
        let unit = |a, b, counts| Candidate {
            mix: Mix {
                a,
                b,
                counts,
                acceleration: 0,
                velocity: 0,
            },
            notch: 0,
            c: 34_881,
        };
        let first = unit(17_439, 17_440, [1, 0, 0, 0]);
        let mut failed = Failed::default();
        failed.push(Attempt::of(&first, first.c));
        failed.push(Attempt::of(&first, first.c + 1));
        let second = unit(17_439, 17_439, [1, 0, 0, 0]);
        failed.push(Attempt::of(&second, 34_883));
        let again = unit(17_440, 17_440, [0, 0, 1, 0]);
        assert!(failed.contains(&Attempt::of(&again, again.c)));
        // Another unit's attempt at the same cycle is not this one.
        assert!(!failed.contains(&Attempt::of(&unit(17_440, 17_440, [1, 0, 0, 0]), again.c)));
        for c in 1..=FAILED_KEPT as u64 {
            failed.push(Attempt::of(&second, c));
        }
        assert!(!failed.contains(&Attempt::of(&again, again.c)));
    }
}
