//! The z-buffer baseline: an ID buffer with per-pixel depth, rasterised by scanlines from the
//! projected faces, whose per-face visible areas are read from pixel counts.
//!
//! A pixel belongs to the nearest face whose projection contains the pixel's centre (depth
//! from the face's plane in screen space, which is exact for orthographic and perspective
//! views alike: the paper's depth is affine over a plane). Depth is stored as f32, like a
//! GPU depth buffer; ties keep the face earlier in global order. Back faces of closed solids
//! (culled by kepler too) and edge-on faces are not drawn. Rows are split into bands that
//! rayon rasterises in parallel, so the baseline uses both cores as kepler does.

use rayon::prelude::*;

use kepler_hsr::View;

use kepler_hsr::plot::Rect;

/// Label of a pixel no face covers.
pub const NONE: u32 = u32::MAX;

/// Rows per band (the unit of parallel work).
const BAND: usize = 64;

/// Square pixels over a screen rectangle: pixel (i, j) covers
/// [x0 + i·h, x0 + (i+1)·h] × [y0 + j·h, y0 + (j+1)·h] (row 0 at the bottom, y up).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Grid {
    /// Left edge.
    pub x0: f64,
    /// Bottom edge.
    pub y0: f64,
    /// Pixel side.
    pub h: f64,
    /// Columns.
    pub w: usize,
    /// Rows.
    pub rows: usize,
}

impl Grid {
    /// `size` pixels along the rectangle's longer side (at least one pixel each way).
    pub fn fit(rect: Rect, size: u32) -> Grid {
        let (dx, dy) = (rect.width(), rect.height());
        let h = (dx.max(dy) / size as f64).max(f64::MIN_POSITIVE);
        Grid {
            x0: rect.xmin,
            y0: rect.ymin,
            h,
            w: ((dx / h).ceil() as usize).clamp(1, size as usize),
            rows: ((dy / h).ceil() as usize).clamp(1, size as usize),
        }
    }

    /// A screen point in pixel units (u, v): pixel (i, j) spans [i, i+1] × [j, j+1].
    pub fn pixel_coords(&self, p: [f64; 2]) -> [f64; 2] {
        [(p[0] - self.x0) / self.h, (p[1] - self.y0) / self.h]
    }

    /// Area of one pixel in screen units.
    pub fn pixel_area(&self) -> f64 {
        self.h * self.h
    }
}

/// A face prepared for rasterising: its polygon in pixel units and its depth plane.
#[derive(Debug, Clone)]
pub struct Shape {
    /// Global face id (the label it writes).
    pub id: u32,
    /// Corners in pixel units.
    pub pts: Vec<[f64; 2]>,
    /// Depth at (u, v) is a·u + b·v + c.
    pub plane: [f64; 3],
    /// Lowest and highest v.
    pub v_range: [f64; 2],
}

/// The depth plane through three points (u, v, z), or None when it is seen edge-on.
pub fn plane(p: [[f64; 3]; 3]) -> Option<[f64; 3]> {
    let d1 = [p[1][0] - p[0][0], p[1][1] - p[0][1], p[1][2] - p[0][2]];
    let d2 = [p[2][0] - p[0][0], p[2][1] - p[0][1], p[2][2] - p[0][2]];
    let n = [
        d1[1] * d2[2] - d1[2] * d2[1],
        d1[2] * d2[0] - d1[0] * d2[2],
        d1[0] * d2[1] - d1[1] * d2[0],
    ];
    if n[2] == 0.0 || !n[2].is_finite() {
        return None;
    }
    let (a, b) = (-n[0] / n[2], -n[1] / n[2]);
    Some([a, b, p[0][2] - a * p[0][0] - b * p[0][1]])
}

/// The drawable faces of a view as shapes on `grid`, in global order.
pub fn shapes(view: &View, grid: &Grid) -> Vec<Shape> {
    view.screen_polygons()
        .filter_map(|(face, corners, refs)| {
            let pts3: Vec<[f64; 3]> = corners
                .iter()
                .map(|p| {
                    let q = grid.pixel_coords([p[0], p[1]]);
                    [q[0], q[1], p[2]]
                })
                .collect();
            let plane = plane(refs.map(|k| pts3[k]))?;
            let pts: Vec<[f64; 2]> = pts3.iter().map(|p| [p[0], p[1]]).collect();
            let lo = pts.iter().map(|p| p[1]).fold(f64::INFINITY, f64::min);
            let hi = pts.iter().map(|p| p[1]).fold(f64::NEG_INFINITY, f64::max);
            Some(Shape {
                id: face.0,
                pts,
                plane,
                v_range: [lo, hi],
            })
        })
        .collect()
}

