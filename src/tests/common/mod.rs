//! Scene builders and checks shared by the integration tests.
#![allow(dead_code)]

use std::sync::Arc;

use crate::emit::lines::{Drawing, LineOptions};
use crate::geom::poly2::{multipolygon_area, MultiPolygon};
use crate::geom::{PolyMesh, M4, P3, V3};
use crate::scene::cleanup::{cleanup, Origin};
use crate::scene::{Mesh, Object, Scene};
use crate::view::{Camera, View};
use crate::visibility::Visibility;
use crate::{render, Outputs, RenderOptions};

/// The shared meshes of `../shared/models`, by file name.
pub(crate) const SHARED_MESHES: [&str; 15] = [
    "beetle.obj",
    "cow.obj",
    "cube.obj",
    "fandisk.obj",
    "grid100.obj",
    "ico3.obj",
    "ico5.obj",
    "nefertiti.obj",
    "ogre.obj",
    "rocker-arm.obj",
    "spot.obj",
    "stanford-bunny.obj",
    "suzanne.obj",
    "teapot.obj",
    "twocubes.obj",
];

/// Loads a scene or mesh file with the default options, unwatched.
pub(crate) fn load(path: &std::path::Path) -> Scene {
    crate::load_scene(
        path,
        &crate::LoadOptions::default(),
        &mut Vec::new(),
        &crate::Progress::default(),
    )
    .unwrap()
}

/// Renders `scene` from `camera` with the default options, unwatched.
pub(crate) fn render_plain<'s>(scene: &'s Scene, camera: &Camera) -> crate::Rendered<'s> {
    render(
        scene,
        camera,
        &RenderOptions::default(),
        &crate::Progress::default(),
    )
    .unwrap()
}

/// Prepares `scene` with the default options, unwatched.
pub(crate) fn prepare(scene: &mut Scene) {
    crate::prepare(
        scene,
        &crate::PrepareOptions::default(),
        &crate::Progress::default(),
    );
}

/// A cleaned mesh from points and faces.
pub(crate) fn mesh(pts: &[[f64; 3]], faces: &[&[u32]]) -> Mesh {
    let raw = PolyMesh::new(
        pts.iter().map(|p| P3::new(p[0], p[1], p[2])).collect(),
        faces.iter().map(|f| f.to_vec()).collect(),
    );
    cleanup(
        &raw,
        &Origin {
            file: std::path::Path::new("test"),
            face_pos: &[],
        },
        &mut Vec::new(),
        Default::default(),
    )
    .unwrap()
}

/// A cleaned primitive.
pub(crate) fn prim(raw: PolyMesh) -> Mesh {
    cleanup(
        &raw,
        &Origin {
            file: std::path::Path::new("prim"),
            face_pos: &[],
        },
        &mut Vec::new(),
        Default::default(),
    )
    .unwrap()
}

/// An axis-aligned square at height z (counter-clockwise seen from +z).
pub(crate) fn square(x0: f64, y0: f64, s: f64, z: f64) -> Mesh {
    mesh(
        &[
            [x0, y0, z],
            [x0 + s, y0, z],
            [x0 + s, y0 + s, z],
            [x0, y0 + s, z],
        ],
        &[&[0, 1, 2, 3]],
    )
}

/// A box mesh.
pub(crate) fn cuboid(lo: [f64; 3], hi: [f64; 3]) -> Mesh {
    prim(crate::primitives::cuboid(
        P3::new(lo[0], lo[1], lo[2]),
        P3::new(hi[0], hi[1], hi[2]),
    ))
}

/// A scene of named leaf objects.
pub(crate) fn scene(objs: Vec<(&str, Mesh)>) -> Scene {
    let subs = objs
        .into_iter()
        .map(|(n, m)| Object::from_mesh(n, m))
        .collect();
    Scene::new(Object::group("", subs), "test".into())
}

/// Camera looking down -z, +y up: screen (x, y) = world (x, y).
pub(crate) fn top() -> Camera {
    Camera::orthographic(V3::new(0., 0., -1.), V3::y()).unwrap()
}

/// Solves a scene through the one pipeline, every face in the view (no cull), and gives a
/// view with its tree for VISP alongside (the render frees its own).
pub(crate) fn run(scene: &Scene, camera: Camera) -> (View, Visibility) {
    let opts = RenderOptions {
        no_inbox: true,
        ..RenderOptions::default()
    };
    let r = render(scene, &camera, &opts, &crate::Progress::default()).expect("in-memory render");
    (View::new(scene, camera), r.visibility)
}

/// The line drawing of a scene through the one pipeline, with its view (tree kept).
pub(crate) fn drawing(scene: &Scene, camera: Camera, lines: LineOptions) -> (View, Drawing) {
    let opts = RenderOptions {
        lines,
        outputs: Outputs {
            drawing: true,
            ..Outputs::default()
        },
        ..RenderOptions::default()
    };
    let r = render(scene, &camera, &opts, &crate::Progress::default()).expect("in-memory render");
    (
        View::new(scene, camera),
        r.drawing.expect("drawing asked for"),
    )
}

/// Areas of every face's VTP.
pub(crate) fn areas(vis: &Visibility) -> Vec<f64> {
    vis.by_id().into_iter().map(|f| f.area).collect()
}

/// Asserts |a - b| <= tol * max(1, |b|).
pub(crate) fn close(a: f64, b: f64, tol: f64) {
    assert!((a - b).abs() <= tol * b.abs().max(1.0), "{a} != {b}");
}

/// Union area of many multipolygons, through geo's boolean ops (an independent engine).
pub(crate) fn union_area(parts: &[&MultiPolygon]) -> f64 {
    use geo::{BooleanOps, Coord, LineString, MultiPolygon as GMP, Polygon as GP};
    let to_geo = |m: &MultiPolygon| -> GMP<f64> {
        GMP(m
            .iter()
            .map(|p| {
                let ring = |r: &Vec<[f64; 2]>| {
                    LineString(r.iter().map(|q| Coord { x: q[0], y: q[1] }).collect())
                };
                GP::new(ring(&p[0]), p[1..].iter().map(ring).collect())
            })
            .collect())
    };
    let mut acc = GMP::<f64>(vec![]);
    for m in parts {
        acc = acc.union(&to_geo(m));
    }
    use geo::Area;
    acc.unsigned_area()
}

/// Sum of areas.
pub(crate) fn total_area(parts: &[&MultiPolygon]) -> f64 {
    parts.iter().map(|m| multipolygon_area(m)).sum()
}

/// A transform from translation.
pub(crate) fn translate(x: f64, y: f64, z: f64) -> M4 {
    nalgebra::Translation3::new(x, y, z).to_homogeneous()
}

/// Shares a prototype.
pub(crate) fn instance(name: &str, proto: &Arc<Object>, m: M4) -> Object {
    Object::instance(name, proto.clone(), m)
}

/// Union area of many multipolygons on a fixed i64 grid (i_overlay, NonZero): precise to
/// f64 precision; used where geo's coarser grid (~1e-10 relative) is not enough.
pub(crate) fn union_area_exact(parts: &[&MultiPolygon]) -> f64 {
    crate::geom::boolean::union_area(parts)
}

pub(crate) use kepler_testkit::{model, models_dir as models};
pub(crate) mod strokes;

pub(crate) use kepler_testkit::Rng;
