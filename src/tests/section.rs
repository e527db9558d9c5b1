//! Section views: cut points exact, faces kept in their places, section faces for closed
//! solids (several pieces, holes), outlines only for open meshes, culling kept sound, the
//! exact checker and the partition invariants on cut scenes, any thread count.

use super::common::*;
use crate::emit::lines::edges::EdgeKind;
use crate::emit::lines::LineOptions;
use crate::geom::{P3, V3};
use crate::scene::{Mesh, Object, Scene};
use crate::view::Camera;
use crate::{render, Outputs, Progress, RenderOptions, Rendered};

fn plane(p: [f64; 3], n: [f64; 3]) -> (P3, V3) {
    (P3::new(p[0], p[1], p[2]), V3::new(n[0], n[1], n[2]))
}

fn opts(planes: &[(P3, V3)]) -> RenderOptions {
    RenderOptions {
        sections: planes.to_vec(),
        outputs: Outputs {
            json: true,
            drawing: true,
            ..Outputs::default()
        },
        ..RenderOptions::default()
    }
}

fn cut<'s>(scene: &'s Scene, camera: &Camera, planes: &[(P3, V3)]) -> Rendered<'s> {
    render(scene, camera, &opts(planes), &Progress::default()).unwrap()
}

fn along(d: [f64; 3]) -> Camera {
    let up = if d[1].abs() > 0.9 { V3::z() } else { V3::y() };
    Camera::orthographic(V3::new(d[0], d[1], d[2]), up).unwrap()
}

/// The section faces of a render: (id, their world corners).
fn section_faces(r: &Rendered) -> Vec<Vec<P3>> {
    let info = r.scene.section.as_ref().unwrap();
    let mut out = Vec::new();
    for leaf in r.scene.leaves() {
        for (k, f) in leaf.mesh.faces.iter().enumerate() {
            if info.is_section((leaf.first_face + k) as u32) {
                out.push(f.vertices.iter().map(|&v| leaf.world_vertex(v)).collect());
            }
        }
    }
    out
}

/// Area of a planar 3D ring (half its Newell normal's length).
fn area3(r: &[P3]) -> f64 {
    crate::geom::newell(r).norm() / 2.0
}

/// Every face's claimed region against the exact answer on the cut scene.
fn exact_agrees(r: &Rendered, camera: &Camera) {
    let rep = crate::exact::check(&r.scene, camera, &r.visibility, None);
    assert!(rep.agrees(), "{:?}", rep.disagreements());
}

/// A closed shell: points and faces.
type Shell = (Vec<[f64; 3]>, Vec<Vec<u32>>);

/// A prism over a 2D polygon (counter-clockwise), from z0 to z1, outward faces.
fn prism(poly: &[[f64; 2]], z0: f64, z1: f64) -> Vec<Shell> {
    let n = poly.len() as u32;
    let mut pts: Vec<[f64; 3]> = poly.iter().map(|p| [p[0], p[1], z0]).collect();
    pts.extend(poly.iter().map(|p| [p[0], p[1], z1]));
    let mut faces: Vec<Vec<u32>> = vec![(0..n).rev().collect(), (n..2 * n).collect()];
    for i in 0..n {
        let j = (i + 1) % n;
        faces.push(vec![i, j, n + j, n + i]);
    }
    vec![(pts, faces)]
}

fn mesh_of(shells: Vec<Shell>) -> Mesh {
    let mut pts = Vec::new();
    let mut faces: Vec<Vec<u32>> = Vec::new();
    for (p, f) in shells {
        let base = pts.len() as u32;
        pts.extend(p);
        faces.extend(f.into_iter().map(|f| f.iter().map(|&k| k + base).collect()));
    }
    let refs: Vec<&[u32]> = faces.iter().map(Vec::as_slice).collect();
    mesh(&pts, &refs)
}

fn cube_scene() -> Scene {
    scene(vec![("cube", cuboid([0., 0., 0.], [1., 1., 1.]))])
}

