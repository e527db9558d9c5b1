//! Screen-space faces: every face of the scene (outside hidden subtrees) projected into the
//! standard view as planar pieces, in global face order.

use std::cmp::Ordering;
use std::ops::Range;

use rayon::prelude::*;

use crate::count::Count;
use crate::geom::accurate::mat_point_dd;
use crate::geom::construct::{near_crossing, near_side};
use crate::geom::convexity::{is_convex_ccw, Strictness};
use crate::geom::poly2::{ring_area, Pt2};
use crate::geom::{newell, orient2d, orient3d_refs, Corners, Rect, P3};
#[cfg(test)]
use crate::scene::Scene;
use crate::scene::{FaceId, FaceIndices, Leaf};

use super::backfaces::BackCull;
use super::camera::{project_dd, Camera, Projection};
use super::cull::Cull;
use super::piece_id::PieceId;
use super::ring_index::{RingIndex, INDEXED_ABOVE};

/// How a projected face presents itself to the viewer.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Facing {
    /// Counter-clockwise in projection: its front (outer) side faces the viewer.
    Front,
    /// Clockwise in projection.
    Back,
    /// Seen exactly edge-on: invisible, hides nothing.
    EdgeOn,
    /// Entirely behind the near plane (perspective): not drawn, hides nothing.
    Clipped,
}

/// One planar piece of a face in screen space (a planar face is one piece; a warped face is
/// split into planar triangles here, so that every piece has a plane).
#[derive(Debug, Clone, Copy)]
pub(crate) struct Piece {
    /// The face this piece belongs to.
    pub face: FaceId,
    /// First corner in [`ScreenFaces::corner_at`].
    pub start: u32,
    /// Number of points.
    pub len: u32,
    /// Index of the leaf object in [`ScreenFaces::leaves`].
    pub leaf: u32,
    /// Screen bounding rectangle.
    pub rect: Rect,
    /// Least depth (farthest from the viewer).
    pub zmin: f64,
    /// Greatest depth (nearest to the viewer).
    pub zmax: f64,
    /// Three well-spread points (offsets from `start`) spanning the face's plane.
    pub refs: [u32; 3],
    /// Sign of orient2d over `refs`: +1 or -1 (0 when edge-on). One byte, beside the flags
    /// below: a piece is 80 bytes, and there is one a face.
    pub ref_turn: i8,
    /// Orientation toward the viewer.
    pub facing: Facing,
    /// True for a back face of a proven solid: hidden by the solid itself (a safe cull).
    pub culled: bool,
    /// True when the projected ring is convex (counter-clockwise after orienting).
    pub convex: bool,
}

impl Piece {
    /// True when this piece can hide anything (not edge-on, not clipped away, not culled).
    pub(crate) fn is_occluder(&self) -> bool {
        matches!(self.facing, Facing::Front | Facing::Back) && !self.culled
    }
}

/// Leaf object info kept for output.
#[derive(Debug, Clone)]
pub(crate) struct LeafInfo {
    /// Object path.
    pub path: String,
    /// Its first face.
    pub first_face: FaceId,
    /// Number of faces.
    pub face_count: u32,
    /// Where its vertices' world points start in [`ScreenFaces::world`].
    pub world_first: u32,
    /// Styled occlude-only: it hides, but is never drawn nor listed.
    pub occlude_only: bool,
}

impl LeafInfo {
    /// The leaf's faces.
    pub(crate) fn faces(&self) -> Range<FaceId> {
        self.first_face..self.first_face.offset(self.face_count)
    }
}

/// All faces in screen space, as planar pieces in global face order.
#[derive(Debug, Clone, Default)]
pub(crate) struct ScreenFaces {
    /// The planar pieces; pieces of one face are consecutive, faces in global order.
    pub pieces: Vec<Piece>,
    /// Where each face's pieces start: face `f`'s pieces are
    /// `face_starts[f]..face_starts[f + 1]` (length: face count + 1; a face of a hidden
    /// subtree has none).
    pub face_starts: Vec<u32>,
    /// The corners of all pieces, piece after piece: each the index of its point in `world`
    /// and in `points`.
    pub corner_at: Vec<u32>,
    /// World points: each projected leaf's vertices placed by its transform (once a vertex,
    /// in mesh order, from [`LeafInfo::world_first`]), and the points near clipping made.
    /// Side-of-plane decisions are made on these (exact input coordinates where not clipped).
    pub world: Vec<P3>,
    /// Projected points (x, y, depth) of the points of `world`, index for index (a vertex
    /// behind the near plane, which no corner names, has one too, maybe not finite).
    pub points: Vec<[f64; 3]>,
    /// Sign of det(M): +1 when the camera keeps the orientation of tetrahedra, -1 when it flips it.
    pub det_sign: f64,
    /// The camera that made them.
    pub camera: Option<Camera>,
    /// The projected leaf objects in global order (leaves of hidden subtrees are absent).
    pub leaves: Vec<LeafInfo>,
    /// Run boxes of every piece of more than [`INDEXED_ABOVE`] points, by ascending piece.
    pub ring_indexes: Vec<(PieceId, RingIndex)>,
    /// In a section view, the first face a cut made (those from it on are section faces).
    pub section_first: Option<u32>,
}

