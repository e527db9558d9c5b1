//! Floating-cell simplification (FCS; Low and Tan 1997, paper 002 section 4.1): vertices are
//! graded by importance, a cell of the given width floats to the most important vertex not
//! yet clustered, and every unclustered vertex within the cell joins that vertex's cluster.
//!
//! Grade of a vertex: cos(θ/2), θ the largest angle between two of its incident edges (a
//! flat or gently curved vertex has θ near 180° and grade near 0; a tip or a sharp corner
//! grades near 1). Ties go to the lower vertex index, so the result is deterministic. The
//! cell is the ball of diameter `width` around its centre vertex, and the representative of
//! a cluster is that centre vertex (an original vertex: no averaging), which keeps the
//! simplified models of different widths consistent with each other (section 5).

use crate::geom::key_hash::KeyMap;

use crate::geom::P3;
use crate::scene::Mesh;

/// The grade of every vertex, cos(θ/2) with θ the largest angle between two incident edges
/// (1 for a vertex with fewer than two distinct incident edges).
pub(crate) fn grades(mesh: &Mesh) -> Vec<f64> {
    let mut nbrs: Vec<Vec<u32>> = vec![Vec::new(); mesh.vertices.len()];
    for f in &mesh.faces {
        let v = &f.vertices;
        for i in 0..v.len() {
            let (a, b) = (v[i], v[(i + 1) % v.len()]);
            nbrs[a as usize].push(b);
            nbrs[b as usize].push(a);
        }
    }
    nbrs.iter_mut()
        .enumerate()
        .map(|(k, n)| {
            n.sort_unstable();
            n.dedup();
            let p = mesh.vertices[k];
            let dirs: Vec<_> = n
                .iter()
                .filter_map(|&j| (mesh.vertices[j as usize] - p).try_normalize(0.0))
                .collect();
            if dirs.len() < 2 {
                return 1.0;
            }
            // The largest angle has the least cosine.
            let mut least = 1.0f64;
            for i in 0..dirs.len() {
                for j in i + 1..dirs.len() {
                    least = least.min(dirs[i].dot(&dirs[j]));
                }
            }
            let theta = least.clamp(-1.0, 1.0).acos();
            (0.5 * theta).cos()
        })
        .collect()
}

/// The vertex order of the floating cells: decreasing grade, then increasing index.
pub(crate) fn cell_order(grades: &[f64]) -> Vec<u32> {
    let mut order: Vec<u32> = (0..grades.len() as u32).collect();
    order.sort_by(|&a, &b| {
        grades[b as usize]
            .total_cmp(&grades[a as usize])
            .then(a.cmp(&b))
    });
    order
}

/// FCS of the vertices with cells of diameter `width`, visiting centres in `order`: the
/// representative (cluster centre) of every vertex.
pub(crate) fn cluster(vertices: &[P3], order: &[u32], width: f64) -> Vec<u32> {
    let n = vertices.len();
    let mut rep = vec![u32::MAX; n];
    if !(width > 0.0 && width.is_finite()) {
        return (0..n as u32).collect();
    }
    let key = |p: &P3| {
        [p.x, p.y, p.z].map(|c| (c / width).floor().clamp(i64::MIN as f64, i64::MAX as f64) as i64)
    };
    let mut grid: KeyMap<[i64; 3], Vec<u32>> = KeyMap::default();
    for (k, p) in vertices.iter().enumerate() {
        grid.entry(key(p)).or_default().push(k as u32);
    }
    let r2 = 0.25 * width * width;
    for &c in order {
        if rep[c as usize] != u32::MAX {
            continue;
        }
        let p = vertices[c as usize];
        let g = key(&p);
        for dx in -1..=1 {
            for dy in -1..=1 {
                for dz in -1..=1 {
                    let Some(cell) = grid.get(&[g[0] + dx, g[1] + dy, g[2] + dz]) else {
                        continue;
                    };
                    for &v in cell {
                        if rep[v as usize] == u32::MAX
                            && (vertices[v as usize] - p).norm_squared() <= r2
                        {
                            rep[v as usize] = c;
                        }
                    }
                }
            }
        }
        rep[c as usize] = c;
    }
    rep
}

