//! The exact predicates every decision of side is made with (robust's adaptive orient2d and
//! orient3d): sign-exact for any finite f64 input, so coplanar faces, shared edges and
//! shared vertices are recognised without tolerances.

use super::poly2::Pt2;
use super::P3;

/// Exact sign of the turn a → b → c: > 0 left (counter-clockwise), < 0 right, 0 collinear.
#[inline]
pub(crate) fn orient2d(a: Pt2, b: Pt2, c: Pt2) -> f64 {
    robust::orient2d(
        robust::Coord { x: a[0], y: a[1] },
        robust::Coord { x: b[0], y: b[1] },
        robust::Coord { x: c[0], y: c[1] },
    )
}

/// Exact sign of the orientation of `d` against the plane through `a`, `b`, `c`: > 0 when
/// `d` lies below it (a, b, c counter-clockwise seen from above), < 0 above, 0 exactly on it.
/// The magnitude approximates six times the tetrahedron's volume.
#[inline]
pub(crate) fn orient3d(a: &P3, b: &P3, c: &P3, d: &P3) -> f64 {
    robust::orient3d(coord3(a), coord3(b), coord3(c), coord3(d))
}

/// [`orient3d`] against a plane given by three reference points.
#[inline]
pub(crate) fn orient3d_refs(refs: &[P3; 3], d: &P3) -> f64 {
    orient3d(&refs[0], &refs[1], &refs[2], d)
}

#[inline]
fn coord3(p: &P3) -> robust::Coord3D<f64> {
    robust::Coord3D {
        x: p.x,
        y: p.y,
        z: p.z,
    }
}

/// Winding number of the closed ring `r` around `p`, or None when `p` lies on the ring
/// (exact).
pub(crate) fn winding(r: &[Pt2], p: Pt2) -> Option<i32> {
    let n = r.len();
    let mut w = 0;
    for i in 0..n {
        w += winding_step(r[i], r[(i + 1) % n], p)?;
    }
    Some(w)
}

/// What the edge a → b adds to the winding number around `p` (+1 or -1 where it crosses
/// the ray from `p` toward +x, else 0), or None when `p` lies on it (exact). Only an edge
/// through `p`, or meeting the ray's line at or right of `p`, gives anything but 0.
#[inline]
pub(crate) fn winding_step(a: Pt2, b: Pt2, p: Pt2) -> Option<i32> {
    let o = orient2d(a, b, p);
    if o == 0.0 && on_segment_collinear(a, b, p) {
        return None;
    }
    if a[1] <= p[1] {
        Some(i32::from(b[1] > p[1] && o > 0.0))
    } else {
        Some(-i32::from(b[1] <= p[1] && o < 0.0))
    }
}

/// For `p` collinear with a and b: true when it lies on the closed segment.
fn on_segment_collinear(a: Pt2, b: Pt2, p: Pt2) -> bool {
    p[0] >= a[0].min(b[0])
        && p[0] <= a[0].max(b[0])
        && p[1] >= a[1].min(b[1])
        && p[1] <= a[1].max(b[1])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn orientation_signs_are_exact() {
        assert!(orient2d([0., 0.], [1., 0.], [0., 1.]) > 0.0);
        assert!(orient2d([0., 0.], [1., 0.], [0., -1.]) < 0.0);
        // Collinear in exact arithmetic, although naive floating point says otherwise.
        assert_eq!(orient2d([0.1, 0.1], [0.3, 0.3], [0.7, 0.7]), 0.0);
        let (a, b, c) = (
            P3::new(0., 0., 0.),
            P3::new(1., 0., 0.),
            P3::new(0., 1., 0.),
        );
        assert!(orient3d(&a, &b, &c, &P3::new(0., 0., -1.)) > 0.0);
        assert!(orient3d(&a, &b, &c, &P3::new(0., 0., 1.)) < 0.0);
        assert_eq!(orient3d_refs(&[a, b, c], &P3::new(0.3, 0.7, 0.)), 0.0);
    }

    #[test]
    fn winding_of_square_and_its_boundary() {
        let sq = [[0., 0.], [2., 0.], [2., 2.], [0., 2.]];
        assert_eq!(winding(&sq, [1., 1.]), Some(1));
        assert_eq!(winding(&sq, [3., 1.]), Some(0));
        assert_eq!(winding(&sq, [2., 1.]), None);
        let cw: Vec<Pt2> = sq.iter().rev().copied().collect();
        assert_eq!(winding(&cw, [1., 1.]), Some(-1));
    }
}
