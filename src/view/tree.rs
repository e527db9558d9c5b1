//! The view tree: the object tree in screen space, with tight screen bounds per node and a
//! bounding-volume split of large leaf meshes, so VISFAC2 can prune whole subtrees.
//!
//! Node bounds are computed per view from the projected faces (tighter than a projected
//! world CBOX), and hold only faces that can hide something (not edge-on, not culled).
//!
//! A mesh with a prepared object tree (paper 002, built once by the prepare stage) keeps
//! that tree's structure: the view only bounds its nodes on the screen. Other meshes get a
//! median split of their pieces by screen position and depth, made for this view.

use std::ops::Range;

use crate::chunked::CHUNK;
use crate::count::Count;
use crate::geom::coarse;
use crate::geom::hull2::convex_hull;
use crate::geom::poly2::Pt2;
use crate::geom::{Box3, Rect, M4};
use crate::prepare::trees::bvtree::{HierarchyKind, ObjectTree};
use crate::scene::{Content, FaceId, Object, Scene};

use super::camera::{Camera, Projection};
use super::cull::HiddenObject;
use super::piece_id::PieceId;
use super::screen::{Piece, ScreenFaces};

/// Pieces per BVH leaf inside a large mesh. A leaf's pieces are tested from one flat array
/// of bounds, a node is a dependent load: 16 a leaf visits a fifth fewer nodes than 4 and
/// costs 1.3-3% less one-thread CPU (ogre, nefertiti, the 1M terrain).
const LEAF_PIECES: usize = 16;
/// Most children of a group's node before the group gets a hierarchy of its own.
const MAX_CHILDREN: usize = 8;

/// What a node holds.
#[derive(Debug, Clone)]
pub(crate) enum NodeKind {
    /// Child nodes: a range of [`ViewTree::children`].
    Inner(Range<u32>),
    /// Pieces: a range of [`ViewTree::pieces`].
    Leaf(Range<u32>),
}

/// What the walk tests first of a candidate occluder piece: its screen rectangle and
/// nearest depth rounded outward to f32 (24 bytes a piece instead of 48: one a face), and
/// its face. A piece the coarse test passes is tested again on its exact bounds.
#[derive(Debug, Clone, Copy)]
pub(crate) struct PieceBound {
    /// Least x and y, rounded down.
    pub lo: [f32; 2],
    /// Greatest x and y, rounded up.
    pub hi: [f32; 2],
    /// Greatest screen depth, rounded up.
    pub zmax: f32,
    /// The face the piece belongs to.
    pub face: FaceId,
}

impl PieceBound {
    fn of(p: &Piece) -> PieceBound {
        let r = &p.rect;
        PieceBound {
            lo: [coarse::down(r.xmin), coarse::down(r.ymin)],
            hi: [coarse::up(r.xmax), coarse::up(r.ymax)],
            zmax: coarse::up(p.zmax),
            face: p.face,
        }
    }

    /// False only when the piece's exact rectangle cannot overlap `probe`'s (open
    /// rectangles, as [`Rect::overlaps`]) or the piece lies wholly behind its least depth:
    /// true wherever the exact test is, and sometimes where it is not.
    #[inline]
    // Not `>=`: the exact test skips only a depth below, so a NaN depth passes both.
    #[allow(clippy::neg_cmp_op_on_partial_ord)]
    pub(crate) fn may_meet(&self, probe: &BoundProbe) -> bool {
        self.lo[0] < probe.hi[0]
            && probe.lo[0] < self.hi[0]
            && self.lo[1] < probe.hi[1]
            && probe.lo[1] < self.hi[1]
            && !(self.zmax < probe.zmin)
    }
}

/// A target's rectangle and least depth rounded outward to f32, for [`PieceBound::may_meet`].
#[derive(Debug, Clone, Copy)]
pub(crate) struct BoundProbe {
    lo: [f32; 2],
    hi: [f32; 2],
    zmin: f32,
}

impl BoundProbe {
    /// The probe of a rectangle and least depth.
    pub(crate) fn new(rect: &Rect, zmin: f64) -> BoundProbe {
        BoundProbe {
            lo: [coarse::down(rect.xmin), coarse::down(rect.ymin)],
            hi: [coarse::up(rect.xmax), coarse::up(rect.ymax)],
            zmin: coarse::down(zmin),
        }
    }
}

/// A node: a subtree with its screen bounds (the CBOX in the standard view).
#[derive(Debug, Clone)]
pub(crate) struct Node {
    /// Screen rectangle of the occluding pieces below.
    pub rect: Rect,
    /// Least depth below.
    pub zmin: f64,
    /// Greatest depth below (nearest to the viewer).
    pub zmax: f64,
    /// Children or faces.
    pub kind: NodeKind,
    /// The object's INBOX in screen space, if it has one.
    pub inbox: Option<u32>,
}

