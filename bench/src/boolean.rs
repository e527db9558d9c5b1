//! Polygon booleans for the accuracy checks, on i_overlay directly: the union of projected
//! faces and the symmetric difference of visible regions, with shoelace areas.
//!
//! As in kepler itself, every call fixes its float-to-integer grid from one rectangle that
//! holds all its input (61 bits a coordinate), so results are exact to f64 precision.

use i_overlay::core::fill_rule::FillRule;
use i_overlay::core::overlay::ShapeType;
use i_overlay::core::overlay_rule::OverlayRule;
use i_overlay::core::solver::{Precision, Solver, Strategy};
use i_overlay::float::overlay::{FloatOverlay, OverlayOptions};
use i_overlay::i_float::adapter::FloatPointAdapter;
use i_overlay::i_float::float::rect::FloatRect;

use crate::rect::Rect;

/// A point of the screen plane.
pub type Pt2 = [f64; 2];
/// A closed ring (the last point is not repeated).
pub type Ring = Vec<Pt2>;
/// Polygons, each an outer ring (counter-clockwise) then its holes (clockwise).
pub type MultiPolygon = Vec<Vec<Ring>>;

/// Single-threaded solver: the bench parallelises over faces instead.
const SOLVER: Solver = Solver {
    strategy: Strategy::Auto,
    precision: Precision::HIGH,
    multithreading: None,
};

/// Signed area of a ring (shoelace; positive for counter-clockwise).
pub fn ring_area(r: &[Pt2]) -> f64 {
    let n = r.len();
    if n < 3 {
        return 0.0;
    }
    let o = r[0];
    let mut s = 0.0;
    for i in 1..n - 1 {
        s += (r[i][0] - o[0]) * (r[i + 1][1] - o[1]) - (r[i + 1][0] - o[0]) * (r[i][1] - o[1]);
    }
    0.5 * s
}

/// Total area of a multipolygon (outer rings minus holes, by signed ring areas).
pub fn multipolygon_area(m: &MultiPolygon) -> f64 {
    m.iter()
        .map(|p| p.iter().map(|r| ring_area(r)).sum::<f64>())
        .sum()
}

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

    #[test]
    fn union_and_xor_of_two_squares_by_hand() {
        let (a, b) = (sq(0., 0., 2.), sq(1., 1., 2.));
        let u = union([&a, &b], &Rect::new(0., 0., 3., 3.));
        assert_eq!(multipolygon_area(&u), 7.0);
        let (ma, mb) = (vec![vec![a]], vec![vec![b]]);
        assert_eq!(xor_area(&ma, &mb), 6.0);
        assert_eq!(xor_area(&ma, &ma), 0.0);
    }
}