/// The ID buffer of a grid: the label of every pixel, row after row from the bottom.
#[derive(Debug, Clone)]
pub struct IdBuffer {
    /// The pixels.
    pub grid: Grid,
    /// Face id per pixel ([`NONE`] where no face is).
    pub ids: Vec<u32>,
}

impl IdBuffer {
    /// Pixel counts per face id (`faces` entries).
    pub fn counts(&self, faces: usize) -> Vec<u64> {
        let mut c = vec![0u64; faces];
        for &id in &self.ids {
            if id != NONE {
                c[id as usize] += 1;
            }
        }
        c
    }
}

/// Rows whose pixel centres (v = j + 1/2) lie in [lo, hi): j from ceil(lo − 1/2) to
/// ceil(hi − 1/2) − 1, clamped to the grid.
fn centre_range(lo: f64, hi: f64, n: usize) -> std::ops::Range<usize> {
    let a = (lo - 0.5).ceil().max(0.0);
    let b = (hi - 0.5).ceil().clamp(0.0, n as f64);
    (a as usize).min(n)..(b as usize).max(a as usize).min(n)
}

/// Rasterises the shapes (in order) into an ID buffer: every pixel centre takes the nearest
/// shape containing it (even-odd rule on the centre's scanline; a centre on an edge belongs
/// to the span on its right).
pub fn rasterise(grid: &Grid, shapes: &[Shape]) -> IdBuffer {
    let bands = grid.rows.div_ceil(BAND);
    let mut bins: Vec<Vec<u32>> = vec![Vec::new(); bands];
    for (k, s) in shapes.iter().enumerate() {
        let r = centre_range(s.v_range[0], s.v_range[1], grid.rows);
        if r.is_empty() {
            continue;
        }
        for bin in &mut bins[r.start / BAND..=(r.end - 1) / BAND] {
            bin.push(k as u32);
        }
    }
    let mut ids = vec![NONE; grid.w * grid.rows];
    ids.par_chunks_mut(grid.w * BAND)
        .zip(bins.par_iter())
        .enumerate()
        .for_each(|(b, (chunk, bin))| {
            let mut depth = vec![f32::NEG_INFINITY; chunk.len()];
            let rows = b * BAND..(b * BAND + chunk.len() / grid.w);
            let mut xs = Vec::new();
            for &k in bin {
                draw(
                    grid,
                    &shapes[k as usize],
                    rows.clone(),
                    chunk,
                    &mut depth,
                    &mut xs,
                );
            }
        });
    IdBuffer { grid: *grid, ids }
}

/// Draws one shape into the rows `rows` of a band (`ids`/`depth` start at row `rows.start`).
fn draw(
    grid: &Grid,
    s: &Shape,
    rows: std::ops::Range<usize>,
    ids: &mut [u32],
    depth: &mut [f32],
    xs: &mut Vec<f64>,
) {
    let r = centre_range(s.v_range[0], s.v_range[1], grid.rows);
    let n = s.pts.len();
    for j in r.start.max(rows.start)..r.end.min(rows.end) {
        let vc = j as f64 + 0.5;
        xs.clear();
        for e in 0..n {
            let (p, q) = (s.pts[e], s.pts[(e + 1) % n]);
            if (p[1] <= vc) != (q[1] <= vc) {
                xs.push(p[0] + (vc - p[1]) / (q[1] - p[1]) * (q[0] - p[0]));
            }
        }
        xs.sort_by(f64::total_cmp);
        let row = (j - rows.start) * grid.w;
        for span in xs.chunks_exact(2) {
            let cols = centre_range(span[0], span[1], grid.w);
            for i in cols {
                let z = (s.plane[0] * (i as f64 + 0.5) + s.plane[1] * vc + s.plane[2]) as f32;
                let k = row + i;
                if z > depth[k] {
                    depth[k] = z;
                    ids[k] = s.id;
                }
            }
        }
    }
}

/// The whole baseline on a view: per-face visible areas from pixel counts at `size` pixels
/// along the longer side of the scene's screen rectangle (and the ID buffer, for checking).
pub fn visible_areas(view: &View, size: u32) -> (Vec<f64>, IdBuffer) {
    let grid = Grid::fit(scene_rect(view), size);
    let buf = rasterise(&grid, &shapes(view, &grid));
    let areas = buf
        .counts(view.face_count())
        .iter()
        .map(|&c| c as f64 * grid.pixel_area())
        .collect();
    (areas, buf)
}

