//! A point's side of a section plane (point P, normal N) decided exactly, and where a segment
//! crosses the plane: the exact crossing rounded once to the nearest f64 point.
//!
//! The side is the sign of (v − P)·N. An f64 evaluation with an error bound settles almost
//! every point; the rest are decided in integers: every f64 is m·2^e, so the dot product is a
//! sum of six products m·m'·2^(e+e') that big integers hold exactly. The crossing of a segment
//! a→b with the plane, da = (a − P)·N < 0 < db = (b − P)·N, is x = (b·da − a·db) / (da − db)
//! (symmetric in a and b: both faces of an edge get the very same point), each coordinate a
//! quotient of big integers rounded to nearest, ties to even.

use std::cmp::Ordering;

use num_bigint::BigInt;
use num_traits::{Signed, Zero};

use super::{P3, V3};

/// A section plane: the points v with (v − point)·normal > 0 are removed.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct CutPlane {
    /// A point of the plane.
    pub point: P3,
    /// The normal, toward the removed side (non-zero, finite).
    pub normal: V3,
}

/// An f64 as an integer times a power of two (exact).
pub(crate) fn split(x: f64) -> (i64, i32) {
    if x == 0.0 {
        return (0, 0);
    }
    let bits = x.to_bits();
    let sign = if bits >> 63 == 0 { 1 } else { -1 };
    let exp = ((bits >> 52) & 0x7ff) as i32;
    let frac = (bits & ((1 << 52) - 1)) as i64;
    let (m, e) = if exp == 0 {
        (frac, -1074)
    } else {
        (frac | (1 << 52), exp - 1075)
    };
    (sign * m, e)
}

/// Σ of terms m·2^e, exactly, as an integer times 2^emin (emin the least exponent).
pub(crate) fn sum_terms(terms: &[(BigInt, i32)]) -> (BigInt, i32) {
    let emin = terms
        .iter()
        .filter(|(m, _)| !m.is_zero())
        .map(|(_, e)| *e)
        .min()
        .unwrap_or(0);
    let mut s = BigInt::zero();
    for (m, e) in terms {
        if !m.is_zero() {
            s += m << ((e - emin) as u32);
        }
    }
    (s, emin)
}

/// (v − P)·N exactly, as an integer times 2^e.
fn exact_distance(v: &P3, pl: &CutPlane) -> (BigInt, i32) {
    let mut terms = Vec::with_capacity(6);
    for k in 0..3 {
        let (mn, en) = split(pl.normal[k]);
        let (mv, ev) = split(v[k]);
        let (mp, ep) = split(pl.point[k]);
        terms.push((BigInt::from(mv) * mn, ev + en));
        terms.push((-(BigInt::from(mp) * mn), ep + en));
    }
    sum_terms(&terms)
}

/// The side of `v`: Greater on the removed side, Less on the kept side, Equal on the plane.
pub(crate) fn side(v: &P3, pl: &CutPlane) -> Ordering {
    let mut d = 0.0;
    let mut mag = 0.0;
    for k in 0..3 {
        d += (v[k] - pl.point[k]) * pl.normal[k];
        mag += (v[k].abs() + pl.point[k].abs()) * pl.normal[k].abs();
    }
    // Three subtractions, three products and two sums: under 8 ulps of `mag`; a bound far
    // above the smallest normal keeps underflow out of the argument.
    let bound = mag * 1e-14;
    if d.abs() > bound && bound > 1e-280 {
        return d.partial_cmp(&0.0).unwrap_or(Ordering::Equal);
    }
    exact_distance(v, pl)
        .0
        .sign()
        .cmp(&num_bigint::Sign::NoSign)
}

