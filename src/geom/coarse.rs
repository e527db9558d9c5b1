//! Bounds held in half the memory: f64 bounds rounded outward to f32, so that a test on the
//! coarse bounds passes wherever the same test on the exact bounds does (a prefilter; the
//! exact bounds decide after it).

/// The greatest f32 at most `x` (`x` itself where it is one; NaN stays NaN). An `x` below
/// the least finite f32 gives minus infinity, one above the greatest gives `f32::MAX`.
#[inline]
pub(crate) fn down(x: f64) -> f32 {
    let f = x as f32;
    if f64::from(f) > x {
        f.next_down()
    } else {
        f
    }
}

/// The least f32 at least `x` (`x` itself where it is one; NaN stays NaN). An `x` above
/// the greatest finite f32 gives infinity, one below the least gives `-f32::MAX`.
#[inline]
pub(crate) fn up(x: f64) -> f32 {
    let f = x as f32;
    if f64::from(f) < x {
        f.next_up()
    } else {
        f
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::rng::XorShift;

    #[test]
    fn rounding_is_outward_and_tight() {
        let mut rng = XorShift::new(35);
        let mut xs: Vec<f64> = (0..10_000)
            .map(|_| rng.range(-0.5, 0.5) * 10f64.powi(rng.below(80) as i32 - 40))
            .collect();
        xs.extend([
            0.0,
            -0.0,
            1.0,
            0.1,
            -0.1,
            1e300,
            -1e300,
            3.4e38,
            f64::MIN_POSITIVE,
        ]);
        xs.extend([f64::INFINITY, f64::NEG_INFINITY, f64::from(f32::MAX), 1e-50]);
        for x in xs {
            let (d, u) = (down(x), up(x));
            assert!(f64::from(d) <= x && x <= f64::from(u), "{x}: {d} {u}");
            if x.is_infinite() {
                assert_eq!((f64::from(d), f64::from(u)), (x, x));
                continue;
            }
            // Tight: no f32 strictly between the result and x.
            assert!(d == f32::MAX || f64::from(d.next_up()) > x, "{x}: {d}");
            assert!(u == -f32::MAX || f64::from(u.next_down()) < x, "{x}: {u}");
            if f64::from(x as f32) == x {
                assert_eq!((d, u), (x as f32, x as f32));
            }
        }
        assert!(down(f64::NAN).is_nan() && up(f64::NAN).is_nan());
    }
}
