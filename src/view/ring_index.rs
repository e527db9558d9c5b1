//! Boxes over runs of a long ring's points, to cut the ring down to what matters inside a
//! window: a 65536-gon against a small face costs the face's neighbourhood, not the ring.
//! Its own structure, not geom's grid: its boxes bound runs of consecutive points, which the
//! cut replaces by their chords, and a spatial index of single points cannot say that.
//!
//! Why the cut ring is as good as the ring inside the window. A run of consecutive points
//! whose box is strictly outside the closed window on one side (every box disjoint from a
//! rectangle is separated from it along x or y) is replaced by its first and last point:
//! the run and the chord that replaces it lie in that open half-plane, which holds no point
//! of the window and reaches infinity, so the closed curve "run, then chord back" winds 0
//! round every point of the window. Winding numbers inside the window are therefore
//! unchanged, and so is every region made from the ring there (its part in front of a plane
//! — the plane's trace is a line, cut the same on both rings —, its clip to the window, its
//! cover of a face inside the window). A convex ring stays convex: its cut keeps a subset
//! of its corners, in order.

use crate::geom::Rect;

/// Points per run at the bottom level.
const RUN: usize = 16;

/// Rings longer than this get an index.
pub(crate) const INDEXED_ABOVE: usize = 64;

/// A binary tree of boxes over runs of a ring's points (level 0: runs of 16 points;
/// each level above: pairs of boxes merged).
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct RingIndex {
    len: usize,
    levels: Vec<Vec<Rect>>,
}

impl RingIndex {
    /// The index of a ring of screen points (x, y, depth; depth is ignored).
    pub(crate) fn new(pts: &[[f64; 3]]) -> RingIndex {
        let mut level: Vec<Rect> = pts
            .chunks(RUN)
            .map(|run| {
                let mut r = Rect::EMPTY;
                run.iter().for_each(|p| r.add([p[0], p[1]]));
                r
            })
            .collect();
        let mut levels = Vec::new();
        while level.len() > 1 {
            let up = level
                .chunks(2)
                .map(|pair| pair.iter().fold(Rect::EMPTY, |a, r| a.union(r)))
                .collect();
            levels.push(std::mem::replace(&mut level, up));
        }
        levels.push(level);
        RingIndex {
            len: pts.len(),
            levels,
        }
    }

    #[cfg(test)]
    /// Number of points of the indexed ring.
    pub(crate) fn len(&self) -> usize {
        self.len
    }

    /// Indices (ascending) of the points of the cut ring for `window`: runs whose box is
    /// strictly outside the window keep their first and last point, the others all theirs.
    pub(crate) fn cut(&self, window: &Rect, out: &mut Vec<u32>) {
        out.clear();
        let top = self.levels.len() - 1;
        for k in 0..self.levels[top].len() {
            self.visit(top, k, window, out);
        }
    }

    /// Points `start..end` of node `k` at `level`.
    fn span(&self, level: usize, k: usize) -> (usize, usize) {
        let width = RUN << level;
        (k * width, ((k + 1) * width).min(self.len))
    }

    fn visit(&self, level: usize, k: usize, window: &Rect, out: &mut Vec<u32>) {
        let (start, end) = self.span(level, k);
        if outside(&self.levels[level][k], window) {
            out.push(start as u32);
            if end - 1 > start {
                out.push((end - 1) as u32);
            }
        } else if level == 0 {
            out.extend(start as u32..end as u32);
        } else {
            for child in [2 * k, 2 * k + 1] {
                if child < self.levels[level - 1].len() {
                    self.visit(level - 1, child, window, out);
                }
            }
        }
    }
}

/// True when box `b` lies strictly outside the closed rectangle `w` along x or y.
fn outside(b: &Rect, w: &Rect) -> bool {
    b.xmax < w.xmin || b.xmin > w.xmax || b.ymax < w.ymin || b.ymin > w.ymax
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::poly2::{ring_area, Pt2};
    use crate::geom::predicates::winding;
    use crate::geom::rng::XorShift as Rng;

    fn star(n: usize, rng: &mut Rng) -> Vec<[f64; 3]> {
        (0..n)
            .map(|k| {
                let a = std::f64::consts::TAU * k as f64 / n as f64;
                let r = 1.0 + 0.6 * rng.unit();
                [r * a.cos(), r * a.sin(), 0.0]
            })
            .collect()
    }

    #[test]
    fn the_cut_ring_winds_like_the_ring_inside_the_window() {
        let mut rng = Rng::new(7);
        for n in [65, 100, 1000, 5000] {
            let pts = star(n, &mut rng);
            let ring: Vec<Pt2> = pts.iter().map(|p| [p[0], p[1]]).collect();
            let index = RingIndex::new(&pts);
            let mut cut = Vec::new();
            for _ in 0..40 {
                let (x, y) = (3.2 * rng.unit() - 1.6, 3.2 * rng.unit() - 1.6);
                let s = 0.5 * rng.unit() * rng.unit();
                let w = Rect {
                    xmin: x,
                    ymin: y,
                    xmax: x + s,
                    ymax: y + 0.7 * s,
                };
                index.cut(&w, &mut cut);
                assert!(cut.windows(2).all(|p| p[0] < p[1]));
                let small: Vec<Pt2> = cut.iter().map(|&i| ring[i as usize]).collect();
                // The clipped areas agree, and winding numbers at points of the window.
                let (a, b) = (
                    ring_area(&w.clip_ring(&ring)),
                    ring_area(&w.clip_ring(&small)),
                );
                assert!((a - b).abs() <= 1e-12, "{a} vs {b}");
                for _ in 0..20 {
                    let p = [x + s * rng.unit(), y + 0.7 * s * rng.unit()];
                    assert_eq!(winding(&ring, p), winding(&small, p), "n {n} at {p:?}");
                }
                if s < 0.05 {
                    assert!(small.len() < n / 2, "{} of {n}", small.len());
                }
            }
        }
    }

    #[test]
    fn a_far_window_keeps_only_run_ends() {
        let pts: Vec<[f64; 3]> = (0..256)
            .map(|k| {
                let a = std::f64::consts::TAU * k as f64 / 256.0;
                [a.cos(), a.sin(), 0.0]
            })
            .collect();
        let index = RingIndex::new(&pts);
        assert_eq!(index.len(), 256);
        let mut cut = Vec::new();
        let far = Rect {
            xmin: 5.0,
            ymin: 5.0,
            xmax: 6.0,
            ymax: 6.0,
        };
        index.cut(&far, &mut cut);
        // The whole ring is one box outside: its first and last point.
        assert_eq!(cut, vec![0, 255]);
        let all = Rect {
            xmin: -2.0,
            ymin: -2.0,
            xmax: 2.0,
            ymax: 2.0,
        };
        index.cut(&all, &mut cut);
        assert_eq!(cut, (0..256).collect::<Vec<u32>>());
    }
}
