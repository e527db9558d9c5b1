//! Computed INBOXes: inside their objects (checked independently), optimal for convex solids,
//! and never changing what is visible.

use std::sync::Arc;

use super::common::{cuboid, mesh, prim, top, translate};
use crate::geom::{Box3, PolyMesh, M4, P3, V3};
use crate::prepare::inbox::{compute_inboxes, mesh_inbox};
use crate::primitives;
use crate::scene::{Mesh, Object, Scene};
use crate::view::Camera;
use crate::{render, Outputs, RenderOptions};
use kepler_testkit::Rng;

/// Independent containment check: no fan triangle meets the box's interior (exact orient3d
/// for convex meshes is not assumed), and sample points of the box have winding number 1.
fn assert_inside(m: &Mesh, b: &Box3, what: &str) {
    assert!(b.has_interior(), "{what}: empty inbox");
    let cbox = Box3::from_points(m.vertices.iter());
    assert!(cbox.contains_box(b), "{what}: inbox leaves the cbox");
    let mut rng = Rng::new(7);
    let c = b.center();
    let mut pts: Vec<P3> = b.corners().iter().map(|p| p + (c - p) * 1e-6).collect();
    pts.push(b.center());
    for _ in 0..20 {
        pts.push(P3::new(
            rng.range(b.lo.x, b.hi.x),
            rng.range(b.lo.y, b.hi.y),
            rng.range(b.lo.z, b.hi.z),
        ));
    }
    for p in &pts {
        let w = m.winding_number(p).abs();
        assert!(w > 0.5, "{what}: {p:?} of the inbox is outside (w = {w})");
    }
    // No edge of the mesh passes through the open box, and no box edge through a face.
    let open = |p: &P3| b.contains_strictly(p);
    for f in &m.faces {
        let v: Vec<P3> = f.vertices.iter().map(|&k| m.vertices[k as usize]).collect();
        for i in 0..v.len() {
            let (a, c) = (v[i], v[(i + 1) % v.len()]);
            for k in 1..64 {
                let p = a + (c - a) * (k as f64 / 64.0);
                assert!(!open(&p), "{what}: a mesh edge crosses the inbox");
            }
            assert!(!open(&a), "{what}: a vertex lies inside the inbox");
        }
    }
}

fn transformed(m: &Mesh, xf: &M4) -> Mesh {
    let raw = PolyMesh::new(
        m.vertices.iter().map(|p| xf.transform_point(p)).collect(),
        m.faces.iter().map(|f| f.vertices.to_vec()).collect(),
    );
    prim(raw)
}

fn random_affine(rng: &mut Rng) -> M4 {
    let axis = V3::new(rng.range(-1., 1.), rng.range(-1., 1.), rng.range(-1., 1.)).normalize();
    let r = nalgebra::Rotation3::from_axis_angle(
        &nalgebra::Unit::new_normalize(axis),
        rng.range(0., 3.),
    );
    let s = V3::new(rng.range(0.5, 2.), rng.range(0.5, 2.), rng.range(0.5, 2.));
    translate(rng.range(-5., 5.), rng.range(-5., 5.), rng.range(-5., 5.))
        * nalgebra::Matrix4::new_nonuniform_scaling(&s)
        * r.to_homogeneous()
}

/// Face planes (outward unit normal, offset) of a convex mesh, from Newell normals.
fn planes(m: &Mesh) -> Vec<(V3, f64)> {
    m.faces
        .iter()
        .map(|f| {
            let p: Vec<P3> = f.vertices.iter().map(|&k| m.vertices[k as usize]).collect();
            let mut n = V3::zeros();
            for i in 0..p.len() {
                let (a, b) = (p[i], p[(i + 1) % p.len()]);
                n += V3::new(
                    (a.y - b.y) * (a.z + b.z),
                    (a.z - b.z) * (a.x + b.x),
                    (a.x - b.x) * (a.y + b.y),
                );
            }
            let n = n.normalize();
            (
                n,
                p.iter().map(|q| n.dot(&q.coords)).sum::<f64>() / p.len() as f64,
            )
        })
        .collect()
}

