//! Constructed points from their exact values: where a segment crosses a face's plane, seen
//! through the camera matrix M, and where it crosses the near plane w' = near. A floating
//! filter (double-double values with error bounds, [`super::accurate`]) answers when its
//! bound is below 2^-60 of the endpoints' screen size; otherwise big integers give the exact
//! point, rounded once (ties to even). Either way each coordinate is within 1 ulp of the
//! larger endpoint coordinate plus ½ ulp of itself of the exact value, whatever the angle
//! between segment and plane (docs/numerics.md).

use std::cmp::Ordering;

use num_bigint::BigInt;

use super::accurate::{div_dd, dot2_fast, mat_point_dd, orient3d_dd, U};
use super::plane_cut::{round_quotient, split, sum_terms};
use super::{M4, P3};

/// Filter bounds are accepted below this fraction of the endpoints' screen size.
const FILTER: f64 = 1.0 / (1u64 << 60) as f64;

/// A double-double with a bound on its distance from the exact value.
type Dd = (f64, f64);

/// The screen point (x, y) of the crossing of segment a→b with the plane through `refs`
/// (a and b strictly on opposite sides, exactly), seen through `m` (x'/w', y'/w'; w' = 1 for
/// an orthographic M). Symmetric: b→a gives the same bits.
pub(crate) fn plane_crossing(refs: &[P3; 3], a: &P3, b: &P3, m: &M4) -> [f64; 2] {
    let (a, b) = if key(a) <= key(b) { (a, b) } else { (b, a) };
    filtered_crossing(refs, a, b, m).unwrap_or_else(|| exact_crossing(refs, a, b, m))
}

fn key(p: &P3) -> [u64; 3] {
    [p.x.to_bits(), p.y.to_bits(), p.z.to_bits()]
}

/// s = (A·h_b − B·h_a) / (A·w_b − B·w_a) with A, B the exact orient3d values of a and b: the
/// homogeneous image of the crossing (b·A − a·B)/(A − B) up to the factor A − B.
fn filtered_crossing(refs: &[P3; 3], a: &P3, b: &P3, m: &M4) -> Option<[f64; 2]> {
    let da = orient3d_dd(&refs[0], &refs[1], &refs[2], a);
    let db = orient3d_dd(&refs[0], &refs[1], &refs[2], b);
    let (ha, hb) = (mat_point_dd(m, a), mat_point_dd(m, b));
    // Σ|m_ij p_j| bounds the products' size; dot2's error is under 16u² of it.
    let (ea, eb) = (row_error(m, a), row_error(m, b));
    // Relative errors of A and B (their signs are exact and opposite).
    let (aa, ab) = (da.hi.abs(), db.hi.abs());
    let eta = da.err / aa + db.err / ab;
    // Written so that a NaN also fails.
    if eta.is_nan() || eta >= FILTER {
        return None;
    }
    let (ca, cb) = ((db.hi, db.lo), (da.hi, da.lo)); // s = (A h_b − B h_a)/(A w_b − B w_a)
    let lin = |r: usize| -> Dd {
        dot2_fast(
            &[cb.0, cb.1, cb.0, -ca.0, -ca.1, -ca.0],
            &[hb[r].0, hb[r].0, hb[r].1, ha[r].0, ha[r].0, ha[r].1],
        )
    };
    let (nx, ny, den) = (lin(0), lin(1), lin(3));
    // The size of the endpoints' screen points times den, and the errors of h (dot2) and of
    // the combination (dot2 of six terms: γ(6)² of its terms' size).
    let sa = (ha[0].0.abs().max(ha[1].0.abs())) / ha[3].0.abs();
    let sb = (hb[0].0.abs().max(hb[1].0.abs())) / hb[3].0.abs();
    let size = sa.max(sb);
    let terms = aa * (hb[0].0.abs() + hb[1].0.abs() + hb[3].0.abs())
        + ab * (ha[0].0.abs() + ha[1].0.abs() + ha[3].0.abs());
    let err = eta * 2.0 * terms + (aa * eb + ab * ea) * 2.0 + 64.0 * U * U * terms;
    // s is a weighted mean of the endpoints' screen points (A, −B, w_a, w_b > 0), so
    // |s| ≤ size, and errors δN, δD ≤ err move it by at most err·(1 + size)/den.
    let d = den.0.abs();
    if !(d > 0.0 && err * (1.0 + size) / d <= FILTER * size && size.is_finite()) {
        return None;
    }
    Some([div_dd(nx, den), div_dd(ny, den)])
}

/// 16u²·Σ|m_ij p_j| over the rows, a bound on [`mat_point_dd`]'s error in any coordinate.
fn row_error(m: &M4, p: &P3) -> f64 {
    let v = [p.x.abs(), p.y.abs(), p.z.abs(), 1.0];
    let most = (0..4)
        .map(|r| (0..4).map(|c| m[(r, c)].abs() * v[c]).sum::<f64>())
        .fold(0.0, f64::max);
    16.0 * U * U * most * (1.0 + 8.0 * U)
}

