//! The edge set of a view: every leaf mesh's undirected edges with the faces beside them, classified.
//!
//! Each shared edge appears once. Kinds: silhouette (the surface folds over it in this view),
//! border (one face beside it, or more than two), crease (dihedral angle above a threshold),
//! plain (any other polygon edge); intersection curves come from [`super::intersect`].

use std::ops::Range;

use rayon::prelude::*;

use crate::count::{Count, Share};
use crate::geom::{P3, V3};
use crate::rank_sort::sort_distinct_by_rank;
use crate::scene::{FaceId, Scene};
use crate::view::{Facing, View};

use super::intersect::intersection_edges;
use super::world::WorldFaces;

/// What a line of the drawing is.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum EdgeKind {
    /// Outline: one face beside it turns toward the viewer, the other away (or is edge-on).
    Silhouette,
    /// Edge of an open surface (one face beside it) or a non-manifold edge (three or more).
    Border,
    /// Dihedral angle between the faces beside it above the crease threshold.
    Crease,
    /// Where two faces cross each other.
    Intersection,
    /// Any other polygon edge.
    Plain,
    /// Where a section plane cut the scene: the outline of a section face, or the cut edge
    /// of an open mesh (drawn with the section pen).
    Section,
}

impl EdgeKind {
    /// Every kind, in drawing order.
    pub const ALL: [EdgeKind; 6] = [
        EdgeKind::Section,
        EdgeKind::Silhouette,
        EdgeKind::Border,
        EdgeKind::Crease,
        EdgeKind::Intersection,
        EdgeKind::Plain,
    ];

    /// Lower-case name (used for SVG ids).
    pub fn name(self) -> &'static str {
        match self {
            EdgeKind::Silhouette => "silhouette",
            EdgeKind::Border => "border",
            EdgeKind::Crease => "crease",
            EdgeKind::Intersection => "intersection",
            EdgeKind::Plain => "plain",
            EdgeKind::Section => "section",
        }
    }
}

/// Which edges a drawing shows (`--edges`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum EdgeSet {
    /// Silhouettes, borders, creases and intersection curves.
    #[default]
    Feature,
    /// Every polygon edge (and intersection curves).
    All,
}

/// Options of the edge set.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EdgeOptions {
    /// Feature edges or all edges.
    pub set: EdgeSet,
    /// Crease threshold: dihedral angle in degrees between face normals.
    pub crease_deg: f64,
}

impl Default for EdgeOptions {
    fn default() -> Self {
        EdgeOptions {
            set: EdgeSet::Feature,
            crease_deg: 30.0,
        }
    }
}

impl EdgeOptions {
    /// The edges a drawing with these options clips in `view` of `scene`: for each, its
    /// world end points, the faces it lies on and its kind; mesh edges first (in order of
    /// first appearance), then the intersection curves of faces that can hide something.
    pub fn edges(&self, scene: &Scene, view: &View) -> Vec<([P3; 2], Vec<FaceId>, EdgeKind)> {
        let world = WorldFaces::build(scene, None, Default::default());
        let mut edges = mesh_edges(&world, view, self, Default::default());
        edges.extend(intersection_edges(
            &world,
            |f| view.screen.face_is_occluder(f),
            Default::default(),
        ));
        edges
            .into_iter()
            .map(|e| (e.ends, e.faces, e.kind))
            .collect()
    }
}

/// One edge (or intersection segment) in world space with the faces beside it.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Edge {
    /// Leaf object the edge is drawn with.
    pub leaf: u32,
    /// World end points.
    pub ends: [P3; 2],
    /// The faces it lies on.
    pub faces: Vec<FaceId>,
    /// Classification.
    pub kind: EdgeKind,
}

/// One traversal of an undirected edge by a face: the edge's key (least vertex first), the
/// corner it starts from and the face. 16 bytes: a 10M-face mesh has 30M of them at once.
#[derive(Clone, Copy, Default)]
struct HalfEdge {
    a: u32,
    b: u32,
    /// The corner the traversal starts from, as an offset in the leaf's corners (so in the
    /// leaf's face order): `base + seq` in [`WorldFaces::vertices`], `base` the leaf's first.
    seq: u32,
    face: u32,
}

impl HalfEdge {
    /// The face's corner the traversal starts from (it runs to the next), in a leaf whose
    /// first corner is `base`.
    fn at(&self, world: &WorldFaces, base: usize) -> usize {
        base + self.seq as usize - world.faces[self.face as usize].first
    }

    /// Whether the traversal goes from `a` to `b`.
    fn fwd(&self, world: &WorldFaces, base: usize) -> bool {
        world.vertices[base + self.seq as usize] == self.a
    }
}

