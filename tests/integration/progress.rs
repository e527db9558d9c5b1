//! Progress all the way: every phase of a load, prepare and render counts its units up to
//! its total, and a watched run gives the same scene and the same bytes as an unwatched one.
//! The picture's phases too, alone and beside the JSON.

use std::collections::BTreeSet;
use std::f64::consts::{PI, TAU};
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};

use kepler_hsr::lines::{EdgeKind, EdgeOptions, EdgeSet, LineOptions};
use kepler_hsr::stats::{Phase, PhaseCount, Stage};
use kepler_hsr::{
    load_scene, prepare, render, Camera, CameraRequest, LoadOptions, Outputs, PrepareOptions,
    Progress, RenderOptions, Scene,
};

/// A fresh directory for this test's files.
fn temp_dir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("kepler-progress-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// A closed UV sphere of `rings` x `segments` faces (quads, and triangles at the poles).
fn sphere_obj(rings: usize, segments: usize) -> String {
    let mut s = String::new();
    let _ = writeln!(s, "v 0 1 0");
    for i in 1..rings {
        let (y, r) = (
            (PI * i as f64 / rings as f64).cos(),
            (PI * i as f64 / rings as f64).sin(),
        );
        for j in 0..segments {
            let a = TAU * j as f64 / segments as f64;
            let _ = writeln!(s, "v {} {y} {}", r * a.cos(), -r * a.sin());
        }
    }
    let _ = writeln!(s, "v 0 -1 0");
    let at = |i: usize, j: usize| 2 + (i - 1) * segments + j % segments;
    let south = 2 + (rings - 1) * segments;
    for j in 0..segments {
        let _ = writeln!(s, "f 1 {} {}", at(1, j), at(1, j + 1));
        let _ = writeln!(s, "f {south} {} {}", at(rings - 1, j + 1), at(rings - 1, j));
    }
    for i in 1..rings - 1 {
        for j in 0..segments {
            let q = [at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)];
            let _ = writeln!(s, "f {} {} {} {}", q[0], q[1], q[2], q[3]);
        }
    }
    s
}

/// An open height field of `n` x `n` cells, two triangles each, over [-2, 2]².
fn ground_obj(n: usize) -> String {
    let mut s = String::new();
    for j in 0..=n {
        for i in 0..=n {
            let (x, z) = (
                4.0 * i as f64 / n as f64 - 2.0,
                4.0 * j as f64 / n as f64 - 2.0,
            );
            let _ = writeln!(s, "v {x} {} {z}", 0.1 * (3.0 * x).sin() * (2.0 * z).cos());
        }
    }
    let at = |i: usize, j: usize| j * (n + 1) + i + 1;
    for j in 0..n {
        for i in 0..n {
            let _ = writeln!(s, "f {} {} {}", at(i, j), at(i, j + 1), at(i + 1, j + 1));
            let _ = writeln!(s, "f {} {} {}", at(i, j), at(i + 1, j + 1), at(i + 1, j));
        }
    }
    s
}

/// A scene of two overlapping placements of a sphere (a shared prototype: trees and
/// inboxes; curves where they cross) above an open ground (capped in prepare).
fn scene_file() -> PathBuf {
    // Tests run on threads of one process: each call writes its own files, so that no test
    // reads a file another is rewriting.
    static CALLS: AtomicUsize = AtomicUsize::new(0);
    let dir = temp_dir(&format!("scene-{}", CALLS.fetch_add(1, Ordering::Relaxed)));
    std::fs::write(dir.join("ball.obj"), sphere_obj(24, 48)).unwrap();
    std::fs::write(dir.join("ground.obj"), ground_obj(30)).unwrap();
    let kdl = "prototype \"ball\" { mesh \"ball.obj\" }\n\
               instance \"a\" of=\"ball\"\n\
               instance \"b\" of=\"ball\" { translate 0.6 0.2 0.1 }\n\
               object \"ground\" { mesh \"ground.obj\"; translate 0 -1.1 0 }\n";
    let path = dir.join("scene.kdl");
    std::fs::write(&path, kdl).unwrap();
    path
}

