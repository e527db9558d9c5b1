//! Time against hidden complexity: the town benchmark (a wall in front of N buildings), timed
//! stage by stage with inboxes on and off, with the buildings in districts and blocks (the
//! paper's hierarchy) and flat under the root.
//!
//! Shared by `kepler-bench` and `cargo bench -p kepler-hsr-bench --bench town`.

use std::fmt::Write as _;
use std::time::Instant;

use kepler_hsr::stats::Stage;
use kepler_hsr::{render, Camera, RenderOptions, V3};

use crate::chart::{Chart, Series, Style};
use crate::generate::{town, TownLayout, TOWN_VIEW_DIR};

/// The Ns of the full benchmark.
pub const TOWN_NS: [usize; 5] = [10, 30, 100, 300, 1000];

/// The measured series: layout, inboxes on or off, label, colour.
pub const SERIES: [(TownLayout, bool, &str, &str); 3] = [
    (
        TownLayout::Districts,
        true,
        "districts and blocks, inboxes",
        "#1f77b4",
    ),
    (TownLayout::Flat, true, "flat, inboxes", "#2ca02c"),
    (TownLayout::Districts, false, "without inboxes", "#d62728"),
];

/// Median stage times of one N, layout, and inboxes on or off.
#[derive(Debug, Clone, PartialEq)]
pub struct TownRow {
    /// Buildings.
    pub n: usize,
    /// Faces of the scene.
    pub faces: usize,
    /// How the buildings are organised.
    pub layout: TownLayout,
    /// Inboxes used.
    pub inbox: bool,
    /// Median milliseconds: build, prepare (inboxes), cull, view, pass.
    pub ms: [f64; 5],
    /// Faces with something visible.
    pub visible_faces: usize,
}

impl TownRow {
    /// The visibility stage: the box cull (VISOBJ on CBOXes and INBOXes) and the pass. With
    /// inboxes off the "cull" only lists the leaves, which is view work.
    pub fn visibility(&self) -> f64 {
        if self.inbox {
            self.ms[2] + self.ms[4]
        } else {
            self.ms[4]
        }
    }
}

/// The town's camera.
pub fn camera() -> Camera {
    let d = TOWN_VIEW_DIR;
    Camera::orthographic(V3::new(d[0], d[1], d[2]), V3::y()).expect("valid camera")
}

/// Stage times in ms of one run (build, prepare, cull, view, pass), and visible faces.
pub fn run(n: usize, layout: TownLayout, use_inbox: bool) -> ([f64; 5], usize) {
    let ms = |d: std::time::Duration| d.as_secs_f64() * 1e3;
    let t = Instant::now();
    let mut scene = town(n, layout);
    let build = ms(t.elapsed());
    let t = Instant::now();
    if use_inbox {
        kepler_hsr::prepare(
            &mut scene,
            &kepler_hsr::PrepareOptions::default(),
            &kepler_hsr::Progress::default(),
        );
    }
    let prepare = ms(t.elapsed());
    let opts = RenderOptions {
        no_inbox: !use_inbox,
        ..RenderOptions::default()
    };
    let r = render(&scene, &camera(), &opts, &kepler_hsr::Progress::default())
        .expect("in-memory render without outputs");
    let visible = r.visibility.iter().filter(|f| f.1.area > 0.0).count();
    let st = |s| ms(r.stats.time(s));
    (
        [
            build,
            prepare,
            st(Stage::Cull),
            st(Stage::View),
            st(Stage::Visibility),
        ],
        visible,
    )
}

/// Median stage times over `runs` runs after one warm-up run.
pub fn measure(n: usize, layout: TownLayout, use_inbox: bool, runs: usize) -> TownRow {
    let (_, visible_faces) = run(n, layout, use_inbox);
    let all: Vec<[f64; 5]> = (0..runs.max(1))
        .map(|_| run(n, layout, use_inbox).0)
        .collect();
    let ms = std::array::from_fn(|s| {
        let mut v: Vec<f64> = all.iter().map(|r| r[s]).collect();
        v.sort_by(f64::total_cmp);
        v[v.len() / 2]
    });
    TownRow {
        n,
        faces: town(n, layout).face_count(),
        layout,
        inbox: use_inbox,
        ms,
        visible_faces,
    }
}

/// The rows as CSV.
pub fn csv(rows: &[TownRow]) -> String {
    let mut s = String::from(
        "n,faces,layout,inbox,load_ms,prepare_ms,cull_ms,view_ms,pass_ms,visibility_ms,visible_faces\n",
    );
    for r in rows {
        let _ = writeln!(
            s,
            "{},{},{:?},{},{:.3},{:.3},{:.3},{:.3},{:.3},{:.3},{}",
            r.n,
            r.faces,
            r.layout,
            r.inbox,
            r.ms[0],
            r.ms[1],
            r.ms[2],
            r.ms[3],
            r.ms[4],
            r.visibility(),
            r.visible_faces
        );
    }
    s
}

/// Visibility time at the largest N over the smallest, for one series.
pub fn growth(rows: &[TownRow], layout: TownLayout, inbox: bool) -> Option<f64> {
    let mine: Vec<&TownRow> = rows
        .iter()
        .filter(|r| r.inbox == inbox && r.layout == layout)
        .collect();
    let lo = mine.iter().min_by_key(|r| r.n)?;
    let hi = mine.iter().max_by_key(|r| r.n)?;
    (hi.n > lo.n).then(|| hi.visibility() / lo.visibility())
}

/// The log-log chart of the visibility stage's time against N, one line per series.
pub fn chart(rows: &[TownRow]) -> Chart {
    let line = |layout: TownLayout, inbox: bool, label: &str, colour: &str| {
        let mine: Vec<&TownRow> = rows
            .iter()
            .filter(|r| r.inbox == inbox && r.layout == layout)
            .collect();
        let mut s = Series::new(
            label,
            colour,
            Style::LineMarkers,
            mine.iter().map(|r| (r.n as f64, r.visibility())).collect(),
        );
        s.labels = mine
            .iter()
            .map(|r| format!("{:.3} ms", r.visibility()))
            .collect();
        s
    };
    let mut notes = vec![
        "a wall in front of N detailed buildings; median visibility stage (cull + pass)".into(),
    ];
    for (layout, inbox, label, _) in SERIES {
        if let Some(g) = growth(rows, layout, inbox) {
            notes.push(format!("{label}: largest N / smallest N = {g:.2}x"));
        }
    }
    Chart {
        title: "Time against hidden complexity: the town".into(),
        notes,
        x_label: "N (buildings)".into(),
        y_label: "visibility time, ms".into(),
        log_x: true,
        log_y: true,
        series: SERIES
            .iter()
            .map(|&(layout, inbox, label, colour)| line(layout, inbox, label, colour))
            .collect(),
    }
}
