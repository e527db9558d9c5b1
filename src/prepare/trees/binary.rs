//! From C(T) to the binary BV-tree B(T) (paper 002 section 4.3): the children of every
//! component are combined bottom-up, like a Huffman code tree, always merging the pair whose
//! merged bounding volume is smallest; below the leaf components a traditional top-down
//! split completes the tree ([`TopDown`]): the surface-area heuristic (Goldsmith and Salmon,
//! the paper's reference for top-down building), or kepler's median split (the rule the view
//! tree used per view: the axis along which the faces' centres spread most, cut at the
//! median). Either way at most [`LEAF_FACES`] faces per leaf.
//!
//! Bounding volume: the CBOX (axis-aligned box in the mesh's frame), the box Franklin's
//! database and kepler's cull use; the merge criterion is its volume (then its area, for flat
//! parts of zero volume).

use std::cmp::Ordering;
use std::collections::BinaryHeap;

use crate::geom::{Box3, P3};
use crate::scene::Mesh;

/// Most faces in a leaf of the top-down split.
pub(crate) const LEAF_FACES: usize = 4;

/// A node under construction.
#[derive(Debug, Clone)]
pub(super) enum Build {
    /// Faces, not yet split.
    Faces(Vec<u32>),
    /// Two children (arena indices).
    Pair(usize, usize),
}

/// A node under construction with its box; `component` marks nodes of the upper BV-tree.
#[derive(Debug, Clone)]
pub(super) struct ArenaNode {
    pub(super) cbox: Box3,
    pub(super) build: Build,
    pub(super) component: bool,
}

/// The nodes under construction, with each face's box and centre.
pub(super) struct Arena {
    pub(super) nodes: Vec<ArenaNode>,
    face_boxes: Vec<Box3>,
    centres: Vec<P3>,
}

impl Arena {
    pub(super) fn new(mesh: &Mesh) -> Arena {
        let face_boxes: Vec<Box3> = mesh
            .faces
            .iter()
            .map(|f| Box3::from_points(f.vertices.iter().map(|&v| &mesh.vertices[v as usize])))
            .collect();
        let centres = face_boxes.iter().map(Box3::center).collect();
        Arena {
            nodes: Vec::new(),
            face_boxes,
            centres,
        }
    }

    fn boxed(&self, faces: &[u32]) -> Box3 {
        faces
            .iter()
            .fold(Box3::empty(), |b, &f| b.union(&self.face_boxes[f as usize]))
    }

    /// A leaf holding `faces` (split later).
    pub(super) fn leaf(&mut self, faces: Vec<u32>, component: bool) -> usize {
        let cbox = self.boxed(&faces);
        self.push(cbox, Build::Faces(faces), component)
    }

    fn push(&mut self, cbox: Box3, build: Build, component: bool) -> usize {
        self.nodes.push(ArenaNode {
            cbox,
            build,
            component,
        });
        self.nodes.len() - 1
    }

    fn pair(&mut self, a: usize, b: usize, component: bool) -> usize {
        let cbox = self.nodes[a].cbox.union(&self.nodes[b].cbox);
        self.push(cbox, Build::Pair(a, b), component)
    }

    /// Section 4.3's bottom-up combination of `kids` (arena nodes) into one binary subtree:
    /// repeatedly merge the pair whose merged box is smallest. Returns its root.
    pub(super) fn merge_bottom_up(&mut self, kids: &[usize]) -> usize {
        let mut alive: Vec<usize> = kids.to_vec();
        if alive.len() == 1 {
            return alive[0];
        }
        let mut live = vec![false; self.nodes.len() + kids.len()];
        for &k in kids {
            live[k] = true;
        }
        let mut heap = BinaryHeap::new();
        for i in 0..alive.len() {
            for j in i + 1..alive.len() {
                heap.push(self.candidate(alive[i], alive[j]));
            }
        }
        while let Some(c) = heap.pop() {
            if !(live[c.a] && live[c.b]) {
                continue;
            }
            live[c.a] = false;
            live[c.b] = false;
            alive.retain(|&k| k != c.a && k != c.b);
            let m = self.pair(c.a, c.b, true);
            if live.len() <= m {
                live.resize(m + 1, false);
            }
            live[m] = true;
            if alive.is_empty() {
                return m;
            }
            for &k in &alive {
                heap.push(self.candidate(k, m));
            }
            alive.push(m);
        }
        unreachable!("the heap holds a pair while two nodes are alive")
    }

    fn candidate(&self, a: usize, b: usize) -> Candidate {
        let u = self.nodes[a].cbox.union(&self.nodes[b].cbox);
        Candidate {
            volume: u.volume(),
            area: area(&u),
            a: a.min(b),
            b: a.max(b),
        }
    }

    /// The traditional top-down split of every pending leaf below `root`, by `rule`.
    pub(super) fn split_leaves(&mut self, root: usize, rule: TopDown) {
        let mut stack = vec![root];
        while let Some(n) = stack.pop() {
            match &mut self.nodes[n].build {
                Build::Pair(a, b) => stack.extend([*a, *b]),
                Build::Faces(f) if f.len() > LEAF_FACES => {
                    let faces = std::mem::take(f);
                    let (l, r) = match rule {
                        TopDown::Area => self.area_halves(faces),
                        TopDown::Median => self.median_halves(faces),
                    };
                    let (a, b) = (self.leaf(l, false), self.leaf(r, false));
                    self.nodes[n].build = Build::Pair(a, b);
                    stack.extend([a, b]);
                }
                Build::Faces(_) => {}
            }
        }
    }

