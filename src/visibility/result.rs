//! The pass's result: every face's visible region, its area and projected area. A face
//! nothing hides keeps no region of its own: it is made from the screen faces when read.

use std::borrow::Cow;
use std::fmt;
use std::sync::Arc;

use crate::geom::poly2::{canonicalize, MultiPolygon, Pt2};
use crate::scene::FaceId;
use crate::view::{PieceId, ScreenFaces};

use super::stats::Counters;

/// One face's result as the pass keeps it (48 bytes, and a heap block only for a region
/// something hides).
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Solved {
    /// Visible region in screen space (canonical); empty for a whole face.
    pub visible: MultiPolygon,
    /// Its area.
    pub area: f64,
    /// The face's projected area (0 when edge-on or clipped).
    pub projected_area: f64,
    /// Nothing hides any of the face, and its projected ring is simple: its region is that
    /// ring ([`whole_region`]), not kept in `visible`.
    pub whole: bool,
}

impl Solved {
    /// Nothing visible, with the face's projected area.
    pub(crate) fn empty(projected_area: f64) -> Self {
        Solved {
            visible: Vec::new(),
            area: 0.0,
            projected_area,
            whole: false,
        }
    }

    /// Nothing visible: taken out of a result that is merged.
    pub(crate) const HIDDEN: Solved = Solved {
        visible: Vec::new(),
        area: 0.0,
        projected_area: 0.0,
        whole: false,
    };
}

/// The region of a face nothing hides, from its piece `p`: the projected ring,
/// counter-clockwise, canonical (it starts at its least point).
pub(crate) fn whole_region(screen: &ScreenFaces, p: PieceId) -> MultiPolygon {
    let mut visible = vec![vec![screen.ring_ccw(p)]];
    canonicalize(&mut visible);
    visible
}

/// The visible part of one face, read from a [`Visibility`].
#[derive(Clone, Copy)]
pub struct FaceVisibility<'a> {
    /// The visible region's area.
    pub area: f64,
    /// The face's projected area (0 when edge-on or clipped).
    pub projected_area: f64,
    region: Region<'a>,
}

/// Where a face's region is: kept, or the ring of a piece nothing hides.
#[derive(Clone, Copy)]
enum Region<'a> {
    Kept(&'a MultiPolygon),
    Whole(&'a ScreenFaces, PieceId),
}

/// No region.
static NONE: MultiPolygon = Vec::new();

impl<'a> FaceVisibility<'a> {
    /// Nothing visible: a face of a culled subtree.
    const HIDDEN: FaceVisibility<'static> = FaceVisibility {
        area: 0.0,
        projected_area: 0.0,
        region: Region::Kept(&NONE),
    };

    /// The visible region in screen space (canonical: rings start at their least point).
    /// Borrowed where the pass kept it; made from the projected ring for a face nothing
    /// hides.
    pub fn visible(&self) -> Cow<'a, MultiPolygon> {
        match self.region {
            Region::Kept(m) => Cow::Borrowed(m),
            Region::Whole(screen, p) => Cow::Owned(whole_region(screen, p)),
        }
    }

    /// `f` folded over the region's points, ring after ring (a whole face's from its
    /// piece's projected points, in their order, without making its region).
    pub(crate) fn fold_points<T>(&self, init: T, mut f: impl FnMut(T, Pt2) -> T) -> T {
        match self.region {
            Region::Kept(m) => m.iter().flatten().flatten().fold(init, |a, p| f(a, *p)),
            Region::Whole(screen, p) => screen.pts(p).iter().fold(init, |a, q| f(a, [q[0], q[1]])),
        }
    }

    /// Nothing of the face is visible.
    pub fn is_empty(&self) -> bool {
        match self.region {
            Region::Kept(m) => m.is_empty(),
            Region::Whole(..) => false,
        }
    }

    /// Nothing hides any of the face: its region is its whole projected ring, so every
    /// edge of the face is visible from end to end.
    pub(crate) fn whole(&self) -> bool {
        matches!(self.region, Region::Whole(..))
    }
}

impl PartialEq for FaceVisibility<'_> {
    fn eq(&self, other: &Self) -> bool {
        self.area == other.area
            && self.projected_area == other.projected_area
            && self.visible() == other.visible()
    }
}

impl fmt::Debug for FaceVisibility<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("FaceVisibility")
            .field("visible", &self.visible())
            .field("area", &self.area)
            .field("projected_area", &self.projected_area)
            .finish()
    }
}

/// The visible-polygon set of a view: the faces the pass solved (a warped face's planar
/// pieces merged), by ascending global id; faces of culled subtrees are absent (empty).
#[derive(Debug, Clone)]
pub struct Visibility {
    ids: Vec<FaceId>,
    faces: Vec<Solved>,
    face_count: usize,
    /// The screen faces the pass solved: the regions of the faces nothing hides.
    screen: Arc<ScreenFaces>,
    /// What the pass did.
    pub counters: Counters,
}

impl Visibility {
    /// The set of `faces` (results of `ids`, ascending) of `screen`.
    pub(crate) fn new(
        ids: Vec<FaceId>,
        faces: Vec<Solved>,
        screen: Arc<ScreenFaces>,
        counters: Counters,
    ) -> Self {
        Visibility {
            ids,
            faces,
            face_count: screen.face_count(),
            screen,
            counters,
        }
    }

    /// Face `id`'s visibility; empty (with no projected area) for a face of a culled subtree.
    pub fn face(&self, id: FaceId) -> FaceVisibility<'_> {
        if self.ids.len() == self.face_count {
            return match self.faces.get(id.index()) {
                Some(_) => self.at(id.index()),
                None => FaceVisibility::HIDDEN,
            };
        }
        match self.ids.binary_search(&id) {
            Ok(k) => self.at(k),
            Err(_) => FaceVisibility::HIDDEN,
        }
    }

    /// The solved faces with their global ids, ascending.
    pub fn iter(&self) -> impl ExactSizeIterator<Item = (FaceId, FaceVisibility<'_>)> + '_ {
        (0..self.ids.len()).map(|k| (self.ids[k], self.at(k)))
    }

    /// The solved faces' ids, ascending.
    pub(crate) fn ids(&self) -> &[FaceId] {
        &self.ids
    }

    /// The `k`th solved face (of [`Visibility::ids`]).
    pub(crate) fn at(&self, k: usize) -> FaceVisibility<'_> {
        let s = &self.faces[k];
        let region = if s.whole {
            let p = self.screen.face_starts[self.ids[k].index()];
            Region::Whole(&self.screen, PieceId(p))
        } else {
            Region::Kept(&s.visible)
        };
        FaceVisibility {
            area: s.area,
            projected_area: s.projected_area,
            region,
        }
    }

    /// Every face's visibility in global face order, solved or not.
    pub fn by_id(&self) -> Vec<FaceVisibility<'_>> {
        (0..self.face_count as u32)
            .map(|id| self.face(FaceId(id)))
            .collect()
    }

    /// Number of faces in the scene (solved or not).
    pub fn face_count(&self) -> usize {
        self.face_count
    }

    /// Number of faces the pass solved.
    pub fn solved_count(&self) -> usize {
        self.faces.len()
    }

    /// Total visible area.
    pub fn total_area(&self) -> f64 {
        self.faces.iter().map(|f| f.area).sum()
    }
}
