//! The fast path against the independent exact check (src/exact: rationals, no boolean
//! engine, no tolerance): hand-worked cases, self-intersecting and inside-out solids that
//! culling used to get wrong, random scenes of every kind, and the shared meshes.

use super::common::*;
use crate::exact::{check, ExactReport};
use crate::geom::{P3, V3};
use crate::scene::{Scene, Solidity};
use crate::view::Camera;
use crate::FaceId;

/// Renders as a user would (prepared: culling where proven safe) and checks every face.
fn prepared_check(mut scene: Scene, cam: Camera, faces: Option<&[FaceId]>) -> ExactReport {
    super::common::prepare(&mut scene);
    let r = super::common::render_plain(&scene, &cam);
    check(&scene, &cam, &r.visibility, faces)
}

fn assert_agrees(what: &str, rep: &ExactReport) {
    for f in rep.disagreements() {
        eprintln!("{what}: {f:?}");
    }
    assert!(
        rep.agrees(),
        "{what}: {} faces disagree; claimed {} exact {}",
        rep.disagreements().len(),
        rep.claimed(),
        rep.visible
    );
}

#[test]
fn unit_cube_from_a_corner() {
    let s = scene(vec![("cube", cuboid([0., 0., 0.], [1., 1., 1.]))]);
    let cam = Camera::orthographic(V3::new(-1., -1., -1.), V3::y()).unwrap();
    let rep = prepared_check(s, cam, None);
    assert_agrees("cube", &rep);
    // Three faces each show 1/sqrt(3) of screen area... the projected hexagon is sqrt(3).
    assert!((rep.visible - 3f64.sqrt()).abs() < 1e-12, "{}", rep.visible);
}

/// A prepared scene whose first leaf is forced to count as a solid: the old cull rule.
fn force_cull(mut scene: Scene) -> Scene {
    super::common::prepare(&mut scene);
    if let crate::scene::Content::Subobjects(subs) = &mut scene.root.content {
        if let crate::scene::Content::Mesh(m) = &mut subs[0].content {
            m.solidity = Some(Solidity::Solid);
        }
    }
    scene
}

fn solidity_of(scene: &Scene) -> Solidity {
    crate::prepare::solidity::solidity(scene.leaves()[0].mesh)
}

/// An octahedron whose top apex is pulled down and out through the side: closed and
/// consistently oriented, but its faces cross (a fold).
fn fold() -> Scene {
    scene(vec![("fold", fold_mesh())])
}

/// The mesh of [`fold`].
fn fold_mesh() -> crate::scene::Mesh {
    let pts = [
        [1., 0., 0.],
        [0., 1., 0.],
        [-1., 0., 0.],
        [0., -1., 0.],
        [0.9, 0.9, -0.3],
        [0., 0., -1.],
    ];
    let faces: [&[u32]; 8] = [
        &[0, 1, 4],
        &[1, 2, 4],
        &[2, 3, 4],
        &[3, 0, 4],
        &[1, 0, 5],
        &[2, 1, 5],
        &[3, 2, 5],
        &[0, 3, 5],
    ];
    mesh(&pts, &faces)
}

/// The unit tetrahedron wound inwards.
fn inward_tetrahedron() -> Scene {
    let pts = [[0., 0., 0.], [1., 0., 0.], [0., 1., 0.], [0., 0., 1.]];
    scene(vec![(
        "tet",
        mesh(&pts, &[&[0, 1, 2], &[0, 3, 1], &[0, 2, 3], &[1, 3, 2]]),
    )])
}

