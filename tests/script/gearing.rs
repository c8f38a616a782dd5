//! Electronic gearing (SPEC §14) scripts: a `Follower` geared to a scripted master — the
//! trapezoid, velocity contouring or the S-curve, its whole command surface, stops included, run
//! in motion — with ratio changes in motion (re-anchoring), deceleration changes (zero refused)
//! and both stops of the follower. Every cycle, while engaged: slave = anchor + ratio · (master
//! travel since the anchor), exactly (i128, modulo the position register's 2⁶⁴ raw wrap), the
//! travel the sum of the master's count changes.

use core::fmt::Debug;

use fixed::types::I32F32;
use profilegen::format::mc1451a::{GearRatio, TrapezoidalAcceleration};
use profilegen::gearing::{ElectronicGear, Follower};
use profilegen::{
    Error, Limits, ProfileGenerator, SCurve, State, StopKind, Trapezoidal, VelocityContouring,
};

use super::{counts, scurve, trapezoidal, velocity, Bytes, Scripted, Step};

/// A master's script: its generator and the steps it runs.
pub trait MasterScript: Clone + Debug {
    /// The master generator.
    type Generator: Scripted;
    /// Builds it (`None`: its registers are refused, as they must be then).
    ///
    /// # Errors
    /// Valid registers refused.
    fn build(&self) -> Result<Option<Self::Generator>, String>;
    /// Its steps.
    fn steps(&self) -> &[Step<<Self::Generator as Scripted>::Command>];
    /// Decodes one from raw bytes (the fuzz target).
    fn decode(bytes: &mut Bytes) -> Self;
}

impl MasterScript for trapezoidal::Script {
    type Generator = Trapezoidal;
    fn build(&self) -> Result<Option<Trapezoidal>, String> {
        trapezoidal::Script::build(self)
    }
    fn steps(&self) -> &[Step<trapezoidal::Command>] {
        &self.steps
    }
    fn decode(bytes: &mut Bytes) -> Self {
        trapezoidal::Script::decode(bytes)
    }
}

impl MasterScript for velocity::Script {
    type Generator = VelocityContouring;
    fn build(&self) -> Result<Option<VelocityContouring>, String> {
        velocity::Script::build(self)
    }
    fn steps(&self) -> &[Step<velocity::Command>] {
        &self.steps
    }
    fn decode(bytes: &mut Bytes) -> Self {
        velocity::Script::decode(bytes)
    }
}

impl MasterScript for scurve::Script {
    type Generator = SCurve;
    fn build(&self) -> Result<Option<SCurve>, String> {
        scurve::Script::build(self)
    }
    fn steps(&self) -> &[Step<scurve::Command>] {
        &self.steps
    }
    fn decode(bytes: &mut Bytes) -> Self {
        scurve::Script::decode(bytes)
    }
}

/// A command to the geared pair.
#[derive(Debug, Clone)]
pub enum Command<C> {
    /// To the master.
    Master(C),
    /// A stop of the master (the follower follows it down).
    MasterStop(StopKind),
    /// A new ratio (raw 1/2^16): re-anchors and re-engages.
    Ratio(i32),
    /// A new smooth-stop deceleration (raw 16.16; zero refused).
    Deceleration(u32),
}

/// The follower, and the test's own account of the gear: what it should be engaged to.
#[derive(Debug, Clone, PartialEq)]
pub struct Geared<M> {
    follower: Follower<M>,
    /// Engaged (by the test's account of SPEC §14: from the start and after a ratio change, until
    /// a stop), with the anchor (slave position bits), the ratio (raw) and the master's travel
    /// since the anchor (counts, unbounded).
    engaged: bool,
    anchor: i64,
    ratio: i64,
    travel: i128,
    /// An abrupt stop not yet stepped (a ratio change then does not re-engage).
    abrupt_pending: bool,
    /// The master's state before the last cycle (for its own checks).
    master_previous: State,
    /// The master was stopped since its last accepted command.
    master_stopped: bool,
}

/// The count a position register shows (the floor).
fn count(state: State) -> i32 {
    (state.position.to_bits() >> 32) as i32
}

