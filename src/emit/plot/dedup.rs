//! A line is drawn once: segments that repeat or overlap a segment kept before them, along
//! the same line, lose the shared part.
//!
//! Segments come in priority order (the caller puts visible pens before hidden ones); each
//! keeps only what no earlier kept segment covers. Two segments lie on one line when both
//! ends of the shorter are within `eps` of the longer's line, and overlap when they share more
//! than `eps` of length. Where a segment is cut, the cut point is the covering segment's own
//! end point, so the pieces meet their neighbours exactly and chain without gaps. A uniform
//! grid finds candidates: each segment is listed in every cell that comes within `eps` of it,
//! so two segments that overlap share a cell ([`overlap`] says why), and the work follows the
//! drawing's length.

use crate::count::Count;
use crate::geom::grid::Cells;
use crate::geom::poly2::{dist, Pt2};
use crate::geom::Rect;

/// Counts of what removing repeated and overlapping segments removed.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct DedupStats {
    /// Segments looked at.
    pub segments: usize,
    /// Segments dropped whole (exact duplicates, or covered by others).
    pub dropped: usize,
    /// Segments that lost part of their length.
    pub trimmed: usize,
    /// Length removed.
    pub length: f64,
}

/// [`dedup_indexed`] without its index (the tests').
#[cfg(test)]
pub(crate) fn dedup(
    segs: &[[Pt2; 2]],
    eps: f64,
    done: Count,
) -> (Vec<(usize, [Pt2; 2])>, DedupStats) {
    let (kept, stats, _) = dedup_indexed(segs, eps, done);
    (kept, stats)
}

/// The parts of `segs` (in priority order) not covered by an earlier segment's kept parts,
/// each with the index of the segment it comes from, in input order; and the index it ends
/// with: every kept part, in order, over `segs`' bounds (the index
/// [`SegmentIndex::new`]`(segs, eps)` with the kept parts inserted would be, which the joins'
/// bridges then ask).
///
/// The segments looked at go to `done`, once per chunk.
pub(crate) fn dedup_indexed(
    segs: &[[Pt2; 2]],
    eps: f64,
    done: Count,
) -> (Vec<(usize, [Pt2; 2])>, DedupStats, SegmentIndex) {
    let mut index = SegmentIndex::new(segs, eps);
    let mut kept: Vec<(usize, [Pt2; 2])> = Vec::with_capacity(segs.len());
    let mut stats = DedupStats {
        segments: segs.len(),
        ..DedupStats::default()
    };
    let mut covers: Vec<Cover> = Vec::new();
    for (i, &[a, b]) in segs.iter().enumerate() {
        done.tick(i);
        let len = dist(a, b);
        if len <= eps {
            stats.dropped += 1;
            stats.length += len;
            continue;
        }
        index.covers(a, b, &mut covers);
        let before = kept.len();
        if covers.is_empty() {
            kept.push((i, [a, b]));
        } else {
            covers.sort_by(|p, q| p.t0.total_cmp(&q.t0).then(p.by.cmp(&q.by)));
            let (mut t, mut pt) = (0.0, a);
            let mut kept_len = 0.0;
            for c in &covers {
                if (c.t0 - t) * len > eps {
                    kept.push((i, [pt, c.p0]));
                    kept_len += (c.t0 - t) * len;
                }
                if c.t1 > t {
                    (t, pt) = (c.t1, c.p1);
                }
            }
            if (1.0 - t) * len > eps {
                kept.push((i, [pt, b]));
                kept_len += (1.0 - t) * len;
            }
            if kept.len() == before {
                stats.dropped += 1;
            } else {
                stats.trimmed += 1;
            }
            stats.length += (len - kept_len).max(0.0);
        }
        for k in &kept[before..] {
            index.insert(k.1);
        }
    }
    done.tick_rest(segs.len());
    (kept, stats, index)
}

