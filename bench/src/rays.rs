//! The ray-sampling baseline, after fogleman/ln: points along every edge every `step`, one
//! ray each from the eye, an edge piece drawn when its point's ray reaches it unobstructed.
//!
//! A ray from the eye to a point projects to a single screen point, so the ray test is done in
//! screen space: the point is hidden when some face's projection contains it and that face's
//! plane is nearer there by more than `eps` (ln's `t > EPS`). Faces are found through a
//! uniform grid over the screen (ln uses a BVH over triangles; the answers are the same).

use rayon::prelude::*;

use kepler_hsr::{Camera, FaceId, View, P3};

use super::zbuffer::{plane, scene_rect};
use kepler_hsr::plot::Rect;

/// A part [t0, t1] of a segment, by parameter (0 at its start, 1 at its end).
pub type Interval = [f64; 2];

/// An edge of the drawing: world end points and the faces it lies on.
pub type Edge = ([P3; 2], Vec<FaceId>);

/// A face as the ray test needs it: screen polygon, depth plane z = a·x + b·y + c, rectangle.
#[derive(Debug, Clone)]
struct Occluder {
    pts: Vec<[f64; 2]>,
    plane: [f64; 3],
    rect: Rect,
}

/// The faces of a view bucketed by a uniform screen grid (cells in compressed rows).
#[derive(Debug, Clone)]
pub struct Index {
    occ: Vec<Occluder>,
    rect: Rect,
    nx: usize,
    ny: usize,
    cell: [f64; 2],
    start: Vec<u32>,
    items: Vec<u32>,
    /// Depth margin under which a face does not count as in front (ln's EPS).
    pub eps: f64,
}

impl Index {
    /// Buckets the drawable faces of a view (about one face per cell on average).
    pub fn build(view: &View) -> Index {
        let mut zlo_hi = (f64::INFINITY, f64::NEG_INFINITY);
        let occ: Vec<Occluder> = view
            .screen_polygons()
            .filter_map(|(_, corners, refs)| {
                zlo_hi = corners
                    .iter()
                    .fold(zlo_hi, |(lo, hi), q| (lo.min(q[2]), hi.max(q[2])));
                let plane = plane(refs.map(|k| corners[k]))?;
                let pts: Vec<[f64; 2]> = corners.iter().map(|q| [q[0], q[1]]).collect();
                Some(Occluder {
                    rect: Rect::of_points(&pts),
                    pts,
                    plane,
                })
            })
            .collect();
        let (zlo, zhi) = zlo_hi;
        let rect = scene_rect(view);
        let n = (occ.len() as f64).sqrt().ceil().max(1.0) as usize;
        let cell = [
            (rect.width() / n as f64).max(f64::MIN_POSITIVE),
            (rect.height() / n as f64).max(f64::MIN_POSITIVE),
        ];
        let mut idx = Index {
            occ,
            rect,
            nx: n,
            ny: n,
            cell,
            start: Vec::new(),
            items: Vec::new(),
            eps: 1e-9 * (zhi - zlo).max(0.0),
        };
        idx.fill();
        idx
    }

    /// Cell range [i0, i1] × [j0, j1] of a rectangle.
    fn cells(&self, r: &Rect) -> [usize; 4] {
        let ci = |x: f64, k: usize, n: usize| {
            (((x - self.rect.bound(k, false)) / self.cell[k])
                .floor()
                .max(0.0) as usize)
                .min(n - 1)
        };
        [
            ci(r.xmin, 0, self.nx),
            ci(r.ymin, 1, self.ny),
            ci(r.xmax, 0, self.nx),
            ci(r.ymax, 1, self.ny),
        ]
    }

    /// Fills the compressed cell lists (counting pass, then placing pass).
    fn fill(&mut self) {
        let mut count = vec![0u32; self.nx * self.ny + 1];
        for o in &self.occ {
            let [i0, j0, i1, j1] = self.cells(&o.rect);
            for j in j0..=j1 {
                for i in i0..=i1 {
                    count[j * self.nx + i + 1] += 1;
                }
            }
        }
        for k in 1..count.len() {
            count[k] += count[k - 1];
        }
        let mut next = count.clone();
        let mut items = vec![0u32; *count.last().unwrap_or(&0) as usize];
        for (k, o) in self.occ.iter().enumerate() {
            let [i0, j0, i1, j1] = self.cells(&o.rect);
            for j in j0..=j1 {
                for i in i0..=i1 {
                    let c = j * self.nx + i;
                    items[next[c] as usize] = k as u32;
                    next[c] += 1;
                }
            }
        }
        self.start = count;
        self.items = items;
    }

    /// True when a face is in front of the screen point p at depth z (the point's ray is
    /// blocked before it reaches the point).
    pub fn hidden(&self, p: [f64; 2], z: f64) -> bool {
        let point = Rect::new(p[0], p[1], p[0], p[1]);
        if !self.rect.contains_rect(&point) {
            return false;
        }
        let [i, j, _, _] = self.cells(&point);
        let c = j * self.nx + i;
        self.items[self.start[c] as usize..self.start[c + 1] as usize]
            .iter()
            .any(|&k| {
                let o = &self.occ[k as usize];
                o.rect.contains_rect(&point)
                    && o.plane[0] * p[0] + o.plane[1] * p[1] + o.plane[2] > z + self.eps
                    && inside(&o.pts, p)
            })
    }
}