/// The exact crossing in big integers, each screen coordinate rounded once.
fn exact_crossing(refs: &[P3; 3], a: &P3, b: &P3, m: &M4) -> [f64; 2] {
    let (ia, ea) = exact_orient(refs, a);
    let (ib, eb) = exact_orient(refs, b);
    let ha = exact_h(m, a);
    let hb = exact_h(m, b);
    let comb = |r: usize| {
        sum_terms(&[
            (&ia * &hb[r].0, ea + hb[r].1),
            (-(&ib * &ha[r].0), eb + ha[r].1),
        ])
    };
    let (den, ed) = comb(3);
    std::array::from_fn(|r| {
        let (num, en) = comb(r);
        round_quotient(&num, &den, en - ed)
    })
}

/// orient3d(refs, p) exactly, as an integer times 2^e.
fn exact_orient(refs: &[P3; 3], p: &P3) -> (BigInt, i32) {
    let pts = [refs[0], refs[1], refs[2], *p];
    let e = pts
        .iter()
        .flat_map(|q| q.iter().copied())
        .filter(|v| *v != 0.0)
        .map(|v| split(v).1)
        .min()
        .unwrap_or(0);
    let int = |v: f64| {
        let (mv, ev) = split(v);
        BigInt::from(mv) << ((ev - e) as u32)
    };
    let d: Vec<[BigInt; 3]> = (0..3)
        .map(|i| std::array::from_fn(|k| int(pts[i][k]) - int(p[k])))
        .collect();
    let det = &d[0][0] * (&d[1][1] * &d[2][2] - &d[1][2] * &d[2][1])
        + &d[1][0] * (&d[2][1] * &d[0][2] - &d[2][2] * &d[0][1])
        + &d[2][0] * (&d[0][1] * &d[1][2] - &d[0][2] * &d[1][1]);
    (det, 3 * e)
}

/// M·(p, 1) exactly: each coordinate an integer times 2^e.
fn exact_h(m: &M4, p: &P3) -> [(BigInt, i32); 4] {
    let v = [p.x, p.y, p.z, 1.0];
    std::array::from_fn(|r| {
        let terms: Vec<(BigInt, i32)> = (0..4)
            .map(|c| {
                let (mm, em) = split(m[(r, c)]);
                let (mv, ev) = split(v[c]);
                (BigInt::from(mm) * mv, em + ev)
            })
            .collect();
        sum_terms(&terms)
    })
}

/// Which side of the near plane w' = near the point `p` lies on, exactly: Greater in front.
/// `h` is [`mat_point_dd`] of `p` (its w' decides most points; big integers the rest).
pub(crate) fn near_side(m: &M4, p: &P3, h: &[Dd; 4], near: f64) -> Ordering {
    let w = h[3];
    let approx = (w.0 - near) + w.1;
    // w is within row_error of the exact w'; the two roundings here are under u each of the
    // values rounded.
    let bound = row_error(m, p) + 2.0 * U * ((w.0 - near).abs() + approx.abs());
    if approx.abs() > 2.0 * bound && approx.is_finite() {
        return approx.partial_cmp(&0.0).unwrap_or(Ordering::Equal);
    }
    let (hw, ew) = exact_h(m, p)[3].clone();
    let (nm, en) = split(near);
    let (diff, _) = sum_terms(&[(hw, ew), (-BigInt::from(nm), en)]);
    diff.sign().cmp(&num_bigint::Sign::NoSign)
}

