//! Hatching instead of fills: every visible face region gets parallel lines whose density
//! follows its shading, cross-hatched where darkest, clipped exactly to the face's VTP.
//!
//! A face's tone comes from its brightness under the light ([`super::shade`]): five tones,
//! from none (lit) to a cross-hatch (dark). Every tone uses the same angle — across the
//! light's direction on the page unless one is asked for — and lines of one family sit at
//! fixed offsets on the page (multiples of the spacing from the page's corner), sparser tones
//! taking every second or fourth line of the densest. So a hatch line runs on across the
//! faces of a smooth mesh and across tone boundaries, and the pieces join into long strokes.
//! Each line is one segment over the whole drawing, the same for every face, cut with the
//! exact segment-against-region test the line drawing uses ([`crate::emit::lines::clip_segment`]).

use rayon::prelude::*;

use crate::count::Count;
use crate::error::{Error, Result};
use crate::geom::boolean;
use crate::geom::poly2::{MultiPolygon, Pt2, Ring};
use crate::geom::{Rect, V3};
use crate::scene::{FaceId, Scene};
use crate::view::View;
use crate::visibility::Visibility;

use super::page::Layout;
use super::shade::{face_shade, light_direction, light_on_screen};
use crate::emit::lines::clip_segment::{at, intervals_in};

/// How hatching looks.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HatchOptions {
    /// Distance between the densest tone's lines, in mm on the page.
    pub spacing_mm: f64,
    /// Angle of the lines on the page in degrees, counter-clockwise from the x axis; default
    /// across the light's direction (45° when the light comes from the viewer).
    pub angle_deg: Option<f64>,
    /// Outlines only around hatched regions: instead of the creases and plain edges, the
    /// boundaries of the hatched tone regions (silhouettes, borders and intersection curves
    /// stay).
    pub outline: bool,
}

impl Default for HatchOptions {
    fn default() -> Self {
        HatchOptions {
            spacing_mm: 1.0,
            angle_deg: None,
            outline: false,
        }
    }
}

/// Number of tones: 0 (not hatched) to `TONES - 1` (cross-hatched).
pub(crate) const TONES: u8 = 5;

/// The tone of a face of brightness `shade` in [0, 1]: darkness in equal steps.
pub(crate) fn tone(shade: f64) -> u8 {
    let dark = (1.0 - shade).clamp(0.0, 1.0);
    ((dark * f64::from(TONES)) as u8).min(TONES - 1)
}

/// The line families of a tone: (spacing as a multiple of the densest, angle offset in
/// degrees).
fn families(tone: u8) -> &'static [(f64, f64)] {
    match tone {
        0 => &[],
        1 => &[(4.0, 0.0)],
        2 => &[(2.0, 0.0)],
        3 => &[(1.0, 0.0)],
        _ => &[(1.0, 0.0), (1.0, 90.0)],
    }
}

/// The hatching of a view: per visible face, its tone and the hatch segments (screen space,
/// clipped to its VTP), tagged with the face's leaf object.
#[derive(Debug, Clone, Default)]
pub(crate) struct Hatching {
    /// Hatch segments with their leaf.
    pub segments: Vec<(u32, [Pt2; 2])>,
    /// Every visible face with its leaf and tone.
    pub tones: Vec<(FaceId, u32, u8)>,
}

/// Hatches every visible face of a solved view; `layout` gives the page scale and frame,
/// `light` the direction toward the light (world; default from the upper left, in front).
///
/// The visible faces hatched go to `done`, once per chunk.
pub(crate) fn hatch(
    scene: &Scene,
    view: &View,
    vis: &Visibility,
    layout: &Layout,
    opts: &HatchOptions,
    light: Option<V3>,
    done: Count,
) -> Result<Hatching> {
    let light = light_direction(&view.camera, light);
    let angle = opts.angle_deg.unwrap_or_else(|| {
        light_on_screen(&view.camera, &light).map_or(45.0, |[x, y]| y.atan2(x).to_degrees() + 90.0)
    });
    let faces: Vec<(FaceId, u32)> = scene
        .leaves()
        .iter()
        .enumerate()
        .flat_map(|(li, leaf)| {
            let first = leaf.first_face;
            (0..leaf.mesh.faces.len()).map(move |k| (FaceId((first + k) as u32), li as u32))
        })
        .filter(|(f, _)| !vis.face(*f).is_empty() && !view.screen.occlude_only(*f))
        .collect();
    let tones: Vec<(FaceId, u32, u8)> = faces
        .par_iter()
        .map(|&(f, leaf)| (f, leaf, tone(face_shade(view, f, &light))))
        .collect();
    let spacing = opts.spacing_mm.max(1e-6);
    check_line_count(&tones, vis, layout, angle, spacing)?;
    let segments = tones
        .par_iter()
        .enumerate()
        .map(|(i, &(f, leaf, t))| {
            done.tick(i);
            let mut out = Vec::new();
            for &(mult, offset) in families(t) {
                let fam = Family::new(layout, angle + offset, spacing * mult);
                for s in fam.clip(&vis.face(f).visible()) {
                    out.push((leaf, s));
                }
            }
            out
        })
        .collect::<Vec<_>>()
        .into_iter()
        .flatten()
        .collect();
    done.tick_rest(tones.len());
    Ok(Hatching { segments, tones })
}

