//! The one pipeline from a loaded scene and a camera to what people look at: level-of-detail
//! substitution, cull, view, visibility, line drawing and emit, with stage times, counters
//! and progress. Every command, the benchmarks and the tests render through [`render`].

use std::borrow::Cow;
use std::time::{Duration, Instant};

use crate::emit::json::to_json;
use crate::emit::lines::{draw, Drawing, LineOptions};
use crate::emit::marks::face_marks;
use crate::emit::picture::{Picture, PlotStats};
use crate::emit::plot::picture;
use crate::emit::png::to_png;
use crate::emit::svg::to_svg;
use crate::error::{Location, Result, Warning};
use crate::prepare::{HierarchyKind, PrepareOptions};
pub use crate::progress::{Progress, Stage};
use crate::scene::Scene;
use crate::view::{substitute, Camera, Cull, LodOptions, LodStats, View};
use crate::visibility::empty::why_empty;
use crate::visibility::{solve_counted, Counters, PassOptions, Visibility};

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
    /// scene itself: [`crate::prepare::prepare_with`]); None: the default choice.
    pub hierarchy: Option<HierarchyKind>,
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

pub use crate::emit::picture::PictureOptions;

/// Stage times and work counters of one render.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct RenderStats {
    /// Wall time per stage, in pipeline order (stages that did not run are absent).
    pub times: Vec<(Stage, Duration)>,
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

    fn timed<T>(&mut self, stage: Stage, progress: Option<&Progress>, f: impl FnOnce() -> T) -> T {
        if let Some(p) = progress {
            p.enter(stage, 0);
        }
        let t = Instant::now();
        let out = f();
        self.times.push((stage, t.elapsed()));
        out
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
    /// The JSON set, when asked for.
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
        to_json(&self.view, &self.visibility, lines.as_ref())
    }

    /// The picture both SVG and PNG draw (texture markings included).
    pub fn picture(&self, opts: &PictureOptions) -> Result<Picture> {
        let empty = Drawing::default();
        let drawing = self.drawing.as_ref().unwrap_or(&empty);
        let marks = face_marks(&self.scene, &self.view, &self.visibility);
        picture(
            &self.scene,
            &self.view,
            &self.visibility,
            drawing,
            &marks,
            opts,
        )
    }
}

/// Renders `scene` (loaded, and best prepared: without INBOXes nothing is culled, the result
/// is the same) from `camera`.
///
/// ```
/// use kepler_hsr::{load_scene, render, Camera, Outputs, RenderOptions};
///
/// let scene = load_scene("scenes/polyhedra.kdl".as_ref(), &mut Vec::new()).unwrap();
/// let outputs = Outputs { json: true, ..Outputs::default() };
/// let r = render(&scene, &Camera::three_quarter(), &RenderOptions { outputs, ..Default::default() }).unwrap();
/// assert!(r.json.unwrap().starts_with("{\"format\":\"kepler-visible/1\""));
/// ```
pub fn render<'s>(scene: &'s Scene, camera: &Camera, opts: &RenderOptions) -> Result<Rendered<'s>> {
    render_with(scene, camera, opts, None)
}

/// [`render`], reporting its stage and counts to `progress` as it goes.
pub fn render_with<'s>(
    scene: &'s Scene,
    camera: &Camera,
    opts: &RenderOptions,
    progress: Option<&Progress>,
) -> Result<Rendered<'s>> {
    let mut stats = RenderStats::default();
    let scene = match &opts.lod {
        Some(lod) => {
            let (mut s, lod_stats) =
                stats.timed(Stage::Lod, progress, || substitute(scene, camera, lod));
            stats.lod = Some(lod_stats);
            let prep = PrepareOptions {
                hierarchy: opts.hierarchy,
            };
            stats.timed(Stage::Prepare, progress, || {
                crate::prepare::prepare_with(&mut s, &prep)
            });
            Cow::Owned(s)
        }
        None => Cow::Borrowed(scene),
    };
    // Hidden lines need every face's facing, so they keep every face in the view.
    let cull = stats.timed(Stage::Cull, progress, || {
        if opts.no_inbox || opts.lines.hidden {
            Cull::none(&scene)
        } else {
            Cull::new(&scene, camera)
        }
    });
    let mut view = stats.timed(Stage::View, progress, || {
        View::from_cull(&scene, *camera, &cull)
    });
    drop(cull);
    crate::view::finite::check_screen(&view.screen, &view.camera)?;
    let pass = PassOptions {
        use_inbox: !opts.no_inbox,
    };
    if let Some(p) = progress {
        p.enter(Stage::Visibility, view.screen.pieces.len());
    }
    let t = Instant::now();
    let visibility = solve_counted(&view, pass, progress.map(Progress::done_counter));
    stats.times.push((Stage::Visibility, t.elapsed()));
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
        stats.timed(Stage::Lines, progress, || {
            draw(&scene, &view, &visibility, &opts.lines)
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
    stats.timed(Stage::Emit, progress, || -> Result<()> {
        // The JSON and the picture read the same solved view: made side by side.
        let (json, pic) = rayon::join(
            || out.json.then(|| r.to_json(out.json_lines)),
            || pictures.then(|| r.picture(&out.picture)).transpose(),
        );
        r.json = json;
        if let Some(pic) = pic? {
            if out.svg {
                r.svg = Some(to_svg(&pic));
            }
            if out.png {
                r.png = Some(to_png(&pic, out.picture.size, out.picture.dpi)?);
            }
            plot = Some(pic.stats);
        }
        Ok(())
    })?;
    stats.plot = plot;
    r.stats = stats;
    Ok(r)
}
