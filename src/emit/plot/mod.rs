//! Plotter post-processing: builds the [`Picture`] of a solved view, the drawing's lines (and
//! hatching, markings, fills) laid out on the page in mm, clipped exactly to the drawing
//! area, each line drawn once, joined into long strokes, hidden lines dashed, and every layer
//! ordered to cut the pen's travel.
//!
//! Steps: frame and page layout; hatch lines (their spacing is in mm); map to the page and
//! clip ([`clip_rect`]); drop repeated and overlapping collinear pieces, visible pens
//! first ([`dedup`]); per layer and pen, join at equal ends then within
//! `join_mm` ([`join`]), simplify when asked (geo's Ramer–Douglas–Peucker), dash the
//! hidden pen ([`dash`]) and join dashes that meet; per layer, order all strokes
//! ([`tour`]).

pub(crate) mod chain;
pub(crate) mod clip_rect;
pub(crate) mod color;
pub(crate) mod dash;
pub(crate) mod dedup;
pub(crate) mod hatch;
pub(crate) mod ink;
pub(crate) mod join;
pub(crate) mod lone;
pub(crate) mod page;
pub(crate) mod pairs;
pub(crate) mod picture;
pub(crate) mod shade;
pub(crate) mod tour;

use std::collections::BTreeMap;

use geo::{LineString, Simplify};
use rayon::prelude::*;

use crate::count::{Share, Span};
use crate::error::{Error, Result};
use crate::geom::poly2::{polyline_length as length, Pt2};
use crate::geom::Rect;
use crate::progress::{Lane, Phase, Stage};
use crate::scene::{FaceId, Scene};
use crate::view::{Frame, View};
use crate::visibility::Visibility;

use self::clip_rect::clip_polyline;
use self::dash::dashes;
use self::dedup::{dedup_indexed, SegmentIndex};
use self::hatch::{hatch, section_hatch, tone_outlines};
use self::ink::Ink;
use self::join::{join, join_sparse};
use self::page::Layout;
use self::picture::{Fill, Layer, LayerMode, Pen, Picture, PictureOptions, PlotStats, Run};
use self::shade::{face_shade, light_direction};
use self::tour::plan_tied;
use crate::emit::lines::{Drawing, Stroke};

/// Coincidence tolerance of [`dedup::dedup`] on the page: lines closer than 0.1 µm are one line
/// (a plotter's step is about 10 µm, a pen 100 µm or more).
const DEDUP_EPS_MM: f64 = 1e-4;

/// One polyline to plot, in screen space.
struct Item {
    pen: Pen,
    leaf: u32,
    pts: Vec<Pt2>,
}