/// An INBOX seen from the camera: the convex hull of its projected corners and its depths.
#[derive(Debug, Clone)]
pub(crate) struct ScreenInbox {
    /// Convex hull, counter-clockwise.
    pub hull: Vec<Pt2>,
    /// Bounding rectangle of the hull.
    pub rect: Rect,
    /// Depth of the farthest corner.
    pub zmin: f64,
}

/// A named object of the scene, as seen in this view.
#[derive(Debug, Clone)]
pub(crate) struct ObjectNode {
    /// Path from the top level.
    pub path: String,
    /// Its node.
    pub node: u32,
    /// Its faces: a contiguous range of the global face order.
    pub faces: Range<FaceId>,
}

/// The whole view tree.
#[derive(Debug, Clone, Default)]
pub(crate) struct ViewTree {
    /// All nodes; the root is the last.
    pub nodes: Vec<Node>,
    /// Child lists, each sorted front to back (greatest `zmax` first).
    pub children: Vec<u32>,
    /// Piece lists of the leaves.
    pub pieces: Vec<PieceId>,
    /// The screen bounds of `pieces`, in the same order: the walk's first test reads these
    /// contiguously instead of the pieces scattered in global order.
    pub piece_bounds: Vec<PieceBound>,
    /// Screen inboxes.
    pub inboxes: Vec<ScreenInbox>,
    /// Named objects in depth-first order.
    pub objects: Vec<ObjectNode>,
}

impl ViewTree {
    /// The root node.
    pub(crate) fn root(&self) -> u32 {
        self.nodes.len() as u32 - 1
    }

    /// Builds the tree of `scene` over its screen faces; `hidden` objects (in global face
    /// order) become empty nodes.
    ///
    /// The faces of each mesh go to `done` once its pieces are placed (every face of the
    /// scene in the end; hidden objects' faces at once).
    pub(crate) fn build(
        scene: &Scene,
        camera: &Camera,
        sf: &ScreenFaces,
        hidden: &[HiddenObject],
        done: Count,
    ) -> ViewTree {
        let mut b = Builder {
            tree: ViewTree::default(),
            sf,
            camera,
            next_face: FaceId(0),
            hidden,
            done,
        };
        b.object(&scene.root, &M4::identity(), "", None);
        b.tree
    }

    /// The object with this path.
    pub(crate) fn object(&self, path: &str) -> Option<&ObjectNode> {
        self.objects.iter().find(|o| o.path == path)
    }
}

struct Builder<'a> {
    tree: ViewTree,
    sf: &'a ScreenFaces,
    camera: &'a Camera,
    next_face: FaceId,
    /// Hidden objects not yet met, in global face order.
    hidden: &'a [HiddenObject<'a>],
    /// The faces placed so far, counted per mesh.
    done: Count<'a>,
}

