//! Accurate floating-point sums with stated error bounds, from error-free transformations
//! (Dekker's product, Knuth's sum): the compensated dot product of a matrix row with a point
//! (Ogita, Rump and Oishi's Dot2) and orient3d's value to twice working precision. Pure IEEE
//! arithmetic (no FMA), so every machine gets the same bits.
//!
//! u = 2^-53 is the unit roundoff. Dot2 of n terms returns a value within u·|exact| +
//! γ(n)²·Σ|terms| of the exact sum, γ(n) = n·u / (1 − n·u): for a 4-term row, 1 ulp of the result
//! plus 2.6e-31 of the terms' magnitudes (no cancellation against a large translation).

/// Unit roundoff, 2^-53.
pub(crate) const U: f64 = f64::EPSILON / 2.0;

/// Magnitude above which Dekker's split could overflow (2^996): larger inputs are summed plainly.
const SPLIT_LIMIT: f64 = 6.696e299;

/// a + b = s + e exactly (Knuth).
#[inline]
pub(crate) fn two_sum(a: f64, b: f64) -> (f64, f64) {
    let s = a + b;
    let bb = s - a;
    (s, (a - (s - bb)) + (b - bb))
}

/// a = hi + lo with each half of 26 bits (Veltkamp).
#[inline]
fn split(a: f64) -> (f64, f64) {
    let c = 134_217_729.0 * a;
    let hi = c - (c - a);
    (hi, a - hi)
}

/// a · b = p + e exactly, for |a|, |b| below 2^996 and no underflow: by Dekker's splitting, or (`FMA`, only inside functions compiled with the
/// fma feature) by one fused multiply-add: the same exact error term either way, so the
/// same bits on every machine.
#[inline(always)]
fn two_prod_in<const FMA: bool>(a: f64, b: f64) -> (f64, f64) {
    let p = a * b;
    if FMA {
        return (p, a.mul_add(b, -p));
    }
    let (ah, al) = split(a);
    let (bh, bl) = split(b);
    (p, al * bl - (((p - ah * bh) - al * bh) - ah * bl))
}

/// True when this processor has fused multiply-add (checked once, then cached by std).
#[inline]
fn has_fma() -> bool {
    #[cfg(target_arch = "x86_64")]
    {
        std::arch::is_x86_feature_detected!("fma")
    }
    #[cfg(not(target_arch = "x86_64"))]
    {
        false
    }
}

