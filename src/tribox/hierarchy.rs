//! Hierarchical triboxes (section 4): a solid split recursively by planes normal to the nine
//! directions into cells, each bounded by its own tribox, stored as a binary tree; a level
//! of detail is the union of the triboxes at a cut of the tree.
//!
//! - Split planes bisect a slab of the cell's tribox. All nine bisectors are candidates,
//!   thickest slab first; the greedy criterion keeps the one whose two triboxes have the
//!   least total area (ties: the thicker slab).
//! - Stop rule: no candidate reduces the area by at least `min_gain` of the parent's, or
//!   the depth limit is reached.
//! - Cells are computed exactly, incrementally from the parent: the parent cell's polygons
//!   (the solid's faces already clipped) are clipped by the split plane. That gives the
//!   paper's vertex categories (a) vertices of S in C, (b) edges of S across C's planes and
//!   (c) edges of C across faces of S. Category (d), vertices of C inside S, comes from the
//!   boundary evaluation of C (bounded by the parent's tribox) with each vertex that could
//!   enlarge the tribox classified by the generalized winding number (closed solids only).
//! - Error of a node: the largest distance to the solid over samples of its tribox's boundary
//!   (vertices and a grid on every face; points inside a closed solid, judged by the nearest
//!   triangle's side, are at distance 0): a sampled one-sided Hausdorff distance from the
//!   tribox to the solid (the other direction is 0, the triboxes of a cut hold the solid).
//!   A cut's error is its nodes' largest. Sampled, so an estimate, not a bound; the true
//!   value over the union of a cut's triboxes can only shrink down the tree, the sampled one
//!   may wobble.
//! - The area criterion counts the boundary of the union of the two children's triboxes: the
//!   sum of their areas less twice the overlap of their faces on the split plane. Summing
//!   the two areas alone (caps included) never pays for a convex-ish shape: a cow or a bunny
//!   would never be split.

use crate::geom::triangle::closest_on_triangle;
use crate::geom::{newell, Box3, PolyMesh, P3};
use crate::scene::triangulate::ear_clip;
use crate::scene::Mesh;

use super::bounds::{direction, project, Tribox};

/// Parameters of the subdivision.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HierarchyOptions {
    /// Deepest level (the root is level 0).
    pub max_depth: usize,
    /// Least relative area reduction a split must bring (the paper's "sufficient proportion").
    pub min_gain: f64,
}

impl Default for HierarchyOptions {
    fn default() -> Self {
        HierarchyOptions {
            max_depth: 6,
            min_gain: 0.02,
        }
    }
}

/// A split plane: direction `k` at value `at`; the first child is `p·d_k ≤ at`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Split {
    /// Direction index (0..9, the paper's order).
    pub k: usize,
    /// Plane offset.
    pub at: f64,
}

/// A node of the tree: one cell of the solid and its tribox.
#[derive(Debug, Clone)]
pub(crate) struct Node {
    /// The tribox of the cell.
    pub tribox: Tribox,
    /// Level in the tree (root 0).
    pub depth: usize,
    /// The split and the two children (indices into [`Hierarchy::nodes`]), if split.
    pub children: Option<(Split, [usize; 2])>,
    /// Sampled largest distance from the tribox's boundary to the solid.
    pub error: f64,
}

/// The binary tree of triboxes of one solid.
#[derive(Debug, Clone)]
pub(crate) struct Hierarchy {
    /// Nodes; the root is node 0.
    pub nodes: Vec<Node>,
}

/// What every level of the build shares.
struct Build<'a> {
    /// The solid, when closed (for category (d)).
    solid: Option<&'a Mesh>,
    /// The whole surface, for errors.
    surface: &'a SurfaceIndex,
    opts: &'a HierarchyOptions,
}

/// A cell while building: its clipped polygons and points of category (d).
struct Cell {
    polygons: Vec<Vec<P3>>,
    inner: Vec<P3>,
}

impl Cell {
    fn tribox(&self) -> Tribox {
        let mut t = Tribox::from_points(self.polygons.iter().flatten());
        for p in &self.inner {
            t.add_point(p);
        }
        t
    }
}

