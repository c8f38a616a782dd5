//! The Cortex-M4 instruction-count probe (SPEC §16).
//!
//! A bare-metal `thumbv7em-none-eabihf` image with no reset handler and no vector table: the
//! harness (`tools/count_instructions.py`) loads it into an emulator and calls the exported
//! `extern "C"` functions below by their symbols, counting the instructions each call executes,
//! from its first instruction to its return.
//!
//! - `probe_move(index, out)`: move `index` of `benches/common/moves.rs` as raw register bits.
//! - `probe_plan_bits(destination, velocity, acceleration, jerk)`: the measured planning call:
//!   the registers from their bits, `SCurve::new` (the whole plan), the generator kept.
//! - `probe_plan(index)`: the same for move `index`, the move generated on the target too.
//! - `probe_step_setup(...)`, `probe_phases(out)`, `probe_step()`: one generator in a static,
//!   stepped one cycle per call, so every cycle's cost is measured on its own.
//! - `probe_restart(destination, velocity)`: that generator restarted after a stop.
//! - `probe_replan_reset()`, `probe_replan_bits(destination, velocity, acceleration, jerk)`: a
//!   generator at rest on 0, and a move planned into it in place (`set_parameters`), as
//!   firmware that keeps its generator starts a move.
//! - `probe_gear_setup(ratio, deceleration)`, `probe_gear_follow(master)`,
//!   `probe_gear_command(command, value)`: an MC1451A electronic gear (`ElectronicGear`), one
//!   `follow` per call with the master's count, and its stops and ratio changes.
//! - `probe_velocity_setup(velocity, acceleration, deceleration)`, `probe_velocity_step()`:
//!   the same for `VelocityContouring` (Juno registers as raw bits).
//! - `probe_trapezoid_setup(words)` (destination, maximum velocity, acceleration, deceleration,
//!   starting velocity as raw bits), `probe_trapezoid_step()`, `probe_trapezoid_complete()`:
//!   the same for `Trapezoidal`; the setup is the measured "starting a move" (it plans).
//! - `probe_trapezoid_command(command, value)`: a stop or a new destination in motion, so the
//!   cycles that follow can be counted too.
//! - `probe_line_setup(words)`, `probe_line_step_<profile>()`, `probe_line_complete()`: a 3-axis
//!   linear interpolation (SPEC §12.3) driven by one of the profiles (`mcx514` the MCX514
//!   trapezoid, `trapezoid` the crate's `Trapezoidal`, `mcx514_scurve` the MCX514 S-curve,
//!   `scurve` the crate's `SCurve`), stepped one cycle per call through
//!   `LinearInterpolation::step`: the measured cost is the profile plus the geometry (SPEC §16).
//! - `probe_axis_step_<profile>()`, `probe_axis_complete()`: the MCX514 trapezoid or S-curve
//!   alone (set up by `probe_line_setup` with profile 3 or 4), its cycle as a one-axis
//!   generator's.
//! - `probe_circle_setup(words)`, `probe_circle_step_<profile>()`, `probe_circle_complete(p)`,
//!   `probe_circle_axes()`: an MCX514 circular interpolation (SPEC §12.4) driven by
//!   `Mcx514Trapezoidal` or the crate's `Trapezoidal`; a step is the profile's cycle plus the
//!   arc's O(1) jump (SPEC §16's 150 is for the two together).
//! - `probe_selftest_panic(1)`, `probe_selftest_runaway()`: a panic and an endless loop, so the
//!   harness can check that it catches both.
#![no_std]
#![no_main]

use core::cell::UnsafeCell;
use core::hint::black_box;
use core::mem::MaybeUninit;
use core::panic::PanicInfo;
use core::sync::atomic::{AtomicU32, Ordering};

use profilegen::format::juno::{Acceleration, TargetVelocity};
use profilegen::format::mc1451a::{
    GearRatio, Jerk, MaxVelocity, ScurveAcceleration, TrapezoidalAcceleration,
};
use profilegen::format::{mcx514, CycleTime};
use profilegen::gearing::ElectronicGear;
use profilegen::interpolation::{
    Arc, ArcWalk, CircularDriving, Direction, InterpolationState, Line, LinearInterpolation,
};
use profilegen::{
    DecelerationMode, Error, Mcx514Parameters, Mcx514SCurve, Mcx514ScurveParameters,
    Mcx514Trapezoidal, ProfileGenerator, SCurve, ScurveParameters, Trapezoidal,
    TrapezoidalParameters, VelocityContouring, VelocityParameters,
};

#[allow(dead_code)] // the probe takes the raw bits, `scurve_move`
#[path = "../../benches/common/moves.rs"]
mod moves;

/// What the planning entry points return when the registers are refused.
const REFUSED: u64 = u64::MAX;

fn parameters(
    destination: i32,
    velocity: u32,
    acceleration: u32,
    jerk: u32,
) -> Result<ScurveParameters, Error> {
    Ok(ScurveParameters {
        // `SCurve::new` checks the destination register's range itself.
        destination,
        max_velocity: MaxVelocity::from_bits(velocity)?,
        // The register is 16 bits; a wider value is out of range, as from_bits would say.
        max_acceleration: ScurveAcceleration::from_bits(
            u16::try_from(acceleration).unwrap_or(u16::MAX),
        )?,
        jerk: Jerk::from_bits(jerk)?,
    })
}

fn plan(destination: i32, velocity: u32, acceleration: u32, jerk: u32) -> u64 {
    // The result is looked at where `SCurve::new` returned it, as a caller keeping it would:
    // moving it out of the `Result` would copy the whole generator, which is not planning.
    match &parameters(destination, velocity, acceleration, jerk).and_then(SCurve::new) {
        Ok(axis) => {
            // The whole generator is the result, not only the total: without this the optimizer
            // could drop the parts of planning that `duration()` does not depend on.
            black_box(axis).duration()
        }
        Err(_) => REFUSED,
    }
}