/// The picture of a solved view: `drawing` is its line drawing, `marks` its face markings.
///
/// In phases of the emit stage, entered in `lane`: with `hatch`, [`Phase::Hatch`]
/// by visible faces hatched; then [`Phase::Dedup`] by segments looked at, [`Phase::Join`] by
/// segments joined (each layer and pen's share its segments), [`Phase::Order`] by strokes
/// (each layer's share its strokes, the layers planned side by side), and with `fill`,
/// [`Phase::Fill`] by visible faces. Mapping to the page and clipping, before dedup, are not
/// counted (a few ms on 200k segments).
pub(crate) fn picture(
    scene: &Scene,
    view: &View,
    vis: &Visibility,
    drawing: &Drawing,
    marks: &[Stroke],
    opts: &PictureOptions,
    lane: &Lane,
) -> Result<Picture> {
    check(opts)?;
    let tops = top_objects(scene);
    let outline_only = opts.hatch.is_some_and(|h| h.outline);
    let mut items: Vec<Item> = Vec::new();
    let mut add = |s: &Stroke, pen: Pen| {
        items.push(Item {
            pen,
            leaf: s.leaf,
            pts: s.pts.clone(),
        })
    };
    for s in &drawing.visible {
        // Outlines only around hatched regions: the tone outlines replace inner edges.
        if !(outline_only && Pen::of(s.kind) == Pen::Edges) {
            add(s, Pen::of(s.kind));
        }
    }
    marks.iter().for_each(|s| add(s, Pen::Mark));
    drawing.hidden.iter().for_each(|s| add(s, Pen::Hidden));

    let regions = opts.fill || opts.hatch.is_some();
    let frame = match opts.frame {
        Some(r) => Frame::of(&view.camera, r),
        None => {
            let mut b = Rect::of_points(drawing.visible.iter().flat_map(|s| s.pts.iter()));
            b = b.union(&Rect::of_points(
                drawing.hidden.iter().flat_map(|s| s.pts.iter()),
            ));
            b = b.union(&Rect::of_points(marks.iter().flat_map(|s| s.pts.iter())));
            if regions {
                for (_, f) in vis.iter() {
                    b = b.union(&Rect::of_points(f.visible().iter().flatten().flatten()));
                }
            }
            Frame::of_scene(&view.camera, scene, b)
        }
    };
    let layout = Layout::new(&frame, opts.page, opts.margin_mm, opts.size)?;

    if let Some(h) = &opts.hatch {
        let faces = vis.iter().filter(|(_, fv)| !fv.is_empty()).count();
        lane.enter_phase(Stage::Emit, Phase::Hatch, faces);
        let hatching = hatch(scene, view, vis, &layout, h, opts.light, lane.count())?;
        for &(leaf, s) in &hatching.segments {
            items.push(Item {
                pen: Pen::Hatch,
                leaf,
                pts: s.to_vec(),
            });
        }
        if h.outline {
            let group = |leaf: u32| match opts.layers {
                LayerMode::Object => tops.of_leaf[leaf as usize],
                _ => 0,
            };
            for (leaf, ring) in tone_outlines(&hatching, vis, group) {
                items.push(Item {
                    pen: Pen::Edges,
                    leaf,
                    pts: ring,
                });
            }
        }
    }

    // Section faces: hatched at 45° on the section layer, whatever else is hatched.
    for (leaf, s) in section_hatch(scene, view, vis, &layout, opts.section_hatch_mm)? {
        items.push(Item {
            pen: Pen::SectionHatch,
            leaf,
            pts: s.to_vec(),
        });
    }

    // Objects styled occlude-only are never drawn.
    let styles = scene.leaf_styles();
    let style = |leaf: u32| styles.get(leaf as usize).copied().unwrap_or_default();
    if !styles.is_empty() {
        items.retain(|it| !style(it.leaf).hidden());
    }
    // On the page, clipped to the drawing area, as segments in priority order.
    let mut stats = PlotStats::default();
    items.sort_by_key(|it| (it.pen, it.leaf));
    let mut segs: Vec<[Pt2; 2]> = Vec::new();
    let mut owner: Vec<(Pen, u32)> = Vec::new();
    let segments = |it: &Item| it.pts.len().saturating_sub(1);
    lane.enter_phase(Stage::Emit, Phase::Page, items.iter().map(segments).sum());
    let mut placed = 0;
    for it in &items {
        // Counted by segments (most lines are a segment or two), a chunk at a time.
        let next = placed + segments(it);
        (placed..next).for_each(|s| lane.count().tick(s));
        placed = next;
        let page: Vec<Pt2> = it.pts.iter().map(|&p| layout.to_page(p)).collect();
        let before = length(&page);
        let mut after = 0.0;
        for part in clip_polyline(&page, &layout.area) {
            after += length(&part);
            for w in part.windows(2) {
                segs.push([w[0], w[1]]);
                owner.push((it.pen, it.leaf));
            }
        }
        stats.clipped_mm += (before - after).max(0.0);
    }
    lane.count().tick_rest(placed);
    let eps = DEDUP_EPS_MM;
    lane.enter_phase(Stage::Emit, Phase::Dedup, segs.len());
    let (kept, dup, drawn) = dedup_indexed(&segs, eps, lane.count());
    stats.duplicates = dup;
    // Every line drawn, to keep the joins' gap bridges off them.
    let mut bridges = Bridges::new(drawn, &kept, &owner);

    // Per layer and pen: join, simplify, dash. An object's style may send its lines (not its
    // hidden lines, nor hatching) to another pen's layer, and set their width.
    let styled = |pen: Pen| !matches!(pen, Pen::Hidden | Pen::Hatch | Pen::SectionHatch);
    let layer_of = |pen: Pen, leaf: u32| match opts.layers {
        LayerMode::Pen => style(leaf)
            .pen
            .filter(|_| styled(pen))
            .unwrap_or(pen.number()),
        LayerMode::Object => tops.of_leaf[leaf as usize] + 1,
        LayerMode::None => 1,
    };
    let weight_of = |pen: Pen, leaf: u32| {
        style(leaf)
            .weight
            .filter(|_| styled(pen))
            .map_or(0, f64::to_bits)
    };
    let mut groups: BTreeMap<(u32, Pen, u64), Vec<Vec<Pt2>>> = BTreeMap::new();
    for (src, s) in kept {
        let (pen, leaf) = owner[src];
        groups
            .entry((layer_of(pen, leaf), pen, weight_of(pen, leaf)))
            .or_default()
            .push(s.to_vec());
    }
    let mut by_layer: BTreeMap<u32, Vec<(Pen, u64, Vec<Pt2>)>> = BTreeMap::new();
    lane.enter_phase(
        Stage::Emit,
        Phase::Join,
        groups.values().map(Vec::len).sum(),
    );
    for ((layer, pen, weight), lines) in groups {
        let share = Share::new(lane.count(), lines.len());
        // The hidden pen's lines are joined twice, before and after dashing.
        let once = if pen == Pen::Hidden { 0.4 } else { 1.0 };
        let mut bridge = |p, q| bridges.allow(p, q, false);
        let mut strokes = join(lines, opts.join_mm, &mut bridge, share.span(0.0, once));
        if opts.simplify_mm > 0.0 {
            strokes = strokes
                .into_iter()
                .map(|l| simplify(&l, opts.simplify_mm))
                .collect();
        }
        if pen == Pen::Hidden {
            // Dashes of different lines that meet (where hidden lines join at a corner) are
            // drawn as one stroke, a gap shorter than the join tolerance bridged where it
            // runs along hidden lines only (the off part of a dash pattern has no ink), as
            // vpype's `linemerge` would join them.
            let [on, off] = opts.dash_mm;
            check_dash_count(&strokes, on, off, &layout)?;
            // Each stroke's dashes on its own, collected in stroke order.
            let dashed: Vec<Vec<Pt2>> = strokes
                .par_iter()
                .flat_map_iter(|l| dashes(l, on, off))
                .collect();
            share.reach(0.5);
            bridges.ink(&dashed);
            let mut bridge = |p, q| bridges.allow(p, q, true);
            // Nearly every dash meets no other: only those that do are joined.
            strokes = join_sparse(dashed, opts.join_mm, &mut bridge, share.span(0.5, 1.0));
        }
        share.finish();
        by_layer
            .entry(layer)
            .or_default()
            .extend(strokes.into_iter().map(|l| (pen, weight, l)));
    }
    // Each layer's drawing order is planned on its own: in parallel, in layer order.
    let by_layer: Vec<_> = by_layer.into_iter().collect();
    let strokes = by_layer.iter().map(|(_, s)| s.len()).sum();
    lane.enter_phase(Stage::Emit, Phase::Order, strokes);
    let layers: Vec<Layer> = by_layer
        .into_par_iter()
        .map(|(number, strokes)| {
            let share = Share::new(lane.count(), strokes.len());
            let name = match opts.layers {
                LayerMode::Pen => Pen::ALL
                    .iter()
                    .find(|p| p.number() == number)
                    .map_or("lines", |p| p.name())
                    .to_string(),
                LayerMode::Object => tops.names[number as usize - 1].clone(),
                LayerMode::None => "drawing".to_string(),
            };
            Layer {
                number,
                name,
                runs: ordered_runs(strokes, share.span(0.0, 1.0)),
            }
        })
        .collect();
    stats.layers = layers.iter().map(Layer::summary).collect();
    let fills = if opts.fill {
        fills(view, vis, &layout, opts.light, lane)
    } else {
        Vec::new()
    };
    Ok(Picture {
        page: layout.page,
        pen_mm: opts.pen_mm,
        background: opts.background,
        fills,
        layers,
        mode: opts.layers,
        stats,
    })
}

