//! Axis-aligned rectangles of the screen plane: face bounds, node bounds, picture frames.

use super::poly2::Pt2;

/// A closed axis-aligned rectangle `[xmin, xmax] × [ymin, ymax]`; empty when `xmin > xmax`
/// or `ymin > ymax` (see [`Rect::EMPTY`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Rect {
    /// Least x.
    pub xmin: f64,
    /// Least y.
    pub ymin: f64,
    /// Greatest x.
    pub xmax: f64,
    /// Greatest y.
    pub ymax: f64,
}

impl Rect {
    /// The empty rectangle: the identity of [`Rect::union`].
    pub const EMPTY: Rect = Rect {
        xmin: f64::INFINITY,
        ymin: f64::INFINITY,
        xmax: f64::NEG_INFINITY,
        ymax: f64::NEG_INFINITY,
    };

    /// The rectangle with these bounds (not reordered).
    pub const fn new(xmin: f64, ymin: f64, xmax: f64, ymax: f64) -> Rect {
        Rect {
            xmin,
            ymin,
            xmax,
            ymax,
        }
    }

    /// The smallest rectangle holding every point ([`Rect::EMPTY`] for none).
    pub fn of_points<'a>(pts: impl IntoIterator<Item = &'a Pt2>) -> Rect {
        let mut r = Rect::EMPTY;
        for p in pts {
            r.add(*p);
        }
        r
    }

    /// Grows the rectangle to hold `p`.
    #[inline]
    pub fn add(&mut self, p: Pt2) {
        self.xmin = self.xmin.min(p[0]);
        self.ymin = self.ymin.min(p[1]);
        self.xmax = self.xmax.max(p[0]);
        self.ymax = self.ymax.max(p[1]);
    }

    /// The smallest rectangle holding both.
    #[inline]
    pub fn union(&self, o: &Rect) -> Rect {
        Rect {
            xmin: self.xmin.min(o.xmin),
            ymin: self.ymin.min(o.ymin),
            xmax: self.xmax.max(o.xmax),
            ymax: self.ymax.max(o.ymax),
        }
    }

    /// True when the rectangle holds no point (NaN bounds included).
    pub fn is_empty(&self) -> bool {
        !(self.xmin <= self.xmax && self.ymin <= self.ymax)
    }

    /// True when the two rectangles share interior area (open overlap).
    #[inline]
    pub fn overlaps(&self, o: &Rect) -> bool {
        self.xmin < o.xmax && o.xmin < self.xmax && self.ymin < o.ymax && o.ymin < self.ymax
    }

    /// True when the two closed rectangles share a point (touching counts).
    #[inline]
    pub fn overlaps_closed(&self, o: &Rect) -> bool {
        self.xmin <= o.xmax && o.xmin <= self.xmax && self.ymin <= o.ymax && o.ymin <= self.ymax
    }

    /// Closed containment of another rectangle.
    #[inline]
    pub fn contains_rect(&self, inner: &Rect) -> bool {
        self.xmin <= inner.xmin
            && self.ymin <= inner.ymin
            && inner.xmax <= self.xmax
            && inner.ymax <= self.ymax
    }

    /// Open containment of a point (strictly inside).
    #[inline]
    pub fn contains_strictly(&self, p: Pt2) -> bool {
        self.xmin < p[0] && p[0] < self.xmax && self.ymin < p[1] && p[1] < self.ymax
    }

    /// Width (negative when empty).
    pub fn width(&self) -> f64 {
        self.xmax - self.xmin
    }

    /// Height (negative when empty).
    pub fn height(&self) -> f64 {
        self.ymax - self.ymin
    }

    /// The longer side.
    pub fn longer_side(&self) -> f64 {
        self.width().max(self.height())
    }

    /// Area (0 when empty).
    pub fn area(&self) -> f64 {
        self.width().max(0.0) * self.height().max(0.0)
    }

    /// The rectangle grown by `d` on every side.
    pub fn padded(&self, d: f64) -> Rect {
        Rect::new(self.xmin - d, self.ymin - d, self.xmax + d, self.ymax + d)
    }

    /// The intersection (possibly empty).
    pub fn intersection(&self, o: &Rect) -> Rect {
        Rect {
            xmin: self.xmin.max(o.xmin),
            ymin: self.ymin.max(o.ymin),
            xmax: self.xmax.min(o.xmax),
            ymax: self.ymax.min(o.ymax),
        }
    }

    /// The bound on `axis` (0 x, 1 y) on the low (`hi == false`) or high side.
    #[inline]
    pub fn bound(&self, axis: usize, hi: bool) -> f64 {
        match (axis, hi) {
            (0, false) => self.xmin,
            (0, true) => self.xmax,
            (_, false) => self.ymin,
            (_, true) => self.ymax,
        }
    }

    /// The part of `ring` inside the rectangle (Sutherland–Hodgman; a non-convex ring may
    /// gain zero-width bridges along the border, which carry no area under NonZero fill).
    /// Empty when less than a triangle is left.
    pub fn clip_ring(&self, ring: &[Pt2]) -> Vec<Pt2> {
        let mut cur: Vec<Pt2> = ring.to_vec();
        for (axis, hi) in [(0, false), (0, true), (1, false), (1, true)] {
            let bound = self.bound(axis, hi);
            let inside = |p: &Pt2| {
                if hi {
                    p[axis] <= bound
                } else {
                    p[axis] >= bound
                }
            };
            if cur.iter().all(inside) {
                continue;
            }
            let n = cur.len();
            let mut next = Vec::with_capacity(n + 2);
            for i in 0..n {
                let (a, b) = (cur[i], cur[(i + 1) % n]);
                if inside(&a) {
                    next.push(a);
                }
                if inside(&a) != inside(&b) {
                    let t = (bound - a[axis]) / (b[axis] - a[axis]);
                    let mut p = [a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])];
                    p[axis] = bound;
                    next.push(p);
                }
            }
            cur = next;
            if cur.len() < 3 {
                return Vec::new();
            }
        }
        cur
    }

    /// Twice the centre's coordinate on `axis` (0 x, 1 y): a sort key without a division.
    #[inline]
    pub fn centre2(&self, axis: usize) -> f64 {
        self.bound(axis, false) + self.bound(axis, true)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn union_overlap_and_containment() {
        let a = Rect::new(0., 0., 2., 1.);
        let b = Rect::new(1., 0.5, 3., 4.);
        assert_eq!(a.union(&b), Rect::new(0., 0., 3., 4.));
        assert_eq!(Rect::EMPTY.union(&a), a);
        assert!(a.overlaps(&b) && b.overlaps(&a));
        // Touching along an edge is not overlap.
        assert!(!a.overlaps(&Rect::new(2., 0., 3., 1.)));
        assert!(a.union(&b).contains_rect(&a) && !a.contains_rect(&b));
        assert!(Rect::EMPTY.is_empty() && !a.is_empty());
        assert_eq!(a.area(), 2.0);
        assert_eq!(Rect::EMPTY.area(), 0.0);
        assert_eq!(a.intersection(&b), Rect::new(1., 0.5, 2., 1.));
    }

    #[test]
    fn from_points_and_open_containment() {
        let r = Rect::of_points(&[[1., 2.], [-1., 5.], [0., 3.]]);
        assert_eq!(r, Rect::new(-1., 2., 1., 5.));
        assert!(r.contains_strictly([0., 3.]) && !r.contains_strictly([1., 3.]));
        assert!(Rect::of_points(&[]).is_empty());
        assert_eq!(r.centre2(0), 0.0);
        assert_eq!(r.padded(1.), Rect::new(-2., 1., 2., 6.));
    }

    #[test]
    fn ring_clip_keeps_the_inside_part() {
        let sq = |x: f64, s: f64| vec![[x, x], [x + s, x], [x + s, x + s], [x, x + s]];
        let unit = Rect::new(0., 0., 1., 1.);
        let c = unit.clip_ring(&sq(-1., 3.));
        assert_eq!(crate::geom::poly2::ring_area(&c), 1.0);
        assert!(unit.clip_ring(&sq(5., 1.)).is_empty());
        assert_eq!(unit.clip_ring(&sq(0.25, 0.5)), sq(0.25, 0.5));
    }
}
