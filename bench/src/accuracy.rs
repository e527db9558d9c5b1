//! Time against accuracy: kepler's exact result and the approximate baselines, each timed and
//! measured against the exact visible-polygon set (areas) or the exact visible lines (lengths).
//!
//! Area error of a method that gives every face a region P_f (the z-buffer: the pixels
//! labelled f) against kepler's exact visible region V_f: Σ_f |P_f Δ V_f|, where
//! |P_f Δ V_f| = |P_f| + |V_f| − 2 |P_f ∩ V_f| and |P_f ∩ V_f| is the exact area of V_f inside
//! the pixels labelled f ([`super::coverage`]). It is reported relative to the total visible
//! area Σ_f |V_f| (the area of the picture the scene covers): a pixel given to the wrong face
//! counts twice, once for each face. Line error of the ray sampler: Σ over edges of the length
//! of the symmetric difference between its sampled visible pieces and kepler's exact visible
//! intervals, relative to the exact visible length.

use std::collections::{BTreeMap, BTreeSet};
use std::time::Instant;

use rayon::prelude::*;

use super::coverage::Coverage;
use super::rays::{self, Edge, Interval};
use super::suite::ms_since;
use super::zbuffer::{self, IdBuffer};
use kepler_hsr::check::{multipolygon_area, ring_area, union, xor_area, MultiPolygon};
use kepler_hsr::lines::EdgeOptions;
use kepler_hsr::{
    render, Camera, FaceId, LodOptions, Outputs, RenderOptions, Scene, View, Visibility,
};

/// What produced a point of the time-against-accuracy chart. Each method is one variant: an
/// approximate kepler mode (tribox `--lod PX`) joins as another.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Method {
    /// kepler's exact visible polygons (view + visibility).
    Exact,
    /// kepler's exact visible lines (view + visibility + line drawing).
    ExactLines,
    /// The z-buffer ID buffer at this many pixels along the longer side.
    ZBuffer(u32),
    /// Ray sampling every 1/k of the picture's longer side, for this k.
    Rays(u32),
    /// kepler with `--lod PX` (objects under PX pixels of a [`LOD_SIZE`] picture drawn as
    /// their triboxes), for this PX.
    Lod(u32),
}

/// Picture size the `--lod` points assume.
pub const LOD_SIZE: u32 = 1024;

impl Method {
    /// Name in tables and CSV.
    pub fn name(self) -> &'static str {
        match self {
            Method::Exact => "kepler-exact",
            Method::ExactLines => "kepler-exact-lines",
            Method::ZBuffer(_) => "zbuffer",
            Method::Rays(_) => "rays",
            Method::Lod(_) => "kepler-lod",
        }
    }

    /// The method's parameter (pixels, or steps per picture side; 0 for none).
    pub fn param(self) -> u32 {
        match self {
            Method::Exact | Method::ExactLines => 0,
            Method::ZBuffer(px) => px,
            Method::Rays(k) => k,
            Method::Lod(px) => px,
        }
    }

    /// What its error measures: visible `area` or visible line `length`.
    pub fn metric(self) -> &'static str {
        match self {
            Method::Exact | Method::ZBuffer(_) | Method::Lod(_) => "area",
            Method::ExactLines | Method::Rays(_) => "length",
        }
    }
}

/// The exact answer a subject's methods are measured against (computed once, untimed).
pub struct Reference {
    /// The view.
    pub view: View,
    /// kepler's visible-polygon set.
    pub vis: Visibility,
    /// Every edge's screen segment (x, y, depth).
    pub segs: Vec<Option<[[f64; 3]; 2]>>,
    /// Every edge's exact visible intervals.
    pub exact: Vec<Vec<Interval>>,
    /// Σ_f |V_f|.
    pub visible_area: f64,
    /// Exact visible line length.
    pub visible_length: f64,
    /// Length of kepler's drawn visible lines (`emit::draw`), which must equal the above.
    pub drawn_length: f64,
}

/// The drawing's edges, exactly as a drawing with default options selects them.
pub fn edges(scene: &Scene, view: &View) -> Vec<Edge> {
    EdgeOptions::default()
        .edges(scene, view)
        .into_iter()
        .map(|(ends, faces, _)| (ends, faces))
        .collect()
}

