//! Circular interpolation of two axes (SPEC §12.4), as the MCX514 does it: around the centre the
//! plane is cut into octants 0–7; in each the *short axis* (the smaller |coordinate|) pulses on
//! every step and the other follows the circle.
//!
//! # The path
//! Let R² = cx² + cy² be the radius squared (the start lies exactly on the circle) and, for a
//! short-axis coordinate s ≥ 0, f(s) = round(√(R² − s²)): the long-axis coordinate nearest to the
//! true circle. In octant 0 (x > 0, 0 ≤ y ≤ x; Y is the short axis) the path is the points
//! (f(y), y); the other seven octants are its mirror images:
//!
//! ```text
//! octant      0        1        2        3        4        5        6        7
//! (x, y)   ( l, s)  ( s, l)  (−s, l)  (−l, s)  (−l,−s)  (−s,−l)  ( s,−l)  ( l,−s)   l = f(s)
//! short       Y        X        X        Y        Y        X        X        Y
//! ```
//!
//! An octant runs from the axis (s = 0) to the diagonal while f(s) ≥ s, i.e. up to
//! m = max{s : 2s² − s < R²}; there f(m) is m or m + 1 (f(m) ≥ m + 2 would make f(m + 1) ≥ m + 1).
//! Counter-clockwise the even octants are traversed *outbound* (s from 0 up to the diagonal) and
//! the odd ones *inbound* (s from the diagonal down to 0); clockwise the other way round. An
//! outbound octant takes **D = f(m)** steps: s = 0 … m, and when f(m) = m + 1 one more, the
//! diagonal step from (m + 1, m) to (m, m + 1) on which both axes pulse; an inbound octant takes
//! **m** steps. A full circle takes 4·(D + m) steps; for r = 10,000, m = D = 7,071 and the
//! circle takes 8 × 7,071 = 56,568 steps, the manual's count (reference 003).
//!
//! Why this stays on the circle: the long axis is the nearest integer to the true circle at the
//! short coordinate, |l − √(R² − s²)| < ½, so the radial error is below ½ as well:
//! |√(s² + l²) − r| = |l² − (R² − s²)| / (√(s² + l²) + r) < ½·(l + √(R² − s²)) / (√(s² + l²) + r)
//! ≤ ½. Within ±1 LSB, as the manual states, with room. Why one pulse per step: inside an octant
//! f(s + 1) ≥ s + 1 gives √(R² − s²) + √(R² − (s + 1)²) > 2s + 1, so the true long coordinate
//! moves by less than one per step and its nearest integer by at most one.
//!
//! # Where an arc ends (our reading of the manual)
//! The MCX514 counts an arc in short-axis pulses, and the arc ends when, in the octant of the
//! finish point, the short axis reaches the finish point's short-axis coordinate. So the end is
//! the path's point with that short coordinate: the finish point itself when it lies on the
//! path (its long coordinate the nearest integer to the circle, as a finish computed by rounding
//! a point of the circle nearly always is), and otherwise the point next to it. A finish point
//! more than one pulse off the path in its long axis is refused ([`Error::Unreachable`]); a
//! finish point at the start (0, 0) is a full circle. [`Arc::end`] is where the arc ends.
//!
//! # Cost
//! [`Arc::position_at`] and [`ArcWalk::advance_to`] find the octant (a walk keeps the octant it
//! is in, so a cycle moves it by at most the octants it crossed, never by the pulses) and
//! evaluate f with one exact integer square root in 32-bit operations (Karatsuba, in `sqrt.rs`): O(1) per
//! cycle however many steps the cycle takes.
//!
//! ```
//! use profilegen::interpolation::{Arc, Direction};
//! // Reference 003: a full circle of radius 10,000 (centre 10,000 pulses along +X).
//! let circle = Arc::from_pulses([10_000, 0], [0, 0], Direction::CounterClockwise)?;
//! assert_eq!(circle.steps(), 56_568); // 7,071 × 8
//! // Counter-clockwise from the left of the centre, a quarter turn is at the bottom.
//! assert_eq!(circle.position_at(14_142), [10_000, -10_000]);
//! assert_eq!(circle.position_at(56_568), [0, 0]);
//! # Ok::<(), profilegen::Error>(())
//! ```