/// Plans the move with these raw register bits and returns its total cycle count
/// (`u64::MAX` when a register is refused). The budgeted call: SPEC §16's "starting a move".
#[no_mangle]
pub extern "C" fn probe_plan_bits(
    destination: i32,
    velocity: u32,
    acceleration: u32,
    jerk: u32,
) -> u64 {
    plan(destination, velocity, acceleration, jerk)
}

/// As [`probe_plan_bits`], for a move of `distance` raw units (2^-32 counts, `distance ≥ 1`) to
/// count 7 from the fractional position it leaves: the moves a stop leaves to plan (the
/// planner's `pure_jerk` plans many of them). Returns the total cycle count.
#[no_mangle]
pub extern "C" fn probe_plan_sub_count(
    distance: u32,
    velocity: u32,
    acceleration: u32,
    jerk: u32,
) -> u64 {
    let start = profilegen::fixed::types::I32F32::from_bits((7i64 << 32) - i64::from(distance));
    match &parameters(7, velocity, acceleration, jerk)
        .and_then(|parameters| SCurve::with_position(parameters, start))
    {
        Ok(axis) => black_box(axis).duration(),
        Err(_) => REFUSED,
    }
}

/// As [`probe_plan_bits`] for move `index` of `moves.rs`, generated here.
#[no_mangle]
pub extern "C" fn probe_plan(index: u32) -> u64 {
    let (destination, velocity, acceleration, jerk) = moves::scurve_move(u64::from(index));
    plan(destination, velocity, u32::from(acceleration), jerk)
}

/// Writes move `index` to `out[0..4]`: destination (as `i32` bits), velocity, acceleration, jerk.
///
/// # Safety
/// `out` points to 4 writable, aligned words.
#[no_mangle]
pub unsafe extern "C" fn probe_move(index: u32, out: *mut u32) {
    let (destination, velocity, acceleration, jerk) = moves::scurve_move(u64::from(index));
    // SAFETY: the caller provides 4 words.
    unsafe {
        out.write(destination as u32);
        out.add(1).write(velocity);
        out.add(2).write(u32::from(acceleration));
        out.add(3).write(jerk);
    }
}

/// The generator that `probe_step` advances: one slot, used by one thread (the emulator's).
struct Slot(UnsafeCell<MaybeUninit<SCurve>>);

// SAFETY: the probe is single-threaded with no interrupts; the harness calls one function at a
// time.
unsafe impl Sync for Slot {}

static AXIS: Slot = Slot(UnsafeCell::new(MaybeUninit::uninit()));

/// Plans the move with these raw register bits into the stepped generator; returns its total cycle
/// count, or `u64::MAX` (and leaves the generator as it was) when a register is refused.
#[no_mangle]
pub extern "C" fn probe_step_setup(
    destination: i32,
    velocity: u32,
    acceleration: u32,
    jerk: u32,
) -> u64 {
    match parameters(destination, velocity, acceleration, jerk).and_then(SCurve::new) {
        Ok(axis) => {
            let total = axis.duration();
            // SAFETY: single-threaded; no reference to the slot outlives a call.
            unsafe { (*AXIS.0.get()).write(axis) };
            total
        }
        Err(_) => REFUSED,
    }
}

/// Writes the stepped generator's plan to `out[0..7]`: the cycles of phases I–VII (saturated to
/// `u32`).
///
/// # Safety
/// `out` points to 7 writable, aligned words; `probe_step_setup` succeeded before.
#[no_mangle]
pub unsafe extern "C" fn probe_phases(out: *mut u32) {
    // SAFETY: initialized by probe_step_setup (the caller's contract); single-threaded.
    let axis = unsafe { (*AXIS.0.get()).assume_init_ref() };
    for (i, &phase) in axis.plan().phases.iter().enumerate() {
        // SAFETY: the caller provides 7 words.
        unsafe { out.add(i).write(u32::try_from(phase).unwrap_or(u32::MAX)) };
    }
}

/// Advances the stepped generator one cycle; returns the new position (I32F32 bits).
///
/// # Safety
/// `probe_step_setup` succeeded before.
#[no_mangle]
pub unsafe extern "C" fn probe_step() -> i64 {
    // SAFETY: initialized by probe_step_setup (the caller's contract); single-threaded.
    let axis = unsafe { (*AXIS.0.get()).assume_init_mut() };
    axis.step().position.to_bits()
}

/// Stops the stepped S-curve generator in motion: 0 smoothly, else abruptly.
///
/// # Safety
/// `probe_step_setup` succeeded before.
#[no_mangle]
pub unsafe extern "C" fn probe_stop(kind: u32) {
    // SAFETY: initialized by probe_step_setup (the caller's contract); single-threaded.
    let axis = unsafe { (*AXIS.0.get()).assume_init_mut() };
    axis.stop(if kind == 0 {
        profilegen::StopKind::Smooth
    } else {
        profilegen::StopKind::Abrupt
    });
}

/// Restarts the stepped S-curve generator (after a stop): `SCurve::restart` to `destination`
/// counts with the maximum velocity `velocity` (raw bits); 0 when it took the move, else 1.
///
/// # Safety
/// `probe_step_setup` succeeded before.
#[no_mangle]
pub unsafe extern "C" fn probe_restart(destination: i32, velocity: u32) -> u32 {
    // SAFETY: initialized by probe_step_setup (the caller's contract); single-threaded.
    let axis = unsafe { (*AXIS.0.get()).assume_init_mut() };
    match MaxVelocity::from_bits(velocity).and_then(|velocity| axis.restart(destination, velocity))
    {
        Ok(()) => 0,
        Err(_) => 1,
    }
}