/// Length of a sorted list of disjoint intervals.
fn measure(ivs: &[Interval]) -> f64 {
    ivs.iter().map(|i| (i[1] - i[0]).max(0.0)).sum()
}

/// Length of the symmetric difference of two sorted lists of disjoint intervals.
pub fn interval_sym_diff(a: &[Interval], b: &[Interval]) -> f64 {
    let (mut i, mut j, mut both) = (0, 0, 0.0);
    while i < a.len() && j < b.len() {
        let lo = a[i][0].max(b[j][0]);
        let hi = a[i][1].min(b[j][1]);
        both += (hi - lo).max(0.0);
        if a[i][1] < b[j][1] {
            i += 1;
        } else {
            j += 1;
        }
    }
    (measure(a) + measure(b) - 2.0 * both).max(0.0)
}

impl Reference {
    /// Solves a prepared scene exactly from a camera.
    pub fn new(scene: &Scene, camera: Camera) -> Reference {
        // Every face in the view (no cull), so the baselines' faces are all there.
        let opts = RenderOptions {
            no_inbox: true,
            outputs: Outputs {
                drawing: true,
                ..Outputs::default()
            },
            ..RenderOptions::default()
        };
        let r = render(scene, &camera, &opts, &kepler_hsr::Progress::default())
            .expect("in-memory render without outputs");
        let (view, vis) = (r.view, r.visibility);
        let edges = edges(scene, &view);
        let segs = rays::segments(&view, &edges);
        let exact: Vec<Vec<Interval>> = edges
            .par_iter()
            .zip(&segs)
            .map(|(e, s)| match s {
                Some([a, b]) => vis
                    .segment_intervals([a[0], a[1]], [b[0], b[1]], &e.1)
                    .into_iter()
                    .filter(|iv| iv[1] > iv[0])
                    .collect(),
                None => Vec::new(),
            })
            .collect();
        let visible_length = exact
            .iter()
            .zip(&segs)
            .map(|(iv, s)| measure(iv) * len(s))
            .sum();
        let drawn = r.drawing.map_or(0.0, |d| d.visible_length());
        Reference {
            visible_area: vis.total_area(),
            drawn_length: drawn,
            view,
            vis,
            segs,
            exact,
            visible_length,
        }
    }
}

/// Screen length of an edge segment (0 when absent).
fn len(s: &Option<[[f64; 3]; 2]>) -> f64 {
    s.map_or(0.0, |[a, b]| (b[0] - a[0]).hypot(b[1] - a[1]))
}

/// The median of values (0 for none).
fn median(mut v: Vec<f64>) -> f64 {
    if v.is_empty() {
        return 0.0;
    }
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

/// An error: in total, relative to its reference, and the median relative error of the faces
/// (or edges) with something visible.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Error {
    /// Σ of the symmetric differences (screen area or screen length).
    pub total: f64,
    /// `total` over Σ|V_f| (or the exact visible length).
    pub relative: f64,
    /// Median over faces (edges) with a visible part of |P_f Δ V_f| / |V_f|.
    pub item_median: f64,
}

impl Error {
    /// The error of per-item (difference, reference size) pairs against a reference total.
    fn of_items(items: &[(f64, f64)], reference: f64) -> Error {
        let total: f64 = items.iter().map(|e| e.0).sum();
        let rel = items
            .iter()
            .filter(|e| e.1 > 0.0)
            .map(|e| e.0 / e.1)
            .collect();
        Error {
            total,
            relative: total / reference.max(f64::MIN_POSITIVE),
            item_median: median(rel),
        }
    }
}

