//! Juno velocity contouring (SPEC §6) and its stops (SPEC §9).

mod strategies;

use fixed::types::I32F32;
use profilegen::conformance::{check_abrupt_stop, Checker};
use profilegen::format::juno::{Acceleration, TargetVelocity};
use profilegen::reference::VelocityContouringF64;
use profilegen::{ProfileGenerator, State, StopKind, VelocityContouring, VelocityParameters};
use proptest::prelude::*;
use strategies::{velocity_script, VelocityCommand};

fn velocity(value: f64) -> TargetVelocity {
    TargetVelocity::from_num(value).unwrap()
}

fn rate(value: f64) -> Acceleration {
    Acceleration::from_num(value).unwrap()
}

fn fixed(value: f64) -> I32F32 {
    I32F32::from_num(value)
}

/// Steps `cycles` cycles through the conformance checker.
fn run(axis: &mut VelocityContouring, checker: &mut Checker, cycles: usize) -> Vec<State> {
    (0..cycles).map(|_| checker.step(axis).unwrap()).collect()
}

/// One segment of a scripted profile: every cycle changes the velocity by exactly `rate` toward
/// `target`, except the last one, which may be shorter and lands exactly on it.
fn assert_segment(states: &[State], start: I32F32, rate: I32F32, target: I32F32) {
    let mut previous = start;
    let mut reached = false;
    for state in states {
        if reached {
            assert_eq!(state.velocity, target);
            assert_eq!(state.acceleration, I32F32::ZERO);
            continue;
        }
        let step = if target > previous { rate } else { -rate };
        let expected = if (target - previous).abs() <= rate {
            target
        } else {
            previous + step
        };
        assert_eq!(
            state.velocity, expected,
            "from {previous} toward {target} at {rate}"
        );
        reached = expected == target;
        previous = state.velocity;
    }
    assert!(reached, "the segment never reached {target}");
}

/// Figure 11-1 of the Juno User Guide as a script of timed commands: V1 at A1; V2 > V1 at A1;
/// V3 < V2 at D; reversal to V4 < 0 (D down to zero, the crossing cycle at D, then A1 away from
/// zero); V5 > 0 (D back to zero, then A1); a change of acceleration A1 → A2 while accelerating.
#[test]
fn figure_11_1() {
    let (a1, a2, d) = (rate(0.25), rate(0.5), rate(0.125));
    let (v1, v2, v3, v4, v5) = (
        velocity(4.0),
        velocity(6.0),
        velocity(3.1),
        velocity(-2.0),
        velocity(5.0),
    );
    let parameters = VelocityParameters {
        velocity: v1,
        acceleration: a1,
        deceleration: d,
    };
    let mut axis = VelocityContouring::new(parameters).unwrap();
    let mut checker = Checker::new(&axis);
    let a1f = a1.to_fixed().to_num::<I32F32>();
    let df = d.to_fixed().to_num::<I32F32>();
    let a2f = a2.to_fixed().to_num::<I32F32>();

    // V1 at A1: 16 cycles of exactly 0.25.
    let states = run(&mut axis, &mut checker, 20);
    assert_segment(&states, I32F32::ZERO, a1f, fixed(4.0));
    assert!(states[..16].iter().all(|s| s.acceleration == fixed(0.25)));

    // V2 > V1: at A1.
    axis.set_velocity(v2);
    let states = run(&mut axis, &mut checker, 10);
    assert_segment(&states, fixed(4.0), a1f, fixed(6.0));

    // V3 < V2: at D; 3.1 is not a whole number of D steps from 6, so the last step is shorter.
    axis.set_velocity(v3);
    let v3f = v3.to_fixed().to_num::<I32F32>();
    let states = run(&mut axis, &mut checker, 30);
    assert_segment(&states, fixed(6.0), df, v3f);
    assert!(
        states.iter().all(|s| s.velocity >= v3f),
        "never past the target"
    );

    // V4 < 0: toward zero at D, the crossing cycle at D, then away from zero at A1.
    axis.set_velocity(v4);
    let states = run(&mut axis, &mut checker, 60);
    let crossing = states.iter().position(|s| s.velocity < 0).unwrap();
    assert!(
        states[..=crossing].iter().all(|s| s.acceleration == -df),
        "toward zero and across at D"
    );
    let after_crossing = states[crossing].velocity;
    assert!(after_crossing > -df, "the crossing cycle moved by D only");
    assert_segment(&states[crossing + 1..], after_crossing, a1f, fixed(-2.0));

    // V5 > 0: back toward zero at D, across at D, then A1; A1 → A2 while accelerating.
    axis.set_velocity(v5);
    let states = run(&mut axis, &mut checker, 16);
    assert!(
        states.iter().all(|s| s.acceleration == df),
        "toward zero at D"
    );
    let states = run(&mut axis, &mut checker, 4);
    assert!(
        states
            .iter()
            .all(|s| s.velocity > 0 && s.acceleration == a1f),
        "away from zero at A1"
    );
    axis.set_acceleration(a2).unwrap();
    let start = states.last().unwrap().velocity;
    let states = run(&mut axis, &mut checker, 12);
    assert_segment(&states, start, a2f, fixed(5.0));
    assert!(states[0].acceleration == a2f, "A2 applies immediately");
}

