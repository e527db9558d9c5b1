//! Edge topology of a face set: closedness and consistent orientation.

use std::collections::HashMap;

use super::object::Face;

/// True when every undirected edge is used by exactly two faces, once in each direction:
/// the faces bound a closed, consistently oriented solid.
pub fn is_closed_oriented(faces: &[Face]) -> bool {
    if faces.is_empty() {
        return false;
    }
    // Count directed edges; a closed oriented surface has each directed edge once and its reverse once.
    let mut directed: HashMap<(u32, u32), u32> = HashMap::with_capacity(faces.len() * 4);
    for f in faces {
        let n = f.vertices.len();
        for i in 0..n {
            let e = (f.vertices[i], f.vertices[(i + 1) % n]);
            *directed.entry(e).or_insert(0) += 1;
        }
    }
    directed
        .iter()
        .all(|(&(a, b), &c)| c == 1 && directed.get(&(b, a)) == Some(&1))
}

/// How the edges of a face set join up.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Topology {
    /// Every edge used by exactly two faces, once in each direction.
    Closed,
    /// Some edge used by one face only (and none used inconsistently).
    Open,
    /// Some edge used twice in one direction, or by more than two faces.
    Inconsistent,
}

/// Classifies the edges of `faces` (an empty set is open).
pub fn edge_topology(faces: &[Face]) -> Topology {
    if faces.is_empty() {
        return Topology::Open;
    }
    let mut directed: HashMap<(u32, u32), u32> = HashMap::with_capacity(faces.len() * 4);
    for f in faces {
        let n = f.vertices.len();
        for i in 0..n {
            *directed
                .entry((f.vertices[i], f.vertices[(i + 1) % n]))
                .or_insert(0) += 1;
        }
    }
    let mut open = false;
    for (&(a, b), &c) in &directed {
        match (c, directed.get(&(b, a)).copied().unwrap_or(0)) {
            (1, 1) => {}
            (1, 0) => open = true,
            _ => return Topology::Inconsistent,
        }
    }
    if open {
        Topology::Open
    } else {
        Topology::Closed
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tet(flip_one: bool) -> Vec<Face> {
        let mut f = vec![vec![0, 2, 1], vec![0, 1, 3], vec![1, 2, 3], vec![2, 0, 3]];
        if flip_one {
            f[0].reverse();
        }
        f.into_iter().map(Face::new).collect()
    }

    #[test]
    fn tetrahedron_closed_and_flipped_not() {
        assert!(is_closed_oriented(&tet(false)));
        assert!(!is_closed_oriented(&tet(true)));
        assert!(!is_closed_oriented(&tet(false)[..3]));
        assert_eq!(edge_topology(&tet(false)), Topology::Closed);
        assert_eq!(edge_topology(&tet(true)), Topology::Inconsistent);
        assert_eq!(edge_topology(&tet(false)[..3]), Topology::Open);
        assert_eq!(edge_topology(&[]), Topology::Open);
    }
}