/// The z-buffer's area error against the exact visible regions.
pub fn area_error(r: &Reference, buf: &IdBuffer) -> Error {
    let g = buf.grid;
    let px = g.pixel_area();
    let counts = buf.counts(r.vis.face_count());
    let per_face: Vec<(f64, f64)> = (0..r.vis.face_count())
        .into_par_iter()
        .map(|f| {
            let fv = r.vis.face(FaceId(f as u32));
            let p = counts[f] as f64 * px;
            let inside = if counts[f] > 0 && fv.area > 0.0 {
                covered_inside(buf, f as u32, &fv.visible()) * px
            } else {
                0.0
            };
            ((p + fv.area - 2.0 * inside).max(0.0), fv.area)
        })
        .collect();
    Error::of_items(&per_face, r.visible_area)
}

/// Exact area (pixel units) of a face's visible region inside the pixels labelled with it.
fn covered_inside(buf: &IdBuffer, f: u32, visible: &MultiPolygon) -> f64 {
    let g = &buf.grid;
    let rings: Vec<Vec<[f64; 2]>> = visible
        .iter()
        .flatten()
        .map(|r| r.iter().map(|&p| g.pixel_coords(p)).collect())
        .collect();
    let cov = Coverage::of(rings.iter().map(|r| r.as_slice()));
    let mut sum = 0.0;
    for y in 0..cov.rows {
        let j = cov.j0 + y as i64;
        if j < 0 || j as usize >= g.rows {
            continue;
        }
        for x in 0..cov.w {
            let i = cov.i0 + x as i64;
            if i < 0 || i as usize >= g.w {
                continue;
            }
            if buf.ids[j as usize * g.w + i as usize] == f {
                sum += cov.area[y * cov.w + x];
            }
        }
    }
    sum
}

/// The ray sampler's line-length error against the exact visible intervals.
pub fn line_error(r: &Reference, sampled: &[Vec<Interval>]) -> Error {
    let per_edge: Vec<(f64, f64)> = r
        .exact
        .iter()
        .zip(sampled)
        .zip(&r.segs)
        .map(|((e, s), seg)| {
            let l = len(seg);
            (interval_sym_diff(e, s) * l, measure(e) * l)
        })
        .collect();
    Error::of_items(&per_edge, r.visible_length)
}

/// An independent check of kepler's exact areas: |Σ_f |V_f| − |∪_f P_f|| / |∪_f P_f|, the
/// union of every drawable face's projection taken in one boolean call (not the per-face
/// subtraction the renderer does). Zero up to f64 rounding when the VTPs tile the picture.
pub fn union_residual(r: &Reference) -> f64 {
    let rings: Vec<Vec<[f64; 2]>> = r
        .view
        .screen_polygons()
        .map(|(_, corners, _)| ccw(corners.iter().map(|q| [q[0], q[1]]).collect()))
        .collect();
    let union = multipolygon_area(&union(rings.iter(), &zbuffer::scene_rect(&r.view)));
    (r.visible_area - union).abs() / union.max(f64::MIN_POSITIVE)
}

/// A ring made counter-clockwise (a projected face turned away from the viewer runs
/// clockwise).
fn ccw(mut ring: Vec<[f64; 2]>) -> Vec<[f64; 2]> {
    if ring_area(&ring) < 0.0 {
        ring.reverse();
    }
    ring
}

/// One timed run of a method from a prepared scene: milliseconds, and what it computed.
pub enum Output {
    /// kepler's own result (its error is 0 by definition).
    Exact,
    /// A z-buffer.
    Pixels(IdBuffer),
    /// Sampled visible intervals per edge.
    Lines(Vec<Vec<Interval>>),
    /// The exact visible polygons of a substituted scene, and its view.
    Substituted(Box<(View, Visibility)>),
}

