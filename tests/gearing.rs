//! MC1451A electronic gearing (SPEC §14): the follower is exactly start + ratio · (master −
//! master start) on every cycle — checked against an independent i128 model — across the
//! master's 32-bit wrap, over 2^32 cycles, through ratio changes in motion, with both stops, and
//! the conformance suite on every cycle.

use profilegen::conformance::{check_abrupt_stop, Checker};
use profilegen::fixed::types::I32F32;
use profilegen::format::juno::{Acceleration, TargetVelocity};
use profilegen::format::mc1451a::{GearRatio, TrapezoidalAcceleration};
use profilegen::gearing::{ElectronicGear, EncoderFollower, Follower};
use profilegen::{ProfileGenerator, State, StopKind, Trapezoidal, TrapezoidalParameters};
use proptest::prelude::*;

/// The golden ratios of SPEC §11: 1.5 → 98,304 and −11.39 → −746,455 raw (1/2^16).
fn golden() -> [GearRatio; 2] {
    let ratios = [
        GearRatio::from_num(1.5).unwrap(),
        GearRatio::from_num(-11.39).unwrap(),
    ];
    assert_eq!(ratios.map(GearRatio::to_bits), [98_304, -746_455]);
    ratios
}

/// The follower's position by the model: `start + ratio · travel` with the ratio's 16
/// fractional bits, in i128, then wrapped to the 32-integer-bit register (low 64 raw bits).
fn model(start: I32F32, ratio: i32, travel: i128) -> I32F32 {
    let exact = i128::from(start.to_bits()) + i128::from(ratio) * travel * (1 << 16);
    I32F32::from_bits(exact as i64)
}

fn master(destination: i32) -> Trapezoidal {
    Trapezoidal::with_position(
        TrapezoidalParameters {
            destination,
            max_velocity: TargetVelocity::from_num(37.25).unwrap(),
            acceleration: Acceleration::from_num(0.75).unwrap(),
            deceleration: Acceleration::from_num(0.5).unwrap(),
            start_velocity: TargetVelocity::ZERO,
        },
        I32F32::from_num(-2_147_480_000),
    )
    .unwrap()
}

/// A trapezoidal master moving 10,000 counts across its wrap (from −2,147,480,000 down past
/// −2^31 to 2,147,477,296): with each golden ratio the follower is exactly start + ratio ·
/// (the master's travel in counts) on every cycle, every cycle conforms, and at the end the
/// follower has moved exactly ratio · 10,000 counts (1.5 → −15,000; −11.39 → 113,900.0244…).
#[test]
fn golden_ratios_follow_a_trapezoid_across_the_wrap() {
    for ratio in golden() {
        let start = I32F32::from_num(123.25);
        let destination = (-2_147_480_000i64 - 10_000) as i32; // wraps to 2,147,477,296
        let mut axis = Follower::new(
            master(destination),
            ratio,
            start,
            TrapezoidalAcceleration::from_num(0.25).unwrap(),
        )
        .unwrap();
        let mut checker = Checker::new(&axis);
        let origin = -2_147_480_000i128;
        let mut travel_seen = 0i128;
        let mut last_count = origin;
        for _ in 0..2_000 {
            let state = checker.step(&mut axis).unwrap();
            let count = i128::from(axis.master().state().position.to_bits() >> 32);
            // Unwrap the master's count by the short way round (it moves < 40 counts/cycle).
            let mut change = count - last_count.rem_euclid(1 << 32);
            if change > 1 << 31 {
                change -= 1 << 32;
            } else if change < -(1 << 31) {
                change += 1 << 32;
            }
            last_count += change;
            travel_seen = last_count - origin;
            assert_eq!(state.position, model(start, ratio.to_bits(), travel_seen));
        }
        assert!(axis.master().is_complete());
        assert_eq!(travel_seen, -10_000);
        let moved = axis.state().position - start;
        // ratio · −10,000: 98,304 · −10,000 / 2^16 = −15,000 exactly; −746,455 · −10,000 / 2^16.
        let expected = I32F32::from_bits((i64::from(ratio.to_bits()) * -10_000) << 16);
        assert_eq!(moved, expected);
        assert_eq!(axis.state().velocity, 0);
    }
}

