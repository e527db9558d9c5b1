//! Line drawings against independent answers: convex solids (an edge is visible exactly when a
//! face beside it is front-facing), visible + hidden = all (non-convex scenes), and the
//! intersection segment of two crossing faces, endpoints worked by hand.

use std::collections::HashMap;
use std::path::PathBuf;

use super::common::*;
use crate::emit::lines::edges::{mesh_edges, EdgeKind, EdgeOptions, EdgeSet};
use crate::emit::lines::intersect::intersection_edges;
use crate::emit::lines::world::WorldFaces;
use crate::emit::lines::{project_segment, total_length, LineOptions};
use crate::geom::{PolyMesh, P3, V3};
use crate::scene::Scene;
use crate::view::{Camera, View};

fn all_edges(hidden: bool) -> LineOptions {
    LineOptions {
        edges: EdgeOptions {
            set: EdgeSet::All,
            crease_deg: 30.0,
        },
        hidden,
    }
}

fn load(path: &std::path::Path) -> Scene {
    super::common::load(path)
}

/// Icosphere: an icosahedron subdivided `n` times, pushed onto the unit sphere.
fn icosphere(n: u32) -> PolyMesh {
    let ico = crate::primitives::by_name("icosahedron").unwrap();
    let mut verts: Vec<P3> = ico
        .vertices
        .iter()
        .map(|p| P3::from(p.coords.normalize()))
        .collect();
    let mut faces: Vec<Vec<u32>> = ico.faces.clone();
    for _ in 0..n {
        let mut mid: HashMap<(u32, u32), u32> = HashMap::new();
        let mut next = Vec::new();
        for f in &faces {
            let mut m = |a: u32, b: u32| {
                *mid.entry((a.min(b), a.max(b))).or_insert_with(|| {
                    let p = (verts[a as usize].coords + verts[b as usize].coords).normalize();
                    verts.push(P3::from(p));
                    verts.len() as u32 - 1
                })
            };
            let (a, b, c) = (f[0], f[1], f[2]);
            let (ab, bc, ca) = (m(a, b), m(b, c), m(c, a));
            next.extend([
                vec![a, ab, ca],
                vec![b, bc, ab],
                vec![c, ca, bc],
                vec![ab, bc, ca],
            ]);
        }
        faces = next;
    }
    PolyMesh::new(verts, faces)
}

/// Analytic visible length of a closed convex scene's edges: an edge counts when a face
/// beside it faces the viewer (world normal against the view direction).
fn convex_visible_length(scene: &Scene, cam: &Camera, dir: V3) -> f64 {
    let mut edges: HashMap<(usize, u32, u32), (P3, P3, bool)> = HashMap::new();
    for (li, leaf) in scene.leaves().iter().enumerate() {
        for f in &leaf.mesh.faces {
            let p: Vec<P3> = f.vertices.iter().map(|&k| leaf.world_vertex(k)).collect();
            let n = (p[1] - p[0]).cross(&(p[2] - p[0]));
            let front = n.dot(&dir) < 0.0;
            for i in 0..p.len() {
                let (a, b) = (f.vertices[i], f.vertices[(i + 1) % p.len()]);
                let e = edges.entry((li, a.min(b), a.max(b))).or_insert((
                    p[i],
                    p[(i + 1) % p.len()],
                    false,
                ));
                e.2 |= front;
            }
        }
    }
    edges
        .values()
        .filter(|e| e.2)
        .map(|(a, b, _)| {
            let [p, q] = project_segment(cam, a, b).unwrap();
            (q[0] - p[0]).hypot(q[1] - p[1])
        })
        .sum()
}

fn check_convex(scene: &Scene, name: &str) {
    for dir in [V3::new(-0.55, -0.5, -0.75), V3::new(0.3, 0.9, -0.2)] {
        let cam = Camera::orthographic(dir, V3::y()).unwrap();
        let (_, d) = drawing(scene, cam, all_edges(true));
        let got = total_length(&d.visible);
        let want = convex_visible_length(scene, &cam, dir);
        assert!(
            (got - want).abs() <= 1e-9 * want,
            "{name}: visible length {got} != {want}"
        );
    }
}

