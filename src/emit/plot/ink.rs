//! The hidden pen's dashes as ink that a bridge between two dashes must keep off: the dash
//! segments in a uniform grid of about a segment a cell, each listed in the cells its box
//! meets, asked only for the few gaps a join tries to bridge.
//!
//! It answers as a [`super::dedup::SegmentIndex`] holding the same segments would (whether
//! any of them runs along a gap for more than `eps`), without listing each segment in the
//! many small cells of the index of every line drawn (sized for all the picture's segments).
//! The grid is filled by counting ([`Cells::lists`]): building it must be cheap, as most of
//! the ink is never asked about.

use crate::geom::grid::Cells;
use crate::geom::poly2::{dist, Pt2};
use crate::geom::Rect;

use super::dedup::overlap;

/// How much a segment's box is widened, in multiples of `eps`: a segment that runs along a
/// gap for more than `eps` comes within `eps` of it ([`overlap`] shows it), so boxes
/// widened by this much meet.
const MARGIN_EPS: f64 = 100.0;

/// The most cells along either axis (a long, thin drawing gets them along its length).
const MAX_LONG: usize = 1 << 16;

/// Dash segments by the grid cells their widened boxes meet.
pub(crate) struct Ink {
    segs: Vec<[Pt2; 2]>,
    grid: Cells,
    /// Cell c's segment numbers are `in_cells[start[c]..start[c + 1]]`, ascending.
    start: Vec<u32>,
    in_cells: Vec<u32>,
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
        let margin = MARGIN_EPS * eps;
        let b = Rect::of_points(segs.iter().flatten()).padded(margin);
        let grid = Cells::by_area(&b, segs.len() as f64, 1024, MAX_LONG);
        let (start, in_cells) = grid.lists(segs.len(), |k| {
            Self::cells(&grid, segs[k][0], segs[k][1], margin)
        });
        Ink {
            segs,
            grid,
            start,
            in_cells,
            margin,
            eps,
        }
    }

    /// The cells (row-major) that a → b's box widened by `margin` meets, clamped to the
    /// grid (a box beyond it meets no segment's but through the border cells, which
    /// clamping keeps).
    fn cells(grid: &Cells, a: Pt2, b: Pt2, margin: f64) -> impl Iterator<Item = usize> {
        let (x0, x1) = (
            grid.column(a[0].min(b[0]) - margin),
            grid.column(a[0].max(b[0]) + margin),
        );
        let (y0, y1) = (
            grid.row(a[1].min(b[1]) - margin),
            grid.row(a[1].max(b[1]) + margin),
        );
        let nx = grid.nx;
        (y0..=y1).flat_map(move |y| (x0..=x1).map(move |x| y * nx + x))
    }

    /// True when a dash segment runs along a → b for more than `eps`.
    pub(crate) fn overlaps(&self, a: Pt2, b: Pt2) -> bool {
        let len = dist(a, b);
        if len == 0.0 || self.segs.is_empty() {
            return false;
        }
        let m = 2.0 * self.margin;
        let near = |s: &[Pt2; 2]| {
            s[0][0].min(s[1][0]) <= a[0].max(b[0]) + m
                && s[0][0].max(s[1][0]) >= a[0].min(b[0]) - m
                && s[0][1].min(s[1][1]) <= a[1].max(b[1]) + m
                && s[0][1].max(s[1][1]) >= a[1].min(b[1]) - m
        };
        Self::cells(&self.grid, a, b, self.margin).any(|c| {
            let listed = self.start[c] as usize..self.start[c + 1] as usize;
            self.in_cells[listed].iter().any(|&k| {
                let s = &self.segs[k as usize];
                near(s) && overlap(a, b, len, s[0], s[1], self.eps).is_some()
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
