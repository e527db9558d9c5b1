//! The hidden pen's dashes as ink that a bridge between two dashes must keep off: the dash
//! segments bucketed by their first point in a hash grid of cells as long as the longest
//! segment, asked only for the few gaps a join tries to bridge.
//!
//! It answers as a [`super::dedup::SegmentIndex`] holding the same segments would (whether
//! any of them runs along a gap for more than `eps`), without listing each segment in every
//! small cell it crosses: the index of every line drawn has cells sized for all the
//! picture's segments, and a dash crossed many of them.

use crate::geom::key_hash::KeyMap;
use crate::geom::poly2::{dist, Pt2};

use super::dedup::overlap;

/// Dash segments by the cell of their first point.
pub(crate) struct Ink {
    /// The segments, cell by cell.
    segs: Vec<[Pt2; 2]>,
    /// Each occupied cell's range in `segs`.
    cells: KeyMap<(i64, i64), (usize, usize)>,
    /// The side of a cell: the longest segment (every point of a segment lies this near its
    /// first point), at least a µm.
    side: f64,
    /// The coincidence tolerance.
    eps: f64,
}

impl Ink {
    /// The ink of `dashes` (polylines), coincident within `eps`.
    pub(crate) fn new(dashes: &[Vec<Pt2>], eps: f64) -> Ink {
        let mut segs: Vec<[Pt2; 2]> = dashes
            .iter()
            .flat_map(|d| d.windows(2).map(|w| [w[0], w[1]]))
            .collect();
        let longest = segs.iter().map(|s| dist(s[0], s[1])).fold(0.0, f64::max);
        let side = if longest.is_finite() {
            longest.max(1e-3)
        } else {
            f64::MAX
        };
        let cell = |p: Pt2| Self::cell_of(p, side);
        segs.sort_unstable_by_key(|s| cell(s[0]));
        let mut cells: KeyMap<(i64, i64), (usize, usize)> = KeyMap::default();
        for (k, s) in segs.iter().enumerate() {
            cells.entry(cell(s[0])).or_insert((k, k)).1 = k + 1;
        }
        Ink {
            segs,
            cells,
            side,
            eps,
        }
    }

    fn cell_of(p: Pt2, side: f64) -> (i64, i64) {
        ((p[0] / side).floor() as i64, (p[1] / side).floor() as i64)
    }

    /// True when a dash segment runs along a → b for more than `eps`.
    pub(crate) fn overlaps(&self, a: Pt2, b: Pt2) -> bool {
        let len = dist(a, b);
        if len == 0.0 {
            return false;
        }
        // A segment along a → b has a point within a few eps of it, so its first point lies
        // within a segment's length and that of a → b's box.
        let reach = self.side + 10.0 * self.eps + 1e-6;
        let (lo, hi) = (
            Self::cell_of([a[0].min(b[0]) - reach, a[1].min(b[1]) - reach], self.side),
            Self::cell_of([a[0].max(b[0]) + reach, a[1].max(b[1]) + reach], self.side),
        );
        (lo.1..=hi.1).any(|y| {
            (lo.0..=hi.0).any(|x| {
                self.cells.get(&(x, y)).is_some_and(|&(from, to)| {
                    self.segs[from..to]
                        .iter()
                        .any(|s| overlap(a, b, len, s[0], s[1], self.eps).is_some())
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
