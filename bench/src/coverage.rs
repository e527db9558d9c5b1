//! Exact area coverage: the area of a polygon (with holes) inside every pixel of a window.
//!
//! The signed-area accumulation of font rasterisers (R. Levien's font-rs), in f64: every edge
//! adds, row by row, the exact trapezoid areas it sweeps to the cells it crosses, and a prefix
//! sum along each row turns those into each cell's covered area. The result is exact up to
//! f64 rounding (a few ulps per cell touched), with no sampling.

/// The covered area of every pixel in a window of whole pixels (pixel units: a pixel is 1×1).
#[derive(Debug, Clone)]
pub struct Coverage {
    /// Column of the window's first cell.
    pub i0: i64,
    /// Row of the window's first cell.
    pub j0: i64,
    /// Cells per row (one more than the region spans, for the accumulation's spill).
    pub w: usize,
    /// Rows.
    pub rows: usize,
    /// Covered area per cell, row after row from the bottom.
    pub area: Vec<f64>,
}

impl Coverage {
    /// The covered area of every pixel under the rings (pixel units; outer rings
    /// counter-clockwise, holes clockwise, as in kepler's multipolygons).
    pub fn of<'a>(rings: impl IntoIterator<Item = &'a [[f64; 2]]> + Clone) -> Coverage {
        let b = kepler_hsr::plot::Rect::of_points(rings.clone().into_iter().flatten());
        if b.is_empty() {
            return Coverage {
                i0: 0,
                j0: 0,
                w: 0,
                rows: 0,
                area: Vec::new(),
            };
        }
        let (i0, j0) = (b.xmin.floor(), b.ymin.floor());
        let w = (b.xmax.ceil() - i0) as usize + 2;
        let rows = ((b.ymax.ceil() - j0) as usize).max(1);
        let mut c = Coverage {
            i0: i0 as i64,
            j0: j0 as i64,
            w,
            rows,
            area: vec![0.0; w * rows],
        };
        for r in rings {
            let n = r.len();
            for k in 0..n {
                let (p, q) = (r[k], r[(k + 1) % n]);
                c.line([p[0] - i0, p[1] - j0], [q[0] - i0, q[1] - j0]);
            }
        }
        c.accumulate();
        c
    }

    /// The covered area of pixel (i, j) (0 outside the window).
    #[cfg(test)]
    pub fn at(&self, i: i64, j: i64) -> f64 {
        let (x, y) = (i - self.i0, j - self.j0);
        if x < 0 || y < 0 || x as usize >= self.w || y as usize >= self.rows {
            return 0.0;
        }
        self.area[y as usize * self.w + x as usize]
    }

    /// Adds the signed areas one edge (window-local coordinates, all ≥ 0) sweeps in each row.
    fn line(&mut self, p0: [f64; 2], p1: [f64; 2]) {
        if p0[1] == p1[1] {
            return;
        }
        // Counter-clockwise rings (y up) must come out positive: an edge going up (+v) on
        // the right of the region adds area to the left of it, hence the sign here.
        let (dir, a, b) = if p0[1] < p1[1] {
            (-1.0, p0, p1)
        } else {
            (1.0, p1, p0)
        };
        let dxdy = (b[0] - a[0]) / (b[1] - a[1]);
        let mut x = a[0];
        let end = (b[1].ceil() as usize).min(self.rows);
        for y in (a[1].floor() as usize)..end {
            let dy = ((y + 1) as f64).min(b[1]) - (y as f64).max(a[1]);
            let xnext = x + dxdy * dy;
            self.row(y * self.w, x, xnext, dy * dir);
            x = xnext;
        }
    }

    /// The contributions of an edge piece from x to xnext within one row (starting at cell
    /// `row`), carrying signed height `d`.
    fn row(&mut self, row: usize, x: f64, xnext: f64, d: f64) {
        let a = &mut self.area;
        let (x0, x1) = if x < xnext { (x, xnext) } else { (xnext, x) };
        let x0floor = x0.floor();
        let x0i = x0floor as usize;
        let x1ceil = x1.ceil();
        let x1i = x1ceil as usize;
        if x1i <= x0i + 1 {
            let xmf = 0.5 * (x + xnext) - x0floor;
            a[row + x0i] += d - d * xmf;
            a[row + x0i + 1] += d * xmf;
            return;
        }
        let s = 1.0 / (x1 - x0);
        let x0f = x0 - x0floor;
        let a0 = 0.5 * s * (1.0 - x0f) * (1.0 - x0f);
        let x1f = x1 - x1ceil + 1.0;
        let am = 0.5 * s * x1f * x1f;
        a[row + x0i] += d * a0;
        if x1i == x0i + 2 {
            a[row + x0i + 1] += d * (1.0 - a0 - am);
        } else {
            let a1 = s * (1.5 - x0f);
            a[row + x0i + 1] += d * (a1 - a0);
            for xi in x0i + 2..x1i - 1 {
                a[row + xi] += d * s;
            }
            let a2 = a1 + (x1i - x0i - 3) as f64 * s;
            a[row + x1i - 1] += d * (1.0 - a2 - am);
        }
        a[row + x1i] += d * am;
    }

    /// Prefix sums along each row: accumulated contributions become covered areas.
    fn accumulate(&mut self) {
        for r in self.area.chunks_exact_mut(self.w) {
            let mut s = 0.0;
            for v in r {
                s += *v;
                *v = s;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn total(c: &Coverage) -> f64 {
        c.area.iter().sum()
    }

    #[test]
    fn rectangle_straddling_pixels() {
        // [0.5, 2.5] × [0.5, 1.5]: quarter, half, quarter in each of two rows.
        let r = [[0.5, 0.5], [2.5, 0.5], [2.5, 1.5], [0.5, 1.5]];
        let c = Coverage::of([&r[..]]);
        for (i, j, a) in [
            (0, 0, 0.25),
            (1, 0, 0.5),
            (2, 0, 0.25),
            (0, 1, 0.25),
            (1, 1, 0.5),
            (2, 1, 0.25),
            (3, 0, 0.0),
        ] {
            assert_eq!(c.at(i, j), a, "pixel ({i}, {j})");
        }
        assert_eq!(total(&c), 2.0);
    }

    #[test]
    fn triangle_by_hand() {
        // (0,0), (2,0), (0,2): pixel (0,0) is full, (1,0) and (0,1) half, (1,1) empty.
        let t = [[0., 0.], [2., 0.], [0., 2.]];
        let c = Coverage::of([&t[..]]);
        assert_eq!(
            [c.at(0, 0), c.at(1, 0), c.at(0, 1), c.at(1, 1)],
            [1.0, 0.5, 0.5, 0.0]
        );
    }

    #[test]
    fn hole_and_offset_window() {
        // A 4×4 square from (-3, 5) with a clockwise 2×2 hole from (-2, 6): 12 in total,
        // the hole's pixels empty, a pixel beside it full.
        let outer = [[-3., 5.], [1., 5.], [1., 9.], [-3., 9.]];
        let hole = [[-2., 6.], [-2., 8.], [0., 8.], [0., 6.]];
        let c = Coverage::of([&outer[..], &hole[..]]);
        assert!((total(&c) - 12.0).abs() < 1e-12);
        assert_eq!(c.at(-2, 6), 0.0);
        assert_eq!(c.at(-3, 6), 1.0);
        assert_eq!(c.at(5, 5), 0.0);
    }

    #[test]
    fn thin_steep_sliver_sums_to_its_area() {
        // A needle crossing many rows and columns: per-cell areas sum to the shoelace area.
        let t = [[0.1, 0.2], [7.9, 5.3], [7.3, 5.9]];
        let c = Coverage::of([&t[..]]);
        let area = kepler_hsr::check::ring_area(&t);
        assert!((total(&c) - area).abs() < 1e-12 * area.max(1.0));
        assert!(c.area.iter().all(|&a| (-1e-12..=1.0 + 1e-12).contains(&a)));
    }
}
