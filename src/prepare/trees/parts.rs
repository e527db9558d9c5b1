//! Parts of a simplified model (paper 002 section 4.2, steps A1-A4, B1-B2, C1), and the
//! components they induce on the original faces: t1 and t2 share a component exactly when
//! F_m(t1) and F_m(t2) lie in one part.
//!
//! S3, S2 and S1 are the triangles, edges and points of the simplified model m (here: the
//! images F_m(t) of the faces given, so that a component is divided by looking only at the
//! elements its own faces simplify to).
//! - A1: triangles reaching each other across shared sides form a part P.
//! - A2: edges of S2 that are a side of a triangle in P join P.
//! - A3: stray edges (a side of no triangle) with both endpoints on triangles of P join P.
//! - A4: points on triangles of P and of no other part join P.
//! - B1: every remaining stray edge is a part; B2: a point that is an end of that edge and of
//!   no other edge or triangle joins it.
//! - C1: every remaining point is a part.

use crate::geom::key_hash::KeyMap;

use super::fcs::{element, sides, Element};
use crate::scene::Mesh;

/// Disjoint sets over 0..n with path halving (the lower root wins, so numbering is stable).
struct Sets(Vec<u32>);

impl Sets {
    fn find(&mut self, mut a: u32) -> u32 {
        while self.0[a as usize] != a {
            let up = self.0[self.0[a as usize] as usize];
            self.0[a as usize] = up;
            a = up;
        }
        a
    }

    fn join(&mut self, a: u32, b: u32) {
        let (a, b) = (self.find(a), self.find(b));
        let (lo, hi) = (a.min(b), a.max(b));
        self.0[hi as usize] = lo;
    }
}

/// The elements the faces simplify to, each once, in order of first appearance.
struct Elements {
    list: Vec<Element>,
    /// Sides of each triangle element (empty for edges and points).
    sides: Vec<Vec<(u32, u32)>>,
    /// Element of each face given.
    of_face: Vec<u32>,
}

fn elements(faces: &[u32], mesh: &Mesh, rep: &[u32]) -> Elements {
    let mut index: KeyMap<Element, u32> = KeyMap::default();
    let mut e = Elements {
        list: Vec::new(),
        sides: Vec::new(),
        of_face: Vec::with_capacity(faces.len()),
    };
    for &f in faces {
        let verts = &mesh.faces[f as usize].vertices;
        let el = element(verts, rep);
        let k = *index.entry(el.clone()).or_insert_with(|| {
            e.list.push(el.clone());
            e.sides.push(Vec::new());
            e.list.len() as u32 - 1
        });
        if matches!(el, Element::Triangle(_)) {
            let s = &mut e.sides[k as usize];
            s.extend(sides(verts, rep));
            s.sort_unstable();
            s.dedup();
        }
        e.of_face.push(k);
    }
    e
}

/// The part of every face in `faces` (parts numbered 0.. in order of their first face).
pub(crate) fn face_parts(faces: &[u32], mesh: &Mesh, rep: &[u32]) -> Vec<u32> {
    let el = elements(faces, mesh, rep);
    let part = element_parts(&el);
    // Renumber by first appearance in face order.
    let mut renum: KeyMap<u32, u32> = KeyMap::default();
    el.of_face
        .iter()
        .map(|&e| {
            let n = renum.len() as u32;
            *renum.entry(part[e as usize]).or_insert(n)
        })
        .collect()
}

