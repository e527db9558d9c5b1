//! Properties on random scenes: VTPs of different faces are disjoint, their union is the
//! union of the projected faces, VISP on random points agrees with membership in the VTPs,
//! and offset/scaled coordinates give the same answers, scaled.

use super::common::*;
use crate::geom::poly2::{locate, Pt2, Side};
use crate::geom::winding;
use crate::geom::{P3, V3};
use crate::query::PointVisibility;
use crate::scene::{Mesh, Scene};
use crate::view::{Camera, Facing, View};
use crate::visibility::visp::visp;
use crate::visibility::Visibility;
use crate::FaceId;

fn random_triangles(rng: &mut Rng, n: usize, offset: f64, scale: f64) -> Scene {
    let objs: Vec<(String, Mesh)> = (0..n)
        .map(|i| {
            let c = [rng.unit(), rng.unit(), rng.unit()];
            let mut p = [[0.0; 3]; 3];
            for v in &mut p {
                for k in 0..3 {
                    v[k] = (c[k] + (rng.unit() - 0.5) * 0.8) * scale + offset;
                }
            }
            (format!("t{i}"), mesh(&p, &[&[0, 1, 2]]))
        })
        .collect();
    scene(objs.iter().map(|(n, m)| (n.as_str(), m.clone())).collect())
}

fn random_solids(rng: &mut Rng, n: usize) -> Scene {
    let names = crate::primitives::names();
    let objs: Vec<(String, Mesh)> = (0..n)
        .map(|i| {
            let raw = crate::primitives::by_name(names[i % names.len()]).unwrap();
            let s = 0.2 + 0.3 * rng.unit();
            let t = V3::new(rng.unit() * 2.0, rng.unit() * 2.0, rng.unit() * 2.0);
            let raw = crate::geom::PolyMesh::new(
                raw.vertices
                    .iter()
                    .map(|v| P3::from(v.coords * s + t))
                    .collect(),
                raw.faces,
            );
            (format!("s{i}"), prim(raw))
        })
        .collect();
    scene(objs.iter().map(|(n, m)| (n.as_str(), m.clone())).collect())
}

fn cameras(rng: &mut Rng, centre: P3) -> Vec<Camera> {
    let mut cams = vec![
        Camera::orthographic(V3::new(0., 0., -1.), V3::y()).unwrap(),
        Camera::three_quarter(),
    ];
    for _ in 0..2 {
        let d = V3::new(rng.unit() - 0.5, rng.unit() - 0.5, rng.unit() - 0.5);
        cams.push(Camera::orthographic(d, V3::new(0.1, 1.0, 0.2)).unwrap());
    }
    let eye = centre + V3::new(2.5, 1.5, 3.0);
    cams.push(Camera::perspective(eye, centre, V3::y(), 50.0, 0.01).unwrap());
    cams
}

/// Checks disjointness and coverage to `tol` of the projected scene area.
pub(super) fn check_partition(view: &View, vis: &Visibility, tol: f64) {
    let regions: Vec<_> = vis.by_id().into_iter().map(|f| f.visible()).collect();
    let vtps: Vec<&crate::geom::poly2::MultiPolygon> = regions.iter().map(|m| &**m).collect();
    let projected: Vec<Vec<Vec<Vec<Pt2>>>> = view
        .screen
        .piece_ids()
        .filter(|&p| matches!(view.screen.piece(p).facing, Facing::Front | Facing::Back))
        .map(|p| vec![vec![view.screen.ring_ccw(p)]])
        .collect();
    let proj_refs: Vec<_> = projected.iter().collect();
    let scene_area = union_area_exact(&proj_refs);
    let sum = total_area(&vtps);
    let union = union_area_exact(&vtps);
    assert!(
        (sum - union).abs() <= tol * scene_area,
        "VTPs overlap: sum {sum} vs union {union}"
    );
    assert!(
        (union - scene_area).abs() <= tol * scene_area,
        "VTPs cover {union}, projected faces {scene_area}"
    );
}

/// VISP on random points of every face against membership in that face's VTP.
fn check_visp(view: &View, vis: &Visibility, rng: &mut Rng, per_face: usize) -> usize {
    let root = view.tree.root();
    let mut checked = 0;
    for f in view.screen.piece_ids() {
        if !matches!(view.screen.piece(f).facing, Facing::Front | Facing::Back) {
            continue;
        }
        // A sliver (seen nearly edge-on) has every point within rounding of its boundary:
        // skip it, as points near VTP edges are skipped below.
        let ring = view.screen.ring_ccw(f);
        let size = view.screen.piece(f).rect.longer_side();
        if crate::geom::poly2::ring_area(&ring) <= 1e-9 * size * size {
            continue;
        }
        let w = view.screen.world_pts(f).to_vec();
        let id = view.screen.piece(f).face;
        for _ in 0..per_face {
            // A random point of the (triangle fan of the) face.
            let k = 1 + (rng.unit() * (w.len() - 2) as f64) as usize;
            let (mut a, mut b) = (rng.unit(), rng.unit());
            if a + b > 1.0 {
                (a, b) = (1.0 - a, 1.0 - b);
            }
            let p = w[0] + (w[k] - w[0]) * a + (w[k + 1] - w[0]) * b;
            let s = view.camera.project(&p);
            let q = [s[0], s[1]];
            if near_boundary(&vis.face(id).visible(), q) || self_overlap(view, id, q) {
                continue;
            }
            let in_vtp = match locate(&vis.face(id).visible(), q) {
                Side::Inside => true,
                Side::Outside => false,
                Side::Boundary => continue,
            };
            let v = visp(view, root, &p, Some(id));
            assert_eq!(
                v == PointVisibility::Visible,
                in_vtp,
                "face {id} (piece {f}), point {p:?}"
            );
            checked += 1;
        }
    }
    checked
}

