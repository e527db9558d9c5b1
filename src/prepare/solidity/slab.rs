//! A plate's slab: the range of n·x over its corners (n its Newell normal, taken as exact),
//! with the rounding of every computed product bounded, so that "strictly beyond the slab"
//! is an exact statement; and points bounding the part of a triangle that lies inside it.
//!
//! Every point of the plate's triangles is a convex combination of its corners, so n·x lies
//! in the slab for all of them, planar or not.

use crate::geom::{P3, V3};

/// The slab of a set of points along a direction.
pub(super) struct Slab {
    n: V3,
    lo: f64,
    hi: f64,
}

/// A bound on the rounding of `n·p` (three products and two sums: at most γ₃ = 3u/(1-3u)
/// ≈ 3.4e-16 of Σ|n_k p_k|) plus that of adding or subtracting the bound itself (u of the
/// sum), with room to spare: a computed n·p moved away by this margin is on the far side of
/// the exact value.
fn margin(n: &V3, p: &P3) -> f64 {
    1e-15 * (n.x * p.x).abs() + 1e-15 * (n.y * p.y).abs() + 1e-15 * (n.z * p.z).abs()
}

impl Slab {
    /// The slab of `pts` along `n`, widened by each point's rounding margin.
    pub(super) fn of(pts: &[P3], n: V3) -> Slab {
        let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
        for p in pts {
            let (d, e) = (n.dot(&p.coords), margin(&n, p));
            lo = lo.min(d - e);
            hi = hi.max(d + e);
        }
        Slab { n, lo, hi }
    }

    /// 1 when `p` lies strictly beyond the slab's high side, -1 beyond its low side, else 0
    /// (inside, or too near to tell).
    pub(super) fn side(&self, p: &P3) -> i32 {
        let (d, e) = (self.n.dot(&p.coords), margin(&self.n, p));
        if d - e > self.hi {
            1
        } else if d + e < self.lo {
            -1
        } else {
            0
        }
    }

    /// Every corner of `u` strictly beyond the slab, on one side: `u` cannot meet anything
    /// inside it.
    pub(super) fn beyond(&self, u: &[P3; 3]) -> bool {
        let s = self.side(&u[0]);
        s != 0 && self.side(&u[1]) == s && self.side(&u[2]) == s
    }

    /// Points whose hull, each point widened to a cube of half-side `pad`, holds the part of
    /// `u` inside the slab, where some corners of `u` lie beyond it on one side and the
    /// others are not beyond it (None otherwise). For a corner a not beyond and a corner c
    /// beyond, the slab ends at a + λ(c − a) along ac; λ is bounded above (numerator rounded
    /// up, denominator down, 1e-12 relative to spare), so the hull of the corners not beyond
    /// and those points holds the part; `pad`, 1e-12 of the coordinates' size, covers the
    /// rounding of the points.
    pub(super) fn part(&self, u: &[P3; 3]) -> Option<(Vec<P3>, f64)> {
        let sides = u.map(|p| self.side(&p));
        let beyond = sides.iter().copied().find(|&s| s != 0)?;
        if sides.contains(&-beyond) || !sides.contains(&0) {
            return None;
        }
        let dot = |p: &P3| (self.n.dot(&p.coords), margin(&self.n, p));
        let mut pts = Vec::with_capacity(4);
        let mut size = 0.0f64;
        for (a, _) in u.iter().zip(sides).filter(|(_, s)| *s == 0) {
            pts.push(*a);
            size = size.max(a.coords.amax());
            let (da, ea) = dot(a);
            for (c, _) in u.iter().zip(sides).filter(|(_, s)| *s != 0) {
                let (dc, ec) = dot(c);
                let (num, den) = if beyond > 0 {
                    (self.hi - (da - ea), (dc - ec) - (da + ea))
                } else {
                    ((da + ea) - self.lo, (da - ea) - (dc + ec))
                };
                if !(num >= 0.0 && den > 0.0) {
                    return None;
                }
                let lambda = (num / den * (1.0 + 1e-12)).min(1.0);
                let end = a + (c - a) * lambda;
                pts.push(end);
                size = size.max(end.coords.amax()).max(c.coords.amax());
            }
        }
        let pad = 1e-12 * size + f64::MIN_POSITIVE;
        pts.iter()
            .all(|p| p.iter().all(|x| x.is_finite()))
            .then_some((pts, pad))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sides_and_the_part_inside() {
        // The unit square at z = 0, turned a little so that nothing is exact.
        let r = nalgebra::Rotation3::from_euler_angles(0.01, 0.02, 0.3);
        let up = |x: f64, y: f64, z: f64| r * P3::new(x, y, z);
        let sq = [
            up(0., 0., 0.),
            up(1., 0., 0.),
            up(1., 1., 0.),
            up(0., 1., 0.),
        ];
        let n = r * V3::z();
        let slab = Slab::of(&sq, n);
        assert!(sq.iter().all(|p| slab.side(p) == 0));
        assert_eq!(slab.side(&up(0.5, 0.5, 1e-3)), 1);
        assert_eq!(slab.side(&up(0.5, 0.5, -1e-3)), -1);
        assert!(slab.beyond(&[up(0., 0., 1.), up(1., 0., 2.), up(0., 1., 0.5)]));
        assert!(!slab.beyond(&[up(0., 0., 1.), up(1., 0., -2.), up(0., 1., 0.5)]));
        // A wall standing on the edge from (0,0) to (1,0): its part in the slab is a sliver
        // along that edge.
        let wall = [sq[0], sq[1], up(0.5, 0.0, 2.0)];
        let (pts, pad) = slab.part(&wall).expect("a part");
        assert_eq!(pts.len(), 4);
        assert!(pad > 0.0 && pad < 1e-11);
        assert_eq!((pts[0], pts[2]), (sq[0], sq[1]));
        for (end, from) in [(pts[1], sq[0]), (pts[3], sq[1])] {
            let d = end - from;
            assert!(d.norm() < 1e-9, "{d:?}");
            // On or just beyond the slab's top, along the wall.
            assert!(n.dot(&d) >= 0.0);
        }
        // Straddling the slab, or wholly beyond it: no part.
        assert!(slab
            .part(&[up(0., 0., 1.), up(1., 0., -2.), sq[2]])
            .is_none());
        assert!(slab
            .part(&[up(0., 0., 1.), up(1., 0., 2.), up(0., 1., 0.5)])
            .is_none());
    }
}
