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
//! - `probe_velocity_setup(velocity, acceleration, deceleration)`, `probe_velocity_step()`:
//!   the same for `VelocityContouring` (Juno registers as raw bits).
//! - `probe_trapezoid_setup(words)` (destination, maximum velocity, acceleration, deceleration,
//!   starting velocity as raw bits), `probe_trapezoid_step()`, `probe_trapezoid_complete()`:
//!   the same for `Trapezoidal`; the setup is the measured "starting a move" (it plans).
//! - `probe_trapezoid_command(command, value)`: a stop or a new destination in motion, so the
//!   cycles that follow can be counted too.
//! - `probe_selftest_panic(1)`, `probe_selftest_runaway()`: a panic and an endless loop, so the
//!   harness can check that it catches both.
#![no_std]
#![no_main]

use core::cell::UnsafeCell;
use core::hint::black_box;
use core::mem::MaybeUninit;
use core::panic::PanicInfo;
use core::sync::atomic::{AtomicU32, Ordering};

use profilegen::format::mc1451a::{Jerk, MaxVelocity, ScurveAcceleration};
use profilegen::format::juno::{Acceleration, TargetVelocity};
use profilegen::{
    Error, ProfileGenerator, SCurve, ScurveParameters, Trapezoidal, TrapezoidalParameters,
    VelocityContouring, VelocityParameters,
};

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

/// A generator slot like [`AXIS`], for the other generators.
struct Other<T>(UnsafeCell<MaybeUninit<T>>);

// SAFETY: as for `Slot`.
unsafe impl<T> Sync for Other<T> {}

static VELOCITY: Other<VelocityContouring> = Other(UnsafeCell::new(MaybeUninit::uninit()));
static TRAPEZOID: Other<Trapezoidal> = Other(UnsafeCell::new(MaybeUninit::uninit()));

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
/// destination `value` (counts), 3 the new maximum velocity `value` (16.16 bits; refused values
/// change nothing).
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
        _ => {
            let _ = TargetVelocity::from_bits(value).and_then(|v| axis.set_max_velocity(v));
        }
    }
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