/// The most dashes the hidden lines of a picture may be cut into (each its own stroke, then
/// joined and ordered): bounds the dash loop's time and memory before it runs.
pub(crate) const MAX_DASHES: f64 = 2_000_000.0;

/// An error when dashing `strokes` (mm on the page) with `on`, `off` would make more than
/// [`MAX_DASHES`] dashes.
fn check_dash_count(strokes: &[Vec<Pt2>], on: f64, off: f64, layout: &Layout) -> Result<()> {
    let total: f64 = strokes.iter().map(|l| length(l)).sum();
    let dashes = (total / (on + off)).ceil() + strokes.len() as f64;
    if dashes <= MAX_DASHES {
        return Ok(());
    }
    Err(Error::Usage(format!(
        "--dash {on},{off}: the hidden lines of this {:.0}x{:.0} mm picture ({total:.0} mm) would make {dashes:.0} dashes, more than {MAX_DASHES}: give a dash and gap of at least {:.3} mm together",
        layout.page.width,
        layout.page.height,
        total / MAX_DASHES
    )))
}

/// Rejects settings no picture can be made with.
fn check(o: &PictureOptions) -> Result<()> {
    let positive = |v: f64| v.is_finite() && v > 0.0;
    let bad = |what: String| Err(Error::Usage(what));
    if !positive(o.pen_mm) {
        return bad(format!("--pen {}: expected a width in mm > 0", o.pen_mm));
    }
    if !(positive(o.dash_mm[0]) && positive(o.dash_mm[1])) {
        return bad(format!(
            "--dash {},{}: expected dash and gap lengths in mm > 0",
            o.dash_mm[0], o.dash_mm[1]
        ));
    }
    if !(o.join_mm.is_finite() && o.join_mm >= 0.0) {
        return bad(format!("--join {}: expected mm >= 0", o.join_mm));
    }
    if !(o.simplify_mm.is_finite() && o.simplify_mm >= 0.0) {
        return bad(format!("--simplify {}: expected mm >= 0", o.simplify_mm));
    }
    if let Some(d) = o.dpi {
        if !(positive(d) && d <= 10_000.0) {
            return bad(format!("--dpi {d}: expected dots per inch in (0, 10000]"));
        }
    }
    if let Some(h) = &o.hatch {
        if !(positive(h.spacing_mm) && h.spacing_mm >= 0.01) {
            return bad(format!(
                "--hatch-spacing {}: expected mm >= 0.01",
                h.spacing_mm
            ));
        }
        if h.angle_deg.is_some_and(|a| !a.is_finite()) {
            return bad("--hatch-angle: expected degrees".into());
        }
    }
    if !(o.section_hatch_mm.is_finite() && o.section_hatch_mm >= 0.01) {
        return bad(format!(
            "--section-hatch {}: expected mm >= 0.01",
            o.section_hatch_mm
        ));
    }
    if let Some(r) = o.frame {
        if r.is_empty()
            || !(r.xmin.is_finite()
                && r.xmax.is_finite()
                && r.ymin.is_finite()
                && r.ymax.is_finite())
        {
            return bad("the picture's frame is empty".into());
        }
    }
    Ok(())
}