impl ScreenFaces {
    #[cfg(test)]
    /// Projects every face of `scene` with `camera`.
    pub(crate) fn build(scene: &Scene, camera: &Camera) -> ScreenFaces {
        Self::from_cull(&Cull::none(scene), camera, Count::NONE)
    }

    /// Projects the faces of the leaves a cull kept; faces of hidden subtrees get no pieces.
    ///
    /// The faces of the kept leaves go to `done` as they are projected, once per chunk.
    pub(crate) fn from_cull(cull: &Cull, camera: &Camera, done: Count) -> ScreenFaces {
        let mut out = ScreenFaces {
            det_sign: camera.matrix.determinant().signum(),
            camera: Some(*camera),
            ..Default::default()
        };
        // Exact sizes for planar faces (the usual case): no doubling on the way.
        let faces: usize = cull.leaves.iter().map(|l| l.mesh.faces.len()).sum();
        let corners: usize = cull
            .leaves
            .iter()
            .flat_map(|l| &l.mesh.faces)
            .map(|f| f.vertices.len())
            .sum();
        let vertices: usize = cull.leaves.iter().map(|l| l.mesh.vertices.len()).sum();
        out.pieces.reserve(faces);
        out.corner_at.reserve(corners);
        out.world.reserve(vertices);
        out.points.reserve(vertices);
        out.face_starts.reserve(cull.face_count as usize + 1);
        out.face_starts.push(0);
        for (li, leaf) in cull.leaves.iter().enumerate() {
            out.face_starts
                .resize(leaf.first_face + 1, out.pieces.len() as u32);
            out.add_leaf(li as u32, leaf, camera, cull.hidden_in_leaf(li), done);
        }
        out.face_starts
            .resize(cull.face_count as usize + 1, out.pieces.len() as u32);
        out
    }

    /// True when face `f` (which must have pieces) belongs to an occlude-only object.
    pub(crate) fn occlude_only(&self, f: FaceId) -> bool {
        self.leaf_of_face(f).occlude_only
    }

    /// True when face `f` was made by a section cut.
    pub(crate) fn is_section(&self, f: FaceId) -> bool {
        self.section_first.is_some_and(|s| f.0 >= s)
    }

    /// Number of faces (not pieces).
    pub(crate) fn face_count(&self) -> usize {
        self.face_starts.len() - 1
    }

    /// The piece `p`.
    #[inline]
    pub(crate) fn piece(&self, p: PieceId) -> &Piece {
        &self.pieces[p.index()]
    }

    /// Every piece id, in order.
    pub(crate) fn piece_ids(&self) -> impl ExactSizeIterator<Item = PieceId> + Clone {
        (0..self.pieces.len() as u32).map(PieceId)
    }

    /// Indices into [`ScreenFaces::pieces`] of the pieces of the faces in `faces`.
    pub(crate) fn piece_span(&self, faces: Range<FaceId>) -> Range<usize> {
        self.face_starts[faces.start.index()] as usize..self.face_starts[faces.end.index()] as usize
    }

    /// The pieces of the faces in `faces`, in order.
    pub(crate) fn pieces_in(
        &self,
        faces: Range<FaceId>,
    ) -> impl ExactSizeIterator<Item = PieceId> + Clone {
        let r = self.piece_span(faces);
        (r.start as u32..r.end as u32).map(PieceId)
    }

    /// The pieces of face `f`.
    pub(crate) fn pieces_of(&self, f: FaceId) -> impl ExactSizeIterator<Item = PieceId> + Clone {
        self.pieces_in(f..f.offset(1))
    }

