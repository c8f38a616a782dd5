//! The MCX514 trapezoid's per-cycle path was laid out again for speed (SPEC §16: no saturating
//! add, the deceleration's trigger retired once it fires). This steps the library's
//! `Mcx514Trapezoidal` beside the implementation it replaced (`tests/previous/`, as it was at
//! commit 59fa77c) over random moves — every register across its range, every deceleration
//! mode, cycle times from 10 µs to 2 s, smooth and abrupt stops at random cycles — and requires
//! the same state, completion and limits on every cycle, bit for bit.

#[path = "previous/mcx514_trapezoidal.rs"]
mod previous_mcx514;

use previous_mcx514::PreviousMcx514Trapezoidal;
use profilegen::format::mcx514::{
    Acceleration, Deceleration, DriveSpeed, InitialSpeed, ManualDecelerationPoint,
};
use profilegen::format::CycleTime;
use profilegen::{
    DecelerationMode, Mcx514Parameters, Mcx514Trapezoidal, ProfileGenerator, StopKind,
};
use proptest::prelude::*;

/// Cycles stepped per move at most (long moves are compared over their start).
const CYCLES: u32 = 4_000;

/// A log-uniform integer in 1 ..= max.
fn log_uniform(max: u32) -> impl Strategy<Value = u32> {
    (0..32 - max.leading_zeros())
        .prop_flat_map(move |b| (1u32 << b)..=((1u64 << (b + 1)) - 1).min(u64::from(max)) as u32)
}

/// A stop given to both generators before the cycle it names.
#[derive(Debug, Clone, Copy)]
struct Stop {
    cycle: u32,
    kind: StopKind,
}

prop_compose! {
    /// Registers across their ranges (SV may exceed DV: both refuse then); AC = DC half the
    /// time for automatic deceleration (the other half both refuse); manual points near the
    /// finish point or anywhere in the register. `round`: whole pulses per cycle at 1 ms (speeds
    /// in thousands of pps, rates in millions of pps/s), so the ramps land exactly on DV and SV
    /// and the ties of every comparison happen.
    fn move_parameters(round: bool)(
        speeds in (log_uniform(8_000_000), log_uniform(8_000_000)),
        ordered in prop::bool::weighted(0.95),
        acceleration in log_uniform(536_870_911),
        deceleration in log_uniform(536_870_911),
        equal_rates in any::<bool>(),
        pulses in prop_oneof![0u32..=200, 0u32..=200_000, 0u32..=1_073_741_824],
        mode in 0..3u8,
        point in prop_oneof![0.0f64..=1.3, Just(-1.0)],
        any_point in 0u32..=4_294_967_292,
    ) -> Mcx514Parameters {
        let (mut initial, mut drive) = if ordered {
            (speeds.0.min(speeds.1), speeds.0.max(speeds.1))
        } else {
            speeds
        };
        let (mut acceleration, mut deceleration) = (acceleration, deceleration);
        if round {
            // 1 … 8,000 pulses/cycle and 1 … 536 pulses/cycle² at 1 ms, small ones likelier.
            (initial, drive) = ((initial % 64 + 1) * 1_000, (drive % 64 + 1) * 1_000);
            if ordered && initial > drive {
                (initial, drive) = (drive, initial);
            }
            (acceleration, deceleration) =
                ((acceleration % 16 + 1) * 1_000_000, (deceleration % 16 + 1) * 1_000_000);
        }
        let point = if point < 0.0 { any_point } else { (point * f64::from(pulses)) as u32 };
        let deceleration_mode = match mode {
            0 => DecelerationMode::Automatic,
            1 => DecelerationMode::Manual(ManualDecelerationPoint::from_bits(point).unwrap()),
            _ => DecelerationMode::Disabled,
        };
        let deceleration = if equal_rates { acceleration } else { deceleration };
        Mcx514Parameters {
            pulses,
            initial_speed: InitialSpeed::from_bits(initial).unwrap(),
            drive_speed: DriveSpeed::from_bits(drive).unwrap(),
            acceleration: Acceleration::from_bits(acceleration).unwrap(),
            deceleration: Deceleration::from_bits(deceleration).unwrap(),
            deceleration_mode,
        }
    }
}

/// Random registers at a random cycle time, or round ones at 1 ms.
fn moves() -> impl Strategy<Value = (Mcx514Parameters, f64)> {
    prop_oneof![
        (move_parameters(false), cycle_time()),
        (move_parameters(true), Just(1e-3)),
    ]
}