#[test]
fn the_cube_cut_in_half_shows_its_section_alone() {
    let mut s = cube_scene();
    prepare(&mut s);
    let cam = along([-1., 0., 0.]);
    let r = cut(&s, &cam, &[plane([0.5, 0., 0.], [1., 0., 0.])]);
    let visible: Vec<_> = r
        .visibility
        .iter()
        .filter(|(_, f)| f.area > 0.0)
        .map(|(id, f)| (id.0, f.area))
        .collect();
    assert_eq!(visible.len(), 1, "{visible:?}");
    assert_eq!(visible[0].0, 6, "the section face follows the cube's six");
    assert!((visible[0].1 - 1.0).abs() < 1e-12);
    let json = r.json.as_deref().unwrap();
    assert!(json.contains("{\"id\":6,\"object\":\"section/cube\",\"section\":true,\"area\":1,"));
    exact_agrees(&r, &cam);
}

#[test]
fn cut_points_are_exact() {
    let s = cube_scene();
    // A cut 1e-9 from a face: the new corners sit exactly on the plane.
    let r = cut(
        &s,
        &Camera::three_quarter(),
        &[plane([1e-9, 0., 0.], [-1., 0., 0.])],
    );
    let secs = section_faces(&r);
    assert_eq!(secs.len(), 1);
    assert!(secs[0].iter().all(|p| p.x == 1e-9), "{:?}", secs[0]);
    assert!((area3(&secs[0]) - 1.0).abs() < 1e-12);
    exact_agrees(&r, &Camera::three_quarter());
    // Oblique, through the centre: a regular hexagon whose corners are edge midpoints, the
    // exact crossings (representable here), on the plane x + y + z = 1.5 exactly.
    let r = cut(
        &s,
        &Camera::three_quarter(),
        &[plane([0.5; 3], [1., 1., 1.])],
    );
    let secs = section_faces(&r);
    assert_eq!(secs.len(), 1);
    assert_eq!(secs[0].len(), 6);
    for p in &secs[0] {
        assert_eq!(p.x + p.y + p.z, 1.5);
        assert!(p.iter().all(|c| [0., 0.5, 1.].contains(c)), "{p}");
    }
    // The hexagon faces the normal (the removed side): counter-clockwise seen from it.
    assert!(crate::geom::newell(&secs[0]).dot(&V3::new(1., 1., 1.)) > 0.0);
    exact_agrees(&r, &Camera::three_quarter());
    // An oblique plane whose crossings round: each corner is the exact point rounded once.
    let pl = plane([0.1, 0.2, 0.3], [0.3, 1.7, 0.9]);
    let r = cut(&s, &Camera::three_quarter(), &[pl]);
    assert_eq!(section_faces(&r).len(), 1);
    for p in section_faces(&r).concat() {
        // Within half an ulp per coordinate of the plane: its exact side may be either, but
        // the f64 distance is tiny.
        let d = (p - pl.0).dot(&pl.1);
        assert!(d.abs() < 1e-15, "{p}: {d}");
    }
    exact_agrees(&r, &Camera::three_quarter());
}

#[test]
fn vertices_on_the_plane_stay_and_make_no_new_points() {
    let s = cube_scene();
    // Through three corners: the kept corner tetrahedron's section is that triangle.
    let r = cut(
        &s,
        &Camera::three_quarter(),
        &[plane([1., 0., 0.], [1., 1., 1.])],
    );
    let secs = section_faces(&r);
    assert_eq!(secs.len(), 1);
    let mut got: Vec<[f64; 3]> = secs[0].iter().map(|p| [p.x, p.y, p.z]).collect();
    got.sort_by(|a, b| a.partial_cmp(b).unwrap());
    assert_eq!(got, vec![[0., 0., 1.], [0., 1., 0.], [1., 0., 0.]]);
    // Every vertex of the cut scene is a cube corner: no crossing was made.
    for leaf in r.scene.leaves() {
        for v in leaf.world_vertices() {
            assert!(v.iter().all(|c| *c == 0.0 || *c == 1.0), "{v}");
        }
    }
    exact_agrees(&r, &Camera::three_quarter());
}

#[test]
fn a_plane_through_a_face_changes_nothing() {
    let mut s = cube_scene();
    prepare(&mut s);
    let cam = Camera::three_quarter();
    let plain = cut(&s, &cam, &[]).json.unwrap();
    for pl in [
        plane([1., 0., 0.], [1., 0., 0.]),
        plane([0., 0., 0.], [-1., 0., 0.]),
        plane([0., 5., 0.], [0., 1., 0.]),
    ] {
        let r = cut(&s, &cam, &[pl]);
        assert_eq!(r.json.unwrap(), plain, "{pl:?}");
        assert!(section_faces(&cut(&s, &cam, &[pl])).is_empty());
    }
}

