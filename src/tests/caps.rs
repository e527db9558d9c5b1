//! Capped open meshes: back faces away from the holes are culled, and the picture equals the
//! two-sided answer — by hand on an open box (looking into the hole and away from it), on
//! mirrored placements, and for random views of random open primitives, with VISP on points
//! of every culled piece as a second, independent witness.

use std::sync::Arc;

use super::common::*;
use crate::geom::{M4, P3, V3};
use crate::query::PointVisibility;
use crate::scene::{CapFailure, Content, Mesh, Object, Scene, Solidity};
use crate::view::{Camera, Facing, View};
use crate::visibility::visp::visp;

/// A box [0,1]×[0,1]×[0,h] with its top (z = h) missing: 5 faces, open at the top.
fn open_box(h: f64) -> Mesh {
    let p: Vec<[f64; 3]> = (0..8)
        .map(|i| {
            [
                (i & 1) as f64,
                ((i >> 1) & 1) as f64,
                ((i >> 2) & 1) as f64 * h,
            ]
        })
        .collect();
    mesh(
        &p,
        &[
            &[0, 2, 3, 1], // floor, facing -z
            &[0, 1, 5, 4], // y = 0
            &[2, 6, 7, 3], // y = 1
            &[0, 4, 6, 2], // x = 0
            &[1, 3, 7, 5], // x = 1
        ],
    )
}

fn prepared(s: &Scene) -> Scene {
    let mut p = s.clone();
    super::common::prepare(&mut p);
    p
}

/// Culled pieces of a prepared scene's view, and the per-face areas of the prepared and the
/// unprepared (two-sided) renders, which must agree to 1e-9 of the total.
fn compare(s: &Scene, cam: Camera) -> usize {
    let (_, two_sided) = run(s, cam);
    let p = prepared(s);
    let (view, capped) = run(&p, cam);
    let (a, b) = (areas(&two_sided), areas(&capped));
    let total: f64 = a.iter().sum();
    for (k, (x, y)) in a.iter().zip(&b).enumerate() {
        assert!(
            (x - y).abs() <= 1e-9 * total.max(1e-300),
            "face {k}: two-sided {x}, capped {y}"
        );
    }
    check_culled_are_hidden(&view);
    view.screen
        .piece_ids()
        .filter(|&f| view.screen.piece(f).culled)
        .count()
}

/// VISP (an independent path: point against occluders) on points inside every culled piece:
/// each is hidden by the faces the view kept.
fn check_culled_are_hidden(view: &View) {
    let root = view.tree.root();
    for f in view.screen.piece_ids() {
        let pc = view.screen.piece(f);
        if !pc.culled {
            continue;
        }
        let w = view.screen.world_pts(f);
        for k in 1..w.len() - 1 {
            // Barycentrics away from round numbers: a ray through an edge of the occluders
            // would be on their boundary, where VISP rightly says visible.
            for (a, b) in [(0.2137, 0.3119), (0.6073, 0.1931), (0.1171, 0.6967)] {
                let p = w[0] + (w[k] - w[0]) * a + (w[k + 1] - w[0]) * b;
                assert_eq!(
                    visp(view, root, &p, Some(pc.face)),
                    PointVisibility::Hidden,
                    "culled piece {f} of face {}: {p:?} is visible",
                    pc.face
                );
            }
        }
    }
}

fn solidity_of(s: &Scene) -> Vec<Solidity> {
    let mut out = Vec::new();
    s.root.for_each_mesh(&M4::identity(), &mut |_, m, _| {
        out.push(m.solidity.unwrap())
    });
    out
}

