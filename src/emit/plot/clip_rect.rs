//! Polylines clipped to a closed rectangle (the page's drawing area), Liang–Barsky per
//! segment. A point where a segment leaves through a side gets that side's coordinate
//! exactly and its other coordinate clamped into the rectangle, so nothing clipped lies
//! outside it, not even by a rounding error.

use crate::geom::poly2::Pt2;
use crate::geom::Rect;

/// The parts of polyline `pts` inside the closed rectangle `r`, as polylines (a part that
/// leaves and re-enters becomes two). Zero-length parts are dropped.
pub(crate) fn clip_polyline(pts: &[Pt2], r: &Rect) -> Vec<Vec<Pt2>> {
    let mut out: Vec<Vec<Pt2>> = Vec::new();
    let mut cur: Vec<Pt2> = Vec::new();
    for w in pts.windows(2) {
        match clip_segment(w[0], w[1], r) {
            Some([p, q]) if p != q => {
                if cur.last() != Some(&p) {
                    if cur.len() > 1 {
                        out.push(std::mem::take(&mut cur));
                    }
                    cur.clear();
                    cur.push(p);
                }
                cur.push(q);
            }
            _ => {}
        }
    }
    if cur.len() > 1 {
        out.push(cur);
    }
    out
}

/// A side of the rectangle: axis (0 x, 1 y) and its bound.
type Side = (usize, f64);

/// The part of segment a → b inside the closed rectangle `r`, or None.
pub(crate) fn clip_segment(a: Pt2, b: Pt2, r: &Rect) -> Option<[Pt2; 2]> {
    let inside = |p: Pt2| r.xmin <= p[0] && p[0] <= r.xmax && r.ymin <= p[1] && p[1] <= r.ymax;
    if inside(a) && inside(b) {
        return Some([a, b]);
    }
    let d = [b[0] - a[0], b[1] - a[1]];
    // Entry and exit parameters, each with the side (axis, bound) that set it.
    let (mut t0, mut t1) = (0.0f64, 1.0f64);
    let (mut s0, mut s1): (Option<Side>, Option<Side>) = (None, None);
    for axis in 0..2 {
        let (lo, hi) = (r.bound(axis, false), r.bound(axis, true));
        if d[axis] == 0.0 {
            if a[axis] < lo || a[axis] > hi {
                return None;
            }
            continue;
        }
        let (ta, tb) = ((lo - a[axis]) / d[axis], (hi - a[axis]) / d[axis]);
        let ((tin, bin), (tout, bout)) = if ta < tb {
            ((ta, lo), (tb, hi))
        } else {
            ((tb, hi), (ta, lo))
        };
        if tin > t0 {
            t0 = tin;
            s0 = Some((axis, bin));
        }
        if tout < t1 {
            t1 = tout;
            s1 = Some((axis, bout));
        }
    }
    if t0 > t1 {
        return None;
    }
    let point = |t: f64, side: Option<Side>, end: Pt2| -> Pt2 {
        let Some((axis, bound)) = side else {
            return end;
        };
        let mut p = [a[0] + t * d[0], a[1] + t * d[1]];
        p[axis] = bound;
        let o = 1 - axis;
        p[o] = p[o].clamp(r.bound(o, false), r.bound(o, true));
        p
    };
    Some([point(t0, s0, a), point(t1, s1, b)])
}

#[cfg(test)]
mod tests {
    use super::*;

    const R: Rect = Rect::new(0.0, 0.0, 10.0, 5.0);

    #[test]
    fn segments_inside_crossing_and_outside() {
        assert_eq!(
            clip_segment([1., 1.], [2., 2.], &R),
            Some([[1., 1.], [2., 2.]])
        );
        assert_eq!(
            clip_segment([-5., 1.], [15., 1.], &R),
            Some([[0., 1.], [10., 1.]])
        );
        assert_eq!(clip_segment([-5., 6.], [15., 6.], &R), None);
        // Diagonal through a corner region, entering on the left and leaving at the top.
        let [p, q] = clip_segment([-1., 0.], [11., 6.], &R).unwrap();
        assert_eq!(p, [0.0, 0.5]);
        assert!((q[0] - 9.0).abs() < 1e-12 && q[1] == 5.0, "{q:?}");
        // Touching the boundary only at a corner gives a zero-length part.
        let t = clip_segment([-1., 4.], [1., 6.], &R).unwrap();
        assert_eq!(t[0], t[1]);
    }

    #[test]
    fn clipped_points_never_leave_the_rectangle() {
        // Many random long segments: every clipped end is inside the closed rectangle.
        let mut rng = crate::geom::rng::XorShift::new(0x2545F4914F6CDD1D);
        let mut rnd = || rng.range(-15.0, 25.0);
        let r = Rect::new(0.1, 0.3, 10.7, 5.9);
        for _ in 0..5000 {
            let (a, b) = ([rnd(), rnd()], [rnd(), rnd()]);
            if let Some(seg) = clip_segment(a, b, &r) {
                for p in seg {
                    assert!(r.xmin <= p[0] && p[0] <= r.xmax && r.ymin <= p[1] && p[1] <= r.ymax);
                }
            }
        }
    }

    #[test]
    fn polyline_leaving_and_reentering_splits() {
        let pl = [[1., 1.], [12., 1.], [12., 3.], [1., 3.]];
        let parts = clip_polyline(&pl, &R);
        assert_eq!(
            parts,
            vec![vec![[1., 1.], [10., 1.]], vec![[10., 3.], [1., 3.]]]
        );
        let inside = [[1., 1.], [2., 1.], [2., 2.]];
        assert_eq!(clip_polyline(&inside, &R), vec![inside.to_vec()]);
    }
}
