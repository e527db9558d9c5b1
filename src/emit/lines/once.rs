//! Every piece of line stroked once: where two drawn segments run along each other on the
//! screen, the one of lower rank loses the shared part.
//!
//! Distinct edges can project onto one screen line: the edges of a face seen (nearly)
//! edge-on, an intersection curve along an edge, an edge right behind another with only
//! edge-on faces between them. Each is visible by itself; drawn as they are, a plotter
//! strokes the shared part twice. Two segments run along each other where they are nearly
//! parallel (sine of their angle at most [`PARALLEL_SIN`]) and within [`ONCE_TOL`] of the
//! drawing's extent of each other; the part of the lower-ranked one within that distance of
//! the other is removed. Ranks: edge kind (silhouette first, as [`EdgeKind::ALL`]), then
//! order in the edge list.

use crate::count::Span;
use crate::geom::box_pairs::{filter_map_pairs, Bounds3};
use crate::geom::poly2::Pt2;

use super::clip_segment::{at, complement, Interval};
use super::edges::EdgeKind;

/// Distance, relative to the drawing's extent, under which two nearly parallel segments
/// count as one line (far below anything a plotter or screen shows, far above f64 rounding
/// of projected points).
pub(crate) const ONCE_TOL: f64 = 4e-9;
/// Largest sine of the angle between two segments that may count as one line (edges that
/// meet at a vertex at any visible angle never do).
pub(crate) const PARALLEL_SIN: f64 = 1e-6;

/// A drawn segment with its rank (lower ranks are kept).
#[derive(Debug, Clone, Copy)]
pub(crate) struct Ranked {
    /// Kind of its edge (earlier in [`EdgeKind::ALL`] ranks first).
    pub kind: EdgeKind,
    /// Index of its edge.
    pub edge: u32,
    /// The screen segment.
    pub seg: [Pt2; 2],
}

impl Ranked {
    fn rank(&self) -> (usize, u32) {
        let k = EdgeKind::ALL.iter().position(|&k| k == self.kind);
        (k.unwrap_or(usize::MAX), self.edge)
    }
}

/// What is left of each segment of `segs` once every shared part is kept only on the
/// higher-ranked segment (of equal ranks, the one of lesser least x, then the earlier): for
/// each, its remaining pieces (in order along it). Segments of `keep` always win and lose
/// nothing themselves (visible lines over hidden ones).
pub(crate) fn stroke_once(segs: &[Ranked], keep: &[[Pt2; 2]]) -> Vec<Vec<[Pt2; 2]>> {
    // No segment, nothing to cut: `keep` is not indexed (nefertiti's visible lines were 1 ms
    // on one thread, indexed against an empty hidden list).
    if segs.is_empty() {
        return Vec::new();
    }
    let (tol, all) = all_ranked(segs, keep);
    let xmin = |s: &[Pt2; 2]| s[0][0].min(s[1][0]);
    let xmax = |s: &[Pt2; 2]| s[0][0].max(s[1][0]);
    // `along` finds nothing for segments farther apart than `tol` (a point of one within
    // `tol` of the other lies within `tol` of its x and y ranges; rounding in `along` is many
    // orders below `tol`), so a pair is tested only when their x ranges come within `tol` and
    // their y ranges within `2 tol`: far fewer calls of its square roots.
    let (ylo, yhi) = (
        |s: &[Pt2; 2]| s[0][1].min(s[1][1]),
        |s: &[Pt2; 2]| s[0][1].max(s[1][1]),
    );
    let apart_in_y =
        |a: &[Pt2; 2], b: &[Pt2; 2]| ylo(a) > yhi(b) + 2.0 * tol || ylo(b) > yhi(a) + 2.0 * tol;
    // Candidate pairs from a grid of boxes grown past that reach (every pair it allows is a
    // candidate), on all threads; the exact tests below then decide.
    let reach = |s: &[Pt2; 2]| -> Bounds3 {
        [
            [xmin(s) - 2.0 * tol, ylo(s) - 3.0 * tol, 0.0],
            [xmax(s) + 2.0 * tol, yhi(s) + 3.0 * tol, 0.0],
        ]
    };
    let mut boxes: Vec<Bounds3> = crate::chunked::map(all.len(), |i| reach(&all[i].0));
    add_directions(&mut boxes, &all);
    let pair = |i: u32, j: u32| {
        let (i, j) = (i as usize, j as usize);
        // Of two segments of one rank, the one of lesser least x (ties: the earlier) wins.
        let (first, second) = match xmin(&all[j].0).total_cmp(&xmin(&all[i].0)) {
            std::cmp::Ordering::Less => (j, i),
            _ => (i, j),
        };
        if xmin(&all[second].0) > xmax(&all[first].0) + tol {
            return None;
        }
        let (hi, lo) = if all[first].1 <= all[second].1 {
            (first, second)
        } else {
            (second, first)
        };
        if all[lo].1 .0 == 0 || apart_in_y(&all[first].0, &all[second].0) {
            return None; // both kept, or too far apart
        }
        along(&all[lo].0, &all[hi].0, tol).map(|iv| (lo, iv))
    };
    let found = filter_map_pairs(&boxes, pair, Span::NONE);
    let mut cuts: Vec<Vec<Interval>> = vec![Vec::new(); all.len()];
    for (lo, iv) in found {
        cuts[lo].push(iv);
    }
    remaining(&all[keep.len()..], &cuts[keep.len()..], tol)
}

