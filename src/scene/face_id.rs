//! Face identity: a face's index in the global face order (depth-first over the object tree,
//! source order within a mesh) — the order `kepler flatten` writes and the JSON `id`.

use std::fmt;
use std::ops::Range;

/// A face's index in the global face order. Distinct from a view's
/// planar piece: a warped face is one face but several planar pieces.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct FaceId(pub u32);

impl FaceId {
    /// The index as a `usize`, for indexing per-face arrays.
    #[inline]
    pub fn index(self) -> usize {
        self.0 as usize
    }

    /// The face `n` places after this one.
    #[inline]
    pub fn offset(self, n: u32) -> FaceId {
        FaceId(self.0 + n)
    }

    /// Every id of a range, in order.
    pub fn each(r: &Range<FaceId>) -> impl ExactSizeIterator<Item = FaceId> + Clone {
        (r.start.0..r.end.0).map(FaceId)
    }
}

impl fmt::Display for FaceId {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}", self.0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ranges_iterate_in_order() {
        let ids: Vec<FaceId> = FaceId::each(&(FaceId(3)..FaceId(6))).collect();
        assert_eq!(ids, [FaceId(3), FaceId(4), FaceId(5)]);
        assert_eq!(FaceId(3).offset(2).index(), 5);
        assert_eq!(FaceId(7).to_string(), "7");
    }
}