#[test]
fn convex_solids_visible_length_is_analytic() {
    check_convex(&scene(vec![("ico", prim(icosphere(2)))]), "icosphere");
    for name in ["cube", "dodecahedron", "truncated_icosahedron", "snub_cube"] {
        let m = prim(crate::primitives::by_name(name).unwrap());
        check_convex(&scene(vec![(name, m)]), name);
    }
}

#[test]
fn ico5_visible_length_is_analytic() {
    let Some(p) = model("ico5.obj") else { return };
    check_convex(&load(&p), "ico5");
}

/// Total projected length of the edge set (mesh edges and intersection segments), each
/// piece of screen line counted once: segments on one line (directions within 1e-9, offsets
/// within 1e-9 of the extent) are merged as intervals along it, as a plotter strokes them.
fn projected_total(scene: &Scene, view: &View) -> f64 {
    let world = WorldFaces::build(scene, None, Default::default());
    let mut edges = mesh_edges(&world, view, &all_edges(true).edges, Default::default());
    edges.extend(intersection_edges(&world, |_| true, Default::default()));
    let segs: Vec<[[f64; 2]; 2]> = edges
        .iter()
        .filter_map(|e| project_segment(&view.camera, &e.ends[0], &e.ends[1]))
        .map(|[p, q]| [[p[0], p[1]], [q[0], q[1]]])
        .filter(|[p, q]| p != q)
        .collect();
    let extent = segs
        .iter()
        .flatten()
        .fold(0.0f64, |m, p| m.max(p[0].abs()).max(p[1].abs()));
    let tol = 1e-9 * extent.max(1.0);
    // Each segment as (unit direction with x > 0 or x = 0 and y > 0, offset, interval).
    let lines: Vec<([f64; 2], f64, [f64; 2])> = segs
        .iter()
        .map(|[p, q]| {
            let (dx, dy) = (q[0] - p[0], q[1] - p[1]);
            let l = dx.hypot(dy);
            let s = if dx > 0.0 || (dx == 0.0 && dy > 0.0) {
                1.0
            } else {
                -1.0
            };
            let d = [s * dx / l, s * dy / l];
            let off = d[0] * p[1] - d[1] * p[0];
            let (a, b) = (d[0] * p[0] + d[1] * p[1], d[0] * q[0] + d[1] * q[1]);
            (d, off, [a.min(b), a.max(b)])
        })
        .collect();
    let mut used = vec![false; lines.len()];
    let mut total = 0.0;
    for i in 0..lines.len() {
        if used[i] {
            continue;
        }
        let (d, off, _) = lines[i];
        let mut ivs: Vec<[f64; 2]> = Vec::new();
        for j in i..lines.len() {
            let (e, o, iv) = lines[j];
            if !used[j] && (d[0] * e[1] - d[1] * e[0]).abs() <= 1e-9 && (off - o).abs() <= tol {
                used[j] = true;
                ivs.push(iv);
            }
        }
        ivs.sort_by(|a, b| a[0].total_cmp(&b[0]));
        let mut cur = ivs[0];
        for iv in &ivs[1..] {
            if iv[0] > cur[1] {
                total += cur[1] - cur[0];
                cur = *iv;
            } else {
                cur[1] = cur[1].max(iv[1]);
            }
        }
        total += cur[1] - cur[0];
    }
    total
}

fn check_complement(scene: &Scene, cam: Camera, name: &str) {
    let (view, d) = drawing(scene, cam, all_edges(true));
    let (v, h) = (total_length(&d.visible), total_length(&d.hidden));
    let all = projected_total(scene, &view);
    assert!(v > 0.0 && h > 0.0, "{name}: {v} {h}");
    assert!(
        (v + h - all).abs() <= 1e-9 * all,
        "{name}: visible {v} + hidden {h} != {all}"
    );
}

