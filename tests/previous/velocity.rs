//! `VelocityContouring` as it stepped before issue #12 (commit abfda4b), kept verbatim in its
//! arithmetic as the yardstick of `tests/same_states.rs`: the generator was rewritten for speed and
//! must produce the same states, bit for bit.

use fixed::types::I32F32;
use profilegen::format::juno::{Acceleration, TargetVelocity};
use profilegen::{State, StopKind, VelocityParameters};

#[derive(Debug, Clone)]
pub struct PreviousVelocity {
    target_velocity: i64,
    acceleration: i64,
    deceleration: i64,
    deceleration_register: Acceleration,
    state: State,
    abrupt_pending: bool,
}

const fn velocity_bits(velocity: TargetVelocity) -> i64 {
    (velocity.to_bits() as i64) << 16
}

const fn rate_bits(rate: Acceleration) -> i64 {
    (rate.to_bits() as i64) << 8
}

impl PreviousVelocity {
    pub fn new(parameters: VelocityParameters) -> Self {
        let mut generator = Self {
            target_velocity: velocity_bits(parameters.velocity),
            acceleration: rate_bits(parameters.acceleration),
            deceleration: 0,
            deceleration_register: parameters.deceleration,
            state: State::at_rest(I32F32::ZERO),
            abrupt_pending: false,
        };
        generator.resolve_deceleration();
        generator
    }

    pub fn set_velocity(&mut self, velocity: TargetVelocity) {
        self.target_velocity = velocity_bits(velocity);
    }

    pub fn set_acceleration(&mut self, acceleration: Acceleration) {
        assert!(!acceleration.is_zero());
        self.acceleration = rate_bits(acceleration);
        self.resolve_deceleration();
    }

    pub fn set_deceleration(&mut self, deceleration: Acceleration) {
        self.deceleration_register = deceleration;
        self.resolve_deceleration();
    }

    fn resolve_deceleration(&mut self) {
        self.deceleration = if self.deceleration_register.is_zero() {
            self.acceleration
        } else {
            rate_bits(self.deceleration_register)
        };
    }

    pub fn step(&mut self) -> State {
        let velocity = self.state.velocity.to_bits();
        let next = if self.abrupt_pending {
            self.abrupt_pending = false;
            0
        } else {
            let target = self.target_velocity;
            let toward_zero = velocity != 0
                && (target.signum() != velocity.signum() || target.abs() < velocity.abs());
            let rate = if toward_zero {
                self.deceleration
            } else {
                self.acceleration
            };
            if target > velocity {
                (velocity + rate).min(target)
            } else {
                (velocity - rate).max(target)
            }
        };
        self.state = self.state.advanced(I32F32::from_bits(next));
        self.state
    }

    pub fn stop(&mut self, kind: StopKind) {
        self.target_velocity = 0;
        if kind == StopKind::Abrupt {
            self.abrupt_pending = true;
        }
    }
}
