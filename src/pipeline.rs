//! The one pipeline from a loaded scene and a camera to what people look at: level-of-detail
//! substitution, cull, view, visibility, line drawing and emit, with stage times, counters
//! and progress. Every command, the benchmarks and the tests render through [`render`].

use std::borrow::Cow;
use std::io::Write;
use std::time::Duration;

use crate::count::Count;
use crate::emit::lines::marks::face_marks;
use crate::emit::lines::{draw, Drawing, LineOptions};
use crate::emit::plot::picture;
use crate::emit::plot::picture::{Picture, PlotStats};
use crate::emit::write::json::{to_json, write_json};
use crate::emit::write::png::to_png;
use crate::emit::write::svg::to_svg;
use crate::error::{Error, Location, Result, Warning};
use crate::prepare::{HierarchyKind, PrepareOptions};
use crate::progress::cpu::{Spent, Stopwatch};
use crate::progress::{Lane, Phase};
pub(crate) use crate::progress::{Progress, Stage};
use crate::scene::Scene;
use crate::view::{substitute, Camera, Cull, LodOptions, LodStats, View};
use crate::visibility::empty::why_empty;
use crate::visibility::{solve, Counters, PassOptions, Visibility};

/// What to render and how.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct RenderOptions {
    /// The line drawing: which edges, and whether hidden lines are computed. Hidden lines
    /// need every face's facing, so asking for them turns the INBOX cull off.
    pub lines: LineOptions,
    /// What to emit into memory.
    pub outputs: Outputs,
    /// Render without inboxes (no cull, no INBOX tests in VISFAC2): for comparison only,
    /// the result is the same.
    pub no_inbox: bool,
    /// Replace small objects by their triboxes first ("model no more than a scene needs").
    pub lod: Option<LodOptions>,
    /// The object tree the substitutes of `lod` are prepared with (the caller prepares the
    /// scene itself: [`crate::prepare()`]); None: the default choice.
    pub hierarchy: Option<HierarchyKind>,
    /// Section planes, each a point and a normal: the side each normal points to is removed,
    /// exactly, and every closed solid cut gets its section faces, numbered after the
    /// scene's faces (`"section": true` in the JSON; the drawing's layer `7 section`).
    /// Empty: the scene file's `section` planes, if any.
    pub sections: Vec<(crate::geom::P3, crate::geom::V3)>,
}

/// The outputs [`render`] emits (each into memory, in [`Rendered`]).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Outputs {
    /// The `kepler-visible/1` JSON visible-polygon set.
    pub json: bool,
    /// With `json`: the line drawing's polylines in the JSON too (`"lines"`).
    pub json_lines: bool,
    /// The line drawing ([`Rendered::drawing`]) even when no output shows it.
    pub drawing: bool,
    /// An SVG line drawing.
    pub svg: bool,
    /// A PNG picture.
    pub png: bool,
    /// How the pictures look.
    pub picture: PictureOptions,
}

pub(crate) use crate::emit::plot::picture::PictureOptions;

/// Stage times and work counters of one render.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct RenderStats {
    /// Wall time per stage, in pipeline order (stages that did not run are absent).
    pub times: Vec<(Stage, Duration)>,
    /// CPU time per stage, all threads together, beside `times` (empty where the system
    /// does not tell: [`crate::stats::process_cpu_time`]).
    pub cpu: Vec<(Stage, Duration)>,
    /// What the visibility pass did.
    pub counters: Counters,
    /// What level-of-detail substitution did, under `lod`.
    pub lod: Option<LodStats>,
    /// What building the picture did (layers, strokes, travel, duplicates), when one was made.
    pub plot: Option<PlotStats>,
}

impl RenderStats {
    /// The time of a stage (zero when it did not run).
    pub fn time(&self, stage: Stage) -> Duration {
        self.times
            .iter()
            .filter(|(s, _)| *s == stage)
            .map(|(_, d)| *d)
            .sum()
    }

    /// Total time of all stages.
    pub fn total(&self) -> Duration {
        self.times.iter().map(|(_, d)| *d).sum()
    }

