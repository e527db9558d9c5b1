//! Tight bounds from the 18 offsets alone: the support of the tribox in each face direction.
//!
//! The support of the polytope {x : n_g·x ≤ α_g} in direction n_f is, by linear programming
//! duality, the least Σ λ_g α_g over non-negative λ with Σ λ_g n_g = n_f; a basic optimum
//! uses at most three faces. The 18 normals are fixed, so the combinations are enumerated
//! once: every set of one, two or three faces whose normals span n_f with positive weights
//! (the weights are 1/2, 1 or 2). [`tighten`] takes the least value over all of them, an
//! exact support up to the rounding of those few additions.
//!
//! The same table gives, for face f, the support of the polytope *without* face f: how far
//! face f's plane may move outward before its face vanishes. [`simplify`] uses it.

use std::sync::OnceLock;

use super::bounds::face_normal;

/// A positive combination of up to three face normals equal to a target face's normal.
#[derive(Debug, Clone, Copy)]
struct Combo {
    /// Faces and their weights (unused slots have weight 0).
    terms: [(u8, f64); 3],
}

impl Combo {
    fn value(&self, offsets: &[f64; 18]) -> f64 {
        self.terms
            .iter()
            .filter(|t| t.1 != 0.0)
            .map(|&(g, w)| w * offsets[g as usize])
            .sum()
    }

    /// Σ |λ_g α_g|: the scale of the rounding in [`Combo::value`].
    fn magnitude(&self, offsets: &[f64; 18]) -> f64 {
        self.terms
            .iter()
            .filter(|t| t.1 != 0.0)
            .map(|&(g, w)| (w * offsets[g as usize]).abs())
            .sum()
    }

    fn uses(&self, f: usize) -> bool {
        self.terms.iter().any(|t| t.1 != 0.0 && t.0 as usize == f)
    }
}

/// Combinations per target face (computed once: the normals are constants).
fn table() -> &'static [Vec<Combo>; 18] {
    static TABLE: OnceLock<[Vec<Combo>; 18]> = OnceLock::new();
    TABLE.get_or_init(|| std::array::from_fn(combos_for))
}

/// All positive combinations of one to three face normals equal to face `f`'s normal.
fn combos_for(f: usize) -> Vec<Combo> {
    let target = face_normal(f);
    let mut out = vec![Combo {
        terms: [(f as u8, 1.0), (0, 0.0), (0, 0.0)],
    }];
    let n: Vec<_> = (0..18).map(face_normal).collect();
    // Pairs: target = a n_i + b n_j with a, b > 0 (normals i, j independent).
    for i in 0..18 {
        for j in i + 1..18 {
            if let Some([a, b]) = solve2(&n[i], &n[j], &target) {
                out.push(Combo {
                    terms: [(i as u8, a), (j as u8, b), (0, 0.0)],
                });
            }
        }
    }
    // Triples of independent normals with all three weights positive.
    for i in 0..18 {
        for j in i + 1..18 {
            for k in j + 1..18 {
                let m = nalgebra::Matrix3::from_columns(&[n[i], n[j], n[k]]);
                let Some(inv) = m.try_inverse() else { continue };
                if m.determinant().abs() < 0.5 {
                    continue;
                }
                let w = inv * target;
                if w.iter().all(|&x| x > 1e-9) {
                    out.push(Combo {
                        terms: [
                            (i as u8, snap(w[0])),
                            (j as u8, snap(w[1])),
                            (k as u8, snap(w[2])),
                        ],
                    });
                }
            }
        }
    }
    out
}

/// Positive weights (a, b) with a·u + b·v = t, for independent u, v; None otherwise.
fn solve2(u: &crate::geom::V3, v: &crate::geom::V3, t: &crate::geom::V3) -> Option<[f64; 2]> {
    let c = u.cross(v);
    if c.norm_squared() < 0.5 || c.dot(t).abs() > 1e-9 {
        return None;
    }
    // Solve in the plane: a = (t × v)·c / |c|², b = (u × t)·c / |c|².
    let a = t.cross(v).dot(&c) / c.norm_squared();
    let b = u.cross(t).dot(&c) / c.norm_squared();
    (a > 1e-9 && b > 1e-9).then(|| [snap(a), snap(b)])
}

/// A weight computed through an inverse, snapped to the multiple of 1/2 it rounds from.
fn snap(x: f64) -> f64 {
    let h = (x * 2.0).round() / 2.0;
    if (x - h).abs() < 1e-9 {
        h
    } else {
        x
    }
}

