//! The MCX514 S-curve's rule for one cycle (SPEC §12.2), as the chip applies it: the next
//! cycle's velocity from the present state, phase and ramp rate. The plan ([`super::plan`])
//! lays the cycles out ahead with it; stepping replays them.

use super::PerCycle;

/// Where the move is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Phase {
    /// At rest before the first cycle.
    Start,
    /// Speeding up toward DV (the rate ramps by JK within AC).
    Accelerating,
    /// At DV with the rate at zero (until deceleration starts).
    Cruising,
    /// Deceleration has started while the rate was still positive: it falls by JK to zero first.
    Easing,
    /// Slowing down toward SV (the rate ramps by DJ within DC).
    Decelerating,
    /// At SV with the rate at zero, to the finish point (a smooth stop makes it
    /// [`Phase::Decelerating`] again, which ends it).
    Creeping,
}

/// The rule's state between two cycles.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) struct Rule {
    pub(super) phase: Phase,
    /// The rate of the present ramp (speed-up while accelerating or easing, slow-down while
    /// decelerating), ≥ 0, raw bits per cycle², and its tail S(rate) ([`super::ramp::Ramp::tail`]).
    pub(super) rate: i64,
    pub(super) tail: i64,
    /// The position (raw I32F32) at or past which a cycle that begins there, speeding up or at
    /// DV, starts to decelerate: the manual point; with automatic deceleration, while speeding
    /// up, half the finish point (rounded up: the pulses left, finish − p, are then ≤ those
    /// output while speeding up, p), and at DV the finish point less those. `i64::MAX`: never.
    pub(super) trigger: i64,
    /// A smooth stop was commanded: decelerate to SV, then stop.
    pub(super) stopping: bool,
    /// The move is over (it reached its finish point, or was stopped): the next cycles rest.
    pub(super) complete: bool,
}

impl Rule {
    /// The rule before a move's first cycle.
    pub(super) const fn new(finish: i64) -> Self {
        Self {
            phase: Phase::Start,
            rate: 0,
            tail: 0,
            trigger: i64::MAX, // set by the first cycle
            stopping: false,
            complete: finish == 0,
        }
    }

    /// One cycle from `position` moving at `velocity` (raw I32F32): its velocity, and the one
    /// the rule wanted before the cut to the pulses left (they differ on the cycle that lands).
    /// Every cycle's velocity is at most the pulses left, so the move lands exactly on the
    /// finish point, complete there (the next cycle drops to zero).
    pub(super) fn cycle(&mut self, profile: &PerCycle, position: i64, velocity: i64) -> (i64, i64) {
        if self.complete {
            return (0, 0);
        }
        let wanted = self.next_velocity(profile, position, velocity);
        // i64: both below 2³¹ pulses in raw I32F32.
        let left = profile.finish - position;
        if wanted >= left {
            self.complete = true;
            (left, wanted)
        } else {
            (wanted, wanted)
        }
    }

    /// The velocity of the next cycle before the cut to the pulses left (raw I32F32), with the
    /// phase it leaves the move in.
    fn next_velocity(&mut self, profile: &PerCycle, position: i64, velocity: i64) -> i64 {
        match self.phase {
            Phase::Cruising if position < self.trigger => velocity,
            Phase::Creeping => velocity,
            Phase::Accelerating if position < self.trigger => {
                self.accelerate(profile, position, velocity)
            }
            Phase::Decelerating => self.decelerate(profile, position, velocity),
            Phase::Start => self.start(profile),
            Phase::Accelerating | Phase::Cruising | Phase::Easing => {
                self.phase = Phase::Easing;
                self.ease(profile, position, velocity)
            }
        }
    }

    /// Speeding up toward DV, or cruising there.
    fn accelerate(&mut self, profile: &PerCycle, position: i64, velocity: i64) -> i64 {
        let gap = profile.drive - velocity;
        if self.rate == 0 && gap < profile.speed_up.first {
            if gap <= 0 {
                // At DV: cruise (what the ramp would choose, sooner).
                self.phase = Phase::Cruising;
                return velocity;
            }
            return self.land(profile, position, velocity, gap);
        }
        let change = profile.speed_up.next(&mut self.rate, &mut self.tail, gap);
        // (Gap 0 with the rate still above zero: at DV already, the trigger set.)
        if change == gap && gap != 0 {
            // At DV this cycle: with automatic deceleration the trigger becomes the finish
            // point less the pulses output while speeding up.
            self.at_drive_speed(profile, position + gap + velocity);
        }
        velocity + change
    }