/// 2^32 cycles of an encoder turning 3 counts per cycle (its register wraps three times over):
/// no drift — the follower is start + ratio · 3 · n at every 2^24th cycle and at the last,
/// with the golden ratio −11.39.
#[test]
fn no_drift_over_two_to_the_32_cycles() {
    let ratio = golden()[1];
    let start = I32F32::from_bits(0x1234_5678_9abc_def0);
    let mut master = i32::MAX - 5;
    let mut gear = ElectronicGear::new(
        ratio,
        master,
        start,
        TrapezoidalAcceleration::from_num(1.0).unwrap(),
    )
    .unwrap();
    let mut state = gear.state();
    for n in 1..=1u64 << 32 {
        master = master.wrapping_add(3);
        state = gear.follow(master);
        if n % (1 << 24) == 0 {
            assert_eq!(
                state.position,
                model(start, ratio.to_bits(), 3 * i128::from(n))
            );
        }
    }
    assert_eq!(state.position, model(start, ratio.to_bits(), 3 << 32));
    // Every cycle moves −11.39 · 3 = −34.17… counts: −746,455 · 3 / 2^16 exactly.
    assert_eq!(state.velocity, I32F32::from_bits((-746_455 * 3) << 16));
    assert_eq!(state.acceleration, 0);
}

/// Both stops: abrupt (the conformance suite's check: velocity zero on the next cycle,
/// position held, then at rest and complete) and smooth (velocity falls by the deceleration,
/// 0.25 counts/cycle², to zero; then complete and put, while the master goes on); then a new
/// ratio re-engages from where the follower rests.
#[test]
fn stops_disengage_and_a_ratio_reengages() {
    let ratio = golden()[0];
    let deceleration = TrapezoidalAcceleration::from_num(0.25).unwrap();
    let mut axis =
        Follower::new(master(-2_147_470_000), ratio, I32F32::ZERO, deceleration).unwrap();
    axis.states().take(100).for_each(drop);
    let mut abrupt = axis.clone();
    assert!(abrupt.state().velocity != 0);
    check_abrupt_stop(&mut abrupt).unwrap();

    let mut checker = Checker::new(&axis);
    let velocity = axis.state().velocity;
    // At cruise the master's count moves 37 or 38 counts a cycle (37.25 counts/cycle, its
    // register shows whole counts): 1.5 times that.
    assert!(velocity == 55.5 || velocity == 57, "{velocity}");
    axis.stop(StopKind::Smooth);
    let cycles = checker.run_until_complete(&mut axis, 1_000).unwrap();
    // Down by 0.25 a cycle, the last to zero: ⌈v / 0.25⌉ cycles (222 or 228).
    let expected = (velocity.to_num::<f64>() / 0.25).ceil() as u64;
    assert_eq!(cycles, expected);
    let rest = axis.state().position;
    for _ in 0..50 {
        assert_eq!(checker.step(&mut axis).unwrap(), State::at_rest(rest));
    }
    // Re-engaged at −11.39 from here: the master's travel from now on, times the new ratio.
    let from = axis.master().state().position.to_bits() >> 32;
    axis.gear_mut().set_ratio(golden()[1]);
    checker.command_given(&axis);
    for _ in 0..30 {
        let state = checker.step(&mut axis).unwrap();
        let travel = (axis.master().state().position.to_bits() >> 32) - from;
        assert_eq!(state.position, model(rest, -746_455, i128::from(travel)));
    }
}

