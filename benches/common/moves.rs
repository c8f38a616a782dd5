//! Random S-curve moves over the whole register ranges, reproducible one by one: move `index` is
//! a pure function of `index`, the same on the host (benches) and on the Cortex-M4 probe
//! (`probe/`, which includes this file by path), so it uses `core` and the (`no_std`) crate only.
//!
//! Every register is log-uniform over its whole raw range: a bit length drawn uniformly, then a
//! uniform value with exactly that many bits. Small and large values are then equally likely per
//! octave, as the extremes of the ranges (the costly corners of planning) need.

/// The seed every move derives from; changing it changes every move.
pub const SEED: u64 = 0x5EED_1451_A0C0_FFEE;

/// splitmix64 (Steele, Lea and Flood): a 64-bit generator whose every state is a good seed, so
/// consecutive indices give independent streams.
#[derive(Debug, Clone)]
pub struct SplitMix64(u64);

impl SplitMix64 {
    /// The stream of move `index`.
    pub const fn for_move(index: u64) -> Self {
        // Scramble the index once so that the streams of neighbouring indices do not overlap
        // (splitmix64 steps its state by the same constant).
        Self(mix(index ^ SEED))
    }

    /// The next 64 random bits.
    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        mix(self.0)
    }

    /// A value log-uniform over `1 ..= 2^max_bits − 1`: a bit length uniform in `1 ..= max_bits`,
    /// then a uniform value with exactly that many bits. `max_bits` is 1 … 63.
    pub fn log_uniform(&mut self, max_bits: u32) -> u64 {
        // Multiply-high maps 32 random bits onto 0 … max_bits − 1 with negligible bias.
        let bits = (((self.next_u64() >> 32) * u64::from(max_bits)) >> 32) as u32 + 1;
        let top = 1u64 << (bits - 1);
        top | (self.next_u64() & (top - 1))
    }
}

const fn mix(mut z: u64) -> u64 {
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

/// S-curve move `index` as raw MC1451A register bits: (destination, maximum velocity, maximum
/// acceleration, jerk). Destination: ±(1 … 2³⁰ − 1) counts, sign uniform; velocity
/// 1 … 1,073,741,823; acceleration 1 … 32,767; jerk 1 … 2,147,483,647: every value legal for
/// `from_bits` and non-zero.
pub fn scurve_move(index: u64) -> (i32, u32, u16, u32) {
    let mut random = SplitMix64::for_move(index);
    let magnitude = random.log_uniform(30) as i32;
    let destination = if random.next_u64() >> 63 == 1 {
        -magnitude
    } else {
        magnitude
    };
    let velocity = random.log_uniform(30) as u32;
    let acceleration = random.log_uniform(15) as u16;
    let jerk = random.log_uniform(31) as u32;
    (destination, velocity, acceleration, jerk)
}

/// S-curve move `index` ([`scurve_move`]) as the parameters `SCurve::new` takes.
pub fn scurve_parameters(index: u64) -> profilegen::ScurveParameters {
    use profilegen::format::mc1451a::{Jerk, MaxVelocity, ScurveAcceleration};
    let (destination, velocity, acceleration, jerk) = scurve_move(index);
    profilegen::ScurveParameters {
        destination,
        max_velocity: MaxVelocity::from_bits(velocity).expect("velocity in range"),
        max_acceleration: ScurveAcceleration::from_bits(acceleration)
            .expect("acceleration in range"),
        jerk: Jerk::from_bits(jerk).expect("jerk in range"),
    }
}