    /// Slowing down toward SV, or creeping there; a smooth stop ends at SV.
    fn decelerate(&mut self, profile: &PerCycle, position: i64, velocity: i64) -> i64 {
        let initial = profile.initial;
        if self.stopping && velocity <= initial {
            // A smooth stop ends at SV, as the chip's decelerating stop does.
            self.complete = true;
            return 0;
        }
        // Excess over SV ≥ 0: the slow-down never goes below SV.
        let excess = velocity - initial;
        if self.rate == 0 && excess < profile.slow_down.first {
            if excess <= 0 {
                // At SV: creep (what the ramp would choose, sooner).
                self.phase = Phase::Creeping;
                return velocity;
            }
            return self.land(profile, position, velocity, -excess);
        }
        velocity
            - profile
                .slow_down
                .next(&mut self.rate, &mut self.tail, excess)
    }

    /// The first cycle: SV at once (DV with deceleration disabled, for good).
    fn start(&mut self, profile: &PerCycle) -> i64 {
        self.phase = Phase::Accelerating;
        if profile.disabled && !self.stopping {
            self.trigger = i64::MAX;
            (self.rate, self.tail) = (0, 0);
            return profile.drive;
        }
        self.trigger = if profile.automatic {
            // While speeding up: 2p ≥ finish, i.e. p ≥ ⌈finish/2⌉.
            (profile.finish + 1) >> 1
        } else {
            profile.manual_point
        };
        if profile.initial == profile.drive {
            self.at_drive_speed(profile, profile.initial);
        }
        if self.stopping {
            // Stopped before the first cycle: SV once (the start), then the stop from there.
            self.phase = Phase::Easing;
        }
        profile.initial
    }

    /// The rate at zero and the speed `change` (raw I32F32 per cycle; |change| below the ramp's
    /// first step) from its target (DV speeding up, SV slowing down): there at once, the rate
    /// the change itself (within the jerk and the cap from zero, and back to zero on the next
    /// cycle). The ramp's own choice from zero would be to stay (+J overshoots): the speed would
    /// never reach DV, and a smooth stop that had to come down to SV would never end.
    fn land(&mut self, profile: &PerCycle, position: i64, velocity: i64, change: i64) -> i64 {
        (self.rate, self.tail) = (change.abs(), 0);
        if change > 0 {
            self.at_drive_speed(profile, position + change + velocity);
        }
        velocity + change
    }

    /// At DV after a cycle that ended at `reached` (raw I32F32 pulses).
    pub(super) fn at_drive_speed(&mut self, profile: &PerCycle, reached: i64) {
        if profile.automatic {
            self.trigger = profile.finish - reached;
        }
    }

    /// Deceleration has started: a rate still rising the speed falls by JK to zero first (the
    /// speed-up's tail kept the speed within DV), then the slow-down begins.
    fn ease(&mut self, profile: &PerCycle, position: i64, velocity: i64) -> i64 {
        if self.rate > 0 {
            let down = self.rate - profile.speed_up.jerk;
            (self.rate, self.tail) = if down > 0 {
                (down, self.tail - down)
            } else {
                (0, 0)
            };
            return velocity + self.rate;
        }
        self.phase = Phase::Decelerating;
        (self.rate, self.tail) = (0, 0);
        self.decelerate(profile, position, velocity)
    }

    /// A smooth stop commanded between two cycles: decelerate to SV, then stop.
    pub(super) fn stop_smoothly(&mut self) {
        self.stopping = true;
        self.phase = match self.phase {
            Phase::Accelerating | Phase::Cruising => Phase::Easing,
            // Creeping: SV reached, the stop ends it (`decelerate`).
            Phase::Creeping => Phase::Decelerating,
            phase => phase,
        };
    }
}