/// Tight offsets: for each face the least value of any combination (its support). A bound
/// is lowered only when a combination beats it by more than the combination's own rounding
/// (8 ulps of the terms), so the bounds of a point set, tight already, stay exactly as they
/// are and every point stays inside.
pub(crate) fn tighten(offsets: &[f64; 18]) -> [f64; 18] {
    let t = table();
    std::array::from_fn(|f| {
        let mut best = offsets[f];
        for c in &t[f] {
            let v = c.value(offsets);
            if v < best - 8.0 * f64::EPSILON * c.magnitude(offsets) {
                best = v;
            }
        }
        best
    })
}

/// The support in face `f`'s direction of the polytope of all faces but `f`.
pub(crate) fn relaxed(offsets: &[f64; 18], f: usize) -> f64 {
    table()[f]
        .iter()
        .filter(|c| !c.uses(f))
        .map(|c| c.value(offsets))
        .fold(f64::INFINITY, f64::min)
}

/// Outward simplification of tight `offsets`: repeatedly, the face whose plane can move out
/// the least distance (at most `tol`) before the face vanishes is moved there. Only outward
/// moves, so the result contains the input polytope.
pub(crate) fn simplify(offsets: &[f64; 18], tol: f64) -> [f64; 18] {
    let mut o = *offsets;
    let mut done = [false; 18];
    loop {
        let mut best: Option<(f64, usize, f64)> = None;
        for f in 0..18 {
            if done[f] {
                continue;
            }
            let r = relaxed(&o, f);
            let push = (r - o[f]) / face_normal(f).norm();
            if push > 0.0 && push <= tol && best.is_none_or(|b| push < b.0) {
                best = Some((push, f, r));
            }
        }
        let Some((_, f, r)) = best else { break };
        o[f] = r;
        done[f] = true;
    }
    o
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::P3;
    use crate::tribox::Tribox;

    #[test]
    fn every_face_has_the_trivial_and_the_block_combinations() {
        let t = table();
        for (f, combos) in t.iter().enumerate() {
            assert!(combos.len() > 3, "face {f}");
            for c in combos {
                let s: crate::geom::V3 = c
                    .terms
                    .iter()
                    .filter(|t| t.1 != 0.0)
                    .map(|&(g, w)| face_normal(g as usize) * w)
                    .sum();
                assert!((s - face_normal(f)).norm() < 1e-12, "face {f}: {c:?}");
            }
        }
    }

    #[test]
    fn loose_chamfer_is_tightened_to_the_block() {
        // The unit cube's tribox with x+y max loosened to 5: tight value is 2.
        let mut t = Tribox::from_points(
            crate::geom::Box3::new(P3::new(0., 0., 0.), P3::new(1., 1., 1.))
                .corners()
                .iter(),
        );
        let before = t;
        t.hi[3] = 5.0;
        // x min loosened to -3: x+y >= 0 and y-x <= 1 add up to 2x >= -1, and the point
        // (-1/2, 1/2, 1/2) meets every other bound, so the tight value is -1/2.
        t.lo[0] = -3.0;
        let tt = t.tightened();
        assert_eq!(tt.hi[3], 2.0);
        assert_eq!(tt.lo[0], -0.5);
        assert!(Tribox::from_offsets(&tt.offsets()).contains(&P3::new(-0.5, 0.5, 0.5)));
        assert!(tt.lo[0] <= before.lo[0]);
    }

    #[test]
    fn simplify_moves_only_outward_and_within_tol() {
        let pts = [
            P3::new(0., 0., 0.),
            P3::new(1., 0., 0.),
            P3::new(0., 1., 0.),
            P3::new(0.99, 0.99, 0.0),
            P3::new(0., 0., 1.),
        ];
        let t = Tribox::from_points(pts.iter()).tightened();
        let s = combos::simplify(&t.offsets(), 0.05);
        for (f, (&after, before)) in s.iter().zip(t.offsets()).enumerate() {
            assert!(after >= before);
            assert!((after - before) / face_normal(f).norm() <= 0.05 + 1e-12);
        }
        // The x+y face (depth 0.02/sqrt2 from the block corner) moved out to x+y = 2.
        assert_eq!(s[7], 2.0);
    }

    use crate::tribox::combos;
}
