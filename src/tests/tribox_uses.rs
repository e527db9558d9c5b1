//! Triboxes in use: hierarchy cells cover the solid (surface and interior), level-of-detail
//! renders keep the visibility invariants, interference agrees with exact tests, and on the
//! shared meshes the tribox sits between the convex hull and the CBOX.

use super::common::*;
use crate::geom::hull3::hull_volume;
use crate::geom::poly2::MultiPolygon;
use crate::geom::{PolyMesh, P3, V3};
use crate::scene::{Mesh, Object, Scene};
use crate::tribox::interfere::interfere;
use crate::tribox::{Hierarchy, HierarchyOptions, Tribox};
use crate::view::{substitute, LodOptions};
use crate::view::{Camera, Facing};
use crate::FaceId;

/// A closed prism over a simple polygon (counter-clockwise), from z = 0 to z = h.
fn extrude(poly: &[[f64; 2]], h: f64) -> Mesh {
    let n = poly.len() as u32;
    let mut v: Vec<P3> = poly.iter().map(|p| P3::new(p[0], p[1], 0.0)).collect();
    v.extend(poly.iter().map(|p| P3::new(p[0], p[1], h)));
    let mut faces = vec![(0..n).rev().collect::<Vec<u32>>(), (n..2 * n).collect()];
    for i in 0..n {
        let j = (i + 1) % n;
        faces.push(vec![i, j, j + n, i + n]);
    }
    prim(PolyMesh::new(v, faces))
}

/// A U-shaped block: a cavity a single tribox fills.
fn u_block() -> Mesh {
    extrude(
        &[
            [0., 0.],
            [6., 0.],
            [6., 5.],
            [5., 5.],
            [5., 1.],
            [1., 1.],
            [1., 5.],
            [0., 5.],
        ],
        2.0,
    )
}

fn inflated(t: &Tribox, eps: f64) -> Tribox {
    let mut t = *t;
    for k in 0..9 {
        t.lo[k] -= eps;
        t.hi[k] += eps;
    }
    t
}

/// Surface samples (corners, centroids, random points of faces) and interior samples.
fn samples(m: &Mesh, rng: &mut Rng) -> (Vec<P3>, Vec<P3>) {
    let mut surface = m.vertices.clone();
    for f in &m.faces {
        let p: Vec<P3> = f.vertices.iter().map(|&v| m.vertices[v as usize]).collect();
        let n = (1..p.len() - 1)
            .map(|i| (p[i] - p[0]).cross(&(p[i + 1] - p[0])))
            .sum::<V3>();
        for [i, j, k] in crate::scene::triangulate::ear_clip(&p, &n) {
            for _ in 0..3 {
                let (mut a, mut b) = (rng.unit(), rng.unit());
                if a + b > 1.0 {
                    (a, b) = (1.0 - a, 1.0 - b);
                }
                surface.push(p[i] + (p[j] - p[i]) * a + (p[k] - p[i]) * b);
            }
        }
    }
    let bb = crate::geom::Box3::from_points(m.vertices.iter());
    let s = bb.size();
    let mut interior = Vec::new();
    for _ in 0..400 {
        let q = bb.lo + V3::new(rng.unit() * s[0], rng.unit() * s[1], rng.unit() * s[2]);
        if m.winding_number(&q).abs() > 0.5 {
            interior.push(q);
        }
    }
    (surface, interior)
}