mod drive;
mod sqrt;
mod walk;

pub use drive::{CircleState, CircularDriving, CircularInterpolation};
pub use walk::ArcWalk;

use crate::format::mcx514::{Centre, FinishPoint};
use crate::{Error, Range};
use sqrt::{isqrt_wide, round_sqrt, round_with_low_word, shift_for};

/// Which way round an arc goes, seen with X to the right and Y up.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Direction {
    /// Clockwise (the chip's CW circular interpolation).
    Clockwise,
    /// Counter-clockwise (CCW).
    CounterClockwise,
}

/// One of the eight octants around a circle's centre, numbered 0–7 counter-clockwise from the
/// +X axis, as the MCX514 numbers them (its status register reports the one it is in).
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct Octant(u8);

impl Octant {
    /// The octant's number, 0 … 7.
    pub const fn index(self) -> u8 {
        self.0
    }

    /// The axis that pulses on every step in this octant (the smaller |coordinate|): 0 for X
    /// (octants 1, 2, 5, 6), 1 for Y (octants 0, 3, 4, 7).
    pub const fn short_axis(self) -> usize {
        match self.0 {
            1 | 2 | 5 | 6 => 0,
            _ => 1,
        }
    }
}

/// Per octant: whether X carries the long coordinate, and the signs of X and Y (the table in the
/// [module docs](self)).
const FRAMES: [(bool, i32, i32); 8] = [
    (true, 1, 1),
    (false, 1, 1),
    (false, -1, 1),
    (true, -1, 1),
    (true, -1, -1),
    (false, -1, -1),
    (false, 1, -1),
    (true, 1, -1),
];

/// A circular arc from the start (the origin) around a centre to a finish point, in pulses: the
/// geometry of an MCX514 circular interpolation (SPEC §12.4). See the [module docs](self) for the
/// path, its ±½ bound and where an arc ends.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Arc {
    /// The centre, pulses, relative to the start.
    centre: [i32; 2],
    /// The finish point as given, relative to the start.
    finish: [i32; 2],
    /// Where the arc ends, relative to the start.
    end: [i32; 2],
    /// R² = cx² + cy² < 2⁶¹.
    radius_squared: u64,
    /// R²·2^shift, with the even shift that puts it into [2⁶⁰, 2⁶²) for the root (see
    /// `sqrt::shift_for`): each cycle's radicand is formed already in the root's range.
    scaled_radius_squared: u64,
    /// Half that shift, ≤ 30.
    half_shift: u32,
    /// Per traversal piece mod 8, the octant's row of `FRAMES` for this direction as the
    /// coefficients of X = ±long or ±short and Y likewise: `[long→X, short→X, long→Y, short→Y]`,
    /// each −1, 0 or 1 (one of each pair 0), so a cycle maps without a branch (two `mla` per axis).
    frames: [[i32; 4]; 8],
    /// m: the last short coordinate of an octant; the steps of an inbound octant.
    inbound_steps: u32,
    /// D = f(m): the steps of an outbound octant.
    outbound_steps: u32,
    counter_clockwise: bool,
    /// The octant the start lies in, counted from the direction's first octant (see
    /// [`Self::octant_of`]), 0 … 7.
    first_piece: u32,
    /// Steps from the start of that octant to the start point (< its steps).
    first_offset: u32,
    /// The arc's steps: short-axis pulses from the start to the end, 1 … 4·(D + m).
    steps: u64,
}

