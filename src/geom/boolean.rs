//! The one adapter to i_overlay: 2D booleans of rings on a fixed i64 grid.
//!
//! Every call fixes its float-to-integer grid from one rectangle that holds all its input:
//! 61 bits per coordinate, a pitch of about 2^-60 of the rectangle's size — finer than f64's
//! own spacing near the rectangle's corners — so results are exact to f64 precision, and the
//! same input always meets the same grid (docs/design.md, measured pitfalls: a grid chosen per call
//! from the inputs drifts; i32 drifts).

use i_overlay::core::fill_rule::FillRule;
use i_overlay::core::overlay::ShapeType;
use i_overlay::core::overlay_rule::OverlayRule;
use i_overlay::core::solver::{Precision, Solver, Strategy};
use i_overlay::float::overlay::{FloatOverlay, OverlayOptions};
use i_overlay::i_float::adapter::FloatPointAdapter;
use i_overlay::i_float::float::rect::FloatRect;

use super::poly2::{multipolygon_area, MultiPolygon, Pt2, Ring};
use super::rect::Rect;

/// Single-threaded solver: kepler parallelises over faces instead.
const SOLVER: Solver = Solver {
    strategy: Strategy::Auto,
    precision: Precision::HIGH,
    multithreading: None,
};

/// An overlay on the fixed grid of `rect` (None when `rect` is empty or not finite).
fn overlay(rect: &Rect, capacity: usize) -> Option<FloatOverlay<Pt2, i64>> {
    let frect = FloatRect::new(rect.xmin, rect.xmax, rect.ymin, rect.ymax).ok()?;
    if rect.is_empty() || !(rect.xmin.is_finite() && rect.xmax.is_finite()) {
        return None;
    }
    let adapter = FloatPointAdapter::<Pt2, i64>::new_conservative(frect);
    Some(FloatOverlay::new_custom(
        adapter,
        OverlayOptions::<f64, i64>::default(),
        SOLVER,
        capacity,
    ))
}

/// `subject` (counter-clockwise) minus the union of `clips` (each counter-clockwise), on the
/// grid of `rect`, which must hold `subject` and every clip. NonZero fill: equal windings
/// never cancel, so overlapping clips subtract once.
pub(crate) fn subtract(subject: &[Pt2], rect: &Rect, clips: &[Ring]) -> MultiPolygon {
    let capacity = subject.len() + clips.iter().map(Vec::len).sum::<usize>();
    let Some(mut ov) = overlay(rect, capacity) else {
        return Vec::new();
    };
    ov = ov.unsafe_add_contour(subject, ShapeType::Subject);
    for c in clips {
        ov = ov.unsafe_add_contour(c, ShapeType::Clip);
    }
    ov.overlay(OverlayRule::Difference, FillRule::NonZero)
}

/// The union of rings of equal orientation (NonZero fill), on the grid of `rect`, which must
/// hold them all.
pub fn union<'a>(rings: impl IntoIterator<Item = &'a Ring>, rect: &Rect) -> MultiPolygon {
    let Some(mut ov) = overlay(rect, 64) else {
        return Vec::new();
    };
    for r in rings {
        ov = ov.unsafe_add_contour(r, ShapeType::Subject);
    }
    ov.overlay(OverlayRule::Subject, FillRule::NonZero)
}

#[cfg(test)]
/// Area of the union of multipolygons, on one grid over all of them.
pub(crate) fn union_area(parts: &[&MultiPolygon]) -> f64 {
    let rect = Rect::of_points(parts.iter().flat_map(|m| m.iter().flatten().flatten()));
    multipolygon_area(&union(parts.iter().flat_map(|m| m.iter().flatten()), &rect))
}

/// Area of the symmetric difference of two multipolygons (even-odd rings), on one grid over
/// both: 0 exactly when they cover the same region, to the grid's precision.
pub fn xor_area(a: &MultiPolygon, b: &MultiPolygon) -> f64 {
    let rect = Rect::of_points(a.iter().chain(b.iter()).flatten().flatten());
    let Some(mut ov) = overlay(&rect, 64) else {
        return 0.0;
    };
    for (m, shape) in [(a, ShapeType::Subject), (b, ShapeType::Clip)] {
        for r in m.iter().flatten().filter(|r| r.len() >= 3) {
            ov = ov.unsafe_add_contour(r, shape);
        }
    }
    multipolygon_area(&ov.overlay(OverlayRule::Xor, FillRule::EvenOdd)).abs()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sq(x: f64, y: f64, s: f64) -> Ring {
        vec![[x, y], [x + s, y], [x + s, y + s], [x, y + s]]
    }

    fn one(r: Ring) -> MultiPolygon {
        vec![vec![r]]
    }

    #[test]
    fn square_minus_two_overlapping_squares() {
        let rect = Rect::new(0., 0., 4., 4.);
        let r = subtract(&sq(0., 0., 4.), &rect, &[sq(0., 0., 2.), sq(1., 1., 2.)]);
        // Union of the two occluders: 4 + 4 - 1 = 7.
        assert_eq!(multipolygon_area(&r), 16.0 - 7.0);
        let hole = subtract(&sq(0., 0., 4.), &rect, &[sq(1., 1., 2.)]);
        assert_eq!(hole.len(), 1);
        assert_eq!(hole[0].len(), 2, "outer ring and one hole");
        assert_eq!(multipolygon_area(&hole), 12.0);
    }

    #[test]
    fn no_drift_with_many_tiny_occluders() {
        // 1000 slivers along the bottom edge: the remaining top must stay exactly at y = 1.
        let clips: Vec<Ring> = (0..1000)
            .map(|i| sq(i as f64 / 1000.0, 0.0, 0.001))
            .collect();
        let r = subtract(&sq(0., 0., 1.), &Rect::new(0., 0., 1., 1.), &clips);
        let max_y = r
            .iter()
            .flatten()
            .flatten()
            .map(|p| p[1])
            .fold(0.0, f64::max);
        assert_eq!(max_y, 1.0);
        assert!((multipolygon_area(&r) - 0.999).abs() < 1e-12);
    }

    #[test]
    fn two_triangles_sharing_a_diagonal_make_the_square() {
        let a = vec![[0., 0.], [1., 0.], [1., 1.]];
        let b = vec![[0., 0.], [1., 1.], [0., 1.]];
        let u = union([&a, &b], &Rect::new(0., 0., 1., 1.));
        assert_eq!(multipolygon_area(&u), 1.0);
        assert_eq!(union_area(&[&one(a), &one(b)]), 1.0);
    }

    #[test]
    fn xor_of_shifted_squares() {
        let (a, b) = (one(sq(0., 0., 2.)), one(sq(1., 0., 2.)));
        assert_eq!(xor_area(&a, &a), 0.0);
        assert_eq!(xor_area(&a, &b), 4.0);
        assert_eq!(xor_area(&a, &Vec::new()), 4.0);
        assert_eq!(xor_area(&Vec::new(), &Vec::new()), 0.0);
    }
}