/// Angle (radians) that one grid cell spans in the direction coordinate of [`add_directions`].
const ANGLE_CELL: f64 = 1e-2;

/// Gives every box a third coordinate, its segment's direction (an angle mod π, scaled so that
/// [`ANGLE_CELL`] is about a grid cell), widened past what [`along`] accepts as parallel: the
/// grid then pairs only segments of nearly one direction. Without it, segments whose boxes
/// overlap but which run in many directions (the spikes of a 100k-corner star) made the pairs
/// quadratic. Directions wrap at an angle of 1 radian (mod π), which few drawings use much: a
/// segment within the margin of it spans every direction, so no parallel pair is lost.
///
/// Each axis is scaled by its boxes' mean extent first (a positive scale per axis keeps every
/// overlap): the grid's cells are cubes, and boxes all tall and thin (the teeth of a 100k-corner
/// comb) otherwise shared a few cells, every pair a candidate.
fn add_directions(boxes: &mut [Bounds3], all: &[RankedSeg]) {
    use std::f64::consts::PI;
    let n = boxes.len().max(1) as f64;
    let mut means = [0.0; 2];
    for (k, mean) in means.iter_mut().enumerate() {
        *mean = boxes.iter().map(|b| b[1][k] - b[0][k]).sum::<f64>() / n;
    }
    let scaled = means.map(|m| m.is_finite() && m > 0.0);
    // Each box's own arithmetic, on all threads for many (the means were summed in order).
    crate::chunked::for_each_mut(boxes, |_, b| {
        for k in (0..2).filter(|&k| scaled[k]) {
            b[0][k] /= means[k];
            b[1][k] /= means[k];
        }
    });
    // Every axis' mean extent is now 1: an angle of ANGLE_CELL spans about as much.
    let scale = 1.0 / ANGLE_CELL;
    // asin(PARALLEL_SIN) with a wide margin for the rounding of atan2.
    let margin = 4.0 * PARALLEL_SIN;
    crate::chunked::for_each_mut(boxes, |i, b| {
        let s = &all[i].0;
        let (dx, dy) = (s[1][0] - s[0][0], s[1][1] - s[0][1]);
        let (lo, hi) = if dx == 0.0 && dy == 0.0 {
            (0.0, PI)
        } else {
            let a = (dy.atan2(dx) - 1.0).rem_euclid(PI);
            if a < margin || a > PI - margin {
                (0.0, PI)
            } else {
                (a - margin, a + margin)
            }
        };
        b[0][2] = lo * scale;
        b[1][2] = hi * scale;
    });
}

/// A segment and its rank: (0, 0, 0) for a kept one, else (1, kind, edge); lower wins.
type RankedSeg = ([Pt2; 2], (usize, usize, u32));

/// The coincidence tolerance for these segments, and all of them, those of `keep` first
/// with the best rank.
fn all_ranked(segs: &[Ranked], keep: &[[Pt2; 2]]) -> (f64, Vec<RankedSeg>) {
    let extent = segs
        .iter()
        .map(|r| &r.seg)
        .chain(keep)
        .flatten()
        .fold(0.0f64, |m, p| m.max(p[0].abs()).max(p[1].abs()));
    let all = keep
        .iter()
        .map(|s| (*s, (0, 0, 0)))
        .chain(segs.iter().map(|r| {
            let (k, e) = r.rank();
            (r.seg, (1, k, e))
        }))
        .collect();
    (ONCE_TOL * extent, all)
}

