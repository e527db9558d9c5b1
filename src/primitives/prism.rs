//! Prisms, antiprisms and axis-aligned boxes.

use std::f64::consts::PI;

use crate::geom::{PolyMesh, P3};

/// The largest number of sides [`prism`] and [`antiprism`] accept (keeps meshes allocatable).
pub(crate) const MAX_SIDES: u32 = 1 << 16;

/// The uniform n-gonal prism: two regular n-gons joined by n squares, unit edges, centred at the
/// origin with the n-gons horizontal (normal ±z). `None` unless 3 ≤ n ≤ [`MAX_SIDES`].
///
/// Vertices 0..n are the bottom n-gon (z = −1/2), n..2n the top one straight above them.
pub(crate) fn prism(n: u32) -> Option<PolyMesh> {
    if !(3..=MAX_SIDES).contains(&n) {
        return None;
    }
    let vertices = rims(n, 1.0, 0.0);
    let mut faces = caps(n);
    for i in 0..n {
        let j = (i + 1) % n;
        faces.push(vec![i, j, n + j, n + i]);
    }
    Some(PolyMesh::new(vertices, faces))
}

/// The uniform n-gonal antiprism: two regular n-gons, the top one turned by π/n, joined by a band
/// of 2n equilateral triangles; unit edges, centred at the origin, n-gons horizontal. `None`
/// unless 3 ≤ n ≤ [`MAX_SIDES`].
///
/// Vertices 0..n are the bottom n-gon, n..2n the top one.
pub(crate) fn antiprism(n: u32) -> Option<PolyMesh> {
    if !(3..=MAX_SIDES).contains(&n) {
        return None;
    }
    // Each top corner sits above the middle of a bottom side, 1 / (2 cos(π/2n)) away across.
    let across = 0.5 / (PI / (2.0 * n as f64)).cos();
    let vertices = rims(n, (1.0 - across * across).sqrt(), 1.0);
    let mut faces = caps(n);
    for i in 0..n {
        let j = (i + 1) % n;
        faces.push(vec![i, j, n + i]);
        faces.push(vec![j, n + j, n + i]);
    }
    Some(PolyMesh::new(vertices, faces))
}

/// The axis-aligned box with opposite corners `lo` and `hi` (in any order): 8 vertices, 6
/// quadrilaterals counter-clockwise seen from outside.
///
/// Vertex `i` takes its x from `hi` when bit 0 of `i` is set (else from `lo`), y likewise from
/// bit 1, z from bit 2. A box flat on some axis is degenerate but still returned.
pub(crate) fn cuboid(lo: P3, hi: P3) -> PolyMesh {
    let (lo, hi) = (lo.inf(&hi), lo.sup(&hi));
    let corner = |i: u32| {
        P3::from(std::array::from_fn(|axis| {
            if i >> axis & 1 == 1 {
                hi[axis]
            } else {
                lo[axis]
            }
        }))
    };
    let faces = [
        [0, 4, 6, 2], // x = lo.x
        [1, 3, 7, 5], // x = hi.x
        [0, 1, 5, 4], // y = lo.y
        [2, 6, 7, 3], // y = hi.y
        [0, 2, 3, 1], // z = lo.z
        [4, 5, 7, 6], // z = hi.z
    ];
    PolyMesh::new((0..8).map(corner).collect(), faces.map(Vec::from).into())
}

/// Two regular n-gons with unit edges: the bottom one at z = −height/2 with a corner on the +x
/// axis, the top one at z = +height/2 turned by `top_turn` · π/n.
fn rims(n: u32, height: f64, top_turn: f64) -> Vec<P3> {
    let circumradius = 0.5 / (PI / n as f64).sin();
    let corner = |k: u32, turn: f64, z: f64| {
        let angle = (2.0 * k as f64 + turn) * PI / n as f64;
        P3::new(circumradius * angle.cos(), circumradius * angle.sin(), z)
    };
    let bottom = (0..n).map(|k| corner(k, 0.0, -height / 2.0));
    let top = (0..n).map(|k| corner(k, top_turn, height / 2.0));
    bottom.chain(top).collect()
}

/// The bottom n-gon 0..n (reversed, so it faces down) and the top n-gon n..2n.
fn caps(n: u32) -> Vec<Vec<u32>> {
    vec![(0..n).rev().collect(), (n..2 * n).collect()]
}

#[cfg(test)]
mod tests {
    use super::super::checks::{assert_closed_convex, assert_uniform, face_census};
    use super::*;
    use std::collections::BTreeMap;

    /// The face census of two n-gon caps and a band of `faces` faces with `sides` sides each.
    fn caps_and_band(n: u32, sides: usize, faces: usize) -> Vec<(usize, usize)> {
        let mut census = BTreeMap::from([(n as usize, 2)]);
        *census.entry(sides).or_default() += faces;
        census.into_iter().collect()
    }

    #[test]
    fn prisms_are_uniform() {
        for n in 3..=12 {
            let mesh = prism(n).unwrap();
            let name = format!("prism({n})");
            assert_uniform(&name, &mesh);
            assert_eq!(mesh.vertices.len(), 2 * n as usize, "{name}");
            assert_eq!(
                face_census(&mesh),
                caps_and_band(n, 4, n as usize),
                "{name}"
            );
        }
    }

    #[test]
    fn antiprisms_are_uniform() {
        for n in 3..=12 {
            let mesh = antiprism(n).unwrap();
            let name = format!("antiprism({n})");
            assert_uniform(&name, &mesh);
            assert_eq!(mesh.vertices.len(), 2 * n as usize, "{name}");
            assert_eq!(
                face_census(&mesh),
                caps_and_band(n, 3, 2 * n as usize),
                "{name}"
            );
        }
    }

    #[test]
    fn largest_n_builds() {
        for mesh in [prism(MAX_SIDES), antiprism(MAX_SIDES)].map(Option::unwrap) {
            assert_eq!(mesh.vertices.len(), 2 * MAX_SIDES as usize);
            assert_eq!(mesh.faces.len() % MAX_SIDES as usize, 2);
        }
    }

    #[test]
    fn cuboid_is_a_closed_outward_box() {
        let (a, b) = (P3::new(1.0, -2.0, 0.5), P3::new(-1.0, 3.0, 4.0));
        let mesh = cuboid(a, b);
        assert_closed_convex("cuboid", &mesh);
        assert_eq!(mesh, cuboid(b, a));
        assert_eq!(face_census(&mesh), vec![(4, 6)]);
        let volume: f64 = (0..6)
            .map(|f| {
                mesh.face_vector_area(f)
                    .dot(&mesh.vertices[mesh.faces[f][0] as usize].coords)
            })
            .sum::<f64>()
            / 3.0;
        assert!((volume - 2.0 * 5.0 * 3.5).abs() < 1e-12);
    }
}
