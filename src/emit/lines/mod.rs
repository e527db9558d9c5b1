//! Hidden-line geometry: the line drawing, the visible (and hidden) part of every edge,
//! computed exactly from the VTPs of the faces beside it, chained into polylines and ordered
//! for a pen plotter.
//!
//! - [`edges`]: which edges a mesh has and which of them are drawn.
//! - [`world`]: the faces in world coordinates; [`intersect`]: where faces cross each other.
//! - [`clip_segment`], [`region`]: the exact segment-against-region test.
//! - [`once`]: every piece of screen line stroked once; [`marks`]: face markings.
//!
//! An edge is visible where it lies on the closed visible region of a face beside it; its
//! hidden part is the rest of it. Edge-on faces have empty VTPs, so the other face decides.
//! Where several edges project onto one screen line, the line is stroked once
//! ([`once`]).

pub(crate) mod clip_segment;
pub(crate) mod edges;
pub(crate) mod intersect;
pub(crate) mod marks;
pub(crate) mod once;
pub(crate) mod region;
pub(crate) mod world;

use std::borrow::Cow;
use std::collections::BTreeMap;
use std::sync::OnceLock;

use rayon::prelude::*;

use crate::count::Count;
use crate::geom::poly2::Pt2;
use crate::geom::P3;
use crate::progress::{Phase, Progress, Stage};
use crate::scene::{FaceId, Scene};
use crate::view::{Camera, Projection, View};
use crate::visibility::Visibility;

use self::clip_segment::{at, complement, intervals_in, intervals_in_region, union, Interval};
use self::edges::{mesh_edges, Edge, EdgeKind, EdgeOptions};
use self::intersect::intersection_edges;
use self::once::{stroke_once, Ranked};
use self::region::Region;
use self::world::WorldFaces;
use crate::emit::plot::chain::{chain, order};
use crate::emit::write::json::Lines;

/// Options of the line drawing.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct LineOptions {
    /// Which edges.
    pub edges: EdgeOptions,
    /// Compute hidden parts too.
    pub hidden: bool,
}

/// One polyline of the drawing.
#[derive(Debug, Clone, PartialEq)]
pub struct Stroke {
    /// Leaf object it belongs to.
    pub leaf: u32,
    /// What kind of line.
    pub kind: EdgeKind,
    /// Screen points.
    pub pts: Vec<Pt2>,
}

/// The polylines of a view, grouped by (leaf, kind) in that order, each group plotter-ordered.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Drawing {
    /// Visible polylines.
    pub visible: Vec<Stroke>,
    /// Hidden polylines (empty unless asked for).
    pub hidden: Vec<Stroke>,
    /// Object path of every leaf (strokes name their leaf by index here).
    pub leaf_paths: Vec<String>,
}

impl Drawing {
    /// The bare polylines, for JSON.
    pub(crate) fn lines(&self) -> Lines {
        let pts = |v: &[Stroke]| v.iter().map(|s| s.pts.clone()).collect();
        Lines {
            visible: pts(&self.visible),
            hidden: pts(&self.hidden),
        }
    }
}

impl Drawing {
    /// Total screen length of the visible strokes.
    pub fn visible_length(&self) -> f64 {
        total_length(&self.visible)
    }
}

impl Camera {
    /// The screen segment (x, y, depth) of the world segment a → b, cut at the near plane
    /// (perspective) exactly as a drawing cuts it; None when nothing of it is in front.
    pub fn project_segment(&self, a: &P3, b: &P3) -> Option<[[f64; 3]; 2]> {
        project_segment_depth(self, a, b)
    }
}

impl Visibility {
    /// The visible parts of the screen segment a → b lying on `faces`, as sorted disjoint
    /// parameter intervals [t0, t1] of [0, 1]: where it is on the closed visible region of
    /// any of them (as a drawing clips an edge).
    pub fn segment_intervals(&self, a: [f64; 2], b: [f64; 2], faces: &[FaceId]) -> Vec<[f64; 2]> {
        visible_intervals(a, b, faces, self)
    }
}

/// The line drawing of a solved view: mesh edges and intersection curves.
///
/// As the lines stage's phases, each counted in `progress`: [`Phase::World`] and
/// [`Phase::Edges`] and [`Phase::Intersections`] by faces, then [`Phase::Clip`] by edges.
pub(crate) fn draw(
    scene: &Scene,
    view: &View,
    vis: &Visibility,
    opts: &LineOptions,
    progress: &Progress,
) -> Drawing {
    progress.enter_phase(Stage::Lines, Phase::World, scene.face_count());
    let world = WorldFaces::build(scene, Some(&view.screen), progress.count());
    progress.enter_phase(Stage::Lines, Phase::Edges, world.faces.len());
    let mut edges = mesh_edges(&world, view, &opts.edges, progress.count());
    progress.enter_phase(Stage::Lines, Phase::Intersections, world.faces.len());
    edges.extend(intersection_edges(
        &world,
        |f| opts.hidden || view.screen.face_is_occluder(f),
        progress.count(),
    ));
    progress.enter_phase(Stage::Lines, Phase::Clip, edges.len());
    let mut drawing = split_edges(view, vis, &edges, opts.hidden, progress.count());
    // Each edge's list of faces freed on all threads.
    crate::chunked::drop_all(edges);
    drawing.leaf_paths = world.paths;
    drawing
}

