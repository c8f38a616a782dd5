//! The shape algebra: the main part of a move as a sum of *triple boxes*, and the *unit mix* that
//! brings its peak acceleration and peak velocity exactly to the limits.
//!
//! A triple box `tb(a, b, c)` is the velocity profile `box(a) ∗ box(b) ∗ box(c)` (the discrete
//! convolution of three runs of ones, `a ≤ b`, `c ≥ a + b`). Its jerk is `+1` for `a` cycles
//! (phase I), 0 for `b − a` (II), `−1` for `a` (III), 0 for `c − a − b` (IV, the cruise), and the
//! mirror image `−1`, 0, `+1` (V–VII). Its peak acceleration is `a`, its peak velocity `a·b`, the
//! distance it covers exactly `a·b·c` (2^-32 counts), and it takes `a + b + c` cycles.
//!
//! The main move is `J` *units*, each a triple box of its own `(aₖ, bₖ, cₖ)`, all starting on
//! cycle 0. Each unit jerks by at most one raw unit on any cycle, so `J` of them never jerk harder
//! than `J`: the jerk limit holds by construction, whatever the mix. While every unit's
//! acceleration stays on its plateau the move's acceleration is `Σ aₖ`, and while every unit
//! cruises its velocity is `Σ aₖ·bₖ`: both are sums of small integers, so a mix of four kinds,
//! `(a, b)`, `(a, b − 1)`, `(a − 1, b)` and `(a − 1, b − 1)`, reaches the limits to the raw unit
//! ([`Mix::solve`]).

use super::products::product;
use crate::division::{div, div_ceil, div_rem, rem};

/// One group of identical units: `count · tb(a, b, c)`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub(super) struct Group {
    /// How many units (raw jerk units) the group holds.
    pub count: u64,
    /// Cycles of phase I (and III, V, VII).
    pub a: u64,
    /// Cycles from the start to the end of phase II (`a ≤ b`).
    pub b: u64,
    /// The cycle on which phase V starts (`c ≥ a + b`).
    pub c: u64,
}

impl Group {
    /// The group's jerk on cycle `n`, raw units: `count` times the unit's ±1 or 0, as the sum of
    /// its eight corners up to `n` ([`corners`]).
    pub fn jerk_at(&self, n: u64) -> i64 {
        let unit: i64 = corners(self.a, self.b, self.c)
            .iter()
            .filter(|&&(at, _)| n >= at)
            .map(|&(_, sign)| sign)
            .sum();
        unit * self.count as i64
    }

    /// The group's velocity on cycle `n`, raw units: `count · (box(a)∗box(b)∗box(c))(n)`. The
    /// profile is symmetric about its middle, so the rising half tells it all: there it is the
    /// running sum of the trapezoid `box(a)∗box(b)`, in closed form per phase. Every value is at
    /// most `count·a·b`, the cruise velocity, so 64 bits hold it.
    pub fn velocity_at(&self, n: u64) -> u64 {
        let (a, b) = (self.a, self.b);
        let total = a + b + self.c;
        if n + 2 >= total {
            return 0;
        }
        let m = n.min(total - 3 - n);
        let rise = if m < a {
            (m + 1) * (m + 2) / 2
        } else if m < b {
            a * (m + 1) - a * (a - 1) / 2
        } else if m + 2 < a + b {
            a * b - (a + b - 1 - m) * (a + b - 2 - m) / 2
        } else {
            a * b
        };
        rise * self.count
    }
}

/// The eight corners of a triple box `tb(a, b, c)`: the cycles where its jerk changes, and by
/// how much (±1), in the order they come.
pub(super) fn corners(a: u64, b: u64, c: u64) -> [(u64, i64); 8] {
    [
        (0, 1),
        (a, -1),
        (b, -1),
        (a + b, 1),
        (c, -1),
        (c + a, 1),
        (c + b, 1),
        (c + a + b, -1),
    ]
}

/// At most this many groups: four kinds, each with or without its cruise one cycle shorter, and
/// two fine units.
pub(super) const MAX_GROUPS: usize = 10;