    /// How face `f` presents itself: its single piece's facing, or for a warped face split
    /// into pieces, the sign of the pieces' summed projected area (clipped or edge-on when no
    /// piece shows area).
    pub(crate) fn face_facing(&self, f: FaceId) -> Facing {
        let pieces = self.pieces_of(f);
        if pieces.len() == 1 {
            return self.piece(PieceId(self.face_starts[f.index()])).facing;
        }
        let mut area = 0.0;
        let mut any_clipped = false;
        for p in pieces {
            match self.piece(p).facing {
                Facing::Front | Facing::Back => {
                    area += ring_area(&self.pts(p).iter().map(|q| [q[0], q[1]]).collect::<Vec<_>>())
                }
                Facing::Clipped => any_clipped = true,
                Facing::EdgeOn => {}
            }
        }
        if area > 0.0 {
            Facing::Front
        } else if area < 0.0 {
            Facing::Back
        } else if any_clipped {
            Facing::Clipped
        } else {
            Facing::EdgeOn
        }
    }

    /// True when some piece of face `f` can hide something (projected, not culled, not
    /// edge-on).
    pub(crate) fn face_is_occluder(&self, f: FaceId) -> bool {
        self.pieces_of(f).any(|p| self.piece(p).is_occluder())
    }

    /// The world points of all pieces of face `f` (the face's own corners when it is one piece).
    pub(crate) fn face_world_pts(&self, f: FaceId) -> Vec<P3> {
        self.pieces_of(f)
            .flat_map(|p| self.world_pts(p).iter().copied())
            .collect()
    }

    /// The leaf object of face `f` (which must have pieces).
    pub(crate) fn leaf_of_face(&self, f: FaceId) -> &LeafInfo {
        &self.leaves[self.leaf_index_of_face(f) as usize]
    }

    /// The index in [`ScreenFaces::leaves`] of face `f`'s leaf (`f` must have pieces).
    pub(crate) fn leaf_index_of_face(&self, f: FaceId) -> u32 {
        self.piece(PieceId(self.face_starts[f.index()])).leaf
    }

    /// The corners of piece `p`: their indices in `world` and `points`.
    #[inline]
    pub(crate) fn corners(&self, p: PieceId) -> &[u32] {
        let pc = self.piece(p);
        &self.corner_at[pc.start as usize..(pc.start + pc.len) as usize]
    }

