//! Test-only checks that a mesh is a closed, outward-oriented convex polyhedron, and uniform.

use std::collections::{BTreeMap, HashMap};

use super::Build;
use crate::geom::{PolyMesh, P3, V3};

/// Tolerance of the metric checks, relative to the edge length or radius.
const TOLERANCE: f64 = 1e-12;

/// Asserts everything a uniform solid of this module promises: closed, consistently and outwardly
/// oriented, planar convex faces, unit edges, all vertices on one sphere about the origin, no
/// repeated vertices.
pub(super) fn assert_uniform(name: &str, mesh: &PolyMesh) {
    assert_closed_convex(name, mesh);
    for (a, b) in edges(mesh) {
        let length = (mesh.vertices[a as usize] - mesh.vertices[b as usize]).norm();
        assert!(
            (length - 1.0).abs() <= TOLERANCE,
            "{name}: edge {a}-{b} has length {length}"
        );
    }
    let radius = mesh.vertices[0].coords.norm();
    assert!(
        centroid(&mesh.vertices).coords.norm() <= TOLERANCE * radius,
        "{name}: off-centre"
    );
    for (i, p) in mesh.vertices.iter().enumerate() {
        let r = p.coords.norm();
        assert!(
            (r - radius).abs() <= TOLERANCE * radius,
            "{name}: vertex {i} at radius {r}"
        );
        for q in &mesh.vertices[..i] {
            assert!((p - q).norm() > 0.5, "{name}: vertex {i} repeated");
        }
    }
}

/// Asserts a closed manifold of Euler characteristic 2 whose faces are planar, convex and
/// oriented outward (seen from the vertex centroid), with positive volume.
pub(super) fn assert_closed_convex(name: &str, mesh: &PolyMesh) {
    let (v, e, f) = (mesh.vertices.len(), edges(mesh).len(), mesh.faces.len());
    assert_eq!(v + f, e + 2, "{name}: V - E + F != 2");
    assert_edges_paired(name, mesh);
    let centre = centroid(&mesh.vertices);
    let mut volume = 0.0;
    for (i, face) in mesh.faces.iter().enumerate() {
        let corners: Vec<P3> = mesh.face_points(i).copied().collect();
        let area = mesh.face_vector_area(i);
        let middle = centroid(&corners);
        assert!(
            area.dot(&(middle - centre)) > 0.0,
            "{name}: face {i} {face:?} faces inward"
        );
        assert_planar_convex(name, &corners, &area.normalize());
        volume += area.dot(&(middle - centre)) / 3.0;
    }
    assert!(volume > 0.0, "{name}: volume {volume}");
}

/// Asserts every directed edge of a face boundary appears once, and its reverse once.
fn assert_edges_paired(name: &str, mesh: &PolyMesh) {
    let mut directed: HashMap<(u32, u32), usize> = HashMap::new();
    for face in &mesh.faces {
        assert!(face.len() >= 3, "{name}: face {face:?} too small");
        for (k, &a) in face.iter().enumerate() {
            *directed.entry((a, face[(k + 1) % face.len()])).or_default() += 1;
        }
    }
    for (&(a, b), &count) in &directed {
        assert_eq!(count, 1, "{name}: edge {a}->{b} used {count} times");
        assert_eq!(
            directed.get(&(b, a)),
            Some(&1),
            "{name}: edge {a}->{b} unpaired"
        );
    }
}

/// Asserts the polygon lies within the tolerance of its plane and turns left at every corner
/// about `normal`.
fn assert_planar_convex(name: &str, corners: &[P3], normal: &V3) {
    let middle = centroid(corners);
    let scale = corners.iter().map(|p| p.coords.norm()).fold(1.0, f64::max);
    let n = corners.len();
    for (k, p) in corners.iter().enumerate() {
        let height = normal.dot(&(p - middle));
        assert!(
            height.abs() <= TOLERANCE * scale,
            "{name}: corner off its face's plane by {height}"
        );
        let (q, r) = (corners[(k + 1) % n], corners[(k + 2) % n]);
        assert!(
            (q - p).cross(&(r - q)).dot(normal) > 0.0,
            "{name}: face not convex"
        );
    }
}

/// The undirected edges of the face boundaries, each as (smaller, larger) vertex index.
fn edges(mesh: &PolyMesh) -> Vec<(u32, u32)> {
    let mut edges: Vec<(u32, u32)> = mesh
        .faces
        .iter()
        .flat_map(|f| {
            f.iter()
                .zip(f.iter().cycle().skip(1))
                .map(|(&a, &b)| (a.min(b), a.max(b)))
        })
        .collect();
    edges.sort_unstable();
    edges.dedup();
    edges
}

/// A known solid: its name, vertex count, and face count by number of sides (increasing).
pub(super) type Known = (&'static str, usize, &'static [(usize, usize)]);

/// Asserts each named solid has the vertex and face counts of the same row of `table`.
pub(super) fn assert_counts(solids: &[(&str, Build)], table: &[Known]) {
    assert_eq!(solids.len(), table.len());
    for (&(name, build), &(known, vertices, faces)) in solids.iter().zip(table) {
        assert_eq!(name, known);
        let mesh = build();
        assert_eq!(mesh.vertices.len(), vertices, "{name}: V");
        assert_eq!(face_census(&mesh), faces, "{name}: faces by sides");
    }
}

/// The number of faces with each number of sides, by increasing sides.
pub(super) fn face_census(mesh: &PolyMesh) -> Vec<(usize, usize)> {
    let mut census = BTreeMap::new();
    for face in &mesh.faces {
        *census.entry(face.len()).or_default() += 1;
    }
    census.into_iter().collect()
}

/// The mean of the points.
fn centroid(points: &[P3]) -> P3 {
    let sum: V3 = points.iter().map(|p| p.coords).sum();
    P3::from(sum / points.len() as f64)
}