/// Where segment a→b crosses the near plane w' = near (a in front or on it, b behind,
/// exactly): the screen point (x'/near, y'/near, z'/near) and the world point, each coordinate
/// the exact value rounded once.
pub(crate) fn near_crossing(a: &P3, b: &P3, m: &M4, near: f64) -> ([f64; 3], P3) {
    let ha = exact_h(m, a);
    let hb = exact_h(m, b);
    let (nm, en) = split(near);
    let dist = |h: &(BigInt, i32)| sum_terms(&[(h.0.clone(), h.1), (-BigInt::from(nm), en)]);
    let (da, ea) = dist(&ha[3]);
    let (db, eb) = dist(&hb[3]);
    // The crossing is (da·b − db·a) / (da − db), in world and in homogeneous coordinates.
    let (den, ed) = sum_terms(&[(da.clone(), ea), (-db.clone(), eb)]);
    let comb = |xa: &(BigInt, i32), xb: &(BigInt, i32)| {
        sum_terms(&[(&da * &xb.0, ea + xb.1), (-(&db * &xa.0), eb + xa.1)])
    };
    // Screen: divided by w' = near as well.
    let den_s = &den * BigInt::from(nm);
    let screen = std::array::from_fn(|r| {
        let (num, e) = comb(&ha[r], &hb[r]);
        round_quotient(&num, &den_s, e - ed - en)
    });
    let world = |k: usize| {
        let (ma, xa) = split(a[k]);
        let (mb, xb) = split(b[k]);
        let (num, e) = comb(&(BigInt::from(ma), xa), &(BigInt::from(mb), xb));
        round_quotient(&num, &den, e - ed)
    };
    (screen, P3::new(world(0), world(1), world(2)))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The crossing through the exact path agrees with the filter where both apply.
    #[test]
    fn filter_and_exact_path_agree() {
        let refs = [
            P3::new(0., 0., 0.),
            P3::new(1., 0., 0.1),
            P3::new(0., 1., 0.2),
        ];
        let m = M4::new(
            0.8, 0.6, 0., 1.5, -0.6, 0.8, 0., -2.5, 0., 0., 0., 1., 0.1, 0.2, -1., 7.,
        );
        let (a, b) = (P3::new(0.3, 0.4, 1.0), P3::new(0.5, 0.2, -1.0));
        let f = filtered_crossing(&refs, &a, &b, &m).unwrap();
        let x = exact_crossing(&refs, &a, &b, &m);
        for k in 0..2 {
            assert!(
                (f[k] - x[k]).abs() <= f64::EPSILON * x[k].abs(),
                "{f:?} {x:?}"
            );
        }
        assert_eq!(
            plane_crossing(&refs, &a, &b, &m),
            plane_crossing(&refs, &b, &a, &m)
        );
    }

    #[test]
    fn orient3d_dd_is_within_its_bound_of_the_exact_value() {
        let mut rng = crate::geom::rng::XorShift::new(31);
        let mut worst = 0.0f64;
        for k in 0..3000 {
            let s = [1.0, 1e3, 1e-3, 1e9][k % 4];
            let p = |r: &mut crate::geom::rng::XorShift| {
                P3::new(r.range(-s, s), r.range(-s, s), r.range(-s, s))
            };
            let refs = [p(&mut rng), p(&mut rng), p(&mut rng)];
            // Points on the plane (rounded), near it, and anywhere.
            let (u, v) = (rng.unit(), rng.unit());
            let on = refs[0] + (refs[1] - refs[0]) * u + (refs[2] - refs[0]) * v;
            for q in [on, on * (1.0 + 1e-12), p(&mut rng)] {
                let dd = orient3d_dd(&refs[0], &refs[1], &refs[2], &q);
                let (x, e) = exact_orient(&refs, &q);
                let (mh, eh) = split(dd.hi);
                let (ml, el) = split(dd.lo);
                let (diff, ed) =
                    sum_terms(&[(x, e), (-BigInt::from(mh), eh), (-BigInt::from(ml), el)]);
                let off = round_quotient(&diff, &BigInt::from(1), ed).abs();
                assert!(off <= dd.err, "{off:e} > {:e} at {k}", dd.err);
                worst = worst.max(off / dd.err);
            }
        }
        assert!(worst < 1.0, "{worst}");
    }

    #[test]
    fn tiny_angles_take_the_exact_path() {
        // A plane tilted by 1e-15 rad, crossed by a segment nearly in it.
        let refs = [
            P3::new(0., 0., 0.),
            P3::new(1., 0., 1e-15),
            P3::new(0., 1., 0.),
        ];
        let m = M4::identity();
        let (a, b) = (P3::new(0., 0.5, 1e-16), P3::new(1., 0.5, 0.));
        let p = plane_crossing(&refs, &a, &b, &m);
        // Exact: z = 1e-15·x on the plane; z = 1e-16·(1 − x) on the segment → x = 1/11 (in
        // the f64 inputs' exact values).
        assert!((p[0] - 1.0 / 11.0).abs() < 1e-3, "{p:?}");
        assert_eq!(p[1], 0.5);
    }

    #[test]
    fn near_crossings_are_exact() {
        let m = M4::new(
            1., 0., 0., 0., 0., 1., 0., 0., 0., 0., 0., 1., 0., 0., -1., 0.,
        );
        // w' = −z: a at depth 2 (in front of near 1), b at depth −2 (behind).
        let (a, b) = (P3::new(1., 0., -2.), P3::new(3., 0., 2.));
        let side = |p: &P3| near_side(&m, p, &mat_point_dd(&m, p), 1.0);
        assert_eq!(side(&a), Ordering::Greater);
        assert_eq!(side(&b), Ordering::Less);
        assert_eq!(side(&P3::new(0., 0., -1.)), Ordering::Equal);
        let (s, w) = near_crossing(&a, &b, &m, 1.0);
        assert_eq!(w, P3::new(1.5, 0., -1.));
        assert_eq!(s, [1.5, 0., 1.]);
    }
}