fn stops() -> impl Strategy<Value = Vec<Stop>> {
    prop::collection::vec(
        (
            prop_oneof![0..40u32, 0..CYCLES],
            prop_oneof![Just(StopKind::Smooth), Just(StopKind::Abrupt)],
        )
            .prop_map(|(cycle, kind)| Stop { cycle, kind }),
        0..3,
    )
}

/// A cycle time from 10 µs to 2 s, log-uniform.
fn cycle_time() -> impl Strategy<Value = f64> {
    (-5.0f64..=0.31).prop_map(|exponent| 10f64.powf(exponent))
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(4_000))]

    #[test]
    fn every_cycle_is_the_same_as_before(
        (parameters, seconds) in moves(),
        stops in stops(),
    ) {
        let cycle = CycleTime::from_seconds(seconds).unwrap();
        let (new, old) = (
            Mcx514Trapezoidal::new(parameters, cycle),
            PreviousMcx514Trapezoidal::new(parameters, cycle),
        );
        prop_assert_eq!(new.is_ok(), old.is_ok(), "{:?} / {:?}", new, old);
        let (Ok(mut new), Ok(mut old)) = (new, old) else {
            return Ok(());
        };
        prop_assert_eq!(new.state(), old.state());
        prop_assert_eq!(new.is_complete(), old.is_complete());
        let mut after_complete = 0;
        for index in 0..CYCLES {
            for stop in stops.iter().filter(|stop| stop.cycle == index) {
                new.stop(stop.kind);
                old.stop(stop.kind);
            }
            let (a, b) = (new.step(), old.step());
            prop_assert_eq!(a, b, "cycle {}", index);
            prop_assert_eq!(new.state(), old.state(), "cycle {}", index);
            prop_assert_eq!(new.is_complete(), old.is_complete(), "cycle {}", index);
            prop_assert_eq!(new.limits(), old.limits(), "cycle {}", index);
            if new.is_complete() {
                // A few cycles at rest after the end, then the next move.
                after_complete += 1;
                if after_complete > 3 {
                    break;
                }
            }
        }
    }
}

/// The registers' extremes at the longest and shortest cycles, where the old path saturated:
/// AC near 2³¹ pulses/cycle², SV and DV at their tops, manual points at both ends.
#[test]
fn the_extremes_are_the_same_as_before() {
    let modes = [
        DecelerationMode::Automatic,
        DecelerationMode::Manual(ManualDecelerationPoint::MIN),
        DecelerationMode::Manual(ManualDecelerationPoint::from_bits(1 << 29).unwrap()),
        DecelerationMode::Manual(ManualDecelerationPoint::MAX),
        DecelerationMode::Disabled,
    ];
    let mut compared = 0;
    for seconds in [2.0, 1.0, 1e-3, 1e-5] {
        let cycle = CycleTime::from_seconds(seconds).unwrap();
        for mode in modes {
            for (initial, drive) in [
                (1, 1),
                (1, 8_000_000),
                (8_000_000, 8_000_000),
                (4_000_000, 8_000_000),
            ] {
                for rate in [1, 536_870_911] {
                    for pulses in [0, 1, 1_000, 1_073_741_823] {
                        let parameters = Mcx514Parameters {
                            pulses,
                            initial_speed: InitialSpeed::from_bits(initial).unwrap(),
                            drive_speed: DriveSpeed::from_bits(drive).unwrap(),
                            acceleration: Acceleration::from_bits(rate).unwrap(),
                            deceleration: Deceleration::from_bits(rate).unwrap(),
                            deceleration_mode: mode,
                        };
                        let (new, old) = (
                            Mcx514Trapezoidal::new(parameters, cycle),
                            PreviousMcx514Trapezoidal::new(parameters, cycle),
                        );
                        assert_eq!(new.is_ok(), old.is_ok(), "{parameters:?} at {seconds} s");
                        let (Ok(mut new), Ok(mut old)) = (new, old) else {
                            continue;
                        };
                        compared += 1;
                        for index in 0..2_000 {
                            if index == 1_500 {
                                new.stop(StopKind::Smooth);
                                old.stop(StopKind::Smooth);
                            }
                            assert_eq!(new.step(), old.step(), "{parameters:?}, cycle {index}");
                            assert_eq!(new.limits(), old.limits(), "{parameters:?}, cycle {index}");
                            assert_eq!(new.is_complete(), old.is_complete());
                        }
                    }
                }
            }
        }
    }
    // Not every combination converts (the smallest registers vanish at 10 µs), but most do.
    assert!(compared > 300, "only {compared} moves compared");
}