/// Regression (issue #17, found by the scripted tests): the register's minimum, −32768
/// counts/cycle, is a legal target, and the limit the generator reports admits it. (The
/// reported maximum was the register's maximum, 32767.99998, and the conformance suite failed
/// the cycle that reached −32768.)
#[test]
fn the_most_negative_target_velocity_conforms() {
    let mut axis = VelocityContouring::new(VelocityParameters {
        velocity: TargetVelocity::MIN,
        acceleration: Acceleration::MAX,
        deceleration: Acceleration::ZERO,
    })
    .unwrap();
    let mut checker = Checker::new(&axis);
    // 32768 / (2^31 − 1)·2^-24 = 256.0000001…: 257 cycles reach the target.
    let states = run(&mut axis, &mut checker, 300);
    assert_eq!(states[256].velocity, fixed(-32768.0));
    assert_eq!(
        states[255].velocity,
        -fixed(Acceleration::MAX.to_f64()) * 256
    );
    assert_eq!(axis.limits().max_velocity, Some(fixed(32768.0)));
}

#[test]
fn deceleration_zero_means_use_the_acceleration() {
    let parameters = VelocityParameters {
        velocity: velocity(3.0),
        acceleration: rate(0.5),
        deceleration: rate(0.0),
    };
    let mut axis = VelocityContouring::new(parameters).unwrap();
    let mut checker = Checker::new(&axis);
    run(&mut axis, &mut checker, 6);
    axis.set_velocity(velocity(1.0));
    let states = run(&mut axis, &mut checker, 4);
    assert_segment(&states, fixed(3.0), fixed(0.5), fixed(1.0));
    // A later acceleration change carries the zero deceleration along with it.
    axis.set_acceleration(rate(0.25)).unwrap();
    axis.set_velocity(velocity(0.0));
    let states = run(&mut axis, &mut checker, 4);
    assert_segment(&states, fixed(1.0), fixed(0.25), fixed(0.0));
}

#[test]
fn zero_acceleration_is_refused_and_changes_nothing() {
    let parameters = VelocityParameters {
        velocity: velocity(1.0),
        acceleration: rate(0.0),
        deceleration: rate(0.5),
    };
    assert!(matches!(
        VelocityContouring::new(parameters),
        Err(profilegen::Error::Zero {
            parameter: "acceleration",
            ..
        })
    ));
    let mut axis = VelocityContouring::new(VelocityParameters {
        acceleration: rate(0.5),
        ..parameters
    })
    .unwrap();
    assert!(axis.set_acceleration(rate(0.0)).is_err());
    assert_eq!(axis.parameters().acceleration, rate(0.5));
}

#[test]
fn smooth_stop_decelerates_at_d_then_completes_and_needs_a_new_velocity() {
    let parameters = VelocityParameters {
        velocity: velocity(-3.0),
        acceleration: rate(0.5),
        deceleration: rate(0.25),
    };
    let mut axis = VelocityContouring::new(parameters).unwrap();
    let mut checker = Checker::new(&axis);
    run(&mut axis, &mut checker, 10);
    axis.stop(StopKind::Smooth);
    assert_eq!(axis.parameters().velocity, TargetVelocity::ZERO);
    let states = run(&mut axis, &mut checker, 12);
    assert_segment(&states, fixed(-3.0), fixed(0.25), I32F32::ZERO);
    assert!(axis.is_complete());
    let rest = axis.state();
    assert_eq!(
        axis.step(),
        State::at_rest(rest.position),
        "a complete generator stays put"
    );
    axis.set_velocity(velocity(1.0));
    assert!(!axis.is_complete());
    assert_eq!(
        axis.step().velocity,
        fixed(0.5),
        "a new velocity restarts motion"
    );
}

