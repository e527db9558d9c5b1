//! Axis-aligned rectangles of the screen plane, for the baselines' grids and bounds.

/// A closed rectangle `[xmin, xmax] × [ymin, ymax]`; empty when `xmin > xmax` or
/// `ymin > ymax` (see [`Rect::EMPTY`]).
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
    pub const EMPTY: Rect = Rect::new(
        f64::INFINITY,
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::NEG_INFINITY,
    );

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
    pub fn of_points<'a>(pts: impl IntoIterator<Item = &'a [f64; 2]>) -> Rect {
        pts.into_iter().fold(Rect::EMPTY, |r, p| r.with(*p))
    }

    /// The smallest rectangle holding this one and `p`.
    pub fn with(&self, p: [f64; 2]) -> Rect {
        Rect::new(
            self.xmin.min(p[0]),
            self.ymin.min(p[1]),
            self.xmax.max(p[0]),
            self.ymax.max(p[1]),
        )
    }

    /// The smallest rectangle holding both.
    pub fn union(&self, o: &Rect) -> Rect {
        Rect::new(
            self.xmin.min(o.xmin),
            self.ymin.min(o.ymin),
            self.xmax.max(o.xmax),
            self.ymax.max(o.ymax),
        )
    }

    /// True when the rectangle holds no point (NaN bounds included).
    pub fn is_empty(&self) -> bool {
        !(self.xmin <= self.xmax && self.ymin <= self.ymax)
    }

    /// Closed containment of another rectangle.
    pub fn contains_rect(&self, inner: &Rect) -> bool {
        self.xmin <= inner.xmin
            && self.ymin <= inner.ymin
            && inner.xmax <= self.xmax
            && inner.ymax <= self.ymax
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

    /// The lower (`hi` false) or upper bound along axis 0 (x) or 1 (y).
    pub fn bound(&self, axis: usize, hi: bool) -> f64 {
        match (axis, hi) {
            (0, false) => self.xmin,
            (0, true) => self.xmax,
            (_, false) => self.ymin,
            (_, true) => self.ymax,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bounds_of_points_and_unions() {
        let r = Rect::of_points(&[[1., 2.], [-1., 5.]]);
        assert_eq!(r, Rect::new(-1., 2., 1., 5.));
        assert!(Rect::EMPTY.is_empty() && !r.is_empty());
        assert_eq!(Rect::EMPTY.union(&r), r);
        assert_eq!((r.width(), r.height(), r.longer_side()), (2., 3., 3.));
        assert!(r.contains_rect(&Rect::new(0., 3., 0., 3.)));
        assert_eq!((r.bound(0, false), r.bound(1, true)), (-1., 5.));
    }
}