/// Segments in a grid, to ask which of them run along a new segment.
pub(crate) struct SegmentIndex {
    grid: CellGrid,
    segs: Vec<[Pt2; 2]>,
    /// Per segment: the last query that met it (a segment is listed in several cells).
    seen: Vec<usize>,
    query: usize,
    cells: Vec<usize>,
    /// The segment `cells` was listed for (an insert of the segment just asked about reuses
    /// them).
    cells_for: Option<[Pt2; 2]>,
    eps: f64,
}

impl SegmentIndex {
    /// An empty index over the bounds of `extent` (segments outside still work, slower);
    /// `eps` is the coincidence tolerance.
    pub(crate) fn new(extent: &[[Pt2; 2]], eps: f64) -> SegmentIndex {
        SegmentIndex {
            grid: CellGrid::new(extent, eps),
            segs: Vec::with_capacity(extent.len()),
            seen: Vec::with_capacity(extent.len()),
            query: 0,
            cells: Vec::new(),
            cells_for: None,
            eps,
        }
    }

    /// Adds a segment.
    pub(crate) fn insert(&mut self, s: [Pt2; 2]) {
        if self.cells_for != Some(s) {
            self.grid.cells_of(s[0], s[1], &mut self.cells);
            self.cells_for = Some(s);
        }
        self.grid.insert(self.segs.len(), &self.cells);
        self.segs.push(s);
        self.seen.push(0);
    }

    /// True when a segment of the index runs along a → b for more than `eps`.
    pub(crate) fn overlaps(&mut self, a: Pt2, b: Pt2) -> bool {
        self.overlaps_where(a, b, |_| true)
    }

    /// True when a segment of the index that `keep` accepts (by its number, in the order
    /// inserted) runs along a → b for more than `eps`: the answer of an index holding only
    /// those.
    pub(crate) fn overlaps_where(&mut self, a: Pt2, b: Pt2, keep: impl Fn(usize) -> bool) -> bool {
        let mut covers = Vec::new();
        self.covers_where(a, b, &mut covers, keep);
        !covers.is_empty()
    }

    /// The parts of a → b that segments of the index cover (unsorted).
    fn covers(&mut self, a: Pt2, b: Pt2, out: &mut Vec<Cover>) {
        self.covers_where(a, b, out, |_| true);
    }

    /// The parts of a → b that segments of the index `keep` accepts cover, each with the
    /// number of the segment covering it (unsorted: cell by cell).
    fn covers_where(&mut self, a: Pt2, b: Pt2, out: &mut Vec<Cover>, keep: impl Fn(usize) -> bool) {
        out.clear();
        let len = dist(a, b);
        if len == 0.0 {
            return;
        }
        self.query += 1;
        self.grid.cells_of(a, b, &mut self.cells);
        self.cells_for = Some([a, b]);
        for &cell in &self.cells {
            for &k in &self.grid.cells[cell] {
                if self.seen[k] == self.query || !keep(k) {
                    continue;
                }
                self.seen[k] = self.query;
                let [c, d] = self.segs[k];
                if let Some(cov) = overlap(a, b, len, c, d, self.eps) {
                    out.push(Cover { by: k, ..cov });
                }
            }
        }
    }
}

/// The part of a → b (parameters t0 < t1) that an earlier segment covers, with the covering
/// points (the earlier segment's ends, or a and b themselves).
#[derive(Debug, Clone, Copy)]
pub(super) struct Cover {
    t0: f64,
    p0: Pt2,
    t1: f64,
    p1: Pt2,
    /// The covering segment's number in its index (0 from [`overlap`] alone).
    by: usize,
}

/// Distance of `p` from the line through `u` and `v` (u != v).
fn line_dist(u: Pt2, v: Pt2, p: Pt2) -> f64 {
    let (dx, dy) = (v[0] - u[0], v[1] - u[1]);
    ((p[0] - u[0]) * dy - (p[1] - u[1]) * dx).abs() / dist(u, v)
}