/// Defines `$name` dispatching to `$body` compiled with fma where the processor has it.
macro_rules! with_fma {
    ($(#[$m:meta])* $vis:vis fn $name:ident($($arg:ident: $ty:ty),*) -> $ret:ty => $imp:ident) => {
        $(#[$m])*
        $vis fn $name($($arg: $ty),*) -> $ret {
            #[cfg(target_arch = "x86_64")]
            {
                #[target_feature(enable = "fma")]
                fn fast($($arg: $ty),*) -> $ret {
                    $imp::<true>($($arg),*)
                }
                if has_fma() {
                    // SAFETY: the processor has the fma feature (checked just above).
                    return unsafe { fast($($arg),*) };
                }
            }
            $imp::<false>($($arg),*)
        }
    };
}

/// Σ x_i·y_i by Dot2 ([`dot2_fast`]): within u·|exact| + γ(n)²·Σ|x_i·y_i| of the exact value, as a
/// double-double (hi, lo) whose sum carries it (hi alone: one more rounding, ½ ulp).
#[inline(always)]
fn dot2_in<const FMA: bool>(x: &[f64], y: &[f64]) -> (f64, f64) {
    let big = x.iter().chain(y).any(|v| v.abs() > SPLIT_LIMIT);
    if big {
        return (x.iter().zip(y).map(|(a, b)| a * b).sum(), 0.0);
    }
    let (mut p, mut s) = (0.0, 0.0);
    for (a, b) in x.iter().zip(y) {
        let (h, r) = two_prod_in::<FMA>(*a, *b);
        let (q, t) = two_sum(p, h);
        p = q;
        s += t + r;
    }
    two_sum(p, s)
}

/// The homogeneous image M·(p, 1) of a world point as double-doubles, each by [`dot2`]:
/// within γ(4)² ≤ 16u² (1.8e-31) of Σ|m_ij·p_j| of the exact value, so a large translation in M
/// no longer cancels the point's own digits.
pub(crate) fn mat_point_dd(m: &super::M4, p: &super::P3) -> [(f64, f64); 4] {
    mat_point_dd_fast(m, p)
}

with_fma!(fn mat_point_dd_fast(m: &super::M4, p: &super::P3) -> [(f64, f64); 4] => mat_point_dd_in);

#[inline(always)]
fn mat_point_dd_in<const FMA: bool>(m: &super::M4, p: &super::P3) -> [(f64, f64); 4] {
    let v = [p.x, p.y, p.z, 1.0];
    std::array::from_fn(|r| {
        let row = [m[(r, 0)], m[(r, 1)], m[(r, 2)], m[(r, 3)]];
        dot2_in::<FMA>(&row, &v)
    })
}

with_fma!(
    /// [`dot2`], with fused multiply-adds where the processor has them (the same bits).
    pub(crate) fn dot2_fast(x: &[f64], y: &[f64]) -> (f64, f64) => dot2_in
);

/// [`mat_point_dd`] rounded to doubles: within 1 ulp plus 1.8e-31·Σ|m_ij·p_j| of the exact value.
pub(crate) fn mat_point(m: &super::M4, p: &super::P3) -> [f64; 4] {
    mat_point_dd(m, p).map(|(hi, lo)| hi + lo)
}

/// (n.0 + n.1) / (d.0 + d.1) for double-doubles (d.0 ≠ 0): the quotient of the leading parts
/// corrected by the exact remainder, within 1 ulp of the exact quotient of the pairs.
pub(crate) fn div_dd(n: (f64, f64), d: (f64, f64)) -> f64 {
    let q = n.0 / d.0;
    if !q.is_finite() || n.0.abs() > SPLIT_LIMIT || d.0.abs() > SPLIT_LIMIT {
        return (n.0 + n.1) / (d.0 + d.1);
    }
    let (p, e) = two_prod_in::<false>(q, d.0);
    let r = (((n.0 - p) - e) + n.1 - q * d.1) / d.0;
    q + r
}

/// orient3d(a, b, c, d) (the determinant of a − d, b − d, c − d, robust's sign convention) as
/// a double-double (hi, lo) and a bound `err` on |hi + lo − exact|: 2048·u²·P,
/// P the permanent (Σ of the six products' magnitudes).
///
/// The nine differences are split exactly (two_sum: d = dh + dl, |dl| ≤ u|dh|); each of the
/// six products of high parts is four exact terms (two_prod three times). The first-order
/// terms of the low parts (under 3u of their product) are summed in f64 (error under 20u·3u·P);
/// the dropped second- and third-order ones are under (3u² + u³)·P. The 25 terms are summed
/// by Dot2's compensated sum, kept as the pair (hi, lo) (not rounded to one double): within
/// γ(24)² ≤ 580u² of their magnitudes (at most (1 + 4u)·P). So |hi + lo − exact| ≤ 650u²·P;
/// the bound allows 2048u²·P.
pub(crate) fn orient3d_dd(a: &super::P3, b: &super::P3, c: &super::P3, d: &super::P3) -> Dd3 {
    orient3d_dd_fast(a, b, c, d)
}

with_fma!(fn orient3d_dd_fast(a: &super::P3, b: &super::P3, c: &super::P3, d: &super::P3) -> Dd3 => orient3d_dd_in);

#[inline(always)]
fn orient3d_dd_in<const FMA: bool>(
    a: &super::P3,
    b: &super::P3,
    c: &super::P3,
    d: &super::P3,
) -> Dd3 {
    let diff = |p: &super::P3, k: usize| two_sum(p[k], -d[k]);
    let (ad, bd, cd) = (
        [diff(a, 0), diff(a, 1), diff(a, 2)],
        [diff(b, 0), diff(b, 1), diff(b, 2)],
        [diff(c, 0), diff(c, 1), diff(c, 2)],
    );
    // det = Σ sign · x · y · z over the six permutations.
    let triples: [(f64, [(f64, f64); 3]); 6] = [
        (1.0, [ad[0], bd[1], cd[2]]),
        (-1.0, [ad[0], bd[2], cd[1]]),
        (1.0, [bd[0], cd[1], ad[2]]),
        (-1.0, [bd[0], cd[2], ad[1]]),
        (1.0, [cd[0], ad[1], bd[2]]),
        (-1.0, [cd[0], ad[2], bd[1]]),
    ];
    let big = [a, b, c, d]
        .iter()
        .any(|p| p.iter().any(|v| v.abs() > 1e90));
    let mut terms = [0.0f64; 25];
    let mut n = 0;
    let mut perm = 0.0;
    let mut lows = 0.0;
    for (sign, [x, y, z]) in triples {
        let (p, e) = two_prod_in::<FMA>(y.0, z.0);
        let (q, f) = two_prod_in::<FMA>(x.0, p);
        let (g, h) = two_prod_in::<FMA>(x.0, e);
        for t in [q, f, g, h] {
            terms[n] = sign * t;
            n += 1;
        }
        lows += sign * (x.1 * y.0 * z.0 + x.0 * y.1 * z.0 + x.0 * y.0 * z.1);
        perm += (x.0 * y.0 * z.0).abs();
    }
    terms[n] = lows;
    let (mut s, mut comp) = (0.0, 0.0);
    for t in &terms[..=n] {
        let (q, r) = two_sum(s, *t);
        s = q;
        comp += r;
    }
    let (hi, lo) = two_sum(s, comp);
    let err = if big || !perm.is_finite() || (perm != 0.0 && perm < 1e-200) {
        f64::INFINITY
    } else {
        2048.0 * U * U * perm + f64::MIN_POSITIVE
    };
    Dd3 { hi, lo, err }
}

/// A value as hi + lo with a bound on its distance from the exact value.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Dd3 {
    /// The leading part.
    pub hi: f64,
    /// The trailing part (|lo| ≤ ½ ulp of hi).
    pub lo: f64,
    /// |hi + lo − exact| ≤ err.
    pub err: f64,
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::{orient3d, P3};

    #[test]
    fn error_free_parts_are_exact() {
        let (s, e) = two_sum(1.0, 1e-20);
        assert_eq!((s, e), (1.0, 1e-20));
        let x = 1.0 + f64::EPSILON;
        let (p, e) = two_prod_in::<false>(x, x);
        assert_eq!(two_prod_in::<true>(x, x), (p, e));
        // (1 + ε)² = 1 + 2ε + ε²: the ε² is the error term.
        assert_eq!(p, 1.0 + 2.0 * f64::EPSILON);
        assert_eq!(e, f64::EPSILON * f64::EPSILON);
    }

    #[test]
    fn dot2_does_not_cancel_against_a_translation() {
        // 4e9·(1 + 2^-40) − 4e9 + 1e-3: plain sums lose the small parts.
        let big = 4e9;
        let x = [big, -big, 1e-3];
        let y = [1.0 + 2f64.powi(-40), 1.0, 1.0];
        let (hi, lo) = dot2_fast(&x, &y);
        let exact = big * 2f64.powi(-40) + 1e-3;
        assert!(
            ((hi + lo) - exact).abs() <= 2.0 * U * exact,
            "{hi} {lo} {exact}"
        );
    }

    #[test]
    fn orient3d_dd_has_the_exact_sign_and_its_bound_holds() {
        let mut rng = crate::geom::rng::XorShift::new(7);
        for _ in 0..2000 {
            let mut p = || P3::new(rng.range(-1.0, 1.0), rng.range(-1.0, 1.0), rng.unit());
            let (a, b, c) = (p(), p(), p());
            // d nearly on the plane: a + s(b − a) + t(c − a) rounded.
            let (s, t) = (rng.unit(), rng.unit());
            let d = a + (b - a) * s + (c - a) * t;
            let v = orient3d_dd(&a, &b, &c, &d);
            // Dekker and fused multiply-add give the same bits.
            assert_eq!(orient3d_dd_in::<false>(&a, &b, &c, &d), v);
            assert_eq!(orient3d_dd_in::<true>(&a, &b, &c, &d), v);
            let exact = orient3d(&a, &b, &c, &d);
            if v.err < v.hi.abs() {
                assert_eq!(v.hi.signum(), exact.signum());
            }
            assert!(v.err.is_finite());
        }
    }
}