/// The main move: groups of units whose heights add up to at most the jerk limit.
#[derive(Debug, Clone, Copy, Default)]
pub(super) struct MainMove {
    /// The groups in `[0, len)`; those after them are not the move's (a main move written over
    /// another, [`Mix::write_main_move`], leaves them as they were).
    groups: [Group; MAX_GROUPS],
    len: usize,
}

/// Main moves are equal when their groups are.
impl PartialEq for MainMove {
    fn eq(&self, other: &Self) -> bool {
        self.groups() == other.groups()
    }
}

impl Eq for MainMove {}

impl MainMove {
    /// The groups.
    pub fn groups(&self) -> &[Group] {
        &self.groups[..self.len]
    }

    /// Adds a *fine unit* `tb(1, 1, cycles)`: a velocity of one raw unit for `cycles` cycles
    /// from the first, `cycles` raw units of distance. (In place: a main move is a few hundred
    /// bytes, which a move by value copied, about an instruction a byte on a Cortex-M4.)
    pub fn add_fine_unit(&mut self, cycles: u64) {
        self.push(Group {
            count: 1,
            a: 1,
            b: 1,
            c: cycles,
        });
    }

    /// The move of `groups` (those without a unit left out).
    pub fn of_groups(groups: &[Group]) -> Self {
        let mut m = Self::default();
        for &g in groups {
            m.push(g);
        }
        m
    }

    fn push(&mut self, group: Group) {
        if group.count > 0 && group.a > 0 && self.len < MAX_GROUPS {
            self.groups[self.len] = group;
            self.len += 1;
        }
    }

    /// The jerk on cycle `n`, raw units.
    pub fn jerk_at(&self, n: u64) -> i64 {
        self.groups().iter().map(|g| g.jerk_at(n)).sum()
    }

    /// The velocity on cycle `n`, raw units.
    pub fn velocity_at(&self, n: u64) -> u64 {
        self.groups().iter().map(|g| g.velocity_at(n)).sum()
    }

    /// The largest of `f` over the groups (0 when empty).
    pub fn most(&self, f: impl Fn(&Group) -> u64) -> u64 {
        self.groups().iter().map(f).max().unwrap_or(0)
    }

    /// The longest first ramp, second ramp and phase V start `(a, b, c)` over the main units:
    /// the groups but fine units `tb(1, 1, x)` (whose `x` may be longer than every other
    /// unit's phase V start), unless there are only those (a second pass, then); zeros when
    /// empty.
    pub fn longest_units(&self) -> (u64, u64, u64) {
        let longest = |fine: bool| {
            self.groups()
                .iter()
                .filter(|g| fine || g.a + g.b > 2)
                .fold((0, 0, 0), |(a, b, c), g| {
                    (a.max(g.a), b.max(g.b), c.max(g.c))
                })
        };
        match longest(false) {
            (0, _, _) => longest(true),
            units => units,
        }
    }

    /// Cycles of the move: the longest unit's.
    pub fn total(&self) -> u64 {
        self.most(|g| g.a + g.b + g.c)
    }

    /// The phase boundaries every unit agrees on: where the move's jerk, acceleration and
    /// velocity have a known sign, whatever the mix. See [`Bounds`].
    pub fn bounds(&self) -> Bounds {
        // One pass over the groups for all eleven extremes (not one per extreme).
        let Some((first, rest)) = self.groups().split_first() else {
            return Bounds::default();
        };
        let mut bounds = Bounds {
            last_rise_start: first.a,
            first_fall_end: first.b,
            rise_end: first.a + first.b,
            first_deceleration: first.c,
            deceleration_jerked: first.c + first.a,
            first_landing: first.c + first.b,
            total: first.a + first.b + first.c,
            floor: *first,
        };
        for g in rest {
            bounds.last_rise_start = bounds.last_rise_start.max(g.a);
            bounds.first_fall_end = bounds.first_fall_end.min(g.b);
            bounds.rise_end = bounds.rise_end.max(g.a + g.b);
            bounds.first_deceleration = bounds.first_deceleration.min(g.c);
            bounds.deceleration_jerked = bounds.deceleration_jerked.max(g.c + g.a);
            bounds.first_landing = bounds.first_landing.min(g.c + g.b);
            bounds.total = bounds.total.max(g.a + g.b + g.c);
            bounds.floor.count += g.count;
            bounds.floor.a = bounds.floor.a.min(g.a);
            bounds.floor.b = bounds.floor.b.min(g.b);
            bounds.floor.c = bounds.floor.c.min(g.c);
        }
        bounds
    }
}