    /// Runs `f` as `stage`, timed (the stage's phases are entered in `f`).
    fn timed<T>(&mut self, stage: Stage, f: impl FnOnce() -> T) -> T {
        let clock = Stopwatch::start();
        let out = f();
        self.record(stage, clock.stop());
        out
    }

    /// Records a stage's wall time, and its CPU time where it was read.
    fn record(&mut self, stage: Stage, spent: Spent) {
        self.times.push((stage, spent.wall));
        if let Some(cpu) = spent.cpu {
            self.cpu.push((stage, cpu));
        }
    }
}

/// The result of [`render`]: the view, every face's visible region, the line drawing and the
/// emitted outputs.
#[derive(Debug)]
pub struct Rendered<'s> {
    /// The scene as rendered (its level-of-detail substitute under `lod`).
    pub scene: Cow<'s, Scene>,
    /// The view: camera and screen-space pieces. Its tree (needed only by the visibility
    /// stage) is freed before the drawing is made, and is empty here.
    pub view: View,
    /// Every face's visible region.
    pub visibility: Visibility,
    /// The line drawing, when an output needs it.
    pub drawing: Option<Drawing>,
    /// The JSON set, when asked for (and not written out by [`render_to`]).
    pub json: Option<String>,
    /// The SVG drawing, when asked for.
    pub svg: Option<String>,
    /// The PNG picture, when asked for.
    pub png: Option<Vec<u8>>,
    /// Stage times and counters.
    pub stats: RenderStats,
    /// What the caller should be told about the result (why it is empty, when it is).
    pub warnings: Vec<Warning>,
}

impl Rendered<'_> {
    /// The `kepler-visible/1` JSON of the visible regions, with the drawing's polylines
    /// when `lines` (and a drawing was made).
    pub fn to_json(&self, lines: bool) -> String {
        let lines = self.drawing.as_ref().filter(|_| lines).map(Drawing::lines);
        to_json(&self.view, &self.visibility, lines.as_ref(), Count::NONE)
    }

    /// [`Rendered::to_json`] written to `w` as it is made, never held whole.
    pub fn write_json(&self, lines: bool, w: &mut dyn Write) -> Result<()> {
        let lines = self.drawing.as_ref().filter(|_| lines).map(Drawing::lines);
        write_json(&self.view, &self.visibility, lines.as_ref(), w, Count::NONE)
            .map_err(Error::Write)
    }
}

/// The picture of `r`, its phases entered and counted in `lane`.
fn picture_of(r: &Rendered, opts: &PictureOptions, lane: &Lane) -> Result<Picture> {
    let empty = Drawing::default();
    let drawing = r.drawing.as_ref().unwrap_or(&empty);
    let marks = face_marks(&r.scene, &r.view, &r.visibility);
    picture(
        &r.scene,
        &r.view,
        &r.visibility,
        drawing,
        &marks,
        opts,
        lane,
    )
}

/// Renders `scene` (loaded, and best prepared: without INBOXes nothing is culled, the result
/// is the same) from `camera`.
///
/// Its stages, their phases and their counts go to `progress` as it goes
/// ([`Progress::phases`] lists them afterwards); the result is the same whatever watches it.
/// The emit stage writes the JSON and builds the picture side by side, and the progress
/// shows one phase at a time: the JSON's ([`Phase::Json`], faces) first, then the picture's
/// ([`Phase::Dedup`] and [`Phase::Join`] by segments, [`Phase::Order`] by strokes) from the
/// moment the JSON is done, the phase the picture is in then counted from there with what it
/// has left (so its rate and time left are those of the work still to do). A picture that is
/// done before the JSON does not show; without JSON, its phases show from the start.
///
/// ```
/// use kepler_hsr::{load_scene, render, Camera, LoadOptions, Outputs, Progress, RenderOptions};
///
/// let path = "scenes/polyhedra.kdl".as_ref();
/// let scene = load_scene(path, &LoadOptions::default(), &mut Vec::new(), &Progress::default()).unwrap();
/// let outputs = Outputs { json: true, ..Outputs::default() };
/// let opts = RenderOptions { outputs, ..Default::default() };
/// let r = render(&scene, &Camera::three_quarter(), &opts, &Progress::default()).unwrap();
/// assert!(r.json.unwrap().starts_with("{\"format\":\"kepler-visible/1\""));
/// ```
pub fn render<'s>(
    scene: &'s Scene,
    camera: &Camera,
    opts: &RenderOptions,
    progress: &Progress,
) -> Result<Rendered<'s>> {
    render_json_to(scene, camera, opts, None, progress)
}