/// The mesh edges of every leaf (in order of first appearance), classified, filtered by `opts.set`.
///
/// The world faces whose edges are done go to `done`: each leaf's faces as its edges are
/// found, grouped and classified.
pub(crate) fn mesh_edges(
    world: &WorldFaces,
    view: &View,
    opts: &EdgeOptions,
    done: Count,
) -> Vec<Edge> {
    let cos_crease = opts.crease_deg.to_radians().cos();
    let all = world.faces.len().max(1) as f64;
    let share = Share::new(done, world.faces.len());
    // Each face's facing once (a warped face's is a sum over its pieces).
    let facing: Vec<Facing> = (0..view.screen.face_count())
        .into_par_iter()
        .map(|f| view.screen.face_facing(FaceId(f as u32)))
        .collect();
    share.reach(FACING_SHARE);
    let mut out = Vec::new();
    let mut start = 0;
    while start < world.faces.len() {
        let leaf = world.faces[start].leaf;
        // A leaf's faces are one run, leaves in ascending order.
        let end = start + world.faces[start..].partition_point(|f| f.leaf == leaf);
        let at = |f: usize| FACING_SHARE + (1.0 - FACING_SHARE) * f as f64 / all;
        let span = share.span(at(start), at(end));
        // The leaf's first corner: half-edges name their corners from it.
        let base = world.faces[start].first;
        let half = half_edges(world, start, end, base);
        let edge = |g: Range<u32>| {
            let adj = &half[g.start as usize..g.end as usize];
            // An edge only of faces a section cut removed is not in the scene (not even as a
            // hidden line).
            if removed_only(world, adj) {
                return None;
            }
            let mut kind = classify(adj, world, base, &facing, cos_crease);
            (opts.set == EdgeSet::All || kind != EdgeKind::Plain).then(|| {
                let h = &adj[0];
                let pts = world.points_of(h.face as usize);
                let at = h.at(world, base);
                let (i, j) = (at, (at + 1) % pts.len());
                if on_section(world, h.face, kind, [&pts[i], &pts[j]]) {
                    kind = EdgeKind::Section;
                }
                Edge {
                    leaf,
                    ends: if h.fwd(world, base) {
                        [pts[i], pts[j]]
                    } else {
                        [pts[j], pts[i]]
                    },
                    faces: faces_beside(adj),
                    kind,
                }
            })
        };
        span.reach(0.25);
        let groups = edge_groups(&half);
        span.reach(0.5);
        let classified = span.span(0.5, 1.0).steps(groups.len());
        let counted = |(i, g): (usize, u32)| {
            classified.tick(i);
            edge(group_at(&half, g))
        };
        if groups.len() > PARALLEL_ABOVE {
            // In parallel, in the same order.
            let found: Vec<Edge> = groups
                .into_par_iter()
                .enumerate()
                .filter_map(counted)
                .collect();
            // The first leaf's list is the list (a copy of 300,000 edges was 0.7 ms on one
            // thread).
            if out.is_empty() {
                out = found;
            } else {
                out.extend(found);
            }
        } else {
            out.extend(groups.into_iter().enumerate().filter_map(counted));
        }
        span.finish();
        start = end;
    }
    share.finish();
    out
}

/// The part of [`mesh_edges`]'s count that every face's facing fills (the rest is
/// the leaves' edges, by faces).
const FACING_SHARE: f64 = 0.1;

/// Above this many edges a leaf's are classified on all threads (the pool's overhead would
/// outweigh the work of a small leaf).
const PARALLEL_ABOVE: usize = 4096;

/// Faces (or half-edges) per chunk of [`half_edges`] (and [`edge_groups`]).
const CHUNK: usize = crate::chunked::CHUNK;

/// Every traversal of an edge by the faces `start..end` (one leaf), grouped by edge, each
/// group in face order; `base` is the leaf's first corner in [`WorldFaces::vertices`].
fn half_edges(world: &WorldFaces, start: usize, end: usize, base: usize) -> Vec<HalfEdge> {
    // In fixed chunks of faces on all threads, each in its place (counted first), in face
    // order.
    let faces = |r: Range<usize>| start + r.start..start + r.end;
    let kept = |v: &[u32], i: usize| v[i] != v[(i + 1) % v.len()];
    let size = |r: Range<usize>| {
        faces(r)
            .map(|f| {
                let v = world.vertices_of(f);
                (0..v.len()).filter(|&i| kept(v, i)).count()
            })
            .sum()
    };
    let mut half = crate::chunked::fill(end - start, CHUNK, size, |r, half| {
        let mut at = 0;
        for f in faces(r) {
            let first = world.faces[f].first - base;
            let v = world.vertices_of(f);
            for i in (0..v.len()).filter(|&i| kept(v, i)) {
                let (p, q) = (v[i], v[(i + 1) % v.len()]);
                half[at] = HalfEdge {
                    a: p.min(q),
                    b: p.max(q),
                    seq: (first + i) as u32,
                    face: f as u32,
                };
                at += 1;
            }
        }
    });
    // Counted by the lesser vertex (a leaf's vertices are about half its faces); seq is
    // unique: the order is the same however the sort runs, and it needs no copy of the list.
    sort_distinct_by_rank(&mut half, |h| h.a, |h| (h.b, h.seq));
    half
}