#[test]
fn fold_and_inside_out_tetrahedron_match_the_exact_answer() {
    let cases = [
        ("fold", fold(), V3::new(0., 0., -1.)),
        ("fold, oblique", fold(), V3::new(-0.3, -0.5, -1.)),
        (
            "inward tetrahedron",
            inward_tetrahedron(),
            V3::new(-1., -1., -1.),
        ),
    ];
    for (what, s, dir) in cases {
        let cam = Camera::orthographic(dir, V3::y()).unwrap();
        assert!(!solidity_of(&s).is_solid(), "{what}: {:?}", solidity_of(&s));
        assert_agrees(what, &prepared_check(s.clone(), cam, None));
        // The old rule (culling it as a solid) gives a wrong answer, and the check sees it.
        let forced = force_cull(s.clone());
        let r = super::common::render_plain(&forced, &cam);
        assert!(
            !check(&forced, &cam, &r.visibility, None).agrees(),
            "{what}: culling must be wrong here"
        );
    }
    assert!(matches!(
        solidity_of(&fold()),
        Solidity::SelfIntersecting(_)
    ));
    assert_eq!(solidity_of(&inward_tetrahedron()), Solidity::InsideOut);
    // Seen from (1, 1, 1) the inward tetrahedron shows its three inner faces at the origin
    // corner, each a right triangle of area 1/2 projected by 1/sqrt(3): sqrt(3)/2 in all.
    let cam = Camera::orthographic(V3::new(-1., -1., -1.), V3::y()).unwrap();
    let rep = prepared_check(inward_tetrahedron(), cam, None);
    assert!(
        (rep.visible - 3f64.sqrt() / 2.0).abs() < 1e-12,
        "{}",
        rep.visible
    );
}

/// A random convex solid (a primitive) scaled and placed, optionally wound inwards.
fn solid(rng: &mut Rng, k: usize, inward: bool) -> crate::scene::Mesh {
    // The three smallest Platonic solids: the check is exact, and slow.
    let raw = crate::primitives::by_name(["tetrahedron", "cube", "octahedron"][k % 3]).unwrap();
    let s = 0.3 + 0.4 * rng.unit();
    let t = V3::new(rng.unit(), rng.unit(), rng.unit());
    let faces = raw
        .faces
        .iter()
        .map(|f| {
            let mut f = f.clone();
            if inward {
                f.reverse();
            }
            f
        })
        .collect();
    prim(crate::geom::PolyMesh::new(
        raw.vertices
            .iter()
            .map(|v| P3::from(v.coords * s + t))
            .collect(),
        faces,
    ))
}

/// Two solids joined into one mesh (they overlap: a self-intersecting closed surface).
fn joined(a: &crate::scene::Mesh, b: &crate::scene::Mesh) -> crate::scene::Mesh {
    let mut pts: Vec<[f64; 3]> = a.vertices.iter().map(|p| [p.x, p.y, p.z]).collect();
    let off = pts.len() as u32;
    pts.extend(b.vertices.iter().map(|p| [p.x, p.y, p.z]));
    let faces: Vec<Vec<u32>> = a
        .faces
        .iter()
        .map(|f| f.vertices.to_vec())
        .chain(
            b.faces
                .iter()
                .map(|f| f.vertices.iter().map(|v| v + off).collect()),
        )
        .collect();
    let refs: Vec<&[u32]> = faces.iter().map(|f| f.as_slice()).collect();
    mesh(&pts, &refs)
}

