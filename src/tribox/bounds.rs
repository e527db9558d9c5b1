//! The tribox of a point set: min and max projections on the paper's nine directions.
//!
//! Section 2.1: T(S) is the intersection of 18 half-spaces, two per direction of
//! D = {x, y, z, x+y, x+z, y+z, x−z, y−x, z−y}. The directions are kept unnormalised, so the
//! bound on x+y is the paper's α_AB of the plane x + y = α_AB.
//!
//! Faces (bounds) are numbered 0..18: face 2k is the min side of direction k (outward normal
//! −d_k, offset −lo\[k\]), face 2k+1 its max side (outward normal d_k, offset hi\[k\]).

#[cfg(test)]
use crate::geom::Box3;
use crate::geom::{M4, P3, V3};

use super::boundary::Boundary;
use super::combos;

/// The nine directions of D, in the paper's order: x, y, z, x+y, x+z, y+z, x−z, y−x, z−y.
pub(crate) const DIRECTIONS: [[i8; 3]; 9] = [
    [1, 0, 0],
    [0, 1, 0],
    [0, 0, 1],
    [1, 1, 0],
    [1, 0, 1],
    [0, 1, 1],
    [1, 0, -1],
    [-1, 1, 0],
    [0, -1, 1],
];

/// The projection of `p` on direction `k`: sums and differences of coordinates, computed the
/// same way everywhere so that a point is exactly inside the tribox built from it.
#[inline]
pub(crate) fn project(p: &P3, k: usize) -> f64 {
    match k {
        0 => p.x,
        1 => p.y,
        2 => p.z,
        3 => p.x + p.y,
        4 => p.x + p.z,
        5 => p.y + p.z,
        6 => p.x - p.z,
        7 => p.y - p.x,
        _ => p.z - p.y,
    }
}

/// Direction `k` as a vector.
pub(crate) fn direction(k: usize) -> V3 {
    let d = DIRECTIONS[k];
    V3::new(f64::from(d[0]), f64::from(d[1]), f64::from(d[2]))
}

/// Outward normal of face `f` (unnormalised: ±d_k).
pub(crate) fn face_normal(f: usize) -> V3 {
    let d = direction(f / 2);
    if f.is_multiple_of(2) {
        -d
    } else {
        d
    }
}

/// A tribox: `lo[k] ≤ p·d_k ≤ hi[k]` for the nine directions. Empty when `lo > hi` somewhere.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Tribox {
    /// Least projection on each direction.
    pub lo: [f64; 9],
    /// Greatest projection on each direction.
    pub hi: [f64; 9],
}

impl Default for Tribox {
    fn default() -> Self {
        Tribox::empty()
    }
}

impl Tribox {
    /// The empty tribox (the identity of [`Tribox::merge`]).
    pub(crate) fn empty() -> Self {
        Tribox {
            lo: [f64::INFINITY; 9],
            hi: [f64::NEG_INFINITY; 9],
        }
    }

