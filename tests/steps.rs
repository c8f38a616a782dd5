//! Step timing (`steps::StepTimer`) against the position trace: on every cycle the events are
//! exactly the whole counts the position crosses (as many as its floor changes, in its
//! direction, consecutive counts), each at the instant the linear motion of that cycle reaches
//! its boundary (checked exactly in i128), in order, with the interval from the previous step
//! equal to the difference of their instants (checked exactly in 256 bits); in all they sum to
//! the count change of the move.

mod strategies;

use profilegen::steps::{Direction, StepEvent, StepTime, StepTimer};
use profilegen::{ProfileGenerator, SCurve, State, Trapezoidal, VelocityContouring};
use proptest::prelude::*;

/// a · b as a 256-bit (high, low) pair.
fn wide(a: u128, b: u128) -> (u128, u128) {
    let (a1, a0) = (a >> 64, a & u128::from(u64::MAX));
    let (b1, b0) = (b >> 64, b & u128::from(u64::MAX));
    let (low, middle1, middle2, high) = (a0 * b0, a0 * b1, a1 * b0, a1 * b1);
    let (middle, carry1) = middle1.overflowing_add(middle2);
    let (low_total, carry2) = low.overflowing_add(middle << 64);
    let high_total = high + (middle >> 64) + (u128::from(carry1) << 64) + u128::from(carry2);
    (high_total, low_total)
}

/// The instant as a fraction over its own denominator: (cycle·d + n, d).
fn as_fraction(time: StepTime) -> (u128, u128) {
    let d = u128::from(time.denominator);
    (u128::from(time.cycle) * d + u128::from(time.numerator), d)
}

/// Checks every cycle's events of `cycles` steps of `axis` against its trace.
fn check<G: ProfileGenerator + Clone>(axis: G, cycles: u64) -> Result<(), TestCaseError> {
    let first = axis.state();
    let mut timer = StepTimer::new(axis);
    let mut before: State = first;
    let mut previous: Option<StepEvent> = None;
    let mut total = 0i64;
    for n in 0..cycles {
        let events: Vec<StepEvent> = timer.step().collect();
        let after = timer.generator().state();
        let (low, high) = (
            before.position.to_bits() >> 32,
            after.position.to_bits() >> 32,
        );
        // The count change, modulo the register (a cycle moves less than 2^31 counts).
        let change = (high as i32).wrapping_sub(low as i32);
        prop_assert_eq!(events.len() as i64, i64::from(change).abs(), "cycle {}", n);
        let p0 = i128::from(before.position.to_bits());
        let v = i128::from(after.velocity.to_bits());
        let mut expected_count = low as i32;
        for event in &events {
            let forward = event.direction == Direction::Forward;
            prop_assert_eq!(forward, v > 0);
            prop_assert_eq!(event.at.cycle, n);
            prop_assert!(event.at.numerator <= event.at.denominator);
            expected_count = if forward {
                expected_count.wrapping_add(1)
            } else {
                expected_count.wrapping_sub(1)
            };
            prop_assert_eq!(event.count, expected_count);
            // The instant: p0 + v·(num/den) is the boundary the count changes at — the count
            // itself going up, the one above it going down (modulo the register: both sides
            // reduced to their low 64 raw bits).
            let boundary = i64::from(if forward {
                event.count
            } else {
                event.count.wrapping_add(1)
            }) << 32;
            let (num, den) = (
                i128::from(event.at.numerator),
                i128::from(event.at.denominator),
            );
            prop_assert_eq!(den, v.abs());
            let reached = p0 * den + v * num;
            prop_assert_eq!(reached % den, 0);
            prop_assert_eq!((reached / den) as i64, boundary);
            // Moving up the step is within (0, 1] of the cycle, moving down within [0, 1).
            let within = if forward { num > 0 } else { num < den };
            prop_assert!(within, "fraction {}/{}", num, den);
            // Order and interval: since = at − previous at, exactly.
            match (previous, event.since_previous) {
                (None, None) => {}
                (Some(last), Some(since)) => {
                    let (a, da) = as_fraction(event.at);
                    let (b, db) = as_fraction(last.at);
                    // a/da − b/db ≥ 0 and equal to (since.cycles·sd + sn)/sd:
                    // (a·db − b·da)·sd = (since.cycles·sd + sn)·da·db.
                    let (ad, bd) = (a * db, b * da);
                    prop_assert!(ad >= bd, "steps in order");
                    let sd = since.denominator;
                    prop_assert!(since.numerator < sd);
                    let whole = u128::from(since.cycles) * sd + since.numerator;
                    prop_assert_eq!(wide(ad - bd, sd), wide(whole, da * db));
                }
                other => prop_assert!(false, "since_previous {:?}", other),
            }
            previous = Some(*event);
        }
        prop_assert_eq!(expected_count, high as i32);
        total += i64::from(change);
        before = after;
    }
    let last = timer.generator().state();
    let moved = ((last.position.to_bits() >> 32) as i32)
        .wrapping_sub((first.position.to_bits() >> 32) as i32);
    prop_assert_eq!(total, i64::from(moved));
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(200))]

    #[test]
    fn trapezoid_steps_match_the_trace(
        mut parameters in strategies::moderate_trapezoidal(),
        start in any::<i64>(),
    ) {
        let start = profilegen::fixed::types::I32F32::from_bits(start);
        parameters.destination = ((start.to_bits() >> 32) as i32).wrapping_add(parameters.destination);
        let axis = Trapezoidal::with_position(parameters, start).unwrap();
        let cycles = axis.predict().and_then(|f| f.completion()).unwrap_or(1_000).min(50_000) + 3;
        check(axis, cycles)?;
    }

    #[test]
    fn scurve_steps_match_the_trace(parameters in strategies::scurve_move()) {
        prop_assume!(parameters.destination.unsigned_abs() < 1 << 20);
        let Ok(axis) = SCurve::new(parameters) else { return Ok(()) };
        let cycles = axis.plan().total.min(50_000) + 3;
        check(axis, cycles)?;
    }

    #[test]
    fn velocity_steps_match_the_trace(
        parameters in strategies::velocity_parameters(),
        start in any::<i64>(),
    ) {
        let axis = VelocityContouring::with_position(
            parameters,
            profilegen::fixed::types::I32F32::from_bits(start),
        )
        .unwrap();
        check(axis, 500)?;
    }
}

