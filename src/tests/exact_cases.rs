//! Exact answers worked by hand: overlapping squares, crossing planes, cyclic bars, an L-shaped
//! solid seen into its corner, a cube from a vertex-on view, coplanar faces, shared edges.

use super::common::*;
use crate::geom::V3;
use crate::view::Camera;
use crate::FaceId;

#[test]
fn two_overlapping_squares() {
    // A (z=1) over B (z=0), offset by (1,1): B loses exactly the 1x1 overlap.
    let s = scene(vec![
        ("a", square(1., 1., 2., 1.)),
        ("b", square(0., 0., 2., 0.)),
    ]);
    let (_, vis) = run(&s, top());
    assert_eq!(areas(&vis), vec![4.0, 3.0]);
    // B's VTP is the L-shaped hexagon: corners exact.
    let b = &vis.face(FaceId(1)).visible();
    assert_eq!(b.len(), 1);
    let mut pts = b[0][0].clone();
    pts.sort_by(|p, q| p.partial_cmp(q).unwrap());
    assert_eq!(
        pts,
        vec![[0., 0.], [0., 2.], [1., 1.], [1., 2.], [2., 0.], [2., 1.]]
    );
    // Reversing the heights swaps the roles.
    let s = scene(vec![
        ("a", square(1., 1., 2., 0.)),
        ("b", square(0., 0., 2., 1.)),
    ]);
    let (_, vis) = run(&s, top());
    assert_eq!(areas(&vis), vec![3.0, 4.0]);
}

#[test]
fn crossing_planes_hide_each_other_on_their_own_side() {
    // Two unit-wide strips crossing along x = 0: A rises with x (z = x), B falls (z = -x).
    let a = mesh(
        &[[-1., 0., -1.], [1., 0., 1.], [1., 1., 1.], [-1., 1., -1.]],
        &[&[0, 1, 2, 3]],
    );
    let b = mesh(
        &[[-1., 0., 1.], [1., 0., -1.], [1., 1., -1.], [-1., 1., 1.]],
        &[&[0, 1, 2, 3]],
    );
    let (_, vis) = run(&scene(vec![("a", a), ("b", b)]), top());
    // Each keeps exactly the half where it is on top: A for x > 0, B for x < 0.
    assert_eq!(areas(&vis), vec![1.0, 1.0]);
    for p in &vis.face(FaceId(0)).visible()[0][0] {
        assert!(p[0] >= 0.0, "{p:?}");
    }
    for p in &vis.face(FaceId(1)).visible()[0][0] {
        assert!(p[0] <= 0.0, "{p:?}");
    }
}

/// A flat bar from `p` to `q` of width `w`, rising linearly from z = 0 at `p` to z = 1 at `q`.
fn bar(p: [f64; 2], q: [f64; 2], w: f64) -> crate::scene::Mesh {
    let (dx, dy) = (q[0] - p[0], q[1] - p[1]);
    let len = (dx * dx + dy * dy).sqrt();
    let (nx, ny) = (-dy / len * w / 2.0, dx / len * w / 2.0);
    mesh(
        &[
            [p[0] - nx, p[1] - ny, 0.],
            [q[0] - nx, q[1] - ny, 1.],
            [q[0] + nx, q[1] + ny, 1.],
            [p[0] + nx, p[1] + ny, 0.],
        ],
        &[&[0, 1, 2, 3]],
    )
}

