//! Exact fractions of big integers, kept small without a gcd: the check's inputs are f64
//! (dyadic rationals), so stripping common factors of two keeps sums and products of them as
//! short as the exact values; divisions add odd denominators along short chains only. (A
//! full gcd after every operation, as general rationals do, cost 90% of the check's time.)

use std::cmp::Ordering;
use std::ops::{Add, AddAssign, Div, Mul, Neg, Sub};

use num_bigint::{BigInt, Sign};
use num_integer::Integer;
use num_traits::{One, ToPrimitive, Zero};

/// An exact rational n / d (d > 0), with its f64 approximation (within a few ulps) kept to
/// settle comparisons of clearly different values without multiplying big numbers.
#[derive(Debug, Clone)]
pub struct Q {
    n: BigInt,
    d: BigInt,
    approx: f64,
}

/// Relative gap between two approximations above which their order is certain (the
/// approximations are within 4 ulps, ~1e-15, of the values).
const APPROX_GAP: f64 = 1e-12;

/// Denominator size (bits) past which a fraction is reduced by its gcd.
const GCD_BITS: u64 = 1024;

impl Q {
    /// The integer `k`.
    pub fn int(k: i64) -> Q {
        Q::new(BigInt::from(k), BigInt::from(1))
    }

    fn new(n: BigInt, d: BigInt) -> Q {
        let mut q = Q { n, d, approx: 0.0 };
        q.approx = q.compute_f64();
        q
    }

    /// The exact value of a finite f64 (None for NaN or infinity).
    pub fn from_float(x: f64) -> Option<Q> {
        if !x.is_finite() {
            return None;
        }
        if x == 0.0 {
            return Some(Q::int(0));
        }
        let (m, e) = crate::prepare::solidity::decompose(x);
        let (n, d) = if e >= 0 {
            (BigInt::from(m) << (e as usize), BigInt::from(1))
        } else {
            (BigInt::from(m), BigInt::from(1) << ((-e) as usize))
        };
        Some(Q { n, d, approx: x })
    }

    /// True for zero.
    pub fn is_zero(&self) -> bool {
        self.n.is_zero()
    }

    /// True when above zero.
    pub fn is_positive(&self) -> bool {
        self.n.sign() == Sign::Plus
    }

    /// The nearest f64 within a few ulps (None never; Option for call-site symmetry).
    pub fn to_f64(&self) -> Option<f64> {
        Some(self.approx)
    }

    fn compute_f64(&self) -> f64 {
        let (nb, db) = (self.n.bits() as i64, self.d.bits() as i64);
        // Keep about 120 significant bits of each before converting.
        let sn = (nb - 120).max(0);
        let sd = (db - 120).max(0);
        let n = (&self.n >> (sn as usize)).to_f64().unwrap_or(f64::NAN);
        let d = (&self.d >> (sd as usize)).to_f64().unwrap_or(f64::NAN);
        n / d * 2f64.powi((sn - sd).clamp(-2000, 2000) as i32)
    }

    /// n / d before [`Q::norm`] (which sets the approximation).
    fn raw(n: BigInt, d: BigInt) -> Q {
        Q { n, d, approx: 0.0 }
    }

    /// Strips the factors of two common to n and d, and sets the approximation.
    fn norm(mut self) -> Q {
        if self.n.is_zero() {
            return Q::int(0);
        }
        let tz = self
            .n
            .trailing_zeros()
            .unwrap_or(0)
            .min(self.d.trailing_zeros().unwrap_or(0));
        if tz > 0 {
            self.n >>= tz as usize;
            self.d >>= tz as usize;
        }
        // Odd denominators from chains of divisions grow without bound: past GCD_BITS a gcd
        // costs less than the multiplications it saves.
        if self.d.bits() > GCD_BITS {
            let g = self.n.gcd(&self.d);
            if !g.is_one() {
                self.n /= &g;
                self.d /= &g;
            }
        }
        self.approx = self.compute_f64();
        self
    }
}

impl PartialEq for Q {
    fn eq(&self, o: &Q) -> bool {
        self.cmp(o) == Ordering::Equal
    }
}

impl Eq for Q {}

impl PartialOrd for Q {
    fn partial_cmp(&self, o: &Q) -> Option<Ordering> {
        Some(self.cmp(o))
    }
}

