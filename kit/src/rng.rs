//! The tests' random generator: xorshift64 with the numbers of the library's own
//! (`geom::rng::XorShift`), so a seed means the same case everywhere.

/// Xorshift64: the same numbers on every machine as the library's `XorShift`.
#[derive(Debug, Clone)]
pub struct Rng(u64);

impl Rng {
    /// A generator from a seed (0 is taken as 1: xorshift never leaves 0).
    pub fn new(seed: u64) -> Rng {
        Rng(seed.max(1))
    }

    /// The next 64 random bits.
    pub fn next_u64(&mut self) -> u64 {
        let mut s = self.0;
        s ^= s << 13;
        s ^= s >> 7;
        s ^= s << 17;
        self.0 = s;
        s
    }

    /// A number in 0..n (n > 0; the slight bias of a modulus is harmless here).
    pub fn below(&mut self, n: usize) -> usize {
        (self.next_u64() % n.max(1) as u64) as usize
    }

    /// A uniform number in [0, 1).
    pub fn unit(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64
    }

    /// A uniform number in [lo, hi).
    pub fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.unit()
    }
}

#[cfg(test)]
mod tests {
    use super::Rng;

    #[test]
    fn the_first_numbers_are_xorshift64s() {
        // x ^= x << 13; x ^= x >> 7; x ^= x << 17 from 1, worked by hand.
        let mut r = Rng::new(1);
        assert_eq!(r.next_u64(), 0x4082_2041);
        assert_eq!(Rng::new(0).next_u64(), 0x4082_2041);
        let u = Rng::new(7).unit();
        assert!((0.0..1.0).contains(&u));
    }
}
