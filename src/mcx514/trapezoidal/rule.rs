//! The MCX514 trapezoid's rule for one cycle (SPEC §12.2), as the chip applies it: what the
//! next cycle's velocity is, from the present state and phase. The plan
//! ([`super::plan`]) lays the cycles out ahead with it; stepping replays them.

use super::PerCycle;

/// Where the move is; each phase has its own one-comparison test for what ends it. The trigger
/// is `i64::MAX` while decelerating, so the test for deceleration needs no phase.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Phase {
    /// At rest before the first cycle.
    Start,
    /// Speeding up by AC toward DV.
    Accelerating,
    /// At DV (deceleration disabled: from the first cycle).
    Cruising,
    /// Slowing down by DC toward SV.
    Decelerating,
    /// At SV after the deceleration (the chip's creep), until the finish point or a stop.
    Creeping,
}

/// The rule's state between two cycles: the phase, the deceleration's trigger, a smooth stop
/// under way, the move over.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) struct Rule {
    pub(super) phase: Phase,
    /// The position (raw I32F32) at or past which a cycle that begins there starts to
    /// decelerate: the manual point; with automatic deceleration, while speeding up, half the
    /// finish point (rounded up: the pulses left, finish − p, are then ≤ the pulses output while
    /// speeding up, p), and once at DV, the finish point less those pulses. `i64::MAX`: never,
    /// and while decelerating (nothing to start then).
    pub(super) trigger: i64,
    /// A smooth stop was commanded: decelerate to SV, then stop.
    pub(super) stopping: bool,
    /// The move is over (it reached its finish point, or was stopped): the next cycles rest.
    pub(super) complete: bool,
}

impl Rule {
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

    /// The velocity of the next cycle, before the cut to the pulses left (raw I32F32), with the
    /// phase it leaves the move in. The rules (SPEC §12.2): SV at once; up by AC to DV; down by
    /// DC to SV from the cycle that begins at or past the trigger; a smooth stop decelerates at
    /// once and stops from SV.
    fn next_velocity(&mut self, profile: &PerCycle, position: i64, velocity: i64) -> i64 {
        if position >= self.trigger {
            self.decelerate();
        }
        match self.phase {
            Phase::Cruising => velocity,
            Phase::Accelerating => {
                // velocity + AC < DV exactly when velocity < DV − AC (0 ≤ velocity): the sum is
                // formed only below DV, so it never passes i64 (AC alone can near 2⁶³ raw).
                if velocity < profile.below_last_speed_up {
                    return velocity + profile.acceleration;
                }
                let drive = profile.drive;
                self.cruise(profile, position + drive);
                drive
            }
            Phase::Decelerating => {
                // Down by DC. No overflow: 0 ≤ velocity and DC < 2⁶³ in raw bits.
                let next = velocity - profile.deceleration;
                if next > profile.initial {
                    // Above SV + DC before: on the ramp (a smooth stop has nothing to end yet).
                    return next;
                }
                self.reach_initial(profile, velocity)
            }
            // max(SV − DC, SV) = SV, cycle after cycle.
            Phase::Creeping => velocity,
            Phase::Start => self.start(profile),
        }
    }

    /// The deceleration's last step, down to SV (never below: the creep), or, with a smooth stop,
    /// the stop from at or below SV, as the chip's decelerating stop ends.
    fn reach_initial(&mut self, profile: &PerCycle, velocity: i64) -> i64 {
        let initial = profile.initial;
        if self.stopping && velocity <= initial {
            self.complete = true;
            return 0;
        }
        if !self.stopping {
            self.phase = Phase::Creeping;
        }
        initial
    }

    /// The cycle that begins at or past the trigger starts the deceleration; nothing triggers
    /// again.
    pub(super) fn decelerate(&mut self) {
        self.phase = Phase::Decelerating;
        self.trigger = i64::MAX;
    }

    /// The first cycle: SV at once (DV with deceleration disabled).
    fn start(&mut self, profile: &PerCycle) -> i64 {
        if profile.disabled {
            self.phase = Phase::Cruising;
            self.trigger = i64::MAX;
            return profile.drive;
        }
        if profile.initial < profile.drive {
            self.phase = Phase::Accelerating;
        } else {
            self.cruise(profile, profile.initial);
        }
        profile.initial
    }

    /// At DV after a cycle that sped up to `reached` (raw I32F32 pulses): with automatic
    /// deceleration, the trigger becomes the finish point less the pulses output while speeding
    /// up.
    fn cruise(&mut self, profile: &PerCycle, reached: i64) {
        self.phase = Phase::Cruising;
        if profile.automatic {
            self.trigger = profile.finish - reached;
        }
    }
}