impl Hierarchy {
    /// Builds the hierarchy of a mesh (its vertices in the frame the triboxes are wanted in).
    pub(crate) fn build(mesh: &Mesh, opts: &HierarchyOptions) -> Hierarchy {
        let polygons: Vec<Vec<P3>> = mesh
            .faces
            .iter()
            .map(|f| {
                f.vertices
                    .iter()
                    .map(|&v| mesh.vertices[v as usize])
                    .collect()
            })
            .collect();
        let surface = SurfaceIndex::new(&polygons);
        let root = Cell {
            polygons,
            inner: Vec::new(),
        };
        let mut h = Hierarchy { nodes: Vec::new() };
        let b = Build {
            solid: mesh.closed.then_some(mesh),
            surface: &surface,
            opts,
        };
        h.grow(root, 0, &b);
        h
    }

    /// Adds the node of `cell` and, recursively, its children; returns its index.
    fn grow(&mut self, cell: Cell, depth: usize, b: &Build) -> usize {
        let (solid, o) = (b.solid, b.opts);
        let tribox = cell.tribox();
        let id = self.nodes.len();
        self.nodes.push(Node {
            tribox,
            depth,
            children: None,
            error: if cell.polygons.is_empty() {
                0.0
            } else {
                b.surface.error(&tribox, b.solid.is_some())
            },
        });
        if depth >= o.max_depth || tribox.is_empty() {
            return id;
        }
        let Some(split) = choose_split(&cell, &tribox, o.min_gain) else {
            return id;
        };
        let (mut lo, mut hi) = split_cell(&cell, split);
        drop(cell);
        if let Some(m) = solid {
            lo.inner
                .extend(inner_vertices(&lo, &tribox, split, true, m));
            hi.inner
                .extend(inner_vertices(&hi, &tribox, split, false, m));
        }
        let l = self.grow(lo, depth + 1, b);
        let h = self.grow(hi, depth + 1, b);
        self.nodes[id].children = Some((split, [l, h]));
        id
    }

    /// The cut at `depth`: nodes at that level, and leaves above it, in tree order.
    pub(crate) fn cut(&self, depth: usize) -> Vec<usize> {
        let mut out = Vec::new();
        let mut stack = vec![0];
        while let Some(n) = stack.pop() {
            match self.nodes[n].children {
                Some((_, [a, b])) if self.nodes[n].depth < depth => {
                    stack.push(b);
                    stack.push(a);
                }
                _ => out.push(n),
            }
        }
        out
    }

    /// Depth of the deepest node.
    pub(crate) fn depth(&self) -> usize {
        self.nodes.iter().map(|n| n.depth).max().unwrap_or(0)
    }

    /// The error of a cut: the largest error of its nodes.
    pub(crate) fn cut_error(&self, cut: &[usize]) -> f64 {
        cut.iter().map(|&n| self.nodes[n].error).fold(0.0, f64::max)
    }

    /// The shallowest cut whose error is at most `tol` (the deepest cut if none is).
    pub(crate) fn cut_within(&self, tol: f64) -> Vec<usize> {
        let deepest = self.depth();
        (0..=deepest)
            .map(|d| self.cut(d))
            .find(|c| self.cut_error(c) <= tol)
            .unwrap_or_else(|| self.cut(deepest))
    }

    /// The union of the cut's triboxes as one polygon mesh (each tribox simplified by `tol`
    /// and cleaned up), with the number of faces of each tribox.
    pub(crate) fn cut_mesh(&self, cut: &[usize], tol: f64) -> PolyMesh {
        let mut out = PolyMesh::default();
        for &n in cut {
            out.append(&self.nodes[n].tribox.simplified(tol).boundary().mesh());
        }
        out
    }
}

/// The best slab bisector by the greedy area criterion, if it gains enough.
fn choose_split(cell: &Cell, t: &Tribox, min_gain: f64) -> Option<Split> {
    let area = t.boundary().area();
    if area.is_nan() || area <= 0.0 {
        return None;
    }
    let mut dirs: Vec<usize> = (0..9).collect();
    dirs.sort_by(|&a, &b| t.thickness(b).total_cmp(&t.thickness(a)).then(a.cmp(&b)));
    let mut best: Option<(f64, Split)> = None;
    for k in dirs {
        if t.hi[k] <= t.lo[k] {
            continue;
        }
        let split = Split {
            k,
            at: 0.5 * (t.lo[k] + t.hi[k]),
        };
        let (a, b) = split_cell(cell, split);
        let total = union_area(&a.tribox(), &b.tribox(), split);
        if best.is_none_or(|(s, _)| total < s) {
            best = Some((total, split));
        }
    }
    best.filter(|(s, _)| *s <= (1.0 - min_gain) * area)
        .map(|(_, split)| split)
}