/// Runs a method once: (milliseconds, output).
pub fn run(scene: &Scene, camera: Camera, m: Method) -> (f64, Output) {
    let t = Instant::now();
    let kepler = |lod: Option<LodOptions>, drawing: bool| {
        let opts = RenderOptions {
            lod,
            outputs: Outputs {
                drawing,
                ..Outputs::default()
            },
            ..RenderOptions::default()
        };
        render(scene, &camera, &opts, &kepler_hsr::Progress::default())
            .expect("in-memory render without outputs")
    };
    if let Method::Lod(px) = m {
        // As `render --lod` does it: substitute, prepare the substitutes, cull, project, solve.
        let r = kepler(Some(LodOptions::new(px as f64, LOD_SIZE)), false);
        return (
            ms_since(t),
            Output::Substituted(Box::new((r.view, r.visibility))),
        );
    }
    let out = match m {
        Method::Exact | Method::ExactLines => {
            std::hint::black_box(kepler(None, m == Method::ExactLines));
            Output::Exact
        }
        Method::ZBuffer(px) => {
            Output::Pixels(zbuffer::visible_areas(&View::new(scene, camera), px).1)
        }
        Method::Rays(k) => {
            let view = View::new(scene, camera);
            let step = zbuffer::scene_rect(&view).longer_side() / k as f64;
            Output::Lines(rays::sample(&view, &edges(scene, &view), step))
        }
        Method::Lod(_) => unreachable!("handled above"),
    };
    (ms_since(t), out)
}

/// The error of a method's output.
pub fn error(r: &Reference, out: &Output) -> Error {
    match out {
        Output::Exact => Error {
            total: 0.0,
            relative: 0.0,
            item_median: 0.0,
        },
        Output::Pixels(buf) => area_error(r, buf),
        Output::Lines(l) => line_error(r, l),
        Output::Substituted(s) => substitute_error(r, &s.0, &s.1),
    }
}