#[test]
fn surviving_faces_keep_their_ids() {
    let s = scene(vec![
        ("a", cuboid([0., 0., 0.], [1., 1., 1.])),
        ("b", cuboid([2., 0., 0.], [3., 1., 1.])),
    ]);
    let cam = Camera::three_quarter();
    let plain = cut(&s, &cam, &[]);
    let r = cut(&s, &cam, &[plane([2.5, 0., 0.], [1., 0., 0.])]);
    // b's +x face (id 6 + its local index) is gone; a is untouched, byte for byte.
    for (id, f) in plain.visibility.iter() {
        let g = r.visibility.face(id);
        if id.0 < 6 {
            assert_eq!(f.visible(), g.visible(), "face {id:?} of the uncut cube");
        }
    }
    assert_eq!(r.scene.section.as_ref().unwrap().first_face, 12);
    assert_eq!(r.scene.section.as_ref().unwrap().removed.len(), 1);
    assert_eq!(section_faces(&r).len(), 1);
    exact_agrees(&r, &cam);
}

#[test]
fn a_u_shape_cut_across_its_arms_gives_two_sections() {
    let u = [
        [0., 0.],
        [3., 0.],
        [3., 3.],
        [2., 3.],
        [2., 1.],
        [1., 1.],
        [1., 3.],
        [0., 3.],
    ];
    let s = scene(vec![("u", mesh_of(prism(&u, 0., 1.)))]);
    let cam = along([0., -1., 0.]);
    let r = cut(&s, &cam, &[plane([0., 2., 0.], [0., 1., 0.])]);
    let secs = section_faces(&r);
    assert_eq!(secs.len(), 2);
    for sf in &secs {
        assert!((area3(sf) - 1.0).abs() < 1e-12);
        assert!(sf.iter().all(|p| p.y == 2.0));
    }
    exact_agrees(&r, &cam);
}

#[test]
fn a_hollow_box_gives_a_section_with_a_hole() {
    // A 4x4x4 box with a 2x2x2 box-shaped hole: two shells, the inner turned inside out.
    let outer = prism(&[[0., 0.], [4., 0.], [4., 4.], [0., 4.]], 0., 4.);
    let mut inner = prism(&[[1., 1.], [3., 1.], [3., 3.], [1., 3.]], 1., 3.);
    for f in &mut inner[0].1 {
        f.reverse();
    }
    let s = scene(vec![("hollow", mesh_of([outer, inner].concat()))]);
    let cam = along([0., 0., -1.]);
    let r = cut(&s, &cam, &[plane([0., 0., 2.], [0., 0., 1.])]);
    let secs = section_faces(&r);
    let total: f64 = secs.iter().map(|f| area3(f)).sum();
    assert!((total - 12.0).abs() < 1e-12, "{total}");
    // Seen from above: the section (12) and, through its hole, the hole's floor (4).
    let info = r.scene.section.clone().unwrap();
    let seen: f64 = r
        .visibility
        .iter()
        .filter(|(id, _)| info.is_section(id.0))
        .map(|(_, f)| f.area)
        .sum();
    assert!((seen - 12.0).abs() < 1e-12, "{seen}");
    let floor: f64 = r
        .visibility
        .iter()
        .filter(|(id, _)| !info.is_section(id.0))
        .map(|(_, f)| f.area)
        .sum();
    assert!((floor - 4.0).abs() < 1e-12, "{floor}");
    exact_agrees(&r, &cam);
}

#[test]
fn an_open_mesh_gets_its_cut_outline_only() {
    // A cube without its top: open, not capped (unprepared).
    let pts = [
        [0., 0., 0.],
        [1., 0., 0.],
        [1., 1., 0.],
        [0., 1., 0.],
        [0., 0., 1.],
        [1., 0., 1.],
        [1., 1., 1.],
        [0., 1., 1.],
    ];
    let faces: [&[u32]; 5] = [
        &[0, 3, 2, 1],
        &[0, 1, 5, 4],
        &[1, 2, 6, 5],
        &[2, 3, 7, 6],
        &[3, 0, 4, 7],
    ];
    let s = scene(vec![("open", mesh(&pts, &faces))]);
    let cam = Camera::three_quarter();
    let r = cut(&s, &cam, &[plane([0.5, 0., 0.], [1., 0., 0.])]);
    assert_eq!(r.scene.face_count(), 5, "no section face");
    let d = r.drawing.as_ref().unwrap();
    let sec: Vec<_> = d
        .visible
        .iter()
        .filter(|s| s.kind == EdgeKind::Section)
        .collect();
    assert!(
        !sec.is_empty(),
        "the cut outline is drawn with the section pen"
    );
    exact_agrees(&r, &cam);
    // A closed cube's cut gets a section face, and its outline is the section's too.
    let cube = cube_scene();
    let r = cut(&cube, &cam, &[plane([0.5, 0., 0.], [1., 0., 0.])]);
    assert_eq!(r.scene.face_count(), 7);
}

