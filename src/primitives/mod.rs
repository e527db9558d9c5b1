//! Built-in polyhedral primitives: Platonic and Archimedean solids, prisms, antiprisms, boxes.
//!
//! Every solid here except [`cuboid`] is uniform: exact closed-form coordinates scaled to unit
//! edges, centred at the origin, all vertices on one sphere. Each planar face is one convex
//! polygon listed counter-clockwise seen from outside, and no vertex is repeated.

mod archimedean;
impl Mesh {
    /// The axis-aligned box between the corners `lo` and `hi`, as a clean closed mesh.
    ///
    /// ```
    /// use kepler_hsr::{Mesh, P3};
    ///
    /// let cube = Mesh::cuboid(P3::new(0., 0., 0.), P3::new(1., 1., 1.));
    /// assert_eq!((cube.vertices.len(), cube.faces.len()), (8, 6));
    /// ```
    pub fn cuboid(lo: P3, hi: P3) -> Mesh {
        Self::clean_solid(&cuboid(lo, hi))
    }

    /// The named Platonic or Archimedean solid (unit edges, centred at the origin) as a
    /// clean closed mesh, or `None` for a name not in [`Mesh::solid_names`].
    ///
    /// ```
    /// let ico = kepler_hsr::Mesh::solid("icosahedron").unwrap();
    /// assert_eq!(ico.faces.len(), 20);
    /// ```
    pub fn solid(name: &str) -> Option<Mesh> {
        by_name(name).map(|raw| Self::clean_solid(&raw))
    }

    /// The snake_case names [`Mesh::solid`] knows: the 5 Platonic then the 13 Archimedean
    /// solids.
    pub fn solid_names() -> Vec<&'static str> {
        names()
    }

    /// A built-in solid after cleanup (they are clean by construction).
    fn clean_solid(raw: &PolyMesh) -> Mesh {
        Self::from_polygons(raw.vertices.clone(), raw.faces.clone(), &mut Vec::new())
            .expect("built-in solids are clean")
    }
}

#[cfg(test)]
mod checks;
mod orbit;
mod platonic;
mod prism;

pub(crate) use prism::{antiprism, cuboid, prism, MAX_SIDES};

use crate::geom::{PolyMesh, P3};
use crate::scene::Mesh;

/// Builds one named solid.
type Build = fn() -> PolyMesh;

/// Every named solid with its builder: the Platonic ones, then the Archimedean ones.
fn catalogue() -> impl Iterator<Item = &'static (&'static str, Build)> {
    platonic::SOLIDS.iter().chain(archimedean::SOLIDS.iter())
}

/// The snake_case names `by_name` knows: the 5 Platonic then the 13 Archimedean solids.
pub(crate) fn names() -> Vec<&'static str> {
    catalogue().map(|&(name, _)| name).collect()
}

/// The named Platonic or Archimedean solid (unit edges, centred at the origin), or `None` for an
/// unknown name. Names are the snake_case ones listed by [`names`], e.g. `"snub_cube"`.
pub(crate) fn by_name(name: &str) -> Option<PolyMesh> {
    catalogue()
        .find(|&&(known, _)| known == name)
        .map(|(_, build)| build())
}

/// The golden ratio φ = (1 + √5) / 2.
fn golden_ratio() -> f64 {
    (1.0 + 5f64.sqrt()) / 2.0
}

/// The solid whose vertices are `vertices` (in convex position, centred at the origin): the
/// facets of their hull, with everything scaled so that edges have unit length.
fn unit_solid(mut vertices: Vec<P3>) -> PolyMesh {
    let faces = crate::geom::hull3::hull_facets(&vertices);
    let (a, b) = (faces[0][0] as usize, faces[0][1] as usize);
    let edge = (vertices[a] - vertices[b]).norm();
    for v in &mut vertices {
        *v = P3::from(v.coords / edge);
    }
    PolyMesh::new(vertices, faces)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_listed_name_builds() {
        let names = names();
        assert_eq!(names.len(), 18);
        for name in names {
            let mesh = by_name(name).unwrap_or_else(|| panic!("{name} unknown"));
            checks::assert_uniform(name, &mesh);
        }
    }

    #[test]
    fn unknown_names_and_small_n_give_none() {
        for name in [
            "",
            "cube ",
            "Cube",
            "snub-cube",
            "great_dodecahedron",
            "prism",
        ] {
            assert!(by_name(name).is_none(), "{name:?}");
        }
        for n in [0, 1, 2, MAX_SIDES + 1, u32::MAX] {
            assert!(prism(n).is_none() && antiprism(n).is_none(), "n = {n}");
        }
    }
}
