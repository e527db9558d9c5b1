//! A closed screen region (a multipolygon) with its ring edges in a packed R-tree: the
//! edges near a segment, and the exact location of a point, cost what lies near them (and a
//! logarithm), not the region's size: a visible region of a million corners is normal.

use crate::geom::poly2::{locate, MultiPolygon, Pt2, Side};
use crate::geom::{winding_step, Rect};

/// Regions with more ring edges than this are indexed; smaller ones are scanned.
const INDEX_ABOVE: usize = 64;
/// Children per node of the R-tree.
const FANOUT: usize = 16;

/// A region and its ring edges, indexed when many.
#[derive(Debug)]
pub(crate) struct Region<'a> {
    /// The region itself.
    pub m: &'a MultiPolygon,
    /// Every ring edge, ring after ring.
    edges: Vec<[Pt2; 2]>,
    /// Bounding rectangle of the region.
    rect: Rect,
    tree: Option<Tree>,
}

/// A static R-tree packed in Hilbert order (after Flatbush): level 0 holds the edges' boxes
/// in that order, each level above one box per `FANOUT` boxes below.
#[derive(Debug)]
struct Tree {
    /// Edge index of each level-0 slot.
    order: Vec<u32>,
    /// Boxes of all levels, level 0 first.
    boxes: Vec<Rect>,
    /// Where each level starts in `boxes` (and one past the root).
    levels: Vec<usize>,
}

impl<'a> Region<'a> {
    /// The region `m` with its edges, indexed when it has many.
    pub(crate) fn new(m: &'a MultiPolygon) -> Region<'a> {
        let mut edges = Vec::new();
        for r in m.iter().flatten() {
            for i in 0..r.len() {
                edges.push([r[i], r[(i + 1) % r.len()]]);
            }
        }
        let rect = Rect::of_points(m.iter().flatten().flatten());
        let tree = (edges.len() > INDEX_ABOVE).then(|| Tree::new(&edges, &rect));
        Region {
            m,
            edges,
            rect,
            tree,
        }
    }

    /// The bounding rectangle (empty for an empty region).
    pub(crate) fn rect(&self) -> Rect {
        self.rect
    }

    /// True when the region has no ring.
    pub(crate) fn is_empty(&self) -> bool {
        self.m.is_empty()
    }

    /// The ring edges whose boxes meet the closed rectangle `r` (every one that does, perhaps
    /// others; each once).
    pub(crate) fn edges_near(&self, r: &Rect) -> Vec<[Pt2; 2]> {
        match &self.tree {
            None => self.edges.clone(),
            Some(t) => {
                let mut out = Vec::new();
                t.visit(r, |i| out.push(self.edges[i]));
                out
            }
        }
    }

    /// Exact location of `p` (non-zero winding over all rings), as
    /// [`crate::geom::poly2::locate`].
    pub(crate) fn locate(&self, p: Pt2) -> Side {
        let Some(t) = &self.tree else {
            return locate(self.m, p);
        };
        // Cast the ray toward the nearest side of the region's rectangle: only edges through
        // p or crossing the ray count, and their boxes meet the ray. A ray toward -x, +y or
        // -y is the +x ray of the plane mirrored or turned, which may flip the winding
        // number's sign, never whether it is zero.
        let r = self.rect;
        let ways = [r.xmax - p[0], p[0] - r.xmin, r.ymax - p[1], p[1] - r.ymin];
        let way = (0..4)
            .min_by(|&a, &b| ways[a].total_cmp(&ways[b]))
            .unwrap_or(0);
        let turn = |q: Pt2| match way {
            0 => q,
            1 => [-q[0], q[1]],
            2 => [q[1], q[0]],
            _ => [-q[1], q[0]],
        };
        let (inf, x, y) = (f64::INFINITY, p[0], p[1]);
        let ray = match way {
            0 => Rect::new(x, y, inf, y),
            1 => Rect::new(-inf, y, x, y),
            2 => Rect::new(x, y, x, inf),
            _ => Rect::new(x, -inf, x, y),
        };
        let tp = turn(p);
        let (mut total, mut on) = (0, false);
        t.visit(&ray, |i| {
            let [a, b] = self.edges[i];
            match winding_step(turn(a), turn(b), tp) {
                None => on = true,
                Some(w) => total += w,
            }
        });
        if on {
            Side::Boundary
        } else if total != 0 {
            Side::Inside
        } else {
            Side::Outside
        }
    }

    /// True when `p` lies within `eps` of a ring edge.
    pub(crate) fn near_boundary(&self, p: Pt2, eps: f64) -> bool {
        let r = Rect::new(p[0] - eps, p[1] - eps, p[0] + eps, p[1] + eps);
        self.edges_near(&r)
            .iter()
            .any(|&[c, d]| dist_to_segment(c, d, p) <= eps)
    }
}

impl Tree {
    fn new(edges: &[[Pt2; 2]], rect: &Rect) -> Tree {
        let boxes: Vec<Rect> = edges.iter().map(|e| Rect::of_points(e.iter())).collect();
        let (w, h) = (rect.width(), rect.height());
        let scale = |v: f64, lo: f64, size: f64| -> u32 {
            if size > 0.0 {
                (((v - lo) / size) * 65535.0).clamp(0.0, 65535.0) as u32
            } else {
                0
            }
        };
        let key = |b: &Rect| {
            let cx = scale(0.5 * (b.xmin + b.xmax), rect.xmin, w);
            let cy = scale(0.5 * (b.ymin + b.ymax), rect.ymin, h);
            hilbert(cx, cy)
        };
        let keys: Vec<u64> = boxes.iter().map(key).collect();
        let mut order: Vec<u32> = (0..edges.len() as u32).collect();
        order.sort_unstable_by_key(|&i| (keys[i as usize], i));
        let mut all: Vec<Rect> = order.iter().map(|&i| boxes[i as usize]).collect();
        let mut levels = vec![0];
        let (mut start, mut len) = (0, all.len());
        while len > 1 {
            for k in (0..len).step_by(FANOUT) {
                let end = (k + FANOUT).min(len);
                let b = all[start + k..start + end]
                    .iter()
                    .fold(Rect::EMPTY, |a, b| a.union(b));
                all.push(b);
            }
            start += len;
            len = all.len() - start;
            levels.push(start);
        }
        levels.push(all.len());
        Tree {
            order,
            boxes: all,
            levels,
        }
    }

