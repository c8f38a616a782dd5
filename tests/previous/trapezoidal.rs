//! `Trapezoidal` as it stepped before issue #12 (commit abfda4b): the braking velocity decided
//! from scratch every cycle (integer square root and divisions). Kept, arithmetic unchanged, as
//! the yardstick of `tests/same_states.rs`: the generator now plans the cycles between commands
//! and brakes incrementally, and must produce the same states, bit for bit.

use fixed::types::I32F32;
use profilegen::{State, StopKind, TrapezoidalParameters};

#[derive(Debug, Clone, Copy)]
struct Profile {
    max_velocity: i64,
    acceleration: i64,
    deceleration: i64,
    start_velocity: i64,
}

fn profile(p: &TrapezoidalParameters) -> Profile {
    let acceleration = i64::from(p.acceleration.to_bits()) << 8;
    let deceleration = match p.deceleration.to_bits() {
        0 => acceleration,
        bits => i64::from(bits) << 8,
    };
    Profile {
        max_velocity: i64::from(p.max_velocity.to_bits()) << 16,
        acceleration,
        deceleration,
        start_velocity: i64::from(p.start_velocity.to_bits()) << 16,
    }
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Mode {
    Move,
    Stopping,
    AbruptPending { resume: bool },
    Stopped,
}

#[derive(Debug, Clone)]
pub struct PreviousTrapezoidal {
    parameters: TrapezoidalParameters,
    profile: Profile,
    destination: i64,
    state: State,
    mode: Mode,
    cached_stop: (i64, i128),
}

impl PreviousTrapezoidal {
    /// `parameters` must be valid (the new generator validates them first).
    pub fn new(parameters: TrapezoidalParameters) -> Self {
        Self {
            parameters,
            profile: profile(&parameters),
            destination: i64::from(parameters.destination) << 32,
            state: State::at_rest(I32F32::ZERO),
            mode: Mode::Move,
            cached_stop: (-1, 0),
        }
    }

    pub fn set_parameters(&mut self, parameters: TrapezoidalParameters) {
        self.change(parameters);
        self.destination = i64::from(parameters.destination) << 32;
        self.mode = match self.mode {
            Mode::Stopped | Mode::Stopping | Mode::Move => Mode::Move,
            Mode::AbruptPending { .. } => Mode::AbruptPending { resume: true },
        };
    }

    pub fn set_destination(&mut self, destination: i32) {
        self.parameters.destination = destination;
        self.destination = i64::from(destination) << 32;
    }

    /// Any change that does not restart a stopped axis (acceleration, deceleration, starting
    /// velocity).
    pub fn change(&mut self, parameters: TrapezoidalParameters) {
        self.profile = profile(&parameters);
        self.parameters = parameters;
        self.cached_stop = (-1, 0);
    }

    pub fn parameters(&self) -> TrapezoidalParameters {
        self.parameters
    }

    fn stopping_distance(&mut self, velocity: i64) -> i128 {
        if self.cached_stop.0 == velocity {
            return self.cached_stop.1;
        }
        let deceleration = i128::from(self.profile.deceleration);
        let velocity_wide = i128::from(velocity);
        let q = velocity_wide / deceleration;
        let distance = (q + 1) * velocity_wide - deceleration * q * (q + 1) / 2;
        self.cached_stop = (velocity, distance);
        distance
    }

    fn braking_velocity(distance: i128, deceleration: i64) -> i64 {
        if distance <= 0 {
            return 0;
        }
        if let (Ok(distance), Ok(deceleration)) =
            (u64::try_from(distance), u64::try_from(deceleration))
        {
            if distance < 1 << 62 {
                let m = 2 * distance / deceleration;
                let q = ((4 * m + 1).isqrt() - 1) / 2;
                let numerator = distance + deceleration * (q * (q + 1) / 2);
                return (numerator / (q + 1)) as i64;
            }
        }
        let deceleration = i128::from(deceleration);
        let m = (2 * distance / deceleration) as u64;
        let q = i128::from(((4 * m + 1).isqrt() - 1) / 2);
        let numerator = distance + deceleration * q * (q + 1) / 2;
        (numerator / (q + 1)) as i64
    }

    fn next_velocity_ahead(&mut self, distance: i128, velocity: i64) -> i64 {
        let Profile {
            max_velocity,
            acceleration,
            deceleration,
            start_velocity,
        } = self.profile;
        let speed_up = if velocity == 0 {
            acceleration + start_velocity
        } else {
            acceleration
        };
        if velocity < 0 {
            let slowed = velocity + deceleration;
            if slowed <= 0 {
                return slowed;
            }
            let braking = Self::braking_velocity(distance, deceleration);
            return slowed.min(acceleration).min(max_velocity).min(braking);
        }
        let upper = if velocity > max_velocity {
            (velocity - deceleration).max(max_velocity)
        } else {
            (velocity + speed_up).min(max_velocity)
        };
        if self.stopping_distance(upper) <= distance {
            return upper;
        }
        Self::braking_velocity(distance, deceleration).max(velocity - deceleration)
    }

    pub fn step(&mut self) -> State {
        let velocity = self.state.velocity.to_bits();
        let next = match self.mode {
            Mode::AbruptPending { resume } => {
                self.mode = if resume { Mode::Move } else { Mode::Stopped };
                0
            }
            Mode::Stopped => 0,
            Mode::Stopping => {
                let deceleration = self.profile.deceleration;
                let next = if velocity > 0 {
                    (velocity - deceleration).max(0)
                } else {
                    (velocity + deceleration).min(0)
                };
                if next == 0 {
                    self.mode = Mode::Stopped;
                }
                next
            }
            Mode::Move => {
                let distance = self.destination.wrapping_sub(self.state.position.to_bits());
                if distance == 0 && velocity == 0 {
                    self.state = State::at_rest(self.state.position);
                    return self.state;
                }
                let direction: i64 = if distance != 0 {
                    distance.signum()
                } else {
                    velocity.signum()
                };
                let ahead = i128::from(distance) * i128::from(direction);
                direction * self.next_velocity_ahead(ahead, velocity * direction)
            }
        };
        self.state = self.state.advanced(I32F32::from_bits(next));
        self.state
    }

    pub fn is_complete(&self) -> bool {
        self.state.velocity == I32F32::ZERO
            && match self.mode {
                Mode::Move => self.destination == self.state.position.to_bits(),
                Mode::Stopped => true,
                Mode::Stopping | Mode::AbruptPending { .. } => false,
            }
    }

    pub fn stop(&mut self, kind: StopKind) {
        self.mode = match (kind, self.mode) {
            (StopKind::Smooth, Mode::AbruptPending { .. }) | (StopKind::Abrupt, _) => {
                Mode::AbruptPending { resume: false }
            }
            (StopKind::Smooth, _) => Mode::Stopping,
        };
    }
}
