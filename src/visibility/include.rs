//! INCLUDE: is a point inside an object? Box shortcuts first, then a point-in-polyhedron test.

use crate::geom::{M4, P3, V3};
use crate::scene::{Content, Mesh, Object};

/// The paper's INCLUDE answer.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Inclusion {
    /// Inside the object.
    In,
    /// Outside the object.
    Out,
}

/// INCLUDE(A, P) for world point `p` and object `a` placed by `xf` (its parent's frame to world).
///
/// Steps as in the paper: inside INBOX, IN; outside CBOX, OUT; a leaf, the generalized
/// winding number w of its faces around P (IN when |w| > 1/2: exact in sign away from the
/// surface, and for open meshes the natural extension); subobjects, IN if any is.
pub fn include(a: &Object, xf: &M4, p: &P3) -> Inclusion {
    let local = match xf.try_inverse() {
        Some(inv) => inv.transform_point(p),
        None => return Inclusion::Out,
    };
    include_local(a, &local)
}

fn include_local(a: &Object, p: &P3) -> Inclusion {
    if a.inbox.is_some_and(|b| b.contains(p)) {
        return Inclusion::In;
    }
    if !a.cbox.contains(p) {
        return Inclusion::Out;
    }
    match &a.content {
        Content::Mesh(m) => {
            if winding_number(m, p).abs() > 0.5 {
                Inclusion::In
            } else {
                Inclusion::Out
            }
        }
        Content::Subobjects(subs) => {
            if subs.iter().any(|s| include_local(s, p) == Inclusion::In) {
                Inclusion::In
            } else {
                Inclusion::Out
            }
        }
        Content::Instance(i) => include(&i.prototype, &i.transform, p),
    }
}

/// Generalized winding number of a mesh's faces around `p`: the sum of the signed solid
/// angles of its (fan-triangulated) faces over 4π (Van Oosterom–Strackee).
pub fn winding_number(m: &Mesh, p: &P3) -> f64 {
    let mut total = 0.0;
    for f in &m.faces {
        let v: Vec<V3> = f
            .vertices
            .iter()
            .map(|&k| m.vertices[k as usize] - p)
            .collect();
        for i in 1..v.len() - 1 {
            total += solid_angle(&v[0], &v[i], &v[i + 1]);
        }
    }
    total / (4.0 * std::f64::consts::PI)
}

fn solid_angle(a: &V3, b: &V3, c: &V3) -> f64 {
    let (la, lb, lc) = (a.norm(), b.norm(), c.norm());
    let num = a.dot(&b.cross(c));
    let den = la * lb * lc + a.dot(b) * lc + a.dot(c) * lb + b.dot(c) * la;
    2.0 * num.atan2(den)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::testing::unit_cube;

    #[test]
    fn cube_inside_outside() {
        let c = unit_cube();
        let id = M4::identity();
        assert_eq!(include(&c, &id, &P3::new(0.5, 0.5, 0.5)), Inclusion::In);
        assert_eq!(include(&c, &id, &P3::new(0.99, 0.01, 0.5)), Inclusion::In);
        assert_eq!(include(&c, &id, &P3::new(1.5, 0.5, 0.5)), Inclusion::Out);
        let w = winding_number(c.mesh().unwrap(), &P3::new(0.3, 0.6, 0.2));
        assert!((w - 1.0).abs() < 1e-12, "{w}");
    }

    #[test]
    fn instance_transform_is_applied() {
        let proto = std::sync::Arc::new(unit_cube());
        let t = nalgebra::Translation3::new(5., 0., 0.).to_homogeneous();
        let inst = Object::instance("i", proto, t);
        assert_eq!(
            include(&inst, &M4::identity(), &P3::new(5.5, 0.5, 0.5)),
            Inclusion::In
        );
        assert_eq!(
            include(&inst, &M4::identity(), &P3::new(0.5, 0.5, 0.5)),
            Inclusion::Out
        );
    }
}