/// Boundary area of the union of the two children's triboxes: their areas less twice the
/// overlap of their faces on the split plane (that overlap is inside the union). The two lie
/// on either side of the plane, so they meet only there.
fn union_area(lo: &Tribox, hi: &Tribox, s: Split) -> f64 {
    if lo.is_empty() || hi.is_empty() {
        return lo.merge(hi).boundary().area();
    }
    let (bl, bh) = (lo.boundary(), hi.boundary());
    let cap = |b: &super::Boundary, f: usize| -> Vec<P3> {
        b.faces[f].iter().map(|&v| b.vertices[v as usize]).collect()
    };
    let near = |v: f64| {
        (v - s.at).abs() <= 1e-9 * (s.at.abs() + lo.hi[s.k] - hi.lo[s.k]).abs().max(1e-300)
    };
    let overlap = if near(lo.hi[s.k]) && near(hi.lo[s.k]) {
        convex_overlap(&cap(&bl, 2 * s.k + 1), &cap(&bh, 2 * s.k), s.k)
    } else {
        0.0
    };
    bl.area() + bh.area() - 2.0 * overlap
}

/// Area of the intersection of two convex polygons lying in one plane normal to direction k.
fn convex_overlap(a: &[P3], b: &[P3], k: usize) -> f64 {
    let n = direction(k);
    // Drop the first axis the normal has a component on; areas scale by |n| / |n_axis|.
    let drop = (0..3).find(|&i| n[i] != 0.0).unwrap_or(0);
    let (u, v) = ((drop + 1) % 3, (drop + 2) % 3);
    let flat = |p: &[P3]| -> Vec<[f64; 2]> {
        let mut r: Vec<[f64; 2]> = p.iter().map(|q| [q[u], q[v]]).collect();
        r.dedup();
        if crate::geom::poly2::ring_area(&r) < 0.0 {
            r.reverse();
        }
        r
    };
    let (pa, pb) = (flat(a), flat(b));
    if pa.len() < 3 || pb.len() < 3 {
        return 0.0;
    }
    let mut out = pa;
    for i in 0..pb.len() {
        let (e0, e1) = (pb[i], pb[(i + 1) % pb.len()]);
        let side =
            |p: [f64; 2]| (e1[0] - e0[0]) * (p[1] - e0[1]) - (e1[1] - e0[1]) * (p[0] - e0[0]);
        let input = std::mem::take(&mut out);
        for j in 0..input.len() {
            let (p, q) = (input[j], input[(j + 1) % input.len()]);
            let (sp, sq) = (side(p), side(q));
            if sp >= 0.0 {
                out.push(p);
            }
            if (sp >= 0.0) != (sq >= 0.0) {
                let t = sp / (sp - sq);
                out.push([p[0] + (q[0] - p[0]) * t, p[1] + (q[1] - p[1]) * t]);
            }
        }
        if out.len() < 3 {
            return 0.0;
        }
    }
    crate::geom::poly2::ring_area(&out).abs() * n.norm() / n[drop].abs()
}

/// The two cells of a split: every polygon clipped to each side (Sutherland–Hodgman against
/// the one plane; the parent's clipping is kept, so the work shrinks down the tree).
fn split_cell(cell: &Cell, s: Split) -> (Cell, Cell) {
    let mut lo = Cell {
        polygons: Vec::new(),
        inner: Vec::new(),
    };
    let mut hi = Cell {
        polygons: Vec::new(),
        inner: Vec::new(),
    };
    for poly in &cell.polygons {
        let vals: Vec<f64> = poly.iter().map(|p| project(p, s.k)).collect();
        let (mn, mx) = vals
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &v| {
                (a.min(v), b.max(v))
            });
        if mx <= s.at {
            lo.polygons.push(poly.clone());
        } else if mn >= s.at {
            hi.polygons.push(poly.clone());
        } else {
            let a = clip(poly, &vals, s.at, true);
            let b = clip(poly, &vals, s.at, false);
            if a.len() >= 3 {
                lo.polygons.push(a);
            }
            if b.len() >= 3 {
                hi.polygons.push(b);
            }
        }
    }
    for p in &cell.inner {
        let v = project(p, s.k);
        if v <= s.at {
            lo.inner.push(*p);
        }
        if v >= s.at {
            hi.inner.push(*p);
        }
    }
    (lo, hi)
}

