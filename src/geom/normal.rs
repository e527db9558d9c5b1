//! Newell's normal of a polygon: twice its vector area, robust for non-planar and
//! non-convex polygons (the one formula every stage uses).

use super::{P3, V3};

/// Newell's normal of the polygon `pts` (closed, last point not repeated): a vector
/// normal to its best-fit plane, of length twice its area, pointing to the side from which
/// it runs counter-clockwise. Zero for fewer than three points or no area.
pub(crate) fn newell(pts: &[P3]) -> V3 {
    newell_by(pts.len(), |i| pts[i])
}

/// [`newell`] of the polygon whose corners are `verts[idx[0]], verts[idx[1]], …`.
pub(crate) fn newell_indexed(verts: &[P3], idx: &[u32]) -> V3 {
    newell_by(idx.len(), |i| verts[idx[i] as usize])
}

/// Newell's sum over the `n` corners given by `at`.
fn newell_by(n: usize, at: impl Fn(usize) -> P3) -> V3 {
    let mut normal = V3::zeros();
    if n < 3 {
        return normal;
    }
    for i in 0..n {
        let (a, b) = (at(i), at((i + 1) % n));
        normal += V3::new(
            (a.y - b.y) * (a.z + b.z),
            (a.z - b.z) * (a.x + b.x),
            (a.x - b.x) * (a.y + b.y),
        );
    }
    normal
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn unit_square_has_normal_of_twice_its_area() {
        let sq = [
            P3::new(0., 0., 0.),
            P3::new(1., 0., 0.),
            P3::new(1., 1., 0.),
            P3::new(0., 1., 0.),
        ];
        assert_eq!(newell(&sq), V3::new(0., 0., 2.));
        assert_eq!(newell_indexed(&sq, &[3, 2, 1, 0]), V3::new(0., 0., -2.));
        assert_eq!(newell(&sq[..2]), V3::zeros());
    }

    #[test]
    fn l_shape_is_not_fooled_by_its_reflex_corner() {
        // Fan triangulation from a reflex corner gets signs wrong; Newell's sum does not.
        let l = [[0., 0.], [2., 0.], [2., 1.], [1., 1.], [1., 2.], [0., 2.]]
            .map(|p| P3::new(p[0], p[1], 5.0));
        assert_eq!(newell(&l), V3::new(0., 0., 6.));
    }
}
