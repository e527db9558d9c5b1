//! The generalized winding number of a polygon mesh around a point in space: the signed
//! solid angle its faces subtend, over 4π. 1 inside a closed outward solid, 0 outside, and a
//! smooth extension for open meshes.

use super::{P3, V3};

/// Generalized winding number of the faces (`faces`, each a list of indices into `verts`)
/// around `p`: the sum of the signed solid angles of their fan triangles over 4π
/// (Van Oosterom–Strackee). Its sign is exact only away from the surface.
pub(crate) fn winding_number<'a>(
    verts: &[P3],
    faces: impl IntoIterator<Item = &'a [u32]>,
    p: &P3,
) -> f64 {
    let mut total = 0.0;
    let mut v: Vec<V3> = Vec::new();
    for f in faces {
        v.clear();
        v.extend(f.iter().map(|&k| verts[k as usize] - p));
        for i in 1..v.len().saturating_sub(1) {
            total += solid_angle(&v[0], &v[i], &v[i + 1]);
        }
    }
    total / (4.0 * std::f64::consts::PI)
}

/// Signed solid angle of the triangle (a, b, c) seen from the origin.
fn solid_angle(a: &V3, b: &V3, c: &V3) -> f64 {
    let (la, lb, lc) = (a.norm(), b.norm(), c.norm());
    let num = a.dot(&b.cross(c));
    let den = la * lb * lc + a.dot(b) * lc + a.dot(c) * lb + b.dot(c) * la;
    2.0 * num.atan2(den)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tetrahedron_inside_and_outside() {
        let v = [
            P3::new(0., 0., 0.),
            P3::new(1., 0., 0.),
            P3::new(0., 1., 0.),
            P3::new(0., 0., 1.),
        ];
        let faces: [&[u32]; 4] = [&[0, 2, 1], &[0, 1, 3], &[0, 3, 2], &[1, 2, 3]];
        let w = |p: P3| winding_number(&v, faces, &p);
        assert!((w(P3::new(0.1, 0.1, 0.1)) - 1.0).abs() < 1e-12);
        assert!(w(P3::new(1., 1., 1.)).abs() < 1e-12);
    }
}