/// Where the main move's jerk and acceleration have a known sign (cycles, 0 = the first step):
///
/// - jerk ≥ 0 on `[0, first_fall_end)`, `[rise_end, first_deceleration)` and
///   `[deceleration_jerked, total)` (no unit in phase III or V), so one unit lower fits there;
/// - jerk ≤ 0 on `[last_rise_start, first_landing)` (no unit in phase I or VII), so one unit
///   higher fits there;
/// - acceleration ≥ 0 before `first_deceleration`, ≤ 0 from `rise_end − 1` on.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub(super) struct Bounds {
    /// The latest end of phase I.
    pub last_rise_start: u64,
    /// The earliest start of phase III.
    pub first_fall_end: u64,
    /// The latest end of phase III (`max(a + b)`).
    pub rise_end: u64,
    /// The earliest start of phase V (`min c`).
    pub first_deceleration: u64,
    /// The latest end of phase V (`max(c + a)`).
    pub deceleration_jerked: u64,
    /// The earliest start of phase VII (`min(c + b)`).
    pub first_landing: u64,
    /// Cycles of the move.
    pub total: u64,
    /// All the units as one group with the shortest ramps and cruise of any: its velocity is
    /// at most the move's on every cycle (`box(m) ≤ box(n)` pointwise for `m ≤ n`, and a
    /// convolution of non-negative boxes keeps that order), and it is still a triple box
    /// (`min a ≤ min b`, `min c ≥ min a + min b`, as each group's are).
    pub floor: Group,
}

/// A unit mix: how many units of each kind, with ramps `(a, b)`. Kinds: `(a, b)`,
/// `(a, b − 1)`, `(a − 1, b)`, `(a − 1, b − 1)`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) struct Mix {
    /// Ramps of the first kind.
    pub a: u64,
    /// Ramps of the first kind.
    pub b: u64,
    /// Units of each kind.
    pub counts: [u64; 4],
    /// Peak acceleration `Σ aₖ`, raw units.
    pub acceleration: u64,
    /// Cruise velocity `Σ aₖ·bₖ`, raw units.
    pub velocity: u64,
}

impl Mix {
    /// How many units, of every kind.
    pub fn units(&self) -> u64 {
        self.counts.iter().sum()
    }

    /// The ramps of each kind.
    pub fn kinds(&self) -> [(u64, u64); 4] {
        let (a, b) = (self.a, self.b);
        [(a, b), (a, b - 1), (a - 1, b), (a - 1, b - 1)]
    }

