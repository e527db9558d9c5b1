//! The largest-volume axis-aligned box inside an intersection of half-spaces n·x ≤ d: a
//! log-barrier Newton method in the box's six coordinates.
//!
//! A box `[lo, hi]` lies in `n·x ≤ d` exactly when its corner maximising n·x does, i.e. when
//! `Σ_i n_i·(n_i > 0 ? hi_i : lo_i) ≤ d` — a linear constraint in (lo, hi). The objective
//! Σ log(hi_i − lo_i) is concave, so the problem is a small convex programme. The result is
//! only approximately optimal and only approximately feasible: callers shrink and verify it.

use nalgebra::{Matrix6, Vector6};

use crate::geom::{Box3, P3, V3};

/// A half-space `normal · x ≤ offset`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HalfSpace {
    /// Outward normal (any length).
    pub normal: V3,
    /// Offset.
    pub offset: f64,
}

/// Target duality gap, in units of log-volume (1e-5 ≈ 0.001 % of volume).
const GAP: f64 = 1e-5;
/// Factor by which the barrier weight grows per outer step.
const MU: f64 = 20.0;
/// Most Newton steps in total.
const MAX_NEWTON: usize = 400;

/// The largest box inside all `planes` (approximately), starting from `interior`, a point
/// strictly inside all of them. None when no strictly feasible start exists or the
/// iteration breaks down (an unbounded or degenerate region).
pub fn largest_box(planes: &[HalfSpace], interior: &P3) -> Option<Box3> {
    let rows: Vec<Row> = planes.iter().map(constraint_row).collect();
    let mut x = start(planes, interior)?;
    let mut t = 1.0;
    let mut steps = 0;
    loop {
        steps += centre(&rows, &mut x, t, MAX_NEWTON.saturating_sub(steps))?;
        if rows.len() as f64 / t < GAP || steps >= MAX_NEWTON {
            break;
        }
        t *= MU;
    }
    let b = Box3::new(P3::new(x[0], x[1], x[2]), P3::new(x[3], x[4], x[5]));
    (b.has_interior() && (0..3).all(|i| b.lo[i].is_finite() && b.hi[i].is_finite())).then_some(b)
}

/// A linear constraint on (lo, hi) with three non-zero coefficients: Σ val·x[idx] ≤ offset.
struct Row {
    idx: [usize; 3],
    val: [f64; 3],
    offset: f64,
}

impl Row {
    fn slack(&self, x: &Vector6<f64>) -> f64 {
        self.offset - (0..3).map(|k| self.val[k] * x[self.idx[k]]).sum::<f64>()
    }
}

/// The linear constraint of one half-space on (lo, hi).
fn constraint_row(h: &HalfSpace) -> Row {
    let n = h.normal;
    Row {
        idx: std::array::from_fn(|i| if n[i] > 0.0 { 3 + i } else { i }),
        val: [n.x, n.y, n.z],
        offset: h.offset,
    }
}

/// A small cube around `p` strictly inside every half-space.
fn start(planes: &[HalfSpace], p: &P3) -> Option<Vector6<f64>> {
    let mut r = f64::INFINITY;
    for h in planes {
        let l1 = h.normal.abs().sum();
        if l1 > 0.0 {
            r = r.min((h.offset - h.normal.dot(&p.coords)) / l1);
        }
    }
    if !(r > 0.0 && r.is_finite()) {
        return None;
    }
    let r = 0.5 * r;
    Some(Vector6::new(
        p.x - r,
        p.y - r,
        p.z - r,
        p.x + r,
        p.y + r,
        p.z + r,
    ))
}

/// The barrier objective: −t Σ log widths − Σ log slacks (None when infeasible).
fn objective(rows: &[Row], x: &Vector6<f64>, t: f64) -> Option<f64> {
    let mut f = 0.0;
    for i in 0..3 {
        let w = x[3 + i] - x[i];
        if w <= 0.0 {
            return None;
        }
        f -= t * w.ln();
    }
    for r in rows {
        let s = r.slack(x);
        if s <= 0.0 {
            return None;
        }
        f -= s.ln();
    }
    Some(f)
}

/// Gradient and Hessian of the objective at a feasible `x`.
fn derivatives(rows: &[Row], x: &Vector6<f64>, t: f64) -> (Vector6<f64>, Matrix6<f64>) {
    let mut g = Vector6::zeros();
    let mut h = Matrix6::zeros();
    for i in 0..3 {
        let w = x[3 + i] - x[i];
        g[i] += t / w;
        g[3 + i] -= t / w;
        let c = t / (w * w);
        h[(i, i)] += c;
        h[(3 + i, 3 + i)] += c;
        h[(i, 3 + i)] -= c;
        h[(3 + i, i)] -= c;
    }
    for r in rows {
        let s = r.slack(x);
        for k in 0..3 {
            let gk = r.val[k] / s;
            g[r.idx[k]] += gk;
            for l in 0..3 {
                h[(r.idx[k], r.idx[l])] += gk * r.val[l] / s;
            }
        }
    }
    (g, h)
}

/// Newton's method on the barrier objective for one `t`; returns the steps taken.
fn centre(rows: &[Row], x: &mut Vector6<f64>, t: f64, budget: usize) -> Option<usize> {
    let mut f = objective(rows, x, t)?;
    for step in 0..budget {
        let (g, h) = derivatives(rows, x, t);
        let dx = -(h.cholesky()?.solve(&g));
        let decrement = -g.dot(&dx);
        if !decrement.is_finite() {
            return None;
        }
        if decrement < 1e-10 {
            return Some(step + 1);
        }
        let mut alpha = 1.0;
        loop {
            let y = *x + dx * alpha;
            if let Some(fy) = objective(rows, &y, t) {
                if fy <= f - 0.25 * alpha * decrement {
                    *x = y;
                    f = fy;
                    break;
                }
            }
            alpha *= 0.5;
            if alpha < 1e-12 {
                return Some(step + 1);
            }
        }
    }
    Some(budget)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn hs(n: [f64; 3], d: f64) -> HalfSpace {
        HalfSpace {
            normal: V3::new(n[0], n[1], n[2]),
            offset: d,
        }
    }

    #[test]
    fn box_in_a_box_is_the_box() {
        let planes = [
            hs([1., 0., 0.], 2.),
            hs([-1., 0., 0.], 0.),
            hs([0., 1., 0.], 1.),
            hs([0., -1., 0.], 0.),
            hs([0., 0., 1.], 3.),
            hs([0., 0., -1.], 1.),
        ];
        let b = largest_box(&planes, &P3::new(1., 0.5, 0.)).unwrap();
        assert!((b.volume() - 8.0).abs() < 1e-4, "{b:?}");
    }

    #[test]
    fn octahedron_box() {
        // |x|+|y|+|z| ≤ 1: the best box is the cube of half-size 1/3, volume 8/27.
        let mut planes = Vec::new();
        for k in 0..8 {
            let s = |b: usize| if k & b == 0 { 1.0 } else { -1.0 };
            planes.push(hs([s(1), s(2), s(4)], 1.0));
        }
        let b = largest_box(&planes, &P3::origin()).unwrap();
        assert!((b.volume() - 8.0 / 27.0).abs() < 1e-5, "{b:?}");
    }

    #[test]
    fn no_interior_gives_none() {
        let planes = [hs([1., 0., 0.], 0.), hs([-1., 0., 0.], 0.)];
        assert!(largest_box(&planes, &P3::origin()).is_none());
    }
}