impl Builder<'_> {
    /// Builds the node of `obj` placed by `xf`; `inbox` is an inbox in `xf`'s source frame.
    fn object(&mut self, obj: &Object, xf: &M4, path: &str, slot: Option<usize>) -> u32 {
        let first = self.next_face;
        if let Some(n) = self.hidden_here(obj) {
            self.next_face = self.next_face.offset(n);
            self.done.add(n as usize);
            let node = self.push(empty_node());
            if let Some(s) = slot {
                self.tree.objects[s].node = node;
                self.tree.objects[s].faces = first..self.next_face;
            }
            return node;
        }
        let inbox = obj.inbox;
        let node = match &obj.content {
            Content::Mesh(m) => {
                let end = first.offset(m.faces.len() as u32);
                self.next_face = end;
                let node = match obj.tree.as_deref() {
                    Some(t) if t.kind == HierarchyKind::Simplify => self
                        .prepared(t, 0, first, xf)
                        .unwrap_or_else(|| self.push(empty_node())),
                    _ => {
                        let sf = self.sf;
                        let span = sf.pieces_in(first..end);
                        let from = span.clone().next().map_or(0, |p| p.0);
                        let ids = crate::chunked::flat_map(span.len(), CHUNK, |r, ids| {
                            let r = from + r.start as u32..from + r.end as u32;
                            ids.extend(r.map(PieceId).filter(|&p| sf.piece(p).is_occluder()));
                        });
                        self.bvh(ids)
                    }
                };
                self.done.add(m.faces.len());
                node
            }
            Content::Subobjects(subs) => {
                let kids: Vec<u32> = subs
                    .iter()
                    .map(|s| {
                        let p = if path.is_empty() {
                            s.name.clone()
                        } else {
                            format!("{path}/{}", s.name)
                        };
                        let slot = self.tree.objects.len();
                        self.tree.objects.push(ObjectNode {
                            path: p.clone(),
                            node: 0,
                            faces: FaceId(0)..FaceId(0),
                        });
                        self.object(s, xf, &p, Some(slot))
                    })
                    .collect();
                self.group(kids)
            }
            Content::Instance(i) => {
                let m = xf * i.transform;
                let n = self.object(&i.prototype, &m, path, None);
                if let Some(pb) = i.prototype.inbox {
                    self.attach_inbox(n, &pb, &m);
                }
                n
            }
        };
        if let Some(b) = inbox {
            self.attach_inbox(node, &b, xf);
        }
        if let Some(s) = slot {
            self.tree.objects[s].node = node;
            self.tree.objects[s].faces = first..self.next_face;
        }
        node
    }

    /// The face count of `obj` when it is the next hidden object (then consumed).
    fn hidden_here(&mut self, obj: &Object) -> Option<u32> {
        let h = self.hidden.first()?;
        if h.first_face != self.next_face || !std::ptr::eq(h.object, obj) {
            return None;
        }
        self.hidden = &self.hidden[1..];
        Some(h.face_count)
    }

    fn attach_inbox(&mut self, node: u32, b: &Box3, xf: &M4) {
        if self.tree.nodes[node as usize].inbox.is_some() || !b.has_interior() {
            return;
        }
        let corners = b.corners().map(|c| xf.transform_point(&c));
        if self.camera.projection == Projection::Perspective
            && !corners.iter().all(|c| self.camera.in_front(c))
        {
            return;
        }
        let s = corners.map(|c| self.camera.project(&c));
        let pts: Vec<Pt2> = s.iter().map(|p| [p[0], p[1]]).collect();
        let hull = convex_hull(pts);
        if hull.len() < 3 {
            return;
        }
        let rect = Rect::of_points(hull.iter());
        let zmin = s.iter().map(|p| p[2]).fold(f64::INFINITY, f64::min);
        self.tree.inboxes.push(ScreenInbox { hull, rect, zmin });
        self.tree.nodes[node as usize].inbox = Some(self.tree.inboxes.len() as u32 - 1);
    }

    fn push(&mut self, node: Node) -> u32 {
        self.tree.nodes.push(node);
        self.tree.nodes.len() as u32 - 1
    }

    /// A node over the nodes of an object's subobjects. A wide group (a town of a thousand
    /// buildings under one root) gets a median-split hierarchy over its children's screen
    /// bounds, so that a walk does not scan every child: the group's node is its root.
    fn group(&mut self, mut kids: Vec<u32>) -> u32 {
        if kids.len() <= MAX_CHILDREN {
            return self.inner(kids);
        }
        let nodes = &self.tree.nodes;
        let centre = |k: u32, axis: usize| {
            let n = &nodes[k as usize];
            match axis {
                2 => n.zmin + n.zmax,
                _ => n.rect.centre2(axis),
            }
        };
        let span = |axis: usize| {
            let (lo, hi) = kids
                .iter()
                .map(|&k| centre(k, axis))
                .filter(|c| c.is_finite())
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), c| {
                    (lo.min(c), hi.max(c))
                });
            hi - lo
        };
        let axis = (0..3)
            .max_by(|&a, &b| span(a).total_cmp(&span(b)).then(b.cmp(&a)))
            .unwrap_or(0);
        let mid = kids.len() / 2;
        kids.select_nth_unstable_by(mid, |&a, &b| {
            centre(a, axis).total_cmp(&centre(b, axis)).then(a.cmp(&b))
        });
        let right = kids.split_off(mid);
        let l = self.group(kids);
        let r = self.group(right);
        self.inner(vec![l, r])
    }

    fn inner(&mut self, mut kids: Vec<u32>) -> u32 {
        let nodes = &self.tree.nodes;
        kids.sort_by(|&a, &b| nodes[b as usize].zmax.total_cmp(&nodes[a as usize].zmax));
        let mut n = empty_node();
        for &k in &kids {
            let c = &self.tree.nodes[k as usize];
            n.grow(&c.rect, c.zmin, c.zmax);
        }
        let start = self.tree.children.len() as u32;
        self.tree.children.extend(kids);
        n.kind = NodeKind::Inner(start..self.tree.children.len() as u32);
        self.push(n)
    }

    /// The view's copy of the prepared object tree's node `n` (faces numbered from `first`,
    /// placed by `xf`): the same structure, with screen bounds of the occluding pieces below
    /// each node (tight for this view) and the node's INBOX projected. Nodes with no
    /// occluding piece are left out; None when nothing below occludes.
    fn prepared(&mut self, t: &ObjectTree, n: u32, first: FaceId, xf: &M4) -> Option<u32> {
        let node = &t.nodes[n as usize];
        let id = match node.children {
            None => {
                let sf = self.sf;
                let ids: Vec<PieceId> = t
                    .faces_of(n)
                    .iter()
                    .flat_map(|&f| sf.pieces_of(first.offset(f)))
                    .filter(|&p| sf.piece(p).is_occluder())
                    .collect();
                if ids.is_empty() {
                    return None;
                }
                self.leaf(ids)
            }
            Some([l, r]) => {
                let kids: Vec<u32> = [l, r]
                    .into_iter()
                    .filter_map(|c| self.prepared(t, c, first, xf))
                    .collect();
                match kids.len() {
                    0 => return None,
                    1 => kids[0],
                    _ => self.inner(kids),
                }
            }
        };
        if let Some(b) = node.inbox {
            self.attach_inbox(id, &b, xf);
        }
        Some(id)
    }

    /// A leaf over pieces.
    fn leaf(&mut self, ids: Vec<PieceId>) -> u32 {
        let mut n = empty_node();
        for &p in &ids {
            let pc = self.sf.piece(p);
            n.grow(&pc.rect, pc.zmin, pc.zmax);
        }
        let start = self.tree.pieces.len() as u32;
        self.tree
            .piece_bounds
            .extend(ids.iter().map(|&p| PieceBound::of(self.sf.piece(p))));
        self.tree.pieces.extend(ids);
        n.kind = NodeKind::Leaf(start..self.tree.pieces.len() as u32);
        self.push(n)
    }

    /// A median-split hierarchy over pieces by their screen rectangles: the pieces are put
    /// in the tree's order first (on all threads: [`median_order`]), then the nodes are made
    /// over that order in one walk, so the tree is the same for any thread count.
    fn bvh(&mut self, mut ids: Vec<PieceId>) -> u32 {
        median_order(self.sf, &mut ids);
        self.bvh_over(ids)
    }

    /// The nodes of the median-split hierarchy over `ids`, already in [`median_order`]:
    /// what [`Builder::leaf`] and [`Builder::inner`] make, walking the halves depth first
    /// (the left half's nodes, the right's, then theirs), made on all threads. Where each
    /// half's nodes and child lists go depends only on its length ([`Shape`]), so each half
    /// fills its own slices of the lists, and the piece bounds are made side by side.
    fn bvh_over(&mut self, ids: Vec<PieceId>) -> u32 {
        let sf = self.sf;
        let shape = Shape::of(ids.len());
        let tree = &mut self.tree;
        let at = At {
            node: tree.nodes.len() as u32,
            child: tree.children.len() as u32,
            piece: tree.pieces.len() as u32,
        };
        let bounds = crate::chunked::map(ids.len(), |k| PieceBound::of(sf.piece(ids[k])));
        // A tree of one mesh takes its lists as they are made (no copy on one thread).
        if tree.piece_bounds.is_empty() {
            tree.piece_bounds = bounds;
        } else {
            tree.piece_bounds.extend(bounds);
        }
        let (nodes, children) = (at.node as usize, at.child as usize);
        // Made (their pages first touched) on all threads: 2.5M nodes on the 10M terrain.
        crate::chunked::extend_map(&mut tree.nodes, shape.nodes, |_| empty_node());
        crate::chunked::extend_map(&mut tree.children, shape.children, |_| 0);
        fill(
            sf,
            &ids,
            &mut tree.nodes[nodes..],
            &mut tree.children[children..],
            at,
        );
        if tree.pieces.is_empty() {
            tree.pieces = ids;
        } else {
            tree.pieces.extend_from_slice(&ids);
        }
        tree.nodes.len() as u32 - 1
    }
}