/// Steps A1-C1: the part of every element.
fn element_parts(el: &Elements) -> Vec<u32> {
    let n = el.list.len();
    const NONE: u32 = u32::MAX;
    let mut part = vec![NONE; n];
    // A1: triangles sharing a side.
    let mut sets = Sets((0..n as u32).collect());
    let mut by_side: KeyMap<(u32, u32), u32> = KeyMap::default();
    for (k, s) in el.sides.iter().enumerate() {
        for side in s {
            match by_side.get(side) {
                Some(&t) => sets.join(t, k as u32),
                None => {
                    by_side.insert(*side, k as u32);
                }
            }
        }
    }
    let mut parts = 0u32;
    let mut root_part: KeyMap<u32, u32> = KeyMap::default();
    // The parts of the triangles incident to each vertex (few, kept sorted).
    let mut vertex_parts: KeyMap<u32, Vec<u32>> = KeyMap::default();
    for (k, e) in el.list.iter().enumerate() {
        if let Element::Triangle(vs) = e {
            let r = sets.find(k as u32);
            let p = *root_part.entry(r).or_insert_with(|| {
                parts += 1;
                parts - 1
            });
            part[k] = p;
            for v in vs {
                let ps = vertex_parts.entry(*v).or_default();
                if let Err(i) = ps.binary_search(&p) {
                    ps.insert(i, p);
                }
            }
        }
    }
    // Edges of S incident to each vertex (for B2).
    let mut vertex_edges: KeyMap<u32, u32> = KeyMap::default();
    for e in &el.list {
        if let Element::Edge(a, b) = e {
            *vertex_edges.entry(*a).or_default() += 1;
            *vertex_edges.entry(*b).or_default() += 1;
        }
    }
    let parts_at = |v: &u32| vertex_parts.get(v).map_or(&[][..], Vec::as_slice);
    for (k, e) in el.list.iter().enumerate() {
        match e {
            Element::Edge(a, b) => {
                if let Some(&t) = by_side.get(&(*a, *b)) {
                    // A2: a side of a triangle.
                    part[k] = part[t as usize];
                } else if let Some(p) = parts_at(a).iter().find(|p| parts_at(b).contains(p)) {
                    // A3: a stray edge with both ends on triangles of one part.
                    part[k] = *p;
                }
            }
            Element::Point(v) => {
                // A4: a point on triangles of exactly one part.
                if let [p] = parts_at(v) {
                    part[k] = *p;
                }
            }
            Element::Triangle(_) => {}
        }
    }
    // B1, B2: remaining stray edges, each a part with its lone end points.
    let mut edge_at: KeyMap<u32, u32> = KeyMap::default();
    for (k, e) in el.list.iter().enumerate() {
        if let (Element::Edge(a, b), NONE) = (e, part[k]) {
            part[k] = parts;
            for v in [a, b] {
                if parts_at(v).is_empty() && vertex_edges.get(v) == Some(&1) {
                    edge_at.insert(*v, parts);
                }
            }
            parts += 1;
        }
    }
    // B2 for the points, then C1: every other point a part of its own.
    for (k, e) in el.list.iter().enumerate() {
        if let (Element::Point(v), NONE) = (e, part[k]) {
            part[k] = match edge_at.get(v) {
                Some(&p) => p,
                None => {
                    parts += 1;
                    parts - 1
                }
            };
        }
    }
    part
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::P3;
    use crate::scene::Face;

    /// Faces given straight as representative lists (identity clustering).
    fn mesh(faces: &[&[u32]]) -> (Mesh, Vec<u32>) {
        let n = 1 + faces
            .iter()
            .flat_map(|f| f.iter())
            .max()
            .copied()
            .unwrap_or(0);
        let m = Mesh {
            vertices: (0..n).map(|i| P3::new(i as f64, 0., 0.)).collect(),
            faces: faces.iter().map(Face::new).collect(),
            closed: false,
            solidity: None,
            caps: Vec::new(),
            proven: None,
            pieces: None,
        };
        (m, (0..n).collect())
    }

    #[test]
    fn figure_2_parts() {
        // Paper's Figure 2 in miniature: two triangles sharing a side with an edge on one of
        // their sides (A2), a stray edge between their vertices (A3) and a point on them (A4);
        // a lone triangle sharing only a vertex with them, with a point of its own (A4); a
        // stray edge with a lone end point (B1, B2); a point where a triangle and a stray
        // edge of different parts meet (C1).
        let faces: Vec<&[u32]> = vec![
            &[0, 1, 2], // T1
            &[1, 2, 3], // T2 shares side 1-2
            &[1, 2, 1], // E1: side 1-2
            &[0, 3, 0], // E2: stray, both ends on part 1
            &[0, 0, 0], // P1 at vertex 0
            &[3, 4, 5], // T7 shares only vertex 3 with part 1
            &[5, 5, 5], // P5 on T7 only
            &[6, 7, 6], // E4: stray edge
            &[7, 7, 7], // P6: end of E4 only
            &[3, 3, 3], // P4: on triangles of two parts
        ];
        let (m, rep) = mesh(&faces);
        let all: Vec<u32> = (0..faces.len() as u32).collect();
        let p = face_parts(&all, &m, &rep);
        assert_eq!(p, vec![0, 0, 0, 0, 0, 1, 1, 2, 2, 3]);
    }

    #[test]
    fn triangles_meeting_at_a_vertex_are_apart_and_subsets_are_split_alone() {
        let (m, rep) = mesh(&[&[0, 1, 2], &[2, 3, 4], &[4, 5, 6], &[6, 7, 0]]);
        assert_eq!(face_parts(&[0, 1, 2, 3], &m, &rep), vec![0, 1, 2, 3]);
        // A subset is divided by its own elements only.
        assert_eq!(face_parts(&[3, 1], &m, &rep), vec![0, 1]);
    }
}
