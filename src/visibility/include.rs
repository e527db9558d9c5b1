//! INCLUDE: is a point inside an object? Box shortcuts first, then a point-in-polyhedron test.

use crate::geom::{M4, P3};
use crate::scene::{Content, Object};

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
pub(crate) fn include(a: &Object, xf: &M4, p: &P3) -> Inclusion {
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
            if m.winding_number(p).abs() > 0.5 {
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
        let w = c.mesh().unwrap().winding_number(&P3::new(0.3, 0.6, 0.2));
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