/// Independent optimiser: random-direction pattern search over (lo, hi) on the volume, with
/// feasibility = all 8 corners behind every face plane.
fn pattern_search_volume(m: &Mesh, seed: u64) -> f64 {
    let pl = planes(m);
    let feasible = |x: &[f64; 6]| {
        (0..3).all(|i| x[i] < x[i + 3])
            && pl.iter().all(|(n, d)| {
                let far: f64 = (0..3)
                    .map(|i| n[i] * if n[i] > 0. { x[i + 3] } else { x[i] })
                    .sum();
                far <= *d
            })
    };
    let vol = |x: &[f64; 6]| (x[3] - x[0]) * (x[4] - x[1]) * (x[5] - x[2]);
    let c = m.vertices.iter().map(|p| p.coords).sum::<V3>() / m.vertices.len() as f64;
    let mut x = [
        c.x - 1e-3,
        c.y - 1e-3,
        c.z - 1e-3,
        c.x + 1e-3,
        c.y + 1e-3,
        c.z + 1e-3,
    ];
    assert!(feasible(&x));
    let cb = Box3::from_points(m.vertices.iter());
    let mut step = cb.size().iter().fold(0.0f64, |a, &b| a.max(b)) * 0.25;
    let mut rng = Rng::new(seed);
    let mut fails = 0;
    while step > 1e-7 {
        let mut d = [0.0; 6];
        for v in &mut d {
            *v = rng.range(-1., 1.);
        }
        let y: [f64; 6] = std::array::from_fn(|i| x[i] + step * d[i]);
        if feasible(&y) && vol(&y) > vol(&x) {
            x = y;
            fails = 0;
        } else {
            fails += 1;
            if fails > 300 {
                step *= 0.5;
                fails = 0;
            }
        }
    }
    vol(&x)
}

#[test]
fn cube_inbox_is_the_cube() {
    let m = cuboid([0., -1., 2.], [3., 1., 2.5]);
    let b = mesh_inbox(&m).unwrap();
    assert_eq!(b, Box3::new(P3::new(0., -1., 2.), P3::new(3., 1., 2.5)));
}

#[test]
fn every_primitive_has_an_inbox_inside_it() {
    let mut solids: Vec<(String, Mesh)> = primitives::names()
        .into_iter()
        .map(|n| (n.to_string(), prim(primitives::by_name(n).unwrap())))
        .collect();
    for k in [3, 5, 8, 17] {
        solids.push((format!("prism{k}"), prim(primitives::prism(k).unwrap())));
        solids.push((
            format!("antiprism{k}"),
            prim(primitives::antiprism(k).unwrap()),
        ));
    }
    for (name, m) in &solids {
        let b = mesh_inbox(m).unwrap_or_else(|| panic!("{name}: no inbox"));
        assert_inside(m, &b, name);
        let ratio = b.volume() / Box3::from_points(m.vertices.iter()).volume();
        assert!(ratio > 0.03, "{name}: inbox only {ratio} of the cbox");
    }
}

#[test]
fn convex_inboxes_are_optimal_within_one_percent() {
    let mut rng = Rng::new(12345);
    let names = primitives::names();
    for k in 0..12 {
        let base = prim(primitives::by_name(names[k % names.len()]).unwrap());
        let m = transformed(&base, &random_affine(&mut rng));
        let b = mesh_inbox(&m).unwrap();
        let what = format!("{} #{k}", names[k % names.len()]);
        assert_inside(&m, &b, &what);
        let other = pattern_search_volume(&m, k as u64 + 1);
        assert!(
            b.volume() >= 0.99 * other,
            "{what}: {} < {other}",
            b.volume()
        );
    }
}

