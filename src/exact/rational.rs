//! Exact rational numbers and screen points for the exact check, with f64 bounds that are
//! only ever used to skip work (never to decide an answer).

pub(crate) use super::fraction::Q;

/// An exact screen point.
#[derive(Debug, Clone, PartialEq, Eq, PartialOrd, Ord)]
pub(crate) struct QPt {
    /// x.
    pub x: Q,
    /// y.
    pub y: Q,
}

/// The exact value of a finite f64.
pub(crate) fn q(x: f64) -> Q {
    Q::from_float(x).unwrap_or_else(|| Q::int(0))
}

/// An f64 interval surely holding `v` (its f64 approximation, within a few ulps, widened by
/// sixteen ulps each way).
pub(crate) fn bounds(v: &Q) -> [f64; 2] {
    let f = v.to_f64().unwrap_or(f64::NAN);
    if !f.is_finite() {
        return [f64::NEG_INFINITY, f64::INFINITY];
    }
    let d = 16.0 * ulp(f);
    [f - d, f + d]
}

fn ulp(f: f64) -> f64 {
    let a = f.abs();
    if a < f64::MIN_POSITIVE {
        return f64::MIN_POSITIVE * f64::EPSILON;
    }
    let next = f64::from_bits(a.to_bits() + 1);
    next - a
}

/// Exact sign of the turn a → b → c: from the f64 approximations where their error bound
/// settles it, else in exact arithmetic.
pub(crate) fn orient(a: &QPt, b: &QPt, c: &QPt) -> i32 {
    let f = |v: &Q| v.to_f64().unwrap_or(f64::NAN);
    let (ax, ay, bx, by, cx, cy) = (f(&a.x), f(&a.y), f(&b.x), f(&b.y), f(&c.x), f(&c.y));
    let (t1, t2) = ((bx - ax) * (cy - ay), (cx - ax) * (by - ay));
    let v = t1 - t2;
    // Each coordinate is within 4 ulps (~1e-15 relative) of its value: each difference is
    // off by ~1e-15 of its ends' size, each product by that times the other factor, the
    // sum by an ulp of the terms; 1e-13 of those sizes is far above the total.
    let bound = 1e-13
        * (t1.abs()
            + t2.abs()
            + (bx - ax).abs() * (cy.abs() + ay.abs())
            + (cy - ay).abs() * (bx.abs() + ax.abs())
            + (cx - ax).abs() * (by.abs() + ay.abs())
            + (by - ay).abs() * (cx.abs() + ax.abs()));
    if v.is_finite() && bound.is_finite() && v.abs() > bound {
        return if v > 0.0 { 1 } else { -1 };
    }
    let v = (&b.x - &a.x) * (&c.y - &a.y) - (&c.x - &a.x) * (&b.y - &a.y);
    sign(&v)
}

/// Sign of a rational (-1, 0, +1).
pub(crate) fn sign(v: &Q) -> i32 {
    if v.is_zero() {
        0
    } else if v.is_positive() {
        1
    } else {
        -1
    }
}

/// Exact winding number of the closed ring `r` around `p` (p must not lie on the ring).
pub(crate) fn winding(r: &[QPt], p: &QPt) -> i32 {
    let n = r.len();
    let mut w = 0;
    for i in 0..n {
        let (a, b) = (&r[i], &r[(i + 1) % n]);
        if a.y <= p.y {
            if b.y > p.y && orient(a, b, p) > 0 {
                w += 1;
            }
        } else if b.y <= p.y && orient(a, b, p) < 0 {
            w -= 1;
        }
    }
    w
}

/// f64 bounds [xmin, xmax, ymin, ymax] surely holding the points.
pub(crate) fn box_of<'a>(pts: impl IntoIterator<Item = &'a QPt>) -> [f64; 4] {
    let mut b = [
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::INFINITY,
        f64::NEG_INFINITY,
    ];
    for p in pts {
        let (x, y) = (bounds(&p.x), bounds(&p.y));
        b = [
            b[0].min(x[0]),
            b[1].max(x[1]),
            b[2].min(y[0]),
            b[3].max(y[1]),
        ];
    }
    b
}

/// True when two f64 boxes [xmin, xmax, ymin, ymax] share a point.
pub(crate) fn boxes_meet(a: &[f64; 4], b: &[f64; 4]) -> bool {
    a[0] <= b[1] && b[0] <= a[1] && a[2] <= b[3] && b[2] <= a[3]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn exact_values_and_safe_bounds() {
        let third = q(1.0) / q(3.0);
        let b = bounds(&third);
        assert!(b[0] < 1.0 / 3.0 && 1.0 / 3.0 < b[1]);
        assert!(q(0.1) * q(10.0) != q(1.0), "0.1 is not 1/10 in binary");
        let p = |x: f64, y: f64| QPt { x: q(x), y: q(y) };
        let sq = [p(0., 0.), p(1., 0.), p(1., 1.), p(0., 1.)];
        assert_eq!(winding(&sq, &p(0.5, 0.5)), 1);
        assert_eq!(winding(&sq, &p(1.5, 0.5)), 0);
        assert_eq!(orient(&sq[0], &sq[1], &sq[2]), 1);
    }
}
