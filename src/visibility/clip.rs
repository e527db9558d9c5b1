//! Batched clipping: a face minus all its occluders in ONE i_overlay call on a fixed i64 grid.
//!
//! The grid is chosen from the face's own rectangle (occluders are clipped to it first), with
//! 61 bits per coordinate: a pitch of about 2^-60 of the face's size, finer than f64's own
//! spacing, so the result is exact to f64 precision (DESIGN.md, measured pitfalls).

use i_overlay::core::fill_rule::FillRule;
use i_overlay::core::overlay::ShapeType;
use i_overlay::core::overlay_rule::OverlayRule;
use i_overlay::core::solver::{Precision, Solver, Strategy};
use i_overlay::float::overlay::{FloatOverlay, OverlayOptions};
use i_overlay::i_float::adapter::FloatPointAdapter;
use i_overlay::i_float::float::rect::FloatRect;

use crate::geom::poly2::{MultiPolygon, Pt2, Ring};

/// Single-threaded solver: kepler parallelises over faces instead.
const SOLVER: Solver = Solver {
    strategy: Strategy::Auto,
    precision: Precision::HIGH,
    multithreading: None,
};

/// `subject` (counter-clockwise) minus the union of `clips` (each counter-clockwise, each
/// inside `rect`, which must contain `subject`). NonZero fill: equal windings never cancel.
pub fn subtract(subject: &[Pt2], rect: &[f64; 4], clips: &[Ring]) -> MultiPolygon {
    let Ok(frect) = FloatRect::new(rect[0], rect[2], rect[1], rect[3]) else {
        return Vec::new();
    };
    let adapter = FloatPointAdapter::<Pt2, i64>::new_conservative(frect);
    let capacity = subject.len() + clips.iter().map(Vec::len).sum::<usize>();
    let options = OverlayOptions::<f64, i64>::default();
    let mut overlay = FloatOverlay::new_custom(adapter, options, SOLVER, capacity)
        .unsafe_add_contour(subject, ShapeType::Subject);
    for c in clips {
        overlay = overlay.unsafe_add_contour(c, ShapeType::Clip);
    }
    overlay.overlay(OverlayRule::Difference, FillRule::NonZero)
}

/// The union of disjoint-interior multipolygons (the pieces of one warped face), on the
/// fixed grid of `rect`, which must contain them all.
pub fn union(parts: &[MultiPolygon], rect: &[f64; 4]) -> MultiPolygon {
    // The parts come out of earlier boolean calls on their own grids: a point may sit an ulp
    // outside its piece's rectangle, so take the rectangle of the parts themselves, padded.
    let b = crate::geom::poly2::bounds(parts.iter().flatten().flatten().flatten());
    let r = super::super::view::tree::union_rect(rect, &b);
    let pad = 1e-9 * (r[2] - r[0]).max(r[3] - r[1]);
    let rect = [r[0] - pad, r[1] - pad, r[2] + pad, r[3] + pad];
    let Ok(frect) = FloatRect::new(rect[0], rect[2], rect[1], rect[3]) else {
        return Vec::new();
    };
    let adapter = FloatPointAdapter::<Pt2, i64>::new_conservative(frect);
    let options = OverlayOptions::<f64, i64>::default();
    let mut overlay = FloatOverlay::new_custom(adapter, options, SOLVER, 64);
    for ring in parts.iter().flatten().flatten() {
        overlay = overlay.unsafe_add_contour(ring, ShapeType::Subject);
    }
    overlay.overlay(OverlayRule::Subject, FillRule::NonZero)
}

/// Clips a ring to an axis-aligned rectangle (Sutherland–Hodgman; a non-convex ring may gain
/// zero-width bridges along the border, which carry no area under NonZero fill).
pub fn clip_to_rect(ring: &[Pt2], rect: &[f64; 4]) -> Ring {
    let mut cur: Ring = ring.to_vec();
    for (axis, bound, keep_below) in [
        (0, rect[0], false),
        (0, rect[2], true),
        (1, rect[1], false),
        (1, rect[3], true),
    ] {
        if cur.iter().all(|p| {
            if keep_below {
                p[axis] <= bound
            } else {
                p[axis] >= bound
            }
        }) {
            continue;
        }
        let inside = |p: &Pt2| {
            if keep_below {
                p[axis] <= bound
            } else {
                p[axis] >= bound
            }
        };
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::poly2::multipolygon_area;

    fn sq(x: f64, y: f64, s: f64) -> Ring {
        vec![[x, y], [x + s, y], [x + s, y + s], [x, y + s]]
    }

    #[test]
    fn square_minus_two_overlapping_squares() {
        let r = subtract(
            &sq(0., 0., 4.),
            &[0., 0., 4., 4.],
            &[sq(0., 0., 2.), sq(1., 1., 2.)],
        );
        // Union of the two occluders: 4 + 4 - 1 = 7.
        assert_eq!(multipolygon_area(&r), 16.0 - 7.0);
    }

    #[test]
    fn hole_in_the_middle() {
        let r = subtract(&sq(0., 0., 4.), &[0., 0., 4., 4.], &[sq(1., 1., 2.)]);
        assert_eq!(r.len(), 1);
        assert_eq!(r[0].len(), 2, "outer ring and one hole");
        assert_eq!(multipolygon_area(&r), 12.0);
    }

    #[test]
    fn rect_clip_keeps_inside_part() {
        let c = clip_to_rect(&sq(-1., -1., 3.), &[0., 0., 1., 1.]);
        assert_eq!(crate::geom::poly2::ring_area(&c), 1.0);
        assert!(clip_to_rect(&sq(5., 5., 1.), &[0., 0., 1., 1.]).is_empty());
    }

    #[test]
    fn no_drift_with_many_tiny_occluders() {
        // 1000 slivers along the bottom edge: the remaining top must stay exactly at y = 1.
        let clips: Vec<Ring> = (0..1000)
            .map(|i| sq(i as f64 / 1000.0, 0.0, 0.001))
            .collect();
        let r = subtract(
            &[[0., 0.], [1., 0.], [1., 1.], [0., 1.]],
            &[0., 0., 1., 1.],
            &clips,
        );
        let max_y = r
            .iter()
            .flatten()
            .flatten()
            .map(|p| p[1])
            .fold(0.0, f64::max);
        assert_eq!(max_y, 1.0);
        assert!((multipolygon_area(&r) - 0.999).abs() < 1e-12);
    }
}

#[cfg(test)]
mod union_tests {
    use super::*;
    use crate::geom::poly2::multipolygon_area;

    #[test]
    fn two_triangles_sharing_a_diagonal_make_the_square() {
        let a: MultiPolygon = vec![vec![vec![[0., 0.], [1., 0.], [1., 1.]]]];
        let b: MultiPolygon = vec![vec![vec![[0., 0.], [1., 1.], [0., 1.]]]];
        let u = union(&[a, b], &[0., 0., 1., 1.]);
        assert_eq!(multipolygon_area(&u), 1.0);
    }
}
