//! Every shared mesh (../shared/models), rendered as a user would (prepared, culled where
//! proven safe): every emitted ring valid, no piece of line stroked twice.

use std::collections::HashMap;

use super::common::strokes::double_strokes;
use super::common::{model, models, SHARED_MESHES};
use crate::emit::lines::edges::{EdgeOptions, EdgeSet};
use crate::emit::lines::LineOptions;
use crate::geom::ring_check::multipolygon_defects;
use crate::geom::V3;
use crate::{render, Camera, Outputs, RenderOptions};

#[test]
fn shared_meshes_emit_valid_rings_and_stroke_each_line_once() {
    let Some(dir) = models() else { return };
    let only = std::env::var("KEPLER_ONLY").ok();
    for name in SHARED_MESHES {
        if only.as_deref().is_some_and(|o| !name.starts_with(o)) {
            continue;
        }
        let path = dir.join(name);
        if !path.exists() {
            eprintln!("skipping {name}: absent");
            continue;
        }
        let mut scene = super::common::load(&path);
        super::common::prepare(&mut scene);
        let cam = Camera::orthographic(V3::new(-1., -2., -3.), V3::y()).unwrap();
        let opts = RenderOptions {
            lines: LineOptions {
                edges: EdgeOptions {
                    set: EdgeSet::All,
                    crease_deg: 30.0,
                },
                hidden: false,
            },
            outputs: Outputs {
                drawing: true,
                ..Outputs::default()
            },
            ..RenderOptions::default()
        };
        let r = render(&scene, &cam, &opts, &crate::Progress::default()).unwrap();
        let mut bad = Vec::new();
        for (id, f) in r.visibility.iter() {
            for d in multipolygon_defects(&f.visible()) {
                bad.push((id, d));
            }
        }
        assert!(bad.is_empty(), "{name}: invalid rings {bad:?}");
        let d = r.drawing.unwrap();
        let size = r
            .view
            .screen
            .points
            .iter()
            .fold(0.0f64, |m, p| m.max(p[0].abs()).max(p[1].abs()));
        let twice = double_strokes(&d.visible, 1e-9 * size);
        let total: f64 = twice.iter().map(|t| t.2).sum();
        for (s, t, l) in twice.iter().take(10) {
            let kind = |k: usize| d.visible[k].kind;
            eprintln!(
                "{name}: {l:e} twice: {:?} {s:?} / {:?} {t:?}",
                kind(s.stroke),
                kind(t.stroke)
            );
        }
        assert!(
            twice.is_empty(),
            "{name}: {} pairs, {total} units stroked twice",
            twice.len()
        );
    }
}

/// teapot.obj's seam vertices are written once with -0 and once with +0: they merge, so the
/// only borders left are the real ones (edges with no coincident partner), and the feature
/// drawing draws no border line along a seam.
#[test]
fn teapot_seams_merge_and_leave_only_real_borders() {
    let Some(path) = model("teapot.obj") else {
        return;
    };
    let scene = super::common::load(&path);
    let mesh = scene.leaves()[0].mesh;
    let mut uses: HashMap<(u32, u32), usize> = HashMap::new();
    for f in &mesh.faces {
        let n = f.vertices.len();
        for i in 0..n {
            let (a, b) = (f.vertices[i], f.vertices[(i + 1) % n]);
            *uses.entry((a.min(b), a.max(b))).or_default() += 1;
        }
    }
    let borders: Vec<(u32, u32)> = uses
        .iter()
        .filter(|(_, &n)| n == 1)
        .map(|(&e, _)| e)
        .collect();
    // Coordinates compared with == (which holds for -0 and +0): no border edge has a twin.
    let at = |k: u32| mesh.vertices[k as usize];
    for (i, &(a, b)) in borders.iter().enumerate() {
        for &(c, d) in &borders[i + 1..] {
            let same = (at(a) == at(c) && at(b) == at(d)) || (at(a) == at(d) && at(b) == at(c));
            assert!(
                !same,
                "border edges {a}-{b} and {c}-{d} coincide: a seam left open"
            );
        }
    }
    assert_eq!(borders.len(), 160, "the teapot's real openings");
}
