//! The trapezoid's future as a [`Prediction`] (SPEC §15): the plan's runs of constant velocity
//! change, laid out at command time, read from the one under way to the rest run.

use crate::predict::{Piece, Prediction, MAX_SEGMENTS};

use super::{Phase, Trapezoidal, ELSEWHERE, RUNS};
use crate::replay::Replay;

/// Whether `run` is the rest run (velocity zero "for ever"): its count starts at `u64::MAX` and
/// falls by one per step, which no move lives long enough to bring below 2^63.
fn is_rest(run: &Replay) -> bool {
    run.next() == 0 && run.increment() == 0 && run.cycles() >= 1 << 63
}

impl Trapezoidal {
    /// The future of this axis from its present state, for as long as it gets no further
    /// command: the state after any number of cycles, the completion cycle and the cycle that
    /// reaches a position, each without stepping (see [`Prediction`]). Read from the plan's
    /// runs (at most eight), one closed form each.
    ///
    /// `None` while the axis decides cycle by cycle (after a command in motion left it moving
    /// away from its destination by more than 2³¹ counts, above its maximum velocity, or too
    /// fast to stop on the destination: the cycle after such a decision plans again). A
    /// pending abrupt stop is predicted: its cycle, then rest — or, when a new maximum velocity
    /// came since, the plan from the state it leaves.
    ///
    /// ```
    /// use profilegen::format::juno::{Acceleration, TargetVelocity};
    /// use profilegen::{ProfileGenerator, Trapezoidal, TrapezoidalParameters};
    ///
    /// let mut axis = Trapezoidal::new(TrapezoidalParameters {
    ///     destination: 1_000,
    ///     max_velocity: TargetVelocity::from_num(20.0)?,
    ///     acceleration: Acceleration::from_num(0.5)?,
    ///     deceleration: Acceleration::ZERO,
    ///     start_velocity: TargetVelocity::ZERO,
    /// })?;
    /// let future = axis.predict().unwrap();
    /// let complete = future.completion().unwrap();
    /// assert_eq!(future.state_at(complete).position, 1_000);
    /// assert_eq!(axis.states_until_complete().count() as u64, complete);
    /// # Ok::<(), profilegen::Error>(())
    /// ```
    pub fn predict(&self) -> Option<Prediction> {
        if self.current % RUNS == ELSEWHERE {
            return match self.phase {
                Phase::AbruptPending { .. } => {
                    // One step (the abrupt stop's, or its resumption's plan) is no loop: the
                    // future after it is the plan it leaves, one cycle later.
                    let mut after = self.clone();
                    crate::ProfileGenerator::step(&mut after);
                    Prediction::after_step(self.state, &after.predict()?)
                }
                _ => None,
            };
        }
        let mut pieces = [Piece::constant(0, 0); MAX_SEGMENTS];
        let first = self.current % RUNS;
        for (count, (slot, run)) in self.runs.iter().enumerate().skip(first).enumerate() {
            if slot == ELSEWHERE {
                // A plan that ends in a decision: not predicted.
                return None;
            }
            pieces[count] = Piece::run(run.next(), run.increment(), run.cycles());
            if is_rest(run) {
                return Prediction::new(self.state, &pieces[..=count]);
            }
        }
        None
    }
}
