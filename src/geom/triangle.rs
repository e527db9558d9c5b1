//! Triangles in space: the closest point of a triangle to a point.

use super::P3;

/// The point of triangle (a, b, c) nearest to `p` (Ericson, Real-Time Collision Detection,
/// 5.1.5: the Voronoi region of `p` decides the vertex, edge or face). A degenerate triangle
/// answers its nearest corner when the face region cannot be solved.
pub(crate) fn closest_on_triangle(p: &P3, a: &P3, b: &P3, c: &P3) -> P3 {
    let (ab, ac, ap) = (b - a, c - a, p - a);
    let (d1, d2) = (ab.dot(&ap), ac.dot(&ap));
    if d1 <= 0.0 && d2 <= 0.0 {
        return *a;
    }
    let bp = p - b;
    let (d3, d4) = (ab.dot(&bp), ac.dot(&bp));
    if d3 >= 0.0 && d4 <= d3 {
        return *b;
    }
    let vc = d1 * d4 - d3 * d2;
    if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
        return a + ab * (d1 / (d1 - d3));
    }
    let cp = p - c;
    let (d5, d6) = (ab.dot(&cp), ac.dot(&cp));
    if d6 >= 0.0 && d5 <= d6 {
        return *c;
    }
    let vb = d5 * d2 - d1 * d6;
    if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
        return a + ac * (d2 / (d2 - d6));
    }
    let va = d3 * d6 - d5 * d4;
    if va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0 {
        return b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
    }
    let denom = va + vb + vc;
    if denom == 0.0 {
        return [a, b, c]
            .into_iter()
            .min_by(|x, y| (*x - p).norm_squared().total_cmp(&(*y - p).norm_squared()))
            .copied()
            .unwrap_or(*a);
    }
    let (v, w) = (vb / denom, vc / denom);
    a + ab * v + ac * w
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_voronoi_region() {
        let (a, b, c) = (
            P3::new(0., 0., 0.),
            P3::new(2., 0., 0.),
            P3::new(0., 2., 0.),
        );
        let at = |x, y, z| closest_on_triangle(&P3::new(x, y, z), &a, &b, &c);
        assert_eq!(at(-1., -1., 5.), a);
        assert_eq!(at(3., -1., 0.), b);
        assert_eq!(at(-1., 3., 0.), c);
        assert_eq!(at(1., -3., 1.), P3::new(1., 0., 0.));
        assert_eq!(at(-3., 1., 1.), P3::new(0., 1., 0.));
        assert_eq!(at(2., 2., 0.), P3::new(1., 1., 0.));
        assert_eq!(at(0.5, 0.5, 7.), P3::new(0.5, 0.5, 0.));
    }
}