    /// The split of `faces` (by their centres, along one axis, at one of [`AREA_BINS`] - 1
    /// evenly spaced planes) whose two boxes' areas, each times its face count, add up least
    /// (the surface-area heuristic of Goldsmith and Salmon); the median split when no plane
    /// separates anything.
    fn area_halves(&self, faces: Vec<u32>) -> (Vec<u32>, Vec<u32>) {
        let c = &self.centres;
        let best = (0..3)
            .filter_map(|axis| {
                self.best_plane(&faces, axis)
                    .map(|(cost, at)| (cost, axis, at))
            })
            .min_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
        let Some((_, axis, at)) = best else {
            return self.median_halves(faces);
        };
        let (l, r): (Vec<u32>, Vec<u32>) = faces.iter().partition(|&&f| c[f as usize][axis] < at);
        if l.is_empty() || r.is_empty() {
            return self.median_halves(faces);
        }
        (l, r)
    }

    /// The least cost of a plane normal to `axis` through `faces` and where it lies.
    fn best_plane(&self, faces: &[u32], axis: usize) -> Option<(f64, f64)> {
        let x = |f: u32| self.centres[f as usize][axis];
        let (lo, hi) = faces
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &f| {
                (lo.min(x(f)), hi.max(x(f)))
            });
        if hi <= lo {
            return None;
        }
        let bin = |v: f64| (((v - lo) / (hi - lo) * AREA_BINS as f64) as usize).min(AREA_BINS - 1);
        let mut boxes = [Box3::empty(); AREA_BINS];
        let mut counts = [0usize; AREA_BINS];
        for &f in faces {
            let b = bin(x(f));
            boxes[b] = boxes[b].union(&self.face_boxes[f as usize]);
            counts[b] += 1;
        }
        // Boxes and counts of every suffix of bins, then prefixes as the plane moves.
        let mut right = vec![(Box3::empty(), 0usize); AREA_BINS + 1];
        for b in (0..AREA_BINS).rev() {
            right[b] = (right[b + 1].0.union(&boxes[b]), right[b + 1].1 + counts[b]);
        }
        let mut left = (Box3::empty(), 0usize);
        let mut best: Option<(f64, f64)> = None;
        for b in 0..AREA_BINS - 1 {
            left = (left.0.union(&boxes[b]), left.1 + counts[b]);
            let r = &right[b + 1];
            if left.1 == 0 || r.1 == 0 {
                continue;
            }
            let cost = area(&left.0) * left.1 as f64 + area(&r.0) * r.1 as f64;
            if best.is_none_or(|(bc, _)| cost < bc) {
                best = Some((cost, lo + (hi - lo) * (b + 1) as f64 / AREA_BINS as f64));
            }
        }
        best
    }

    /// The median split of `faces` along the axis their centres spread most on.
    fn median_halves(&self, mut faces: Vec<u32>) -> (Vec<u32>, Vec<u32>) {
        let c = &self.centres;
        let span = |axis: usize| {
            let (lo, hi) = faces
                .iter()
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &f| {
                    let x = c[f as usize][axis];
                    (lo.min(x), hi.max(x))
                });
            hi - lo
        };
        let axis = (0..3)
            .max_by(|&a, &b| span(a).total_cmp(&span(b)).then(b.cmp(&a)))
            .unwrap_or(0);
        let mid = faces.len() / 2;
        faces.select_nth_unstable_by(mid, |&a, &b| {
            c[a as usize][axis]
                .total_cmp(&c[b as usize][axis])
                .then(a.cmp(&b))
        });
        let right = faces.split_off(mid);
        (faces, right)
    }
}

/// Candidate planes per axis of the area split, plus one.
pub(crate) const AREA_BINS: usize = 16;

/// The traditional top-down split used below the leaf components.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TopDown {
    /// At the median of the faces' centres along the axis they spread most on.
    Median,
    /// Where the two halves' box areas weighted by their face counts add up least.
    Area,
}

/// Surface area of a box (half of it: only comparisons matter).
pub(super) fn area(b: &Box3) -> f64 {
    let s = b.size();
    s[0] * s[1] + s[1] * s[2] + s[2] * s[0]
}

/// A pair that could be merged, ordered so that the heap pops the smallest merged box first.
#[derive(Debug, Clone, Copy)]
struct Candidate {
    volume: f64,
    area: f64,
    a: usize,
    b: usize,
}

impl Candidate {
    fn key(&self) -> impl Ord {
        (Total(self.volume), Total(self.area), self.a, self.b)
    }
}

/// f64 with the total order.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Total(f64);

impl Eq for Total {}

impl PartialOrd for Total {
    fn partial_cmp(&self, o: &Self) -> Option<Ordering> {
        Some(self.cmp(o))
    }
}

impl Ord for Total {
    fn cmp(&self, o: &Self) -> Ordering {
        self.0.total_cmp(&o.0)
    }
}

impl PartialEq for Candidate {
    fn eq(&self, o: &Self) -> bool {
        self.cmp(o) == Ordering::Equal
    }
}

impl Eq for Candidate {}

impl PartialOrd for Candidate {
    fn partial_cmp(&self, o: &Self) -> Option<Ordering> {
        Some(self.cmp(o))
    }
}

impl Ord for Candidate {
    /// Reversed: the smallest key is the greatest, for the max-heap.
    fn cmp(&self, o: &Self) -> Ordering {
        o.key().cmp(&self.key())
    }
}