/// True when `q` lies in the projection of two pieces of the same (warped, folded) face:
/// the face-level VTP then rightly shows the face there even if this piece is hidden.
fn self_overlap(view: &View, id: FaceId, q: Pt2) -> bool {
    view.screen
        .pieces_of(id)
        .filter(|&p| matches!(winding(&view.screen.ring_ccw(p), q), Some(w) if w != 0))
        .count()
        > 1
}

/// True within 1e-9 (relative to the ring's size) of an edge of the multipolygon.
fn near_boundary(m: &crate::geom::poly2::MultiPolygon, q: Pt2) -> bool {
    m.iter().flatten().any(|r| {
        let size = crate::geom::Rect::of_points(r.iter()).longer_side();
        (0..r.len()).any(|i| {
            let (a, b) = (r[i], r[(i + 1) % r.len()]);
            let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
            let l2 = dx * dx + dy * dy;
            let t = if l2 > 0.0 {
                (((q[0] - a[0]) * dx + (q[1] - a[1]) * dy) / l2).clamp(0.0, 1.0)
            } else {
                0.0
            };
            let (ex, ey) = (a[0] + t * dx - q[0], a[1] + t * dy - q[1]);
            (ex * ex + ey * ey).sqrt() <= 1e-9 * size
        })
    })
}

#[test]
fn random_interpenetrating_triangles() {
    let mut rng = Rng::new(0x9E3779B97F4A7C15);
    let mut checked = 0;
    for round in 0..6 {
        let s = random_triangles(&mut rng, 40 + 10 * round, 0.0, 1.0);
        for cam in cameras(&mut rng, P3::new(0.5, 0.5, 0.5)) {
            let (view, vis) = run(&s, cam);
            check_partition(&view, &vis, 1e-9);
            checked += check_visp(&view, &vis, &mut rng, 4);
        }
    }
    assert!(checked > 1000, "only {checked} points checked");
}

#[test]
fn random_closed_solids() {
    let mut rng = Rng::new(12345);
    for _ in 0..3 {
        let mut s = random_solids(&mut rng, 14);
        // Prepared: each primitive is proven solid, so its back faces are culled.
        super::common::prepare(&mut s);
        for (ci, cam) in cameras(&mut rng, P3::new(1.0, 1.0, 1.0))
            .into_iter()
            .enumerate()
        {
            eprintln!("camera {ci}");
            let (view, vis) = run(&s, cam);
            assert!(vis.counters.faces_culled > 0);
            check_partition(&view, &vis, 1e-9);
            check_visp(&view, &vis, &mut rng, 2);
        }
    }
}

#[test]
fn offset_and_scaled_coordinates_give_scaled_answers() {
    let base = random_triangles(&mut Rng::new(7), 60, 0.0, 1.0);
    let shifted = random_triangles(&mut Rng::new(7), 60, 1e6, 1.0);
    let shrunk = random_triangles(&mut Rng::new(7), 60, 0.0, 1e-6);
    for dir in [V3::new(0., 0., -1.), V3::new(-0.4, -0.7, -1.0)] {
        let cam = Camera::orthographic(dir, V3::y()).unwrap();
        let (_, a) = run(&base, cam);
        let (_, b) = run(&shifted, cam);
        let (_, c) = run(&shrunk, cam);
        let total: f64 = a.by_id().into_iter().map(|f| f.area).sum();
        for i in (0..a.face_count() as u32).map(FaceId) {
            // Offsetting by 1e6 leaves ~1e-10 of absolute precision in the coordinates.
            assert!(
                (a.face(i).area - b.face(i).area).abs() <= 1e-9 * total,
                "face {i}: {} vs {}",
                a.face(i).area,
                b.face(i).area
            );
            assert!(
                (a.face(i).area * 1e-12 - c.face(i).area).abs() <= 1e-9 * total * 1e-12,
                "face {i}"
            );
        }
    }
}

#[test]
fn output_is_identical_whatever_the_thread_count() {
    let s = random_triangles(&mut Rng::new(99), 80, 0.0, 1.0);
    let cam = Camera::three_quarter();
    let one = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap()
        .install(|| run(&s, cam).1);
    let many = rayon::ThreadPoolBuilder::new()
        .num_threads(4)
        .build()
        .unwrap()
        .install(|| run(&s, cam).1);
    assert_eq!(one.by_id(), many.by_id());
    assert_eq!(one.counters, many.counters);
}

#[test]
fn shared_meshes_from_several_views() {
    let Some(dir) = models() else { return };
    let mut rng = Rng::new(2024);
    for name in [
        "cube.obj",
        "twocubes.obj",
        "ico3.obj",
        "suzanne.obj",
        "beetle.obj",
        "spot.obj",
        "teapot.obj",
    ] {
        let path = dir.join(name);
        if !path.exists() {
            eprintln!("skipping {name}: absent");
            continue;
        }
        let s = super::common::load(&path);
        let b = s.cbox();
        let c = b.center();
        let r = (b.hi - b.lo).norm();
        let cams = [
            Camera::three_quarter(),
            Camera::orthographic(V3::new(0.3, -0.5, 1.0), V3::y()).unwrap(),
            Camera::perspective(c + V3::new(0.7, 0.5, 1.1) * r, c, V3::y(), 45.0, 1e-3 * r)
                .unwrap(),
        ];
        for (ci, cam) in cams.into_iter().enumerate() {
            eprintln!("{name} camera {ci}");
            let (view, vis) = run(&s, cam);
            check_partition(&view, &vis, 1e-9);
            check_visp(&view, &vis, &mut rng, 1);
        }
    }
}
