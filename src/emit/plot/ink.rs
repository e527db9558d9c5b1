//! The hidden pen's dashes as ink that a bridge between two dashes must keep off: the dash
//! segments in a hash grid of cells about a segment long, each listed in the cells its box
//! meets, asked only for the few gaps a join tries to bridge.
//!
//! It answers as a [`super::dedup::SegmentIndex`] holding the same segments would (whether
//! any of them runs along a gap for more than `eps`), without listing each segment in the
//! many small cells of the index of every line drawn (sized for all the picture's segments).

use rayon::prelude::*;

use crate::geom::key_hash::KeyMap;
use crate::geom::poly2::{dist, Pt2};

use super::dedup::overlap;

/// How much a segment's box is widened, in multiples of `eps`: a segment that runs along a
/// gap for more than `eps` comes within `eps` of it ([`overlap`] shows it), so boxes
/// widened by this much meet.
const MARGIN_EPS: f64 = 100.0;

/// The most cells along an axis of a segment's box: cells are at least an eighth of the
/// longest segment.
const CELLS_PER_SEGMENT: f64 = 8.0;

/// Dash segments by the grid cells their widened boxes meet.
pub(crate) struct Ink {
    segs: Vec<[Pt2; 2]>,
    /// Segment numbers, cell by cell.
    in_cells: Vec<u32>,
    /// Each occupied cell's range in `in_cells`.
    cells: KeyMap<(i64, i64), (usize, usize)>,
    /// The side of a cell.
    side: f64,
    /// How much boxes are widened.
    margin: f64,
    /// The coincidence tolerance.
    eps: f64,
}

impl Ink {
    /// The ink of `dashes` (polylines), coincident within `eps`.
    pub(crate) fn new(dashes: &[Vec<Pt2>], eps: f64) -> Ink {
        let segs: Vec<[Pt2; 2]> = dashes
            .iter()
            .flat_map(|d| d.windows(2).map(|w| [w[0], w[1]]))
            .collect();
        let lengths = || segs.iter().map(|s| dist(s[0], s[1]));
        let longest = lengths().fold(0.0, f64::max);
        let mean = lengths().sum::<f64>() / segs.len().max(1) as f64;
        let side = mean.max(longest / CELLS_PER_SEGMENT).max(1e-3);
        let side = if side.is_finite() { side } else { f64::MAX };
        let margin = MARGIN_EPS * eps;
        let mut listed: Vec<((i64, i64), u32)> = Vec::with_capacity(2 * segs.len());
        for (k, s) in segs.iter().enumerate() {
            let (lo, hi) = Self::box_cells(s[0], s[1], margin, side);
            for y in lo.1..=hi.1 {
                for x in lo.0..=hi.0 {
                    listed.push(((x, y), k as u32));
                }
            }
        }
        // The pairs are distinct, so the order is the same on any number of threads.
        listed.par_sort_unstable();
        let mut cells: KeyMap<(i64, i64), (usize, usize)> = KeyMap::default();
        for (k, &(c, _)) in listed.iter().enumerate() {
            cells.entry(c).or_insert((k, k)).1 = k + 1;
        }
        Ink {
            segs,
            in_cells: listed.into_iter().map(|(_, k)| k).collect(),
            cells,
            side,
            margin,
            eps,
        }
    }

    /// The least and greatest cells of a → b's box widened by `margin`.
    fn box_cells(a: Pt2, b: Pt2, margin: f64, side: f64) -> ((i64, i64), (i64, i64)) {
        let cell = |v: f64| (v / side).floor() as i64;
        (
            (cell(a[0].min(b[0]) - margin), cell(a[1].min(b[1]) - margin)),
            (cell(a[0].max(b[0]) + margin), cell(a[1].max(b[1]) + margin)),
        )
    }

    /// True when a dash segment runs along a → b for more than `eps`.
    pub(crate) fn overlaps(&self, a: Pt2, b: Pt2) -> bool {
        let len = dist(a, b);
        if len == 0.0 {
            return false;
        }
        let m = 2.0 * self.margin;
        let near = |s: &[Pt2; 2]| {
            s[0][0].min(s[1][0]) <= a[0].max(b[0]) + m
                && s[0][0].max(s[1][0]) >= a[0].min(b[0]) - m
                && s[0][1].min(s[1][1]) <= a[1].max(b[1]) + m
                && s[0][1].max(s[1][1]) >= a[1].min(b[1]) - m
        };
        let (lo, hi) = Self::box_cells(a, b, self.margin, self.side);
        (lo.1..=hi.1).any(|y| {
            (lo.0..=hi.0).any(|x| {
                self.cells.get(&(x, y)).is_some_and(|&(from, to)| {
                    self.in_cells[from..to].iter().any(|&k| {
                        let s = &self.segs[k as usize];
                        near(s) && overlap(a, b, len, s[0], s[1], self.eps).is_some()
                    })
                })
            })
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::emit::plot::dedup::SegmentIndex;
    use crate::geom::rng::XorShift;

    #[test]
    fn ink_answers_as_a_segment_index_of_the_dashes() {
        // Dashes along a few lines (one turning a corner), asked about gaps along them, beside
        // them and across them: the same answers as an index holding every dash segment.
        let mut dashes: Vec<Vec<Pt2>> = Vec::new();
        for k in 0..40 {
            let x = 1.5 * f64::from(k);
            dashes.push(vec![[x, 0.0], [x + 1.0, 0.0]]);
            dashes.push(vec![[x, x * 0.5], [x + 0.6, x * 0.5 + 0.3]]);
        }
        dashes.push(vec![[0.0, 5.0], [0.5, 5.0], [0.5, 5.5]]);
        let eps = 1e-4;
        let ink = Ink::new(&dashes, eps);
        let extent: Vec<[Pt2; 2]> = dashes
            .iter()
            .flat_map(|d| d.windows(2).map(|w| [w[0], w[1]]))
            .collect();
        let mut index = SegmentIndex::new(&extent, eps);
        extent.iter().for_each(|&s| index.insert(s));
        let mut rng = XorShift::new(7);
        let mut unit = || rng.below(1_000_000) as f64 / 1e6;
        let mut asked = vec![
            ([0.2, 0.0], [0.25, 0.0]),
            ([1.0, 0.0], [1.5, 0.0]),
            ([0.9, 0.0], [1.6, 0.0]),
            ([0.5, 5.0], [0.5, 5.2]),
            ([0.5, 5.2], [0.5, 5.6]),
            ([0.2, 0.00005], [0.3, 0.00005]),
            ([0.2, 0.001], [0.3, 0.001]),
        ];
        for _ in 0..200 {
            let x = 60.0 * unit();
            let (dx, dy) = (0.2 * unit() - 0.1, 0.2 * unit() - 0.1);
            let y = if unit() < 0.5 { 0.0 } else { x * 0.5 };
            asked.push(([x, y], [x + dx.abs(), y + if y == 0.0 { 0.0 } else { dy }]));
        }
        let mut hits = 0;
        for (a, b) in asked {
            let want = index.overlaps(a, b);
            assert_eq!(ink.overlaps(a, b), want, "{a:?} -> {b:?}");
            hits += usize::from(want);
        }
        assert!(hits > 20, "{hits}");
    }
}
