//! Electronic gearing to an encoder (SPEC §14) scripts: an `EncoderFollower` whose master is a
//! scripted encoder (a start count anywhere, near the ±2³¹ wrap too, then runs of cycles each
//! moving by a constant change of up to ±(2³¹ − 1) counts, then standing still), with ratio
//! changes in motion (re-anchoring), deceleration changes (zero refused) and both stops. Every
//! cycle, while engaged: slave = anchor + ratio · (encoder travel since the anchor), exactly
//! (i128, modulo the position register's 2⁶⁴ raw wrap), the travel the sum of the script's own
//! changes (not of the wrapped counts the follower sees). Every ratio is held to the documented
//! range of the follower's speed: |ratio · change| < 2³⁰ counts per cycle for the script's
//! largest change (a change of 2³¹ − 1 counts a cycle runs with ratios up to ½, one of 2¹⁶
//! with all of them).

use fixed::types::I32F32;
use profilegen::format::mc1451a::{GearRatio, TrapezoidalAcceleration};
use profilegen::gearing::EncoderFollower;
use profilegen::{Error, Limits, ProfileGenerator, State, StopKind};

use super::gearing::check_gear;
use super::{counts, Bytes, Scripted, Step};

/// The most an encoder moves in a cycle (the gear undoes the wrap of changes below 2³¹).
const MAX_CHANGE: i64 = (1 << 31) - 1;

/// The scripted encoder: its count, and runs of (cycles, change per cycle); past the last run
/// it has no more counts (the follower's master then stands still).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Encoder {
    count: i32,
    runs: Vec<(u32, i32)>,
    run: usize,
    done: u32,
}

impl Encoder {
    /// The next cycle's count and the change that made it (unwrapped); `None` past the runs.
    fn advance(&mut self) -> Option<(i32, i32)> {
        loop {
            let &(cycles, change) = self.runs.get(self.run)?;
            if self.done < cycles {
                self.done += 1;
                self.count = self.count.wrapping_add(change);
                return Some((self.count, change));
            }
            self.run += 1;
            self.done = 0;
        }
    }

    /// The cycles of counts still to come.
    fn left(&self) -> u64 {
        let rest: u64 = self
            .runs
            .iter()
            .skip(self.run)
            .map(|&(c, _)| u64::from(c))
            .sum();
        rest - u64::from(self.done.min(self.runs.get(self.run).map_or(0, |r| r.0)))
    }
}

impl Iterator for Encoder {
    type Item = i32;
    fn next(&mut self) -> Option<i32> {
        self.advance().map(|(count, _)| count)
    }
}

/// The largest ratio (raw, magnitude) a script whose largest change is `change` counts may
/// use: the follower's speed |ratio · change| / 2¹⁶ below 2³⁰ counts per cycle (the gear's
/// documented range), at most the register's 2³⁰.
fn ratio_limit(runs: &[(u32, i32)]) -> i64 {
    let change = runs
        .iter()
        .map(|&(_, c)| i64::from(c).abs())
        .max()
        .unwrap_or(0);
    ((1i64 << 46) - 1)
        .checked_div(change)
        .map_or(1 << 30, |limit| limit.min(1 << 30))
}

/// `bits` held to ±`limit` (and the register's range).
fn held(bits: i64, limit: i64) -> i32 {
    bits.clamp(-limit.min(1 << 30), limit.min((1 << 30) - 1)) as i32
}

/// A command to the gear.
#[derive(Debug, Clone)]
pub enum Command {
    /// A new ratio (raw 1/2^16): re-anchors and re-engages.
    Ratio(i32),
    /// A new smooth-stop deceleration (raw 16.16; zero refused).
    Deceleration(u32),
}