/// How many nodes and child-list entries the median split of a run of pieces makes.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Shape {
    nodes: usize,
    children: usize,
}

impl Shape {
    /// The shape over `n` pieces: one leaf up to [`LEAF_PIECES`], else the halves' shapes
    /// and an inner node over the two.
    fn of(n: usize) -> Shape {
        if n <= LEAF_PIECES {
            return Shape {
                nodes: 1,
                children: 0,
            };
        }
        let (l, r) = (Shape::of(n / 2), Shape::of(n - n / 2));
        Shape {
            nodes: l.nodes + r.nodes + 1,
            children: l.children + r.children + 2,
        }
    }
}

/// Where a run's first node, child-list entry and piece sit in the tree's lists.
#[derive(Debug, Clone, Copy)]
struct At {
    node: u32,
    child: u32,
    piece: u32,
}

/// Fills `nodes` and `children` (exactly the run's [`Shape`], at `at`) with the median
/// split's nodes over `ids` (the pieces at `at.piece`), the root last; returns the root.
fn fill(
    sf: &ScreenFaces,
    ids: &[PieceId],
    nodes: &mut [Node],
    children: &mut [u32],
    at: At,
) -> Node {
    let mut n = empty_node();
    if ids.len() <= LEAF_PIECES {
        // As [`Builder::leaf`].
        for &p in ids {
            let pc = sf.piece(p);
            n.grow(&pc.rect, pc.zmin, pc.zmax);
        }
        n.kind = NodeKind::Leaf(at.piece..at.piece + ids.len() as u32);
        nodes[0] = n.clone();
        return n;
    }
    let (left, right) = ids.split_at(ids.len() / 2);
    let (ls, rs) = (Shape::of(left.len()), Shape::of(right.len()));
    let (lnodes, rest) = nodes.split_at_mut(ls.nodes);
    let (rnodes, root) = rest.split_at_mut(rs.nodes);
    let (lkids, rest) = children.split_at_mut(ls.children);
    let (rkids, own) = rest.split_at_mut(rs.children);
    let r_at = At {
        node: at.node + ls.nodes as u32,
        child: at.child + ls.children as u32,
        piece: at.piece + left.len() as u32,
    };
    let (l, r) = if ids.len() < SPLIT_ALONE_BELOW {
        (
            fill(sf, left, lnodes, lkids, at),
            fill(sf, right, rnodes, rkids, r_at),
        )
    } else {
        rayon::join(
            || fill(sf, left, lnodes, lkids, at),
            || fill(sf, right, rnodes, rkids, r_at),
        )
    };
    // As [`Builder::inner`]: the two roots, nearest first (a stable sort), bound together.
    let mut kids = [(r_at.node - 1, &l), (r_at.node + rs.nodes as u32 - 1, &r)];
    kids.sort_by(|a, b| b.1.zmax.total_cmp(&a.1.zmax));
    for (slot, (k, c)) in own.iter_mut().zip(kids) {
        n.grow(&c.rect, c.zmin, c.zmax);
        *slot = k;
    }
    let first = at.child + (ls.children + rs.children) as u32;
    n.kind = NodeKind::Inner(first..first + 2);
    root[0] = n.clone();
    n
}