/// What a face simplifies to: F_m(t), the element of the simplified model m it maps to.
#[derive(Debug, Clone, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub(crate) enum Element {
    /// A point (the face collapsed to one representative).
    Point(u32),
    /// An edge (two representatives, the lower first).
    Edge(u32, u32),
    /// A triangle (or polygon) of three or more representatives, sorted.
    Triangle(Vec<u32>),
}

/// F_m(t) for the face with vertices `face`: its representatives with repeats that follow
/// each other around the ring removed; three or more left make a triangle.
pub(crate) fn element(face: &[u32], rep: &[u32]) -> Element {
    let mut ring: Vec<u32> = face.iter().map(|&v| rep[v as usize]).collect();
    ring.dedup();
    while ring.len() > 1 && ring.first() == ring.last() {
        ring.pop();
    }
    let mut distinct = ring.clone();
    distinct.sort_unstable();
    distinct.dedup();
    match distinct.len() {
        1 => Element::Point(distinct[0]),
        2 => Element::Edge(distinct[0], distinct[1]),
        _ => Element::Triangle(distinct),
    }
}

/// The sides of a triangle element of the face `face`: consecutive distinct representatives
/// around its ring, each pair with the lower first.
pub(crate) fn sides(face: &[u32], rep: &[u32]) -> Vec<(u32, u32)> {
    let mut ring: Vec<u32> = face.iter().map(|&v| rep[v as usize]).collect();
    ring.dedup();
    while ring.len() > 1 && ring.first() == ring.last() {
        ring.pop();
    }
    (0..ring.len())
        .map(|i| {
            let (a, b) = (ring[i], ring[(i + 1) % ring.len()]);
            (a.min(b), a.max(b))
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::Face;

    fn strip(n: usize) -> Mesh {
        // A strip of 2n triangles along x, unit squares, at z = 0.
        let mut vertices = Vec::new();
        for i in 0..=n {
            vertices.push(P3::new(i as f64, 0., 0.));
            vertices.push(P3::new(i as f64, 1., 0.));
        }
        let mut faces = Vec::new();
        for i in 0..n as u32 {
            let (a, b, c, d) = (2 * i, 2 * i + 2, 2 * i + 3, 2 * i + 1);
            faces.push(Face::new(vec![a, b, c]));
            faces.push(Face::new(vec![a, c, d]));
        }
        Mesh {
            vertices,
            faces,
            closed: false,
            solidity: None,
            caps: Vec::new(),
            proven: None,
            pieces: None,
        }
    }

    #[test]
    fn grades_tell_corners_from_flat_vertices() {
        let m = strip(3);
        let g = grades(&m);
        // An inner vertex of the strip has a straight angle (cos 90° = 0); the corner at
        // (0, 0) has neighbours at 90° and 45° from each other: its largest angle is 90°.
        assert!(g[2].abs() < 1e-12, "{}", g[2]);
        assert!((g[0] - (std::f64::consts::FRAC_PI_4).cos()).abs() < 1e-12);
    }

    #[test]
    fn cells_take_vertices_within_half_the_width() {
        let m = strip(3);
        let order = cell_order(&grades(&m));
        // Width 0: every vertex is its own cluster.
        let r0 = cluster(&m.vertices, &order, 0.0);
        assert_eq!(r0, (0..8).collect::<Vec<u32>>());
        // Width 2.1: a ball of radius 1.05 around each corner first.
        let r = cluster(&m.vertices, &order, 2.1);
        assert!(r.iter().enumerate().all(|(v, &c)| {
            (m.vertices[v] - m.vertices[c as usize]).norm() <= 1.05 && r[c as usize] == c
        }));
        // The first centre is the most important vertex: a corner (index 0 by the tie rule).
        assert_eq!(order[0], 0);
        assert_eq!(r[1], 0);
        assert_eq!(r[2], 0);
    }

    #[test]
    fn faces_map_to_points_edges_and_triangles() {
        let rep = [0, 0, 2, 3, 2];
        assert_eq!(element(&[0, 1, 0], &rep), Element::Point(0));
        assert_eq!(element(&[0, 1, 2], &rep), Element::Edge(0, 2));
        assert_eq!(element(&[4, 3, 0], &rep), Element::Triangle(vec![0, 2, 3]));
        assert_eq!(
            element(&[0, 2, 1, 3], &rep),
            Element::Triangle(vec![0, 2, 3])
        );
        assert_eq!(sides(&[4, 3, 1], &rep), vec![(2, 3), (0, 3), (0, 2)]);
    }
}