/// The point where segment a→b crosses the plane, `a` and `b` strictly on opposite sides:
/// the exact crossing, each coordinate rounded once to the nearest f64.
pub(crate) fn crossing(a: &P3, b: &P3, pl: &CutPlane) -> P3 {
    let (da, ea) = exact_distance(a, pl);
    let (db, eb) = exact_distance(b, pl);
    // Both at one exponent: da = A·2^e, db = B·2^e.
    let e = ea.min(eb);
    let big_a = da << ((ea - e) as u32);
    let big_b = db << ((eb - e) as u32);
    let den = &big_a - &big_b;
    let mut out = [0.0; 3];
    for (k, o) in out.iter_mut().enumerate() {
        let (mb, xb) = split(b[k]);
        let (ma, xa) = split(a[k]);
        // x = (b·A − a·B) / (A − B): the 2^e cancels.
        let (num, e0) = sum_terms(&[
            (BigInt::from(mb) * &big_a, xb),
            (-(BigInt::from(ma) * &big_b), xa),
        ]);
        *o = round_quotient(&num, &den, e0);
    }
    P3::new(out[0], out[1], out[2])
}

/// num / den · 2^e rounded to the nearest f64 (ties to even); den ≠ 0, the value finite.
pub(crate) fn round_quotient(num: &BigInt, den: &BigInt, e: i32) -> f64 {
    if num.is_zero() {
        return 0.0;
    }
    let negative = num.is_negative() != den.is_negative();
    let (n, d) = (num.abs(), den.abs());
    // Scale so that the integer quotient has 55 or 56 bits.
    let k = n.bits() as i64 - d.bits() as i64;
    let sh = 55 - k;
    let (q, r) = if sh >= 0 {
        let n2: BigInt = &n << (sh as u32);
        (&n2 / &d, &n2 % &d)
    } else {
        let d2: BigInt = &d << ((-sh) as u32);
        (&n / &d2, &n % &d2)
    };
    let sticky = !r.is_zero();
    let bq = q.bits() as i64;
    let mut drop = bq - 53;
    let mut e2 = e as i64 - sh + drop;
    if e2 < -1074 {
        drop += -1074 - e2;
        e2 = -1074;
    }
    let mant = round_shift(&q, drop, sticky);
    let (mut mant, mut e2) = (mant, e2);
    if mant >= 1u64 << 53 {
        mant >>= 1;
        e2 += 1;
    }
    let bits = if mant < 1u64 << 52 {
        // Subnormal (e2 is -1074 here), or zero.
        mant
    } else {
        let biased = e2 + 52 + 1023;
        if biased >= 2047 {
            return if negative {
                f64::NEG_INFINITY
            } else {
                f64::INFINITY
            };
        }
        ((biased as u64) << 52) | (mant & ((1u64 << 52) - 1))
    };
    let x = f64::from_bits(bits);
    if negative {
        -x
    } else {
        x
    }
}

/// q / 2^drop rounded to nearest, ties to even, `sticky` saying whether bits below q were
/// lost already (then a tie is not one).
fn round_shift(q: &BigInt, drop: i64, sticky: bool) -> u64 {
    use num_traits::ToPrimitive;
    if drop <= 0 {
        return (q << ((-drop) as u32)).to_u64().unwrap_or(u64::MAX);
    }
    if drop as u64 > q.bits() + 1 {
        return 0;
    }
    let drop = drop as u32;
    let kept: BigInt = q >> drop;
    let rest: BigInt = q - (&kept << drop);
    let half: BigInt = BigInt::from(1) << (drop - 1);
    let mut m = kept.to_u64().unwrap_or(u64::MAX);
    match rest.cmp(&half) {
        Ordering::Greater => m += 1,
        Ordering::Equal if sticky || m & 1 == 1 => m += 1,
        _ => {}
    }
    m
}

#[cfg(test)]
mod tests {
    use super::*;

    fn plane(p: [f64; 3], n: [f64; 3]) -> CutPlane {
        CutPlane {
            point: P3::new(p[0], p[1], p[2]),
            normal: V3::new(n[0], n[1], n[2]),
        }
    }