/// The screen image of the world segment a → b, clipped to the near plane (perspective);
/// None when nothing of it is in front.
pub(crate) fn project_segment(camera: &Camera, a: &P3, b: &P3) -> Option<[Pt2; 2]> {
    project_segment_depth(camera, a, b).map(|[p, q]| [[p[0], p[1]], [q[0], q[1]]])
}

/// [`project_segment`] with the screen depth of each end: (x, y, z).
pub(crate) fn project_segment_depth(camera: &Camera, a: &P3, b: &P3) -> Option<[[f64; 3]; 2]> {
    let (mut ha, mut hb) = (camera.clip_coords(a), camera.clip_coords(b));
    if camera.projection == Projection::Orthographic {
        return Some([[ha[0], ha[1], ha[2]], [hb[0], hb[1], hb[2]]]);
    }
    let near = camera.near;
    let (da, db) = (ha[3] - near, hb[3] - near);
    if da < 0.0 && db < 0.0 {
        return None;
    }
    let cut = |p: [f64; 4], q: [f64; 4], dp: f64, dq: f64| {
        let t = dp / (dp - dq);
        let mut h: [f64; 4] = std::array::from_fn(|k| p[k] + t * (q[k] - p[k]));
        h[3] = near;
        h
    };
    if da < 0.0 {
        ha = cut(ha, hb, da, db);
    } else if db < 0.0 {
        hb = cut(ha, hb, da, db);
    }
    let s = |h: [f64; 4]| [h[0] / h[3], h[1] / h[3], h[2] / h[3]];
    Some([s(ha), s(hb)])
}

/// Visible intervals of the screen segment a → b: on the closed VTP of any of `faces`.
pub(crate) fn visible_intervals(
    a: Pt2,
    b: Pt2,
    faces: &[FaceId],
    vis: &Visibility,
) -> Vec<Interval> {
    let lists: Vec<Vec<Interval>> = faces
        .iter()
        .map(|&f| intervals_in(a, b, &vis.face(f).visible()))
        .collect();
    union(&lists)
}

/// The VTP of every face an edge lies on as an indexed [`Region`], made when first asked
/// for: the edges of one face are clipped against its region many times. Only the faces of
/// the edges get a slot (a terrain's few feature lines touch few of its faces).
struct Regions<'v> {
    vis: &'v Visibility,
    /// The faces of the edges, ascending, once each.
    faces: Vec<FaceId>,
    /// Their regions, beside `faces`.
    made: Vec<OnceLock<Region<'v>>>,
}

impl<'v> Regions<'v> {
    fn new(vis: &'v Visibility, edges: &[Edge]) -> Self {
        let chunk = crate::chunked::CHUNK;
        let mut faces: Vec<FaceId> = crate::chunked::flat_map(edges.len(), chunk, |r, out| {
            out.extend(edges[r].iter().flat_map(|e| e.faces.iter().copied()));
        });
        faces.par_sort_unstable();
        faces.dedup();
        faces.shrink_to_fit();
        let made = crate::chunked::map(faces.len(), |_| OnceLock::new());
        Regions { vis, faces, made }
    }

    /// [`visible_intervals`] with the regions indexed once.
    fn visible_intervals(&self, a: Pt2, b: Pt2, faces: &[FaceId]) -> Vec<Interval> {
        // An edge of a face nothing hides lies on that face's closed VTP from end to end.
        if faces.iter().any(|&f| self.vis.face(f).whole()) {
            return vec![[0.0, 1.0]];
        }
        let lists: Vec<Vec<Interval>> = faces
            .iter()
            .map(
                |&f| match (self.vis.face(f).visible(), self.faces.binary_search(&f)) {
                    (Cow::Borrowed(vtp), Ok(k)) => {
                        intervals_in_region(a, b, self.made[k].get_or_init(|| Region::new(vtp)))
                    }
                    // Not a face of the edges given to `new` (or a region made when read):
                    // indexed for this use alone.
                    (vtp, _) => intervals_in_region(a, b, &Region::new(&vtp)),
                },
            )
            .collect();
        union(&lists)
    }
}

/// Visible and hidden pieces of one edge.
type Pieces = (Vec<[Pt2; 2]>, Vec<[Pt2; 2]>);