#[test]
fn three_cyclically_overlapping_bars() {
    // Three bars along the sides of an equilateral triangle, each extended by e past the
    // corners and rising along its length: at every corner the arriving bar (high end) lies
    // over the leaving bar (low end). A over B over C over A: no depth order exists.
    let (w, e) = (0.5, 1.0);
    let s3 = 3f64.sqrt();
    let corners = [[0.0, 0.0], [4.0, 0.0], [2.0, 2.0 * s3]];
    let ext = |a: [f64; 2], b: [f64; 2]| {
        let (dx, dy) = ((b[0] - a[0]) / 4.0, (b[1] - a[1]) / 4.0);
        (
            [a[0] - e * dx, a[1] - e * dy],
            [b[0] + e * dx, b[1] + e * dy],
        )
    };
    let bars: Vec<_> = (0..3)
        .map(|i| {
            let (p, q) = ext(corners[i], corners[(i + 1) % 3]);
            bar(p, q, w)
        })
        .collect();
    let names = ["a", "b", "c"];
    let s = scene(names.iter().zip(bars).map(|(n, m)| (*n, m)).collect());
    let (_, vis) = run(&s, top());
    // Each bar (length 6, width w) loses exactly one rhombus, the crossing of two strips of
    // width w at 60 degrees: area w^2 / sin 60.
    let expected = 6.0 * w - w * w / (s3 / 2.0);
    for f in vis.by_id() {
        close(f.area, expected, 1e-12);
    }
}

/// The L-shaped prism: L = (0,0),(2,0),(2,1),(1,1),(1,2),(0,2) extruded over z in [0,1].
fn l_solid() -> crate::scene::Mesh {
    let l = [[0., 0.], [2., 0.], [2., 1.], [1., 1.], [1., 2.], [0., 2.]];
    let mut pts = Vec::new();
    for z in [0., 1.] {
        for p in l {
            pts.push([p[0], p[1], z]);
        }
    }
    let mut faces: Vec<Vec<u32>> = vec![(0..6).rev().collect(), (6..12).collect()];
    for i in 0..6u32 {
        let j = (i + 1) % 6;
        faces.push(vec![i, j, j + 6, i + 6]);
    }
    let refs: Vec<&[u32]> = faces.iter().map(|f| f.as_slice()).collect();
    mesh(&pts, &refs)
}

#[test]
fn l_shaped_solid_seen_into_its_corner() {
    let m = l_solid();
    assert!(m.closed);
    // Toward the viewer: v = (1, -0.5, 0.3). The inner face x = 1 (y in [1,2]) faces the
    // viewer; rays from its points with y < 1.5 pass through the lower arm. Hidden part, in
    // (y, z) on the face: y in [1, 1.5], z <= 1 - 0.6 (y - 1): area 0.5 - 0.6/8 = 0.425.
    // Visible 0.575 of the unit face, projected by |n.v|/|v| = 1/sqrt(1.34).
    let s = scene(vec![("l", m)]);
    let cam = Camera::orthographic(V3::new(-1., 0.5, -0.3), V3::z()).unwrap();
    let (view, vis) = run(&s, cam);
    let inner = view
        .screen
        .piece_ids()
        .find(|&p| {
            view.screen
                .world_pts(p)
                .iter()
                .all(|w| w.x == 1.0 && w.y >= 1.0)
        })
        .map(|p| view.screen.piece(p).face)
        .unwrap();
    close(vis.face(inner).area, 0.575 / 1.34f64.sqrt(), 1e-12);
    // Front faces together cover the silhouette exactly once.
    let regions: Vec<_> = vis.by_id().into_iter().map(|f| f.visible()).collect();
    let parts: Vec<&crate::geom::poly2::MultiPolygon> = regions.iter().map(|m| &**m).collect();
    close(total_area(&parts), union_area_exact(&parts), 1e-14);
    close(total_area(&parts), union_area(&parts), 1e-9);
}

#[test]
fn cube_from_a_vertex_on_view() {
    let s = scene(vec![("cube", cuboid([0., 0., 0.], [1., 1., 1.]))]);
    let (_, vis) = run(
        &s,
        Camera::orthographic(V3::new(-1., -1., -1.), V3::y()).unwrap(),
    );
    let mut a = areas(&vis);
    a.sort_by(|x, y| x.partial_cmp(y).unwrap());
    let third = 1.0 / 3f64.sqrt();
    for (got, want) in a.iter().zip([0., 0., 0., third, third, third]) {
        close(*got, want, 1e-14);
    }
    // The silhouette is a regular hexagon of area sqrt(3) (edge sqrt(2/3)).
    close(a.iter().sum(), 3f64.sqrt(), 1e-14);
}