/// The generator that `probe_replan_bits` plans into, in place: what firmware that keeps one
/// generator per axis does to start each move.
static REPLAN: Slot = Slot(UnsafeCell::new(MaybeUninit::uninit()));

/// Puts the re-planned generator at rest on 0 with nothing to do (a move of no distance), ready
/// for `probe_replan_bits`: not part of what that call counts.
#[no_mangle]
pub extern "C" fn probe_replan_reset() -> u32 {
    match parameters(0, 1, 1, 1).and_then(SCurve::new) {
        Ok(axis) => {
            // SAFETY: single-threaded; no reference to the slot outlives a call.
            unsafe { (*REPLAN.0.get()).write(axis) };
            0
        }
        Err(_) => 1,
    }
}

/// As [`probe_plan_bits`], planned in place into the generator `probe_replan_reset` put at rest
/// on 0 (`SCurve::set_parameters`: no generator cleared or copied out). Returns the move's total
/// cycle count, `u64::MAX` when refused.
///
/// # Safety
/// `probe_replan_reset` succeeded before, and no move has been planned since.
#[no_mangle]
pub unsafe extern "C" fn probe_replan_bits(
    destination: i32,
    velocity: u32,
    acceleration: u32,
    jerk: u32,
) -> u64 {
    // SAFETY: initialized by probe_replan_reset (the caller's contract); single-threaded.
    let axis = unsafe { (*REPLAN.0.get()).assume_init_mut() };
    match parameters(destination, velocity, acceleration, jerk)
        .and_then(|parameters| axis.set_parameters(parameters))
    {
        Ok(()) => black_box(&*axis).duration(),
        Err(_) => REFUSED,
    }
}

/// 1 when the stepped S-curve generator is complete, else 0.
///
/// # Safety
/// `probe_step_setup` succeeded before.
#[no_mangle]
pub unsafe extern "C" fn probe_complete() -> u32 {
    // SAFETY: initialized by probe_step_setup (the caller's contract); single-threaded.
    let axis = unsafe { (*AXIS.0.get()).assume_init_ref() };
    u32::from(axis.is_complete())
}

/// A generator slot like [`AXIS`], for the other generators.
struct Other<T>(UnsafeCell<MaybeUninit<T>>);

// SAFETY: as for `Slot`.
unsafe impl<T> Sync for Other<T> {}

static VELOCITY: Other<VelocityContouring> = Other(UnsafeCell::new(MaybeUninit::uninit()));
static GEAR: Other<ElectronicGear> = Other(UnsafeCell::new(MaybeUninit::uninit()));
static TRAPEZOID: Other<Trapezoidal> = Other(UnsafeCell::new(MaybeUninit::uninit()));

/// Sets up an MC1451A electronic gear (SPEC §14): ratio `ratio` (16.16 bits), the master's
/// count 0, the follower at rest at 0, smooth-stop deceleration `deceleration` (raw); 0 on
/// success, 1 when refused.
#[no_mangle]
pub extern "C" fn probe_gear_setup(ratio: i32, deceleration: u32) -> u32 {
    let gear = || -> Result<ElectronicGear, Error> {
        ElectronicGear::new(
            GearRatio::from_bits(ratio)?,
            0,
            profilegen::fixed::types::I32F32::ZERO,
            TrapezoidalAcceleration::from_bits(deceleration)?,
        )
    };
    match gear() {
        Ok(gear) => {
            // SAFETY: single-threaded; no reference to the slot outlives a call.
            unsafe { (*GEAR.0.get()).write(gear) };
            0
        }
        Err(_) => 1,
    }
}

/// One cycle of the gear with the master's count `master` (`ElectronicGear::follow`, the
/// follower's cycle); returns the follower's position.
///
/// # Safety
/// `probe_gear_setup` succeeded before.
#[no_mangle]
pub unsafe extern "C" fn probe_gear_follow(master: i32) -> i64 {
    // SAFETY: initialized by probe_gear_setup (the caller's contract); single-threaded.
    let gear = unsafe { (*GEAR.0.get()).assume_init_mut() };
    gear.follow(master).position.to_bits()
}

/// Gives the gear a command: 0 a smooth stop, 1 an abrupt stop, 2 the new ratio `value` (16.16
/// bits; refused values change nothing).
///
/// # Safety
/// `probe_gear_setup` succeeded before.
#[no_mangle]
pub unsafe extern "C" fn probe_gear_command(command: u32, value: i32) {
    // SAFETY: initialized by probe_gear_setup (the caller's contract); single-threaded.
    let gear = unsafe { (*GEAR.0.get()).assume_init_mut() };
    match command {
        0 => gear.stop(profilegen::StopKind::Smooth),
        1 => gear.stop(profilegen::StopKind::Abrupt),
        _ => {
            if let Ok(ratio) = GearRatio::from_bits(value) {
                gear.set_ratio(ratio);
            }
        }
    }
}

/// Sets up the stepped velocity-contouring generator from raw Juno registers; 0 on success,
/// 1 when refused.
#[no_mangle]
pub extern "C" fn probe_velocity_setup(velocity: i32, acceleration: u32, deceleration: u32) -> u32 {
    let parameters = || -> Result<VelocityContouring, Error> {
        VelocityContouring::new(VelocityParameters {
            velocity: TargetVelocity::from_bits(velocity)?,
            acceleration: Acceleration::from_bits(acceleration)?,
            deceleration: Acceleration::from_bits(deceleration)?,
        })
    };
    match parameters() {
        Ok(axis) => {
            // SAFETY: single-threaded; no reference to the slot outlives a call.
            unsafe { (*VELOCITY.0.get()).write(axis) };
            0
        }
        Err(_) => 1,
    }
}