/// The faces beside an edge, each once, in face order: a face that runs along one edge many
/// times (`f 1 2 3 1 2 3 ...`, winding round a triangle) is clipped against once, not once
/// per traversal (which made the lines stage quadratic in the face's corners).
fn faces_beside(adj: &[HalfEdge]) -> Vec<FaceId> {
    let mut faces: Vec<FaceId> = adj.iter().map(|h| FaceId(h.face)).collect();
    // A group is in (face, corner) order: one face's traversals are neighbours.
    faces.dedup();
    faces
}

/// The edges in grouped half-edges, each as where its group starts ([`group_at`] gives the
/// group), in order of first appearance: 4 bytes an edge, not a range's 8 (a 10M-face
/// terrain has 15M edges, and the lines stage's peak was here with its half-edges).
fn edge_groups(half: &[HalfEdge]) -> Vec<u32> {
    // Where each edge's group starts, found in fixed chunks on all threads (counted, then
    // written in place: no parts beside the list).
    let n = half.len();
    let starts_at =
        |i: &usize| *i == 0 || (half[*i].a, half[*i].b) != (half[i - 1].a, half[i - 1].b);
    let mut starts: Vec<u32> = crate::chunked::fill(
        n,
        CHUNK,
        |r| r.filter(starts_at).count(),
        |r, out| {
            for (o, i) in out.iter_mut().zip(r.filter(starts_at)) {
                *o = i as u32;
            }
        },
    );
    // Each group's first seq is unique and below the leaf's corners: counted.
    sort_distinct_by_rank(&mut starts, |&g| half[g as usize].seq, |_| ());
    starts
}

/// The index range of the group of grouped half-edges that starts at `start`: up to the
/// first half-edge of another edge.
fn group_at(half: &[HalfEdge], start: u32) -> Range<u32> {
    let s = start as usize;
    let edge = (half[s].a, half[s].b);
    let len = half[s + 1..]
        .iter()
        .take_while(|h| (h.a, h.b) == edge)
        .count();
    start..start + 1 + len as u32
}

/// True when every face beside an edge was removed whole by a section cut.
fn removed_only(world: &WorldFaces, adj: &[HalfEdge]) -> bool {
    world.section.as_deref().is_some_and(|info| {
        adj.iter()
            .all(|h| info.removed.binary_search(&h.face).is_ok())
    })
}

/// True when an outline or border edge of face `face` lies where a section cut the scene:
/// an edge of a section face, or one of a cut leaf with both ends on the cut (corners on a
/// plane, crossings the cut made).
fn on_section(world: &WorldFaces, face: u32, kind: EdgeKind, ends: [&P3; 2]) -> bool {
    let Some(info) = world.section.as_deref() else {
        return false;
    };
    if !matches!(kind, EdgeKind::Border | EdgeKind::Silhouette) {
        return false;
    }
    info.is_section(face) || (info.in_cut_leaf(face) && info.on_one_plane(ends[0], ends[1]))
}

/// Kind of a mesh edge in this view.
fn classify(
    adj: &[HalfEdge],
    world: &WorldFaces,
    base: usize,
    facing: &[Facing],
    cos_crease: f64,
) -> EdgeKind {
    let [(f, f_fwd), (g, g_fwd)] = match adj {
        [x, y] => [(x.face, x.fwd(world, base)), (y.face, y.fwd(world, base))],
        _ => return EdgeKind::Border,
    };
    let (ff, fg) = (facing[f as usize], facing[g as usize]);
    let drawn = |x: Facing| matches!(x, Facing::Front | Facing::Back);
    if ff == Facing::Clipped || fg == Facing::Clipped {
        return EdgeKind::Border;
    }
    if (ff == Facing::EdgeOn && drawn(fg)) || (fg == Facing::EdgeOn && drawn(ff)) {
        return EdgeKind::Silhouette;
    }
    // Consistently oriented neighbours traverse the edge in opposite directions.
    let consistent = f_fwd != g_fwd;
    if drawn(ff) && drawn(fg) && ((ff != fg) == consistent) {
        return EdgeKind::Silhouette;
    }
    let (nf, mut ng) = (
        world.faces[f as usize].normal,
        world.faces[g as usize].normal,
    );
    if !consistent {
        ng = -ng;
    }
    if is_crease(&nf, &ng, cos_crease) {
        EdgeKind::Crease
    } else {
        EdgeKind::Plain
    }
}