fn check_cover(m: &Mesh, what: &str) {
    assert!(m.closed, "{what} must be a closed solid");
    let h = Hierarchy::build(
        m,
        &HierarchyOptions {
            max_depth: 5,
            min_gain: 0.0,
        },
    );
    assert!(h.depth() >= 1, "{what}: never split");
    let mut rng = Rng::new(31);
    let (surface, interior) = samples(m, &mut rng);
    assert!(!interior.is_empty());
    let eps = 1e-9 * h.nodes[0].tribox.thickness(0);
    for d in 0..=h.depth() {
        let cut = h.cut(d);
        let boxes: Vec<Tribox> = cut
            .iter()
            .map(|&n| inflated(&h.nodes[n].tribox, eps))
            .collect();
        for p in surface.iter().chain(&interior) {
            assert!(
                boxes.iter().any(|t| t.contains(p)),
                "{what}, level {d}: {p:?} uncovered"
            );
        }
        // Children sit inside their parent and on their own side of the split.
        for (i, n) in h.nodes.iter().enumerate() {
            if let Some((s, [a, b])) = n.children {
                let (ta, tb) = (&h.nodes[a].tribox, &h.nodes[b].tribox);
                assert!(
                    ta.hi[s.k] <= s.at + eps && tb.lo[s.k] >= s.at - eps,
                    "node {i}"
                );
                assert!(ta.tightened().volume() <= n.tribox.volume() * (1.0 + 1e-9));
            }
        }
    }
    // Deeper cuts: no larger volume; the deepest cut's error is below the root's (the
    // vertex-sampled error is not monotone level by level).
    let vol = |d| -> f64 { h.cut(d).iter().map(|&n| h.nodes[n].tribox.volume()).sum() };
    for d in 1..=h.depth() {
        assert!(
            vol(d) <= vol(d - 1) * (1.0 + 1e-9),
            "{what}: level {d} grew"
        );
    }
    assert!(
        h.cut_error(&h.cut(h.depth())) < h.cut_error(&h.cut(0)),
        "{what}"
    );
}

#[test]
fn hierarchy_cells_cover_the_solid() {
    check_cover(&u_block(), "U block");
    // A star: cells whose corners lie inside the solid (category (d)).
    let star: Vec<[f64; 2]> = (0..10)
        .map(|i| {
            let a = i as f64 * std::f64::consts::PI / 5.0;
            let r = if i % 2 == 0 { 3.0 } else { 1.2 };
            [r * a.cos(), r * a.sin()]
        })
        .collect();
    check_cover(&extrude(&star, 1.5), "star prism");
}

#[test]
fn lod_render_keeps_visibility_invariants() {
    let ball = |s: f64, at: V3| {
        let raw = crate::primitives::by_name("truncated_icosahedron").unwrap();
        prim(PolyMesh::new(
            raw.vertices
                .iter()
                .map(|v| P3::from(v.coords * s + at))
                .collect(),
            raw.faces,
        ))
    };
    let mut objs = vec![("wall", cuboid([-4., -4., -1.], [4., 4., -0.5]))];
    let names: Vec<String> = (0..6).map(|i| format!("b{i}")).collect();
    for (i, n) in names.iter().enumerate() {
        let x = -3.0 + i as f64 * 1.2;
        objs.push((
            n.as_str(),
            ball(0.05 + 0.05 * i as f64, V3::new(x, 0.3 * i as f64, 0.5)),
        ));
    }
    let scene = scene(objs);
    let cam = Camera::orthographic(V3::new(-0.2, -0.3, -1.0), V3::y()).unwrap();
    let (sub, stats) = substitute(&scene, &cam, &LodOptions::new(60.0, 800));
    assert!(stats.objects_replaced >= 2, "{stats:?}");
    assert!(stats.faces_modelled < stats.faces_in_scene);
    assert_eq!(stats.faces_modelled, sub.face_count());
    // Every original vertex lies in its object's substitute's tribox.
    for (o, s) in scene.root.subobjects().iter().zip(sub.root.subobjects()) {
        let t = inflated(&Tribox::from_points(s.vertices()), 1e-9);
        assert!(o.vertices().iter().all(|v| t.contains(v)), "{}", o.name);
    }
    // The render of the substituted scene: VTPs partition the projected faces.
    let (view, vis) = run(&sub, cam);
    let regions: Vec<_> = vis.by_id().into_iter().map(|f| f.visible()).collect();
    let vtps: Vec<&MultiPolygon> = regions.iter().map(|m| &**m).collect();
    let projected: Vec<MultiPolygon> = view
        .screen
        .piece_ids()
        .filter(|&p| matches!(view.screen.piece(p).facing, Facing::Front | Facing::Back))
        .map(|p| vec![vec![view.screen.ring_ccw(p)]])
        .collect();
    let all = union_area_exact(&projected.iter().collect::<Vec<_>>());
    let sum = total_area(&vtps);
    let union = union_area_exact(&vtps);
    close(sum, union, 1e-9); // disjoint
    close(union, all, 1e-9); // cover
                             // The substitutes are visible in front of the wall.
    let wall_area: f64 = (0..6).map(|f| vis.face(FaceId(f)).area).sum();
    assert!(wall_area < 64.0 * 1.2);
}