    #[test]
    fn sides_are_exact_near_the_plane() {
        let pl = plane([0.5, 0., 0.], [1., 0., 0.]);
        assert_eq!(side(&P3::new(0.5, 7., -3.), &pl), Ordering::Equal);
        let up = f64::from_bits(0.5f64.to_bits() + 1);
        let down = f64::from_bits(0.5f64.to_bits() - 1);
        assert_eq!(side(&P3::new(up, 0., 0.), &pl), Ordering::Greater);
        assert_eq!(side(&P3::new(down, 0., 0.), &pl), Ordering::Less);
        // An oblique plane through (0.1, 0.2, 0.3) with normal (1, 1, 1): 0.1 + 0.2 + 0.3 is
        // not 0.6 in f64, but the exact sum decides.
        let ob = plane([0.1, 0.2, 0.3], [1., 1., 1.]);
        assert_eq!(side(&P3::new(0.1, 0.2, 0.3), &ob), Ordering::Equal);
        assert_eq!(side(&P3::new(0.3, 0.2, 0.1), &ob), Ordering::Equal);
        assert_eq!(side(&P3::new(0.2, 0.2, 0.2), &ob), Ordering::Greater);
    }

    #[test]
    fn crossings_are_the_exact_point_rounded_once() {
        let pl = plane([1e-9, 0., 0.], [1., 0., 0.]);
        let x = crossing(&P3::new(0., 0., 0.), &P3::new(1., 1., 3.), &pl);
        assert_eq!(x.x, 1e-9);
        assert_eq!(x.y, 1e-9);
        // 3e-9 rounded once from the exact 3 × (the f64 1e-9).
        let exact = 3.0 * 1e-9;
        assert!((x.z - exact).abs() <= f64::EPSILON * exact);
        // Symmetric: the same bits from either end.
        let y = crossing(&P3::new(1., 1., 3.), &P3::new(0., 0., 0.), &pl);
        assert_eq!(x, y);
        // Oblique: x + y + z = 1 on the segment (0,0,0)→(1,1,1) is (1/3, 1/3, 1/3).
        let ob = plane([1., 0., 0.], [1., 1., 1.]);
        let t = crossing(&P3::new(0., 0., 0.), &P3::new(1., 1., 1.), &ob);
        assert_eq!(t, P3::new(1. / 3., 1. / 3., 1. / 3.));
        // A midpoint: the exact (0.1 + 0.7) / 2 rounded once is f64's correctly rounded sum
        // halved (halving is exact).
        let mid = plane([0., 0., 0.], [1., 0., 0.]);
        let m = crossing(&P3::new(-1., 0.1, 0.), &P3::new(1., 0.7, 0.), &mid);
        assert_eq!(m.y, (0.1f64 + 0.7) / 2.0);
        assert_eq!(m.x, 0.0);
    }

    #[test]
    fn rounding_ties_to_even_and_subnormals() {
        // 1 + 2^-53 is a tie between 1 and 1 + 2^-52: to even, 1.
        let num = (BigInt::from(1) << 53) + 1;
        assert_eq!(round_quotient(&num, &(BigInt::from(1) << 53), 0), 1.0);
        // 1 + 3·2^-53 rounds up to 1 + 2^-51.
        let num = (BigInt::from(1) << 53) + 3;
        assert_eq!(
            round_quotient(&num, &(BigInt::from(1) << 53), 0),
            1.0 + 2f64.powi(-51)
        );
        assert_eq!(
            round_quotient(&BigInt::from(1), &BigInt::from(3), 0),
            1.0 / 3.0
        );
        assert_eq!(
            round_quotient(&BigInt::from(-2), &BigInt::from(3), 0),
            -2.0 / 3.0
        );
        assert_eq!(
            round_quotient(&BigInt::from(1), &BigInt::from(1), -1074),
            5e-324
        );
        assert_eq!(
            round_quotient(&BigInt::from(7), &BigInt::from(1), 10),
            7168.0
        );
    }
}