impl<M: Scripted> Geared<M> {
    fn new(master: M, ratio: i32, slave: I32F32, deceleration: u32) -> Option<Self> {
        let ratio_register = GearRatio::from_bits(ratio).ok()?;
        let deceleration = TrapezoidalAcceleration::from_bits(deceleration).ok()?;
        let master_previous = master.state();
        let follower = match Follower::new(master, ratio_register, slave, deceleration) {
            Ok(follower) => follower,
            Err(_) => return None, // zero deceleration: refused, as documented
        };
        Some(Self {
            follower,
            engaged: true,
            anchor: slave.to_bits(),
            ratio: i64::from(ratio),
            travel: 0,
            abrupt_pending: false,
            master_previous,
            master_stopped: false,
        })
    }
}

impl<M: Scripted> ProfileGenerator for Geared<M> {
    fn step(&mut self) -> State {
        let before = count(self.follower.master().state());
        self.master_previous = self.follower.master().state();
        let state = self.follower.step();
        let after = count(self.follower.master().state());
        // The master moves less than 2^31 counts a cycle: the change modulo 2^32, signed.
        self.travel += i128::from(after.wrapping_sub(before));
        self.abrupt_pending = false;
        state
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

impl<M: Scripted> Scripted for Geared<M> {
    type Command = Command<M::Command>;

    fn apply(&mut self, command: &Command<M::Command>) -> Result<(), Error> {
        match *command {
            Command::Master(ref command) => {
                self.follower.master_mut().apply(command)?;
                self.master_stopped = false;
            }
            Command::MasterStop(kind) => {
                self.follower.master_mut().stop(kind);
                self.master_stopped = true;
            }
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

    /// Engaged: the master's bound, and a cycle for the follower's last difference. Stopping:
    /// the velocity over the deceleration.
    fn settle_bound(&self, _stopped: bool) -> f64 {
        if self.engaged {
            return self.follower.master().settle_bound(self.master_stopped) + 2.0;
        }
        let limits = self.follower.limits();
        let deceleration = limits.max_slow_down.map_or(f64::INFINITY, |d| d.to_num());
        counts(self.state().velocity.to_bits()).abs() / deceleration + 3.0
    }

    /// Engaged: the master settled and the follower at rest if the master is; else complete.
    fn settled(&self) -> bool {
        if self.engaged {
            // The master settled (at rest, or at its target velocity), the follower at rest with
            // a master at rest.
            let master = self.follower.master();
            master.settled() && (master.state().velocity != 0 || self.state().velocity == 0)
        } else {
            self.is_complete()
        }
    }

    fn velocity_register(&self) -> Option<i64> {
        None
    }

    fn check_cycle(&self, previous: &State, commanded: bool) -> Result<(), String> {
        let master = self.follower.master();
        master.check_cycle(&self.master_previous, commanded)?;
        check_gear(
            (self.engaged, self.anchor, self.ratio, self.travel),
            self.follower.gear(),
            previous,
            self.state(),
            commanded,
        )
    }
}

/// SPEC §14 on one cycle of a follower, against the test's own account `(engaged, anchor, ratio
/// (raw), travel (counts))`: the engagement as accounted; engaged, the slave exactly anchor +
/// ratio · travel (the ratio's 16 fractional bits to I32F32's 32, modulo 2^64 raw units, the
/// register's wrap); disengaged and not commanded, never speeding up, toward zero.
pub fn check_gear(
    (engaged, anchor, ratio, travel): (bool, i64, i64, i128),
    gear: &ElectronicGear,
    previous: &State,
    state: State,
    commanded: bool,
) -> Result<(), String> {
    if engaged != gear.is_engaged() {
        return Err(format!("engaged {}, expected {engaged}", gear.is_engaged()));
    }
    let slave = state.position.to_bits();
    if engaged {
        let expected = i128::from(anchor) + i128::from(ratio) * travel * (1 << 16);
        if expected.rem_euclid(1 << 64) != i128::from(slave as u64) {
            return Err(format!(
                "slave {slave} (bits), expected {expected} mod 2^64: anchor {anchor}, ratio \
                 {ratio}, travel {travel}"
            ));
        }
    } else if !commanded {
        let (before, after) = (previous.velocity.to_bits(), state.velocity.to_bits());
        if after.abs() > before.abs() || after.signum() * before.signum() < 0 {
            return Err(format!("stopping from {before} sped up to {after} (bits)"));
        }
    }
    Ok(())
}

/// The master's script and the gear's.
#[derive(Debug, Clone)]
pub struct Script<S: MasterScript> {
    /// The master.
    pub master: S,
    /// Ratio (raw), the slave's start, the deceleration (raw).
    pub gear: (i32, I32F32, u32),
    /// The steps.
    pub steps: Vec<Step<Command<<S::Generator as Scripted>::Command>>>,
}

impl<S: MasterScript> Script<S> {
    /// Builds the pair and runs the script.
    ///
    /// # Errors
    /// The first check that failed.
    pub fn run(&self, budget: u64) -> Result<u64, String> {
        let Some(master) = self.master.build()? else {
            return Ok(0);
        };
        let (ratio, slave, deceleration) = self.gear;
        match Geared::new(master, ratio, slave, deceleration) {
            Some(geared) => super::run(geared, &self.steps, budget),
            None if deceleration == 0 => Ok(0),
            None => Err("valid gear registers refused".into()),
        }
    }

    /// The master's own steps as the pair's — its commands and stops to the master, or (stops,
    /// where `to_master` says no) to the follower — with the gear's commands inserted (at
    /// indices into the growing list, reduced modulo its length + 1).
    pub fn from_master(
        master: S,
        gear: (i32, I32F32, u32),
        inserts: Vec<(usize, Command<<S::Generator as Scripted>::Command>)>,
        to_master: &[bool],
    ) -> Self {
        let mut steps: Vec<_> = master
            .steps()
            .iter()
            .enumerate()
            .map(|(i, step)| match step {
                Step::Run(k) => Step::Run(*k),
                Step::RunFraction(f) => Step::RunFraction(*f),
                Step::Command(c) => Step::Command(Command::Master(c.clone())),
                // A stop to the master half the time, else to the follower.
                Step::Stop(kind) if to_master.get(i % to_master.len().max(1)) == Some(&true) => {
                    Step::Command(Command::MasterStop(*kind))
                }
                Step::Stop(kind) => Step::Stop(*kind),
                Step::Finish => Step::Finish,
            })
            .collect();
        for (at, command) in inserts {
            let at = at % (steps.len() + 1);
            steps.insert(at, Step::Command(command));
        }
        Self {
            master,
            gear,
            steps,
        }
    }

    /// Decodes a script from raw bytes (the fuzz target).
    pub fn decode(bytes: &mut Bytes) -> Self {
        let master = S::decode(bytes);
        let ratio = bytes
            .boosted_signed(1 << 30)
            .clamp(-(1 << 30), (1 << 30) - 1) as i32;
        let slave = bytes.position();
        let deceleration = bytes.boosted(TrapezoidalAcceleration::MAX_BITS.into()) as u32;
        let to_master: Vec<bool> = (0..12).map(|_| bytes.byte() & 1 == 0).collect();
        let inserts = (0..bytes.byte() % 5)
            .map(|_| {
                let at = usize::from(bytes.byte());
                let command = if bytes.byte() % 4 == 0 {
                    Command::Deceleration(
                        bytes.boosted(TrapezoidalAcceleration::MAX_BITS.into()) as u32
                    )
                } else {
                    Command::Ratio(
                        bytes
                            .boosted_signed(1 << 30)
                            .clamp(-(1 << 30), (1 << 30) - 1) as i32,
                    )
                };
                (at, command)
            })
            .collect();
        Self::from_master(master, (ratio, slave, deceleration), inserts, &to_master)
    }
}

/// The proptest strategy for a master's scripts: its own script, its commands and stops given
/// to the master or (stops) to the follower, with ratio and deceleration changes mixed in.
#[cfg(test)]
pub fn script<S: MasterScript + 'static>(
    master: impl proptest::strategy::Strategy<Value = S> + 'static,
) -> impl proptest::strategy::Strategy<Value = Script<S>>
where
    <S::Generator as Scripted>::Command: 'static,
{
    use super::{boosted, boosted_signed, position};
    use proptest::prelude::*;
    let ratio =
        || boosted_signed(1 << 30).prop_map(|bits| bits.clamp(-(1 << 30), (1 << 30) - 1) as i32);
    let deceleration =
        || boosted(0, TrapezoidalAcceleration::MAX_BITS.into()).prop_map(|bits| bits as u32);
    let gear_command = prop_oneof![
        3 => ratio().prop_map(Command::Ratio),
        1 => deceleration().prop_map(Command::Deceleration),
    ];
    (
        master,
        (ratio(), position(), deceleration()),
        prop::collection::vec((any::<usize>(), gear_command), 0..4),
        prop::collection::vec(any::<bool>(), 12),
    )
        .prop_map(|(master, gear, inserts, to_master)| {
            Script::from_master(master, gear, inserts, &to_master)
        })
}
