//! Piece identity: a planar piece's index among a view's screen pieces. A planar face is one
//! piece; a warped face is split into several planar triangles, each a piece of its own.

use std::fmt;

/// A piece's index in [`ScreenFaces::pieces`](super::ScreenFaces::pieces). Pieces of one
/// face are consecutive and pieces follow global face order, so comparing two pieces'
/// ids compares their faces' order (the coplanar tie rule).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub(crate) struct PieceId(pub u32);

impl PieceId {
    /// The index as a `usize`, for indexing per-piece arrays.
    #[inline]
    pub(crate) fn index(self) -> usize {
        self.0 as usize
    }
}

impl fmt::Display for PieceId {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}", self.0)
    }
}