/// On a timer of 1,000 ticks per cycle, a move's pulses come out at the floors of their exact
/// instants: the delays between them add up to the last instant's ticks (no drift).
#[test]
fn ticks_do_not_drift() {
    use profilegen::format::juno::{Acceleration, TargetVelocity};
    let axis = VelocityContouring::new(profilegen::VelocityParameters {
        velocity: TargetVelocity::from_num(0.3).unwrap(),
        acceleration: Acceleration::from_num(0.3).unwrap(),
        deceleration: Acceleration::ZERO,
    })
    .unwrap();
    let mut timer = StepTimer::new(axis);
    let mut last_tick = 0u128;
    let mut delays = 0u128;
    let mut count = 0;
    for _ in 0..10_000 {
        for event in timer.step() {
            let tick = event.at.ticks(1_000);
            delays += tick - last_tick;
            last_tick = tick;
            count += 1;
        }
    }
    // 0.3 counts/cycle (16.16: 19,661/65,536, a hair above 0.3) for 10,000 cycles: 3,000 steps,
    // the k-th at k·65,536/19,661 cycles; the last at ⌊3000 · 65,536 · 1,000 / 19,661⌋ ticks.
    assert_eq!(count, 3_000);
    assert_eq!(delays, last_tick);
    assert_eq!(last_tick, 3_000 * 65_536 * 1_000 / 19_661);
}

/// A timer over a borrowed trait object, the generator left with its owner: the same events as
/// over the generator itself.
#[test]
fn a_timer_borrows_a_trait_object() {
    use profilegen::format::juno::{Acceleration, TargetVelocity};
    let parameters = profilegen::VelocityParameters {
        velocity: TargetVelocity::from_num(-1.75).unwrap(),
        acceleration: Acceleration::from_num(0.5).unwrap(),
        deceleration: Acceleration::ZERO,
    };
    let mut owned = StepTimer::new(VelocityContouring::new(parameters).unwrap());
    let mut axis = VelocityContouring::new(parameters).unwrap();
    let object: &mut dyn ProfileGenerator = &mut axis;
    let mut borrowed = StepTimer::new(object);
    for _ in 0..50 {
        assert!(owned.step().eq(borrowed.step()));
    }
    assert_eq!(axis.state(), owned.generator().state());
    assert!(axis.state().position < -70);
}