/// The part of polygon `poly` (projections `vals`) on the side `v ≤ at` (`below`) or `v ≥ at`.
/// Crossing points are placed exactly on the plane's value in direction k by construction of
/// the interpolation parameter; coordinates carry ordinary rounding.
fn clip(poly: &[P3], vals: &[f64], at: f64, below: bool) -> Vec<P3> {
    let inside = |v: f64| if below { v <= at } else { v >= at };
    let n = poly.len();
    let mut out = Vec::with_capacity(n + 2);
    for i in 0..n {
        let j = (i + 1) % n;
        let (a, b) = (&poly[i], &poly[j]);
        let (va, vb) = (vals[i], vals[j]);
        if inside(va) {
            out.push(*a);
        }
        if inside(va) != inside(vb) && va != at && vb != at {
            let t = (at - va) / (vb - va);
            out.push(a + (b - a) * t);
        }
    }
    out
}

/// Vertices of the child cell's region C ∩ T(parent) that lie inside the solid and outside
/// the tribox of the cell's clipped surface (only those can enlarge it): category (d).
fn inner_vertices(cell: &Cell, parent: &Tribox, s: Split, below: bool, solid: &Mesh) -> Vec<P3> {
    let mut region = *parent;
    if below {
        region.hi[s.k] = region.hi[s.k].min(s.at);
    } else {
        region.lo[s.k] = region.lo[s.k].max(s.at);
    }
    let region = region.tightened();
    if region.is_empty() {
        return Vec::new();
    }
    let surface = cell.tribox();
    region
        .boundary()
        .mesh()
        .vertices
        .into_iter()
        .filter(|v| !surface.contains(v) && solid.winding_number(v).abs() > 0.5)
        .collect()
}

/// The solid's surface as triangles in a bounding-box tree, for nearest-distance queries.
struct SurfaceIndex {
    tris: Vec<[P3; 3]>,
    /// Nodes: box, and either children or a range of `tris`.
    nodes: Vec<(Box3, IndexKind)>,
}

enum IndexKind {
    Inner(usize, usize),
    Leaf(usize, usize),
}

impl SurfaceIndex {
    fn new(polygons: &[Vec<P3>]) -> SurfaceIndex {
        // Ear clipping, not fans: faces may be non-convex.
        let mut tris: Vec<[P3; 3]> = polygons
            .iter()
            .flat_map(|p| {
                let n = newell(p);
                ear_clip(p, &n)
                    .into_iter()
                    .map(|[a, b, c]| [p[a], p[b], p[c]])
                    .collect::<Vec<_>>()
            })
            .collect();
        let mut idx = SurfaceIndex {
            tris: Vec::new(),
            nodes: Vec::new(),
        };
        let n = tris.len();
        if n > 0 {
            idx.split(&mut tris, 0, n);
        }
        idx.tris = tris;
        idx
    }

    /// Builds the node over `tris[a..b]` (median split on the longest axis); returns it.
    fn split(&mut self, tris: &mut [[P3; 3]], a: usize, b: usize) -> usize {
        let bx = Box3::from_points(tris[a..b].iter().flatten());
        let id = self.nodes.len();
        if b - a <= 8 {
            self.nodes.push((bx, IndexKind::Leaf(a, b)));
            return id;
        }
        self.nodes.push((bx, IndexKind::Leaf(a, b)));
        let s = bx.size();
        let axis = (0..3).max_by(|&i, &j| s[i].total_cmp(&s[j])).unwrap_or(0);
        let m = (a + b) / 2;
        let key = |t: &[P3; 3]| t[0][axis] + t[1][axis] + t[2][axis];
        tris[a..b].select_nth_unstable_by(m - a, |x, y| key(x).total_cmp(&key(y)));
        let l = self.split(tris, a, m);
        let r = self.split(tris, m, b);
        self.nodes[id].1 = IndexKind::Inner(l, r);
        id
    }

    /// Distance from `p` to the solid: 0 inside (behind the nearest triangle, for closed
    /// solids), else to the nearest triangle.
    fn distance(&self, p: &P3, closed: bool) -> f64 {
        let mut best = f64::INFINITY;
        let mut nearest: Option<(P3, usize)> = None;
        let mut stack = vec![0usize];
        while let Some(n) = stack.pop() {
            let (bx, kind) = &self.nodes[n];
            if box_distance2(bx, p) >= best {
                continue;
            }
            match *kind {
                IndexKind::Inner(l, r) => {
                    let (dl, dr) = (
                        box_distance2(&self.nodes[l].0, p),
                        box_distance2(&self.nodes[r].0, p),
                    );
                    if dl < dr {
                        stack.extend([r, l]);
                    } else {
                        stack.extend([l, r]);
                    }
                }
                IndexKind::Leaf(a, b) => {
                    for (i, t) in self.tris[a..b].iter().enumerate() {
                        let q = closest_on_triangle(p, &t[0], &t[1], &t[2]);
                        let d = (q - p).norm_squared();
                        if d < best {
                            best = d;
                            nearest = Some((q, a + i));
                        }
                    }
                }
            }
        }
        if let (true, Some((q, i))) = (closed, nearest) {
            let t = &self.tris[i];
            if (t[1] - t[0]).cross(&(t[2] - t[0])).dot(&(p - q)) < 0.0 {
                return 0.0;
            }
        }
        best.sqrt()
    }