impl Arc {
    /// The arc around `centre` from the start to `finish`, both relative to the start, one
    /// checked register per axis; `finish` (0, 0) is a full circle.
    ///
    /// # Errors
    /// [`Error::Zero`] (parameter `centre`) for a centre at the start (radius 0);
    /// [`Error::OutOfRange`] (parameter `radius`) when the circle would leave the 32-bit
    /// position range (radius + |centre coordinate| above 2,147,483,647 pulses);
    /// [`Error::Unreachable`] (parameter `finish point`) for a finish point more than one pulse
    /// off the circle's path (see the [module docs](self)).
    pub fn new(
        centre: [Centre; 2],
        finish: [FinishPoint; 2],
        direction: Direction,
    ) -> Result<Self, Error> {
        let centre = centre.map(Centre::to_bits);
        let finish = finish.map(FinishPoint::to_bits);
        if centre == [0, 0] {
            return Err(Error::Zero {
                parameter: Centre::PARAMETER,
                range: Centre::RANGE,
            });
        }
        // |cᵢ| < 2³⁰: the squares and their sum stay below 2⁶¹.
        let radius_squared = centre.map(|c| u64::from(c.unsigned_abs()).pow(2));
        let radius_squared = radius_squared[0] + radius_squared[1];
        // Every point of the path is within f(0) = round(r) of the centre.
        let reach = u64::from(round_sqrt(radius_squared));
        let widest = u64::from(centre[0].unsigned_abs().max(centre[1].unsigned_abs()));
        let limit = i32::MAX as u64 - widest;
        if reach > limit {
            return Err(Error::OutOfRange {
                parameter: "radius",
                value: reach as f64,
                range: Range::of_register(1, limit as i64, 0, "pulses"),
            });
        }
        let inbound_steps = last_short_coordinate(radius_squared);
        let outbound_steps = round_sqrt(radius_squared - u64::from(inbound_steps).pow(2));
        let counter_clockwise = direction == Direction::CounterClockwise;
        let frames = core::array::from_fn(|piece| {
            let octant = if counter_clockwise { piece } else { 7 - piece };
            let (long_is_x, sign_x, sign_y) = FRAMES[octant];
            if long_is_x {
                [sign_x, 0, 0, sign_y]
            } else {
                [0, sign_x, sign_y, 0]
            }
        });
        let mut arc = Self {
            centre,
            finish,
            end: [0, 0],
            radius_squared,
            scaled_radius_squared: radius_squared << shift_for(radius_squared),
            half_shift: shift_for(radius_squared) / 2,
            frames,
            inbound_steps,
            outbound_steps,
            counter_clockwise,
            first_piece: 0,
            first_offset: 0,
            steps: 0,
        };
        // The start, relative to the centre, lies exactly on the circle, so on the path.
        let start = [-centre[0], -centre[1]];
        let (piece, offset) = arc.locate(start).ok_or(Error::Unreachable {
            parameter: "centre",
            reason: "internal: the start is not on the circle's path",
        })?;
        arc.first_piece = piece;
        arc.first_offset = offset;
        let period = arc.full_circle_steps();
        let start_position = arc.circle_position(piece, offset);
        if finish == [0, 0] {
            arc.steps = period;
            arc.end = [0, 0];
            return Ok(arc);
        }
        // The finish relative to the centre; |fᵢ − cᵢ| < 2³¹.
        let target = [finish[0] - centre[0], finish[1] - centre[1]];
        let mut best: Option<(u64, [i32; 2])> = None;
        for octant in 0..8 {
            let Some((piece, offset)) = arc.in_octant(target, octant) else {
                continue;
            };
            let point = arc.point(piece, offset);
            // i64: the point is within 2³¹ of the centre, the target too.
            let [dx, dy] =
                [0, 1].map(|axis| (i64::from(point[axis]) - i64::from(target[axis])).abs());
            if dx.max(dy) > 1 {
                continue;
            }
            // The first time the walk reaches that position after the start: 1 … a period.
            let position = arc.circle_position(piece, offset);
            let steps = (position + period - start_position - 1) % period + 1;
            if best.is_none_or(|(fewest, _)| steps < fewest) {
                best = Some((steps, point));
            }
        }
        let (steps, end) = best.ok_or(Error::Unreachable {
            parameter: FinishPoint::PARAMETER,
            reason: "it lies more than one pulse off the circle through the start and around \
                     the centre (the arc ends where the short axis reaches the finish point's \
                     short-axis coordinate, so the finish point must be on the circle)",
        })?;
        arc.steps = steps;
        arc.end = [end[0] + centre[0], end[1] + centre[1]];
        Ok(arc)
    }