#[test]
fn coplanar_faces_earlier_is_in_front() {
    let s = scene(vec![
        ("first", square(1., 1., 2., 0.)),
        ("second", square(0., 0., 2., 0.)),
    ]);
    let (_, vis) = run(&s, top());
    assert_eq!(areas(&vis), vec![4.0, 3.0]);
    let s = scene(vec![
        ("first", square(0., 0., 2., 0.)),
        ("second", square(1., 1., 2., 0.)),
    ]);
    let (_, vis) = run(&s, top());
    assert_eq!(areas(&vis), vec![4.0, 3.0]);
    // Also from below, and from a skew direction: the rule does not depend on the view.
    for dir in [V3::new(0., 0., 1.), V3::new(0.3, -0.2, -1.0)] {
        let (_, vis) = run(&s, Camera::orthographic(dir, V3::y()).unwrap());
        close(
            vis.face(FaceId(1)).area / vis.face(FaceId(0)).area,
            0.75,
            1e-12,
        );
    }
}

#[test]
fn shared_edge_fold_hides_exactly() {
    // F and G share the edge (2,0,0)-(0,2,0); G folds back over F. Seen from above, G covers
    // F's projection exactly: F must be empty, with no sliver along the shared edge.
    let over = mesh(
        &[[0., 0., 0.], [2., 0., 0.], [0., 2., 0.], [0., 0., 1.]],
        &[&[0, 1, 2], &[1, 2, 3]],
    );
    let (_, vis) = run(&scene(vec![("fold", over)]), top());
    assert_eq!(areas(&vis), vec![0.0, 2.0]);
    assert!(vis.face(FaceId(0)).is_empty());
    let under = mesh(
        &[[0., 0., 0.], [2., 0., 0.], [0., 2., 0.], [0., 0., -1.]],
        &[&[0, 1, 2], &[1, 2, 3]],
    );
    let (_, vis) = run(&scene(vec![("fold", under)]), top());
    assert_eq!(areas(&vis), vec![2.0, 0.0]);
}

#[test]
fn shared_edge_between_front_faces_leaves_both_whole() {
    // A tent seen from above: two slopes sharing the ridge; neither hides the other.
    let tent = mesh(
        &[
            [0., 0., 0.],
            [2., 0., 0.],
            [2., 1., 1.],
            [0., 1., 1.],
            [2., 2., 0.],
            [0., 2., 0.],
        ],
        &[&[0, 1, 2, 3], &[3, 2, 4, 5]],
    );
    let (_, vis) = run(&scene(vec![("tent", tent)]), top());
    assert_eq!(areas(&vis), vec![2.0, 2.0]);
    assert_eq!(vis.counters.faces_clipped, 0);
}

#[test]
fn edge_on_face_is_invisible_and_hides_nothing() {
    let wall = mesh(
        &[[0., 1., 0.], [2., 1., 0.], [2., 1., 5.], [0., 1., 5.]],
        &[&[0, 1, 2, 3]],
    );
    let s = scene(vec![("wall", wall), ("floor", square(0., 0., 2., -1.))]);
    let (_, vis) = run(&s, top());
    assert_eq!(areas(&vis), vec![0.0, 4.0]);
}

#[test]
fn parallel_planes_nearer_hides_farther_from_both_sides() {
    let s = scene(vec![
        ("low", square(0., 0., 2., 0.)),
        ("high", square(0., 0., 2., 1.)),
    ]);
    let (_, vis) = run(&s, top());
    assert_eq!(areas(&vis), vec![0.0, 4.0]);
    let (_, vis) = run(
        &s,
        Camera::orthographic(V3::new(0., 0., 1.), V3::y()).unwrap(),
    );
    assert_eq!(areas(&vis), vec![4.0, 0.0]);
}

