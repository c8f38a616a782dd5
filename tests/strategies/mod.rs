//! proptest strategies shared by the test files: valid parameters of every generator, spanning
//! the whole register ranges (log-uniform where a range spans many orders of magnitude).
#![allow(dead_code)] // each test file uses its own subset

use profilegen::format::juno::{Acceleration, TargetVelocity};
use profilegen::{StopKind, VelocityParameters};
use proptest::prelude::*;

/// A raw value log-uniform in `1 ..= max` (each power of two equally likely).
pub fn log_uniform(max: u64) -> impl Strategy<Value = u64> {
    let bits = 64 - max.leading_zeros();
    (1..=bits).prop_flat_map(move |b| {
        let low = 1u64 << (b - 1);
        let high = if b == 64 {
            u64::MAX
        } else {
            ((1u64 << b) - 1).min(max)
        };
        low..=high
    })
}

/// A non-zero Juno rate (8.24), anywhere in its range.
pub fn juno_rate() -> impl Strategy<Value = Acceleration> {
    log_uniform(Acceleration::MAX_BITS as u64)
        .prop_map(|bits| Acceleration::from_bits(bits as u32).unwrap())
}

/// A Juno deceleration: zero ("use the acceleration") a quarter of the time.
pub fn juno_deceleration() -> impl Strategy<Value = Acceleration> {
    prop_oneof![1 => Just(Acceleration::ZERO), 3 => juno_rate()]
}

/// A signed Juno velocity (16.16), anywhere in its range, zero now and then.
pub fn juno_velocity() -> impl Strategy<Value = TargetVelocity> {
    prop_oneof![
        1 => Just(TargetVelocity::ZERO),
        8 => (log_uniform(i32::MAX as u64), any::<bool>()).prop_map(|(bits, negative)| {
            let bits = bits as i32;
            TargetVelocity::from_bits(if negative { -bits } else { bits }).unwrap()
        }),
    ]
}

/// A command of a velocity-contouring script.
#[derive(Debug, Clone, Copy)]
pub enum VelocityCommand {
    /// New target velocity.
    Velocity(TargetVelocity),
    /// New acceleration (non-zero).
    Acceleration(Acceleration),
    /// New deceleration.
    Deceleration(Acceleration),
    /// A stop.
    Stop(StopKind),
}

/// Initial parameters and a list of (cycles to run, then command).
#[derive(Debug, Clone)]
pub struct VelocityScript {
    /// The parameters the generator starts with.
    pub initial: VelocityParameters,
    /// Each entry: run this many cycles, then give the command.
    pub commands: Vec<(u32, VelocityCommand)>,
}

pub fn velocity_parameters() -> impl Strategy<Value = VelocityParameters> {
    (juno_velocity(), juno_rate(), juno_deceleration()).prop_map(
        |(velocity, acceleration, deceleration)| VelocityParameters {
            velocity,
            acceleration,
            deceleration,
        },
    )
}

pub fn velocity_command() -> impl Strategy<Value = VelocityCommand> {
    prop_oneof![
        6 => juno_velocity().prop_map(VelocityCommand::Velocity),
        2 => juno_rate().prop_map(VelocityCommand::Acceleration),
        2 => juno_deceleration().prop_map(VelocityCommand::Deceleration),
        1 => Just(VelocityCommand::Stop(StopKind::Smooth)),
        1 => Just(VelocityCommand::Stop(StopKind::Abrupt)),
    ]
}

pub fn velocity_script() -> impl Strategy<Value = VelocityScript> {
    (
        velocity_parameters(),
        prop::collection::vec((0u32..300, velocity_command()), 1..16),
    )
        .prop_map(|(initial, commands)| VelocityScript { initial, commands })
}

use profilegen::TrapezoidalParameters;

/// The longest move, in cycles of the continuous-time optimum, the trapezoidal strategies make:
/// parameters are drawn so that even the slowest combination stays below it.
pub const TRAPEZOIDAL_CYCLES: f64 = 200_000.0;

