//! Axis-aligned boxes: the paper's BOX (XL, YL, ZL, XH, YH, ZH), used for CBOX and INBOX.

use super::{M4, P3};

/// An axis-aligned box `[lo, hi]`. An empty box has `lo > hi` on some axis.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Box3 {
    /// (XL, YL, ZL)
    pub lo: P3,
    /// (XH, YH, ZH)
    pub hi: P3,
}

impl Box3 {
    /// The empty box (the identity of [`Box3::union`]).
    pub fn empty() -> Self {
        Box3 {
            lo: P3::new(f64::INFINITY, f64::INFINITY, f64::INFINITY),
            hi: P3::new(f64::NEG_INFINITY, f64::NEG_INFINITY, f64::NEG_INFINITY),
        }
    }

    /// The box with the given corners (not reordered).
    pub fn new(lo: P3, hi: P3) -> Self {
        Box3 { lo, hi }
    }

    /// The smallest box holding all `points`.
    pub fn from_points<'a>(points: impl IntoIterator<Item = &'a P3>) -> Self {
        let mut b = Box3::empty();
        for p in points {
            b.add_point(p);
        }
        b
    }

    /// Grows the box to hold `p`.
    pub fn add_point(&mut self, p: &P3) {
        for i in 0..3 {
            self.lo[i] = self.lo[i].min(p[i]);
            self.hi[i] = self.hi[i].max(p[i]);
        }
    }

    /// The smallest box holding both.
    pub fn union(&self, o: &Box3) -> Box3 {
        let mut b = *self;
        for i in 0..3 {
            b.lo[i] = b.lo[i].min(o.lo[i]);
            b.hi[i] = b.hi[i].max(o.hi[i]);
        }
        b
    }

    /// True when the box holds no point.
    pub fn is_empty(&self) -> bool {
        (0..3).any(|i| self.lo[i] > self.hi[i])
    }

    /// True when the box has positive extent on all three axes.
    pub fn has_interior(&self) -> bool {
        (0..3).all(|i| self.lo[i] < self.hi[i])
    }

    /// Closed containment of a point.
    pub fn contains(&self, p: &P3) -> bool {
        (0..3).all(|i| self.lo[i] <= p[i] && p[i] <= self.hi[i])
    }

    /// Open containment of a point (strictly inside).
    pub fn contains_strictly(&self, p: &P3) -> bool {
        (0..3).all(|i| self.lo[i] < p[i] && p[i] < self.hi[i])
    }

    /// Closed containment of another box.
    pub fn contains_box(&self, o: &Box3) -> bool {
        o.is_empty() || (0..3).all(|i| self.lo[i] <= o.lo[i] && o.hi[i] <= self.hi[i])
    }

    /// Edge lengths (0 for an empty box).
    pub fn size(&self) -> [f64; 3] {
        if self.is_empty() {
            return [0.0; 3];
        }
        [
            self.hi.x - self.lo.x,
            self.hi.y - self.lo.y,
            self.hi.z - self.lo.z,
        ]
    }

    /// Volume (0 for an empty box).
    pub fn volume(&self) -> f64 {
        let s = self.size();
        s[0] * s[1] * s[2]
    }

    /// The centre.
    pub fn center(&self) -> P3 {
        nalgebra::center(&self.lo, &self.hi)
    }

    /// The 8 corners, bit i of the index choosing hi on axis i.
    pub fn corners(&self) -> [P3; 8] {
        std::array::from_fn(|k| {
            P3::new(
                if k & 1 == 0 { self.lo.x } else { self.hi.x },
                if k & 2 == 0 { self.lo.y } else { self.hi.y },
                if k & 4 == 0 { self.lo.z } else { self.hi.z },
            )
        })
    }

    /// The box around the 8 transformed corners (an affine `m`): conservative, and exact for
    /// axis-preserving transforms.
    pub fn transformed(&self, m: &M4) -> Box3 {
        if self.is_empty() {
            return *self;
        }
        let pts = self.corners().map(|c| m.transform_point(&c));
        Box3::from_points(pts.iter())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn union_and_volume() {
        let a = Box3::new(P3::new(0., 0., 0.), P3::new(1., 2., 3.));
        let b = Box3::new(P3::new(-1., 0., 0.), P3::new(0., 1., 1.));
        let u = a.union(&b);
        assert_eq!(u.volume(), 12.0);
        assert!(Box3::empty().is_empty());
        assert_eq!(Box3::empty().union(&a), a);
        assert!(u.contains_box(&a) && !a.contains_box(&u));
    }

    #[test]
    fn rotated_box_is_conservative() {
        let a = Box3::new(P3::new(0., 0., 0.), P3::new(1., 1., 1.));
        let m = nalgebra::Rotation3::from_axis_angle(&nalgebra::Vector3::z_axis(), 0.5)
            .to_homogeneous();
        let t = a.transformed(&m);
        for c in a.corners() {
            assert!(t.contains(&m.transform_point(&c)));
        }
    }
}