/// [`render`], the JSON (when `opts.outputs.json`) written to `json` as it is made instead
/// of kept in [`Rendered::json`]: the text of a big scene (over a gigabyte at ten million
/// faces) is never held whole. The bytes are those [`render`] keeps. A write that fails
/// ends the render with [`Error::Write`].
pub fn render_to<'s>(
    scene: &'s Scene,
    camera: &Camera,
    opts: &RenderOptions,
    json: &mut dyn Write,
    progress: &Progress,
) -> Result<Rendered<'s>> {
    render_json_to(scene, camera, opts, Some(json), progress)
}

/// [`render`] and [`render_to`]: the JSON kept (`json` None) or written to `json`.
fn render_json_to<'s>(
    scene: &'s Scene,
    camera: &Camera,
    opts: &RenderOptions,
    json: Option<&mut dyn Write>,
    progress: &Progress,
) -> Result<Rendered<'s>> {
    let mut stats = RenderStats::default();
    let scene = match &opts.lod {
        Some(lod) => {
            progress.enter(Stage::Lod, 0);
            let (mut s, lod_stats) = stats.timed(Stage::Lod, || substitute(scene, camera, lod));
            stats.lod = Some(lod_stats);
            let prep = PrepareOptions {
                hierarchy: opts.hierarchy,
                ..PrepareOptions::default()
            };
            stats.timed(Stage::Prepare, || {
                crate::prepare::prepare(&mut s, &prep, progress)
            });
            Cow::Owned(s)
        }
        None => Cow::Borrowed(scene),
    };
    // The render's planes, or else the scene file's.
    let asked = if opts.sections.is_empty() {
        &scene.sections
    } else {
        &opts.sections
    };
    let scene = if asked.is_empty() || scene.section.is_some() {
        scene
    } else {
        let planes = crate::view::section::check_planes(asked)?;
        // Timed with the view stage: the cut is the view's first step.
        progress.enter(Stage::View, 0);
        Cow::Owned(stats.timed(Stage::View, || {
            crate::view::section::cut_scene(&scene, &planes)
        }))
    };
    // Hidden lines need every face's facing, so they keep every face in the view.
    progress.enter(Stage::Cull, 0);
    let cull = stats.timed(Stage::Cull, || {
        let mut cull = if opts.no_inbox || opts.lines.hidden {
            Cull::none(&scene)
        } else {
            Cull::new(&scene, camera)
        };
        if let Some(info) = &scene.section {
            cull.hide_removed(info);
        }
        cull
    });
    let mut view = stats.timed(Stage::View, || {
        View::from_cull(&scene, *camera, &cull, progress)
    });
    drop(cull);
    crate::view::finite::check_screen(&view.screen, &view.camera)
        .map_err(|e| crate::view::finite::placed(e, &scene, &view.camera))?;
    let pass = PassOptions {
        use_inbox: !opts.no_inbox,
    };
    progress.enter(Stage::Visibility, view.screen.pieces.len());
    let clock = Stopwatch::start();
    let visibility = solve(&view, pass, progress.count());
    stats.record(Stage::Visibility, clock.stop());
    stats.counters = visibility.counters;
    let mut warnings = Vec::new();
    if let Some(why) = why_empty(scene.face_count(), &view, &visibility) {
        warnings.push(Warning {
            location: Location::file(&scene.source),
            message: why,
        });
    }
    // Emitting needs the screen faces, not the tree: free it before the drawing's own memory.
    view.tree = Default::default();
    let out = &opts.outputs;
    let pictures = out.svg || out.png;
    let drawing = (pictures || out.drawing || (out.json && out.json_lines)).then(|| {
        stats.timed(Stage::Lines, || {
            draw(&scene, &view, &visibility, &opts.lines, progress)
        })
    });
    let mut r = Rendered {
        scene,
        view,
        visibility,
        drawing,
        json: None,
        svg: None,
        png: None,
        stats: RenderStats::default(),
        warnings,
    };
    let mut plot = None;
    // The JSON is counted by faces written, the picture in its phases (page, dedup, join,
    // order, then the SVG's and the PNG's polylines). Made side by side, they share the bar
    // one after the other: the JSON's phase first, the picture's in a lane behind it, shown
    // from the JSON's end on (the phase the picture is in then with what it has left); a
    // picture done before the JSON never shows.
    if out.json {
        progress.enter_phase(Stage::Emit, Phase::Json, r.visibility.solved_count());
    } else {
        progress.enter(Stage::Emit, 0);
    }
    let lane = if out.json {
        Lane::behind(progress)
    } else {
        Lane::open(progress)
    };
    stats.timed(Stage::Emit, || -> Result<()> {
        // The JSON and the picture (with its SVG and PNG) read the same solved view: made
        // side by side, the picture on the pool, the JSON here (its writer need not be
        // `Send`).
        let mut pic = Ok(None);
        let kept = rayon::in_place_scope(|s| {
            if pictures {
                let (r, lane, pic) = (&r, &lane, &mut pic);
                s.spawn(move |_| {
                    *pic = picture_of(r, &out.picture, lane).and_then(|pic| {
                        let svg = out.svg.then(|| {
                            lane.enter_phase(Stage::Emit, Phase::Svg, pic.polylines());
                            to_svg(&pic, lane.count())
                        });
                        let (size, dpi) = (out.picture.size, out.picture.dpi);
                        let png = out.png.then(|| {
                            lane.enter_phase(Stage::Emit, Phase::Png, pic.polylines());
                            to_png(&pic, size, dpi, lane.count())
                        });
                        Ok(Some((pic.stats, svg, png.transpose()?)))
                    });
                });
            }
            let lines = r.drawing.as_ref().filter(|_| out.json_lines);
            let lines = lines.map(Drawing::lines);
            let (view, vis, done) = (&r.view, &r.visibility, progress.count());
            let kept = match (out.json, json) {
                (false, _) => Ok(None),
                (true, None) => Ok(Some(to_json(view, vis, lines.as_ref(), done))),
                (true, Some(w)) => write_json(view, vis, lines.as_ref(), w, done)
                    .map(|()| None)
                    .map_err(Error::Write),
            };
            lane.release();
            kept
        });
        r.json = kept?;
        if let Some((stats, svg, png)) = pic? {
            (r.svg, r.png, plot) = (svg, png, Some(stats));
        }
        Ok(())
    })?;
    stats.plot = plot;
    r.stats = stats;
    Ok(r)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn render_to_writes_the_bytes_render_keeps() {
        let path = "scenes/town.kdl".as_ref();
        let scene = crate::load_scene(
            path,
            &Default::default(),
            &mut Vec::new(),
            &Progress::default(),
        )
        .unwrap();
        let opts = RenderOptions {
            outputs: Outputs {
                json: true,
                svg: true,
                ..Outputs::default()
            },
            ..RenderOptions::default()
        };
        let camera = Camera::three_quarter();
        let none = Progress::default();
        let kept = render(&scene, &camera, &opts, &none).unwrap();
        let mut w: Vec<u8> = Vec::new();
        let written = render_to(&scene, &camera, &opts, &mut w, &none).unwrap();
        assert_eq!(written.json, None);
        assert_eq!(Some(String::from_utf8(w).unwrap()), kept.json);
        assert_eq!(written.svg, kept.svg);
        // A writer that takes nothing ends the render with the write's error.
        let mut full: &mut [u8] = &mut [];
        let e = render_to(&scene, &camera, &opts, &mut full, &none).unwrap_err();
        assert!(matches!(e, Error::Write(_)), "{e}");
    }
}
