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