    /// The arc from pulses per axis: centre and finish point relative to the start.
    ///
    /// # Errors
    /// [`Error::OutOfRange`] (parameters `centre`, `finish point`) for a coordinate outside
    /// ±1,073,741,823 pulses, and those of [`Self::new`].
    pub fn from_pulses(
        centre: [i32; 2],
        finish: [i32; 2],
        direction: Direction,
    ) -> Result<Self, Error> {
        let centre = [Centre::from_bits(centre[0])?, Centre::from_bits(centre[1])?];
        let finish = [
            FinishPoint::from_bits(finish[0])?,
            FinishPoint::from_bits(finish[1])?,
        ];
        Self::new(centre, finish, direction)
    }

    /// The centre, pulses relative to the start.
    pub const fn centre(&self) -> [i32; 2] {
        self.centre
    }

    /// The finish point as given, pulses relative to the start ((0, 0) for a full circle).
    pub const fn finish(&self) -> [i32; 2] {
        self.finish
    }

    /// Where the arc ends, pulses relative to the start: the finish point when it lies on the
    /// path, else the path's point with the finish point's short-axis coordinate in its octant.
    pub const fn end(&self) -> [i32; 2] {
        self.end
    }

    /// The direction.
    pub const fn direction(&self) -> Direction {
        if self.counter_clockwise {
            Direction::CounterClockwise
        } else {
            Direction::Clockwise
        }
    }

    /// R² = cx² + cy², pulses².
    pub const fn radius_squared(&self) -> u64 {
        self.radius_squared
    }

    /// The arc's steps: the short-axis pulses from the start to the end (the count the manual
    /// deceleration point is taken from), 1 … [`Self::full_circle_steps`].
    pub const fn steps(&self) -> u64 {
        self.steps
    }

    /// The steps of a full circle of this radius: 4·(D + m) (see the [module docs](self)).
    pub const fn full_circle_steps(&self) -> u64 {
        4 * (self.outbound_steps as u64 + self.inbound_steps as u64)
    }

    /// Both axes' positions after `step` steps, pulses relative to the start: O(1). Steps past
    /// the end stay on the end.
    pub fn position_at(&self, step: u64) -> [i32; 2] {
        let mut walk = self.walk();
        walk.advance_to(step)
    }

    /// The octant of step `step` (the step that arrives at the point [`Self::position_at`]
    /// gives; for step 0, the first step's).
    pub fn octant_at(&self, step: u64) -> Octant {
        let mut walk = self.walk();
        walk.advance_to(step);
        walk.octant()
    }

    /// A cursor at the start that follows the arc one step at a time (as an iterator) or many
    /// at once ([`ArcWalk::advance_to`]).
    pub fn walk(&self) -> ArcWalk {
        ArcWalk::new(*self)
    }

    /// The steps of octant number `piece` of the traversal: D outbound (even), m inbound (odd).
    const fn piece_steps(&self, piece: u32) -> u32 {
        if piece % 2 == 0 {
            self.outbound_steps
        } else {
            self.inbound_steps
        }
    }

    /// The octant of traversal piece `piece`: pieces are counted from octant 0 counter-clockwise
    /// and from octant 7 clockwise, so the even pieces are the outbound octants either way.
    const fn octant_of(&self, piece: u32) -> Octant {
        // Mod 8: the low three bits, whatever the wrap.
        if self.counter_clockwise {
            Octant((piece & 7) as u8)
        } else {
            Octant((7u32.wrapping_sub(piece) & 7) as u8)
        }
    }