/// The screen rectangle of every drawable face.
pub fn scene_rect(view: &View) -> Rect {
    view.screen_polygons()
        .flat_map(|(_, corners, _)| corners)
        .fold(Rect::EMPTY, |mut acc, p| {
            acc.add([p[0], p[1]]);
            acc
        })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn square(id: u32, x: f64, y: f64, s: f64, z: f64) -> Shape {
        Shape {
            id,
            pts: vec![[x, y], [x + s, y], [x + s, y + s], [x, y + s]],
            plane: [0.0, 0.0, z],
            v_range: [y, y + s],
        }
    }

    fn grid(w: usize, rows: usize) -> Grid {
        Grid {
            x0: 0.0,
            y0: 0.0,
            h: 1.0,
            w,
            rows,
        }
    }

    #[test]
    fn unit_square_at_known_resolution() {
        // The unit square on a 4×4 grid over [0, 1]²: every one of the 16 centres is inside.
        let g = Grid::fit(Rect::new(0., 0., 1., 1.), 4);
        assert_eq!((g.w, g.rows, g.h), (4, 4, 0.25));
        let s = Shape {
            id: 0,
            pts: vec![[0., 0.], [4., 0.], [4., 4.], [0., 4.]],
            plane: [0., 0., 0.],
            v_range: [0., 4.],
        };
        assert_eq!(rasterise(&g, &[s]).counts(1), vec![16]);
        // A 2.5 × 1.5 pixel rectangle from (0.25, 0.25) covers centres 0.5..2.5 × 0.5..1.5:
        // 3 columns (0.5, 1.5, 2.5 < 2.75) by 2 rows (0.5, 1.5 < 1.75).
        let r = Shape {
            id: 0,
            pts: vec![[0.25, 0.25], [2.75, 0.25], [2.75, 1.75], [0.25, 1.75]],
            plane: [0., 0., 0.],
            v_range: [0.25, 1.75],
        };
        assert_eq!(rasterise(&grid(8, 8), &[r]).counts(1), vec![6]);
    }

    #[test]
    fn half_open_edges_share_no_pixel() {
        // Two rectangles side by side sharing the edge u = cut: through no centre (2, 2.6) or
        // through a column of centres (2.5, which go to the right one): each centre once.
        for (cut, left) in [(2.0, 8), (2.5, 8), (2.6, 12)] {
            let a = Shape {
                id: 0,
                pts: vec![[0., 0.], [cut, 0.], [cut, 4.], [0., 4.]],
                plane: [0., 0., 0.],
                v_range: [0., 4.],
            };
            let b = Shape {
                id: 1,
                pts: vec![[cut, 0.], [4., 0.], [4., 4.], [cut, 4.]],
                plane: [0., 0., 0.],
                v_range: [0., 4.],
            };
            let c = rasterise(&grid(4, 4), &[a, b]).counts(2);
            assert_eq!(c[0] + c[1], 16);
            assert_eq!(c[0], left);
        }
    }

    #[test]
    fn nearer_square_wins_overlap_whatever_the_order() {
        // A 4×4 square at depth 1 and a 2×2 square at depth 2 (nearer) over its corner.
        let far = square(0, 0., 0., 4., 1.);
        let near = square(1, 2., 2., 2., 2.);
        for shapes in [vec![far.clone(), near.clone()], vec![near, far]] {
            let c = rasterise(&grid(6, 6), &shapes).counts(2);
            assert_eq!(c, vec![12, 4]);
        }
    }

    #[test]
    fn tilted_plane_depth_decides_per_pixel() {
        // A square rising from depth 0 at u = 0 to depth 4 at u = 4, crossing a flat square at
        // depth 2: the tilted one is in front right of u = 2 (columns 2 and 3).
        let flat = square(0, 0., 0., 4., 2.);
        let mut tilt = square(1, 0., 0., 4., 0.);
        tilt.plane = plane([[0., 0., 0.], [4., 0., 4.], [0., 4., 0.]]).unwrap();
        assert_eq!(tilt.plane, [1., 0., 0.]);
        let buf = rasterise(&grid(4, 4), &[flat, tilt]);
        assert_eq!(buf.counts(2), vec![8, 8]);
        assert_eq!(&buf.ids[0..4], &[0, 0, 1, 1]);
    }

    #[test]
    fn bands_meet_without_gaps() {
        // A grid taller than one band: a full-grid square covers every pixel exactly once.
        let g = grid(3, 2 * BAND + 5);
        let s = square(0, 0., 0., 3., 0.);
        let mut s = s;
        s.pts = vec![[0., 0.], [3., 0.], [3., g.rows as f64], [0., g.rows as f64]];
        s.v_range = [0., g.rows as f64];
        assert_eq!(rasterise(&g, &[s]).counts(1), vec![3 * g.rows as u64]);
    }
}