#[test]
fn abrupt_stop_zeroes_the_velocity_on_the_next_cycle_and_holds_position() {
    let parameters = VelocityParameters {
        velocity: velocity(7.5),
        acceleration: rate(1.5),
        deceleration: rate(0.25),
    };
    let mut axis = VelocityContouring::new(parameters).unwrap();
    let mut checker = Checker::new(&axis);
    run(&mut axis, &mut checker, 8);
    axis.stop(StopKind::Abrupt);
    assert!(!axis.is_complete(), "the stop applies on the next cycle");
    check_abrupt_stop(&mut axis).unwrap();
    let mut checker = Checker::new(&axis);
    axis.set_velocity(velocity(-1.0));
    checker.command_given(&axis);
    assert_eq!(checker.step(&mut axis).unwrap().velocity, fixed(-1.0));
}

#[test]
fn position_wraps_at_32_integer_bits() {
    let parameters = VelocityParameters {
        velocity: velocity(1000.0),
        acceleration: rate(127.0),
        deceleration: rate(0.0),
    };
    let start = I32F32::from_num(i32::MAX - 2_000);
    let mut axis = VelocityContouring::with_position(parameters, start).unwrap();
    let mut checker = Checker::new(&axis);
    let states = run(&mut axis, &mut checker, 10);
    // 127 + 254 + 381 + 508 + 635 + 762 + 889 + 1000 · 3 = 6556 counts travelled.
    let travelled: i64 = 127 + 254 + 381 + 508 + 635 + 762 + 889 + 3 * 1000;
    let expected = (i64::from(i32::MAX - 2_000) + travelled - (1i64 << 32)) as i32;
    assert_eq!(states.last().unwrap().position, I32F32::from_num(expected));
    assert!(expected < 0, "it wrapped");
}

/// The rate SPEC §6 prescribes for the next cycle, computed independently of the generator.
fn prescribed_rate(
    velocity: I32F32,
    target: I32F32,
    acceleration: I32F32,
    deceleration: I32F32,
) -> I32F32 {
    let toward_zero =
        velocity != 0 && (target.signum() != velocity.signum() || target.abs() < velocity.abs());
    if toward_zero {
        deceleration
    } else {
        acceleration
    }
}

/// How far the exact velocity may be from the continuous-time reference.
///
/// Both models move toward the same target at the same rate while their velocities have the same
/// sign, so their difference cannot grow then. It grows only while they are on opposite sides of
/// zero, or when one crosses zero within the cycle: the chip takes the whole crossing cycle at D,
/// the continuous model switches to A at the crossing instant. Each such cycle adds at most one
/// cycle's worth of the larger rate. (Counterexample to a fixed bound of max(A, D): after a
/// crossing, a smooth stop turns the velocity lag into a time lag of (A − D)/D cycles, and a new
/// target set when the exact axis is at rest and the float one is not yet exceeds max(A, D).)
#[derive(Debug, Default)]
struct AgreementBound {
    allowed: f64,
}

impl AgreementBound {
    /// Takes one cycle into account; returns whether the two were apart in it (on opposite sides
    /// of zero, or one of them crossing it).
    fn update(
        &mut self,
        exact_before: f64,
        float_before: f64,
        exact_after: f64,
        float_after: f64,
        rate: f64,
    ) -> bool {
        let sign = |v: f64| {
            if v > 0.0 {
                1
            } else if v < 0.0 {
                -1
            } else {
                0
            }
        };
        let apart = sign(exact_before) * sign(float_before) < 0
            || sign(exact_after) * sign(float_after) < 0
            || sign(exact_before) * sign(exact_after) < 0
            || sign(float_before) * sign(float_after) < 0;
        if apart {
            self.allowed += rate;
        } else {
            self.allowed = self.allowed.max(rate);
        }
        apart
    }

    fn agreed(&mut self) {
        self.allowed = 0.0;
    }
}