/// The follower, the test's own copy of its encoder, and the test's account of the gear.
#[derive(Debug, Clone, PartialEq)]
pub struct Geared {
    follower: EncoderFollower<Encoder>,
    /// The encoder as the test steps it, beside the follower's.
    encoder: Encoder,
    /// Engaged (by the test's account of SPEC §14: from the start and after a ratio change,
    /// until a stop), with the anchor (slave position bits), the ratio (raw) and the encoder's
    /// travel since the anchor (counts, unbounded).
    engaged: bool,
    anchor: i64,
    ratio: i64,
    travel: i128,
    /// An abrupt stop not yet stepped (a ratio change then does not re-engage).
    abrupt_pending: bool,
}

impl ProfileGenerator for Geared {
    fn step(&mut self) -> State {
        if let Some((_, change)) = self.encoder.advance() {
            self.travel += i128::from(change);
        }
        self.abrupt_pending = false;
        self.follower.step()
    }
    fn state(&self) -> State {
        self.follower.state()
    }
    fn is_complete(&self) -> bool {
        self.follower.is_complete()
    }
    fn stop(&mut self, kind: StopKind) {
        if self.engaged || !self.follower.is_complete() {
            self.abrupt_pending |= kind == StopKind::Abrupt && !self.follower.is_complete();
        }
        self.engaged = false;
        self.follower.stop(kind);
    }
    fn limits(&self) -> Limits {
        self.follower.limits()
    }
}

impl Scripted for Geared {
    type Command = Command;

    fn apply(&mut self, command: &Command) -> Result<(), Error> {
        match *command {
            Command::Ratio(bits) => {
                let ratio = GearRatio::from_bits(bits)?;
                self.follower.gear_mut().set_ratio(ratio);
                if !self.abrupt_pending {
                    self.engaged = true;
                }
                self.anchor = self.follower.state().position.to_bits();
                self.ratio = i64::from(bits);
                self.travel = 0;
            }
            Command::Deceleration(bits) => {
                let deceleration = TrapezoidalAcceleration::from_bits(bits)?;
                self.follower.gear_mut().set_deceleration(deceleration)?;
            }
        }
        Ok(())
    }

    /// Engaged: the encoder's cycles still to come, and a cycle for the follower's last
    /// difference. Stopping: the velocity over the deceleration.
    fn settle_bound(&self, _stopped: bool) -> f64 {
        if self.engaged {
            return self.encoder.left() as f64 + 2.0;
        }
        let limits = self.follower.limits();
        let deceleration = limits.max_slow_down.map_or(f64::INFINITY, |d| d.to_num());
        counts(self.state().velocity.to_bits()).abs() / deceleration + 3.0
    }

    /// Engaged: the encoder run out and the follower at rest; else complete.
    fn settled(&self) -> bool {
        if self.engaged {
            self.encoder.left() == 0 && self.state().velocity == 0
        } else {
            self.is_complete()
        }
    }

    fn velocity_register(&self) -> Option<i64> {
        None
    }

    fn check_cycle(&self, previous: &State, commanded: bool) -> Result<(), String> {
        check_gear(
            (self.engaged, self.anchor, self.ratio, self.travel),
            self.follower.gear(),
            previous,
            self.state(),
            commanded,
        )
    }
}

/// The encoder's script and the gear's.
#[derive(Debug, Clone)]
pub struct Script {
    /// The encoder's count at the start and its runs (cycles, change per cycle).
    pub encoder: (i32, Vec<(u32, i32)>),
    /// Ratio (raw), the slave's start, the deceleration (raw).
    pub gear: (i32, I32F32, u32),
    /// The steps.
    pub steps: Vec<Step<Command>>,
}