/// Crossing-number point-in-polygon test (plain floating point, as a sampler would).
fn inside(r: &[[f64; 2]], p: [f64; 2]) -> bool {
    let mut c = false;
    let n = r.len();
    for k in 0..n {
        let (a, b) = (r[k], r[(k + 1) % n]);
        if (a[1] > p[1]) != (b[1] > p[1]) {
            let x = a[0] + (p[1] - a[1]) / (b[1] - a[1]) * (b[0] - a[0]);
            if p[0] < x {
                c = !c;
            }
        }
    }
    c
}

/// The screen segment (x, y, depth) of the world segment a → b, cut at the near plane
/// (perspective) exactly as the drawing cuts it; None when nothing of it is in front.
pub fn segment(camera: &Camera, a: &P3, b: &P3) -> Option<[[f64; 3]; 2]> {
    camera.project_segment(a, b)
}

/// The visible intervals of one screen segment sampled every `step`: it is cut into
/// ⌈length / step⌉ equal pieces, each drawn when the ray to its midpoint is unobstructed
/// (depth is affine along a screen segment, so it is interpolated exactly).
pub fn sample_segment(index: &Index, s: &[[f64; 3]; 2], step: f64) -> Vec<Interval> {
    let [a, b] = *s;
    let len = (b[0] - a[0]).hypot(b[1] - a[1]);
    if len == 0.0 {
        return Vec::new();
    }
    let n = (len / step).ceil().max(1.0) as usize;
    let mut out: Vec<Interval> = Vec::new();
    for k in 0..n {
        let t = (k as f64 + 0.5) / n as f64;
        let p = [a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])];
        let z = a[2] + t * (b[2] - a[2]);
        if index.hidden(p, z) {
            continue;
        }
        let (t0, t1) = (k as f64 / n as f64, (k + 1) as f64 / n as f64);
        match out.last_mut() {
            Some(last) if last[1] == t0 => last[1] = t1,
            _ => out.push([t0, t1]),
        }
    }
    out
}

/// Every edge's screen segment (None where it is behind the near plane).
pub fn segments(view: &View, edges: &[Edge]) -> Vec<Option<[[f64; 3]; 2]>> {
    edges
        .iter()
        .map(|e| segment(&view.camera, &e.0[0], &e.0[1]))
        .collect()
}

/// The whole baseline: sampled visible intervals of every edge.
pub fn sample(view: &View, edges: &[Edge], step: f64) -> Vec<Vec<Interval>> {
    let index = Index::build(view);
    segments(view, edges)
        .par_iter()
        .map(|s| match s {
            Some(s) => sample_segment(&index, s, step),
            None => Vec::new(),
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn index_of(occ: Vec<Occluder>) -> Index {
        let mut idx = Index {
            occ,
            rect: Rect::new(0., 0., 4., 4.),
            nx: 2,
            ny: 2,
            cell: [2., 2.],
            start: Vec::new(),
            items: Vec::new(),
            eps: 1e-9,
        };
        idx.fill();
        idx
    }

    #[test]
    fn a_square_in_front_hides_the_middle_of_a_segment() {
        // A square over [1, 3]² at depth 1; a segment from (0, 2) to (4, 2) at depth 0.
        let sq = Occluder {
            pts: vec![[1., 1.], [3., 1.], [3., 3.], [1., 3.]],
            plane: [0., 0., 1.],
            rect: Rect::new(1., 1., 3., 3.),
        };
        let idx = index_of(vec![sq]);
        assert!(idx.hidden([2., 2.], 0.0));
        assert!(
            !idx.hidden([2., 2.], 2.0),
            "the point is in front of the square"
        );
        assert!(!idx.hidden([0.5, 2.], 0.0));
        let seg = [[0., 2., 0.], [4., 2., 0.]];
        // Step 1: pieces [0,1], [1,2], [2,3], [3,4]: midpoints 0.5 and 3.5 visible.
        assert_eq!(
            sample_segment(&idx, &seg, 1.0),
            vec![[0.0, 0.25], [0.75, 1.0]]
        );
        // Step 0.3: 14 pieces; the visible parts approach [0, 1/4] and [3/4, 1].
        let v = sample_segment(&idx, &seg, 0.3);
        let len: f64 = v.iter().map(|i| i[1] - i[0]).sum();
        assert!((len - 0.5).abs() <= 1.0 / 14.0 + 1e-12);
    }

    #[test]
    fn point_in_polygon_of_a_concave_ring() {
        let l = [[0., 0.], [2., 0.], [2., 1.], [1., 1.], [1., 2.], [0., 2.]];
        assert!(inside(&l, [0.5, 1.5]));
        assert!(!inside(&l, [1.5, 1.5]));
    }
}
