//! PMD Juno register formats (User Guide ch. 11, the format table of p. 68).

use fixed::types::{I16F16, U8F24};

super::register! {
    /// Juno target velocity: signed 16.16, counts/cycle. Its sign is the direction of motion.
    ///
    /// ```
    /// use profilegen::format::juno::TargetVelocity;
    /// // The manual's worked example: 13.825 counts/cycle · 65,536 = 906,035.
    /// assert_eq!(TargetVelocity::from_num(13.825)?.to_bits(), 906_035);
    /// # Ok::<(), profilegen::Error>(())
    /// ```
    TargetVelocity(I16F16, i32, frac = 16, min = i32::MIN, max = i32::MAX),
    parameter = "velocity",
    unit = "counts/cycle",
    per_second = 1, physical_unit = "counts/s"
}

super::register! {
    /// Juno acceleration or deceleration: unsigned 8.24, counts/cycle², limited by the manual to
    /// 31 of its 32 bits (0 … 127.99999994).
    ///
    /// ```
    /// use profilegen::format::juno::Acceleration;
    /// // The manual's worked example: 0.01180 counts/cycle² · 2^24 = 197,971.
    /// assert_eq!(Acceleration::from_num(0.01180)?.to_bits(), 197_971);
    /// # Ok::<(), profilegen::Error>(())
    /// ```
    Acceleration(U8F24, u32, frac = 24, min = 0, max = 0x7FFF_FFFF),
    parameter = "acceleration",
    unit = "counts/cycle²",
    per_second = 2, physical_unit = "counts/s²"
}
