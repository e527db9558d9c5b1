//! Whether a given box lies inside an object (an explicit INBOX is checked as computed ones
//! are proven): inside one of its closed solids, no face of that solid meeting the box, its
//! centre enclosed (winding number 1).
//!
//! The faces are tested with the separating-axis test in f64 against the box grown by a
//! margin of [`MARGIN`] of the object's size (its rounding error is far below the margin):
//! when none meets it, the box itself is proven inside and kept. A box that touches faces
//! (an INBOX that is a solid's own box) is then tested shrunk by the margin: a face that
//! touches it from outside passes, a face that enters it fails, and the shrunk box is the
//! one proven inside, and the one kept.

use crate::geom::solid_angle::winding_number;
use crate::geom::{Box3, M4, P3, V3};
use crate::scene::Object;

use crate::geom::tri_box::tri_meets_box;

/// Relative margin by which a checked box is shrunk (of the object's largest CBOX side).
pub(crate) const MARGIN: f64 = 1e-9;

/// Why a box is not inside an object.
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum Outside {
    /// The box has no interior (after the margin).
    Flat,
    /// No leaf of the object is a closed solid, so nothing can hold a box.
    NoSolid,
    /// A face of the named leaf enters the box (the leaf whose CBOX holds the box).
    Crossed {
        /// Path of the leaf below the object.
        leaf: String,
        /// The face's index in the leaf.
        face: usize,
    },
    /// The box meets no face but lies outside every closed solid that could hold it.
    Beyond,
}

impl std::fmt::Display for Outside {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Outside::Flat => write!(f, "it has no interior"),
            Outside::NoSolid => write!(f, "the object has no closed solid to hold it"),
            Outside::Crossed { leaf, face } => {
                let leaf = if leaf.is_empty() { "the object" } else { leaf };
                write!(f, "face {face} of {leaf} passes through it")
            }
            Outside::Beyond => write!(f, "it lies outside the object's solids"),
        }
    }
}

/// The box `b` (in the frame `object.cbox` is in) when it lies inside one closed solid of
/// `object` clear of its faces by the margin; else `b` shrunk by the margin, when that lies
/// inside one; else why not.
pub(crate) fn inside(object: &Object, b: &Box3) -> Result<Box3, Outside> {
    let scale = object.cbox.size().iter().fold(0.0f64, |a, &x| a.max(x));
    let m = V3::repeat(MARGIN * scale);
    let shrunk = Box3::new(b.lo + m, b.hi - m);
    if !shrunk.has_interior() {
        return Err(Outside::Flat);
    }
    if held(object, &Box3::new(b.lo - m, b.hi + m)).is_ok() {
        return Ok(*b);
    }
    held(object, &shrunk).map(|()| shrunk)
}