#[test]
fn interference_matches_exact_tests() {
    let cube = |lo: [f64; 3], s: f64| cuboid(lo, [lo[0] + s, lo[1] + s, lo[2] + s]);
    // A diamond (octahedron) and a cube corner beside it: CBOXes meet, triboxes do not.
    let oct = prim(PolyMesh::new(
        vec![
            P3::new(1., 0., 0.),
            P3::new(-1., 0., 0.),
            P3::new(0., 1., 0.),
            P3::new(0., -1., 0.),
            P3::new(0., 0., 1.),
            P3::new(0., 0., -1.),
        ],
        vec![
            vec![0, 2, 4],
            vec![2, 1, 4],
            vec![1, 3, 4],
            vec![3, 0, 4],
            vec![2, 0, 5],
            vec![1, 2, 5],
            vec![3, 1, 5],
            vec![0, 3, 5],
        ],
    ));
    let s = scene(vec![
        ("diamond", oct),
        ("corner", cube([0.7, 0.7, -0.2], 0.5)),
        ("pierce", cube([-0.2, -0.2, 0.5], 0.4)),
        ("far", cube([5., 5., 5.], 1.)),
        ("inside", cube([5.3, 5.3, 5.3], 0.2)),
    ]);
    let r = interfere(&s);
    let find = |a: &str, b: &str| {
        r.tribox_meet
            .iter()
            .find(|p| r.objects[p.0] == a && r.objects[p.1] == b)
            .map(|p| p.2)
    };
    assert_eq!(find("diamond", "corner"), None, "x+y separates them");
    assert_eq!(find("diamond", "pierce"), Some(true));
    assert_eq!(
        find("far", "inside"),
        Some(false),
        "nested: triboxes meet, faces do not"
    );
    assert!(r.cbox_meet > r.tribox_meet.len());
    assert_eq!(r.pairs, 10);
}

#[test]
fn shared_meshes_tribox_between_hull_and_cbox() {
    let Some(dir) = models() else { return };
    for name in ["cow.obj", "spot.obj", "ico3.obj", "fandisk.obj"] {
        let p = dir.join(name);
        if !p.exists() {
            eprintln!("skipping {name}: absent");
            continue;
        }
        let scene: Scene = super::common::load(&p);
        let pts: Vec<P3> = scene
            .leaves()
            .iter()
            .flat_map(|l| {
                l.mesh
                    .vertices
                    .iter()
                    .map(|v| l.transform.transform_point(v))
            })
            .collect();
        let t = Tribox::from_points(pts.iter());
        assert!(pts.iter().all(|q| t.contains(q)), "{name}");
        let (vt, vb, vh) = (t.volume(), t.cbox().volume(), hull_volume(&pts));
        assert!(
            vh <= vt * (1.0 + 1e-9) && vt <= vb * (1.0 + 1e-12),
            "{name}: hull {vh} tribox {vt} cbox {vb}"
        );
        let faces = t.boundary().mesh().faces.len();
        assert!(faces <= 18, "{name}: {faces}");
        let _ = Object::group("", vec![]);
    }
}