    /// The projected points (x, y, depth) of piece `p`.
    #[inline]
    pub(crate) fn pts(&self, p: PieceId) -> Corners<'_, [f64; 3]> {
        Corners::new(self.corners(p), &self.points)
    }

    /// The projected ring of piece `p` in (x, y), counter-clockwise.
    pub(crate) fn ring_ccw(&self, p: PieceId) -> Vec<Pt2> {
        let mut r: Vec<Pt2> = self.pts(p).iter().map(|q| [q[0], q[1]]).collect();
        if self.piece(p).facing == Facing::Back {
            r.reverse();
        }
        r
    }

    /// The world points of piece `p`.
    #[inline]
    pub(crate) fn world_pts(&self, p: PieceId) -> Corners<'_> {
        Corners::new(self.corners(p), &self.world)
    }

    /// The three world reference points of piece `p`'s plane.
    pub(crate) fn plane_refs(&self, p: PieceId) -> [P3; 3] {
        let w = self.world_pts(p);
        self.piece(p).refs.map(|k| w[k as usize])
    }

    /// The factor that makes `orient3d` over piece `p`'s [`ScreenFaces::plane_refs`]
    /// positive for points in front of its plane (toward the viewer): from the turn of its
    /// projected reference points and the camera's orientation sign (0 when edge-on).
    pub(crate) fn front_sign(&self, p: PieceId) -> f64 {
        -f64::from(self.piece(p).ref_turn) * self.det_sign
    }

    /// Projects the faces of a leaf, except its `hidden` ones (local indices, ascending: faces
    /// of components the cull found HIDDEN get no pieces).
    ///
    /// The vertices are projected, then the faces, on all threads: a task of faces at a
    /// time into a [`Part`] of its own, a batch of tasks between two appends (the parts held
    /// are a batch's), appended in face order: the tables are those of one thread.
    fn add_leaf(&mut self, li: u32, leaf: &Leaf, camera: &Camera, hidden: &[u32], done: Count) {
        let world_first = self.world.len() as u32;
        if leaf.mesh.vertices.len() <= TASK_FACES {
            self.world.extend(leaf.world_vertices());
        } else {
            let verts = leaf.mesh.vertices.par_iter();
            self.world
                .par_extend(verts.map(|v| leaf.transform.transform_point(v)));
        }
        // Held apart while the parts are appended (their new points after all the tasks).
        let world = std::mem::take(&mut self.world);
        let leaf_world = &world[world_first as usize..];
        // Small leaves stay off the thread pool (a town's thousands would each wait on it).
        let alone = leaf_world.len() <= TASK_FACES;
        let clip_of = |p: &P3| mat_point_dd(&camera.matrix, p);
        let clip: Vec<[(f64, f64); 4]> = if alone {
            leaf_world.iter().map(clip_of).collect()
        } else {
            leaf_world.par_iter().map(clip_of).collect()
        };
        let screen_of = |h: &[(f64, f64); 4]| project_dd(h, camera.projection);
        if alone {
            self.points.extend(clip.iter().map(screen_of));
        } else {
            self.points.par_extend(clip.par_iter().map(screen_of));
        }
        // Each vertex's side of the near plane, exactly (only perspective clips).
        let side = |(p, h): (&P3, &[(f64, f64); 4])| {
            near_side(&camera.matrix, p, h, camera.near) != Ordering::Less
        };
        let front: Vec<bool> = match camera.projection {
            Projection::Orthographic => Vec::new(),
            Projection::Perspective if alone => leaf_world.iter().zip(&clip).map(side).collect(),
            Projection::Perspective => leaf_world.par_iter().zip(&clip).map(side).collect(),
        };
        drop(clip);
        let all_in_front = front.iter().all(|&f| f);
        let points = std::mem::take(&mut self.points);
        // Back faces hide nothing a front face does not, and are hidden themselves, only on a
        // proven solid (prepare) seen from outside its convex hull (every vertex in front of
        // the near plane), or on a capped open mesh so seen, away from its holes.
        let back_cull = BackCull::of_leaf(leaf, camera, all_in_front);
        self.leaves.push(LeafInfo {
            path: leaf.path.clone(),
            first_face: FaceId(leaf.first_face as u32),
            face_count: leaf.mesh.faces.len() as u32,
            world_first,
            occlude_only: false,
        });
        let job = LeafJob {
            li,
            leaf,
            camera,
            front: &front,
            world: leaf_world,
            points: &points[world_first as usize..],
            world_first,
            all_in_front,
            back_cull: &back_cull,
            mirrors: leaf.mirrors(),
            hidden,
        };
        let n = leaf.mesh.faces.len();
        let tasks: Vec<usize> = (0..n).step_by(TASK_FACES).collect();
        let (mut new_world, mut new_points) = (Vec::new(), Vec::new());
        let task = |&lo: &usize| {
            let faces = lo..(lo + TASK_FACES).min(n);
            done.add(faces.len());
            job.part(faces)
        };
        let made = |batch: &[usize]| -> Vec<Part> {
            if batch.len() == 1 {
                batch.iter().map(task).collect()
            } else {
                batch.par_iter().map(task).collect()
            }
        };
        let mut appended = |parts: Vec<Part>, this: &mut ScreenFaces| {
            for part in parts {
                let new_base = (world.len() + new_world.len()) as u32;
                new_world.extend_from_slice(&part.new_world);
                new_points.extend_from_slice(&part.new_points);
                this.append(part, new_base);
            }
        };
        // Each batch's parts are appended (in order, on one thread) while the next batch is
        // made on the others; a leaf of one batch never reaches the thread pool.
        let mut ready: Vec<Part> = Vec::new();
        for batch in tapered(&tasks) {
            ready = if ready.is_empty() {
                made(batch)
            } else {
                let last = std::mem::take(&mut ready);
                rayon::join(|| appended(last, self), || made(batch)).1
            };
        }
        appended(ready, self);
        self.world = world;
        self.world.extend(new_world);
        self.points = points;
        self.points.extend(new_points);
    }

    /// Appends a part's pieces and corners (its new world and screen points, which are to
    /// be numbered from `new_base`, are the caller's to append).
    fn append(&mut self, part: Part, new_base: u32) {
        let corner_base = self.corner_at.len() as u32;
        let piece_base = self.pieces.len() as u32;
        self.corner_at
            .extend(part.corner_at.iter().map(|&c| match new_point(c) {
                Some(k) => new_base + k,
                None => c,
            }));
        self.pieces.extend(part.pieces.into_iter().map(|mut p| {
            p.start += corner_base;
            p
        }));
        self.face_starts
            .extend(part.face_ends.iter().map(|&e| piece_base + e));
        self.ring_indexes.extend(
            part.ring_indexes
                .into_iter()
                .map(|(p, index)| (PieceId(piece_base + p), index)),
        );
    }

    /// The run boxes of piece `p`, when it has more than [`INDEXED_ABOVE`] points.
    pub(crate) fn ring_index(&self, p: PieceId) -> Option<&RingIndex> {
        if self.piece(p).len as usize <= INDEXED_ABOVE {
            return None;
        }
        let k = self.ring_indexes.binary_search_by_key(&p, |e| e.0).ok()?;
        Some(&self.ring_indexes[k].1)
    }
}