    /// The mix of `jerk` units with ramps `(a, b)` (`1 ≤ a ≤ b`) whose peak acceleration is
    /// `min(acceleration, jerk·a)` exactly and whose cruise velocity is `velocity` — exactly if
    /// the kinds allow it, else the nearest below it (`under`) or above it (`!under`, to be
    /// brought down by a velocity notch). `None` if the ramps are too long or too short for
    /// that velocity.
    ///
    /// From above, when no split meets the velocity at the acceleration limit, the mix may stay
    /// further above it (as many units of the shorter second ramp as fit): the velocity notch
    /// takes the difference, where cruising from below would cost the distance over `V²` cycles
    /// (four million cycles for 2^30 counts at 2^-12 counts/cycle, one raw unit under).
    ///
    /// The acceleration fixes how many units have the shorter first ramp: `m = jerk·a − peak`
    /// (at most `jerk`, as `a` is at most one more than `acceleration / jerk`). The velocity is
    /// then `peak·b − L` where each unit given the shorter second ramp lowers it by its first
    /// ramp, `a` or `a − 1`: `a·x + (a − 1)·y = L` is solved by `y ≡ −L (mod a)` (the inverse of
    /// `a − 1` modulo `a` is `−1`), the least such `y` first.
    pub fn solve(
        a: u64,
        b: u64,
        jerk: u64,
        acceleration: u64,
        velocity: u64,
        under: bool,
    ) -> Option<Self> {
        if a == 0 || b < a {
            return None;
        }
        // jerk < 2^31 and a < 2^24, so no product here leaves 64 bits; checked all the same.
        let full_height = product(jerk, a)?;
        let peak = full_height.min(acceleration);
        // Units with the shorter first ramp; with a = 1 they are empty (a − 1 = 0). More than
        // the jerk's units (`a > ⌊A/J⌋ + 1`, ramps [`super::search`]'s `around` tries): even
        // all of them short would pass the acceleration, so there is no mix.
        let short = full_height - peak;
        let (long, short) = if a == 1 {
            (peak, 0)
        } else {
            (jerk.checked_sub(short)?, short)
        };
        let highest = product(peak, b)?;
        let lowering = highest.checked_sub(velocity)?;
        // A unit (a, b − 1) with b = a would have its ramps the other way round (its peak
        // acceleration is a − 1): second ramps are shortened only with b > a.
        let long_room = if b > a { long } else { 0 };
        // Long units made short: below the acceleration limit, or with a = 1, where a short
        // unit is no unit (fewer units, a lower peak acceleration).
        let below_limit = peak < acceleration || a == 1;
        // (x, y, z): x units (a, b − 1), y units (a − 1, b − 1) from the short ones, z long
        // units made short (a − 1, b), which only a peak below the acceleration limit allows.
        let (x, y, z) = split(lowering, a, long_room, short)
            .map(|(x, y)| (x, y, 0))
            .or_else(|| {
                (below_limit && a > 1)
                    .then(|| by_shorter_first_ramps(lowering, a, b, long_room, long))
                    .flatten()
            })
            .or_else(|| nearest(lowering, a, long_room, short, under).map(|(x, y)| (x, y, 0)))
            .or_else(|| {
                let z = if under {
                    div_ceil(lowering, b)
                } else {
                    div(lowering, b)
                };
                (below_limit && z <= long).then_some((0, 0, z))
            })
            .or_else(|| {
                // From above, at the acceleration limit and with too few short units for the
                // rest: as many units of a as fit, the rest left to the velocity notch.
                let x = div(lowering, a).min(long_room);
                (!under).then_some((x, 0, 0))
            })?;
        Some(Self {
            a,
            b,
            counts: [long - x - z, x, short - y + z, y],
            acceleration: peak - z,
            velocity: highest - a * x - (a - 1) * y - b * z,
        })
    }

    /// The main move of this mix with phase V starting on cycle `c` for every unit but the
    /// `early[k]` units of kind `k`, whose cruise is one cycle shorter.
    pub fn main_move(&self, c: u64, early: [u64; 4]) -> MainMove {
        let mut main = MainMove::default();
        self.write_main_move(c, early, &mut main);
        main
    }

    /// [`Self::main_move`] written over `main`: the search tries main move after main move, and
    /// a new one is a few hundred bytes cleared (about an instruction a byte on a Cortex-M4).
    pub fn write_main_move(&self, c: u64, early: [u64; 4], main: &mut MainMove) {
        main.len = 0;
        for (k, (a, b)) in self.kinds().into_iter().enumerate() {
            main.push(Group {
                count: self.counts[k] - early[k],
                a,
                b,
                c,
            });
            main.push(Group {
                count: early[k],
                a,
                b,
                c: c - 1,
            });
        }
    }

    /// The area `aₖ·bₖ` of one unit of each kind.
    pub fn areas(&self) -> [u64; 4] {
        self.kinds().map(|(a, b)| a * b)
    }
}