/// The 45° hatching of the visible parts of a section view's section faces, `spacing_mm`
/// apart on the page, each segment with its face's leaf (in face order).
pub(crate) fn section_hatch(
    scene: &Scene,
    view: &View,
    vis: &Visibility,
    layout: &Layout,
    spacing_mm: f64,
) -> Result<Vec<(u32, [Pt2; 2])>> {
    let Some(first) = view.screen.section_first else {
        return Ok(Vec::new());
    };
    let fam = Family::new(layout, 45.0, spacing_mm);
    let firsts: Vec<usize> = scene.leaves().iter().map(|l| l.first_face).collect();
    let faces: Vec<FaceId> = (first as usize..view.screen.face_count())
        .map(|f| FaceId(f as u32))
        .filter(|&f| !vis.face(f).is_empty())
        .collect();
    let lines: u64 = faces
        .iter()
        .map(|&f| fam.count(&vis.face(f).visible()))
        .fold(0, u64::saturating_add);
    if lines > MAX_HATCH_LINES {
        return Err(Error::Usage(format!(
            "--section-hatch {spacing_mm}: hatching the section faces would draw {lines} lines, more than {MAX_HATCH_LINES}: give a wider spacing"
        )));
    }
    Ok(faces
        .par_iter()
        .map(|&f| {
            // The leaf's index in the scene's order (the drawing's), not the view's.
            let leaf = firsts.partition_point(|&ff| ff <= f.index()) as u32 - 1;
            fam.clip(&vis.face(f).visible())
                .into_iter()
                .map(|s| (leaf, s))
                .collect::<Vec<_>>()
        })
        .collect::<Vec<_>>()
        .into_iter()
        .flatten()
        .collect())
}

/// The most hatch lines (one line of one family across one face) a picture may have: each
/// is cut against its face exactly and may become several strokes, so this bounds the time
/// and memory of hatching (10 million lines: about a GB of strokes) before any is made.
pub(crate) const MAX_HATCH_LINES: u64 = 10_000_000;

/// An error when hatching the faces of `tones` at `spacing` mm would draw more than
/// [`MAX_HATCH_LINES`] lines (counted exactly, in integers, whatever the thread count).
fn check_line_count(
    tones: &[(FaceId, u32, u8)],
    vis: &Visibility,
    layout: &Layout,
    angle: f64,
    spacing: f64,
) -> Result<()> {
    let lines: u64 = tones
        .par_iter()
        .map(|&(f, _, t)| {
            families(t)
                .iter()
                .map(|&(mult, offset)| {
                    Family::new(layout, angle + offset, spacing * mult)
                        .count(&vis.face(f).visible())
                })
                .fold(0u64, u64::saturating_add)
        })
        .reduce(|| 0, u64::saturating_add);
    if lines <= MAX_HATCH_LINES {
        return Ok(());
    }
    let page = layout.page;
    Err(Error::Usage(format!(
        "--hatch-spacing {spacing}: hatching this {:.0}x{:.0} mm picture would draw {lines} lines, more than {MAX_HATCH_LINES}: give a wider spacing (or a smaller page)",
        page.width, page.height
    )))
}

/// One family of parallel lines, fixed on the page: screen lines m·p = (k·S − K) / s.
struct Family {
    /// Unit normal of the lines in screen space.
    m: Pt2,
    /// Unit direction along the lines in screen space.
    dir: Pt2,
    /// Screen distance between lines.
    step: f64,
    /// Screen offset of line k = 0.
    base: f64,
    /// Half the length of every line, from its foot on the content's centre.
    reach: f64,
    /// The centre of the framed content.
    centre: Pt2,
}