/// Faces one thread projects at a time.
const TASK_FACES: usize = 1 << 12;

/// Most tasks projected side by side before their parts are appended (the last batch's are
/// appended alone: a batch of 64 left a quarter of a 1M-face leaf's appending on one thread).
const TASKS_AT_ONCE: usize = 16;

/// `tasks` in batches of at most [`TASKS_AT_ONCE`], each half of those left (one at the
/// least), so that the last batches taper to one task: the last batch's parts are appended
/// on one thread with nothing made beside them (nefertiti's last batch of nine tasks was
/// 1.4 ms of its view stage alone on a thread; a one-task batch is a tenth of that).
fn tapered(tasks: &[usize]) -> impl Iterator<Item = &[usize]> {
    let mut rest = tasks;
    std::iter::from_fn(move || {
        let take = (rest.len() / 2).clamp(1, TASKS_AT_ONCE).min(rest.len());
        let (batch, after) = rest.split_at(take);
        rest = after;
        (!batch.is_empty()).then_some(batch)
    })
}

/// A corner of a [`Part`] naming the part's `k`th new point (one clipping made) is
/// `u32::MAX - k`: no table of world points comes near that length.
fn new_point(c: u32) -> Option<u32> {
    (c > u32::MAX / 2).then(|| u32::MAX - c)
}

/// What projecting the faces of one leaf needs, shared by its tasks.
struct LeafJob<'a> {
    li: u32,
    leaf: &'a Leaf<'a>,
    camera: &'a Camera,
    /// Each vertex's side of the near plane (empty: all in front).
    front: &'a [bool],
    /// World points of the leaf's vertices (from `world_first` in the table).
    world: &'a [P3],
    /// Their screen points.
    points: &'a [[f64; 3]],
    world_first: u32,
    all_in_front: bool,
    back_cull: &'a BackCull<'a>,
    mirrors: bool,
    /// The leaf's hidden faces, local indices ascending.
    hidden: &'a [u32],
}

/// The pieces of a run of faces, made apart: corners name the table's points, or the
/// part's new points ([`new_point`]); piece starts and ids count from the part's own.
#[derive(Default)]
struct Part {
    pieces: Vec<Piece>,
    corner_at: Vec<u32>,
    new_world: Vec<P3>,
    new_points: Vec<[f64; 3]>,
    ring_indexes: Vec<(u32, RingIndex)>,
    /// The part's pieces after each face.
    face_ends: Vec<u32>,
}

impl LeafJob<'_> {
    /// The pieces of the leaf's faces `faces` (local indices).
    fn part(&self, faces: Range<usize>) -> Part {
        let mut part = Part::default();
        let from = self.hidden.partition_point(|&h| (h as usize) < faces.start);
        let mut hidden = self.hidden[from..].iter().peekable();
        let mut scratch = Vec::new();
        for k in faces {
            if hidden.next_if_eq(&&(k as u32)).is_none() {
                self.face(&mut part, k, &mut scratch);
            }
            part.face_ends.push(part.pieces.len() as u32);
        }
        part
    }

    /// Adds the pieces of face `k` (local index) to `part`.
    fn face(&self, part: &mut Part, k: usize, scratch: &mut Vec<[f64; 3]>) {
        let mut idx: FaceIndices = self.leaf.mesh.faces[k].vertices.clone();
        if self.mirrors {
            idx.reverse();
        }
        let id = FaceId((self.leaf.first_face + k) as u32);
        for piece in planar_pieces(&idx, self.world) {
            let mut poly: Vec<Corner> = piece
                .iter()
                .map(|&v| {
                    let f = self.front.get(v as usize).copied().unwrap_or(true);
                    let q = self.points[v as usize];
                    (f, self.world[v as usize], self.world_first + v, q)
                })
                .collect();
            if !self.all_in_front {
                poly = clip_near(&poly, self.camera);
            }
            part.add_piece(id, self.li, &poly, self.camera, self.back_cull, scratch);
        }
    }
}