/// Below this many pieces a median split is made on the calling thread.
const SPLIT_ALONE_BELOW: usize = 1 << 14;

/// Puts `ids` in the order of a median-split hierarchy: the pieces of the first half by the
/// axis of greatest spread before those of the second, recursively, down to leaves of
/// [`LEAF_PIECES`]. The halves are ordered side by side; each split depends on its slice
/// alone, so the order is the same for any thread count.
fn median_order(sf: &ScreenFaces, ids: &mut [PieceId]) {
    if ids.len() <= LEAF_PIECES {
        return;
    }
    let centres = Centres::of(sf, ids);
    split_order(&centres, ids);
}

/// The split keys of a run of pieces, side by side: each piece's screen x and y centre and
/// its depth centre (all doubled, as [`Rect::centre2`]), so that the splits read one small
/// array instead of the 80-byte pieces scattered through [`ScreenFaces`].
struct Centres {
    /// The least piece id held.
    first: u32,
    /// `[x, y, z]` of pieces `first..`, in id order.
    keys: Vec<[f64; 3]>,
}

/// Pieces per task when the keys are computed on all threads.
const CENTRES_TASK: usize = 1 << 12;

impl Centres {
    /// The keys of every piece id from the least to the greatest of `ids` (a mesh's
    /// occluding pieces: one run of ids with a few gaps).
    fn of(sf: &ScreenFaces, ids: &[PieceId]) -> Centres {
        use rayon::prelude::*;
        let first = ids.iter().map(|p| p.0).min().unwrap_or(0);
        let last = ids.iter().map(|p| p.0).max().unwrap_or(0);
        let keys = (first..last + 1)
            .into_par_iter()
            .with_min_len(CENTRES_TASK)
            .map(|i| {
                let pc = sf.piece(PieceId(i));
                [pc.rect.centre2(0), pc.rect.centre2(1), pc.zmin + pc.zmax]
            })
            .collect();
        Centres { first, keys }
    }

    /// Piece `p`'s key on `axis` (0 and 1 screen x and y, 2 depth).
    fn at(&self, p: PieceId, axis: usize) -> f64 {
        self.keys[(p.0 - self.first) as usize][axis]
    }
}