fn edge_pieces(view: &View, regions: &Regions, e: &Edge, hidden: bool) -> Pieces {
    let Some([a, b]) = project_segment(&view.camera, &e.ends[0], &e.ends[1]) else {
        return (Vec::new(), Vec::new());
    };
    if a == b {
        return (Vec::new(), Vec::new());
    }
    let shown = regions.visible_intervals(a, b, &e.faces);
    let seg = |iv: &Interval| [at(a, b, iv[0]), at(a, b, iv[1])];
    let keep = |iv: &&Interval| iv[1] > iv[0];
    let vis_pieces = shown.iter().filter(keep).map(seg).collect();
    let hid_pieces = if hidden {
        complement(&shown).iter().filter(keep).map(seg).collect()
    } else {
        Vec::new()
    };
    (vis_pieces, hid_pieces)
}

/// Clips every edge against the VTPs, strokes every piece of line once ([`stroke_once`]),
/// then chains and orders the pieces per (leaf, kind).
///
/// The edges clipped go to `done`, once per chunk.
pub(crate) fn split_edges(
    view: &View,
    vis: &Visibility,
    edges: &[Edge],
    hidden: bool,
    done: Count,
) -> Drawing {
    let regions = Regions::new(vis, edges);
    let pieces: Vec<Pieces> = edges
        .par_iter()
        .enumerate()
        .map(|(i, e)| {
            done.tick(i);
            edge_pieces(view, &regions, e, hidden)
        })
        .collect();
    done.tick_rest(edges.len());
    // Every piece of line once: shared parts go to the higher-ranked edge, and hidden lines
    // give way to visible ones.
    let ranked = |pick: fn(&Pieces) -> &Vec<[Pt2; 2]>| -> Vec<(usize, Ranked)> {
        edges
            .iter()
            .zip(&pieces)
            .enumerate()
            .flat_map(|(k, (e, p))| {
                pick(p).iter().map(move |seg| {
                    let r = Ranked {
                        kind: e.kind,
                        edge: k as u32,
                        seg: *seg,
                    };
                    (k, r)
                })
            })
            .collect()
    };
    let vis_ranked = ranked(|p| &p.0);
    let vis_once = stroke_once(&vis_ranked.iter().map(|x| x.1).collect::<Vec<_>>(), &[]);
    let hid_ranked = ranked(|p| &p.1);
    // The clipped pieces and the indexed regions (a list each) freed on all threads.
    crate::chunked::drop_all(pieces);
    crate::chunked::drop_all(regions.made);
    let hid_once = if hid_ranked.is_empty() {
        Vec::new()
    } else {
        let shown: Vec<[Pt2; 2]> = vis_once.iter().flatten().copied().collect();
        stroke_once(&hid_ranked.iter().map(|x| x.1).collect::<Vec<_>>(), &shown)
    };
    let mut vis_groups: BTreeMap<(u32, EdgeKind), Vec<[Pt2; 2]>> = BTreeMap::new();
    let mut hid_groups: BTreeMap<(u32, EdgeKind), Vec<[Pt2; 2]>> = BTreeMap::new();
    for ((k, _), v) in vis_ranked.iter().zip(vis_once) {
        let e = &edges[*k];
        vis_groups.entry((e.leaf, e.kind)).or_default().extend(v);
    }
    for ((k, _), h) in hid_ranked.iter().zip(hid_once) {
        let e = &edges[*k];
        hid_groups.entry((e.leaf, e.kind)).or_default().extend(h);
    }
    let (visible, hidden) = rayon::join(|| strokes(vis_groups), || strokes(hid_groups));
    Drawing {
        visible,
        hidden,
        leaf_paths: Vec::new(),
    }
}

/// Chained, ordered strokes of grouped segments: the groups on all threads, their strokes
/// joined in group order.
pub(crate) fn strokes(groups: BTreeMap<(u32, EdgeKind), Vec<[Pt2; 2]>>) -> Vec<Stroke> {
    let of_group = |((leaf, kind), segs): ((u32, EdgeKind), Vec<[Pt2; 2]>)| -> Vec<Stroke> {
        let lines = chain(&segs).into_iter().filter(|l| !is_dot(l)).collect();
        order(lines)
            .into_iter()
            .map(|pts| Stroke { leaf, kind, pts })
            .collect()
    };
    let groups: Vec<_> = groups.into_iter().collect();
    let parts: Vec<Vec<Stroke>> = if groups.len() > 1 {
        groups.into_par_iter().map(of_group).collect()
    } else {
        groups.into_iter().map(of_group).collect()
    };
    parts.into_iter().flatten().collect()
}