/// A prism over a simple polygon (counter-clockwise), from z0 to z1.
fn extrude(poly: &[[f64; 2]], z0: f64, z1: f64) -> Mesh {
    let n = poly.len() as u32;
    let mut pts: Vec<[f64; 3]> = poly.iter().map(|p| [p[0], p[1], z0]).collect();
    pts.extend(poly.iter().map(|p| [p[0], p[1], z1]));
    let bottom: Vec<u32> = (0..n).rev().collect();
    let top: Vec<u32> = (n..2 * n).collect();
    let sides: Vec<Vec<u32>> = (0..n)
        .map(|i| vec![i, (i + 1) % n, n + (i + 1) % n, n + i])
        .collect();
    let mut faces: Vec<&[u32]> = vec![&bottom, &top];
    faces.extend(sides.iter().map(|s| s.as_slice()));
    mesh(&pts, &faces)
}

fn l_shape() -> Mesh {
    extrude(
        &[[0., 0.], [4., 0.], [4., 1.], [1., 1.], [1., 3.], [0., 3.]],
        0.,
        1.,
    )
}

fn cross() -> Mesh {
    extrude(
        &[
            [1., 0.],
            [2., 0.],
            [2., 1.],
            [3., 1.],
            [3., 2.],
            [2., 2.],
            [2., 3.],
            [1., 3.],
            [1., 2.],
            [0., 2.],
            [0., 1.],
            [1., 1.],
        ],
        -1.,
        1.,
    )
}

fn stairs() -> Mesh {
    extrude(
        &[
            [0., 0.],
            [5., 0.],
            [5., 1.],
            [3., 1.],
            [3., 2.],
            [1., 2.],
            [1., 4.],
            [0., 4.],
        ],
        0.,
        2.,
    )
}

#[test]
fn non_convex_inboxes_are_inside_and_large() {
    let mut rng = Rng::new(99);
    for (name, m, best) in [
        ("L", l_shape(), 4.0),
        ("cross", cross(), 6.0),
        ("stairs", stairs(), 10.0),
    ] {
        for k in 0..3 {
            let xf = if k == 0 {
                M4::identity()
            } else {
                random_affine(&mut rng)
            };
            let tm = transformed(&m, &xf);
            let b = mesh_inbox(&tm).unwrap_or_else(|| panic!("{name} #{k}: none"));
            assert_inside(&tm, &b, name);
            if k == 0 {
                assert!(b.volume() > 0.95 * best, "{name}: {} < {best}", b.volume());
            }
        }
    }
}

#[test]
fn open_meshes_have_no_inbox_and_groups_take_the_largest() {
    let sq = super::common::square(0., 0., 1., 0.);
    assert!(mesh_inbox(&sq).is_none());
    let mut g = Object::group(
        "g",
        vec![
            Object::from_mesh("a", cuboid([0., 0., 0.], [1., 1., 1.])),
            Object::from_mesh("b", cuboid([2., 0., 0.], [4., 2., 2.])),
            Object::from_mesh("sq", sq),
        ],
    );
    compute_inboxes(&mut g, Default::default());
    assert_eq!(
        g.inbox,
        Some(Box3::new(P3::new(2., 0., 0.), P3::new(4., 2., 2.)))
    );
    assert!(g.subobjects()[2].inbox.is_none());
}