impl Part {
    fn add_piece(
        &mut self,
        face: FaceId,
        leaf: u32,
        poly: &[Corner],
        camera: &Camera,
        back_cull: &BackCull,
        pts: &mut Vec<[f64; 3]>,
    ) {
        let start = self.corner_at.len() as u32;
        pts.clear();
        for &(_, w, at, q) in poly {
            // A point clipping made joins the part's new points.
            let at = if at == NEW_POINT {
                self.new_world.push(w);
                self.new_points.push(q);
                u32::MAX - (self.new_world.len() as u32 - 1)
            } else {
                at
            };
            self.corner_at.push(at);
            pts.push(q);
        }
        let mut piece = describe(face, pts, start, leaf);
        piece.culled = back_cull.culls(&piece);
        if let (Some(eye), true) = (camera.eye, poly.len() >= 3) {
            // The eye exactly in the piece's plane: edge-on, whatever rounding the divide did.
            let refs = piece.refs.map(|k| poly[k as usize].1);
            if orient3d_refs(&refs, &eye) == 0.0 {
                piece.facing = Facing::EdgeOn;
                piece.culled = false;
            }
        }
        if poly.len() > INDEXED_ABOVE {
            let id = self.pieces.len() as u32;
            self.ring_indexes.push((id, RingIndex::new(pts)));
        }
        self.pieces.push(piece);
    }
}

/// The planar pieces of a face (the warped-face split rule, shared with the exact check in
/// [`crate::exact`]): itself when its vertices lie exactly on one plane (robust
/// orient3d = 0 against three of them), else the triangles of an ear-clipping triangulation.
/// Exact planarity is what makes "G in front of F's plane" and "F behind G's plane" the same
/// question, so VTPs and VISP agree by construction; axis-aligned and primitive faces stay whole.
pub(crate) fn planar_pieces(idx: &[u32], world: &[P3]) -> Vec<Vec<u32>> {
    if idx.len() > 3 {
        let pts: Vec<P3> = idx.iter().map(|&k| world[k as usize]).collect();
        if !exactly_planar(&pts) {
            let tris = crate::scene::triangulate::ear_clip(&pts, &newell(&pts));
            return tris
                .iter()
                .map(|t| t.iter().map(|&i| idx[i]).collect())
                .collect();
        }
    }
    vec![idx.to_vec()]
}

/// True when every point lies exactly on the plane of a well-spread triple of them.
fn exactly_planar(pts: &[P3]) -> bool {
    let arr: Vec<[f64; 3]> = pts.iter().map(|p| [p.x, p.y, p.z]).collect();
    let refs = reference_triple(&arr).map(|k| pts[k as usize]);
    pts.iter().all(|p| orient3d_refs(&refs, p) == 0.0)
}

/// A corner on its way into a piece: in front of the near plane (exact), world point, the
/// world point's index in [`ScreenFaces::world`] ([`NEW_POINT`] for a point clipping made) and,
/// for such a point, its screen point.
type Corner = (bool, P3, u32, [f64; 3]);

/// [`Corner`]'s index of a world point not yet in the table.
const NEW_POINT: u32 = u32::MAX;

/// Sutherland–Hodgman clip of a polygon (world points, exact sides) to w' >= near: each new
/// point is the exact crossing, rounded once in screen and in world coordinates.
fn clip_near(poly: &[Corner], camera: &Camera) -> Vec<Corner> {
    let n = poly.len();
    let mut out = Vec::with_capacity(n + 2);
    for i in 0..n {
        let ((fa, wa, at, sa), (fb, wb, _, _)) = (poly[i], poly[(i + 1) % n]);
        if fa {
            out.push((fa, wa, at, sa));
        }
        if fa != fb {
            let (front, back) = if fa { (&wa, &wb) } else { (&wb, &wa) };
            let (screen, world) = near_crossing(front, back, &camera.matrix, camera.near);
            out.push((true, world, NEW_POINT, screen));
        }
    }
    if out.len() < 3 {
        out.clear();
    }
    out
}