/// Advances the stepped velocity-contouring generator one cycle; returns the new position.
///
/// # Safety
/// `probe_velocity_setup` succeeded before.
#[no_mangle]
pub unsafe extern "C" fn probe_velocity_step() -> i64 {
    // SAFETY: initialized by probe_velocity_setup (the caller's contract); single-threaded.
    let axis = unsafe { (*VELOCITY.0.get()).assume_init_mut() };
    axis.step().position.to_bits()
}

/// Gives the stepped velocity-contouring generator a command in motion: 0 a smooth stop, 1 an
/// abrupt stop, 2 the new target velocity `value` (16.16 bits), 3 the new acceleration and 4 the
/// new deceleration `value` (8.24 bits); refused values change nothing.
///
/// # Safety
/// `probe_velocity_setup` succeeded before.
#[no_mangle]
pub unsafe extern "C" fn probe_velocity_command(command: u32, value: i32) {
    // SAFETY: initialized by probe_velocity_setup (the caller's contract); single-threaded.
    let axis = unsafe { (*VELOCITY.0.get()).assume_init_mut() };
    match command {
        0 => axis.stop(profilegen::StopKind::Smooth),
        1 => axis.stop(profilegen::StopKind::Abrupt),
        2 => {
            if let Ok(v) = TargetVelocity::from_bits(value) {
                axis.set_velocity(v);
            }
        }
        3 => {
            let _ = Acceleration::from_bits(value as u32).and_then(|a| axis.set_acceleration(a));
        }
        _ => {
            if let Ok(d) = Acceleration::from_bits(value as u32) {
                axis.set_deceleration(d);
            }
        }
    }
}

/// Sets up the stepped trapezoid from `words[0..5]`: destination, maximum velocity (16.16),
/// acceleration and deceleration (8.24), starting velocity (16.16), raw bits; 0 on success, 1
/// when refused. The measured "starting a move": validation and the plan.
///
/// # Safety
/// `words` points to 5 readable, aligned words.
#[no_mangle]
pub unsafe extern "C" fn probe_trapezoid_setup(words: *const u32) -> u32 {
    // SAFETY: the caller provides 5 words.
    let word = |i: usize| unsafe { words.add(i).read() };
    let parameters = || -> Result<Trapezoidal, Error> {
        Trapezoidal::new(TrapezoidalParameters {
            destination: word(0) as i32,
            max_velocity: TargetVelocity::from_bits(word(1) as i32)?,
            acceleration: Acceleration::from_bits(word(2))?,
            deceleration: Acceleration::from_bits(word(3))?,
            start_velocity: TargetVelocity::from_bits(word(4) as i32)?,
        })
    };
    match parameters() {
        Ok(axis) => {
            // SAFETY: single-threaded; no reference to the slot outlives a call.
            unsafe { (*TRAPEZOID.0.get()).write(axis) };
            0
        }
        Err(_) => 1,
    }
}

/// Advances the stepped trapezoid one cycle; returns the new position.
///
/// # Safety
/// `probe_trapezoid_setup` succeeded before.
#[no_mangle]
pub unsafe extern "C" fn probe_trapezoid_step() -> i64 {
    // SAFETY: initialized by probe_trapezoid_setup (the caller's contract); single-threaded.
    let axis = unsafe { (*TRAPEZOID.0.get()).assume_init_mut() };
    axis.step().position.to_bits()
}

/// 1 when the stepped trapezoid is complete, else 0.
///
/// # Safety
/// `probe_trapezoid_setup` succeeded before.
#[no_mangle]
pub unsafe extern "C" fn probe_trapezoid_complete() -> u32 {
    // SAFETY: initialized by probe_trapezoid_setup (the caller's contract); single-threaded.
    let axis = unsafe { (*TRAPEZOID.0.get()).assume_init_ref() };
    u32::from(axis.is_complete())
}

/// Gives the stepped trapezoid a command in motion: 0 a smooth stop, 1 an abrupt stop, 2 the new
/// destination `value` (counts), 3 the new maximum velocity `value` (16.16 bits), 4 the new
/// acceleration and 5 the new deceleration `value` (8.24 bits); refused values change nothing.
///
/// # Safety
/// `probe_trapezoid_setup` succeeded before.
#[no_mangle]
pub unsafe extern "C" fn probe_trapezoid_command(command: u32, value: i32) {
    // SAFETY: initialized by probe_trapezoid_setup (the caller's contract); single-threaded.
    let axis = unsafe { (*TRAPEZOID.0.get()).assume_init_mut() };
    match command {
        0 => axis.stop(profilegen::StopKind::Smooth),
        1 => axis.stop(profilegen::StopKind::Abrupt),
        2 => axis.set_destination(value),
        3 => {
            let _ = TargetVelocity::from_bits(value).and_then(|v| axis.set_max_velocity(v));
        }
        4 => {
            let _ = Acceleration::from_bits(value as u32).and_then(|a| axis.set_acceleration(a));
        }
        _ => {
            if let Ok(d) = Acceleration::from_bits(value as u32) {
                axis.set_deceleration(d);
            }
        }
    }
}

/// The 3-axis line being stepped and its driving profile (one slot per profile kind).
static LINE_MCX514: Other<Stepped<LinearInterpolation<'static, Mcx514Trapezoidal, 3>>> =
    Other(UnsafeCell::new(MaybeUninit::uninit()));
static LINE_MCX514_PROFILE: Other<Mcx514Trapezoidal> =
    Other(UnsafeCell::new(MaybeUninit::uninit()));
static LINE_TRAPEZOID: Other<Stepped<LinearInterpolation<'static, Trapezoidal, 3>>> =
    Other(UnsafeCell::new(MaybeUninit::uninit()));