    /// Calls `f` with the index of every edge whose box meets the closed rectangle `r`.
    fn visit(&self, r: &Rect, mut f: impl FnMut(usize)) {
        let top = self.levels.len() - 2;
        let mut stack = vec![(top, 0usize)];
        while let Some((level, k)) = stack.pop() {
            let b = &self.boxes[self.levels[level] + k];
            if !b.overlaps_closed(r) {
                continue;
            }
            if level == 0 {
                f(self.order[k] as usize);
                continue;
            }
            let below = self.levels[level] - self.levels[level - 1];
            for c in (k * FANOUT..((k + 1) * FANOUT).min(below)).rev() {
                stack.push((level - 1, c));
            }
        }
    }
}

/// The position of (x, y) along a Hilbert curve over a 2^16 × 2^16 grid.
fn hilbert(mut x: u32, mut y: u32) -> u64 {
    let mut d = 0u64;
    let mut s = 1u32 << 15;
    while s > 0 {
        let rx = u32::from(x & s > 0);
        let ry = u32::from(y & s > 0);
        d += u64::from(s) * u64::from(s) * u64::from((3 * rx) ^ ry);
        if ry == 0 {
            if rx == 1 {
                x = 0xffff - x;
                y = 0xffff - y;
            }
            std::mem::swap(&mut x, &mut y);
        }
        s >>= 1;
    }
    d
}

/// Distance of `p` from the segment c → d.
pub(crate) fn dist_to_segment(c: Pt2, d: Pt2, p: Pt2) -> f64 {
    let (dx, dy) = (d[0] - c[0], d[1] - c[1]);
    let l2 = dx * dx + dy * dy;
    let t = if l2 > 0.0 {
        (((p[0] - c[0]) * dx + (p[1] - c[1]) * dy) / l2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (p[0] - c[0] - t * dx).hypot(p[1] - c[1] - t * dy)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A star with `k` points and a square hole: many edges, so it is gridded.
    fn star(k: usize) -> MultiPolygon {
        let outer: Vec<Pt2> = (0..2 * k)
            .map(|i| {
                let a = i as f64 * std::f64::consts::PI / k as f64;
                let r = if i % 2 == 0 { 1.0 } else { 0.6 };
                [r * a.cos(), r * a.sin()]
            })
            .collect();
        let hole = vec![[-0.2, -0.2], [-0.2, 0.2], [0.2, 0.2], [0.2, -0.2]];
        vec![vec![outer, hole]]
    }

    #[test]
    fn grid_answers_as_the_full_scan() {
        let m = star(200);
        let r = Region::new(&m);
        assert!(r.tree.is_some());
        let mut s = 1u64;
        let mut rnd = || {
            s = s
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (s >> 11) as f64 / (1u64 << 53) as f64 * 2.4 - 1.2
        };
        let mut pts: Vec<Pt2> = (0..2000).map(|_| [rnd(), rnd()]).collect();
        // Corners and edge midpoints: on the boundary.
        pts.extend(m[0][0].iter().take(50));
        pts.extend([[0.2, 0.0], [-0.2, 0.2], [0.0, -0.2]]);
        for p in pts {
            assert_eq!(r.locate(p), locate(&m, p), "{p:?}");
            let full = r
                .edges
                .iter()
                .any(|&[c, d]| dist_to_segment(c, d, p) <= 1e-3);
            assert_eq!(r.near_boundary(p, 1e-3), full, "{p:?}");
        }
        let q = Rect {
            xmin: 0.1,
            ymin: 0.1,
            xmax: 0.5,
            ymax: 0.3,
        };
        let near = r.edges_near(&q);
        let want: Vec<[Pt2; 2]> = r
            .edges
            .iter()
            .copied()
            .filter(|e| Rect::of_points(e.iter()).overlaps_closed(&q))
            .collect();
        assert!(want.iter().all(|e| near.contains(e)));
        assert!(near.len() < r.edges.len() / 2);
    }
}