#[test]
fn the_open_box_caps_and_culls_only_away_from_its_mouth() {
    let s = scene(vec![("box", open_box(1.0))]);
    let p = prepared(&s);
    assert_eq!(solidity_of(&p), vec![Solidity::Capped(1)]);
    let Content::Subobjects(subs) = &p.root.content else {
        panic!()
    };
    assert_eq!(subs[0].mesh().unwrap().caps.len(), 4);

    // From below: the cap faces away, so every back face is culled (the floor faces us).
    let below = Camera::orthographic(V3::new(0.3, 0.2, 1.0), V3::y()).unwrap();
    assert_eq!(compare(&s, below), 2);

    // Looking into the mouth: the cap faces us and lies over everything; the inside of the
    // floor and the far walls is seen through the hole and nothing may be culled.
    let into = Camera::orthographic(V3::new(0.3, 0.2, -1.0), V3::y()).unwrap();
    assert_eq!(compare(&s, into), 0);
    let (_, vis) = run(&p, into);
    assert!(vis.face(crate::FaceId(0)).area > 0.5, "the floor is seen");

    // In perspective, from above the mouth and from below.
    let c = P3::new(0.5, 0.5, 0.5);
    let above = Camera::perspective(P3::new(1.2, 0.9, 3.0), c, V3::y(), 50.0, 0.01).unwrap();
    assert_eq!(compare(&s, above), 0);
    let under = Camera::perspective(P3::new(1.2, 0.9, -3.0), c, V3::y(), 50.0, 0.01).unwrap();
    // The eye is beyond x = 1 and between y = 0 and y = 1: the walls x = 0, y = 0, y = 1
    // face away.
    assert_eq!(compare(&s, under), 3);
    // The eye inside the box (behind no near plane of the scene's hull): nothing culled.
    let inside = Camera::perspective(
        P3::new(0.5, 0.5, 0.4),
        P3::new(0.5, 0.5, 0.0),
        V3::y(),
        90.0,
        0.01,
    )
    .unwrap();
    assert_eq!(compare(&s, inside), 0);
}

#[test]
fn a_tall_open_box_seen_from_the_side_culls_the_back_faces_below_the_mouth() {
    // Seen from the side and a little above, the mouth is a thin sliver at the top: the far
    // wall, tall, reaches it and stays; the floor, far below, is culled.
    let s = scene(vec![("tower", open_box(6.0))]);
    let cam = Camera::orthographic(V3::new(0.2, 1.0, -0.15), V3::z()).unwrap();
    let culled = compare(&s, cam);
    assert_eq!(culled, 1);
    let p = prepared(&s);
    let v = View::new(&p, cam);
    let floor = v.screen.pieces_of(crate::FaceId(0)).next().unwrap();
    assert!(v.screen.piece(floor).culled);
    assert_eq!(v.screen.piece(floor).facing, Facing::Back);
}

#[test]
fn mirrored_placements_cull_like_their_image() {
    let proto = Arc::new(Object::from_mesh("box", open_box(2.0)));
    let mirror = M4::new_nonuniform_scaling(&V3::new(-1.0, 1.0, 1.0));
    let flip_z = translate(3.0, 0.0, 0.0) * M4::new_nonuniform_scaling(&V3::new(1.0, 1.0, -1.0));
    let s = Scene::new(
        Object::group(
            "",
            vec![
                instance("plain", &proto, translate(-3.0, 0.0, 0.0)),
                instance("mirrored", &proto, mirror),
                instance("upside-down", &proto, flip_z),
            ],
        ),
        "test".into(),
    );
    let mut culled = 0;
    for dir in [
        V3::new(0.3, 0.2, 1.0),
        V3::new(0.3, 0.2, -1.0),
        V3::new(-0.4, 1.0, 0.3),
        V3::new(0.1, -1.0, -0.4),
    ] {
        culled += compare(
            &s,
            Camera::orthographic(dir, V3::new(0.1, 0.2, 1.0)).unwrap(),
        );
    }
    assert!(culled > 0);
}