/// A raw value log-uniform in `low ..= high`.
pub fn log_uniform_between(low: u64, high: u64) -> impl Strategy<Value = u64> {
    let low = low.max(1);
    log_uniform(high)
        .prop_map(move |bits| bits.max(low))
        .prop_filter("in range", move |bits| *bits <= high)
}

/// A trapezoidal move from rest at 0, spanning the register ranges: distances from 1 count to
/// 2^31 − 1, velocities from 1/65536 to 32767, rates across 8.24, with and without a separate
/// deceleration and a starting velocity. Velocity and rates have lower bounds that depend on the
/// distance, so that no move lasts much more than [`TRAPEZOIDAL_CYCLES`].
pub fn trapezoidal_move() -> impl Strategy<Value = TrapezoidalParameters> {
    (log_uniform(i32::MAX as u64), any::<bool>())
        .prop_flat_map(|(distance, negative)| {
            let counts = distance as f64;
            // Cruise time ≤ limit: v ≥ distance / limit.
            let min_velocity = ((counts / TRAPEZOIDAL_CYCLES) * 65_536.0).ceil() as u64;
            // Triangle time 2·√(distance/a) ≤ limit: a ≥ 4·distance / limit².
            let min_rate = ((4.0 * counts / (TRAPEZOIDAL_CYCLES * TRAPEZOIDAL_CYCLES)) * 16_777_216.0).ceil() as u64;
            (
                Just(if negative { -(distance as i64) } else { distance as i64 }),
                log_uniform_between(min_velocity, i32::MAX as u64),
                log_uniform_between(min_rate, Acceleration::MAX_BITS as u64),
                prop_oneof![1 => Just(0u64), 2 => log_uniform_between(min_rate, Acceleration::MAX_BITS as u64)],
                prop_oneof![2 => Just(0.0f64), 1 => 0.0f64..=1.0],
            )
        })
        .prop_map(|(destination, velocity, acceleration, deceleration, start_fraction)| {
            let start = (velocity as f64 * start_fraction) as i32;
            TrapezoidalParameters {
                destination: destination as i32,
                max_velocity: TargetVelocity::from_bits(velocity as i32).unwrap(),
                acceleration: Acceleration::from_bits(acceleration as u32).unwrap(),
                deceleration: Acceleration::from_bits(deceleration as u32).unwrap(),
                start_velocity: TargetVelocity::from_bits(start).unwrap(),
            }
        })
}

/// A command given to a trapezoidal move in motion.
#[derive(Debug, Clone, Copy)]
pub enum TrapezoidalCommand {
    /// New destination.
    Destination(i32),
    /// New maximum velocity.
    MaxVelocity(TargetVelocity),
    /// New acceleration.
    Acceleration(Acceleration),
    /// New deceleration.
    Deceleration(Acceleration),
    /// A stop.
    Stop(StopKind),
}

/// Moderate parameters for scripts of changes in motion (so that every script comes to rest in
/// a bounded number of cycles).
pub fn moderate_trapezoidal() -> impl Strategy<Value = TrapezoidalParameters> {
    (
        -100_000i32..100_000,
        (1u32 << 16)..(200 << 16),
        (1u32 << 16)..(4u32 << 24),
        prop_oneof![Just(0u32), (1u32 << 16)..(4u32 << 24)],
    )
        .prop_map(|(destination, velocity, acceleration, deceleration)| {
            TrapezoidalParameters {
                destination,
                max_velocity: TargetVelocity::from_bits(velocity as i32).unwrap(),
                acceleration: Acceleration::from_bits(acceleration).unwrap(),
                deceleration: Acceleration::from_bits(deceleration).unwrap(),
                start_velocity: TargetVelocity::ZERO,
            }
        })
}