/// The scene's debug description without the times its object trees took to build.
fn described(scene: &kepler_hsr::Scene) -> String {
    let text = format!("{scene:?}");
    let mut out = String::with_capacity(text.len());
    let mut rest = text.as_str();
    while let Some(k) = rest.find("times: BuildTimes {") {
        out.push_str(&rest[..k]);
        rest = &rest[k..];
        rest = &rest[rest.find('}').map_or(rest.len(), |e| e + 1)..];
    }
    out.push_str(rest);
    out
}

/// What every phase of a log counted, as `(stage, phase, done, total)`.
fn counts(log: &[PhaseCount]) -> Vec<(Stage, Phase, usize, usize)> {
    log.iter()
        .map(|c| (c.stage, c.phase, c.done, c.total))
        .collect()
}

/// Every counted phase of `log` reached its total and never ran past it.
fn assert_full(log: &[PhaseCount]) {
    for c in log.iter().filter(|c| c.total > 0) {
        assert_eq!(c.done, c.total, "{c:?}");
    }
}

#[test]
fn every_phase_counts_to_its_total_and_changes_nothing() {
    let path = scene_file();
    let opts = LoadOptions::default();
    let progress = Progress::new();
    let mut warnings = Vec::new();
    let mut scene = load_scene(&path, &opts, &mut warnings, &progress).unwrap();
    prepare(&mut scene, &PrepareOptions::default(), &progress);
    let mut plain = load_scene(&path, &opts, &mut Vec::new(), &Progress::default()).unwrap();
    prepare(&mut plain, &PrepareOptions::default(), &Progress::default());
    assert!(described(&scene) == described(&plain), "the scenes differ");

    let camera = Camera::for_scene(&scene, &CameraRequest::default()).unwrap();
    let outputs = Outputs {
        json: true,
        svg: true,
        ..Outputs::default()
    };
    let ropts = RenderOptions {
        outputs,
        ..RenderOptions::default()
    };
    let watched = Progress::new();
    let r = render(&scene, &camera, &ropts, &watched).unwrap();
    let bare = render(&plain, &camera, &ropts, &Progress::default()).unwrap();
    assert_eq!(r.json, bare.json);
    assert_eq!(r.svg, bare.svg);

    let mut log = progress.phases();
    log.extend(watched.phases());
    assert_full(&log);
    let seen: BTreeSet<(Stage, Phase)> = log.iter().map(|c| (c.stage, c.phase)).collect();
    for want in [
        (Stage::Load, Phase::Whole),
        (Stage::Load, Phase::Read),
        (Stage::Load, Phase::Parse),
        (Stage::Load, Phase::Cleanup),
        (Stage::Prepare, Phase::Solidity),
        (Stage::Prepare, Phase::Inboxes),
        (Stage::Prepare, Phase::Trees),
        (Stage::Cull, Phase::Whole),
        (Stage::View, Phase::Project),
        (Stage::View, Phase::Tree),
        (Stage::Visibility, Phase::Whole),
        (Stage::Lines, Phase::World),
        (Stage::Lines, Phase::Edges),
        (Stage::Lines, Phase::Intersections),
        (Stage::Lines, Phase::Clip),
        (Stage::Emit, Phase::Json),
    ] {
        assert!(seen.contains(&want), "{want:?} not in {:?}", counts(&log));
    }
    // The long phases count, and what: two mesh files, the sphere's faces once (a shared
    // prototype), every placed face in the view and the lines.
    let ball = 24 * 48;
    let ground = 2 * 30 * 30;
    let total = |s: Stage, p: Phase| {
        log.iter()
            .filter(|c| (c.stage, c.phase) == (s, p))
            .map(|c| c.total)
            .collect::<Vec<_>>()
    };
    let size = |f: &str| std::fs::metadata(path.with_file_name(f)).unwrap().len() as usize;
    assert_eq!(
        total(Stage::Load, Phase::Parse),
        [size("ball.obj"), size("ground.obj")]
    );
    assert_eq!(total(Stage::Load, Phase::Cleanup), [ball, ground]);
    assert_eq!(total(Stage::Prepare, Phase::Solidity), [ball + ground]);
    assert_eq!(total(Stage::Prepare, Phase::Trees), [ball]);
    assert_eq!(total(Stage::View, Phase::Tree), [2 * ball + ground]);
    assert_eq!(total(Stage::Lines, Phase::World), [2 * ball + ground]);
    assert!(total(Stage::Lines, Phase::Clip)[0] > 0);
    assert!(total(Stage::Emit, Phase::Json)[0] > 0);
    let curves = r.drawing.as_ref().unwrap().visible.iter();
    assert!(curves.filter(|s| s.kind == EdgeKind::Intersection).count() > 0);
}