#[test]
fn random_views_of_random_open_primitives_equal_the_two_sided_answer() {
    let names = crate::primitives::names();
    let mut rng = Rng::new(0x5DEECE66D);
    let (mut culled, mut capped, mut refused) = (0, 0, 0);
    for round in 0..4 {
        let objs: Vec<(String, Mesh)> = (0..10)
            .map(|i| {
                let raw = crate::primitives::by_name(names[(i + round) % names.len()]).unwrap();
                let s = 0.3 + 0.3 * rng.unit();
                let t = V3::new(rng.unit() * 2.0, rng.unit() * 2.0, rng.unit() * 2.0);
                // Drop one or two faces (neighbours or not).
                let mut faces = raw.faces.clone();
                for _ in 0..1 + (rng.unit() * 2.0) as usize {
                    let k = (rng.unit() * faces.len() as f64) as usize;
                    faces.remove(k.min(faces.len() - 1));
                }
                let raw = crate::geom::PolyMesh::new(
                    raw.vertices
                        .iter()
                        .map(|v| P3::from(v.coords * s + t))
                        .collect(),
                    faces,
                );
                (format!("o{i}"), prim(raw))
            })
            .collect();
        let s = scene(objs.iter().map(|(n, m)| (n.as_str(), m.clone())).collect());
        for st in solidity_of(&prepared(&s)) {
            match st {
                Solidity::Capped(_) => capped += 1,
                Solidity::Open(_) => refused += 1,
                other => panic!("{other:?}"),
            }
        }
        let centre = P3::new(1.2, 1.2, 1.2);
        let mut cams = vec![];
        for _ in 0..3 {
            let d = V3::new(rng.unit() - 0.5, rng.unit() - 0.5, rng.unit() - 0.5);
            cams.push(Camera::orthographic(d, V3::new(0.1, 1.0, 0.2)).unwrap());
        }
        let eye = centre + V3::new(rng.unit() * 6.0 - 3.0, 2.5, rng.unit() * 6.0 - 3.0);
        cams.push(Camera::perspective(eye, centre, V3::y(), 50.0, 0.01).unwrap());
        for cam in cams {
            culled += compare(&s, cam);
        }
    }
    assert!(
        capped > 20 && culled > 100,
        "capped {capped}, culled {culled}"
    );
    eprintln!("capped {capped}, refused {refused}, culled {culled}");
}

#[test]
fn a_sheet_is_refused_and_keeps_two_sides() {
    // One square: flat, so no cap encloses anything.
    let s = scene(vec![("sheet", square(0.0, 0.0, 1.0, 0.0))]);
    let st = solidity_of(&prepared(&s));
    assert_eq!(st[0], Solidity::Open(CapFailure::InsideOut));
    assert_eq!(compare(&s, top()), 0);
}

/// A unit cube of triangles whose top edge y = 0, z = 1 has its midpoint as a corner of the
/// top's triangles but not of the front's: a T-junction crack (a hole of zero area).
fn cracked_cube() -> Mesh {
    let mut p: Vec<[f64; 3]> = (0..8)
        .map(|i| [(i & 1) as f64, ((i >> 1) & 1) as f64, ((i >> 2) & 1) as f64])
        .collect();
    p.push([0.5, 0.0, 1.0]); // 8: on the edge 4-5
    mesh(
        &p,
        &[
            &[0, 2, 3],
            &[0, 3, 1], // floor, facing -z
            &[0, 1, 5],
            &[0, 5, 4], // front, y = 0: the edge 5 -> 4 passes over 8
            &[2, 6, 7],
            &[2, 7, 3], // back, y = 1
            &[0, 4, 6],
            &[0, 6, 2], // x = 0
            &[1, 3, 7],
            &[1, 7, 5], // x = 1
            &[4, 8, 6],
            &[8, 5, 7],
            &[8, 7, 6], // top, z = 1, through 8
        ],
    )
}

#[test]
fn a_t_junction_crack_is_closed_and_the_cube_culls_like_the_two_sided_render() {
    let s = scene(vec![("cube", cracked_cube())]);
    assert!(matches!(
        solidity_of(&prepared(&s))[..],
        [Solidity::Capped(1)]
    ));
    let mut culled = 0;
    for d in [
        V3::new(-1.0, -2.0, -3.0),
        V3::new(0.3, 1.0, -0.2),
        V3::new(0.0, 0.4, -1.0),
    ] {
        culled += compare(&s, Camera::orthographic(d, V3::y()).unwrap());
    }
    let eye = P3::new(0.5, -3.0, 2.5);
    culled += compare(
        &s,
        Camera::perspective(eye, P3::new(0.5, 0.5, 0.5), V3::z(), 50.0, 0.01).unwrap(),
    );
    assert!(culled >= 12, "culled {culled}");
}
