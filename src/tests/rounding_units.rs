//! Exact where methods used to fail (issue 31): a seeded, generated family of ill-conditioned
//! scenes, each face measured against the independent exact check in units of output rounding
//! (symmetric difference / (2^-52 · largest |screen coordinate| · face perimeter)), and every
//! ring of the visible regions and of the JSON checked simple. Classes: dihedral sweeps from
//! 1e-6 to 1e-16 rad in random orientations, rotated flush solids (boxes, prisms, an assembly),
//! offsets from 1e3 to 1e12 in perspective and orthographic, eyes from 1e-3 to 1e-12 off a
//! face's plane with fields of view up to 170°, and the ring scenes of the issue (town, plate).
//! Every face must be within [`ALLOWANCE_UNITS`]; the worst figure per class is printed
//! (`--nocapture`) and recorded in docs/numerics.md.

use super::common::*;
use crate::check::VisibleSet;
use crate::exact::{check, ALLOWANCE_UNITS};
use crate::geom::ring_check::multipolygon_defects;
use crate::geom::{PolyMesh, P3, V3};
use crate::scene::{Mesh, Scene};
use crate::view::Camera;
use crate::FaceId;

/// The worst of a class: units, the case and face that gave it, and the defects seen.
#[derive(Debug, Default)]
struct Worst {
    units: f64,
    at: String,
    over: Vec<String>,
    rings: Vec<String>,
}

impl Worst {
    /// Renders `scene` (prepared) from `cam`, checks it exactly and its rings; records.
    fn measure(&mut self, what: &str, mut scene: Scene, cam: Camera) {
        prepare(&mut scene);
        let opts = crate::RenderOptions {
            outputs: crate::Outputs {
                json: true,
                ..Default::default()
            },
            ..Default::default()
        };
        let t0 = std::time::Instant::now();
        let r = crate::render(&scene, &cam, &opts, &crate::Progress::default()).unwrap();
        let t1 = t0.elapsed();
        let rep = check(&scene, &cam, &r.visibility, None);
        if std::env::var_os("KEPLER_ISSUE31_TIMES").is_some() {
            let worst = rep.worst_units();
            eprintln!(
                "{what}: render {t1:?}, check {:?}, worst {worst:.3} units",
                t0.elapsed() - t1
            );
        }
        for f in &rep.faces {
            if f.units > self.units {
                self.units = f.units;
                self.at = format!("{what}, face {}", f.face.0);
            }
            if !f.agrees() {
                self.over.push(format!("{what}: {f:?}"));
            }
        }
        self.rings(what, &scene, &r);
    }

    /// Records every invalid ring of the visible regions and of the JSON.
    fn rings(&mut self, what: &str, scene: &Scene, r: &crate::Rendered) {
        for id in 0..scene.face_count() as u32 {
            let m = &r.visibility.face(FaceId(id)).visible();
            for d in multipolygon_defects(m) {
                self.rings.push(format!("{what}: face {id} region {d:?}"));
            }
        }
        let json = r.json.clone().unwrap_or_default();
        let set = VisibleSet::parse(&json, "render".as_ref()).unwrap();
        for (id, f) in &set.faces {
            for d in multipolygon_defects(&f.visible) {
                self.rings.push(format!("{what}: face {id} JSON {d:?}"));
            }
        }
    }

    fn report(&self, class: &str) -> Vec<String> {
        eprintln!(
            "issue 31 | {class} | worst {:.3} units ({}) | {} faces over | {} bad rings",
            self.units,
            self.at,
            self.over.len(),
            self.rings.len()
        );
        let mut out: Vec<String> = self.over.iter().take(5).cloned().collect();
        out.extend(self.rings.iter().take(5).cloned());
        out
    }
}

/// A random rotation.
fn rotation(rng: &mut Rng) -> nalgebra::Rotation3<f64> {
    let axis = V3::new(rng.unit() - 0.5, rng.unit() - 0.5, rng.unit() - 0.5);
    nalgebra::Rotation3::from_axis_angle(&nalgebra::Unit::new_normalize(axis), rng.unit() * 6.2)
}

/// A mesh from points (rotated by `rot`, each rounded to f64 once) and faces.
fn placed(rot: &nalgebra::Rotation3<f64>, off: V3, pts: &[[f64; 3]], faces: &[&[u32]]) -> Mesh {
    let p: Vec<[f64; 3]> = pts
        .iter()
        .map(|q| {
            let v = rot * P3::new(q[0], q[1], q[2]) + off;
            [v.x, v.y, v.z]
        })
        .collect();
    mesh(&p, faces)
}

/// A primitive's mesh rotated by `rot`.
fn placed_prim(rot: &nalgebra::Rotation3<f64>, raw: PolyMesh) -> Mesh {
    prim(PolyMesh::new(
        raw.vertices.iter().map(|v| rot * v).collect(),
        raw.faces,
    ))
}