static LINE_TRAPEZOID_PROFILE: Other<Trapezoidal> = Other(UnsafeCell::new(MaybeUninit::uninit()));
static LINE_MCX514_SCURVE: Other<Stepped<LinearInterpolation<'static, Mcx514SCurve, 3>>> =
    Other(UnsafeCell::new(MaybeUninit::uninit()));
static LINE_MCX514_SCURVE_PROFILE: Other<Mcx514SCurve> =
    Other(UnsafeCell::new(MaybeUninit::uninit()));
static LINE_SCURVE: Other<Stepped<LinearInterpolation<'static, SCurve, 3>>> =
    Other(UnsafeCell::new(MaybeUninit::uninit()));
static LINE_SCURVE_PROFILE: Other<SCurve> = Other(UnsafeCell::new(MaybeUninit::uninit()));
/// Which slot the last successful `probe_line_setup` filled: 0 MCX514, 1 trapezoid, 2 MCX514
/// S-curve, 5 the crate's S-curve.
static LINE_KIND: AtomicU32 = AtomicU32::new(u32::MAX);
/// The MCX514 trapezoid alone (the driving axis as a one-axis generator, no geometry), set up
/// by `probe_line_setup` with profile 3.
static AXIS_MCX514: Other<Mcx514Trapezoidal> = Other(UnsafeCell::new(MaybeUninit::uninit()));
/// The MCX514 S-curve alone, set up by `probe_line_setup` with profile 4.
static AXIS_MCX514_SCURVE: Other<Mcx514SCurve> = Other(UnsafeCell::new(MaybeUninit::uninit()));
/// Which axis alone the last set-up filled: 3 the trapezoid, 4 the S-curve.
static AXIS_KIND: AtomicU32 = AtomicU32::new(u32::MAX);

/// Sets up the stepped 3-axis line from `words`: `[0]` the profile (0 the MCX514 trapezoid,
/// 1 the crate's `Trapezoidal`, 2 the MCX514 S-curve; 3 the MCX514 trapezoid and 4 the MCX514
/// S-curve alone, for `probe_axis_step_<profile>`, no line), `[1..4]` the finish point (pulses, `i32` bits), then
///
/// - MCX514: `[4]` the cycle time in µs, `[5]` SV, `[6]` DV (pps), `[7]` AC, `[8]` DC (pps/s),
///   `[9]` the deceleration mode (0 automatic, 1 manual at `[10]`, 2 disabled); the S-curve
///   also `[11]` JK and `[12]` DJ (pps/s²);
/// - trapezoid: `[4]` maximum velocity (16.16), `[5]` acceleration, `[6]` deceleration (8.24),
///   `[7]` starting velocity (16.16), raw bits; destination: the line's steps.
/// - S-curve (profile 5, the crate's `SCurve`): `[4]` maximum velocity, `[5]` maximum
///   acceleration, `[6]` jerk, raw bits (as `probe_plan_bits`); destination: the line's steps.
///
/// Returns the line's steps, or `u64::MAX` when refused.
///
/// # Safety
/// `words` points to 13 readable, aligned words.
#[no_mangle]
pub unsafe extern "C" fn probe_line_setup(words: *const u32) -> u64 {
    // SAFETY: the caller provides 13 words.
    let word = |i: usize| unsafe { words.add(i).read() };
    let line = match Line::from_pulses([word(1) as i32, word(2) as i32, word(3) as i32]) {
        Ok(line) => line,
        Err(_) => return REFUSED,
    };
    let steps = u64::from(line.steps());
    let mcx514 = || -> Result<Mcx514Parameters, Error> {
        let deceleration_mode = match word(9) {
            0 => DecelerationMode::Automatic,
            1 => DecelerationMode::Manual(mcx514::ManualDecelerationPoint::from_bits(word(10))?),
            _ => DecelerationMode::Disabled,
        };
        Ok(Mcx514Parameters {
            pulses: line.steps(),
            initial_speed: mcx514::InitialSpeed::from_bits(word(5))?,
            drive_speed: mcx514::DriveSpeed::from_bits(word(6))?,
            acceleration: mcx514::Acceleration::from_bits(word(7))?,
            deceleration: mcx514::Deceleration::from_bits(word(8))?,
            deceleration_mode,
        })
    };
    let cycle = || CycleTime::from_seconds(f64::from(word(4)) * 1e-6);
    match word(0) {
        0 | 3 => {
            let profile = || Mcx514Trapezoidal::new(mcx514()?, cycle()?);
            let Ok(profile) = profile() else {
                return REFUSED;
            };
            if word(0) == 3 {
                // SAFETY: single-threaded; no reference to the slot outlives a call.
                unsafe { (*AXIS_MCX514.0.get()).write(profile) };
                AXIS_KIND.store(3, Ordering::Relaxed);
                return steps;
            }
            // SAFETY: single-threaded; the profile lives in its static for as long as the line
            // that borrows it (both are replaced together, by the next set-up).
            let profile = unsafe { (*LINE_MCX514_PROFILE.0.get()).write(profile) };
            // SAFETY: as above.
            unsafe {
                (*LINE_MCX514.0.get()).write(Stepped {
                    line: line.drive(profile),
                    axes: [0; 3],
                })
            };
            LINE_KIND.store(0, Ordering::Relaxed);
        }
        2 | 4 => {
            let profile = || -> Result<Mcx514SCurve, Error> {
                Mcx514SCurve::new(
                    Mcx514ScurveParameters {
                        trapezoid: mcx514()?,
                        jerk: mcx514::Jerk::from_bits(word(11))?,
                        deceleration_jerk: mcx514::DecelerationJerk::from_bits(word(12))?,
                    },
                    cycle()?,
                )
            };
            let Ok(profile) = profile() else {
                return REFUSED;
            };
            if word(0) == 4 {
                // SAFETY: single-threaded; no reference to the slot outlives a call.
                unsafe { (*AXIS_MCX514_SCURVE.0.get()).write(profile) };
                AXIS_KIND.store(4, Ordering::Relaxed);
                return steps;
            }
            // SAFETY: as for the MCX514 slots.
            let profile = unsafe { (*LINE_MCX514_SCURVE_PROFILE.0.get()).write(profile) };
            // SAFETY: as above.
            unsafe {
                (*LINE_MCX514_SCURVE.0.get()).write(Stepped {
                    line: line.drive(profile),
                    axes: [0; 3],
                })
            };
            LINE_KIND.store(2, Ordering::Relaxed);
        }
        5 => {
            let profile = || -> Result<SCurve, Error> {
                SCurve::new(parameters(line.steps() as i32, word(4), word(5), word(6))?)
            };
            let Ok(profile) = profile() else {
                return REFUSED;
            };
            // SAFETY: as for the MCX514 slots.
            let profile = unsafe { (*LINE_SCURVE_PROFILE.0.get()).write(profile) };
            // SAFETY: as above.
            unsafe {
                (*LINE_SCURVE.0.get()).write(Stepped {
                    line: line.drive(profile),
                    axes: [0; 3],
                })
            };
            LINE_KIND.store(5, Ordering::Relaxed);
        }
        _ => {
            let profile = || -> Result<Trapezoidal, Error> {
                Trapezoidal::new(TrapezoidalParameters {
                    destination: line.steps() as i32,
                    max_velocity: TargetVelocity::from_bits(word(4) as i32)?,
                    acceleration: Acceleration::from_bits(word(5))?,
                    deceleration: Acceleration::from_bits(word(6))?,
                    start_velocity: TargetVelocity::from_bits(word(7) as i32)?,
                })
            };
            let Ok(profile) = profile() else {
                return REFUSED;
            };
            // SAFETY: as for the MCX514 slots.
            let profile = unsafe { (*LINE_TRAPEZOID_PROFILE.0.get()).write(profile) };
            // SAFETY: as above.
            unsafe {
                (*LINE_TRAPEZOID.0.get()).write(Stepped {
                    line: line.drive(profile),
                    axes: [0; 3],
                })
            };
            LINE_KIND.store(1, Ordering::Relaxed);
        }
    }
    steps
}