/// A smooth stop takes the deceleration off the speed every cycle, in either direction, and
/// lands on zero without passing it; a new deceleration given while stopping applies from the
/// next cycle. By hand: ±1.5 × 10 counts a cycle = ±15 counts/cycle; at 2 counts/cycle² the
/// speeds are 13, 11, 9, then at 0.5: 8.5, 8, …, 0.5, 0 (18 more cycles), then rest.
#[test]
fn a_smooth_stop_slows_by_the_deceleration_exactly_either_way() {
    for sign in [1, -1] {
        let mut gear = ElectronicGear::new(
            GearRatio::from_num(1.5 * f64::from(sign)).unwrap(),
            0,
            I32F32::ZERO,
            TrapezoidalAcceleration::from_num(2.0).unwrap(),
        )
        .unwrap();
        let mut master = 0;
        let mut follow = |gear: &mut ElectronicGear| {
            master += 10;
            gear.follow(master).velocity
        };
        for _ in 0..3 {
            follow(&mut gear);
        }
        assert_eq!(gear.state().velocity, 15 * sign);
        gear.stop(StopKind::Smooth);
        let mut speeds = Vec::new();
        for _ in 0..3 {
            speeds.push(follow(&mut gear));
        }
        gear.set_deceleration(TrapezoidalAcceleration::from_num(0.5).unwrap())
            .unwrap();
        while !gear.is_complete() {
            speeds.push(follow(&mut gear));
        }
        let expected: Vec<I32F32> = [13.0, 11.0, 9.0]
            .into_iter()
            .chain((0..18).map(|k| 8.5 - 0.5 * f64::from(k)))
            .map(|speed| I32F32::from_num(speed * f64::from(sign)))
            .collect();
        assert_eq!(speeds, expected, "sign {sign}");
        assert_eq!(follow(&mut gear), 0);
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(500))]

    /// Random encoders (any start, any change per cycle below 2^31 counts, so the register
    /// wraps freely) and random ratios over the whole register, changed in motion at random
    /// cycles: on every cycle the follower is the model's anchor + ratio · (the master's travel
    /// since the ratio came in force), with the travel unwrapped independently in i128.
    #[test]
    fn the_follower_is_exactly_ratio_times_the_master(
        first in any::<i32>(),
        changes in prop::collection::vec(-(1i64 << 31) + 1..1 << 31, 1..300),
        ratios in prop::collection::vec((0usize..300, GearRatio::MIN_BITS..=GearRatio::MAX_BITS), 1..5),
        start in any::<i64>(),
    ) {
        let ratio = GearRatio::from_bits(ratios[0].1).unwrap();
        let start = I32F32::from_bits(start);
        let mut gear = ElectronicGear::new(ratio, first, start, TrapezoidalAcceleration::MAX).unwrap();
        let (mut anchor, mut ratio_bits, mut travel) = (start, ratio.to_bits(), 0i128);
        let mut count = first;
        for (n, change) in changes.iter().enumerate() {
            if let Some(&(_, bits)) = ratios[1..].iter().find(|(at, _)| *at == n) {
                gear.set_ratio(GearRatio::from_bits(bits).unwrap());
                anchor = gear.state().position;
                ratio_bits = bits;
                travel = 0;
            }
            count = (i64::from(count) + change) as i32; // the register wraps
            travel += i128::from(*change);
            let before = gear.state();
            let state = gear.follow(count);
            prop_assert_eq!(state.position, model(anchor, ratio_bits, travel), "cycle {}", n);
            // The identities of SPEC §5, modulo the register.
            prop_assert_eq!(state.velocity.to_bits(), state.position.to_bits().wrapping_sub(before.position.to_bits()));
            prop_assert_eq!(state.acceleration.to_bits(), state.velocity.to_bits().wrapping_sub(before.velocity.to_bits()));
        }
    }

    /// The conformance suite on every cycle of an encoder follower whose velocities stay within
    /// the register (|ratio · change| < 2^30 counts/cycle), with a stop at the end.
    #[test]
    fn encoder_followers_conform(
        changes in prop::collection::vec(-1_000i32..1_000, 1..200),
        ratio in -(1i32 << 20)..1 << 20,
        first in any::<i32>(),
        smooth in any::<bool>(),
    ) {
        let counts: Vec<i32> = changes
            .iter()
            .scan(first, |count, change| {
                *count = count.wrapping_add(*change);
                Some(*count)
            })
            .collect();
        let mut axis = EncoderFollower::new(
            counts.into_iter(),
            first,
            GearRatio::from_bits(ratio).unwrap(),
            I32F32::from_num(-5.5),
            TrapezoidalAcceleration::from_num(0.5).unwrap(),
        )
        .unwrap();
        let mut checker = Checker::new(&axis);
        for _ in 0..changes.len() {
            checker.step(&mut axis).map_err(|v| TestCaseError::fail(v.to_string()))?;
        }
        if smooth {
            axis.stop(StopKind::Smooth);
            checker
                .run_until_complete(&mut axis, 1 << 40)
                .map_err(|v| TestCaseError::fail(v.to_string()))?;
            prop_assert!(axis.is_complete());
        } else {
            check_abrupt_stop(&mut axis).map_err(|rule| TestCaseError::fail(format!("{rule:?}")))?;
        }
    }
}