/// Two unit quads crossing at `theta` along the line y = 0.1 (as four triangles, or two quads).
fn crossing_quads(rot: &nalgebra::Rotation3<f64>, theta: f64, tris: bool) -> Scene {
    let (c, s) = (theta.cos(), theta.sin());
    let a = [[-1., -1., 0.], [1., -1., 0.], [1., 1., 0.], [-1., 1., 0.]];
    let b = [
        [-0.8, -1., -1.1 * s],
        [1.2, -1., -1.1 * s],
        [1.2, 1. * c, 0.9 * s],
        [-0.8, 1. * c, 0.9 * s],
    ];
    let faces: Vec<&[u32]> = if tris {
        vec![&[0, 1, 2], &[0, 2, 3]]
    } else {
        vec![&[0, 1, 2, 3]]
    };
    scene(vec![
        ("a", placed(rot, V3::zeros(), &a, &faces)),
        ("b", placed(rot, V3::zeros(), &b, &faces)),
    ])
}

/// A view of a rotated scene from roughly the rotated +z side: orthographic or perspective.
fn view_of(rng: &mut Rng, rot: &nalgebra::Rotation3<f64>, perspective: bool) -> Camera {
    let d = rot * V3::new(rng.unit() - 0.5, rng.unit() - 0.5, 2.0);
    if perspective {
        let eye = P3::from(d * 2.5);
        Camera::perspective(eye, P3::origin(), rot * V3::y(), 50.0, 1e-3).unwrap()
    } else {
        Camera::orthographic(-d, rot * V3::y()).unwrap()
    }
}

#[test]
fn dihedral_sweeps_are_within_output_rounding() {
    let mut rng = Rng::new(31);
    let mut w = Worst::default();
    for e in [6, 8, 10, 12, 14, 15, 16] {
        let theta = 10f64.powi(-e);
        for k in 0..4 {
            let rot = rotation(&mut rng);
            let cam = view_of(&mut rng, &rot, k % 2 == 1);
            w.measure(
                &format!("1e-{e} rad, case {k}"),
                crossing_quads(&rot, theta, k < 2),
                cam,
            );
        }
    }
    let bad = w.report("dihedral 1e-6..1e-16");
    assert!(bad.is_empty() && w.units <= ALLOWANCE_UNITS, "{bad:#?}");
}

/// Boxes and prisms with flush faces (coplanar before the rotation), rotated.
fn flush_solids(rot: &nalgebra::Rotation3<f64>, kind: usize) -> Scene {
    let b = |lo: [f64; 3], hi: [f64; 3]| {
        placed_prim(
            rot,
            crate::primitives::cuboid(P3::new(lo[0], lo[1], lo[2]), P3::new(hi[0], hi[1], hi[2])),
        )
    };
    match kind {
        // Two boxes side by side, their tops flush and their sides against each other.
        0 => scene(vec![
            ("a", b([0., 0., 0.], [1., 1., 1.])),
            ("b", b([1., 0.2, 0.], [1.8, 0.9, 1.])),
        ]),
        // A triangular prism standing on a box, its base flush with the box's top.
        1 => {
            let tri = crate::primitives::prism(3).unwrap();
            let lo = tri.vertices.iter().fold(f64::INFINITY, |m, v| m.min(v.z));
            let tri = PolyMesh::new(
                tri.vertices
                    .iter()
                    .map(|v| P3::new(0.5 + 0.3 * v.x, 0.5 + 0.3 * v.y, 1.0 + 0.4 * (v.z - lo)))
                    .collect(),
                tri.faces,
            );
            scene(vec![
                ("base", b([0., 0., 0.], [1., 1., 1.])),
                ("prism", placed_prim(rot, tri)),
            ])
        }
        // An assembly: a plate, two blocks flush on it and against each other.
        _ => scene(vec![
            ("plate", b([0., 0., 0.], [2., 1., 0.2])),
            ("block1", b([0.2, 0.2, 0.2], [1.0, 0.8, 0.6])),
            ("block2", b([1.0, 0.2, 0.2], [1.6, 0.8, 0.6])),
        ]),
    }
}

/// Slow (about a minute a case): the exact check meets the equal-depth lines of nearly
/// coplanar planes in rationals of thousands of bits. Run with `--ignored`.
#[test]
#[ignore]
fn rotated_flush_solids_are_within_output_rounding() {
    let mut rng = Rng::new(3131);
    let mut w = Worst::default();
    for kind in 0..3 {
        for k in 0..2 {
            let rot = rotation(&mut rng);
            let cam = view_of(&mut rng, &rot, k % 2 == 1);
            w.measure(
                &format!("flush kind {kind}, case {k}"),
                flush_solids(&rot, kind),
                cam,
            );
        }
    }
    let bad = w.report("rotated flush solids");
    assert!(bad.is_empty() && w.units <= ALLOWANCE_UNITS, "{bad:#?}");
}

