//! The S-curve's future as a [`Prediction`] (SPEC §15): the run of constant jerk under way, then
//! the schedule's remaining runs, each a segment whose closed form starts from the state before
//! it.

use crate::predict::{Piece, Prediction, MAX_SEGMENTS};

use super::{Motion, SCurve, PENDING, SENTINEL};

impl SCurve {
    /// The future of this axis from its present state, for as long as it gets no further
    /// command: the state after any number of cycles, the completion cycle and the cycle that
    /// reaches a position, each without stepping (see [`Prediction`]). Built from the plan's
    /// runs in one pass (at most 45 closed forms).
    ///
    /// A smooth stop is predicted too (it is laid out as jerk changes when it is given), except
    /// from the states it then decides one cycle at a time (`None`; none from a move); a
    /// pending abrupt stop is predicted (its one cycle, then rest).
    ///
    /// ```
    /// use profilegen::format::mc1451a::{Jerk, MaxVelocity, ScurveAcceleration};
    /// use profilegen::{ProfileGenerator, SCurve, ScurveParameters};
    ///
    /// let mut axis = SCurve::new(ScurveParameters {
    ///     destination: 1_000,
    ///     max_velocity: MaxVelocity::from_num(2.75)?,
    ///     max_acceleration: ScurveAcceleration::from_num(0.175)?,
    ///     jerk: Jerk::from_num(0.0075)?,
    /// })?;
    /// let future = axis.predict().unwrap();
    /// assert_eq!(future.completion(), Some(axis.plan().total));
    /// let halfway = future.first_cycle_at(500.into()).unwrap();
    /// let state = future.state_at(halfway);
    /// assert_eq!(axis.states().nth(halfway as usize - 1), Some(state));
    /// assert!(state.position >= 500);
    /// # Ok::<(), profilegen::Error>(())
    /// ```
    pub fn predict(&self) -> Option<Prediction> {
        let state = self.state;
        let velocity = state.velocity.to_bits();
        let mut pieces = [Piece::constant(0, 0); MAX_SEGMENTS];
        let mut count = 0;
        let mut push = |piece: Piece| {
            if let Some(slot) = pieces.get_mut(count) {
                *slot = piece;
                count += 1;
            }
        };
        match self.motion() {
            // Its one cycle (velocity zero, position held), then rest.
            Motion::AbruptPending => {
                push(Piece::constant(0, 1));
                push(Piece::constant(0, 0));
            }
            Motion::Rest => push(Piece::constant(velocity, 0)),
            Motion::Planned | Motion::Stopping if self.arrived() => {
                push(Piece::constant(velocity, 0));
            }
            // A smooth stop decided cycle by cycle.
            Motion::Stopping if self.run.next == SENTINEL => return None,
            Motion::Planned | Motion::Stopping => {
                // The run under way: the jerk for `countdown` more steps from the present
                // acceleration — or, on the first step of a move started right after an abrupt
                // stop, the plan from its start (that step's corrected jerk makes its
                // acceleration the first run's jerk, as from acceleration zero).
                let (acceleration, run) = if self.run.next == PENDING {
                    (0, self.schedule.run(0))
                } else {
                    (state.acceleration.to_bits(), self.run)
                };
                let (jerk, countdown, next) = (run.jerk, run.cycles(), run.after());
                push(Piece {
                    cycles: countdown,
                    c0: velocity,
                    c1: acceleration,
                    c2: jerk,
                    continues: false,
                });
                // Each later run continues from the state the closed forms lead to; the end
                // marker, last, holds the rest for ever (a smooth stop's is the array's last).
                let end = if self.motion() == Motion::Stopping {
                    SENTINEL
                } else {
                    self.schedule.len()
                };
                for index in next..end {
                    let change = self.schedule.change(index);
                    push(Piece::jerk_run(change.jerk, change.hold));
                }
            }
        }
        Prediction::new(state, &pieces[..count])
    }
}