/// Top-level objects: for every leaf, the index of its top-level object (the first part of
/// its path), numbered in order of first appearance, and their names.
struct TopObjects {
    of_leaf: Vec<u32>,
    names: Vec<String>,
}

fn top_objects(scene: &Scene) -> TopObjects {
    let mut names: Vec<String> = Vec::new();
    let of_leaf = scene
        .leaves()
        .iter()
        .map(|l| {
            let top = l.path.split('/').next().unwrap_or("").to_string();
            let k = names.iter().position(|n| *n == top).unwrap_or_else(|| {
                names.push(top);
                names.len() - 1
            });
            k as u32
        })
        .collect();
    TopObjects { of_leaf, names }
}

/// A polyline simplified to within `tol` (Ramer–Douglas–Peucker, geo); its ends stay.
fn simplify(l: &[Pt2], tol: f64) -> Vec<Pt2> {
    let ls: LineString<f64> = l.iter().map(|p| (p[0], p[1])).collect();
    ls.simplify(tol).0.iter().map(|c| [c.x, c.y]).collect()
}

/// A layer's strokes in plotting order, grouped into runs of one pen; planning the order
/// fills `span`.
fn ordered_runs(strokes: Vec<(Pen, u64, Vec<Pt2>)>, span: Span) -> Vec<Run> {
    let ends: Vec<[Pt2; 2]> = strokes
        .iter()
        .map(|(_, _, l)| [l[0], l[l.len() - 1]])
        .collect();
    // Hidden dashes along a line with nothing else near are drawn in a row.
    let dashed: Vec<bool> = strokes.iter().map(|s| s.0 == Pen::Hidden).collect();
    let mut strokes: Vec<Option<(Pen, u64, Vec<Pt2>)>> = strokes.into_iter().map(Some).collect();
    let mut runs: Vec<Run> = Vec::new();
    for (i, rev) in plan_tied(&ends, &dashed, span) {
        let Some((pen, weight, mut l)) = strokes[i].take() else {
            continue;
        };
        if rev {
            l.reverse();
        }
        // A weight's bits, 0 for none (a weight is above 0).
        let width_mm = (weight != 0).then(|| f64::from_bits(weight));
        match runs.last_mut() {
            Some(r) if r.pen == pen && r.width_mm == width_mm => r.lines.push(l),
            _ => runs.push(Run {
                pen,
                width_mm,
                lines: vec![l],
            }),
        }
    }
    runs
}

