//! PMD MC1451A register formats (datasheet p. 19 and the chipset's parameter tables).

use fixed::types::{I16F16, I32F0, U0F16, U0F32, U16F16};

super::register! {
    /// MC1451A destination position: signed 32 bits, counts, limited to ±2³⁰.
    Destination(I32F0, i32, frac = 0, min = -1_073_741_824, max = 1_073_741_823),
    parameter = "destination",
    unit = "counts"
}

super::register! {
    /// MC1451A maximum velocity: unsigned 32 bits with 1/2¹⁶ scaling, counts/cycle, 30 bits used.
    ///
    /// ```
    /// use profilegen::format::mc1451a::MaxVelocity;
    /// // Datasheet: 2.75 counts/sample → 180,224 (0x2C000).
    /// assert_eq!(MaxVelocity::from_num(2.75)?.to_bits(), 0x2C000);
    /// # Ok::<(), profilegen::Error>(())
    /// ```
    MaxVelocity(U16F16, u32, frac = 16, min = 0, max = 1_073_741_823),
    parameter = "velocity",
    unit = "counts/cycle",
    per_second = 1, physical_unit = "counts/s"
}

super::register! {
    /// MC1451A S-curve maximum acceleration: unsigned **16** bits with 1/2¹⁶ scaling,
    /// counts/cycle², so at most 32,767/65,536 ≈ 0.49998.
    ///
    /// ```
    /// use profilegen::format::mc1451a::ScurveAcceleration;
    /// // Datasheet: 0.175 counts/sample² → 11,468.8 → 11,469 (0x2CCD): round to nearest.
    /// assert_eq!(ScurveAcceleration::from_num(0.175)?.to_bits(), 0x2CCD);
    /// # Ok::<(), profilegen::Error>(())
    /// ```
    ScurveAcceleration(U0F16, u16, frac = 16, min = 0, max = 32_767),
    parameter = "acceleration",
    unit = "counts/cycle²",
    per_second = 2, physical_unit = "counts/s²"
}

super::register! {
    /// MC1451A jerk: unsigned 32 bits with 1/2³² scaling, counts/cycle³, 31 bits used.
    ///
    /// ```
    /// use profilegen::format::mc1451a::Jerk;
    /// // 0.0075 · 2^32 = 32,212,254.72 → 32,212,255 (the datasheet prints 32,212,256).
    /// assert_eq!(Jerk::from_num(0.0075)?.to_bits(), 32_212_255);
    /// # Ok::<(), profilegen::Error>(())
    /// ```
    Jerk(U0F32, u32, frac = 32, min = 0, max = 2_147_483_647),
    parameter = "jerk",
    unit = "counts/cycle³",
    per_second = 3, physical_unit = "counts/s³"
}

super::register! {
    /// MC1451A trapezoidal-mode acceleration: unsigned 32 bits with 1/2¹⁶ scaling, counts/cycle².
    TrapezoidalAcceleration(U16F16, u32, frac = 16, min = 0, max = 1_073_741_823),
    parameter = "acceleration",
    unit = "counts/cycle²",
    per_second = 2, physical_unit = "counts/s²"
}

super::register! {
    /// MC1451A electronic gear ratio: signed 32 bits with 1/2¹⁶ scaling, ±2¹⁴.
    ///
    /// ```
    /// use profilegen::format::mc1451a::GearRatio;
    /// assert_eq!(GearRatio::from_num(-11.39)?.to_bits(), -746_455);
    /// # Ok::<(), profilegen::Error>(())
    /// ```
    GearRatio(I16F16, i32, frac = 16, min = -1_073_741_824, max = 1_073_741_823),
    parameter = "gear ratio",
    unit = ""
}
