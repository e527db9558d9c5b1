//! The cell geometry of uniform grids of square cells in the plane: how many cells, how big,
//! which cell a point falls in, and points bucketed by cell. The callers keep their own
//! search orders (the stroke order of the plot output depends on them).

use super::poly2::Pt2;
use super::Rect;

/// Square cells of side `cell` from `origin`, `nx` by `ny` of them (row-major index).
#[derive(Debug, Clone, Copy)]
pub(crate) struct Cells {
    /// The corner of cell (0, 0).
    pub origin: Pt2,
    /// The side of a cell.
    pub cell: f64,
    /// Cells along x.
    pub nx: usize,
    /// Cells along y.
    pub ny: usize,
}

impl Cells {
    /// `n` by `n` cells over `b`: the side is `b`'s longer side over `n` (1 where that side is
    /// 0 or not finite), from `b`'s least corner.
    pub(crate) fn square(b: &Rect, n: usize) -> Cells {
        Cells {
            origin: [b.xmin, b.ymin],
            cell: side(b, n),
            nx: n,
            ny: n,
        }
    }

    /// Cells of [`Cells::square`]'s side over `b`, only as many along each axis as cover `b`
    /// (one where `b` is empty, from the origin).
    pub(crate) fn fitted(b: &Rect, n: usize) -> Cells {
        let cell = side(b, n);
        if b.is_empty() {
            return Cells {
                origin: [0.0, 0.0],
                cell,
                nx: 1,
                ny: 1,
            };
        }
        let count = |w: f64| ((w / cell).ceil() as usize).clamp(1, n);
        Cells {
            origin: [b.xmin, b.ymin],
            cell,
            nx: count(b.width()),
            ny: count(b.height()),
        }
    }

    /// About `items` square cells over `b`'s area, never coarser than
    /// [`Cells::fitted`]`(b, per_side(items, max_side))`: a long, thin `b` gets many cells
    /// along its length (a comb of 100,000 teeth is not one row of a few hundred crowded
    /// cells), at most `max_long` along either axis.
    pub(crate) fn by_area(b: &Rect, items: f64, max_side: usize, max_long: usize) -> Cells {
        let square = Cells::fitted(b, per_side(items, max_side));
        let (w, h) = (b.width(), b.height());
        let area = w * h;
        if b.is_empty() || !(area > 0.0 && area.is_finite()) || items < 1.0 {
            return square;
        }
        let cell = (area / items)
            .sqrt()
            .max(b.longer_side() / max_long as f64)
            .min(square.cell);
        let count = |v: f64| ((v / cell).ceil() as usize).clamp(1, max_long);
        Cells {
            origin: square.origin,
            cell,
            nx: count(w),
            ny: count(h),
        }
    }

    /// Number of cells.
    pub(crate) fn len(&self) -> usize {
        self.nx * self.ny
    }

    /// The cell column and row of `p`, clamped to the grid.
    #[inline]
    pub(crate) fn coords(&self, p: Pt2) -> (usize, usize) {
        (self.column(p[0]), self.row(p[1]))
    }

    /// The column of x, clamped to the grid.
    #[inline]
    pub(crate) fn column(&self, x: f64) -> usize {
        self.along(x, self.origin[0], self.nx)
    }

    /// The row of y, clamped to the grid.
    #[inline]
    pub(crate) fn row(&self, y: f64) -> usize {
        self.along(y, self.origin[1], self.ny)
    }

    /// The cell along one axis (origin `o`, `n` cells) of coordinate `v`, clamped.
    #[inline]
    fn along(&self, v: f64, o: f64, n: usize) -> usize {
        (((v - o) / self.cell).floor().max(0.0) as usize).min(n - 1)
    }

    /// The row-major index of `p`'s cell.
    #[inline]
    pub(crate) fn index(&self, p: Pt2) -> usize {
        let (x, y) = self.coords(p);
        y * self.nx + x
    }

    /// The points' indices cell by cell (a counting sort, in index order within a cell), and
    /// where each cell's run starts: cell c holds `slots[start[c]..start[c + 1]]`.
    pub(crate) fn buckets(&self, pts: &[Pt2]) -> (Vec<u32>, Vec<u32>) {
        self.lists(pts.len(), |s| std::iter::once(self.index(pts[s])))
    }