impl Ord for Q {
    fn cmp(&self, o: &Q) -> Ordering {
        let (a, b) = (self.approx, o.approx);
        let ok = |x: f64| x.abs() > 1e-200 && x.abs() < 1e200;
        if ok(a) && ok(b) {
            let gap = APPROX_GAP * a.abs().max(b.abs());
            if a < b - gap {
                return Ordering::Less;
            }
            if a > b + gap {
                return Ordering::Greater;
            }
        }
        if self.d == o.d {
            return self.n.cmp(&o.n);
        }
        (&self.n * &o.d).cmp(&(&o.n * &self.d))
    }
}

impl<'a> Add<&'a Q> for &'a Q {
    type Output = Q;
    fn add(self, o: &Q) -> Q {
        if self.d == o.d {
            return Q::raw(&self.n + &o.n, self.d.clone()).norm();
        }
        Q::raw(&self.n * &o.d + &o.n * &self.d, &self.d * &o.d).norm()
    }
}

impl<'a> Sub<&'a Q> for &'a Q {
    type Output = Q;
    fn sub(self, o: &Q) -> Q {
        self + &(-o)
    }
}

impl<'a> Mul<&'a Q> for &'a Q {
    type Output = Q;
    fn mul(self, o: &Q) -> Q {
        Q::raw(&self.n * &o.n, &self.d * &o.d).norm()
    }
}

impl<'a> Div<&'a Q> for &'a Q {
    type Output = Q;
    /// Panics on division by zero (callers divide by proven nonzero values).
    fn div(self, o: &Q) -> Q {
        assert!(!o.is_zero(), "exact division by zero");
        let (mut n, mut d) = (&self.n * &o.d, &self.d * &o.n);
        if d.sign() == Sign::Minus {
            n = -n;
            d = -d;
        }
        Q::raw(n, d).norm()
    }
}

impl Neg for &Q {
    type Output = Q;
    fn neg(self) -> Q {
        Q {
            n: -&self.n,
            d: self.d.clone(),
            approx: -self.approx,
        }
    }
}

impl Neg for Q {
    type Output = Q;
    fn neg(self) -> Q {
        Q {
            n: -self.n,
            d: self.d,
            approx: -self.approx,
        }
    }
}

/// The owned and mixed forms of a binary operator, through the by-reference one.
macro_rules! owned_ops {
    ($($tr:ident $f:ident),*) => {$(
        impl $tr<Q> for Q {
            type Output = Q;
            fn $f(self, o: Q) -> Q {
                (&self).$f(&o)
            }
        }
        impl<'a> $tr<&'a Q> for Q {
            type Output = Q;
            fn $f(self, o: &Q) -> Q {
                (&self).$f(o)
            }
        }
        impl<'a> $tr<Q> for &'a Q {
            type Output = Q;
            fn $f(self, o: Q) -> Q {
                self.$f(&o)
            }
        }
    )*};
}

owned_ops!(Add add, Sub sub, Mul mul, Div div);

impl AddAssign<&Q> for Q {
    fn add_assign(&mut self, o: &Q) {
        *self = &*self + o;
    }
}

impl AddAssign<Q> for Q {
    fn add_assign(&mut self, o: Q) {
        *self = &*self + &o;
    }
}

impl std::iter::Sum for Q {
    fn sum<I: Iterator<Item = Q>>(it: I) -> Q {
        it.fold(Q::int(0), |a, b| a + b)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn arithmetic_is_exact() {
        let q = |x: f64| Q::from_float(x).unwrap();
        let third = Q::int(1) / Q::int(3);
        assert_eq!(&third * &Q::int(3), Q::int(1));
        assert_eq!(q(0.5) + q(0.25), q(0.75));
        assert!(q(0.1) + q(0.2) != q(0.3));
        assert!(q(0.1) < q(0.2));
        assert_eq!(-q(2.5), q(-2.5));
        assert_eq!(q(-3.0) / q(-1.5), Q::int(2));
        assert_eq!((third.to_f64().unwrap() - 1.0 / 3.0).abs(), 0.0);
        assert_eq!(q(1e300).to_f64(), Some(1e300));
        assert_eq!(q(1e-300).to_f64(), Some(1e-300));
        // Sums of dyadics stay short: the denominator is the largest power of two.
        let s = q(1.0 / 1024.0) + q(3.0 / 8.0);
        assert_eq!(s.d, BigInt::from(1024));
    }
}