/// The area error of a substituted scene, object by object: a substitute's faces are not the
/// original's, so what is compared is the visible region of each drawn object (the union of
/// its faces' VTPs; an original leaf belongs to the substitute at its own path or the nearest
/// enclosing one), summed |exact Δ substituted| over Σ|V_f|.
pub fn substitute_error(r: &Reference, view: &View, vis: &Visibility) -> Error {
    let drawn: BTreeSet<&str> = view.object_paths().collect();
    let key = |path: &str| -> String {
        let mut p = path;
        while !drawn.contains(p) {
            match p.rfind('/') {
                Some(i) => p = &p[..i],
                None => return path.to_string(),
            }
        }
        p.to_string()
    };
    let mut regions: BTreeMap<String, [MultiPolygon; 2]> = BTreeMap::new();
    for (k, (v, vw)) in [(&r.vis, &r.view), (vis, view)].into_iter().enumerate() {
        for (id, fv) in v.iter().filter(|f| !f.1.is_empty()) {
            let path = key(vw.face_path(id));
            regions.entry(path).or_default()[k].extend(fv.visible().iter().cloned());
        }
    }
    let diffs: Vec<(f64, f64)> = regions
        .values()
        .map(|[a, b]| (xor_area(a, b), multipolygon_area(a)))
        .collect();
    Error::of_items(&diffs, r.visible_area)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::zbuffer::NONE;

    /// How many pixels no face took.
    fn empty_pixels(buf: &IdBuffer) -> usize {
        buf.ids.iter().filter(|&&i| i == NONE).count()
    }
    use crate::zbuffer::Grid;
    use kepler_hsr::{Mesh, Object, P3, V3};

    #[test]
    fn interval_differences_by_hand() {
        let a = [[0.0, 0.5], [0.75, 1.0]];
        let b = [[0.25, 0.75]];
        // |a| = 0.75, |b| = 0.5, |a ∩ b| = 0.25: 0.75 + 0.5 − 0.5.
        assert_eq!(interval_sym_diff(&a, &b), 0.75);
        assert_eq!(interval_sym_diff(&a, &a), 0.0);
        assert_eq!(interval_sym_diff(&[], &b), 0.5);
    }

    #[test]
    fn symmetric_difference_of_a_square_on_pixels_by_hand() {
        // V = [0.5, 2.5] × [0.5, 1.5] (area 2) on a 4×4 grid of unit pixels; the buffer gives
        // face 0 the pixels (1, 0) and (1, 1): |P| = 2, |P ∩ V| = 0.5 + 0.5 = 1, so
        // |P Δ V| = 2 + 2 − 2 = 2, relative to |V| = 2: 1.
        let grid = Grid {
            x0: 0.,
            y0: 0.,
            h: 1.,
            w: 4,
            rows: 4,
        };
        let mut ids = vec![NONE; 16];
        ids[1] = 0;
        ids[4 + 1] = 0;
        let buf = IdBuffer { grid, ids };
        let v = vec![vec![vec![[0.5, 0.5], [2.5, 0.5], [2.5, 1.5], [0.5, 1.5]]]];
        assert_eq!(covered_inside(&buf, 0, &v), 1.0);
        let mut buf2 = buf.clone();
        // Giving it the six pixels V touches: |P| = 6, |P ∩ V| = 2, |P Δ V| = 4.
        for k in [0, 2, 4, 6] {
            buf2.ids[k] = 0;
        }
        assert_eq!(covered_inside(&buf2, 0, &v), 2.0);
        assert_eq!(empty_pixels(&buf2), 10);
    }

    #[test]
    fn zbuffer_error_shrinks_with_resolution_and_exact_checks_out() {
        // Two unit squares, one over the other's corner, seen from the front.
        let sq = |x: f64, y: f64, z: f64| {
            Mesh::from_polygons(
                vec![
                    P3::new(x, y, z),
                    P3::new(x + 1., y, z),
                    P3::new(x + 1., y + 1., z),
                    P3::new(x, y + 1., z),
                ],
                vec![vec![0, 1, 2, 3]],
                &mut Vec::new(),
            )
            .unwrap()
        };
        let scene = Scene::new(
            Object::group(
                "",
                vec![
                    Object::from_mesh("a", sq(0., 0., 0.)),
                    Object::from_mesh("b", sq(0.3, 0.3, 1.)),
                ],
            ),
            "t".into(),
        );
        let cam = Camera::orthographic(V3::new(0., 0., -1.), V3::y()).unwrap();
        let r = Reference::new(&scene, cam);
        assert!((r.visible_area - (2.0 - 0.49)).abs() < 1e-12);
        assert!(union_residual(&r) < 1e-12);
        assert!((r.visible_length - r.drawn_length).abs() < 1e-9);
        let err = |px| match run(&scene, cam, Method::ZBuffer(px)).1 {
            Output::Pixels(b) => area_error(&r, &b).relative,
            _ => unreachable!(),
        };
        // 10 and 100 pixels over 1.3: pixel edges never meet the squares' edges at 0.3, 1, 1.3.
        let (coarse, fine) = (err(10), err(100));
        assert!(fine < coarse && fine > 0.0, "{coarse} {fine}");
        let lines = |k| match run(&scene, cam, Method::Rays(k)).1 {
            Output::Lines(l) => line_error(&r, &l).relative,
            _ => unreachable!(),
        };
        assert!(lines(1000) <= lines(10));
    }

    #[test]
    fn lod_error_is_zero_for_itself_and_grows_with_the_pixel_size() {
        let ico = Mesh::solid("icosahedron").unwrap();
        let at = |x: f64| nalgebra::Translation3::new(x, 0., 0.).to_homogeneous();
        let proto = std::sync::Arc::new(Object::from_mesh("ico", ico));
        let objs = (0..3)
            .map(|k| Object::instance(format!("i{k}"), proto.clone(), at(3. * k as f64)))
            .collect();
        let mut scene = Scene::new(Object::group("", objs), "t".into());
        kepler_hsr::prepare(
            &mut scene,
            &kepler_hsr::PrepareOptions::default(),
            &kepler_hsr::Progress::default(),
        );
        let cam = Camera::orthographic(V3::new(0.3, -0.2, -1.), V3::y()).unwrap();
        let r = Reference::new(&scene, cam);
        let err = |px| match run(&scene, cam, Method::Lod(px)).1 {
            Output::Substituted(s) => substitute_error(&r, &s.0, &s.1).relative,
            _ => unreachable!(),
        };
        // Nothing is under 1 pixel: nothing is substituted and nothing differs.
        assert_eq!(err(1), 0.0);
        // Everything is under 10000 pixels: each icosahedron is drawn as its tribox, which
        // contains it, so the error is the triboxes' extra area: positive and small.
        let big = err(10_000);
        assert!(big > 0.0 && big < 0.5, "{big}");
        assert_eq!(substitute_error(&r, &r.view, &r.vis).total, 0.0);
    }
}