/// Random small scenes of every kind the fast path must get right.
fn random_scene(rng: &mut Rng, kind: usize) -> Scene {
    match kind {
        // Interpenetrating triangles.
        0 => scene(
            (0..6)
                .map(|i| {
                    let c = [rng.unit(), rng.unit(), rng.unit()];
                    let p: Vec<[f64; 3]> = (0..3)
                        .map(|_| std::array::from_fn(|k| c[k] + (rng.unit() - 0.5) * 1.2))
                        .collect();
                    (["a", "b", "c", "d", "e", "f"][i], mesh(&p, &[&[0, 1, 2]]))
                })
                .collect(),
        ),
        // Cyclic overlap: three bars each over the next.
        1 => {
            let j = 0.05 * rng.unit();
            scene(vec![
                ("x", cuboid([0., 0., 0.], [3., 0.6, 0.2 + j])),
                ("y", cuboid([2.3, 0., 0.1], [2.9, 3., 0.4])),
                (
                    "z",
                    mesh(
                        &[
                            [3., 2.4, 0.3],
                            [0., 2.4, -0.1],
                            [0., 3., -0.1],
                            [3., 3., 0.3],
                        ],
                        &[&[0, 1, 2, 3]],
                    ),
                ),
                ("w", cuboid([0., 0., -0.3 + j], [0.6, 3., -0.05])),
            ])
        }
        // Coplanar overlapping faces of different objects.
        2 => {
            let z = (rng.unit() * 4.0).round() / 4.0;
            scene(vec![
                ("p", square(0., 0., 1., z)),
                ("q", square(0.25 + 0.5 * rng.unit(), 0.25, 1., z)),
                ("r", cuboid([0.5, 0.5, z], [1.2, 1.4, z + 0.5])),
            ])
        }
        // Self-intersecting closed solids: overlapping primitives joined into one mesh.
        3 => {
            let (a, b) = (solid(rng, 1, false), solid(rng, 2, false));
            scene(vec![
                ("joined", joined(&a, &b)),
                ("other", solid(rng, 3, false)),
            ])
        }
        // One mesh of four pieces through one another: a fold (crossing itself), an inside-out
        // solid and two proper ones. Only the proper ones are proven and culled.
        5 => {
            let good = joined(&solid(rng, 1, false), &solid(rng, 2, false));
            let bad = joined(&fold_mesh(), &solid(rng, 0, true));
            scene(vec![("parts", joined(&good, &bad))])
        }
        // Inside-out solids, next to a proper one.
        _ => scene(vec![
            ("inward", solid(rng, 4, true)),
            ("outward", solid(rng, 0, false)),
            ("inward2", solid(rng, 5, true)),
        ]),
    }
}

#[test]
fn random_scenes_of_every_kind_match_the_exact_answer() {
    let mut rng = Rng::new(11);
    // One round in the suite (the check is big-number arithmetic, slow in a dev build);
    // KEPLER_EXACT_ROUNDS=N runs more.
    let rounds = std::env::var("KEPLER_EXACT_ROUNDS")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(1);
    for round in 0..rounds {
        for kind in 0..6 {
            let s = random_scene(&mut rng, kind);
            let b = s.cbox();
            let (c, r) = (b.center(), (b.hi - b.lo).norm());
            let dir = V3::new(rng.unit() - 0.5, rng.unit() - 0.5, -1.0);
            let cams = [
                Camera::orthographic(dir, V3::y()).unwrap(),
                Camera::perspective(c - dir.normalize() * 1.2 * r, c, V3::y(), 50.0, 0.3 * r)
                    .unwrap(),
            ];
            for (ci, cam) in cams.into_iter().enumerate() {
                let what = format!("round {round} kind {kind} camera {ci}");
                assert_agrees(&what, &prepared_check(s.clone(), cam, None));
            }
        }
    }
}

/// One mesh holding a fold (crossing itself), an inside-out solid and two proper
/// solids, all through one another: the proper pieces are proven and their back faces
/// culled; the fold's back faces (the nearest surface from below) are not. The exact check
/// agrees in four views, and forcing the whole mesh to cull is wrong and seen to be.
#[test]
fn only_proven_pieces_cull() {
    let mut rng = Rng::new(5);
    let good = joined(&solid(&mut rng, 1, false), &solid(&mut rng, 2, false));
    let bad = joined(&fold_mesh(), &solid(&mut rng, 0, true));
    let s = scene(vec![("parts", joined(&good, &bad))]);
    let mut prepared = s.clone();
    super::common::prepare(&mut prepared);
    let m = prepared.leaves()[0].mesh;
    assert!(
        matches!(m.solidity, Some(Solidity::SelfIntersecting(_))),
        "{:?} {:?}",
        m.solidity,
        m.proven
    );
    let p = m.proven.as_ref().expect("the proper pieces are proven");
    assert_eq!((p.proven, p.pieces), (2, 4));
    let good_faces = good.faces.len();
    assert!(p.faces[..good_faces].iter().all(|&f| f));
    assert!(p.faces[good_faces..].iter().all(|&f| !f));
    for (k, dir) in [[0., 0., -1.], [0., 0., 1.], [-1., -2., -3.], [2., 1., -1.]]
        .into_iter()
        .enumerate()
    {
        let cam = Camera::orthographic(V3::new(dir[0], dir[1], dir[2]), V3::y()).unwrap();
        let r = super::common::render_plain(&prepared, &cam);
        assert!(
            r.stats.counters.faces_culled > 0,
            "view {k}: the proper pieces cull"
        );
        assert_agrees(
            &format!("pieces view {k}"),
            &prepared_check(s.clone(), cam, None),
        );
    }
    // From below the fold shows back faces nearest: culling the whole mesh is wrong.
    let cam = Camera::orthographic(V3::new(0., 0., 1.), V3::y()).unwrap();
    let forced = force_cull(s);
    let r = super::common::render_plain(&forced, &cam);
    assert!(!check(&forced, &cam, &r.visibility, None).agrees());
}