#[test]
fn a_non_convex_face_cut_into_parts_gives_simple_rings_and_only_its_cut() {
    // An arch (legs down) in z = 0, cut at y = 0.5: its kept part is the two legs, one face.
    // Its region is two simple rings, and the cut outline runs along the legs only (2 units),
    // not across the gap between them.
    let pts = [
        [0., 0., 0.],
        [1., 0., 0.],
        [1., 1., 0.],
        [2., 1., 0.],
        [2., 0., 0.],
        [3., 0., 0.],
        [3., 2., 0.],
        [0., 2., 0.],
    ];
    let faces: [&[u32]; 1] = [&[0, 1, 2, 3, 4, 5, 6, 7]];
    let s = scene(vec![("arch", mesh(&pts, &faces))]);
    let cam = along([0., 0., -1.]);
    let r = cut(&s, &cam, &[plane([0., 0.5, 0.], [0., 1., 0.])]);
    let fv = r.visibility.face(crate::scene::FaceId(0));
    let region = fv.visible();
    assert_eq!(region.len(), 2, "{region:?}");
    assert!(
        crate::geom::ring_check::multipolygon_defects(&region).is_empty(),
        "{region:?}"
    );
    assert!((fv.area - 1.0).abs() < 1e-15, "{}", fv.area);
    let d = r.drawing.as_ref().unwrap();
    let cut_len: f64 = d
        .visible
        .iter()
        .filter(|s| s.kind == EdgeKind::Section)
        .flat_map(|s| s.pts.windows(2))
        .map(|w| (w[1][0] - w[0][0]).hypot(w[1][1] - w[0][1]))
        .sum();
    assert!((cut_len - 2.0).abs() < 1e-12, "cut outline {cut_len}");
    exact_agrees(&r, &cam);
}

#[test]
fn inboxes_on_the_removed_side_are_dropped() {
    // A wall with an INBOX on its group hides a small box behind it; cut away the wall in
    // front of the box, obliquely (x + z > 7.5), and what is left of the box shows.
    let mut wall = Object::group(
        "g",
        vec![Object::from_mesh(
            "wall",
            cuboid([0., 0., 1.], [10., 10., 2.]),
        )],
    );
    wall.inbox = Some(crate::geom::Box3::new(
        P3::new(0., 0., 1.),
        P3::new(10., 10., 2.),
    ));
    let small = Object::from_mesh("small", cuboid([7., 4., -1.], [8., 5., 0.]));
    let s = Scene::new(Object::group("", vec![wall, small]), "test".into());
    let cam = along([0., 0., -1.]);
    let plain = cut(&s, &cam, &[]);
    assert!(
        plain.view.culled.subtrees > 0,
        "the INBOX hides the small box uncut"
    );
    let r = cut(&s, &cam, &[plane([7.5, 0., 0.], [1., 0., 1.])]);
    assert_eq!(r.view.culled.subtrees, 0);
    let small_seen: f64 = r
        .visibility
        .iter()
        .filter(|(id, _)| (6..12).contains(&id.0))
        .map(|(_, f)| f.area)
        .sum();
    // The top's kept half (x <= 7.5 at z = 0).
    assert!((small_seen - 0.5).abs() < 1e-12, "{small_seen}");
    exact_agrees(&r, &cam);
}

