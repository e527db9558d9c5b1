//! Time against hidden complexity: the town benchmark (a wall in front of N buildings), timed
//! stage by stage with inboxes on and off.
//!
//! Shared by `kepler bench` and `cargo bench --bench town` (which includes this file).

use std::fmt::Write as _;
use std::time::Instant;

use kepler::geom::V3;
use kepler::prepare::compute_inboxes;
use kepler::scene::generate::{town, TOWN_VIEW_DIR};
use kepler::view::{Camera, View};
use kepler::visibility::{solve, PassOptions};

use super::chart::{Chart, Series, Style};

/// The Ns of the full benchmark.
pub const TOWN_NS: [usize; 5] = [10, 30, 100, 300, 1000];

/// Median stage times of one N with inboxes on or off.
#[derive(Debug, Clone, PartialEq)]
pub struct TownRow {
    /// Buildings.
    pub n: usize,
    /// Faces of the scene.
    pub faces: usize,
    /// Inboxes used.
    pub inbox: bool,
    /// Median milliseconds: build, prepare (inboxes), view, visibility.
    pub ms: [f64; 4],
    /// Faces with something visible.
    pub visible_faces: usize,
}

/// The town's camera.
pub fn camera() -> Camera {
    let d = TOWN_VIEW_DIR;
    Camera::orthographic(V3::new(d[0], d[1], d[2]), V3::y()).expect("valid camera")
}

/// Stage times in ms of one run (build, prepare, view, visibility), and visible faces.
pub fn run(n: usize, use_inbox: bool) -> ([f64; 4], usize) {
    let ms = |t: Instant| t.elapsed().as_secs_f64() * 1e3;
    let t = Instant::now();
    let mut scene = town(n);
    let build = ms(t);
    let t = Instant::now();
    if use_inbox {
        compute_inboxes(&mut scene.root);
    }
    let prepare = ms(t);
    let t = Instant::now();
    let view = View::new(&scene, camera());
    let view_ms = ms(t);
    let t = Instant::now();
    let vis = solve(&view, PassOptions { use_inbox });
    let vis_ms = ms(t);
    let visible = vis.faces.iter().filter(|f| f.area > 0.0).count();
    ([build, prepare, view_ms, vis_ms], visible)
}

/// Median stage times over `runs` runs after one warm-up run.
pub fn measure(n: usize, use_inbox: bool, runs: usize) -> TownRow {
    let (_, visible_faces) = run(n, use_inbox);
    let all: Vec<[f64; 4]> = (0..runs.max(1)).map(|_| run(n, use_inbox).0).collect();
    let ms = std::array::from_fn(|s| {
        let mut v: Vec<f64> = all.iter().map(|r| r[s]).collect();
        v.sort_by(f64::total_cmp);
        v[v.len() / 2]
    });
    TownRow {
        n,
        faces: town(n).face_count(),
        inbox: use_inbox,
        ms,
        visible_faces,
    }
}

/// The rows as CSV.
pub fn csv(rows: &[TownRow]) -> String {
    let mut s =
        String::from("n,faces,inbox,load_ms,prepare_ms,view_ms,visibility_ms,visible_faces\n");
    for r in rows {
        let _ = writeln!(
            s,
            "{},{},{},{:.3},{:.3},{:.3},{:.3},{}",
            r.n, r.faces, r.inbox, r.ms[0], r.ms[1], r.ms[2], r.ms[3], r.visible_faces
        );
    }
    s
}

/// Visibility time at the largest N over the smallest, with inboxes on or off.
pub fn growth(rows: &[TownRow], inbox: bool) -> Option<f64> {
    let mine: Vec<&TownRow> = rows.iter().filter(|r| r.inbox == inbox).collect();
    let lo = mine.iter().min_by_key(|r| r.n)?;
    let hi = mine.iter().max_by_key(|r| r.n)?;
    (hi.n > lo.n).then(|| hi.ms[3] / lo.ms[3])
}

/// The log-log chart of the visibility stage's time against N, with and without inboxes.
pub fn chart(rows: &[TownRow]) -> Chart {
    let line = |inbox: bool, label: &str, colour: &str| {
        let mine: Vec<&TownRow> = rows.iter().filter(|r| r.inbox == inbox).collect();
        let mut s = Series::new(
            label,
            colour,
            Style::LineMarkers,
            mine.iter().map(|r| (r.n as f64, r.ms[3])).collect(),
        );
        s.labels = mine.iter().map(|r| format!("{:.0} ms", r.ms[3])).collect();
        s
    };
    let mut notes =
        vec!["a wall in front of N detailed buildings; median visibility-stage time".into()];
    for (inbox, what) in [(true, "with"), (false, "without")] {
        if let Some(g) = growth(rows, inbox) {
            notes.push(format!("{what} inboxes: largest N / smallest N = {g:.2}x"));
        }
    }
    Chart {
        title: "Time against hidden complexity: the town".into(),
        notes,
        x_label: "N (buildings)".into(),
        y_label: "visibility time, ms".into(),
        log_x: true,
        log_y: true,
        series: vec![
            line(true, "with inboxes", "#1f77b4"),
            line(false, "without inboxes", "#d62728"),
        ],
    }
}
