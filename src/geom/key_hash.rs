//! Hash maps keyed by exact bits (a point's coordinates, a grid cell): a fast deterministic
//! hasher instead of SipHash, whose resistance to chosen keys buys nothing on a scene's own
//! numbers. Callers never read such a map's iteration order.

use std::collections::HashMap;
use std::hash::{BuildHasherDefault, Hasher};

use super::poly2::Pt2;

/// A hash map hashed by [`KeyHasher`].
pub(crate) type KeyMap<K, V> = HashMap<K, V, BuildHasherDefault<KeyHasher>>;

/// Multiply-rotate mixing with a final avalanche (the low mantissa bits of coordinates read
/// from `f32` files are all zero, so the output must be well mixed).
#[derive(Debug, Default, Clone, Copy)]
pub(crate) struct KeyHasher(u64);

impl Hasher for KeyHasher {
    fn finish(&self) -> u64 {
        let mut h = self.0;
        h ^= h >> 33;
        h = h.wrapping_mul(0xff51_afd7_ed55_8ccd);
        h ^= h >> 33;
        h = h.wrapping_mul(0xc4ce_b9fe_1a85_ec53);
        h ^ (h >> 33)
    }

    fn write(&mut self, bytes: &[u8]) {
        // Eight bytes a step (a slice of `u32`s hashes as one byte string), the rest with
        // its length, so strings of different lengths rarely collide.
        let mut chunks = bytes.chunks_exact(8);
        for c in &mut chunks {
            let mut w = [0u8; 8];
            w.copy_from_slice(c);
            self.write_u64(u64::from_le_bytes(w));
        }
        let rest = chunks.remainder();
        let mut w = [0u8; 8];
        w[..rest.len()].copy_from_slice(rest);
        self.write_u64(u64::from_le_bytes(w) ^ ((rest.len() as u64) << 59));
    }

    fn write_u64(&mut self, v: u64) {
        self.0 = (self.0.rotate_left(23) ^ v).wrapping_mul(0x9e37_79b9_7f4a_7c15);
    }

    fn write_i64(&mut self, v: i64) {
        self.write_u64(v as u64);
    }

    fn write_u32(&mut self, v: u32) {
        self.write_u64(u64::from(v));
    }

    fn write_usize(&mut self, v: usize) {
        self.write_u64(v as u64);
    }
}

/// The exact bits of a 2D point as a hash key: -0 and 0 are the same point.
pub(crate) fn point_key(p: Pt2) -> (u64, u64) {
    ((p[0] + 0.0).to_bits(), (p[1] + 0.0).to_bits())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn minus_zero_is_zero_and_the_map_finds_its_keys() {
        assert_eq!(point_key([-0.0, 1.5]), point_key([0.0, 1.5]));
        assert_ne!(point_key([1.0, 2.0]), point_key([2.0, 1.0]));
        let mut m: KeyMap<(u64, u64), usize> = KeyMap::default();
        for i in 0..1000 {
            m.insert(point_key([i as f64 * 0.25, -(i as f64)]), i);
        }
        assert!((0..1000).all(|i| m[&point_key([i as f64 * 0.25, -(i as f64)])] == i));
    }
}