#[test]
fn visible_plus_hidden_is_everything() {
    let s = scene(vec![
        ("a", cuboid([0., 0., 0.], [2., 1., 1.])),
        ("b", cuboid([0.5, -0.5, 0.3], [1.2, 2., 0.6])),
        ("floor", square(-1., -1., 4., -0.5)),
    ]);
    check_complement(&s, Camera::three_quarter(), "boxes");
    let persp = Camera::perspective(
        P3::new(4., 3., 5.),
        P3::new(0.5, 0.5, 0.),
        V3::y(),
        40.0,
        0.1,
    )
    .unwrap();
    check_complement(&s, persp, "boxes in perspective");
    if let Some(p) = model("twocubes.obj") {
        check_complement(&load(&p), Camera::three_quarter(), "twocubes");
    }
}

#[test]
fn crossing_faces_draw_their_intersection_exactly() {
    // Horizontal square z = 0 over [0,2]^2; vertical square x = 1, y in [0.5,3], z in [-1,1].
    let f = mesh(
        &[[0., 0., 0.], [2., 0., 0.], [2., 2., 0.], [0., 2., 0.]],
        &[&[0, 1, 2, 3]],
    );
    let g = mesh(
        &[[1., 0.5, -1.], [1., 3., -1.], [1., 3., 1.], [1., 0.5, 1.]],
        &[&[0, 1, 2, 3]],
    );
    let s = scene(vec![("f", f), ("g", g)]);
    let cam = Camera::orthographic(V3::new(0.3, -0.2, -1.0), V3::y()).unwrap();
    let (_, d) = drawing(&s, cam, LineOptions::default());
    let cut: Vec<_> = d
        .visible
        .iter()
        .filter(|s| s.kind == EdgeKind::Intersection)
        .collect();
    assert_eq!(cut.len(), 1, "{:?}", d.visible);
    let p = |x: [f64; 3]| {
        let q = cam.project(&P3::new(x[0], x[1], x[2]));
        [q[0], q[1]]
    };
    let mut got = vec![cut[0].pts[0], cut[0].pts[cut[0].pts.len() - 1]];
    let mut want = vec![p([1., 0.5, 0.]), p([1., 2., 0.])];
    got.sort_by(|a, b| a.partial_cmp(b).unwrap());
    want.sort_by(|a, b| a.partial_cmp(b).unwrap());
    assert_eq!(got, want);
}

/// No stroke of the example scenes' drawings is a dot of rounding noise (pieces about 1e-15
/// long, left where an edge touches a visible region at a point, used to be drawn as dots
/// with round caps: 7 in assembly, 58 in town).
#[test]
fn example_drawings_have_no_zero_length_strokes() {
    use crate::emit::lines::is_dot;
    use crate::CameraRequest;
    use crate::{render, Outputs, RenderOptions};
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("scenes");
    for name in ["assembly", "town", "polyhedra"] {
        let mut scene = load(&root.join(format!("{name}.kdl")));
        super::common::prepare(&mut scene);
        let camera = Camera::for_scene(&scene, &CameraRequest::default()).unwrap();
        let opts = RenderOptions {
            lines: LineOptions {
                hidden: true,
                ..Default::default()
            },
            outputs: Outputs {
                drawing: true,
                ..Default::default()
            },
            ..Default::default()
        };
        let r = render(&scene, &camera, &opts, &crate::Progress::default()).unwrap();
        let d = r.drawing.as_ref().expect("drawing asked for");
        assert!(!d.visible.is_empty(), "{name}");
        for s in d.visible.iter().chain(&d.hidden) {
            let length: f64 = s
                .pts
                .windows(2)
                .map(|w| (w[1][0] - w[0][0]).hypot(w[1][1] - w[0][1]))
                .sum();
            assert!(length > 1e-9 && !is_dot(&s.pts), "{name}: dot {:?}", s.pts);
        }
    }
}