/// [`median_order`] over keys already gathered.
fn split_order(c: &Centres, ids: &mut [PieceId]) {
    if ids.len() <= LEAF_PIECES {
        return;
    }
    // Axis 0 and 1 are screen x and y, axis 2 is depth: splitting by depth too separates
    // the front and back layers of a mesh, so the depth test prunes whole nodes. The three
    // spans are folded in one pass, each in the slice's order (the same bits as three).
    // Least and greatest are exact, so the spans are the same folded on any threads.
    let none = || ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
    let add = |(mut lo, mut hi): ([f64; 3], [f64; 3]), &p: &PieceId| {
        for axis in 0..3 {
            let k = c.at(p, axis);
            lo[axis] = lo[axis].min(k);
            hi[axis] = hi[axis].max(k);
        }
        (lo, hi)
    };
    let (lo, hi) = if ids.len() < SPLIT_ALONE_BELOW {
        ids.iter().fold(none(), add)
    } else {
        use rayon::prelude::*;
        let join = |(l1, h1): ([f64; 3], [f64; 3]), (l2, h2): ([f64; 3], [f64; 3])| {
            (
                [0, 1, 2].map(|a| l1[a].min(l2[a])),
                [0, 1, 2].map(|a| h1[a].max(h2[a])),
            )
        };
        ids.par_iter()
            .with_min_len(CHUNK)
            .fold(none, add)
            .reduce(none, join)
    };
    // A zero's sign may hang on the fold's grouping (the least of 0 and -0): + 0.0 drops it.
    let span = |axis: usize| hi[axis] - lo[axis] + 0.0;
    let axis = (0..3)
        .max_by(|&a, &b| span(a).total_cmp(&span(b)).then(b.cmp(&a)))
        .unwrap_or(0);
    let mid = ids.len() / 2;
    ids.select_nth_unstable_by(mid, |&a, &b| {
        c.at(a, axis).total_cmp(&c.at(b, axis)).then(a.cmp(&b))
    });
    let (left, right) = ids.split_at_mut(mid);
    if left.len() + right.len() < SPLIT_ALONE_BELOW {
        split_order(c, left);
        split_order(c, right);
    } else {
        rayon::join(|| split_order(c, left), || split_order(c, right));
    }
}

impl Node {
    /// Grows the bounds to hold a rectangle and depth range.
    fn grow(&mut self, rect: &Rect, zmin: f64, zmax: f64) {
        self.rect = self.rect.union(rect);
        self.zmin = self.zmin.min(zmin);
        self.zmax = self.zmax.max(zmax);
    }
}