#[test]
fn instance_inboxes_follow_the_transform() {
    let proto = Arc::new(Object::from_mesh(
        "c",
        cuboid([-1., -1., -1.], [1., 1., 1.]),
    ));
    let r = nalgebra::Rotation3::from_axis_angle(&V3::z_axis(), 0.3).to_homogeneous();
    let mut g = Object::group(
        "g",
        vec![
            Object::instance("t", proto.clone(), translate(5., 0., 0.)),
            Object::instance("r", proto.clone(), translate(0., 5., 0.) * r),
        ],
    );
    compute_inboxes(&mut g, Default::default());
    let t = g.subobjects()[0].inbox.unwrap();
    assert_eq!(t, Box3::new(P3::new(4., -1., -1.), P3::new(6., 1., 1.)));
    let rb = g.subobjects()[1].inbox.unwrap();
    let inv = (translate(0., 5., 0.) * r).try_inverse().unwrap();
    for c in rb.corners() {
        let q = inv.transform_point(&c);
        assert!(q.iter().all(|x| x.abs() <= 1.0), "{q:?}");
    }
    assert!((rb.size()[2] - 2.0).abs() < 1e-5);
    // The prototype is prepared once and stays shared.
    let p0 = match &g.subobjects()[0].content {
        crate::scene::Content::Instance(i) => i.prototype.clone(),
        _ => unreachable!(),
    };
    let p1 = match &g.subobjects()[1].content {
        crate::scene::Content::Instance(i) => i.prototype.clone(),
        _ => unreachable!(),
    };
    assert!(Arc::ptr_eq(&p0, &p1));
    assert!(p0.inbox.is_some());
}

fn scene_behind_wall() -> Scene {
    let proto = Arc::new(Object::from_mesh(
        "ico",
        prim(primitives::by_name("icosahedron").unwrap()),
    ));
    let objs = vec![
        Object::from_mesh("wall", cuboid([-10., -10., 5.], [10., 10., 6.])),
        Object::from_mesh("l", transformed(&l_shape(), &translate(-3., -3., 0.))),
        Object::from_mesh("cross", transformed(&cross(), &translate(2., 1., -3.))),
        Object::instance("i1", proto.clone(), translate(0., 0., 2.)),
        Object::group(
            "g",
            vec![
                Object::from_mesh("c", cuboid([3., 3., 0.], [4., 4., 1.])),
                Object::instance("i2", proto, translate(-4., 4., 1.)),
            ],
        ),
        // Partly visible: sticks out beside the wall.
        Object::from_mesh("tall", cuboid([8., -1., 0.], [12., 1., 8.])),
    ];
    Scene::new(Object::group("", objs), "test".into())
}

/// Inboxes on (culled view, VISFAC2's complete-hide test) against inboxes off (every face
/// projected and walked): the visible-polygon sets must be equal, face by face.
/// Returns whether the cull hid a subtree.
fn assert_same_visibility(mut scene: Scene, camera: Camera, expect_pruning: bool) -> bool {
    compute_inboxes(&mut scene.root, Default::default());
    let json = |no_inbox| {
        let outputs = Outputs {
            json: true,
            ..Outputs::default()
        };
        let opts = RenderOptions {
            no_inbox,
            outputs,
            ..RenderOptions::default()
        };
        render(&scene, &camera, &opts, &crate::Progress::default()).unwrap()
    };
    let (culled, full) = (json(false), json(true));
    let (with, without) = (&culled.visibility, &full.visibility);
    assert_eq!(with.face_count(), without.face_count());
    for (f, (a, b)) in with.by_id().into_iter().zip(without.by_id()).enumerate() {
        assert_eq!(a.visible(), b.visible(), "face {f} differs");
        assert_eq!(a.area, b.area, "face {f} differs");
    }
    // The JSON a regression suite keeps is the same bytes.
    assert_eq!(culled.json, full.json);
    if expect_pruning {
        let c = with.counters;
        assert!(
            c.subtrees_hidden > 0 && c.emptied_by_inbox + c.subtrees_hidden > 0,
            "{c:?}"
        );
        assert!(with.solved_count() < with.face_count());
    }
    with.counters.subtrees_hidden > 0
}

#[test]
fn inboxes_do_not_change_visibility() {
    // Looking down -z: the wall (z 5..6) hides everything under it.
    assert_same_visibility(scene_behind_wall(), top(), true);
    let oblique = Camera::orthographic(V3::new(0.3, -0.2, -1.), V3::y()).unwrap();
    assert_same_visibility(scene_behind_wall(), oblique, true);
    let persp =
        Camera::perspective(P3::new(1.3, 2.1, 30.), P3::origin(), V3::y(), 50., 0.1).unwrap();
    assert_same_visibility(scene_behind_wall(), persp, false);
    let side = Camera::orthographic(V3::new(1., 0.4, 0.2), V3::z()).unwrap();
    assert_same_visibility(scene_behind_wall(), side, false);
}