/// A 3×3 grid of unit cubes with its corner at `o`.
fn cube_grid(o: P3) -> Scene {
    let mut objs = Vec::new();
    let names = ["c0", "c1", "c2", "c3", "c4", "c5", "c6", "c7", "c8"];
    for i in 0..3 {
        for j in 0..3 {
            let lo = P3::new(o.x + 1.5 * i as f64, o.y + 1.5 * j as f64, o.z);
            let hi = P3::new(lo.x + 1.0, lo.y + 1.0, lo.z + 1.0 + 0.25 * j as f64);
            objs.push((names[3 * i + j], prim(crate::primitives::cuboid(lo, hi))));
        }
    }
    scene(objs)
}

#[test]
fn offsets_far_from_the_origin_are_within_output_rounding() {
    let mut w = Worst::default();
    for o in [1e3, 1e6, 1e9, 0.99e12] {
        let corner = P3::new(o, -o, o);
        let centre = corner + V3::new(2.0, 2.0, 0.5);
        let eye = centre + V3::new(5.0, -7.0, 6.0);
        let persp = Camera::perspective(eye, centre, V3::z(), 40.0, 1e-2).unwrap();
        w.measure(
            &format!("offset {o:e}, perspective"),
            cube_grid(corner),
            persp,
        );
        let ortho = Camera::orthographic(V3::new(-1., 0.8, -1.3), V3::z()).unwrap();
        w.measure(
            &format!("offset {o:e}, orthographic"),
            cube_grid(corner),
            ortho,
        );
    }
    let bad = w.report("offsets 1e3..1e12");
    assert!(bad.is_empty() && w.units <= ALLOWANCE_UNITS, "{bad:#?}");
}

/// A plate with two blocks on it (z = 0 is the plate's top).
fn plate() -> Scene {
    scene(vec![
        ("plate", cuboid([-2., -2., -0.1], [2., 2., 0.])),
        ("block", cuboid([-0.5, 0.3, 0.], [0.4, 0.9, 0.3])),
        ("post", cuboid([0.6, -0.8, 0.], [0.8, -0.5, 1.0])),
    ])
}

#[test]
fn eyes_next_to_a_face_plane_are_within_output_rounding() {
    let mut w = Worst::default();
    for e in [3, 6, 9, 12] {
        let h = 10f64.powi(-e);
        for fov in [90.0, 150.0, 170.0] {
            // Looking down at the plate from h above it (the default near plane).
            let eye = P3::new(0.05, 0.1, h);
            let down = Camera::for_scene(
                &plate(),
                &crate::CameraRequest {
                    eye: Some(eye),
                    target: Some(P3::new(0.05, 0.3, -1.0)),
                    fov_deg: Some(fov),
                    up: Some(V3::y()),
                    ..Default::default()
                },
            )
            .unwrap();
            w.measure(&format!("{h:e} above, down, fov {fov}"), plate(), down);
            // Grazing: looking along the plate from h above it.
            let along =
                Camera::perspective(eye, P3::new(3.0, 1.0, h), V3::z(), fov, h / 4.0).unwrap();
            w.measure(&format!("{h:e} above, along, fov {fov}"), plate(), along);
        }
    }
    let bad = w.report("eyes 1e-3..1e-12 off a plane");
    assert!(bad.is_empty() && w.units <= ALLOWANCE_UNITS, "{bad:#?}");
}

#[test]
fn the_issues_ring_scenes_have_simple_rings() {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/town.kdl");
    let mut town = load(&path);
    prepare(&mut town);
    let mut w = Worst::default();
    let cams = [
        (
            "town from (-1.2,5.5,26)",
            Camera::for_scene(
                &town,
                &crate::CameraRequest {
                    eye: Some(P3::new(-1.2, 5.5, 26.0)),
                    target: Some(P3::new(0.5, 6.0, -60.0)),
                    fov_deg: Some(50.0),
                    ..Default::default()
                },
            )
            .unwrap(),
        ),
        (
            "town along (1,-1,-1.5)",
            Camera::for_scene(
                &town,
                &crate::CameraRequest {
                    dir: Some(V3::new(1.0, -1.0, -1.5)),
                    ..Default::default()
                },
            )
            .unwrap(),
        ),
    ];
    let opts = crate::RenderOptions {
        outputs: crate::Outputs {
            json: true,
            ..Default::default()
        },
        ..Default::default()
    };
    for (what, cam) in cams {
        let r = crate::render(&town, &cam, &opts, &crate::Progress::default()).unwrap();
        w.rings(what, &town, &r);
    }
    // The plate from 1e-6 above it, fov 150, checked exactly as well.
    let eye = P3::new(0.05, 0.1, 1e-6);
    let cam = Camera::for_scene(
        &plate(),
        &crate::CameraRequest {
            eye: Some(eye),
            target: Some(P3::new(0.05, 0.3, -1.0)),
            fov_deg: Some(150.0),
            ..Default::default()
        },
    )
    .unwrap();
    w.measure("plate from 1e-6 above, fov 150", plate(), cam);
    let bad = w.report("ring scenes");
    assert!(bad.is_empty(), "{bad:#?}");
}