/// Relative length under which a polyline is rounding noise, not a line: clipping an edge
/// against regions that touch it at a point leaves pieces about 1e-15 long, which a round cap
/// would draw as a dot. No picture (at most 32768 pixels across) resolves 1e-9 of its size.
const DOT: f64 = 1e-9;

/// Whether polyline `pts` is a dot: its length is at most `DOT` (1e-9) times the magnitude of its
/// coordinates (the scale of the rounding that made it).
pub(crate) fn is_dot(pts: &[Pt2]) -> bool {
    let scale = pts.iter().flatten().fold(0.0f64, |m, c| m.max(c.abs()));
    let length: f64 = pts
        .windows(2)
        .map(|w| (w[1][0] - w[0][0]).hypot(w[1][1] - w[0][1]))
        .sum();
    length <= DOT * scale
}

/// Total length of polylines.
pub(crate) fn total_length(strokes: &[Stroke]) -> f64 {
    strokes
        .iter()
        .flat_map(|s| s.pts.windows(2))
        .map(|w| (w[1][0] - w[0][0]).hypot(w[1][1] - w[0][1]))
        .sum()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::V3;
    use crate::scene::testing::unit_cube_scene;
    use crate::visibility::{solve, PassOptions};

    #[test]
    fn cube_from_front_is_a_square_outline() {
        let scene = unit_cube_scene();
        let cam = Camera::orthographic(V3::new(0., 0., -1.), V3::y()).unwrap();
        let view = View::new(&scene, cam);
        let vis = solve(&view, PassOptions::default(), crate::count::Count::NONE);
        let opts = LineOptions {
            hidden: true,
            ..Default::default()
        };
        let d = draw(&scene, &view, &vis, &opts, &Progress::default());
        assert!((total_length(&d.visible) - 4.0).abs() < 1e-12);
        assert_eq!(d.visible.len(), 1, "one closed outline");
        // The back square's outline coincides with the front's; side edges project to points.
        assert!(total_length(&d.hidden) <= 4.0 + 1e-12);
    }

    #[test]
    fn rounding_dots_are_dropped_real_short_lines_kept() {
        let mut groups = BTreeMap::new();
        let real = [[0.0, 0.0], [1e-6, 0.0]];
        let dot = [[0.5, 0.5], [0.5 + 1e-15, 0.5]];
        let far_dot = [[1e6, 1e6], [1e6, 1e6 + 1e-7]];
        groups.insert((0, EdgeKind::Border), vec![real, dot, far_dot]);
        let s = strokes(groups);
        assert_eq!(s.len(), 1);
        let mut kept = s[0].pts.clone();
        kept.sort_by(|a, b| a.partial_cmp(b).unwrap());
        assert_eq!(kept, real.to_vec());
        assert!(is_dot(&[[0.0, 0.0], [0.0, 0.0]]));
        assert!(!is_dot(&[[1e-300, 0.0], [0.0, 0.0]]));
    }

    /// Groups chained and ordered on three threads give the one-thread strokes, in group
    /// order.
    #[test]
    fn strokes_of_groups_on_several_threads_are_the_one_thread_strokes() {
        let mut s = 7u64;
        let mut next = move || {
            s = s
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (s >> 11) as f64 / (1u64 << 53) as f64
        };
        let mut groups = BTreeMap::new();
        for leaf in 0..3 {
            for kind in [EdgeKind::Silhouette, EdgeKind::Crease, EdgeKind::Plain] {
                // Random walks (chains), each from a new start (several strokes to order).
                let mut p = [next(), next()];
                let segs: Vec<[Pt2; 2]> = (0..200)
                    .map(|k| {
                        if k % 17 == 0 {
                            p = [next(), next()];
                        }
                        let q = [p[0] + 0.01 * next(), p[1] + 0.01 * next()];
                        let seg = [p, q];
                        p = q;
                        seg
                    })
                    .collect();
                groups.insert((leaf, kind), segs);
            }
        }
        let pool = crate::chunked::pool;
        let one = pool(1).install(|| strokes(groups.clone()));
        assert!(one.len() > 9, "{} strokes", one.len());
        assert!(one
            .windows(2)
            .all(|w| (w[0].leaf, w[0].kind) <= (w[1].leaf, w[1].kind)));
        assert_eq!(pool(3).install(|| strokes(groups)), one);
    }

    #[test]
    fn perspective_segment_is_cut_at_near_plane() {
        let cam = Camera::perspective(P3::new(0., 0., 5.), P3::new(0., 0., 0.), V3::y(), 40.0, 1.0)
            .unwrap();
        let s = project_segment(&cam, &P3::new(0., 1., 0.), &P3::new(0., 1., 10.)).unwrap();
        assert!(s[1][1].is_finite());
        assert!(project_segment(&cam, &P3::new(0., 1., 6.), &P3::new(0., 1., 10.)).is_none());
    }
}