/// Random scenes: groups of boxes and polyhedra (some instanced) at random depths under a few
/// random slabs, seen from random orthographic and perspective cameras. Culling must never
/// change a visible polygon, and across the set it must actually cull.
#[test]
fn culling_random_scenes_changes_nothing() {
    let mut rng = Rng::new(0x5eed_cafe);
    let ico = Arc::new(Object::from_mesh(
        "ico",
        prim(primitives::by_name("icosahedron").unwrap()),
    ));
    let mut culled = 0;
    for _ in 0..12 {
        let mut objs = Vec::new();
        for w in 0..rng.range(1.0, 3.99) as usize {
            let (x, y, z) = (rng.range(-6., 0.), rng.range(-6., 0.), rng.range(2., 6.));
            let (sx, sy) = (rng.range(4., 10.), rng.range(4., 10.));
            objs.push(Object::from_mesh(
                format!("slab{w}"),
                cuboid([x, y, z], [x + sx, y + sy, z + rng.range(0.2, 1.)]),
            ));
        }
        for g in 0..rng.range(2.0, 5.99) as usize {
            let parts = (0..rng.range(1.0, 4.99) as usize)
                .map(|k| {
                    let (x, y, z) = (rng.range(-5., 5.), rng.range(-5., 5.), rng.range(-4., 1.5));
                    if rng.unit() < 0.4 {
                        Object::instance(format!("i{k}"), ico.clone(), translate(x, y, z))
                    } else {
                        let s = rng.range(0.3, 2.);
                        Object::from_mesh(format!("b{k}"), cuboid([x, y, z], [x + s, y + s, z + s]))
                    }
                })
                .collect();
            objs.push(Object::group(format!("g{g}"), parts));
        }
        let scene = Scene::new(Object::group("", objs), "random".into());
        let dir = V3::new(rng.range(-0.4, 0.4), rng.range(-0.4, 0.4), -1.);
        let camera = if rng.unit() < 0.5 {
            Camera::orthographic(dir, V3::y()).unwrap()
        } else {
            let eye = P3::new(rng.range(-3., 3.), rng.range(-3., 3.), rng.range(15., 30.));
            Camera::perspective(eye, P3::origin(), V3::y(), 50., 0.1).unwrap()
        };
        culled += assert_same_visibility(scene, camera, false) as usize;
    }
    eprintln!("{culled} of 12 random scenes culled a subtree");
    assert!(
        culled >= 3,
        "only {culled} random scenes exercised the cull"
    );
}

#[test]
fn a_wide_tilted_disc_gets_its_optimal_box() {
    // The rod of assembly.kdl made `prism 65536`, smaller: a disc 40 times wider than thick,
    // turned off every axis. The largest box in it is a long thin slab whose barrier
    // Hessian grows ill-conditioned as the centring closes in; the box must still come from
    // the optimisation (within a percent of a direct search), not from growing seeds.
    let base = prim(primitives::prism(4096).unwrap());
    let rot = |deg: f64, axis: V3| {
        nalgebra::Rotation3::from_axis_angle(&nalgebra::Unit::new_normalize(axis), deg.to_radians())
            .to_homogeneous()
    };
    let xf = rot(25.0, V3::y())
        * rot(12.0, V3::z())
        * rot(90.0, V3::y())
        * nalgebra::Matrix4::new_nonuniform_scaling(&V3::new(0.35, 0.35, 5.2));
    let m = transformed(&base, &xf);
    let b = mesh_inbox(&m).expect("an inbox");
    assert_inside(&m, &b, "tilted disc");
    let other = pattern_search_volume(&m, 3);
    assert!(b.volume() >= 0.99 * other, "{} < {other}", b.volume());
}