/// Flat-shaded visible regions on the page, clipped to the drawing area: one fill per grey
/// holding the regions of every face of that grey. Visible regions are disjoint, so the
/// even-odd fill of their union is each of them; drawn as one path, the triangles of one flat
/// surface meet without the light anti-aliasing seam that two separately filled, half-covered
/// edge pixels blend to. Counts the visible faces in `lane` ([`Phase::Fill`]).
fn fills(
    view: &View,
    vis: &Visibility,
    layout: &Layout,
    light: Option<crate::geom::V3>,
    lane: &Lane,
) -> Vec<Fill> {
    let light = light_direction(&view.camera, light);
    let mut by_grey: BTreeMap<u8, Vec<Vec<Pt2>>> = BTreeMap::new();
    let visible = || {
        vis.iter()
            .filter(|(f, fv)| !fv.is_empty() && !view.screen.occlude_only(*f))
    };
    let n = visible().count();
    lane.enter_phase(Stage::Emit, Phase::Fill, n);
    let done = lane.count();
    for (k, (f, fv)) in visible().enumerate() {
        done.tick(k);
        let f: FaceId = f;
        let region = fv.visible();
        let rings = region
            .iter()
            .flatten()
            .map(|r| r.iter().map(|&p| layout.to_page(p)).collect::<Vec<Pt2>>())
            .map(|r| layout.area.clip_ring(&r))
            .filter(|r| r.len() >= 3);
        let grey = (110.0 + 140.0 * face_shade(view, f, &light))
            .round()
            .clamp(0.0, 255.0) as u8;
        by_grey.entry(grey).or_default().extend(rings);
    }
    done.tick_rest(n);
    by_grey
        .into_iter()
        .filter(|(_, rings)| !rings.is_empty())
        .map(|(grey, rings)| Fill { rings, grey })
        .collect()
}

/// Where a join may bridge a gap: never along a line already drawn, except that a gap
/// between two hidden dashes may run along hidden lines where they have no ink (their dash
/// pattern's off parts).
struct Bridges {
    /// Every segment drawn, and every bridge.
    drawn: SegmentIndex,
    /// Which of `drawn`'s first segments (the lines drawn, by number) are the hidden pen's:
    /// a gap between dashes may run along those; `None` without hidden lines.
    hidden: Option<Vec<bool>>,
    /// The hidden dashes (the hidden pen's ink), each group's as it is dashed.
    ink: Vec<Ink>,
}

impl Bridges {
    /// The bridges of a picture whose lines drawn are `kept` (with their sources' `owner`),
    /// `drawn` the index of them all, in order (dedup's).
    fn new(drawn: SegmentIndex, kept: &[(usize, [Pt2; 2])], owner: &[(Pen, u32)]) -> Self {
        let hidden: Vec<bool> = kept.iter().map(|k| owner[k.0].0 == Pen::Hidden).collect();
        Bridges {
            drawn,
            hidden: hidden.contains(&true).then_some(hidden),
            ink: Vec::new(),
        }
    }

    /// Adds hidden dashes to the ink a bridge along hidden lines must keep off.
    fn ink(&mut self, dashes: &[Vec<Pt2>]) {
        if self.hidden.is_some() {
            self.ink.push(Ink::new(dashes, DEDUP_EPS_MM));
        }
    }

    /// Whether the gap from `p` to `q` may be drawn (then it is, from now on); with
    /// `along_hidden`, hidden lines do not stop it.
    fn allow(&mut self, p: Pt2, q: Pt2, along_hidden: bool) -> bool {
        let free = match (&self.hidden, along_hidden) {
            (Some(hidden), true) => {
                // Lines drawn but the hidden pen's, and the bridges (numbered after them).
                let solid = |k: usize| !hidden.get(k).is_some_and(|&h| h);
                !self.drawn.overlaps_where(p, q, solid)
                    && !self.ink.iter().any(|i| i.overlaps(p, q))
            }
            _ => !self.drawn.overlaps(p, q),
        };
        if free {
            self.drawn.insert([p, q]);
        }
        free
    }
}
