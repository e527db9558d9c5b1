//! Convex hulls in the plane and the exact tests on them: hull, proper turn, containment.

use super::poly2::Pt2;
use super::predicates::orient2d;

/// Convex hull (Andrew's monotone chain, exact turns), counter-clockwise, no collinear points.
pub(crate) fn convex_hull(mut pts: Vec<Pt2>) -> Vec<Pt2> {
    pts.sort_by(|a, b| a[0].total_cmp(&b[0]).then(a[1].total_cmp(&b[1])));
    pts.dedup();
    if pts.len() < 3 {
        return pts;
    }
    let mut hull: Vec<Pt2> = Vec::with_capacity(pts.len() * 2);
    for pass in 0..2 {
        let start = hull.len();
        let iter: Box<dyn Iterator<Item = &Pt2>> = if pass == 0 {
            Box::new(pts.iter())
        } else {
            Box::new(pts.iter().rev())
        };
        for &p in iter {
            while hull.len() >= start + 2
                && orient2d(hull[hull.len() - 2], hull[hull.len() - 1], p) <= 0.0
            {
                hull.pop();
            }
            hull.push(p);
        }
        hull.pop();
    }
    hull
}

/// True when some three consecutive points of the ring make a proper turn (exact): the
/// ring encloses area.
pub(crate) fn has_turn(r: &[Pt2]) -> bool {
    let n = r.len();
    (0..n).any(|i| orient2d(r[i], r[(i + 1) % n], r[(i + 2) % n]) != 0.0)
}

/// True when convex counter-clockwise `outer` (with area) contains every point of `inner` (closed).
pub(crate) fn covers_convex(outer: &[Pt2], inner: &[Pt2]) -> bool {
    if !has_turn(outer) {
        return false;
    }
    let n = outer.len();
    (0..n).all(|i| {
        let (p, q) = (outer[i], outer[(i + 1) % n]);
        p == q || inner.iter().all(|&r| orient2d(p, q, r) >= 0.0)
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hull_of_square_with_inner_and_collinear_points() {
        let h = convex_hull(vec![
            [0., 0.],
            [1., 0.],
            [2., 0.],
            [2., 2.],
            [0., 2.],
            [1., 1.],
            [0., 1.],
        ]);
        assert_eq!(h, vec![[0., 0.], [2., 0.], [2., 2.], [0., 2.]]);
    }

    #[test]
    fn degenerate_ring_covers_nothing() {
        let p = [1.0, 1.0];
        assert!(!covers_convex(&[p, p, p], &[[0., 0.], [1., 0.], [0., 1.]]));
        assert!(!covers_convex(&[[0., 0.], [1., 1.], [2., 2.]], &[[1., 1.]]));
    }

    #[test]
    fn cover_test_is_closed() {
        let big = [[0., 0.], [2., 0.], [2., 2.], [0., 2.]];
        assert!(covers_convex(&big, &[[0., 0.], [2., 2.], [1., 0.5]]));
        assert!(!covers_convex(&big, &[[0., 0.], [2.1, 2.]]));
    }
}