    /// Largest distance to the solid over samples of the tribox's boundary: its vertices
    /// and a grid of 15 points on each fan triangle of each face.
    fn error(&self, t: &Tribox, closed: bool) -> f64 {
        if t.is_empty() || self.nodes.is_empty() {
            return 0.0;
        }
        let m = t.boundary().mesh();
        let mut worst = m
            .vertices
            .iter()
            .map(|v| self.distance(v, closed))
            .fold(0.0, f64::max);
        for f in &m.faces {
            let p: Vec<P3> = f.iter().map(|&v| m.vertices[v as usize]).collect();
            for i in 1..p.len() - 1 {
                for a in 0..=4 {
                    for b in 0..=4 - a {
                        let (u, v) = (a as f64 / 4.0, b as f64 / 4.0);
                        let q = p[0] + (p[i] - p[0]) * u + (p[i + 1] - p[0]) * v;
                        worst = worst.max(self.distance(&q, closed));
                    }
                }
            }
        }
        worst
    }
}

/// Squared distance from a point to a box (0 inside).
fn box_distance2(b: &Box3, p: &P3) -> f64 {
    (0..3)
        .map(|i| {
            let d = (b.lo[i] - p[i]).max(0.0).max(p[i] - b.hi[i]);
            d * d
        })
        .sum()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::primitives;
    use crate::scene::cleanup::{cleanup, Origin};

    fn clean(raw: &PolyMesh) -> Mesh {
        cleanup(
            raw,
            &Origin {
                file: std::path::Path::new("t"),
                face_pos: &[],
            },
            &mut Vec::new(),
            crate::count::Count::NONE,
        )
        .unwrap()
    }

    /// An L-shaped prism: a cavity a single tribox cannot follow.
    fn ell() -> Mesh {
        let pts = [[0., 0.], [6., 0.], [6., 1.], [1., 1.], [1., 6.], [0., 6.]];
        let mut v: Vec<P3> = pts.iter().map(|p| P3::new(p[0], p[1], 0.0)).collect();
        v.extend(pts.iter().map(|p| P3::new(p[0], p[1], 1.0)));
        let mut faces = vec![vec![5, 4, 3, 2, 1, 0], vec![6, 7, 8, 9, 10, 11]];
        for i in 0..6u32 {
            let j = (i + 1) % 6;
            faces.push(vec![i, j, j + 6, i + 6]);
        }
        clean(&PolyMesh::new(v, faces))
    }

    #[test]
    fn l_shape_splits_and_children_are_tighter() {
        let m = ell();
        assert!(m.closed);
        let h = Hierarchy::build(&m, &HierarchyOptions::default());
        assert!(h.nodes.len() >= 3, "{}", h.nodes.len());
        let v0 = h.nodes[0].tribox.volume();
        let v1: f64 = h.cut(1).iter().map(|&n| h.nodes[n].tribox.volume()).sum();
        assert!(v1 < v0, "{v1} vs {v0}");
        assert!(h.cut_error(&h.cut(1)) <= h.cut_error(&h.cut(0)) + 1e-12);
        // The cut's triboxes hold every vertex of the solid.
        for d in 0..=h.depth() {
            let cut = h.cut(d);
            for p in &m.vertices {
                assert!(
                    cut.iter().any(|&n| h.nodes[n].tribox.contains(p)),
                    "level {d}: {p:?}"
                );
            }
        }
    }

    #[test]
    fn cube_stops_at_the_root() {
        let m = clean(&primitives::cuboid(
            P3::new(0., 0., 0.),
            P3::new(1., 2., 3.),
        ));
        let h = Hierarchy::build(&m, &HierarchyOptions::default());
        assert_eq!(h.nodes.len(), 1, "splitting a box cannot reduce its area");
        assert!(h.nodes[0].error < 1e-12);
    }
}