/// False only where a → b (length `len`) and c → d cannot lie on one line by [`overlap`]'s
/// test, decided without a square root. If both ends of the shorter are within `eps` of the
/// longer's line, the cross product of their directions is at most 2 `eps` times the longer
/// length, which is less than `len` plus c → d's L1 length; the margins (a factor, and a
/// term for the product's rounding) keep it true of the rounded distances too.
fn nearly_parallel(a: Pt2, b: Pt2, len: f64, c: Pt2, d: Pt2, eps: f64) -> bool {
    let (ux, uy) = (b[0] - a[0], b[1] - a[1]);
    let (vx, vy) = (d[0] - c[0], d[1] - c[1]);
    let l1 = vx.abs() + vy.abs();
    (ux * vy - uy * vx).abs() <= 2.01 * eps * (len + l1) + 1e-12 * len * l1
}

/// How c → d covers a → b (length `len`), when they lie on one line and share more than `eps`.
///
/// Then they come within `eps` of each other (what the grids of this index and of
/// [`super::ink`] rely on; rounding aside). The cover is a part of a → b longer than `eps`
/// whose points project on a → b's line between c's and d's projections. If c → d is the
/// shorter, take X in the cover: c → d crosses the line through X perpendicular to a → b, at
/// Z, and Z lies within `eps` of a → b's line as c and d do, so |XZ| ≤ `eps`. Otherwise a
/// and b lie within `eps` of c → d's line; take it as the x axis, c at 0 and d at x = |cd|,
/// so every point of a → b has |y| ≤ `eps`. If a point of a → b has x in [0, |cd|], it lies
/// within `eps` of c → d. Else a → b lies wholly on one side, say x < 0 (the other is the
/// mirror image). Orient a → b's unit direction u so that u_x ≥ 0: the cover's points X
/// have X·u between c's projection 0 and d's |cd| u_x, so from its first point X0 (X0·u ≥
/// 0) to its last X1 = X0 + s u, with s > `eps`, X1·u > `eps`. But X1·u = x1 u_x + y1 u_y ≤
/// |y1| ≤ `eps`, as x1 < 0 and u_x ≥ 0: a contradiction.
pub(super) fn overlap(a: Pt2, b: Pt2, len: f64, c: Pt2, d: Pt2, eps: f64) -> Option<Cover> {
    if !nearly_parallel(a, b, len, c, d, eps) {
        return None;
    }
    let lc = dist(c, d);
    if lc == 0.0 {
        return None;
    }
    let on_line = if lc >= len {
        line_dist(c, d, a) <= eps && line_dist(c, d, b) <= eps
    } else {
        line_dist(a, b, c) <= eps && line_dist(a, b, d) <= eps
    };
    if !on_line {
        return None;
    }
    let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
    let param = |p: Pt2| ((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / (len * len);
    let (mut tc, mut td, mut c, mut d) = (param(c), param(d), c, d);
    if tc > td {
        (tc, td, c, d) = (td, tc, d, c);
    }
    let (t0, p0) = if tc > 0.0 { (tc, c) } else { (0.0, a) };
    let (t1, p1) = if td < 1.0 { (td, d) } else { (1.0, b) };
    ((t1 - t0) * len > eps).then_some(Cover {
        t0,
        p0,
        t1,
        p1,
        by: 0,
    })
}

/// Segments to a cell of [`CellGrid`] (the grid has a quarter as many cells as segments):
/// nefertiti's hidden-line picture (154k segments) spent 3% less time in emit with
/// four a cell than with one, fewer cells to visit outweighing more segments to test; 2 to 8
/// were alike.
const SEGMENTS_PER_CELL: f64 = 4.0;

/// Square cells over the segments' bounds, a few segments a cell. Each segment is listed in
/// every cell that comes within `pad` of it (`eps`, with a margin for rounding), and a query
/// looks in the cells that come within `pad` of the segment asked about: two segments within
/// 2 `pad` of each other share the cell of the point halfway between their nearest points, so
/// a segment that covers another ([`overlap`]) is always met.
struct CellGrid {
    frame: Cells,
    cells: Vec<Vec<usize>>,
    /// How far from a segment its cells reach.
    pad: f64,
}

impl CellGrid {
    fn new(segs: &[[Pt2; 2]], eps: f64) -> CellGrid {
        let b = Rect::of_points(segs.iter().flatten());
        let frame = Cells::by_area(&b, segs.len() as f64 / SEGMENTS_PER_CELL, 1024, 1 << 16);
        // The rounding of the cells' bounds and of the positions along a segment is a few
        // ulps of the coordinates; 1e-9 of their size is far more.
        let size = [b.xmin, b.xmax, b.ymin, b.ymax]
            .iter()
            .filter(|v| v.is_finite())
            .fold(frame.cell, |m, v| m.max(v.abs()));
        CellGrid {
            frame,
            cells: vec![Vec::new(); frame.len()],
            pad: eps + 1e-9 * size,
        }
    }

    /// The cells that come within `pad` of a → b, row by row (sorted, unique): in each row,
    /// the columns of the part of a → b within `pad` of the row's band, widened by `pad`. A
    /// point outside the grid counts as in the cell it is clamped to, and the edge rows and
    /// columns reach to infinity, so segments outside the bounds are found too.
    fn cells_of(&self, a: Pt2, b: Pt2, out: &mut Vec<usize>) {
        out.clear();
        let f = &self.frame;
        let pad = self.pad;
        let (ylo, yhi) = (a[1].min(b[1]), a[1].max(b[1]));
        let (r0, r1) = (f.row(ylo - pad), f.row(yhi + pad));
        let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
        for r in r0..=r1 {
            // The row's band widened by `pad`; the edge rows reach to infinity.
            let y0 = if r == 0 {
                f64::NEG_INFINITY
            } else {
                f.origin[1] + r as f64 * f.cell - pad
            };
            let y1 = if r + 1 == f.ny {
                f64::INFINITY
            } else {
                f.origin[1] + (r + 1) as f64 * f.cell + pad
            };
            // The x extent of a → b's part within the band.
            let (xa, xb) = if y0 <= ylo && yhi <= y1 {
                (a[0], b[0])
            } else {
                let t = |y: f64| ((y - a[1]) / dy).clamp(0.0, 1.0);
                let (t0, t1) = (t(y0), t(y1));
                (a[0] + t0 * dx, a[0] + t1 * dx)
            };
            let (c0, c1) = (f.column(xa.min(xb) - pad), f.column(xa.max(xb) + pad));
            out.extend((c0..=c1).map(|c| r * f.nx + c));
        }
    }

    fn insert(&mut self, k: usize, cells: &[usize]) {
        for &c in cells {
            self.cells[c].push(k);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The prefilter never rejects a pair the on-line test accepts: random segments, many
    /// along one line with their ends moved by up to twice the tolerance, at several scales.
    #[test]
    fn nearly_parallel_keeps_every_pair_on_one_line() {
        let mut rng = crate::geom::rng::XorShift::new(77);
        let mut on_line = 0;
        for k in 0..200_000 {
            let scale: f64 = [1e-3, 1.0, 300.0, 1e6][k % 4];
            let eps = [0.0, 1e-9, 1e-4, 1e-2][(k / 4) % 4] * scale.min(1.0);
            let p = |rng: &mut crate::geom::rng::XorShift| {
                [rng.range(-scale, scale), rng.range(-scale, scale)]
            };
            let (a, b) = (p(&mut rng), p(&mut rng));
            let along = |rng: &mut crate::geom::rng::XorShift| {
                let t = rng.range(-0.5, 1.5);
                let j = [rng.range(-2.0, 2.0) * eps, rng.range(-2.0, 2.0) * eps];
                [
                    a[0] + t * (b[0] - a[0]) + j[0],
                    a[1] + t * (b[1] - a[1]) + j[1],
                ]
            };
            let (c, d) = if k % 3 == 0 {
                (p(&mut rng), p(&mut rng))
            } else {
                (along(&mut rng), along(&mut rng))
            };
            let (len, lc) = (dist(a, b), dist(c, d));
            if len == 0.0 || lc == 0.0 {
                continue;
            }
            let accepted = if lc >= len {
                line_dist(c, d, a) <= eps && line_dist(c, d, b) <= eps
            } else {
                line_dist(a, b, c) <= eps && line_dist(a, b, d) <= eps
            };
            if accepted {
                on_line += 1;
                assert!(
                    nearly_parallel(a, b, len, c, d, eps),
                    "{a:?} {b:?} {c:?} {d:?} {eps}"
                );
            }
        }
        assert!(on_line > 10_000, "{on_line}");
    }

    #[test]
    fn a_counted_dedup_counts_every_segment_and_keeps_the_same() {
        use std::sync::atomic::{AtomicUsize, Ordering};
        let segs: Vec<[Pt2; 2]> = (0..3000)
            .map(|k| {
                let x = f64::from(k % 1500);
                [[x, 0.0], [x + 2.0, 0.0]]
            })
            .collect();
        let p = AtomicUsize::new(0);
        let counted = dedup(&segs, 1e-9, Count::to(&p));
        assert_eq!(p.load(Ordering::Relaxed), 3000);
        assert_eq!(counted, dedup(&segs, 1e-9, Count::NONE));
    }

    fn total(pieces: &[(usize, [Pt2; 2])]) -> f64 {
        pieces.iter().map(|(_, [a, b])| dist(*a, *b)).sum()
    }

    #[test]
    fn exact_and_reversed_duplicates_are_dropped() {
        let s = [
            [[0., 0.], [1., 0.]],
            [[1., 0.], [0., 0.]],
            [[0., 0.], [1., 0.]],
            [[0., 1.], [1., 1.]],
        ];
        let (k, st) = dedup(&s, 1e-9, Count::NONE);
        assert_eq!(k, vec![(0, s[0]), (3, s[3])]);
        assert_eq!((st.dropped, st.trimmed), (2, 0));
    }

    #[test]
    fn overlapping_collinear_pieces_keep_the_uncovered_parts() {
        // [0, 4] kept; [2, 6] keeps [4, 6]; [-1, 7] keeps [-1, 0] and [6, 7]; an inner piece
        // [1, 3] on a parallel line 1e-3 away is a different line.
        let s = [
            [[0., 0.], [4., 0.]],
            [[2., 0.], [6., 0.]],
            [[7., 0.], [-1., 0.]],
            [[1., 1e-3], [3., 1e-3]],
        ];
        let (k, _) = dedup(&s, 1e-9, Count::NONE);
        assert_eq!(
            k,
            vec![
                (0, s[0]),
                (1, [[4., 0.], [6., 0.]]),
                (2, [[7., 0.], [6., 0.]]),
                (2, [[0., 0.], [-1., 0.]]),
                (3, s[3]),
            ]
        );
    }

    #[test]
    fn rounding_sized_offsets_still_count_as_one_line() {
        // A diagonal and a piece of it whose ends were rounded off the line.
        let a = [0.1, 0.2];
        let b = [7.3, 5.9];
        let at = |t: f64| {
            [
                a[0] + t * (b[0] - a[0]) + 1e-15,
                a[1] + t * (b[1] - a[1]) - 1e-15,
            ]
        };
        let s = [[a, b], [at(0.25), at(0.75)]];
        let (k, st) = dedup(&s, 1e-9, Count::NONE);
        assert_eq!(k.len(), 1);
        assert_eq!(st.dropped, 1);
    }

    #[test]
    fn random_collinear_pieces_cover_their_union_once() {
        // Pieces of three lines: the kept length equals the length of each line's union of
        // intervals, computed independently in one dimension; kept pieces do not overlap.
        let mut rng = crate::geom::rng::XorShift::new(0x9E3779B97F4A7C15);
        let mut rnd = || rng.unit();
        let lines = [
            ([0.0, 0.0], [1.0, 0.5]),
            ([3.0, 1.0], [3.0, 4.0]),
            ([-2.0, 5.0], [6.0, 5.0]),
        ];
        let mut segs = Vec::new();
        let mut ivs: Vec<Vec<[f64; 2]>> = vec![Vec::new(); 3];
        for k in 0..300 {
            let l = k % 3;
            let (p, q) = lines[l];
            let (mut t0, mut t1) = (rnd() * 10.0, rnd() * 10.0);
            if rnd() < 0.3 {
                t1 = t0; // a repeat of the previous piece on this line, when any
                if let Some(&[u, v]) = ivs[l].last() {
                    (t0, t1) = (u, v);
                }
            }
            let at = |t: f64| [p[0] + t * (q[0] - p[0]), p[1] + t * (q[1] - p[1])];
            if t0 != t1 {
                segs.push([at(t0), at(t1)]);
                ivs[l].push([t0.min(t1), t0.max(t1)]);
            }
        }
        let (kept, _) = dedup(&segs, 1e-9, Count::NONE);
        let mut want = 0.0;
        for (l, iv) in ivs.iter_mut().enumerate() {
            iv.sort_by(|a, b| a[0].total_cmp(&b[0]));
            let unit = dist(lines[l].0, lines[l].1);
            let (mut lo, mut hi) = (f64::NAN, f64::NAN);
            for &[a, b] in iv.iter() {
                if hi.is_nan() || a > hi {
                    if hi > lo {
                        want += (hi - lo) * unit;
                    }
                    (lo, hi) = (a, b);
                } else {
                    hi = hi.max(b);
                }
            }
            if hi > lo {
                want += (hi - lo) * unit;
            }
        }
        let got = total(&kept);
        assert!((got - want).abs() < 1e-9 * want, "{got} != {want}");
        // Nothing kept overlaps anything else kept.
        let (again, st) = dedup(
            &kept.iter().map(|k| k.1).collect::<Vec<_>>(),
            1e-9,
            Count::NONE,
        );
        assert_eq!((again.len(), st.dropped, st.trimmed), (kept.len(), 0, 0));
    }

    /// A round's scale (of the coordinates) and tolerance: four scales, three tolerances.
    fn scale_and_eps(round: usize) -> (f64, f64) {
        let scale: f64 = [1e-2, 1.0, 300.0, 1e5][round % 4];
        (scale, [1e-4, 1e-9, 1e-3][round % 3] * scale.min(1.0))
    }

    /// Random segments near a few lines (pieces, near-repeats, crumbs across them) and
    /// scattered ones, at several scales, some outside the bounds the index was made for.
    fn tangle(
        rng: &mut crate::geom::rng::XorShift,
        n: usize,
        scale: f64,
        eps: f64,
    ) -> Vec<[Pt2; 2]> {
        let lines: Vec<(Pt2, Pt2)> = (0..4)
            .map(|_| {
                let p = [rng.range(-scale, scale), rng.range(-scale, scale)];
                let q = [rng.range(-scale, scale), rng.range(-scale, scale)];
                (p, q)
            })
            .collect();
        (0..n)
            .map(|k| {
                let (p, q) = lines[rng.below(lines.len())];
                let at = |t: f64, j: f64| {
                    let (dx, dy) = (q[0] - p[0], q[1] - p[1]);
                    let l = (dx * dx + dy * dy).sqrt();
                    [p[0] + t * dx - j * dy / l, p[1] + t * dy + j * dx / l]
                };
                let jitter = |rng: &mut crate::geom::rng::XorShift| rng.range(-1.5, 1.5) * eps;
                match k % 5 {
                    // Pieces along a line, ends off it by up to 1.5 eps, some beyond the bounds.
                    0 | 1 => {
                        let (t, u) = (rng.range(-0.5, 1.5), rng.range(-0.5, 1.5));
                        [at(t, jitter(rng)), at(u, jitter(rng))]
                    }
                    // A crumb of a few eps at any angle, on or near a line.
                    2 => {
                        let c = at(rng.range(-0.2, 1.2), jitter(rng));
                        let (r, w) = (rng.range(0.1, 8.0) * eps, rng.range(0.0, 6.3));
                        [c, [c[0] + r * w.cos(), c[1] + r * w.sin()]]
                    }
                    // A short piece of a line, slightly turned.
                    3 => {
                        let t = rng.range(0.0, 1.0);
                        [at(t, 0.0), at(t + rng.range(-0.01, 0.01), jitter(rng))]
                    }
                    _ => {
                        let p = [rng.range(-scale, scale), rng.range(-scale, scale)];
                        [p, [p[0] + rng.range(-0.1, 0.1) * scale, p[1]]]
                    }
                }
            })
            .collect()
    }

    /// The grid meets every segment that covers a query: its covers are those of all the
    /// segments inserted, tested one by one.
    #[test]
    fn the_index_finds_every_cover_a_brute_force_finds() {
        let mut rng = crate::geom::rng::XorShift::new(0xD0D0);
        let mut found = 0;
        for round in 0..24 {
            let (scale, eps) = scale_and_eps(round);
            let mut segs = tangle(&mut rng, 600, scale, eps);
            // Bounds of a part of the segments only: the rest lie partly outside.
            let mut index = SegmentIndex::new(&segs[..100], eps);
            // Pieces along the cells' sides, within eps on either side of them (where a grid
            // that lists a segment only in the cells it passes through misses its cover).
            let f = index.grid.frame;
            for k in 0..600 {
                let side = f.origin[k % 2] + rng.below(f.nx.max(f.ny) + 1) as f64 * f.cell;
                let off = |rng: &mut crate::geom::rng::XorShift| side + rng.range(-0.9, 0.9) * eps;
                let along = |rng: &mut crate::geom::rng::XorShift| {
                    f.origin[1 - k % 2] + rng.range(-1.0, 40.0) * f.cell
                };
                let (u, v) = (along(&mut rng), along(&mut rng));
                let (p, q) = (off(&mut rng), off(&mut rng));
                let piece = if k % 2 == 0 {
                    [[p, u], [q, v]]
                } else {
                    [[u, p], [v, q]]
                };
                segs.insert(2 * k % segs.len(), piece);
            }
            let (old, new) = segs.split_at(segs.len() / 2);
            for &s in old {
                index.insert(s);
            }
            let key = |c: &Cover| (c.by, c.t0, c.p0, c.t1, c.p1);
            let mut got = Vec::new();
            for &[a, b] in new {
                index.covers(a, b, &mut got);
                got.sort_by_key(|p| p.by);
                let len = dist(a, b);
                let want: Vec<Cover> = old
                    .iter()
                    .enumerate()
                    .filter_map(|(k, &[c, d])| {
                        overlap(a, b, len, c, d, eps).map(|cov| Cover { by: k, ..cov })
                    })
                    .collect();
                assert_eq!(
                    got.iter().map(key).collect::<Vec<_>>(),
                    want.iter().map(key).collect::<Vec<_>>(),
                    "{a:?} {b:?} eps {eps}"
                );
                found += want.len();
            }
        }
        assert!(found > 2000, "{found} covers");
    }

    /// Distance between two segments (0 where they cross).
    fn segment_distance(a: Pt2, b: Pt2, c: Pt2, d: Pt2) -> f64 {
        let side =
            |p: Pt2, q: Pt2, r: Pt2| (q[0] - p[0]) * (r[1] - p[1]) - (q[1] - p[1]) * (r[0] - p[0]);
        let crosses = side(a, b, c) * side(a, b, d) < 0.0 && side(c, d, a) * side(c, d, b) < 0.0;
        let to = |p: Pt2, u: Pt2, v: Pt2| {
            let (dx, dy) = (v[0] - u[0], v[1] - u[1]);
            let t =
                (((p[0] - u[0]) * dx + (p[1] - u[1]) * dy) / (dx * dx + dy * dy)).clamp(0.0, 1.0);
            dist(p, [u[0] + t * dx, u[1] + t * dy])
        };
        if crosses {
            0.0
        } else {
            to(a, c, d)
                .min(to(b, c, d))
                .min(to(c, a, b))
                .min(to(d, a, b))
        }
    }

    /// What the grid relies on: two segments one covers part of come within eps of each
    /// other, at any angle (crumbs a few eps long across a line included).
    #[test]
    fn a_cover_comes_within_eps() {
        let mut rng = crate::geom::rng::XorShift::new(0xC0DE);
        let (mut near, mut steep) = (0, 0);
        for round in 0..40 {
            let (scale, eps) = scale_and_eps(round);
            let segs = tangle(&mut rng, 400, scale, eps);
            for (i, &[a, b]) in segs.iter().enumerate() {
                for &[c, d] in &segs[..i] {
                    let len = dist(a, b);
                    if len == 0.0 || overlap(a, b, len, c, d, eps).is_none() {
                        continue;
                    }
                    let gap = segment_distance(a, b, c, d);
                    assert!(
                        gap <= eps * (1.0 + 1e-9),
                        "{a:?} {b:?} {c:?} {d:?} {eps}: {gap}"
                    );
                    near += 1;
                    let dot = (b[0] - a[0]) * (d[0] - c[0]) + (b[1] - a[1]) * (d[1] - c[1]);
                    if dot.abs() < 0.9 * len * dist(c, d) {
                        steep += 1;
                    }
                }
            }
        }
        assert!(near > 10_000 && steep > 100, "{near} {steep}");
    }

    #[test]
    fn a_masked_query_answers_as_an_index_of_what_it_keeps() {
        // Pieces along a few lines (so that queries find covers), every third left out.
        let mut rng = crate::geom::rng::XorShift::new(35);
        let piece = |rng: &mut crate::geom::rng::XorShift| {
            let line = rng.below(4) as f64;
            let (t, u) = (rng.range(0.0, 100.0), rng.range(0.0, 100.0));
            let at = |t: f64| [t, 0.5 * t + 7.0 * line];
            [at(t), at(u)]
        };
        let segs: Vec<[Pt2; 2]> = (0..600).map(|_| piece(&mut rng)).collect();
        let keep = |k: usize| !k.is_multiple_of(3);
        let mut all = SegmentIndex::new(&segs, 1e-9);
        let mut only = SegmentIndex::new(&segs, 1e-9);
        for (k, &s) in segs.iter().enumerate() {
            all.insert(s);
            if keep(k) {
                only.insert(s);
            }
        }
        let (mut a, mut b) = (Vec::new(), Vec::new());
        let mut found = 0;
        for _ in 0..300 {
            let [p, q] = piece(&mut rng);
            all.covers_where(p, q, &mut a, keep);
            only.covers(p, q, &mut b);
            assert_eq!(all.overlaps_where(p, q, keep), !b.is_empty());
            let key = |c: &Cover| (c.t0, c.p0, c.t1, c.p1);
            assert_eq!(
                a.iter().map(key).collect::<Vec<_>>(),
                b.iter().map(key).collect::<Vec<_>>()
            );
            found += a.len();
        }
        assert!(found > 300, "{found} covers");
    }
}