/// `a·x + b·z = lowering` with `x ≤ long_room`, `x + z ≤ long` (`z` long units given the
/// shorter first ramp, which lowers the peak acceleration too: only below its limit): `z ≡
/// lowering·b⁻¹ (mod a)` by the extended Euclid algorithm, the least such `z`.
fn by_shorter_first_ramps(
    lowering: u64,
    a: u64,
    b: u64,
    long_room: u64,
    long: u64,
) -> Option<(u64, u64, u64)> {
    let (g, inverse) = inverse_mod(rem(b, a), a);
    if rem(lowering, g) != 0 {
        return None;
    }
    let modulus = div(a, g);
    // Both factors are below the modulus (< 2^24), so the product fits.
    let z = rem(
        rem(div(lowering, g), modulus) * rem(inverse, modulus),
        modulus,
    );
    let x = div(lowering.checked_sub(product(b, z)?)?, a);
    (x <= long_room && x + z <= long).then_some((x, 0, z))
}

/// `(g, v)`: `g = gcd(value, modulus)` and `v·value ≡ g (mod modulus)`, by the extended Euclid
/// algorithm (the values are ramps, below 2^47).
fn inverse_mod(value: u64, modulus: u64) -> (u64, u64) {
    // The modulus is a first ramp (< 2^24), so the steps fit 32 bits: a hardware division each
    // on a 32-bit core, where a 64-bit one is a library call.
    let (Ok(value), Ok(modulus)) = (i32::try_from(value), i32::try_from(modulus)) else {
        return (modulus, 0); // unreachable for ramps; "no inverse" to the caller
    };
    let (mut old_r, mut r) = (value, modulus);
    let (mut old_s, mut s) = (1i32, 0i32);
    while r != 0 {
        let q = old_r / r;
        (old_r, r) = (r, old_r - q * r);
        (old_s, s) = (s, old_s - q * s);
    }
    (old_r as u64, old_s.rem_euclid(modulus) as u64)
}

/// The split nearest `lowering` from above (`under`) or below: as many units of `a` as fit,
/// then units of `a − 1` for the rest; `None` if the units cannot lower that far.
fn nearest(lowering: u64, a: u64, long: u64, short: u64, under: bool) -> Option<(u64, u64)> {
    let x = if under {
        div_ceil(lowering, a)
    } else {
        div(lowering, a)
    }
    .min(long);
    let rest = lowering.saturating_sub(a * x);
    let y = match (rest, a - 1) {
        (0, _) => 0,
        (_, 0) => return None,
        (rest, by) if under => div_ceil(rest, by),
        (rest, by) => div(rest, by),
    };
    (y <= short).then_some((x, y))
}