/// What is left of each segment once its cut intervals (any order) are taken away: pieces
/// longer than `tol`, in order along it.
///
/// On all threads for many segments (each a list of its own to make).
fn remaining(segs: &[RankedSeg], cuts: &[Vec<Interval>], tol: f64) -> Vec<Vec<[Pt2; 2]>> {
    crate::chunked::map(segs.len(), |k| {
        let seg = segs[k].0;
        if cuts[k].is_empty() {
            return vec![seg];
        }
        let mut c = cuts[k].clone();
        c.sort_by(|a, b| a[0].total_cmp(&b[0]));
        complement(&merge(c))
            .into_iter()
            .filter(|iv| iv[1] > iv[0])
            .map(|iv| [at(seg[0], seg[1], iv[0]), at(seg[0], seg[1], iv[1])])
            .filter(|p| (p[1][0] - p[0][0]).hypot(p[1][1] - p[0][1]) > tol)
            .collect()
    })
}

/// The parameter interval of `s` within `tol` of segment `h`, when the two are nearly
/// parallel and it is longer than `tol`.
fn along(s: &[Pt2; 2], h: &[Pt2; 2], tol: f64) -> Option<Interval> {
    let (ds, dh) = (sub(s[1], s[0]), sub(h[1], h[0]));
    if far_from_parallel(ds, dh) {
        return None;
    }
    let (ls, lh) = (norm(ds), norm(dh));
    if ls == 0.0 || lh == 0.0 || (cross(ds, dh) / (ls * lh)).abs() > PARALLEL_SIN {
        return None;
    }
    let u = [dh[0] / lh, dh[1] / lh];
    // Along h: a(t) = (s(t) - h0)·u must lie in [0, lh]; across: |(s(t) - h0) × u| ≤ tol.
    let (a0, a1) = (dot(sub(s[0], h[0]), u), dot(ds, u));
    let (c0, c1) = (cross(sub(s[0], h[0]), u), cross(ds, u));
    let mut iv = [0.0f64, 1.0f64];
    let mut clamp = |v0: f64, v1: f64, lo: f64, hi: f64| {
        // v0 + v1 t in [lo, hi].
        if v1 == 0.0 {
            if v0 < lo || v0 > hi {
                iv = [1.0, 0.0];
            }
            return;
        }
        let (t0, t1) = ((lo - v0) / v1, (hi - v0) / v1);
        iv[0] = iv[0].max(t0.min(t1));
        iv[1] = iv[1].min(t0.max(t1));
    };
    clamp(a0, a1, 0.0, lh);
    clamp(c0, c1, -tol, tol);
    ((iv[1] - iv[0]) * ls > tol).then_some(iv)
}

/// True only of directions the parallel test of [`along`] turns away, decided before its
/// square roots: squared, with a margin far above the rounding of either form.
fn far_from_parallel(ds: Pt2, dh: Pt2) -> bool {
    let c = cross(ds, dh);
    c * c > PARALLEL_SIN * PARALLEL_SIN * (1.0 + 1e-6) * (dot(ds, ds) * dot(dh, dh))
}

/// Sorted intervals merged where they overlap or touch.
fn merge(ivs: Vec<Interval>) -> Vec<Interval> {
    let mut out: Vec<Interval> = Vec::with_capacity(ivs.len());
    for iv in ivs {
        match out.last_mut() {
            Some(last) if iv[0] <= last[1] => last[1] = last[1].max(iv[1]),
            _ => out.push(iv),
        }
    }
    out
}

fn sub(a: Pt2, b: Pt2) -> Pt2 {
    [a[0] - b[0], a[1] - b[1]]
}

fn dot(a: Pt2, b: Pt2) -> f64 {
    a[0] * b[0] + a[1] * b[1]
}

fn cross(a: Pt2, b: Pt2) -> f64 {
    a[0] * b[1] - a[1] * b[0]
}