#[test]
fn prepared_solids_and_several_planes() {
    // Proven solids (back faces culled where uncut) and two planes: the corner of a box cut
    // off by both; every face against the exact answer, from several cameras.
    let mut s = scene(vec![
        ("a", cuboid([0., 0., 0.], [2., 2., 2.])),
        ("b", cuboid([3., 0., 0.], [4., 1., 1.])),
        ("c", cuboid([-3., 0., -3.], [-2., 1., -2.])),
    ]);
    prepare(&mut s);
    let planes = [
        plane([1., 0., 0.], [1., 0., 0.2]),
        plane([0., 1.3, 0.], [0.1, 1., 0.]),
    ];
    for cam in [
        Camera::three_quarter(),
        along([-1., -0.4, -0.2]),
        along([1., 0.3, 0.5]),
        Camera::perspective(
            P3::new(6., 5., 7.),
            P3::new(1., 0.5, 0.5),
            V3::y(),
            50.,
            0.01,
        )
        .unwrap(),
    ] {
        let r = cut(&s, &cam, &planes);
        assert!(!section_faces(&r).is_empty());
        exact_agrees(&r, &cam);
        // Regions of different faces do not overlap and cover the projected faces.
        super::invariants::check_partition(&r.view, &r.visibility, 1e-9);
    }
}

#[test]
fn cut_output_is_identical_whatever_the_thread_count() {
    let s = scene(vec![
        ("a", cuboid([0., 0., 0.], [2., 2., 2.])),
        ("b", cuboid([1., 1., 1.], [3., 2.5, 2.5])),
    ]);
    let cam = Camera::three_quarter();
    let mut o = opts(&[plane([1.5, 1.2, 0.], [1., 0.3, 0.1])]);
    o.outputs.svg = true;
    let go = |n| {
        let r = rayon::ThreadPoolBuilder::new()
            .num_threads(n)
            .build()
            .unwrap()
            .install(|| render(&s, &cam, &o, &Progress::default()).unwrap());
        (r.json.unwrap(), r.svg.unwrap())
    };
    let one = go(1);
    assert_eq!(one, go(4));
    assert!(one.1.contains("7 section"), "{}", one.0);
}

#[test]
fn bad_planes_are_refused() {
    let s = cube_scene();
    for (pl, why) in [
        (plane([0., 0., 0.], [0., 0., 0.]), "the normal is zero"),
        (plane([f64::NAN, 0., 0.], [1., 0., 0.]), "not finite"),
        (plane([2e12, 0., 0.], [1., 0., 0.]), "beyond 1e12"),
    ] {
        let e = render(
            &s,
            &Camera::three_quarter(),
            &opts(&[pl]),
            &Progress::default(),
        )
        .unwrap_err()
        .to_string();
        assert!(e.contains(why), "{e}");
    }
}

#[test]
fn the_line_options_do_not_matter_to_the_cut() {
    // Hidden lines turn the cull off; the cut is the same.
    let s = cube_scene();
    let cam = Camera::three_quarter();
    let mut o = opts(&[plane([0.5, 0., 0.], [1., 0., 0.])]);
    let a = render(&s, &cam, &o, &Progress::default()).unwrap().json;
    o.lines = LineOptions {
        hidden: true,
        ..LineOptions::default()
    };
    let b = render(&s, &cam, &o, &Progress::default()).unwrap().json;
    assert_eq!(a, b);
}

#[test]
fn hidden_lines_leave_out_what_the_cut_removed() {
    let s = cube_scene();
    let cam = Camera::orthographic(V3::new(-0.3, -0.4, -1.), V3::y()).unwrap();
    let mut o = opts(&[plane([0.5, 0., 0.], [1., 0., 0.])]);
    o.lines = LineOptions {
        hidden: true,
        ..LineOptions::default()
    };
    let r = render(&s, &cam, &o, &Progress::default()).unwrap();
    let d = r.drawing.as_ref().unwrap();
    assert!(!d.hidden.is_empty());
    // Every point drawn is the projection of a point with x <= 0.5: screen x is world
    // x·m00 + y·m01 + z·m02; the removed half would reach further.
    let reach = |x: f64| {
        let m = cam.matrix;
        let mut best = f64::NEG_INFINITY;
        for y in [0., 1.] {
            for z in [0., 1.] {
                best = best.max(m[(0, 0)] * x + m[(0, 1)] * y + m[(0, 2)] * z);
            }
        }
        best
    };
    let limit = reach(0.5).max(reach(0.0)) + 1e-9;
    assert!(
        reach(1.0) > limit + 0.1,
        "the removed half would show beyond the limit"
    );
    for st in d.hidden.iter().chain(&d.visible) {
        for p in &st.pts {
            assert!(p[0] <= limit, "{p:?} beyond {limit}");
        }
    }
}