/// `a·x + (a − 1)·y = lowering` with `0 ≤ x ≤ long`, `0 ≤ y ≤ short`, the least `y` first; `None`
/// if there is no such split. `a ≥ 1`.
fn split(lowering: u64, a: u64, long: u64, short: u64) -> Option<(u64, u64)> {
    if a == 1 {
        return (lowering <= long).then_some((lowering, 0));
    }
    // (a − 1)·y ≡ lowering (mod a) ⇔ y ≡ −lowering (mod a); then y = y₀ + a·t and
    // x = x₀ − (a − 1)·t. With lowering = q·a + r: y₀ = 0 and x₀ = q when r = 0, else
    // y₀ = a − r and x₀ = (lowering − (a − 1)(a − r))/a = q + r + 1 − a (one division).
    let (q, r) = div_rem(lowering, a);
    let (y0, x0) = if r == 0 {
        (0, q)
    } else {
        (a - r, (q + r + 1).checked_sub(a)?)
    };
    // The least t ≥ 0 with x ≤ long.
    let t = match x0.checked_sub(long) {
        Some(over) if over > 0 => div_ceil(over, a - 1),
        _ => 0,
    };
    let y = y0.checked_add(product(a, t)?)?;
    let x = x0.checked_sub(product(a - 1, t)?)?;
    (y <= short && x <= long).then_some((x, y))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The closed forms agree with a plain convolution.
    #[test]
    fn group_closed_forms_agree_with_convolution() {
        for (a, b, c) in [
            (1, 1, 2),
            (2, 3, 5),
            (3, 3, 6),
            (2, 5, 9),
            (1, 4, 7),
            (4, 4, 20),
        ] {
            let group = Group { count: 3, a, b, c };
            let total = (a + b + c + 2) as usize;
            let mut velocity = vec![0i64; total];
            for i in 0..a {
                for j in 0..b {
                    for k in 0..c {
                        velocity[(i + j + k) as usize] += 3;
                    }
                }
            }
            let mut previous = (0i64, 0i64);
            for (n, &v) in velocity.iter().enumerate() {
                let acceleration = v - previous.0;
                let jerk = acceleration - previous.1;
                assert_eq!(group.velocity_at(n as u64), v as u64, "{a} {b} {c} at {n}");
                assert_eq!(group.jerk_at(n as u64), jerk, "{a} {b} {c} at {n}");
                previous = (v, acceleration);
            }
            let distance: i64 = velocity.iter().sum();
            assert_eq!(distance as u64, a * b * c * 3);
        }
    }

    /// The floor of the bounds (all the units as the box of the shortest ramps and cruise) is
    /// at most the move's velocity on every cycle, for mixes of every kind with early units.
    #[test]
    fn the_floor_is_under_the_velocity() {
        for (a, b, jerk, acceleration, velocity, c, early) in [
            (3u64, 7u64, 10u64, 28u64, 190u64, 14u64, [1u64, 2, 0, 1]),
            (5, 9, 4, 18, 149, 20, [0, 1, 1, 0]),
            (1, 6, 100, 40, 230, 8, [3, 0, 0, 0]),
            (4, 4, 7, 1_000, 108, 9, [2, 0, 0, 0]),
        ] {
            let mix = Mix::solve(a, b, jerk, acceleration, velocity, true).unwrap();
            let early = core::array::from_fn(|k| early[k].min(mix.counts[k]));
            let main = mix.main_move(c, early);
            let floor = main.bounds().floor;
            assert_eq!(floor.count, mix.counts.iter().sum::<u64>());
            for n in 0..main.total() + 2 {
                assert!(
                    floor.velocity_at(n) <= main.velocity_at(n),
                    "{a} {b} at {n}"
                );
            }
        }
    }

    /// First ramps longer than the acceleration allows (`a > ⌊A/J⌋ + 1`) have no mix: even
    /// all `J` units with the shorter ramp `a − 1` would pass it (`J·(a − 1) > A`). With J = 1,
    /// A = 1: a = 2 is a mix (one unit of ramp 1), a = 3 and 4 are not (nor with J = 3, A = 5
    /// and a = 4: 3·3 > 5), and none of them panics.
    #[test]
    fn first_ramps_past_the_acceleration_have_no_mix() {
        // One unit (1, 4): its velocity 4.
        assert!(Mix::solve(2, 4, 1, 1, 4, true).is_some());
        for (a, jerk, acceleration) in [(3u64, 1u64, 1u64), (4, 1, 1), (4, 3, 5)] {
            for under in [true, false] {
                assert_eq!(Mix::solve(a, a + 2, jerk, acceleration, 1, under), None);
            }
        }
    }

    /// The mix meets the acceleration and the velocity exactly where the kinds allow it.
    #[test]
    fn mix_is_exact() {
        for (a, b, jerk, acceleration, velocity) in [
            (3u64, 7u64, 10u64, 28u64, 190u64),
            (5, 9, 4, 18, 149),
            (1, 6, 100, 40, 230),
            (4, 4, 7, 1_000, 108),
        ] {
            let velocity: u64 = velocity;
            let mix = Mix::solve(a, b, jerk, acceleration, velocity, true).unwrap();
            let kinds = mix.kinds();
            let units: u64 = mix.counts.iter().sum();
            assert!(units <= jerk);
            let peak: u64 = (0..4).map(|k| mix.counts[k] * kinds[k].0).sum();
            let cruise: u64 = (0..4).map(|k| mix.counts[k] * mix.areas()[k]).sum();
            assert!(peak <= acceleration.min(jerk * a));
            assert_eq!((peak, cruise), (mix.acceleration, mix.velocity));
            assert_eq!(cruise, velocity);
        }
    }
}