fn empty_node() -> Node {
    Node {
        rect: Rect::EMPTY,
        zmin: f64::INFINITY,
        zmax: f64::NEG_INFINITY,
        kind: NodeKind::Leaf(0..0),
        inbox: None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::V3;
    use crate::scene::testing::warped_scene;

    /// Every piece below node `n`, in walk order.
    fn pieces_below(tree: &ViewTree, n: u32) -> Vec<PieceId> {
        match &tree.nodes[n as usize].kind {
            NodeKind::Leaf(r) => tree.pieces[r.start as usize..r.end as usize].to_vec(),
            NodeKind::Inner(r) => tree.children[r.start as usize..r.end as usize]
                .iter()
                .flat_map(|&c| pieces_below(tree, c))
                .collect(),
        }
    }

    /// The median split as it was first written: every key read from the pieces, each
    /// axis's span in a pass of its own.
    fn median_order_by_pieces(sf: &ScreenFaces, ids: &mut [PieceId]) {
        if ids.len() <= LEAF_PIECES {
            return;
        }
        let centre = |p: PieceId, axis: usize| {
            let pc = sf.piece(p);
            match axis {
                2 => pc.zmin + pc.zmax,
                _ => pc.rect.centre2(axis),
            }
        };
        let span = |axis: usize| {
            let (lo, hi) = ids
                .iter()
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &f| {
                    (lo.min(centre(f, axis)), hi.max(centre(f, axis)))
                });
            hi - lo
        };
        let axis = (0..3)
            .max_by(|&a, &b| span(a).total_cmp(&span(b)).then(b.cmp(&a)))
            .unwrap_or(0);
        let mid = ids.len() / 2;
        ids.select_nth_unstable_by(mid, |&a, &b| {
            centre(a, axis).total_cmp(&centre(b, axis)).then(a.cmp(&b))
        });
        let (left, right) = ids.split_at_mut(mid);
        median_order_by_pieces(sf, left);
        median_order_by_pieces(sf, right);
    }

    /// The keys gathered side by side give the same order as the pieces read in place, on
    /// random triangles whose corners sit on a coarse lattice (many equal keys, so the ties
    /// are broken by id) and with every third piece left out (gaps in the run of ids).
    /// `n` random triangles whose corners sit on a lattice of `lattice` steps a side, seen
    /// by an orthographic camera: the screen faces and the camera.
    fn random_triangles(seed: u64, n: u32, lattice: usize) -> (ScreenFaces, Camera) {
        use crate::geom::rng::XorShift;
        use crate::geom::{PolyMesh, P3};
        let mut rng = XorShift::new(seed);
        let (mut pts, mut faces) = (Vec::new(), Vec::new());
        for f in 0..n {
            for _ in 0..3 {
                let c = [0; 3].map(|_| rng.below(lattice) as f64);
                pts.push(P3::new(c[0], c[1], c[2]));
            }
            faces.push(vec![3 * f, 3 * f + 1, 3 * f + 2]);
        }
        let mesh = crate::scene::testing::leaf("tris", &PolyMesh::new(pts, faces));
        let scene = Scene::new(Object::group("", vec![mesh]), "t".into());
        let camera = Camera::orthographic(V3::new(-1., -2., -3.), V3::y()).unwrap();
        (ScreenFaces::build(&scene, &camera), camera)
    }

    #[test]
    fn gathered_keys_order_as_the_pieces() {
        let (sf, _) = random_triangles(35, 3000, 9);
        let mut ids: Vec<PieceId> = sf.piece_ids().filter(|p| p.0 % 3 != 1).collect();
        assert!(ids.len() > 1000);
        let mut want = ids.clone();
        median_order_by_pieces(&sf, &mut want);
        median_order(&sf, &mut ids);
        assert_eq!(ids, want);
    }

    /// [`Builder::bvh_over`] as first written: leaves and inner nodes pushed one by one,
    /// depth first.
    fn bvh_one_by_one(b: &mut Builder, ids: &[PieceId]) -> u32 {
        if ids.len() <= LEAF_PIECES {
            return b.leaf(ids.to_vec());
        }
        let (left, right) = ids.split_at(ids.len() / 2);
        let l = bvh_one_by_one(b, left);
        let r = bvh_one_by_one(b, right);
        b.inner(vec![l, r])
    }

    /// A tree's lists as comparable values (nodes by their bounds' bits and kind).
    fn listed(t: &ViewTree) -> (Vec<String>, Vec<u32>, Vec<PieceId>, Vec<String>) {
        let nodes = t.nodes.iter().map(|n| format!("{n:?}")).collect();
        let bounds = t.piece_bounds.iter().map(|b| format!("{b:?}")).collect();
        (nodes, t.children.clone(), t.pieces.clone(), bounds)
    }

    /// The hierarchy filled in place on several threads is the one built node by node, for
    /// runs of every shape (one leaf, a leaf and one more, odd halves, runs long enough to be
    /// split on several threads), after a first run already in the lists.
    #[test]
    fn filled_hierarchy_is_the_one_built_node_by_node() {
        let (sf, camera) = random_triangles(36, 2 * SPLIT_ALONE_BELOW as u32 + 77, 50);
        let all: Vec<PieceId> = sf.piece_ids().collect();
        assert!(all.len() > 2 * SPLIT_ALONE_BELOW);
        let builder = || Builder {
            tree: ViewTree::default(),
            sf: &sf,
            camera: &camera,
            next_face: FaceId(0),
            hidden: &[],
            done: Count::NONE,
        };
        for len in [
            1,
            LEAF_PIECES,
            LEAF_PIECES + 1,
            3 * LEAF_PIECES + 5,
            1001,
            all.len(),
        ] {
            let mut ids = all[all.len() - len..].to_vec();
            median_order(&sf, &mut ids);
            let mut one = builder();
            bvh_one_by_one(&mut one, &all[..40]);
            let root = bvh_one_by_one(&mut one, &ids);
            let mut filled = builder();
            bvh_one_by_one(&mut filled, &all[..40]);
            let got = crate::chunked::pool(3).install(|| filled.bvh_over(ids.clone()));
            assert_eq!(got, root, "{len} pieces");
            assert_eq!(listed(&filled.tree), listed(&one.tree), "{len} pieces");
            // A tree's first mesh takes the lists whole.
            let (mut alone, mut fresh) = (builder(), builder());
            let root = bvh_one_by_one(&mut alone, &ids);
            let got = crate::chunked::pool(3).install(|| fresh.bvh_over(ids.clone()));
            assert_eq!(got, root, "{len} pieces alone");
            assert_eq!(
                listed(&fresh.tree),
                listed(&alone.tree),
                "{len} pieces alone"
            );
        }
    }

    #[test]
    fn faces_and_pieces_are_told_apart() {
        let mut scene = warped_scene();
        // Prepared: the wall is a proven solid, so its back faces are culled.
        crate::prepare::prepare(
            &mut scene,
            &crate::PrepareOptions::default(),
            &crate::Progress::default(),
        );
        let camera = Camera::orthographic(V3::new(0., 0., -1.), V3::y()).unwrap();
        let sf = ScreenFaces::build(&scene, &camera);
        // The bent quad is one face but two planar pieces: every later face's piece is one on.
        assert_eq!((sf.face_count(), sf.pieces.len()), (19, 20));
        assert_eq!(sf.pieces_of(FaceId(0)).count(), 2);
        for f in 1..19 {
            let p: Vec<PieceId> = sf.pieces_of(FaceId(f)).collect();
            assert_eq!(p, [PieceId(f + 1)]);
            assert_eq!(sf.piece(p[0]).face, FaceId(f));
        }
        let tree = ViewTree::build(&scene, &camera, &sf, &[], Count::NONE);
        // The leaf lists hold pieces; their bounds name the pieces' faces.
        for (p, b) in tree.pieces.iter().zip(&tree.piece_bounds) {
            assert_eq!(b.face, sf.piece(*p).face);
            let (r, z) = (sf.piece(*p).rect, sf.piece(*p).zmax);
            assert!(f64::from(b.lo[0]) <= r.xmin && f64::from(b.lo[1]) <= r.ymin);
            assert!(f64::from(b.hi[0]) >= r.xmax && f64::from(b.hi[1]) >= r.ymax);
            assert!(f64::from(b.zmax) >= z);
        }
        // Objects hold face ranges of the global order, not piece ranges.
        let ranges: Vec<(&str, u32, u32)> = tree
            .objects
            .iter()
            .map(|o| (o.path.as_str(), o.faces.start.0, o.faces.end.0))
            .collect();
        assert_eq!(
            ranges,
            [
                ("warped", 0, 1),
                ("wall", 1, 7),
                ("hidden", 7, 13),
                ("beside", 13, 19)
            ]
        );
        // Seen along -z the wall shows one face (its top at z = 2, face 1 + 1): back face
        // culled, sides edge-on. Its node holds that face's piece, numbered one on.
        let wall = tree.object("wall").unwrap();
        let below = pieces_below(&tree, wall.node);
        assert_eq!(below.len(), 1);
        let face = sf.piece(below[0]).face;
        assert!(FaceId::each(&wall.faces).any(|f| f == face));
        assert_eq!(below[0], PieceId(face.0 + 1));
        assert_eq!(sf.world_pts(below[0])[0].z, 2.0);
        // Both pieces of the bent quad are occluders of the warped object's node.
        let warped = tree.object("warped").unwrap();
        assert_eq!(pieces_below(&tree, warped.node), [PieceId(0), PieceId(1)]);
    }

    #[test]
    fn coarse_bounds_pass_wherever_the_exact_ones_do() {
        let mut rng = crate::geom::rng::XorShift::new(35);
        // Coordinates on a fine grid and near each other, so that many exact tests are
        // decided by less than an f32's spacing.
        let v = |rng: &mut crate::geom::rng::XorShift| 0.3 + rng.below(64) as f64 * 1e-9;
        let (mut exact, mut coarse) = (0, 0);
        for _ in 0..20_000 {
            let mut rect = || {
                let (a, b, c, d) = (v(&mut rng), v(&mut rng), v(&mut rng), v(&mut rng));
                Rect::new(a.min(b), c.min(d), a.max(b), c.max(d))
            };
            let (r, q) = (rect(), rect());
            let (zmax, zmin) = (v(&mut rng), v(&mut rng));
            let piece = PieceBound {
                lo: [coarse::down(r.xmin), coarse::down(r.ymin)],
                hi: [coarse::up(r.xmax), coarse::up(r.ymax)],
                zmax: coarse::up(zmax),
                face: FaceId(0),
            };
            let meets = r.overlaps(&q) && zmax >= zmin;
            let may = piece.may_meet(&BoundProbe::new(&q, zmin));
            assert!(may || !meets, "{r:?} {q:?} {zmax} {zmin}");
            exact += usize::from(meets);
            coarse += usize::from(may);
        }
        // The test is not empty: both kinds of answer happen, and the coarse one is wider.
        assert!(
            exact > 1000 && coarse > exact && coarse < 20_000,
            "{exact} {coarse}"
        );
    }
}