/// ogre: its body crosses itself, its 43 other pieces (armour, eyes, teeth) are proven,
/// some with their holes capped. Checked exactly on back faces of proven pieces (culled
/// unless near a cap) and a sample of the rest.
#[test]
fn ogre_proven_pieces_match_the_exact_answer() {
    let Some(path) = model("ogre.obj") else {
        return;
    };
    let mut s = super::common::load(&path);
    super::common::prepare(&mut s);
    let d = V3::new(-1., -2., -3.);
    let m = s.leaves()[0].mesh;
    let p = m.proven.as_ref().expect("ogre's pieces are proven");
    assert_eq!((p.proven, p.pieces), (43, 44));
    let back = |f: &crate::scene::Face| {
        let v = |i: usize| m.vertices[f.vertices[i] as usize];
        (v(1) - v(0)).cross(&(v(2) - v(0))).dot(&d) > 0.0
    };
    let step = std::env::var("KEPLER_EXACT_STEP")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(9973);
    let mut faces: Vec<FaceId> = (0..m.faces.len())
        .filter(|&k| p.faces[k] && back(&m.faces[k]))
        .step_by(step / 4)
        .map(|k| FaceId(k as u32))
        .collect();
    faces.extend((0..m.faces.len() as u32).step_by(step).map(FaceId));
    let cam = Camera::orthographic(d, V3::y()).unwrap();
    let r = super::common::render_plain(&s, &cam);
    assert!(
        r.stats.counters.faces_culled > 30_000,
        "{}",
        r.stats.counters.faces_culled
    );
    assert_agrees("ogre", &check(&s, &cam, &r.visibility, Some(&faces)));
}

/// The cow: closed and outward but 81 pairs of its triangles cross at the back end, where
/// two back faces are the nearest surface. Checked on the faces around that spot and a
/// sample of the rest (every face is an occluder of the check), orthographic and in
/// perspective; `kepler check cow.obj --exact` checks them all.
#[test]
fn cow_matches_the_exact_answer() {
    let Some(path) = model("cow.obj") else { return };
    let s = super::common::load(&path);
    assert_eq!(solidity_of(&s), Solidity::SelfIntersecting(81));
    let mut faces: Vec<FaceId> = [5380, 5381, 5382, 5446, 5465, 5472, 5473, 5474]
        .into_iter()
        .map(FaceId)
        .collect();
    // A sample of the rest: every 389th face in the suite (KEPLER_EXACT_STEP=N for more).
    let step = std::env::var("KEPLER_EXACT_STEP")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(389);
    faces.extend((0..s.face_count() as u32).step_by(step).map(FaceId));
    let b = s.cbox();
    let (c, r) = (b.center(), (b.hi - b.lo).norm());
    let d = V3::new(-1., -2., -3.);
    let cams = [
        Camera::orthographic(d, V3::y()).unwrap(),
        Camera::perspective(c - d.normalize() * 1.5 * r, c, V3::y(), 40.0, 0.1 * r).unwrap(),
    ];
    for (ci, cam) in cams.into_iter().enumerate() {
        let rep = prepared_check(s.clone(), cam, Some(&faces));
        assert_agrees(&format!("cow camera {ci}"), &rep);
        // Faces 5465 and 5473 (back faces, yet the nearest surface) show area.
        if ci == 0 {
            for id in [5465, 5473] {
                let f = rep.faces.iter().find(|f| f.face == FaceId(id)).unwrap();
                assert!(f.visible > 0.0, "face {id} shows nothing: {f:?}");
            }
        }
    }
}