/// A line being stepped and where each cycle's axes go, as a caller would output them to its
/// pulse generators: beside the line, so that every profile's line reaches both from one base
/// address. (With the axes in a static of their own, LLVM merged it with one profile's line
/// only: the others paid two instructions a cycle to form its address, which measured the
/// harness, not the line.)
struct Stepped<L> {
    line: L,
    axes: [i32; 3],
}

/// One cycle's result handed on: every axis stored with a volatile write, as to a peripheral's
/// registers (a plain store nothing reads would be optimized away, and the geometry with it),
/// the driving step count returned. (The axes are what a line outputs; the driving axis's 64-bit
/// position, returned before, had to be held across the geometry, which spilled it to the
/// stack: four instructions a cycle that measured the harness, not the line.)
#[inline(always)]
fn output(state: InterpolationState<3>, out: &mut [i32; 3]) -> u32 {
    for (slot, axis) in out.iter_mut().zip(state.axes) {
        // SAFETY: a valid, aligned word (a reference).
        unsafe { core::ptr::write_volatile(slot, axis) };
    }
    state.step
}

/// Advances the MCX514-driven line one cycle: `LinearInterpolation::step`.
///
/// # Safety
/// `probe_line_setup` succeeded before with profile 0.
#[no_mangle]
pub unsafe extern "C" fn probe_line_step_mcx514() -> u32 {
    // SAFETY: initialized by probe_line_setup (the caller's contract); single-threaded.
    let stepped = unsafe { (*LINE_MCX514.0.get()).assume_init_mut() };
    output(stepped.line.step(), &mut stepped.axes)
}

/// Advances the trapezoid-driven line one cycle: `LinearInterpolation::step`.
///
/// # Safety
/// `probe_line_setup` succeeded before with profile 1.
#[no_mangle]
pub unsafe extern "C" fn probe_line_step_trapezoid() -> u32 {
    // SAFETY: initialized by probe_line_setup (the caller's contract); single-threaded.
    let stepped = unsafe { (*LINE_TRAPEZOID.0.get()).assume_init_mut() };
    output(stepped.line.step(), &mut stepped.axes)
}

/// Advances the S-curve-driven line one cycle: `LinearInterpolation::step`.
///
/// # Safety
/// `probe_line_setup` succeeded before with profile 5.
#[no_mangle]
pub unsafe extern "C" fn probe_line_step_scurve() -> u32 {
    // SAFETY: initialized by probe_line_setup (the caller's contract); single-threaded.
    let stepped = unsafe { (*LINE_SCURVE.0.get()).assume_init_mut() };
    output(stepped.line.step(), &mut stepped.axes)
}

/// Advances the MCX514-S-curve-driven line one cycle: `LinearInterpolation::step`.
///
/// # Safety
/// `probe_line_setup` succeeded before with profile 2.
#[no_mangle]
pub unsafe extern "C" fn probe_line_step_mcx514_scurve() -> u32 {
    // SAFETY: initialized by probe_line_setup (the caller's contract); single-threaded.
    let stepped = unsafe { (*LINE_MCX514_SCURVE.0.get()).assume_init_mut() };
    output(stepped.line.step(), &mut stepped.axes)
}

