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
pub(crate) struct HalfSpace {
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
pub(crate) fn largest_box(planes: &[HalfSpace], interior: &P3) -> Option<Box3> {
    // Solved with `interior` at the origin: far from the world's origin the slacks would
    // be small differences of large offsets, and Newton's method would crawl.
    let c = interior.coords;
    let planes: Vec<HalfSpace> = planes
        .iter()
        .map(|h| HalfSpace {
            normal: h.normal,
            offset: h.offset - h.normal.dot(&c),
        })
        .collect();
    let b = largest_box_at_origin(&planes)?;
    let out = Box3::new(b.lo + c, b.hi + c);
    out.has_interior().then_some(out)
}

/// [`largest_box`] with the interior point at the origin.
fn largest_box_at_origin(planes: &[HalfSpace]) -> Option<Box3> {
    let rows: Vec<Row> = planes.iter().map(constraint_row).collect();
    let mut x = start(planes, &P3::origin())?;
    let mut t = 1.0;
    let mut steps = 0;
    loop {
        // Every step taken keeps `x` strictly feasible, so where a later centring breaks
        // down (an ill-conditioned Hessian: a box thin across a wide, tilted disc), the
        // last point is still a good box, only less close to the optimum. The caller
        // verifies whatever box it gets exactly.
        match centre(&rows, &mut x, t, MAX_NEWTON.saturating_sub(steps)) {
            Some(s) => steps += s,
            None if t > 1.0 => break,
            None => return None,
        }
        if rows.len() as f64 / t < GAP || steps >= MAX_NEWTON {
            break;
        }
        t *= MU;
    }
    let b = Box3::new(P3::new(x[0], x[1], x[2]), P3::new(x[3], x[4], x[5]));
    (b.has_interior() && (0..3).all(|i| b.lo[i].is_finite() && b.hi[i].is_finite())).then_some(b)
}

/// Up to this many half-spaces, [`largest_box_within`] solves with all of them at once.
const DIRECT: usize = 48;
/// Most violated half-spaces added to the working set per round.
const ADD: usize = 32;
/// Rounds of adding violated half-spaces before solving with all of them.
const ROUNDS: usize = 40;

/// [`largest_box`] for many half-spaces whose intersection lies in `bounds`: solved on a
/// small working set (the bounds' six walls and the planes met first along 26 rays from
/// `interior`), adding the half-spaces the working set's box still violates until it
/// violates none. The walls are implied by the planes, so the box found is optimal for
/// all of them; each round costs one pass over the planes, not a Newton step per plane.
pub(crate) fn largest_box_within(
    planes: &[HalfSpace],
    interior: &P3,
    bounds: &Box3,
) -> Option<Box3> {
    if planes.len() <= DIRECT {
        return largest_box(planes, interior);
    }
    let mut chosen = vec![false; planes.len()];
    let mut working = walls(bounds);
    for d in directions() {
        if let Some(k) = first_hit(planes, interior, &d) {
            if !std::mem::replace(&mut chosen[k], true) {
                working.push(planes[k]);
            }
        }
    }
    for round in 0..ROUNDS {
        let b = largest_box(&working, interior)?;
        let mut violated: Vec<(f64, usize)> = planes
            .iter()
            .enumerate()
            .filter(|&(k, _)| !chosen[k])
            .filter_map(|(k, h)| {
                let e = excess(h, &b);
                (e > 0.0).then_some((e, k))
            })
            .collect();
        if violated.is_empty() {
            return Some(b);
        }
        violated.sort_by(|a, b| b.0.total_cmp(&a.0).then(a.1.cmp(&b.1)));
        // Twice as many every few rounds: a curved side (a 65536-gon's rim) needs many
        // nearly equal planes, and 40 rounds of 32 would not reach them.
        for &(_, k) in violated.iter().take(ADD << (round / 4)) {
            chosen[k] = true;
            working.push(planes[k]);
        }
    }
    largest_box(planes, interior)
}

/// The six half-spaces of a box.
fn walls(b: &Box3) -> Vec<HalfSpace> {
    let mut out = Vec::with_capacity(6);
    for i in 0..3 {
        let mut n = V3::zeros();
        n[i] = 1.0;
        out.push(HalfSpace {
            normal: n,
            offset: b.hi[i],
        });
        out.push(HalfSpace {
            normal: -n,
            offset: -b.lo[i],
        });
    }
    out
}

/// The 26 directions to the faces, edges and corners of a cube.
fn directions() -> impl Iterator<Item = V3> {
    (0..27).filter(|&k| k != 13).map(|k| {
        V3::new(
            (k % 3) as f64 - 1.0,
            (k / 3 % 3) as f64 - 1.0,
            (k / 9) as f64 - 1.0,
        )
    })
}

/// The plane a ray from `p` along `d` meets first, if any.
fn first_hit(planes: &[HalfSpace], p: &P3, d: &V3) -> Option<usize> {
    planes
        .iter()
        .enumerate()
        .filter_map(|(k, h)| {
            let along = h.normal.dot(d);
            (along > 0.0).then(|| ((h.offset - h.normal.dot(&p.coords)) / along, k))
        })
        .min_by(|a, b| a.0.total_cmp(&b.0))
        .map(|(_, k)| k)
}

/// How far the corner of `b` farthest along the half-space's normal lies beyond it.
fn excess(h: &HalfSpace, b: &Box3) -> f64 {
    let n = h.normal;
    (0..3)
        .map(|i| n[i] * if n[i] > 0.0 { b.hi[i] } else { b.lo[i] })
        .sum::<f64>()
        - h.offset
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
    fn working_set_finds_the_box_of_all_planes() {
        // A prism over a regular 2000-gon of circumradius 1, z in [0, 1]: the best box has
        // the inscribed square's corners on the polygon (half-size about 1/sqrt(2)).
        let n = 2000;
        let mut planes = vec![hs([0., 0., 1.], 1.), hs([0., 0., -1.], 0.)];
        let apothem = (std::f64::consts::PI / n as f64).cos();
        for k in 0..n {
            let a = (k as f64 + 0.5) * std::f64::consts::TAU / n as f64;
            planes.push(hs([a.cos(), a.sin(), 0.], apothem));
        }
        let bounds = Box3::new(P3::new(-1., -1., 0.), P3::new(1., 1., 1.));
        let p = P3::new(0.1, 0., 0.5);
        let fast = largest_box_within(&planes, &p, &bounds).unwrap();
        let slow = largest_box(&planes, &p).unwrap();
        assert!(
            (fast.volume() - slow.volume()).abs() < 1e-4 * slow.volume(),
            "{fast:?} {slow:?}"
        );
        assert!(planes.iter().all(|h| excess(h, &fast) <= 0.0));
        assert!((fast.volume() - 2.0).abs() < 1e-3, "{fast:?}");
    }

    #[test]
    fn no_interior_gives_none() {
        let planes = [hs([1., 0., 0.], 0.), hs([-1., 0., 0.], 0.)];
        assert!(largest_box(&planes, &P3::origin()).is_none());
    }
}