/// Render options for every edge with hidden lines dashed, into `outputs`.
fn hidden_lines(outputs: Outputs) -> RenderOptions {
    let edges = EdgeOptions {
        set: EdgeSet::All,
        ..EdgeOptions::default()
    };
    RenderOptions {
        lines: LineOptions {
            edges,
            hidden: true,
        },
        outputs,
        ..RenderOptions::default()
    }
}

/// The test scene loaded and prepared, with its default camera.
fn prepared_scene() -> (Scene, Camera) {
    let path = scene_file();
    let mut scene = load_scene(
        &path,
        &LoadOptions::default(),
        &mut Vec::new(),
        &Progress::default(),
    )
    .unwrap();
    prepare(&mut scene, &PrepareOptions::default(), &Progress::default());
    let camera = Camera::for_scene(&scene, &CameraRequest::default()).unwrap();
    (scene, camera)
}

#[test]
fn the_picture_counts_its_segments_and_strokes() {
    let (scene, camera) = prepared_scene();
    let ropts = hidden_lines(Outputs {
        svg: true,
        png: true,
        ..Outputs::default()
    });
    let watched = Progress::new();
    let r = render(&scene, &camera, &ropts, &watched).unwrap();
    let bare = render(&scene, &camera, &ropts, &Progress::default()).unwrap();
    assert_eq!(r.svg, bare.svg);
    assert_eq!(r.png, bare.png);

    let log = watched.phases();
    assert_full(&log);
    let emit: Vec<(Stage, Phase, usize, usize)> = counts(&log)
        .into_iter()
        .filter(|c| c.0 == Stage::Emit)
        .collect();
    // Alone, the picture shows every phase: the segments put on the page (none clipped
    // away: the page is the drawing's own), the same segments looked at for repeats, those
    // kept joined, every stroke of every layer ordered, then written and painted.
    let plot = r.stats.plot.as_ref().unwrap();
    let segments = plot.duplicates.segments;
    let strokes: usize = plot.layers.iter().map(|l| l.strokes).sum();
    let phase = |p: Phase| emit.iter().find(|c| c.1 == p).map(|c| c.3);
    assert_eq!(phase(Phase::Whole), Some(0), "{emit:?}");
    assert_eq!(plot.clipped_mm, 0.0);
    assert_eq!(phase(Phase::Page), Some(segments));
    assert_eq!(phase(Phase::Dedup), Some(segments));
    assert!(phase(Phase::Join).is_some_and(|n| n > 0 && n <= segments));
    assert_eq!(phase(Phase::Order), Some(strokes));
    assert_eq!(phase(Phase::Svg), Some(strokes));
    assert_eq!(phase(Phase::Png), Some(strokes));
    let order: Vec<Phase> = emit.iter().map(|c| c.1).collect();
    assert!(order.windows(2).all(|w| w[0] < w[1]), "in order: {order:?}");
    assert!(plot
        .layers
        .iter()
        .any(|l| l.name == "hidden" && l.strokes > 100));
}