    /// Items `0..items` listed in every cell `cells_of(i)` names (a counting sort: each cell's
    /// items ascending), and where each cell's run starts: cell c holds
    /// `listed[start[c]..start[c + 1]]`. `cells_of` is asked twice an item, to count and to
    /// place.
    pub(crate) fn lists<I: Iterator<Item = usize>>(
        &self,
        items: usize,
        cells_of: impl Fn(usize) -> I,
    ) -> (Vec<u32>, Vec<u32>) {
        let mut start = vec![0u32; self.len() + 1];
        for i in 0..items {
            cells_of(i).for_each(|c| start[c + 1] += 1);
        }
        for c in 0..self.len() {
            start[c + 1] += start[c];
        }
        let mut fill = start.clone();
        let mut listed = vec![0u32; start[self.len()] as usize];
        for i in 0..items {
            for c in cells_of(i) {
                listed[fill[c] as usize] = i as u32;
                fill[c] += 1;
            }
        }
        (start, listed)
    }
}

/// Cells per side for about `items` entries, one a cell: √items rounded up, from 1 to `max`.
pub(crate) fn per_side(items: f64, max: usize) -> usize {
    (items.sqrt().ceil() as usize).clamp(1, max)
}

/// The side of `n` cells along `b`'s longer side (1 where that side is 0 or not finite).
fn side(b: &Rect, n: usize) -> f64 {
    let size = b.longer_side();
    if size > 0.0 && size.is_finite() {
        size / n as f64
    } else {
        1.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Each cell's run holds exactly the points that fall in it, in index order.
    #[test]
    fn buckets_hold_each_cells_points_in_order() {
        let pts: Vec<Pt2> = (0..200)
            .map(|i| [(i * 37 % 101) as f64 * 0.1, (i * 53 % 97) as f64 * 0.1])
            .collect();
        let grid = Cells::square(&Rect::of_points(pts.iter()), 7);
        let (start, slots) = grid.buckets(&pts);
        assert_eq!(start.len(), grid.len() + 1);
        for c in 0..grid.len() {
            let run = &slots[start[c] as usize..start[c + 1] as usize];
            let want: Vec<u32> = (0..pts.len() as u32)
                .filter(|&s| grid.index(pts[s as usize]) == c)
                .collect();
            assert_eq!(run, want.as_slice(), "cell {c}");
        }
    }

    #[test]
    fn points_fall_in_their_cells_clamped_to_the_grid() {
        let b = Rect::of_points([[0.0, 0.0], [4.0, 1.0]].iter());
        let sq = Cells::square(&b, 4);
        assert_eq!((sq.cell, sq.len()), (1.0, 16));
        assert_eq!(sq.coords([2.5, 0.5]), (2, 0));
        assert_eq!(sq.coords([4.0, 1.0]), (3, 1));
        assert_eq!(sq.coords([-3.0, 9.0]), (0, 3));
        let fit = Cells::fitted(&b, 4);
        assert_eq!((fit.nx, fit.ny), (4, 1));
        assert_eq!(fit.index([3.5, 1.0]), 3);
        assert_eq!(per_side(10.0, 1024), 4);
        assert_eq!(per_side(0.0, 1024), 1);
    }

    #[test]
    fn long_thin_bounds_get_cells_by_area() {
        let comb = Rect::of_points([[0.0, 0.0], [25_000.0, 10.0]].iter());
        let g = Cells::by_area(&comb, 100_000.0, 1024, 1 << 16);
        assert!((g.cell - 250_000f64.sqrt() / 100_000f64.sqrt()).abs() < 1e-12);
        assert_eq!((g.nx, g.ny), (15_812, 7));
        // A square gets the square grid; a segment (no area) too; the long cap holds.
        let sq = Rect::of_points([[0.0, 0.0], [4.0, 4.0]].iter());
        let a = Cells::by_area(&sq, 16.0, 1024, 1 << 16);
        assert_eq!((a.cell, a.nx, a.ny), (1.0, 4, 4));
        let line = Rect::of_points([[0.0, 0.0], [4.0, 0.0]].iter());
        assert_eq!(Cells::by_area(&line, 16.0, 1024, 1 << 16).nx, 4);
        let capped = Cells::by_area(&comb, 1e9, 1024, 1000);
        assert_eq!(capped.nx, 1000);
    }
}