impl Script {
    /// Builds the follower and runs the script.
    ///
    /// # Errors
    /// The first check that failed.
    pub fn run(&self, budget: u64) -> Result<u64, String> {
        let (start, ref runs) = self.encoder;
        let encoder = Encoder {
            count: start,
            runs: runs.clone(),
            run: 0,
            done: 0,
        };
        let (ratio, slave, deceleration) = self.gear;
        let (Ok(ratio_register), Ok(deceleration_register)) = (
            GearRatio::from_bits(ratio),
            TrapezoidalAcceleration::from_bits(deceleration),
        ) else {
            return Err("a register in its range refused".into());
        };
        let follower = match EncoderFollower::new(
            encoder.clone(),
            start,
            ratio_register,
            slave,
            deceleration_register,
        ) {
            Ok(follower) => follower,
            Err(_) if deceleration == 0 => return Ok(0), // refused, as documented
            Err(error) => return Err(format!("valid gear registers refused: {error}")),
        };
        let geared = Geared {
            follower,
            encoder,
            engaged: true,
            anchor: slave.to_bits(),
            ratio: i64::from(ratio),
            travel: 0,
            abrupt_pending: false,
        };
        super::run(geared, &self.steps, budget)
    }

    /// Decodes a script from raw bytes (the fuzz target).
    pub fn decode(bytes: &mut Bytes) -> Self {
        let start = match bytes.byte() % 3 {
            0 => i32::MAX - (bytes.bits(2) % 512) as i32,
            1 => i32::MIN + (bytes.bits(2) % 512) as i32,
            _ => bytes.bits(4) as u32 as i32,
        };
        let runs: Vec<(u32, i32)> = (0..bytes.byte() % 9)
            .map(|_| {
                let cycles = bytes.bits(2) as u32 % 600;
                (cycles, bytes.boosted_signed(MAX_CHANGE as u64) as i32)
            })
            .collect();
        let limit = ratio_limit(&runs);
        let ratio = held(bytes.boosted_signed(1 << 30), limit);
        let slave = bytes.position();
        let deceleration = bytes.boosted(TrapezoidalAcceleration::MAX_BITS.into()) as u32;
        let steps =
            bytes.steps(|bytes| {
                Some(if bytes.byte() % 4 == 0 {
                    Command::Deceleration(
                        bytes.boosted(TrapezoidalAcceleration::MAX_BITS.into()) as u32
                    )
                } else {
                    Command::Ratio(held(bytes.boosted_signed(1 << 30), limit))
                })
            });
        Self {
            encoder: (start, runs),
            gear: (ratio, slave, deceleration),
            steps,
        }
    }
}

/// The proptest strategy.
#[cfg(test)]
pub fn script() -> impl proptest::strategy::Strategy<Value = Script> {
    use super::{boosted, boosted_signed, position, steps};
    use proptest::prelude::*;
    let start = prop_oneof![
        1 => (0i32..512).prop_map(|near| i32::MAX - near),
        1 => (0i32..512).prop_map(|near| i32::MIN + near),
        2 => any::<i32>(),
    ];
    let run = (
        prop_oneof![0u32..8, 0u32..600],
        boosted_signed(MAX_CHANGE as u64).prop_map(|change| change as i32),
    );
    // Ratios as raw values, held to the script's limit once its runs are known.
    let ratio = || boosted_signed(1 << 30);
    let deceleration =
        || boosted(0, TrapezoidalAcceleration::MAX_BITS.into()).prop_map(|bits| bits as u32);
    let command = prop_oneof![
        3 => ratio().prop_map(|bits| Command::Ratio(bits as i32)),
        1 => deceleration().prop_map(Command::Deceleration),
    ];
    (
        (start, prop::collection::vec(run, 0..8)),
        (ratio(), position(), deceleration()),
        steps(command, 12),
    )
        .prop_map(|((start, runs), (ratio, slave, deceleration), steps)| {
            let limit = ratio_limit(&runs);
            let steps = steps
                .into_iter()
                .map(|step| match step {
                    Step::Command(Command::Ratio(bits)) => {
                        Step::Command(Command::Ratio(held(bits.into(), limit)))
                    }
                    step => step,
                })
                .collect();
            Script {
                encoder: (start, runs),
                gear: (held(ratio, limit), slave, deceleration),
                steps,
            }
        })
}