#[test]
fn perspective_sees_near_box_in_front() {
    use crate::geom::P3;
    // A unit square at z = 1 in front of a 4x4 square at z = 0, eye on the axis at z = 3.
    let s = scene(vec![
        ("back", square(-2., -2., 4., 0.)),
        ("front", square(-0.5, -0.5, 1., 1.)),
    ]);
    let cam = Camera::perspective(P3::new(0., 0., 3.), P3::origin(), V3::y(), 90.0, 0.01).unwrap();
    let (_, vis) = run(&s, cam);
    // Screen x = x / d (f = 1): back at d = 3 spans [-2/3, 2/3]; front at d = 2 spans [-1/4, 1/4].
    close(vis.face(FaceId(1)).area, 0.25, 1e-14);
    close(vis.face(FaceId(0)).area, 16.0 / 9.0 - 0.25, 1e-14);
}

#[test]
fn perspective_eye_in_a_face_plane_sees_it_edge_on() {
    use crate::geom::P3;
    use crate::view::Facing;
    // A box whose top face lies in the plane z = 2, eye at height 2 looking across it, and a
    // wall in front of the box: the top face is exactly edge-on, nothing leaks past the wall.
    let s = scene(vec![
        ("wall", cuboid([-5., -1., 0.], [5., 0., 4.])),
        ("box", cuboid([-1., -4., 0.], [1., -2., 2.])),
    ]);
    let cam = Camera::perspective(
        P3::new(0.3, 10., 2.),
        P3::new(0., 0., 2.),
        V3::z(),
        50.0,
        0.1,
    )
    .unwrap();
    let (view, vis) = run(&s, cam);
    let top = (0..view.screen.face_count() as u32)
        .map(FaceId)
        .find(|&f| {
            view.screen
                .face_world_pts(f)
                .iter()
                .all(|p| p.z == 2.0 && p.y < -1.0)
        })
        .unwrap();
    assert_eq!(view.screen.face_facing(top), Facing::EdgeOn);
    // Every face of the box is behind the wall.
    let box_faces = view.tree.object("box").unwrap().faces.clone();
    for f in FaceId::each(&box_faces) {
        assert_eq!(vis.face(f).area, 0.0, "face {f} leaks");
    }
}

#[test]
fn vtp_in_texture_coordinates() {
    use crate::visibility::vtp_texture::vtp_in_texture;
    // A horizontal square [0,2]^2 at z = 3 (texture frame: x = (1,0,0), y = (0,1,0), origin
    // (0,0,3)) under a square [1,3]x[0,2] at z = 5. From above the hidden part is [1,2]x[0,2];
    // looking along (0.2,-0.1,-1) the upper square's shadow on z = 3 shifts by (0.4,-0.2), the
    // hidden part is [1.4,2]x[0,1.8] and the visible area 4 - 1.08 = 2.92.
    let s = scene(vec![
        ("top", square(1., 0., 2., 5.)),
        ("base", square(0., 0., 2., 3.)),
    ]);
    for (cam, want) in [
        (top(), 2.0),
        (
            Camera::orthographic(V3::new(0.2, -0.1, -1.0), V3::y()).unwrap(),
            2.92,
        ),
    ] {
        let (view, vis) = run(&s, cam);
        let t = vtp_in_texture(&view, &vis, FaceId(1)).unwrap();
        let area: f64 = t.iter().map(crate::geom::poly2::polygon_area).sum();
        close(area, want, 1e-12);
        for p in t.iter().flatten().flatten() {
            assert!(
                p[0] > -1e-12 && p[0] < 2.0 + 1e-12 && p[1] > -1e-12 && p[1] < 2.0 + 1e-12,
                "{p:?}"
            );
        }
    }
}
