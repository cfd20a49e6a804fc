//! Reproducible random numbers for the tests, without a dependency: splitmix64 (Steele, Lea and
//! Flood 2014), whose 64-bit outputs pass BigCrush; every test and example draws from it.

/// A splitmix64 stream from `seed`.
pub struct SplitMix(pub u64);

impl SplitMix {
    /// The next 64 random bits.
    pub fn bits(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// A uniform number in `[0, 1)` from the top 53 of `bits`.
    pub fn unit(bits: u64) -> f64 {
        (bits >> 11) as f64 / (1u64 << 53) as f64
    }

    /// The next uniform number in `[0, 1)`.
    pub fn uniform(&mut self) -> f64 {
        Self::unit(self.bits())
    }

    /// The next uniform number in `[lo, hi)`.
    pub fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.uniform()
    }

    /// The next uniform number in `[-1, 1)`.
    pub fn symmetric(&mut self) -> f64 {
        self.range(-1.0, 1.0)
    }

    /// `count` numbers uniform in `[lo, hi)`.
    pub fn fill(&mut self, count: usize, lo: f64, hi: f64) -> Vec<f64> {
        (0..count).map(|_| self.range(lo, hi)).collect()
    }
}