/// Advances the MCX514 trapezoid alone one cycle (a one-axis generator's cycle, SPEC §16).
///
/// # Safety
/// `probe_line_setup` succeeded before with profile 3.
#[no_mangle]
pub unsafe extern "C" fn probe_axis_step_mcx514() -> i64 {
    // SAFETY: initialized by probe_line_setup (the caller's contract); single-threaded.
    let axis = unsafe { (*AXIS_MCX514.0.get()).assume_init_mut() };
    axis.step().position.to_bits()
}

/// Advances the MCX514 S-curve alone one cycle (a one-axis generator's cycle, SPEC §16).
///
/// # Safety
/// `probe_line_setup` succeeded before with profile 4.
#[no_mangle]
pub unsafe extern "C" fn probe_axis_step_mcx514_scurve() -> i64 {
    // SAFETY: initialized by probe_line_setup (the caller's contract); single-threaded.
    let axis = unsafe { (*AXIS_MCX514_SCURVE.0.get()).assume_init_mut() };
    axis.step().position.to_bits()
}

/// 1 when the MCX514 profile set up alone last (profile 3 or 4) is complete, else 0.
///
/// # Safety
/// `probe_line_setup` succeeded before with profile 3 or 4.
#[no_mangle]
pub unsafe extern "C" fn probe_axis_complete() -> u32 {
    // SAFETY: initialized by probe_line_setup for the kind it recorded; single-threaded.
    let complete = unsafe {
        if AXIS_KIND.load(Ordering::Relaxed) == 4 {
            (*AXIS_MCX514_SCURVE.0.get())
                .assume_init_ref()
                .is_complete()
        } else {
            (*AXIS_MCX514.0.get()).assume_init_ref().is_complete()
        }
    };
    u32::from(complete)
}

/// 1 when the line set up last is complete, else 0; the axes' positions in `out[0..3]`.
///
/// # Safety
/// `probe_line_setup` succeeded before; `out` points to 3 writable, aligned words.
#[no_mangle]
pub unsafe extern "C" fn probe_line_complete(out: *mut i32) -> u32 {
    // SAFETY: initialized by probe_line_setup for the kind it recorded; single-threaded.
    let (complete, axes) = unsafe {
        match LINE_KIND.load(Ordering::Relaxed) {
            0 => {
                let line = &(*LINE_MCX514.0.get()).assume_init_ref().line;
                (line.is_complete(), line.state().axes)
            }
            2 => {
                let line = &(*LINE_MCX514_SCURVE.0.get()).assume_init_ref().line;
                (line.is_complete(), line.state().axes)
            }
            5 => {
                let line = &(*LINE_SCURVE.0.get()).assume_init_ref().line;
                (line.is_complete(), line.state().axes)
            }
            _ => {
                let line = &(*LINE_TRAPEZOID.0.get()).assume_init_ref().line;
                (line.is_complete(), line.state().axes)
            }
        }
    };
    for (i, axis) in axes.iter().enumerate() {
        // SAFETY: the caller provides 3 words.
        unsafe { out.add(i).write(*axis) };
    }
    u32::from(complete)
}

/// A circular interpolation: the driving profile and the walk along the arc.
struct Circle<G> {
    profile: G,
    walk: ArcWalk,
}

static CIRCLE_MCX514: Other<Circle<Mcx514Trapezoidal>> =
    Other(UnsafeCell::new(MaybeUninit::uninit()));
static CIRCLE_TRAPEZOID: Other<Circle<Trapezoidal>> = Other(UnsafeCell::new(MaybeUninit::uninit()));

/// Sets up a stepped circle from `words`: `[0..2]` the centre, `[2..4]` the finish point (pulses
/// relative to the start, `i32` bits), `[4]` 1 for counter-clockwise, then the profile `[5]`:
///
/// - 0, the MCX514 trapezoid: `[6]` SV, `[7]` DV (pps), `[8]` AC, `[9]` DC (pps/s), `[10]` the
///   manual deceleration point, `[11]` the cycle time in µs;
/// - 1, the crate's `Trapezoidal`: `[6]` maximum velocity (16.16), `[7]` acceleration, `[8]`
///   deceleration (8.24), raw bits; the destination is the arc's steps.
///
/// Returns 0 on success, 1 when refused.
///
/// # Safety
/// `words` points to 12 readable, aligned words.
#[no_mangle]
pub unsafe extern "C" fn probe_circle_setup(words: *const u32) -> u32 {
    // SAFETY: the caller provides 12 words.
    let word = |i: usize| unsafe { words.add(i).read() };
    let direction = if word(4) == 1 {
        Direction::CounterClockwise
    } else {
        Direction::Clockwise
    };
    let Ok(arc) = Arc::from_pulses(
        [word(0) as i32, word(1) as i32],
        [word(2) as i32, word(3) as i32],
        direction,
    ) else {
        return 1;
    };
    if word(5) == 0 {
        let profile = || -> Result<Mcx514Trapezoidal, Error> {
            let cycle = CycleTime::from_seconds(f64::from(word(11)) * 1e-6)?;
            arc.mcx514_profile(
                CircularDriving {
                    initial_speed: mcx514::InitialSpeed::from_bits(word(6))?,
                    drive_speed: mcx514::DriveSpeed::from_bits(word(7))?,
                    acceleration: mcx514::Acceleration::from_bits(word(8))?,
                    deceleration: mcx514::Deceleration::from_bits(word(9))?,
                    jerk: None,
                    deceleration_jerk: None,
                    deceleration_mode: DecelerationMode::Manual(
                        mcx514::ManualDecelerationPoint::from_bits(word(10))?,
                    ),
                },
                cycle,
            )
        };
        let Ok(profile) = profile() else {
            return 1;
        };
        let circle = Circle {
            profile,
            walk: arc.walk(),
        };
        // SAFETY: single-threaded; no reference to the slot outlives a call.
        unsafe { (*CIRCLE_MCX514.0.get()).write(circle) };
    } else {
        let profile = || -> Result<Trapezoidal, Error> {
            Trapezoidal::new(TrapezoidalParameters {
                destination: i32::try_from(arc.steps()).unwrap_or(i32::MAX),
                max_velocity: TargetVelocity::from_bits(word(6) as i32)?,
                acceleration: Acceleration::from_bits(word(7))?,
                deceleration: Acceleration::from_bits(word(8))?,
                start_velocity: TargetVelocity::ZERO,
            })
        };
        let Ok(profile) = profile() else {
            return 1;
        };
        let circle = Circle {
            profile,
            walk: arc.walk(),
        };
        // SAFETY: as above.
        unsafe { (*CIRCLE_TRAPEZOID.0.get()).write(circle) };
    }
    0
}

