//! Planar polygons in screen space: rings, polygons with holes, multipolygons; their areas,
//! point location and canonical form.

use super::predicates::winding;

/// A point of the screen plane.
pub type Pt2 = [f64; 2];
/// A closed ring (the last point is not repeated).
pub type Ring = Vec<Pt2>;
/// A polygon: outer ring (counter-clockwise) first, then holes (clockwise).
pub type Polygon = Vec<Ring>;
/// A set of disjoint polygons.
pub type MultiPolygon = Vec<Polygon>;

/// Signed area of a ring (shoelace; positive for counter-clockwise).
pub fn ring_area(r: &[Pt2]) -> f64 {
    let n = r.len();
    if n < 3 {
        return 0.0;
    }
    let o = r[0];
    let mut s = 0.0;
    for i in 1..n - 1 {
        s += (r[i][0] - o[0]) * (r[i + 1][1] - o[1]) - (r[i + 1][0] - o[0]) * (r[i][1] - o[1]);
    }
    0.5 * s
}

/// Distance between two points (sqrt of the sum of squares, not hypot: screen and page
/// coordinates are far from overflow, and this is several times faster).
#[inline]
pub(crate) fn dist(a: Pt2, b: Pt2) -> f64 {
    let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
    (dx * dx + dy * dy).sqrt()
}

/// Length of a polyline.
pub(crate) fn polyline_length(l: &[Pt2]) -> f64 {
    l.windows(2).map(|w| dist(w[0], w[1])).sum()
}

/// Area of a polygon with holes (outer minus holes, by signed ring areas).
pub(crate) fn polygon_area(p: &Polygon) -> f64 {
    p.iter().map(|r| ring_area(r)).sum()
}

/// Total area of a multipolygon.
pub fn multipolygon_area(m: &MultiPolygon) -> f64 {
    m.iter().map(polygon_area).sum()
}

/// Where a point lies relative to a region.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Side {
    /// Strictly inside.
    Inside,
    /// On the boundary.
    Boundary,
    /// Strictly outside.
    Outside,
}

/// Exact location of `p` relative to a multipolygon (non-zero winding over all rings).
pub(crate) fn locate(m: &MultiPolygon, p: Pt2) -> Side {
    let mut total = 0;
    for poly in m {
        for r in poly {
            match winding(r, p) {
                None => return Side::Boundary,
                Some(w) => total += w,
            }
        }
    }
    if total != 0 {
        Side::Inside
    } else {
        Side::Outside
    }
}

/// The ring rotated to start at its lexicographically smallest point (x, then y): the
/// start [`canonicalize`] gives every ring.
pub(crate) fn start_at_least(r: &mut [Pt2]) {
    let key = |p: &Pt2, q: &Pt2| p[0].total_cmp(&q[0]).then(p[1].total_cmp(&q[1]));
    if let Some(k) = (0..r.len()).min_by(|&i, &j| key(&r[i], &r[j])) {
        r.rotate_left(k);
    }
}

/// Canonical form: every ring starts at its lexicographically smallest point (x, then y),
/// holes sorted after the outer ring, polygons sorted by their outer ring's start.
pub(crate) fn canonicalize(m: &mut MultiPolygon) {
    let key = |p: &Pt2, q: &Pt2| p[0].total_cmp(&q[0]).then(p[1].total_cmp(&q[1]));
    for poly in m.iter_mut() {
        for r in poly.iter_mut() {
            start_at_least(r);
        }
        if poly.len() > 2 {
            poly[1..].sort_by(|a, b| key(&a[0], &b[0]));
        }
    }
    m.retain(|p| !p.is_empty() && !p[0].is_empty());
    m.sort_by(|a, b| key(&a[0][0], &b[0][0]));
}

#[cfg(test)]
mod tests {
    use super::*;

    fn square(x0: f64, y0: f64, s: f64) -> Ring {
        vec![[x0, y0], [x0 + s, y0], [x0 + s, y0 + s], [x0, y0 + s]]
    }

    #[test]
    fn areas_and_location() {
        let mut hole = square(1., 1., 1.);
        hole.reverse();
        let m: MultiPolygon = vec![vec![square(0., 0., 3.), hole]];
        assert_eq!(multipolygon_area(&m), 8.0);
        assert_eq!(locate(&m, [0.5, 0.5]), Side::Inside);
        assert_eq!(locate(&m, [1.5, 1.5]), Side::Outside);
        assert_eq!(locate(&m, [1.0, 1.5]), Side::Boundary);
        assert_eq!(locate(&m, [3.0, 3.0]), Side::Boundary);
        assert_eq!(locate(&m, [4.0, 1.0]), Side::Outside);
    }

    #[test]
    fn canonical_rotation_and_order() {
        let mut m: MultiPolygon = vec![
            vec![vec![[5., 5.], [6., 5.], [5., 6.]]],
            vec![vec![[1., 0.], [1., 1.], [0., 0.]]],
        ];
        canonicalize(&mut m);
        assert_eq!(m[0][0][0], [0., 0.]);
        assert_eq!(m[0][0], vec![[0., 0.], [1., 0.], [1., 1.]]);
        assert_eq!(m[1][0][0], [5., 5.]);
    }
}