/// Ok when one closed solid of `object` holds `b`: its CBOX holds `b`, no face meets `b`,
/// and `b`'s centre has winding number ±1.
fn held(object: &Object, b: &Box3) -> Result<(), Outside> {
    let centre = b.center();
    let half = (b.hi - b.lo) * 0.5;
    let mut why = Outside::NoSolid;
    let mut found = false;
    object.for_each_mesh(&M4::identity(), &mut |path, mesh, xf| {
        if found || !mesh.closed {
            return;
        }
        let world: Vec<P3> = mesh
            .vertices
            .iter()
            .map(|v| xf.transform_point(v))
            .collect();
        if !Box3::from_points(world.iter()).contains_box(b) {
            if why == Outside::NoSolid {
                why = Outside::Beyond;
            }
            return;
        }
        for (k, f) in mesh.faces.iter().enumerate() {
            let v = &f.vertices;
            for i in 1..v.len().saturating_sub(1) {
                let t = [
                    world[v[0] as usize],
                    world[v[i] as usize],
                    world[v[i + 1] as usize],
                ];
                if tri_meets_box(&t, &centre, &half) {
                    why = Outside::Crossed {
                        leaf: path.join("/"),
                        face: k,
                    };
                    return;
                }
            }
        }
        let w = winding_number(
            &world,
            mesh.faces.iter().map(|f| f.vertices.as_slice()),
            &centre,
        );
        if (w.abs() - 1.0).abs() < 0.25 {
            found = true;
        } else if why == Outside::NoSolid {
            why = Outside::Beyond;
        }
    });
    if found {
        Ok(())
    } else {
        Err(why)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::testing::{cuboid, unit_cube};

    fn b(lo: [f64; 3], hi: [f64; 3]) -> Box3 {
        Box3::new(P3::from(lo), P3::from(hi))
    }

    #[test]
    fn boxes_inside_touching_crossing_and_outside() {
        let cube = unit_cube();
        // The cube itself: touching every face from inside is inside.
        let s = inside(&cube, &b([0., 0., 0.], [1., 1., 1.])).unwrap();
        assert!(s.lo.x > 0.0 && s.lo.x < 1e-8 && s.hi.x < 1.0 && s.hi.x > 1.0 - 1e-8);
        // Clear of every face: kept as given.
        let clear = b([0.2, 0.2, 0.2], [0.5, 0.5, 0.5]);
        assert_eq!(inside(&cube, &clear), Ok(clear));
        // Poking out of one side by 1e-6: a face passes through it.
        let e = inside(&cube, &b([0.2, 0.2, 0.2], [1.000001, 0.5, 0.5])).unwrap_err();
        assert!(
            matches!(e, Outside::Beyond | Outside::Crossed { .. }),
            "{e:?}"
        );
        assert_eq!(
            inside(&cube, &b([0., 0., 0.], [1., 1., 0.])),
            Err(Outside::Flat)
        );
        // A group: inside one part is enough; a box across two touching parts is not.
        let g = Object::group(
            "g",
            vec![
                cuboid("a", [0., 0., 0.], [1., 1., 1.]),
                cuboid("b", [1., 0., 0.], [2., 1., 1.]),
            ],
        );
        assert!(inside(&g, &b([1.2, 0.1, 0.1], [1.8, 0.9, 0.9])).is_ok());
        let e = inside(&g, &b([0.5, 0.1, 0.1], [1.5, 0.9, 0.9])).unwrap_err();
        assert_eq!(e, Outside::Beyond);
        // A hollow: an L-shaped solid's notch is outside it though inside its CBOX.
        let l = crate::scene::testing::leaf("l", &l_prism());
        assert!(l.mesh().unwrap().closed);
        let e = inside(&l, &b([1.2, 1.2, 0.2], [1.8, 1.8, 0.8])).unwrap_err();
        assert!(matches!(e, Outside::Beyond), "{e:?}");
        let e = inside(&l, &b([0.5, 0.5, 0.2], [1.5, 1.5, 0.8])).unwrap_err();
        assert!(matches!(e, Outside::Crossed { face: _, .. }), "{e:?}");
        assert!(inside(&l, &b([0.1, 0.1, 0.1], [0.9, 1.9, 0.9])).is_ok());
    }

    /// An L-shaped prism: the square [0,2]² without the quarter [1,2]², z in [0, 1].
    fn l_prism() -> crate::geom::PolyMesh {
        let ring = [[0., 0.], [2., 0.], [2., 1.], [1., 1.], [1., 2.], [0., 2.]];
        let mut v: Vec<P3> = ring.iter().map(|p| P3::new(p[0], p[1], 0.)).collect();
        v.extend(ring.iter().map(|p| P3::new(p[0], p[1], 1.)));
        let n = ring.len() as u32;
        let mut faces = vec![(0..n).rev().collect::<Vec<u32>>(), (n..2 * n).collect()];
        for i in 0..n {
            let j = (i + 1) % n;
            faces.push(vec![i, j, j + n, i + n]);
        }
        crate::geom::PolyMesh::new(v, faces)
    }
}