    /// The long and short coordinates `offset` steps into an outbound or inbound piece (0 … its
    /// steps): outbound s = offset, and past m only the diagonal step's end (m, m + 1); inbound
    /// s = m − offset. The long coordinate is f(s).
    #[inline(always)]
    fn long_and_short(&self, outbound: bool, offset: u32) -> (u32, u32) {
        let m = self.inbound_steps;
        if outbound {
            if offset <= m {
                (self.long_at(offset), offset)
            } else {
                (m, offset)
            }
        } else {
            let short = m - offset;
            (self.long_at(short), short)
        }
    }

    /// The point `offset` steps into traversal piece `piece` (0 … its steps), relative to the
    /// centre.
    fn point(&self, piece: u32, offset: u32) -> [i32; 2] {
        let (long, short) = self.long_and_short(piece % 2 == 0, offset);
        let (long_is_x, sign_x, sign_y) = FRAMES[usize::from(self.octant_of(piece).0)];
        // Both below 2³¹ (the reach was checked): the casts are exact.
        let (long, short) = (long as i32, short as i32);
        if long_is_x {
            [sign_x * long, sign_y * short]
        } else {
            [sign_x * short, sign_y * long]
        }
    }

    /// f(s) = round(√(R² − s²)) for s ≤ m (so R²/4 ≤ R² − s² ≤ R², the root's domain with
    /// the circle's shift: m² < (R² + m)/2).
    ///
    /// In the root's range without a 64-bit shift: with t = s·2^(shift/2), the radicand
    /// R²·2^shift − t² = (R² − s²)·2^shift lies in [2⁵⁸, 2⁶²) (R²·2^shift ∈ [2⁶⁰, 2⁶²) and
    /// R² − s² ≥ R²/4), and t² ≤ R²·2^shift/2 + m·2^shift/2 < 2⁶² makes t < 2³¹ a u32. Its
    /// floor root shifted back by shift/2 is ⌊√(R² − s²)⌋ (a floor of a floor). The rounding
    /// needs n − q² ≤ 2q < 2³², so the low words give it (n the unscaled R² − s²).
    #[inline(always)]
    fn long_at(&self, short: u32) -> u32 {
        let scaled_short = short << self.half_shift;
        let radicand = self
            .scaled_radius_squared
            .wrapping_sub(u64::from(scaled_short) * u64::from(scaled_short));
        let root = isqrt_wide(radicand) >> self.half_shift;
        let low = (self.radius_squared as u32).wrapping_sub(short.wrapping_mul(short));
        round_with_low_word(low, root)
    }

    /// The position on a full circle traversed from the direction's first octant's start.
    fn circle_position(&self, piece: u32, offset: u32) -> u64 {
        let pair = u64::from(self.outbound_steps) + u64::from(self.inbound_steps);
        u64::from(piece / 2) * pair
            + u64::from(if piece % 2 == 0 {
                0
            } else {
                self.outbound_steps
            })
            + u64::from(offset)
    }

    /// The traversal piece (0 … 7) and offset at which the path's point with `point`'s short
    /// coordinate lies in octant `octant`, if `point` (relative to the centre) is in that
    /// octant's closed sector and the short coordinate lies on the octant's stretch of path.
    fn in_octant(&self, point: [i32; 2], octant: u32) -> Option<(u32, u32)> {
        let (long_is_x, sign_x, sign_y) = FRAMES[octant as usize];
        // i64: a coordinate relative to the centre is below 2³¹ in magnitude.
        let (x, y) = (
            i64::from(point[0]) * i64::from(sign_x),
            i64::from(point[1]) * i64::from(sign_y),
        );
        let (long, short) = if long_is_x { (x, y) } else { (y, x) };
        if short < 0 || long < short {
            return None;
        }
        let piece = if self.counter_clockwise {
            octant
        } else {
            7 - octant
        };
        let short = u32::try_from(short).ok()?;
        if piece % 2 == 0 {
            (short < self.outbound_steps).then_some((piece, short))
        } else {
            (1..=self.inbound_steps)
                .contains(&short)
                .then(|| (piece, self.inbound_steps - short))
        }
    }