#[test]
fn hatching_and_fills_count_their_visible_faces() {
    let (scene, camera) = prepared_scene();
    let mut ropts = hidden_lines(Outputs {
        svg: true,
        ..Outputs::default()
    });
    ropts.outputs.picture.hatch = Some(kepler_hsr::plot::HatchOptions::default());
    ropts.outputs.picture.fill = true;
    let watched = Progress::new();
    let r = render(&scene, &camera, &ropts, &watched).unwrap();
    assert_eq!(
        r.svg,
        render(&scene, &camera, &ropts, &Progress::default())
            .unwrap()
            .svg
    );
    let log = watched.phases();
    assert_full(&log);
    // Every face with a visible part is hatched (its tone may draw no line) and filled, once.
    let visible = r.visibility.iter().filter(|(_, f)| !f.is_empty()).count();
    let total = |p: Phase| -> Vec<usize> {
        counts(&log)
            .into_iter()
            .filter(|c| c.0 == Stage::Emit && c.1 == p)
            .map(|c| c.3)
            .collect()
    };
    assert!(visible > 100, "{visible}");
    assert_eq!(total(Phase::Hatch), [visible]);
    assert_eq!(total(Phase::Fill), [visible]);
    // The SVG counts the fills' rings (each closed with a Z, which nothing else writes)
    // and the strokes.
    let rings = r.svg.as_deref().unwrap().matches('Z').count();
    let plot = r.stats.plot.as_ref().unwrap();
    let strokes: usize = plot.layers.iter().map(|l| l.strokes).sum();
    assert!(rings >= visible, "{rings} rings");
    assert_eq!(total(Phase::Svg), [rings + strokes]);
}

#[test]
fn the_picture_beside_the_json_shows_after_it() {
    let (scene, camera) = prepared_scene();
    let ropts = hidden_lines(Outputs {
        json: true,
        svg: true,
        ..Outputs::default()
    });
    let bare = render(&scene, &camera, &ropts, &Progress::default()).unwrap();
    // Which of the picture's phases show depends on when the JSON ends: whatever shows
    // comes after the JSON and counts to its total.
    for _ in 0..3 {
        let watched = Progress::new();
        let r = render(&scene, &camera, &ropts, &watched).unwrap();
        assert_eq!((&r.json, &r.svg), (&bare.json, &bare.svg));
        let log = watched.phases();
        assert_full(&log);
        let emit: Vec<Phase> = log
            .iter()
            .filter(|c| c.stage == Stage::Emit)
            .map(|c| c.phase)
            .collect();
        assert_eq!(emit.first(), Some(&Phase::Json), "{emit:?}");
        let picture = [
            Phase::Page,
            Phase::Dedup,
            Phase::Join,
            Phase::Order,
            Phase::Svg,
        ];
        assert!(emit[1..].iter().all(|p| picture.contains(p)));
        assert!(emit.windows(2).all(|w| w[0] < w[1]), "in order: {emit:?}");
    }
}

#[test]
fn every_mesh_format_counts_its_bytes() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/meshes");
    for name in [
        "cube_ascii.ply",
        "cube_le.ply",
        "cube_ascii.stl",
        "cube_binary.stl",
    ] {
        let path = dir.join(name);
        let progress = Progress::new();
        let opts = LoadOptions::default();
        load_scene(&path, &opts, &mut Vec::new(), &progress).unwrap();
        let log = progress.phases();
        assert_full(&log);
        let len = std::fs::metadata(&path).unwrap().len() as usize;
        let parsed = counts(&log)
            .into_iter()
            .filter(|c| c.1 == Phase::Parse)
            .collect::<Vec<_>>();
        assert_eq!(parsed, [(Stage::Load, Phase::Parse, len, len)], "{name}");
    }
}