    /// The tribox of a point set: one pass updating 18 bounds (section 3).
    pub(crate) fn from_points<'a>(points: impl IntoIterator<Item = &'a P3>) -> Self {
        let mut t = Tribox::empty();
        for p in points {
            t.add_point(p);
        }
        t
    }

    /// The tribox with the given 18 face offsets (face `f` is `n_f·x ≤ offsets[f]`).
    pub(crate) fn from_offsets(offsets: &[f64; 18]) -> Self {
        Tribox {
            lo: std::array::from_fn(|k| -offsets[2 * k]),
            hi: std::array::from_fn(|k| offsets[2 * k + 1]),
        }
    }

    /// The 18 face offsets: face `f` is the half-space `face_normal(f)·x ≤ offsets[f]`.
    pub(crate) fn offsets(&self) -> [f64; 18] {
        std::array::from_fn(|f| self.offset(f))
    }

    /// Offset of face `f`.
    pub(crate) fn offset(&self, f: usize) -> f64 {
        if f.is_multiple_of(2) {
            -self.lo[f / 2]
        } else {
            self.hi[f / 2]
        }
    }

    /// Grows the tribox to hold `p`.
    pub(crate) fn add_point(&mut self, p: &P3) {
        for k in 0..9 {
            let v = project(p, k);
            self.lo[k] = self.lo[k].min(v);
            self.hi[k] = self.hi[k].max(v);
        }
    }

    /// The tribox of the union (merging up the object tree).
    pub(crate) fn merge(&self, o: &Tribox) -> Tribox {
        Tribox {
            lo: std::array::from_fn(|k| self.lo[k].min(o.lo[k])),
            hi: std::array::from_fn(|k| self.hi[k].max(o.hi[k])),
        }
    }

    /// True when no point satisfies the bounds as stored (some `lo > hi`). Bounds that are
    /// not tight may describe an empty set without this: see [`Tribox::tightened`].
    pub(crate) fn is_empty(&self) -> bool {
        (0..9).any(|k| self.lo[k] > self.hi[k] || self.lo[k].is_nan() || self.hi[k].is_nan())
    }

    /// Closed containment of a point (18 comparisons).
    pub(crate) fn contains(&self, p: &P3) -> bool {
        (0..9).all(|k| {
            let v = project(p, k);
            self.lo[k] <= v && v <= self.hi[k]
        })
    }

    /// The interference test: false when some slab separates the two (at most 18
    /// comparisons); true means the triboxes may meet. Exact for tight bounds: two convex
    /// sets bounded by the same nine directions are disjoint exactly when one of those
    /// directions, or a cross product of two of them, separates them; this test checks the
    /// nine face directions only, so it is conservative (never says "apart" wrongly).
    pub(crate) fn interferes(&self, o: &Tribox) -> bool {
        !self.is_empty()
            && !o.is_empty()
            && (0..9).all(|k| self.lo[k] <= o.hi[k] && o.lo[k] <= self.hi[k])
    }

    #[cfg(test)]
    /// The axis-aligned box of the x, y and z bounds (the paper's B(S), the CBOX).
    pub(crate) fn cbox(&self) -> Box3 {
        Box3::new(
            P3::new(self.lo[0], self.lo[1], self.lo[2]),
            P3::new(self.hi[0], self.hi[1], self.hi[2]),
        )
    }

    /// Width of the slab of direction `k` measured along the unit direction.
    pub(crate) fn thickness(&self, k: usize) -> f64 {
        (self.hi[k] - self.lo[k]) / direction(k).norm()
    }

    /// The same tribox with every bound tight (each face plane touching the polytope):
    /// section 3's boundary evaluation needs tight bounds. See [`combos::tighten`].
    pub(crate) fn tightened(&self) -> Tribox {
        if self.is_empty() {
            return Tribox::empty();
        }
        let t = Tribox::from_offsets(&combos::tighten(&self.offsets()));
        if t.is_empty() {
            Tribox::empty()
        } else {
            t
        }
    }

    /// The boundary (section 3) of the tightened bounds.
    pub(crate) fn boundary(&self) -> Boundary {
        Boundary::evaluate(&self.tightened())
    }

    #[cfg(test)]
    /// Volume, from the boundary.
    pub(crate) fn volume(&self) -> f64 {
        if self.is_empty() {
            return 0.0;
        }
        self.boundary().volume()
    }

    /// A conservative tribox of the set after the affine transform `m`: the tribox of the
    /// transformed boundary vertices. It holds every transformed point of the set, and it is
    /// the tightest tribox of the transformed tribox.
    pub(crate) fn transformed(&self, m: &M4) -> Tribox {
        if self.is_empty() {
            return *self;
        }
        let b = self.boundary();
        Tribox::from_points(
            b.vertices
                .iter()
                .map(|v| m.transform_point(v))
                .collect::<Vec<_>>()
                .iter(),
        )
    }

    /// Outward simplification (section 3): face planes that can be pushed out by at most
    /// `tol` (a distance) until their face vanishes are pushed there, smallest push first.
    /// The result contains the original.
    pub(crate) fn simplified(&self, tol: f64) -> Tribox {
        if self.is_empty() {
            return *self;
        }
        Tribox::from_offsets(&combos::simplify(&self.tightened().offsets(), tol)).tightened()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cube_points() -> Vec<P3> {
        Box3::new(P3::new(0., 0., 0.), P3::new(1., 2., 3.))
            .corners()
            .to_vec()
    }

    #[test]
    fn bounds_of_points_and_containment() {
        let pts = cube_points();
        let t = Tribox::from_points(pts.iter());
        assert_eq!(t.lo, [0., 0., 0., 0., 0., 0., -3., -1., -2.]);
        assert_eq!(t.hi, [1., 2., 3., 3., 4., 5., 1., 2., 3.]);
        for p in &pts {
            assert!(t.contains(p));
        }
        assert!(!t.contains(&P3::new(1.0, 2.0, 3.1)));
        assert_eq!(t.cbox(), Box3::from_points(pts.iter()));
    }

    #[test]
    fn merge_is_union_and_empty_is_identity() {
        let a = Tribox::from_points([P3::new(0., 0., 0.)].iter());
        let b = Tribox::from_points([P3::new(1., 1., 1.)].iter());
        let m = a.merge(&b);
        assert_eq!(Tribox::empty().merge(&a), a);
        assert!(m.contains(&P3::new(0., 0., 0.)) && m.contains(&P3::new(1., 1., 1.)));
        assert!(Tribox::empty().is_empty() && !a.is_empty());
    }

    #[test]
    fn interference_uses_diagonals() {
        // Two unit cubes' corners meeting diagonally in x+y but with overlapping boxes: the
        // points near (1,1) and (2,2) seen in the plane, tetrahedra leaning apart.
        let a = Tribox::from_points(
            [
                P3::new(0., 0., 0.),
                P3::new(1., 0., 0.),
                P3::new(0., 1., 0.),
                P3::new(0., 0., 1.),
            ]
            .iter(),
        );
        let b = Tribox::from_points(
            [
                P3::new(1., 1., 0.),
                P3::new(0.6, 1., 0.),
                P3::new(1., 0.6, 0.),
                P3::new(1., 1., 1.),
            ]
            .iter(),
        );
        assert!(a.cbox().union(&b.cbox()).volume() > 0.0);
        let boxes_meet =
            (0..3).all(|i| a.cbox().lo[i] <= b.cbox().hi[i] && b.cbox().lo[i] <= a.cbox().hi[i]);
        assert!(boxes_meet);
        assert!(!a.interferes(&b), "x+y separates them");
        assert!(a.interferes(&a));
    }

    #[test]
    fn transformed_contains_transformed_points() {
        let pts = cube_points();
        let t = Tribox::from_points(pts.iter());
        let m = nalgebra::Rotation3::from_axis_angle(&V3::y_axis(), 0.7).to_homogeneous()
            * M4::new_scaling(1.5);
        let tt = t.transformed(&m);
        for p in &pts {
            assert!(tt.contains(&m.transform_point(p)));
        }
        // Under the identity, the tribox of a tribox's vertices is the tribox itself.
        let same = t.transformed(&M4::identity());
        for k in 0..9 {
            assert!((same.lo[k] - t.lo[k]).abs() < 1e-12 && (same.hi[k] - t.hi[k]).abs() < 1e-12);
        }
    }

    #[test]
    fn volume_of_box_points_is_box_volume() {
        let t = Tribox::from_points(cube_points().iter());
        assert!((t.volume() - 6.0).abs() < 1e-12);
        assert_eq!(Tribox::empty().volume(), 0.0);
    }
}
