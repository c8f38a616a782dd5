//! The golden values of SPEC §11 (the Juno and MC1451A rows, and the MCX514 rows that need no
//! circle geometry): each an `assert_eq!` on raw bits, with the manual's own figure beside it.

use profilegen::format::juno::{Acceleration, TargetVelocity};
use profilegen::format::mc1451a::{GearRatio, Jerk, MaxVelocity, ScurveAcceleration};
use profilegen::format::mcx514::{
    self, acceleration_for_change, deceleration_pulses, linear_manual_deceleration_point,
    manual_deceleration_point, Deceleration, DriveSpeed, FinishPoint, InitialSpeed,
};
use profilegen::format::CycleTime;

/// Juno User Guide p. 68, along the manual's own rounded chain: 9,765 cycles/s, 13.825
/// counts/cycle, 1,172 cycles, 0.01180 counts/cycle².
#[test]
fn juno_worked_example_along_the_manuals_rounded_chain() {
    let manual_rate = CycleTime::from_hertz(9_765.0).unwrap();
    // Manual: 135,000 / 9,765 = 13.825 (it rounds 13.82488… to three decimals).
    let velocity_per_cycle = manual_rate.per_cycle(135_000.0, 1);
    assert!((velocity_per_cycle - 13.825).abs() < 0.0002);
    // Manual: "13.825 * 65,536 = 906,035".
    assert_eq!(TargetVelocity::from_num(13.825).unwrap().to_bits(), 906_035);
    // Manual: ".120 sec * 9,765 cycles/sec = 1,172 cycles".
    let cycles = manual_rate.cycles_in(0.120).unwrap();
    assert_eq!(cycles.round() as u32, 1_172);
    // Manual: "13.825 / 1,172 = .01180"; then ".01180 * 16,777,216 = 197,971".
    assert!((13.825_f64 / 1_172.0 - 0.01180).abs() < 0.000_005);
    assert_eq!(Acceleration::from_num(0.01180).unwrap().to_bits(), 197_971);
}

/// The same example computed exactly from 135,000 counts/s, 0.120 s and 102.4 µs.
#[test]
fn juno_worked_example_exact() {
    let juno = CycleTime::JUNO;
    // 135,000 · 102.4e-6 = 13.824 counts/cycle; · 65,536 = 905,969.664 → 905,970.
    let velocity = TargetVelocity::from_physical(135_000.0, juno).unwrap();
    assert_eq!(velocity.to_bits(), 905_970);
    // 0.120 s / 102.4 µs = 1,171.875 cycles.
    assert_eq!(juno.cycles_in(0.120).unwrap(), 1_171.875);
    // 13.824 / 1,171.875 = 0.01179648 counts/cycle²; · 2^24 = 197,912.09 → 197,912.
    let acceleration = juno.acceleration_for_change(0.0, 135_000.0, 0.120).unwrap();
    assert_eq!(
        Acceleration::from_num(acceleration).unwrap().to_bits(),
        197_912
    );
}

/// MC1451A datasheet p. 19, footnote *: 2.75 counts/sample → 180,224 (0x2C000), exact.
#[test]
fn mc1451a_velocity() {
    assert_eq!(MaxVelocity::from_num(2.75).unwrap().to_bits(), 180_224);
    assert_eq!(MaxVelocity::from_num(2.75).unwrap().to_bits(), 0x2C000);
}

/// Footnote **: 0.175 · 65,536 = 11,468.8 → 11,469 (0x2CCD): the datasheet rounds to nearest.
#[test]
fn mc1451a_scurve_acceleration_rounds_to_nearest() {
    assert_eq!(
        ScurveAcceleration::from_num(0.175).unwrap().to_bits(),
        11_469
    );
    assert_eq!(
        ScurveAcceleration::from_num(0.175).unwrap().to_bits(),
        0x2CCD
    );
}

/// Footnote ***: 0.0075 · 2^32 = 32,212,254.72, which rounds to 32,212,255 (0x1EB851F).
/// The datasheet prints 32,212,256 (0x1EB8520): its slip, one LSB off. We follow the arithmetic.
#[test]
fn mc1451a_jerk_is_the_exact_rounding_not_the_datasheets_slip() {
    let jerk = Jerk::from_num(0.0075).unwrap();
    assert_eq!(jerk.to_bits(), 32_212_255);
    assert_eq!(jerk.to_bits(), 0x1EB_851F);
    assert_ne!(
        jerk.to_bits(),
        32_212_256,
        "the datasheet's printed figure is 1 LSB high"
    );
}

/// Gear ratio, signed 32 bits with 1/2^16 scaling: 1.5 → 98,304; −11.39 → −746,455 (0xFFF49C29).
#[test]
fn mc1451a_gear_ratio() {
    assert_eq!(GearRatio::from_num(1.5).unwrap().to_bits(), 98_304);
    let negative = GearRatio::from_num(-11.39).unwrap().to_bits();
    assert_eq!(negative, -746_455);
    assert_eq!(negative as u32, 0xFFF4_9C29);
}

/// MCX514 manual §3.8.1 (reference 003): "finish point (X:-20000, Y:30000, Z:-50000), if the pulse
/// number necessary for deceleration is 5000, … the user should set 50000-5000=45000 as the manual
/// deceleration point of the main axis".
#[test]
fn mcx514_linear_manual_deceleration_point() {
    let finish = [-20_000, 30_000, -50_000].map(|p| FinishPoint::from_bits(p).unwrap());
    let point = linear_manual_deceleration_point(&finish, 5_000).unwrap();
    assert_eq!(point.to_bits(), 45_000);
}

/// MCX514 manual §3.8.2: "If the initial speed is 500PPS and accelerated to 20KPPS in 0.3 SEC, the
/// acceleration will be (20000−500)/0.3 = 65000PPS/SEC", written as "WR6 ← FDE8h".
#[test]
fn mcx514_circle_acceleration() {
    let initial = InitialSpeed::from_bits(500).unwrap();
    let drive = DriveSpeed::from_bits(20_000).unwrap();
    let acceleration = acceleration_for_change(initial, drive, 0.3).unwrap();
    assert_eq!(acceleration.to_bits(), 65_000);
    assert_eq!(acceleration.to_bits(), 0xFDE8);
}

/// MCX514 manual §3.8.2: "the output pulses during acceleration will be (500+20000)×0.3/2 =3075.
/// Thus, if we set the deceleration as same as the acceleration, the manual deceleration point
/// will be 56568 - 3075=53493". 56,568 is the manual's short-axis count of the r = 10,000 circle,
/// 7071 × 8 (the circle geometry itself is not in the crate yet).
#[test]
fn mcx514_circle_acceleration_pulses_and_manual_deceleration_point() {
    let initial = InitialSpeed::from_bits(500).unwrap();
    let drive = DriveSpeed::from_bits(20_000).unwrap();
    let deceleration = Deceleration::from_bits(65_000).unwrap();
    let pulses = deceleration_pulses(initial, drive, deceleration);
    assert_eq!(pulses, 3_075);
    let short_axis_pulses = 7_071 * 8;
    assert_eq!(short_axis_pulses, 56_568);
    let point = manual_deceleration_point(short_axis_pulses, pulses).unwrap();
    assert_eq!(point.to_bits(), 53_493);
    assert_eq!(
        point,
        mcx514::ManualDecelerationPoint::from_bits(53_493).unwrap()
    );
}