/// Bounds, reference triple, facing and convexity of a projected piece of `face` (not culled:
/// that is the leaf's [`BackCull`]'s to say).
fn describe(face: FaceId, p: &[[f64; 3]], start: u32, leaf: u32) -> Piece {
    let mut f = Piece {
        face,
        start,
        len: p.len() as u32,
        leaf,
        rect: Rect::EMPTY,
        zmin: f64::INFINITY,
        zmax: f64::NEG_INFINITY,
        refs: [0, 0, 0],
        ref_turn: 0,
        facing: Facing::Clipped,
        culled: false,
        convex: false,
    };
    if p.len() < 3 {
        return f;
    }
    for q in p {
        f.rect.add([q[0], q[1]]);
        f.zmin = f.zmin.min(q[2]);
        f.zmax = f.zmax.max(q[2]);
    }
    f.refs = reference_triple(p);
    let [a, b, c] = f.refs.map(|k| [p[k as usize][0], p[k as usize][1]]);
    let turn = orient2d(a, b, c);
    f.ref_turn = (turn > 0.0) as i8 - (turn < 0.0) as i8;
    let ring: Vec<Pt2> = p.iter().map(|q| [q[0], q[1]]).collect();
    let area = if p.len() == 3 { turn } else { ring_area(&ring) };
    f.facing = if turn == 0.0 || area == 0.0 {
        Facing::EdgeOn
    } else if area > 0.0 {
        Facing::Front
    } else {
        Facing::Back
    };
    if f.facing != Facing::EdgeOn {
        let mut r = ring;
        if f.facing == Facing::Back {
            r.reverse();
        }
        f.convex = is_convex_ccw(&r, Strictness::AllowDegenerate);
    }
    f
}