/// Where each cycle of a circle puts its axes (x, y; the third word unused).
static CIRCLE_AXES: Other<[i32; 3]> = Other(UnsafeCell::new(MaybeUninit::uninit()));

/// One cycle of a circle: the profile's step and the arc's jump to the step it reached (what
/// `CircularInterpolation::step` does, `ArcWalk::advance_to_whole`), both axes stored with volatile writes as `output` does
/// for the line; returns the driving position.
#[inline(always)]
fn circle_step<G: ProfileGenerator>(circle: &mut Circle<G>) -> i64 {
    let driving = circle.profile.step();
    // The whole steps: the position's integer part (an i32), clamped by the walk.
    let axes = circle
        .walk
        .advance_to_whole((driving.position.to_bits() >> 32) as i32);
    let out = CIRCLE_AXES.0.get().cast::<i32>();
    for (i, axis) in axes.into_iter().enumerate() {
        // SAFETY: aligned words of a static (three, two used); single-threaded.
        unsafe { out.add(i).write_volatile(axis) };
    }
    driving.position.to_bits()
}

/// Advances the MCX514-driven circle one cycle.
///
/// # Safety
/// `probe_circle_setup` succeeded before with profile 0.
#[no_mangle]
pub unsafe extern "C" fn probe_circle_step_mcx514() -> i64 {
    // SAFETY: initialized by probe_circle_setup (the caller's contract); single-threaded.
    circle_step(unsafe { (*CIRCLE_MCX514.0.get()).assume_init_mut() })
}

/// Advances the trapezoid-driven circle one cycle.
///
/// # Safety
/// `probe_circle_setup` succeeded before with profile 1.
#[no_mangle]
pub unsafe extern "C" fn probe_circle_step_trapezoid() -> i64 {
    // SAFETY: initialized by probe_circle_setup (the caller's contract); single-threaded.
    circle_step(unsafe { (*CIRCLE_TRAPEZOID.0.get()).assume_init_mut() })
}

/// 1 when the stepped circle's profile (0 MCX514, 1 trapezoid) is complete, else 0; the axes
/// are in `CIRCLE_AXES`.
///
/// # Safety
/// `probe_circle_setup` succeeded before with that profile.
#[no_mangle]
pub unsafe extern "C" fn probe_circle_complete(profile: u32) -> u32 {
    // SAFETY: initialized by probe_circle_setup (the caller's contract); single-threaded.
    let complete = if profile == 0 {
        unsafe { (*CIRCLE_MCX514.0.get()).assume_init_ref() }
            .profile
            .is_complete()
    } else {
        unsafe { (*CIRCLE_TRAPEZOID.0.get()).assume_init_ref() }
            .profile
            .is_complete()
    };
    u32::from(complete)
}

/// The stepped circle's axes after the last step: x in the low word, y in the high.
#[no_mangle]
pub extern "C" fn probe_circle_axes() -> u64 {
    let axes = CIRCLE_AXES.0.get().cast::<i32>();
    // SAFETY: aligned words of a static, written by the last step; single-threaded.
    let (x, y) = unsafe { (axes.read_volatile(), axes.add(1).read_volatile()) };
    u64::from(x as u32) | (u64::from(y as u32) << 32)
}

/// Panics when `panic` is non-zero: the harness's check that a panic is caught and located.
#[no_mangle]
pub extern "C" fn probe_selftest_panic(panic: u32) -> u32 {
    assert!(black_box(panic) == 0, "probe self-test panic");
    0
}

/// Never returns: the harness's check that a runaway is caught.
#[no_mangle]
pub extern "C" fn probe_selftest_runaway() -> u32 {
    let mut n: u32 = 0;
    loop {
        n = black_box(n.wrapping_add(1));
    }
}

/// Where the last panic was: line, and the file name's address and length in the image.
#[no_mangle]
pub static PROBE_PANIC_LINE: AtomicU32 = AtomicU32::new(0);
#[no_mangle]
pub static PROBE_PANIC_FILE: AtomicU32 = AtomicU32::new(0);
#[no_mangle]
pub static PROBE_PANIC_FILE_LEN: AtomicU32 = AtomicU32::new(0);

#[panic_handler]
fn panic(info: &PanicInfo) -> ! {
    let location = info.location();
    if let Some(location) = location {
        PROBE_PANIC_LINE.store(location.line(), Ordering::Relaxed);
        PROBE_PANIC_FILE.store(location.file().as_ptr() as u32, Ordering::Relaxed);
        PROBE_PANIC_FILE_LEN.store(location.file().len() as u32, Ordering::Relaxed);
    }
    probe_panicked()
}

/// Every panic ends here; the harness stops when execution reaches this symbol.
#[no_mangle]
#[inline(never)]
pub extern "C" fn probe_panicked() -> ! {
    loop {
        // SAFETY: `udf` only raises an undefined-instruction fault, which the emulator reports.
        unsafe { core::arch::asm!("udf #0", options(nomem, nostack)) };
    }
}