fn run_script(script: strategies::VelocityScript, strict: bool) -> Result<(), TestCaseError> {
    let first = script.initial;
    let mut axis = VelocityContouring::new(first).unwrap();
    let mut model = VelocityContouringF64::new(
        first.velocity.to_f64(),
        first.acceleration.to_f64(),
        first.deceleration.to_f64(),
    );
    let mut checker = Checker::new(&axis);
    let mut target = first.velocity.to_fixed().to_num::<I32F32>();
    let mut acceleration = first.acceleration.to_fixed().to_num::<I32F32>();
    let mut deceleration_register = first.deceleration.to_fixed().to_num::<I32F32>();
    let mut bound = AgreementBound::default();
    let mut abrupt = false;
    for (gap, command) in script.commands {
        for _ in 0..gap {
            let deceleration = if deceleration_register == 0 {
                acceleration
            } else {
                deceleration_register
            };
            let before = axis.state().velocity;
            let float_before = model.velocity();
            let rate = prescribed_rate(before, target, acceleration, deceleration);
            let state = checker
                .step(&mut axis)
                .map_err(|v| TestCaseError::fail(v.to_string()))?;
            model.advance(1.0);
            if abrupt {
                prop_assert_eq!(state.velocity, I32F32::ZERO);
                abrupt = false;
            } else {
                let change = state.velocity - before;
                prop_assert!(
                    change.abs() <= rate,
                    "changed by {} at rate {}",
                    change,
                    rate
                );
                prop_assert!(
                    state.velocity == target || change.abs() == rate,
                    "a short step off target"
                );
                prop_assert!(
                    (before <= target) == (state.velocity <= target) || state.velocity == target,
                    "past the target"
                );
            }
            let larger_rate: f64 = acceleration.max(deceleration).to_num();
            let apart = bound.update(
                before.to_num(),
                float_before,
                state.velocity.to_num(),
                model.velocity(),
                larger_rate,
            );
            if strict {
                // Never apart, so the bound stays the largest rate in force since the two last
                // agreed: not necessarily the present rate, which a command may have lowered
                // (the lag built up at the old rate takes time to shrink).
                prop_assert!(!apart, "a strict script crossed zero");
            }
            let difference = (state.velocity.to_num::<f64>() - model.velocity()).abs();
            prop_assert!(
                difference <= bound.allowed * (1.0 + 1e-9) + 1e-9,
                "exact {} vs float {}: more than {}",
                state.velocity,
                model.velocity(),
                bound.allowed
            );
            if difference < 1e-12 {
                bound.agreed();
            }
        }
        match command {
            VelocityCommand::Velocity(v) => {
                axis.set_velocity(v);
                model.set_velocity(v.to_f64());
                target = v.to_fixed().to_num();
            }
            VelocityCommand::Acceleration(a) => {
                axis.set_acceleration(a).unwrap();
                model.set_acceleration(a.to_f64());
                acceleration = a.to_fixed().to_num();
            }
            VelocityCommand::Deceleration(d) => {
                axis.set_deceleration(d);
                model.set_deceleration(d.to_f64());
                deceleration_register = d.to_fixed().to_num();
            }
            VelocityCommand::Stop(kind) => {
                axis.stop(kind);
                model.stop(kind);
                target = I32F32::ZERO;
                // A smooth stop does not cancel an abrupt stop still pending.
                abrupt = abrupt || kind == StopKind::Abrupt;
            }
        }
        checker.command_given(&axis);
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(3000))]

    /// Random timed commands: identities and limits on every cycle, the prescribed rate exactly,
    /// never past the target, and agreement with the continuous-time reference (see
    /// [`AgreementBound`]).
    #[test]
    fn random_scripts(script in velocity_script()) {
        run_script(script, false)?;
    }

    /// Scripts whose velocities never change sign: the exact velocity is within one cycle's worth
    /// of the rates in force of the continuous-time reference on every cycle.
    #[test]
    fn one_signed_scripts_agree_within_one_cycle_of_the_rate(script in velocity_script().prop_map(|mut script| {
        let positive = |v: TargetVelocity| TargetVelocity::from_bits(v.to_bits().saturating_abs()).unwrap();
        script.initial.velocity = positive(script.initial.velocity);
        for (_, command) in &mut script.commands {
            if let VelocityCommand::Velocity(v) = command {
                *v = positive(*v);
            }
        }
        script
    })) {
        run_script(script, true)?;
    }
}