pub fn trapezoidal_command() -> impl Strategy<Value = TrapezoidalCommand> {
    prop_oneof![
        4 => (-100_000i32..100_000).prop_map(TrapezoidalCommand::Destination),
        2 => moderate_trapezoidal().prop_map(|p| TrapezoidalCommand::MaxVelocity(p.max_velocity)),
        2 => moderate_trapezoidal().prop_map(|p| TrapezoidalCommand::Acceleration(p.acceleration)),
        2 => moderate_trapezoidal().prop_map(|p| TrapezoidalCommand::Deceleration(p.deceleration)),
        1 => Just(TrapezoidalCommand::Stop(StopKind::Smooth)),
        1 => Just(TrapezoidalCommand::Stop(StopKind::Abrupt)),
    ]
}

use profilegen::format::mc1451a::{Jerk, MaxVelocity, ScurveAcceleration};
use profilegen::ScurveParameters;

/// The longest S-curve move (cycles of the continuous-time optimum) the strategy makes.
pub const SCURVE_CYCLES: f64 = 200_000.0;

/// An S-curve move from rest at 0 across the register ranges: jerk from the smallest raw value
/// up, distances from 1 count to 2^30, accelerations and velocities over their ranges — with the
/// lower bounds on jerk, acceleration and velocity that keep the continuous optimum below
/// [`SCURVE_CYCLES`] (so small jerks come with short moves).
pub fn scurve_move() -> impl Strategy<Value = ScurveParameters> {
    (log_uniform((1 << 30) - 1), any::<bool>())
        .prop_flat_map(|(distance, negative)| {
            let counts = distance as f64;
            let t = SCURVE_CYCLES;
            // Jerk-limited: T = (32·d/j)^(1/3) ≤ t ⇒ j ≥ 32·d/t³. Acceleration-limited:
            // T ≈ 2√(d/a) ⇒ a ≥ 4d/t². Cruise: v ≥ d/t.
            let min_jerk = (32.0 * counts / (t * t * t) * 4_294_967_296.0).ceil() as u64;
            let min_acceleration = (4.0 * counts / (t * t) * 65_536.0).ceil() as u64;
            let min_velocity = (counts / t * 65_536.0).ceil() as u64;
            (
                Just(if negative {
                    -(distance as i64)
                } else {
                    distance as i64
                }),
                log_uniform_between(min_velocity, MaxVelocity::MAX_BITS as u64),
                log_uniform_between(min_acceleration, ScurveAcceleration::MAX_BITS as u64),
                log_uniform_between(min_jerk, Jerk::MAX_BITS as u64),
            )
        })
        .prop_map(
            |(destination, velocity, acceleration, jerk)| ScurveParameters {
                destination: destination.clamp(-(1 << 30), (1 << 30) - 1) as i32,
                max_velocity: MaxVelocity::from_bits(velocity as u32).unwrap(),
                max_acceleration: ScurveAcceleration::from_bits(acceleration as u16).unwrap(),
                jerk: Jerk::from_bits(jerk as u32).unwrap(),
            },
        )
}

/// Any S-curve move from rest at 0: every register over its whole range, log-uniform, with no
/// bound on the move's length (up to ~7·10¹³ cycles) — for plans, not for stepping.
pub fn any_scurve_move() -> impl Strategy<Value = ScurveParameters> {
    (
        log_uniform((1 << 30) - 1),
        any::<bool>(),
        log_uniform(MaxVelocity::MAX_BITS as u64),
        log_uniform(ScurveAcceleration::MAX_BITS as u64),
        log_uniform(Jerk::MAX_BITS as u64),
    )
        .prop_map(
            |(distance, negative, velocity, acceleration, jerk)| ScurveParameters {
                destination: if negative {
                    -(distance as i32)
                } else {
                    distance as i32
                },
                max_velocity: MaxVelocity::from_bits(velocity as u32).unwrap(),
                max_acceleration: ScurveAcceleration::from_bits(acceleration as u16).unwrap(),
                jerk: Jerk::from_bits(jerk as u32).unwrap(),
            },
        )
}