fn norm(a: Pt2) -> f64 {
    a[0].hypot(a[1])
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `along` without its early turn-away: the on-line test alone, as it was.
    fn along_by_norms(s: &[Pt2; 2], h: &[Pt2; 2]) -> bool {
        let (ds, dh) = (sub(s[1], s[0]), sub(h[1], h[0]));
        let (ls, lh) = (norm(ds), norm(dh));
        !(ls == 0.0 || lh == 0.0 || (cross(ds, dh) / (ls * lh)).abs() > PARALLEL_SIN)
    }

    /// The squared turn-away before the square roots never turns away a pair the norms'
    /// test keeps: random pairs at angles around PARALLEL_SIN, over scales from 1e-150 to
    /// 1e150.
    #[test]
    fn the_early_turn_away_agrees_with_the_norms() {
        let mut rng = crate::geom::rng::XorShift::new(99);
        let (mut kept, mut near) = (0, 0);
        for k in 0..300_000 {
            let scale = 10f64.powi([-150, -3, 0, 2, 150][k % 5]);
            let a = rng.range(0.0, std::f64::consts::TAU);
            let angle = PARALLEL_SIN * rng.range(0.0, 2.0) * if k % 2 == 0 { 1.0 } else { -1.0 };
            let (l1, l2) = (rng.range(1e-3, 10.0) * scale, rng.range(1e-3, 10.0) * scale);
            let o = [rng.range(-1.0, 1.0) * scale, rng.range(-1.0, 1.0) * scale];
            let h = [o, [o[0] + l1 * a.cos(), o[1] + l1 * a.sin()]];
            let b = a + angle;
            let s = [o, [o[0] + l2 * b.cos(), o[1] + l2 * b.sin()]];
            let by_norms = along_by_norms(&s, &h);
            let turned = far_from_parallel(sub(s[1], s[0]), sub(h[1], h[0]));
            assert!(!(turned && by_norms), "{s:?} {h:?}");
            kept += usize::from(by_norms);
            near += usize::from(!turned && !by_norms);
        }
        assert!(kept > 10_000 && near > 0, "{kept} {near}");
    }

    fn r(kind: EdgeKind, edge: u32, a: Pt2, b: Pt2) -> Ranked {
        Ranked {
            kind,
            edge,
            seg: [a, b],
        }
    }

    #[test]
    fn overlapping_collinear_segments_keep_the_higher_rank() {
        let segs = [
            r(EdgeKind::Plain, 0, [0., 0.], [4., 0.]),
            r(EdgeKind::Silhouette, 1, [3., 0.], [1., 0.]),
            // Meets the first at a vertex at a right angle: untouched.
            r(EdgeKind::Plain, 2, [4., 0.], [4., 3.]),
        ];
        let out = stroke_once(&segs, &[]);
        assert_eq!(out[1], vec![[[3., 0.], [1., 0.]]]);
        assert_eq!(out[0], vec![[[0., 0.], [1., 0.]], [[3., 0.], [4., 0.]]]);
        assert_eq!(out[2], vec![[[4., 0.], [4., 3.]]]);
    }

    /// The rule by a sweep over all segments sorted by least x (stable), every later one
    /// whose x range comes within `tol` paired with the earlier: the reference the grid of
    /// candidate pairs must reproduce.
    fn by_sweep(segs: &[Ranked], keep: &[[Pt2; 2]]) -> Vec<Vec<[Pt2; 2]>> {
        let (tol, all) = all_ranked(segs, keep);
        let xmin = |s: &[Pt2; 2]| s[0][0].min(s[1][0]);
        let xmax = |s: &[Pt2; 2]| s[0][0].max(s[1][0]);
        let mut order: Vec<usize> = (0..all.len()).collect();
        order.sort_by(|&i, &j| xmin(&all[i].0).total_cmp(&xmin(&all[j].0)));
        let mut cuts: Vec<Vec<Interval>> = vec![Vec::new(); all.len()];
        for (k, &i) in order.iter().enumerate() {
            for &j in &order[k + 1..] {
                if xmin(&all[j].0) > xmax(&all[i].0) + tol {
                    break;
                }
                let (hi, lo) = if all[i].1 <= all[j].1 { (i, j) } else { (j, i) };
                if all[lo].1 .0 != 0 {
                    if let Some(iv) = along(&all[lo].0, &all[hi].0, tol) {
                        cuts[lo].push(iv);
                    }
                }
            }
        }
        remaining(&all[keep.len()..], &cuts[keep.len()..], tol)
    }

    /// `n` lines through the square [-5, 5]², each a point and a unit direction.
    fn random_lines(rng: &mut crate::geom::rng::XorShift, n: usize) -> Vec<(Pt2, Pt2)> {
        (0..n)
            .map(|_| {
                let a = [rng.range(-5., 5.), rng.range(-5., 5.)];
                let t = rng.range(0., std::f64::consts::TAU);
                (a, [t.cos(), t.sin()])
            })
            .collect()
    }

    #[test]
    fn grid_pairs_cut_what_a_sweep_cuts() {
        // Pieces of a few lines (so many overlap along them, ranks tied and not), some an ulp
        // off, reversed, or turned slightly, with kept lines among them.
        let mut rng = crate::geom::rng::XorShift::new(41);
        let lines = random_lines(&mut rng, 6);
        let piece = |rng: &mut crate::geom::rng::XorShift| {
            let (a, d) = lines[rng.below(lines.len())];
            let (t0, t1) = (rng.range(0., 8.), rng.range(0., 8.));
            let off = if rng.below(3) == 0 { 1e-15 } else { 0.0 };
            let turn = if rng.below(5) == 0 { 1e-7 } else { 0.0 };
            [
                [a[0] + d[0] * t0 + off, a[1] + d[1] * t0],
                [a[0] + (d[0] + turn) * t1, a[1] + (d[1] - turn) * t1 + off],
            ]
        };
        let kinds = [EdgeKind::Silhouette, EdgeKind::Crease, EdgeKind::Plain];
        let mut cut_some = 0;
        for round in 0..20 {
            let segs: Vec<Ranked> = (0..60)
                .map(|_| Ranked {
                    kind: kinds[rng.below(3)],
                    edge: rng.below(12) as u32,
                    seg: piece(&mut rng),
                })
                .collect();
            let keep: Vec<[Pt2; 2]> = (0..round % 4).map(|_| piece(&mut rng)).collect();
            let (grid, sweep) = (stroke_once(&segs, &keep), by_sweep(&segs, &keep));
            assert_eq!(grid, sweep, "round {round}");
            cut_some += grid
                .iter()
                .zip(&segs)
                .filter(|(g, s)| g.as_slice() != [s.seg])
                .count();
        }
        assert!(cut_some > 100, "the pieces overlap: {cut_some} cut");
    }

    /// Over a chunk of segments the boxes and the pieces left are made on all threads: the
    /// same pieces as on one thread. With no segments, nothing to cut, whatever is kept.
    #[test]
    fn many_segments_on_several_threads_are_cut_as_on_one() {
        let mut rng = crate::geom::rng::XorShift::new(43);
        let kinds = [EdgeKind::Silhouette, EdgeKind::Crease, EdgeKind::Plain];
        // Short pieces of 40 lines through a square: many overlap, most do not.
        let lines = random_lines(&mut rng, 40);
        let segs: Vec<Ranked> = (0..3 * crate::chunked::CHUNK)
            .map(|k| {
                let (a, d) = lines[rng.below(lines.len())];
                let t0 = rng.range(0., 8.);
                let t1 = t0 + rng.range(0.01, 0.5);
                Ranked {
                    kind: kinds[rng.below(3)],
                    edge: k as u32,
                    seg: [
                        [a[0] + d[0] * t0, a[1] + d[1] * t0],
                        [a[0] + d[0] * t1, a[1] + d[1] * t1],
                    ],
                }
            })
            .collect();
        let keep: Vec<[Pt2; 2]> = segs[..50].iter().map(|r| r.seg).collect();
        let pool = crate::chunked::pool;
        let one = pool(1).install(|| stroke_once(&segs, &keep));
        let cut = one
            .iter()
            .zip(&segs)
            .filter(|(o, s)| o.as_slice() != [s.seg]);
        assert!(cut.count() > 1000, "the pieces overlap");
        assert_eq!(pool(3).install(|| stroke_once(&segs, &keep)), one);
        assert_eq!(stroke_once(&[], &keep), by_sweep(&[], &keep));
        assert!(stroke_once(&[], &keep).is_empty());
    }

    #[test]
    fn nearly_collinear_copies_and_kept_lines() {
        // The same segment an ulp off, reversed: drawn once.
        let segs = [
            r(
                EdgeKind::Silhouette,
                0,
                [-15.342991981424783, 11.112696255179376],
                [-15.347482168095203, 11.105495937983646],
            ),
            r(
                EdgeKind::Plain,
                1,
                [-15.347482168095198, 11.105495937983656],
                [-15.342991981424785, 11.112696255179376],
            ),
        ];
        let out = stroke_once(&segs, &[]);
        assert_eq!(out[0].len(), 1);
        assert!(out[1].is_empty(), "{:?}", out[1]);
        // A hidden segment under a visible one disappears where it is covered.
        let hidden = [r(EdgeKind::Silhouette, 0, [0., 0.], [2., 0.])];
        let out = stroke_once(&hidden, &[[[1., 0.], [5., 0.]]]);
        assert_eq!(out[0], vec![[[0., 0.], [1., 0.]]]);
    }
}