impl Family {
    /// Lines at `angle_deg` on the page (counter-clockwise as seen), `spacing_mm` apart.
    fn new(layout: &Layout, angle_deg: f64, spacing_mm: f64) -> Family {
        let (s, c) = angle_deg.to_radians().sin_cos();
        // Screen y is up, as seen: a page angle is the same screen angle.
        let dir = [c, s];
        let m = [-s, c];
        // The page point of screen p is area.min + scale (p.x − x0, y1 − p.y); its offset along
        // the page normal (−s, −c) (y down) is scale (m·p) + K.
        let (a, cr) = (layout.area, layout.content);
        let k_const =
            -s * (a.xmin - layout.scale * cr.xmin) - c * (a.ymin + layout.scale * cr.ymax);
        let centre = [0.5 * (cr.xmin + cr.xmax), 0.5 * (cr.ymin + cr.ymax)];
        let reach = 0.5 * cr.width().hypot(cr.height()) * 1.01 + 1e-9;
        Family {
            m,
            dir,
            step: spacing_mm / layout.scale,
            base: -k_const / layout.scale,
            reach,
            centre,
        }
    }

    /// The segment of line k over the whole content.
    fn line(&self, k: i64) -> [Pt2; 2] {
        let off = self.base + k as f64 * self.step;
        let foot_t = off - (self.m[0] * self.centre[0] + self.m[1] * self.centre[1]);
        let foot = [
            self.centre[0] + foot_t * self.m[0],
            self.centre[1] + foot_t * self.m[1],
        ];
        let r = self.reach;
        [
            [foot[0] - r * self.dir[0], foot[1] - r * self.dir[1]],
            [foot[0] + r * self.dir[0], foot[1] + r * self.dir[1]],
        ]
    }

    /// The numbers k0..=k1 of this family's lines that cross the region's extent (None when
    /// it has none).
    fn range(&self, region: &MultiPolygon) -> Option<(i64, i64)> {
        let pts = region.iter().flatten().flatten();
        let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
        for p in pts {
            let o = self.m[0] * p[0] + self.m[1] * p[1];
            lo = lo.min(o);
            hi = hi.max(o);
        }
        if lo > hi || lo.is_nan() || hi.is_nan() {
            return None;
        }
        let k0 = ((lo - self.base) / self.step).ceil() as i64;
        let k1 = ((hi - self.base) / self.step).floor() as i64;
        Some((k0, k1))
    }

    /// How many of this family's lines cross the region's extent.
    fn count(&self, region: &MultiPolygon) -> u64 {
        self.range(region).map_or(0, |(k0, k1)| {
            k1.saturating_sub(k0).saturating_add(1).max(0) as u64
        })
    }

    /// The pieces of this family's lines inside the closed region.
    fn clip(&self, region: &MultiPolygon) -> Vec<[Pt2; 2]> {
        let Some((k0, k1)) = self.range(region) else {
            return Vec::new();
        };
        let mut out = Vec::new();
        for k in k0..=k1 {
            let [a, b] = self.line(k);
            for iv in intervals_in(a, b, region) {
                if iv[1] > iv[0] {
                    out.push([at(a, b, iv[0]), at(a, b, iv[1])]);
                }
            }
        }
        out
    }
}

