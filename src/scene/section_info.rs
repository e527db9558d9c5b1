//! What a section cut left in a scene for the later stages: its planes, the faces it removed
//! whole, the faces of the leaves it cut, and where the section faces begin.

use std::collections::HashSet;
use std::ops::Range;

use crate::geom::P3;

/// The record of a cut, kept on the cut [`super::Scene`].
#[derive(Debug, Clone, Default)]
pub(crate) struct SectionInfo {
    /// The first section face: the scene's own faces run below it, the cut faces from it.
    pub first_face: u32,
    /// Faces wholly on a removed side, ascending: they keep their ids and get no pieces.
    pub removed: Vec<u32>,
    /// The face ranges of the leaves the cut changed (ascending, disjoint).
    pub cut_leaves: Vec<Range<u32>>,
    /// By plane, the points of cut leaves on it, by their exact coordinates (−0 as +0):
    /// corners on it and the crossings the cut made (rounded, so not exactly on it).
    pub on_cut: Vec<HashSet<[u64; 3]>>,
}

impl SectionInfo {
    /// True when face `f` is a section face (made by the cut).
    pub(crate) fn is_section(&self, f: u32) -> bool {
        f >= self.first_face
    }

    /// True when `a` and `b` are points of cut leaves on one plane: the ends of a cut edge.
    pub(crate) fn on_one_plane(&self, a: &P3, b: &P3) -> bool {
        let key = |p: &P3| {
            [
                (p.x + 0.0).to_bits(),
                (p.y + 0.0).to_bits(),
                (p.z + 0.0).to_bits(),
            ]
        };
        let (a, b) = (key(a), key(b));
        self.on_cut.iter().any(|s| s.contains(&a) && s.contains(&b))
    }

    /// True when face `f` belongs to a leaf the cut changed.
    pub(crate) fn in_cut_leaf(&self, f: u32) -> bool {
        let k = self.cut_leaves.partition_point(|r| r.end <= f);
        self.cut_leaves.get(k).is_some_and(|r| r.contains(&f))
    }

    /// The removed faces in `faces`, as offsets from its start (ascending).
    pub(crate) fn removed_in(&self, faces: Range<u32>) -> impl Iterator<Item = u32> + '_ {
        let from = self.removed.partition_point(|&f| f < faces.start);
        self.removed[from..]
            .iter()
            .take_while(move |&&f| f < faces.end)
            .map(move |&f| f - faces.start)
    }
}