/// Three vertices spanning the face plane well: the first, the farthest from it, and the
/// farthest from the line through those two.
fn reference_triple(p: &[[f64; 3]]) -> [u32; 3] {
    if p.len() == 3 {
        return [0, 1, 2];
    }
    let d2 = |a: &[f64; 3], b: &[f64; 3]| (0..3).map(|k| (a[k] - b[k]).powi(2)).sum::<f64>();
    let i1 = (1..p.len())
        .max_by(|&i, &j| d2(&p[0], &p[i]).total_cmp(&d2(&p[0], &p[j])))
        .unwrap_or(1);
    let e = [p[i1][0] - p[0][0], p[i1][1] - p[0][1], p[i1][2] - p[0][2]];
    let cross2 = |q: &[f64; 3]| {
        let v = [q[0] - p[0][0], q[1] - p[0][1], q[2] - p[0][2]];
        let c = [
            e[1] * v[2] - e[2] * v[1],
            e[2] * v[0] - e[0] * v[2],
            e[0] * v[1] - e[1] * v[0],
        ];
        c[0] * c[0] + c[1] * c[1] + c[2] * c[2]
    };
    let i2 = (1..p.len())
        .filter(|&i| i != i1)
        .max_by(|&i, &j| cross2(&p[i]).total_cmp(&cross2(&p[j])))
        .unwrap_or(2);
    if i1 < i2 {
        [0, i1 as u32, i2 as u32]
    } else {
        [0, i2 as u32, i1 as u32]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The batches hold every task once, in order, at most [`TASKS_AT_ONCE`] at a time, and
    /// end in a batch of one task.
    #[test]
    fn batches_taper_to_one_task() {
        for n in [0usize, 1, 2, 3, 9, 25, 31, 32, 33, 100, 245] {
            let tasks: Vec<usize> = (0..n).collect();
            let batches: Vec<&[usize]> = tapered(&tasks).collect();
            assert_eq!(batches.concat(), tasks, "{n} tasks");
            assert!(batches
                .iter()
                .all(|b| (1..=TASKS_AT_ONCE).contains(&b.len())));
            if n > 0 {
                assert_eq!(batches.last().map(|b| b.len()), Some(1), "{n} tasks");
            }
        }
        let sizes = |n: usize| -> Vec<usize> {
            let tasks: Vec<usize> = (0..n).collect();
            tapered(&tasks).map(<[usize]>::len).collect()
        };
        assert_eq!(sizes(25), [12, 6, 3, 2, 1, 1]);
        assert_eq!(sizes(40)[..2], [16, 12]);
    }

    #[test]
    fn near_clip_cuts_polygon() {
        // w' = −z, near 0.5: (0, 0, 1) is behind, the others in front.
        #[rustfmt::skip]
        let matrix = crate::geom::M4::new(
            1., 0., 0., 0.,
            0., 1., 0., 0.,
            0., 0., 0., 1.,
            0., 0., -1., 0.,
        );
        let cam = Camera {
            matrix,
            projection: Projection::Perspective,
            near: 0.5,
            eye: Some(P3::origin()),
        };
        let corner = |p: P3, at: u32| {
            let h = mat_point_dd(&matrix, &p);
            let f = near_side(&matrix, &p, &h, 0.5) != Ordering::Less;
            (f, p, at, [0.0; 3])
        };
        let poly = [
            corner(P3::new(0., 0., 1.), 0),
            corner(P3::new(1., 0., -1.), 1),
            corner(P3::new(0., 1., -1.), 2),
        ];
        let c = clip_near(&poly, &cam);
        assert_eq!(c.len(), 4);
        // The corners kept keep their points' indices; the two cut points are new, on the
        // near plane (z = −0.5), exactly.
        let at: Vec<u32> = c.iter().map(|e| e.2).collect();
        assert_eq!(at, [NEW_POINT, 1, 2, NEW_POINT]);
        assert_eq!(c[0].1, P3::new(0.75, 0., -0.5));
        assert_eq!(c[0].3, [1.5, 0., 2.]);
        let behind = [
            corner(P3::new(0., 0., -0.1), 0),
            corner(P3::new(1., 0., -0.1), 1),
            corner(P3::new(0., 1., -0.2), 2),
        ];
        assert!(clip_near(&behind, &cam).is_empty());
    }

    /// A grid of many tasks' faces seen in perspective from an eye just above it, so that
    /// the near plane cuts faces in every task: the parts join into consistent tables.
    #[test]
    fn faces_projected_in_parts_make_one_table() {
        use crate::scene::{Mesh, Object};
        let n = 70; // 2 * 70 * 70 = 9,800 faces: three tasks.
        let mut vertices = Vec::new();
        for j in 0..=n {
            for i in 0..=n {
                vertices.push(P3::new(i as f64 / n as f64, 0.0, j as f64 / n as f64));
            }
        }
        let at = |i: usize, j: usize| (j * (n + 1) + i) as u32;
        let mut faces = Vec::new();
        for j in 0..n {
            for i in 0..n {
                faces.push(vec![at(i, j), at(i, j + 1), at(i + 1, j + 1)]);
                faces.push(vec![at(i, j), at(i + 1, j + 1), at(i + 1, j)]);
            }
        }
        let mesh = Mesh::from_polygons(vertices, faces, &mut Vec::new()).unwrap();
        let scene = Scene::new(Object::from_mesh("grid", mesh), "grid".into());
        let eye = P3::new(0.5, 0.05, -0.2);
        let camera =
            Camera::perspective(eye, P3::new(0.5, 0.0, 1.0), crate::V3::y(), 90.0, 0.3).unwrap();
        let sf = ScreenFaces::build(&scene, &camera);
        assert_eq!(sf.face_count(), 2 * n * n);
        assert_eq!(sf.world.len(), sf.points.len());
        let vertices = (n + 1) * (n + 1);
        let mut made = 0;
        for p in sf.piece_ids() {
            let piece = sf.piece(p);
            let mut rect = Rect::EMPTY;
            for &c in sf.corners(p) {
                let q = sf.points[c as usize];
                rect.add([q[0], q[1]]);
                if c as usize >= vertices {
                    // A point clipping made: on the near plane, projected where it is.
                    made += 1;
                    let h = camera.clip_coords(&sf.world[c as usize]);
                    assert!((h[3] - camera.near).abs() < 1e-12, "{h:?}");
                    let r = camera.project(&sf.world[c as usize]);
                    assert!(
                        (r[0] - q[0]).abs() + (r[1] - q[1]).abs() < 1e-9,
                        "{r:?} {q:?}"
                    );
                }
            }
            if piece.facing != Facing::Clipped {
                assert_eq!(rect, piece.rect);
            }
        }
        assert!(made > 100, "only {made} points made by clipping");
        let starts = &sf.face_starts;
        assert!(starts.windows(2).all(|w| w[0] <= w[1]));
        assert_eq!(*starts.last().unwrap() as usize, sf.pieces.len());
    }

    #[test]
    fn facing_of_ccw_cw_and_edge_on() {
        let ccw = [[0., 0., 0.], [1., 0., 0.], [0., 1., 0.]];
        assert_eq!(describe(FaceId(0), &ccw, 0, 0).facing, Facing::Front);
        let cw = [[0., 0., 0.], [0., 1., 0.], [1., 0., 0.]];
        let mut f = describe(FaceId(0), &cw, 0, 0);
        assert_eq!(f.facing, Facing::Back);
        assert!(!f.culled && f.is_occluder());
        f.culled = BackCull::All.culls(&f);
        assert!(f.culled && !f.is_occluder());
        let edge = [[0., 0., 0.], [1., 0., 0.], [2., 0., 1.]];
        assert_eq!(describe(FaceId(0), &edge, 0, 0).facing, Facing::EdgeOn);
    }
}