/// True when the angle between two (non-zero) normals exceeds the threshold given by its cosine.
fn is_crease(n1: &V3, n2: &V3, cos_crease: f64) -> bool {
    let l = n1.norm() * n2.norm();
    l > 0.0 && n1.dot(n2) < cos_crease * l
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::testing::unit_cube_scene;
    use crate::view::Camera;
    /// A height field of `n` by `n` cells, two triangles each: an open mesh of one hole.
    fn height_field(n: u32) -> crate::scene::Mesh {
        let h = |x: u32, y: u32| ((x * 7 + y * 13) % 5) as f64 * 0.1 + (x as f64 * 0.3).sin();
        let vertices = (0..=n)
            .flat_map(|y| (0..=n).map(move |x| crate::geom::P3::new(x as f64, y as f64, h(x, y))))
            .collect();
        let at = |x: u32, y: u32| y * (n + 1) + x;
        let faces = (0..n)
            .flat_map(|y| (0..n).map(move |x| (x, y)))
            .flat_map(|(x, y)| {
                [
                    [at(x, y), at(x + 1, y), at(x + 1, y + 1)],
                    [at(x, y), at(x + 1, y + 1), at(x, y + 1)],
                ]
            })
            .map(crate::scene::Face::new)
            .collect();
        crate::scene::Mesh {
            vertices,
            faces,
            ..Default::default()
        }
    }

    #[test]
    fn edges_found_on_several_threads_are_the_one_thread_edges() {
        // Half-edges and their groups made in many chunks on three threads.
        let mesh = height_field(160);
        let faces = mesh.faces.len();
        let obj = crate::scene::Object::from_mesh("field", mesh);
        let scene = Scene::new(crate::scene::Object::group("", vec![obj]), "t".into());
        let view = View::new(&scene, Camera::three_quarter());
        let world = WorldFaces::build(&scene, None, crate::count::Count::NONE);
        let opts = EdgeOptions {
            set: EdgeSet::All,
            crease_deg: 30.0,
        };
        let pool = crate::chunked::pool;
        let edges = || mesh_edges(&world, &view, &opts, crate::count::Count::NONE);
        let one = pool(1).install(edges);
        assert!(faces > CHUNK && one.len() > faces, "{} edges", one.len());
        assert_eq!(pool(3).install(edges), one);
    }

    fn count(edges: &[Edge], kind: EdgeKind) -> usize {
        edges.iter().filter(|e| e.kind == kind).count()
    }

    #[test]
    fn cube_three_quarter_has_six_silhouette_edges() {
        let scene = unit_cube_scene();
        let view = View::new(&scene, Camera::three_quarter());
        let world = WorldFaces::build(&scene, None, crate::count::Count::NONE);
        let opts = EdgeOptions {
            set: EdgeSet::All,
            crease_deg: 30.0,
        };
        let all = mesh_edges(&world, &view, &opts, crate::count::Count::NONE);
        assert_eq!(all.len(), 12, "each shared edge once");
        assert!(all.iter().all(|e| e.faces.len() == 2));
        assert_eq!(count(&all, EdgeKind::Silhouette), 6);
        assert_eq!(count(&all, EdgeKind::Crease), 6);
        let feat = mesh_edges(
            &world,
            &view,
            &EdgeOptions::default(),
            crate::count::Count::NONE,
        );
        assert_eq!(feat.len(), 12);
        let none = EdgeOptions {
            set: EdgeSet::Feature,
            crease_deg: 95.0,
        };
        assert_eq!(
            mesh_edges(&world, &view, &none, crate::count::Count::NONE).len(),
            6
        );
    }

    #[test]
    fn open_square_has_four_borders() {
        let scene = crate::scene::testing::unit_square_scene(vec![vec![0, 1, 2], vec![0, 2, 3]]);
        let view = View::new(&scene, Camera::three_quarter());
        let world = WorldFaces::build(&scene, None, crate::count::Count::NONE);
        let opts = EdgeOptions {
            set: EdgeSet::All,
            crease_deg: 30.0,
        };
        let e = mesh_edges(&world, &view, &opts, crate::count::Count::NONE);
        assert_eq!(e.len(), 5);
        assert_eq!(count(&e, EdgeKind::Border), 4);
        assert_eq!(count(&e, EdgeKind::Plain), 1);
        assert_eq!(
            mesh_edges(
                &world,
                &view,
                &EdgeOptions::default(),
                crate::count::Count::NONE
            )
            .len(),
            4
        );
    }
}