/// The outlines of the hatched regions: for each (group, tone) of a hatched tone, the boundary
/// rings of the union of its faces' visible regions, as closed polylines with the group's
/// first leaf. `group` maps a leaf to the group whose faces are merged (a layer's object, or
/// one for all).
pub(crate) fn tone_outlines(
    hatching: &Hatching,
    vis: &Visibility,
    group: impl Fn(u32) -> u32 + Sync,
) -> Vec<(u32, Vec<Pt2>)> {
    let mut keys: Vec<(u32, u8, u32)> = hatching
        .tones
        .iter()
        .filter(|&&(_, _, t)| t > 0)
        .map(|&(_, leaf, t)| (group(leaf), t, leaf))
        .collect();
    keys.sort_unstable();
    keys.dedup_by_key(|k| (k.0, k.1));
    keys.par_iter()
        .map(|&(g, t, leaf)| {
            let regions: Vec<_> = hatching
                .tones
                .iter()
                .filter(|&&(_, l, tt)| tt == t && group(l) == g)
                .map(|&(f, _, _)| vis.face(f).visible())
                .collect();
            let rings: Vec<&Ring> = regions.iter().flat_map(|m| m.iter().flatten()).collect();
            let rect = Rect::of_points(rings.iter().flat_map(|r| r.iter()));
            let union = boolean::union(rings.iter().copied(), &rect);
            union
                .into_iter()
                .flatten()
                .filter(|r| r.len() >= 2)
                .map(|mut r| {
                    r.push(r[0]);
                    (leaf, r)
                })
                .collect::<Vec<_>>()
        })
        .collect::<Vec<_>>()
        .into_iter()
        .flatten()
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::view::Frame;

    fn layout() -> Layout {
        let content = Rect::new(0., 0., 10., 10.);
        let frame = Frame {
            rect: content.padded(0.5),
            unit: 10.0,
            content,
        };
        Layout::new(
            &frame,
            Some(super::super::page::PageSize::parse("120x120").unwrap()),
            Some(10.0),
            1,
        )
        .unwrap()
    }

    #[test]
    fn tones_run_from_lit_to_cross_hatched() {
        assert_eq!(tone(1.0), 0);
        assert_eq!(tone(0.0), TONES - 1);
        assert!(tone(0.5) > tone(0.9));
        assert_eq!(families(TONES - 1).len(), 2);
    }

    #[test]
    fn lines_sit_on_the_page_grid_and_inside_the_region() {
        // 10 screen units are 100 mm: 2 mm spacing is 0.2 screen units. Horizontal lines on
        // the page are at y = 10 + 2k mm, i.e. screen y = 10 − (10 + 2k − 10) / 10.
        let l = layout();
        let fam = Family::new(&l, 0.0, 2.0);
        let sq: MultiPolygon = vec![vec![vec![
            [1.05, 1.05],
            [2.95, 1.05],
            [2.95, 2.95],
            [1.05, 2.95],
        ]]];
        let segs = fam.clip(&sq);
        assert_eq!(segs.len(), 9, "page y = 82, 84, ..., 98 mm");
        for s in &segs {
            let page = l.to_page(s[0]);
            let k = (page[1] - 10.0) / 2.0;
            assert!((k - k.round()).abs() < 1e-9, "{page:?}");
            assert!((s[0][0] - 1.05).abs() < 1e-12 && (s[1][0] - 2.95).abs() < 1e-12);
        }
    }

    #[test]
    fn adjacent_faces_share_their_lines() {
        // Two squares side by side: the same lines, cut at the shared edge, meet end to end.
        let l = layout();
        let fam = Family::new(&l, 30.0, 1.0);
        let left: MultiPolygon = vec![vec![vec![[1., 1.], [5., 1.], [5., 5.], [1., 5.]]]];
        let right: MultiPolygon = vec![vec![vec![[5., 1.], [9., 1.], [9., 5.], [5., 5.]]]];
        let (a, b) = (fam.clip(&left), fam.clip(&right));
        let meets = a
            .iter()
            .flatten()
            .filter(|p| b.iter().flatten().any(|q| q == *p))
            .count();
        assert!(meets >= 10, "{meets} shared end points");
        // Total hatch length is the same as hatching the union.
        let union: MultiPolygon = vec![vec![vec![[1., 1.], [9., 1.], [9., 5.], [1., 5.]]]];
        let len = |v: &[[Pt2; 2]]| -> f64 {
            v.iter()
                .map(|s| (s[1][0] - s[0][0]).hypot(s[1][1] - s[0][1]))
                .sum()
        };
        let whole = len(&fam.clip(&union));
        assert!((len(&a) + len(&b) - whole).abs() < 1e-9 * whole);
    }

    #[test]
    fn exact_clip_agrees_with_geo() {
        // A concave region with a hole, hatched at an odd angle: the pieces' total length
        // equals geo's line clipping (an independent engine), to its float grid's precision.
        use geo::{BooleanOps, Length, LineString, MultiLineString, Polygon};
        let l = layout();
        let fam = Family::new(&l, 23.0, 0.37);
        let outer = vec![[1., 1.], [9., 2.], [6., 5.], [9., 9.], [2., 8.], [3.5, 4.5]];
        let hole = vec![[4., 3.], [4.5, 6.], [6.5, 6.5], [5.5, 3.5]];
        let region: MultiPolygon = vec![vec![outer.clone(), hole.clone()]];
        let ours: f64 = fam
            .clip(&region)
            .iter()
            .map(|s| crate::geom::poly2::dist(s[0], s[1]))
            .sum();
        let ring = |r: &[Pt2]| -> LineString<f64> { r.iter().map(|p| (p[0], p[1])).collect() };
        let poly = Polygon::new(ring(&outer), vec![ring(&hole)]);
        let lines: MultiLineString<f64> = (-1000..1000)
            .map(|k| {
                let [a, b] = fam.line(k);
                ring(&[a, b])
            })
            .collect();
        let theirs: f64 = poly
            .clip(&lines, false)
            .0
            .iter()
            .map(|ls| geo::Euclidean.length(ls))
            .sum();
        assert!(ours > 10.0);
        assert!(
            (ours - theirs).abs() < 1e-6 * ours,
            "{ours} vs geo {theirs}"
        );
    }
}