    /// The traversal piece and offset of a point of the path (relative to the centre).
    fn locate(&self, point: [i32; 2]) -> Option<(u32, u32)> {
        (0..8).find_map(|octant| {
            let (piece, offset) = self.in_octant(point, octant)?;
            (self.point(piece, offset) == point).then_some((piece, offset))
        })
    }
}

/// m = max{s : 2s² − s < R²}: the last short coordinate s with f(s) ≥ s (round(√(R² − s²)) ≥ s
/// ⇔ R² − s² ≥ (s − ½)² ⇔ 2s² − s + ¼ ≤ R² ⇔ 2s² − s < R² for integers).
fn last_short_coordinate(radius_squared: u64) -> u32 {
    // √(R²/2) is within one of the answer: start there and step (at most twice).
    let mut short = sqrt::isqrt(radius_squared / 2);
    let fits = |s: u32| {
        let s = u64::from(s);
        2 * s * s - s < radius_squared
    };
    while fits(short + 1) {
        short += 1;
    }
    while short > 0 && !fits(short) {
        short -= 1;
    }
    short
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::{Arc, Direction};

    /// round(√n) for n < 2⁶², independently: u128's floor root, one more when n − q² > q.
    fn nearest_root(n: u64) -> u32 {
        let n = u128::from(n);
        let q = n.isqrt();
        (q + u128::from(n - q * q > q)) as u32
    }

    /// The long coordinate f(s) = round(√(R² − s²)) that each cycle evaluates (the radicand
    /// formed scaled, the rounding from the low words) against u128 arithmetic, for centres
    /// across the whole register range — R² up to 2⁶¹, where the root's shift is 0 — and short
    /// coordinates at both ends of an octant and spread between.
    #[test]
    fn the_long_coordinate_is_the_nearest_root_at_every_scale() {
        let mut seed = 0x9e37_79b9_7f4a_7c15_u64;
        let mut next = move || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            seed
        };
        let mut shift_zero = 0;
        for round in 0..20_000 {
            // Magnitudes log-uniform up to 2³⁰ − 1 (every other round: at least 2²⁹), every sign.
            let large = round % 2 == 0;
            let mut coordinate = || {
                let bits = if large { 30 } else { next() % 31 };
                let magnitude = (next() & ((1 << bits) - 1)).min((1 << 30) - 1) as i32;
                let magnitude = if large {
                    magnitude | (1 << 29)
                } else {
                    magnitude
                };
                if next() % 2 == 0 {
                    magnitude
                } else {
                    -magnitude
                }
            };
            let centre = [coordinate(), coordinate()];
            if centre == [0, 0] {
                continue;
            }
            let Ok(arc) = Arc::from_pulses(centre, [0, 0], Direction::CounterClockwise) else {
                continue;
            };
            shift_zero += usize::from(arc.half_shift == 0);
            let m = arc.inbound_steps;
            let mut shorts = std::vec![0, 1, m / 2, m.saturating_sub(1), m];
            shorts.extend((0..8).map(|_| (next() % (u64::from(m) + 1)) as u32));
            for short in shorts.into_iter().filter(|&s| s <= m) {
                let n = arc.radius_squared - u64::from(short).pow(2);
                assert_eq!(
                    arc.long_at(short),
                    nearest_root(n),
                    "centre {centre:?}, s = {short} (round {round})"
                );
            }
        }
        // The largest circles (R² ≥ 2⁶⁰) were among them.
        assert!(shift_zero > 100, "{shift_zero} circles with shift 0");
    }
}
