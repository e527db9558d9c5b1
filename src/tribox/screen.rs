//! The tribox idea in screen space: an 8-sided bound over the directions x, y, x+y, x−y (an
//! octagon), tighter than a rectangle, with an 8-comparison overlap test; and a measurement
//! of what it would prune in VISFAC2's "does not hide" test.

use crate::geom::poly2::Pt2;
use crate::view::tree::NodeKind;
use crate::view::{Facing, View};
use crate::visibility::occlusion::{rects_overlap, separated_convex};

/// Bounds on x, y, x+y and x−y of a set of screen points. Empty when `lo > hi`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Octagon {
    /// Least x, y, x+y, x−y.
    pub lo: [f64; 4],
    /// Greatest x, y, x+y, x−y.
    pub hi: [f64; 4],
}

impl Default for Octagon {
    fn default() -> Self {
        Octagon::empty()
    }
}

impl Octagon {
    /// The empty octagon (identity of [`Octagon::merge`]).
    pub fn empty() -> Self {
        Octagon {
            lo: [f64::INFINITY; 4],
            hi: [f64::NEG_INFINITY; 4],
        }
    }

    /// The octagon of points.
    pub fn from_points<'a>(pts: impl IntoIterator<Item = &'a Pt2>) -> Self {
        let mut o = Octagon::empty();
        for p in pts {
            o.add(p[0], p[1]);
        }
        o
    }

    /// Grows the octagon to hold (x, y).
    pub fn add(&mut self, x: f64, y: f64) {
        let v = [x, y, x + y, x - y];
        for (k, v) in v.into_iter().enumerate() {
            self.lo[k] = self.lo[k].min(v);
            self.hi[k] = self.hi[k].max(v);
        }
    }

    /// The octagon of the union.
    pub fn merge(&self, o: &Octagon) -> Octagon {
        Octagon {
            lo: std::array::from_fn(|k| self.lo[k].min(o.lo[k])),
            hi: std::array::from_fn(|k| self.hi[k].max(o.hi[k])),
        }
    }

    /// False when one of the four directions separates the two (at most 8 comparisons);
    /// the first two are the rectangle test.
    pub fn overlaps(&self, o: &Octagon) -> bool {
        (0..4).all(|k| self.lo[k] <= o.hi[k] && o.lo[k] <= self.hi[k])
    }
}

/// What rectangles and octagons prune in VISFAC2's walk over the view tree, for every face
/// that can show something as the target (walks run in full: INBOX and covering-face early
/// exits are left out, so both tests see the same candidates).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct PruneCounts {
    /// Target faces walked.
    pub targets: u64,
    /// Nodes entered with rectangles (and depth) only.
    pub nodes_rect: u64,
    /// Nodes entered when octagons are tested too.
    pub nodes_octagon: u64,
    /// Candidate occluder faces passing the rectangle and depth tests.
    pub faces_rect: u64,
    /// Of those, faces whose octagon does not overlap the target's.
    pub faces_octagon_apart: u64,
    /// Of those, faces the exact convex separation test (run next today) would not reject:
    /// what the octagon prunes that nothing else does before the occlusion region.
    pub faces_octagon_only: u64,
    /// Faces passing rectangle and depth that the exact convex separation test rejects.
    pub faces_separated: u64,
}

/// Counts what octagons would add to the rectangle tests of VISFAC2 in this view.
pub fn prune_counts(view: &View) -> PruneCounts {
    let sf = &view.screen;
    let tree = &view.tree;
    let face_oct: Vec<Octagon> = (0..sf.faces.len())
        .map(|g| {
            let mut o = Octagon::empty();
            for p in sf.pts(g) {
                o.add(p[0], p[1]);
            }
            o
        })
        .collect();
    // Nodes are stored children first.
    let mut node_oct = vec![Octagon::empty(); tree.nodes.len()];
    for (n, node) in tree.nodes.iter().enumerate() {
        node_oct[n] = match &node.kind {
            NodeKind::Inner(r) => tree.children[r.start as usize..r.end as usize]
                .iter()
                .fold(Octagon::empty(), |o, &c| o.merge(&node_oct[c as usize])),
            NodeKind::Leaf(r) => tree.faces[r.start as usize..r.end as usize]
                .iter()
                .fold(Octagon::empty(), |o, &g| o.merge(&face_oct[g as usize])),
        };
    }
    let mut c = PruneCounts::default();
    let mut stack = Vec::new();
    for (f, t) in sf.faces.iter().enumerate() {
        if !matches!(t.facing, Facing::Front | Facing::Back) || t.culled {
            continue;
        }
        c.targets += 1;
        let ring: Vec<Pt2> = sf.ring_ccw(f);
        for use_oct in [false, true] {
            stack.clear();
            stack.push(tree.root());
            while let Some(n) = stack.pop() {
                let node = &tree.nodes[n as usize];
                if !rects_overlap(&node.rect, &t.rect) || node.zmax < t.zmin {
                    continue;
                }
                if use_oct && !node_oct[n as usize].overlaps(&face_oct[f]) {
                    continue;
                }
                if use_oct {
                    c.nodes_octagon += 1;
                } else {
                    c.nodes_rect += 1;
                }
                match &node.kind {
                    NodeKind::Inner(r) => {
                        stack.extend(&tree.children[r.start as usize..r.end as usize])
                    }
                    NodeKind::Leaf(r) if !use_oct => {
                        for &g in &tree.faces[r.start as usize..r.end as usize] {
                            let sg = &sf.faces[g as usize];
                            if sg.id == t.id
                                || !rects_overlap(&sg.rect, &t.rect)
                                || sg.zmax < t.zmin
                            {
                                continue;
                            }
                            c.faces_rect += 1;
                            let separated = sg.convex && t.convex && {
                                let mut r2: Vec<Pt2> =
                                    sf.pts(g as usize).iter().map(|p| [p[0], p[1]]).collect();
                                if sg.facing == Facing::Back {
                                    r2.reverse();
                                }
                                separated_convex(&r2, &ring)
                            };
                            c.faces_separated += u64::from(separated);
                            if !face_oct[g as usize].overlaps(&face_oct[f]) {
                                c.faces_octagon_apart += 1;
                                c.faces_octagon_only += u64::from(!separated);
                            }
                        }
                    }
                    NodeKind::Leaf(_) => {}
                }
            }
        }
    }
    c
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn diagonal_neighbours_overlap_as_rectangles_not_octagons() {
        // Two thin diagonal strips side by side along x = y.
        let a = Octagon::from_points([[0.0, 0.0], [1.0, 1.0], [0.1, 0.0]].iter());
        let b = Octagon::from_points([[0.5, 0.2], [1.5, 1.2], [1.4, 1.2]].iter());
        let rects = (0..2).all(|k| a.lo[k] <= b.hi[k] && b.lo[k] <= a.hi[k]);
        assert!(rects);
        assert!(!a.overlaps(&b));
        assert!(a.overlaps(&a.merge(&b)));
        assert!(!Octagon::empty().overlaps(&a));
    }
}
