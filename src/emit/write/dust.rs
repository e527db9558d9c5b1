//! Rounding dust kept out of the canonical JSON: ring points a few ulps apart merged, and
//! polygons and holes whose area is within the rounding of zero left out.
//!
//! The rule (docs/numerics.md, "Rounding dust in the JSON"): with S the view's screen extent
//! (the largest |coordinate| of any visible point) and δ = [`DUST_ULPS`] · ε · S (ε = 2^-52,
//! so δ is that many units of f64 rounding at the scene's scale):
//! - walking a ring from its first point, a point within δ, in x and in y, of the point kept
//!   before it (the last ones also against the first) is merged into that point; a ring that
//!   this leaves with fewer than 3 points is dropped, and a polygon whose outer ring is dropped
//!   goes with its holes;
//! - a hole whose area is at most δ times its perimeter is filled, and a polygon whose area
//!   (outer ring less holes) is at most δ times its perimeter (all its rings) is dropped: such
//!   a region is on average at most 2δ wide, so moving each side by the rounding closes it;
//! - the other rings get their points merged: each run of points so merged becomes its first
//!   point, or, where that would leave the ring not simple or turning the wrong way (exact
//!   [`ring_defect`]) or make an edge it gains meet another ring of the face (exact; a vertex
//!   both rings already had is no new contact), its last point; where both fail the ring is
//!   kept as it was. Thin regions are looked for again after the merges, and the rings put
//!   back in canonical form (least point first).
//!
//! Every point of a run lies within δ of its first, so a merge moves the boundary by at most
//! 2√2·δ (Hausdorff distance). The regions outside this rule are written exactly as the
//! visibility stage made them.

use std::borrow::Cow;
use std::ops::Range;

use crate::geom::orient2d;
use crate::geom::poly2::{canonicalize, ring_area, MultiPolygon, Polygon, Pt2, Ring};
use crate::geom::ring_check::{ring_defect, same_direction, segments_meet};

/// The merge distance δ in units of f64 rounding (ε) of the view's screen extent: the same
/// as the exact check's `ROUNDING_ULPS`, the distance it already allows any f64 outline of a
/// face to lie from the exact one.
pub(crate) const DUST_ULPS: f64 = 16.0;

/// δ for a view whose largest |screen coordinate| is `extent`.
pub(crate) fn dust_delta(extent: f64) -> f64 {
    DUST_ULPS * f64::EPSILON * extent
}

/// The largest of `m` and the |coordinates| of `p`: folded over every point of the regions,
/// the view's extent (0 when there is none).
pub(crate) fn extent_with(m: f64, p: Pt2) -> f64 {
    m.max(p[0].abs()).max(p[1].abs())
}

/// The region without dust (see the module documentation): borrowed when there is none.
/// Empty when the whole region was dust.
pub(crate) fn clean(m: &MultiPolygon, delta: f64) -> Cow<'_, MultiPolygon> {
    if !has_dust(m, delta) {
        return Cow::Borrowed(m);
    }
    let mut out: MultiPolygon = m.clone();
    // Dust rings go first, so that a merge is never held back by a ring about to go.
    drop_collapsed(&mut out, delta);
    drop_thin(&mut out, delta);
    merge_points(&mut out, delta);
    drop_thin(&mut out, delta);
    // A ring merged into the last points of its runs may start elsewhere.
    canonicalize(&mut out);
    Cow::Owned(out)
}

/// Drops every ring that merging leaves with fewer than 3 points (an outer ring with its
/// holes).
fn drop_collapsed(m: &mut MultiPolygon, delta: f64) {
    let collapses = |r: &Ring| merged(r, delta).is_some_and(|r| r.len() < 3);
    m.retain(|poly| !collapses(&poly[0]));
    for poly in m.iter_mut() {
        let mut k = 1;
        while k < poly.len() {
            if collapses(&poly[k]) {
                poly.remove(k);
            } else {
                k += 1;
            }
        }
    }
}

/// True when the rule changes something in `m`.
fn has_dust(m: &MultiPolygon, delta: f64) -> bool {
    m.iter().any(|poly| {
        poly.iter().any(|r| merged(r, delta).is_some())
            || poly
                .iter()
                .skip(1)
                .any(|h| thin(std::slice::from_ref(h), delta))
            || thin(poly, delta)
    })
}

/// True when a and b are within δ in x and in y.
fn close(a: Pt2, b: Pt2, delta: f64) -> bool {
    (a[0] - b[0]).abs() <= delta && (a[1] - b[1]).abs() <= delta
}

/// The ring with every point within δ of the point kept before it left out (the last ones
/// also against the first); None when no point goes.
fn merged(r: &[Pt2], delta: f64) -> Option<Ring> {
    let runs = runs(r, delta);
    (runs.len() < r.len()).then(|| runs.iter().map(|k| r[k.start]).collect())
}

/// The ring's points in runs to merge, in order: each run starts at a point kept (the first
/// point, then every point not within δ of the start of the run before) and holds the points
/// after it within δ of that start; points at the end within δ of the first point are left
/// out of the last run (they go with the first).
fn runs(r: &[Pt2], delta: f64) -> Vec<Range<usize>> {
    let mut starts: Vec<usize> = Vec::with_capacity(r.len());
    for (i, &p) in r.iter().enumerate() {
        if starts.last().is_some_and(|&k| close(r[k], p, delta)) {
            continue;
        }
        starts.push(i);
    }
    let mut end = r.len();
    while starts.len() > 1 && close(r[starts[starts.len() - 1]], r[0], delta) {
        end = starts.pop().unwrap_or(end);
    }
    (0..starts.len())
        .map(|j| starts[j]..starts.get(j + 1).copied().unwrap_or(end))
        .collect()
}

/// Merges close points ring by ring (polygons in order, outer ring first), each run into its
/// first point, or where that spoils the ring into its last point; a merge that spoils its
/// ring either way, or whose new edges meet another ring of the face (as it stands then), is
/// undone.
fn merge_points(m: &mut MultiPolygon, delta: f64) {
    for p in 0..m.len() {
        for k in 0..m[p].len() {
            let r = &m[p][k];
            let runs = runs(r, delta);
            if runs.len() == r.len() || runs.len() < 3 {
                continue;
            }
            let firsts: Vec<usize> = runs.iter().map(|k| k.start).collect();
            let lasts: Vec<usize> = runs.iter().map(|k| k.end - 1).collect();
            let ok = [firsts, lasts].into_iter().find_map(|keep| {
                let new: Ring = keep.iter().map(|&i| r[i]).collect();
                let n = keep.len();
                // The edges that span left-out points.
                let spans: Vec<(Pt2, Pt2)> = (0..n)
                    .filter(|&i| keep[(i + 1) % n] != (keep[i] + 1) % r.len())
                    .map(|i| (new[i], new[(i + 1) % n]))
                    .collect();
                (ring_defect(&new, k == 0).is_none() && !meets_other_rings(m, (p, k), &spans))
                    .then_some(new)
            });
            if let Some(new) = ok {
                m[p][k] = new;
            }
        }
    }
}

/// True when one of the `spans` (new edges of ring `at` of `m`) touches or crosses an edge of
/// another ring of `m` (exact), other than at an end of both that a collinear overlap does not
/// extend: rings of a face may touch at a vertex, and such a contact was there before.
fn meets_other_rings(m: &MultiPolygon, at: (usize, usize), spans: &[(Pt2, Pt2)]) -> bool {
    m.iter().enumerate().any(|(p, poly)| {
        poly.iter().enumerate().any(|(k, other)| {
            let b = bbox(other);
            (p, k) != at
                && spans.iter().any(|&(s, t)| {
                    // A span off the other ring's box cannot meet it.
                    let lo = |c: usize| s[c].min(t[c]) <= b[c + 2];
                    let hi = |c: usize| s[c].max(t[c]) >= b[c];
                    lo(0)
                        && lo(1)
                        && hi(0)
                        && hi(1)
                        && edges(other).any(|(c, d)| new_contact(s, t, c, d))
                })
        })
    })
}

/// A closed ring's edges.
fn edges(r: &[Pt2]) -> impl Iterator<Item = (Pt2, Pt2)> + '_ {
    let n = r.len();
    (0..n).map(move |i| (r[i], r[(i + 1) % n]))
}

/// A ring's box: least x, least y, greatest x, greatest y.
fn bbox(r: &[Pt2]) -> [f64; 4] {
    r.iter().fold(
        [
            f64::INFINITY,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::NEG_INFINITY,
        ],
        |b, p| {
            [
                b[0].min(p[0]),
                b[1].min(p[1]),
                b[2].max(p[0]),
                b[3].max(p[1]),
            ]
        },
    )
}

/// Exact: the closed segments ab and cd share a point other than an end of both, unless
/// they lie on one line and overlap beyond it.
fn new_contact(a: Pt2, b: Pt2, c: Pt2, d: Pt2) -> bool {
    let shared = [(a, b, c, d), (a, b, d, c), (b, a, c, d), (b, a, d, c)]
        .into_iter()
        .find(|(p, _, r, _)| p == r);
    match shared {
        // Off one line, two segments meet in at most one point: the shared end. On one line
        // they overlap beyond it when they leave it the same way.
        Some((p, q, _, s)) => {
            orient2d(a, b, c) == 0.0 && orient2d(a, b, d) == 0.0 && same_direction(p, q, s)
        }
        None => segments_meet(a, b, c, d),
    }
}

/// Fills thin holes, then drops thin polygons.
fn drop_thin(m: &mut MultiPolygon, delta: f64) {
    for poly in m.iter_mut() {
        let mut k = 1;
        while k < poly.len() {
            if thin(std::slice::from_ref(&poly[k]), delta) {
                poly.remove(k);
            } else {
                k += 1;
            }
        }
    }
    m.retain(|poly: &Polygon| !thin(poly, delta));
}

/// True when the rings' summed area is at most δ times their summed perimeter.
fn thin(rings: &[Ring], delta: f64) -> bool {
    let area: f64 = rings.iter().map(|r| ring_area(r)).sum();
    area.abs() <= delta * rings.iter().map(|r| perimeter(r)).sum::<f64>()
}

/// A closed ring's length.
fn perimeter(r: &[Pt2]) -> f64 {
    let n = r.len();
    (0..n)
        .map(|i| {
            let (a, b) = (r[i], r[(i + 1) % n]);
            (b[0] - a[0]).hypot(b[1] - a[1])
        })
        .sum()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::poly2::multipolygon_area;

    fn square(x: f64, y: f64, s: f64) -> Ring {
        vec![[x, y], [x + s, y], [x + s, y + s], [x, y + s]]
    }

    fn up(x: f64) -> f64 {
        f64::from_bits(x.to_bits() + 1)
    }

    #[test]
    fn clean_regions_are_borrowed_untouched() {
        let m = vec![vec![square(0., 0., 1.)]];
        assert!(matches!(clean(&m, dust_delta(1.0)), Cow::Borrowed(_)));
        // A tiny but real square, far below any absolute threshold, is kept.
        let tiny = vec![vec![square(0.5, 0.5, 1e-9)]];
        assert!(matches!(clean(&tiny, dust_delta(1.0)), Cow::Borrowed(_)));
        let pts = [&m, &tiny].into_iter().flatten().flatten().flatten();
        assert_eq!(pts.fold(0.0, |e, p| extent_with(e, *p)), 1.0);
    }

    #[test]
    fn one_ulp_pairs_merge_and_the_first_point_stays() {
        let delta = dust_delta(1.0);
        // Points one ulp apart in the middle of a ring, and the last one ulp from the first.
        let r = vec![
            [0.0, 0.0],
            [1.0, 0.0],
            [up(1.0), up(0.0)],
            [1.0, 1.0],
            [0.0, 1.0],
            [0.0, f64::from_bits(1)],
        ];
        let m = vec![vec![r]];
        let c = clean(&m, delta);
        assert_eq!(*c, vec![vec![square(0., 0., 1.)]]);
        // Just over δ apart: kept.
        let far = vec![vec![vec![
            [0.0, 0.0],
            [1.0, 0.0],
            [1.0 + 1.1 * delta, 0.0],
            [1.0, 1.0],
        ]]];
        assert!(matches!(clean(&far, delta), Cow::Borrowed(_)));
    }

    #[test]
    fn collapsed_rings_go_and_an_outer_ring_takes_its_holes() {
        let delta = dust_delta(4.0);
        // suzanne's face 3: a triangle whose two points are one ulp apart.
        let sliver = vec![
            [-5.254232250917861, 0.2643626128904635],
            [-5.2292511515387, 0.24397062926205362],
            [-5.2292511515387, 0.24397062926205365],
        ];
        let m = vec![vec![sliver.clone()], vec![square(0., 0., 1.)]];
        assert_eq!(*clean(&m, delta), vec![vec![square(0., 0., 1.)]]);
        // An outer sliver with a hole: both go. A sliver hole goes alone.
        let mut hole = square(0.25, 0.25, 0.5);
        hole.reverse();
        let with_hole = vec![vec![sliver.clone(), hole.clone()]];
        assert!(clean(&with_hole, delta).is_empty());
        let mut sliver_hole = sliver;
        sliver_hole.reverse();
        let m = vec![vec![square(-6., 0., 1.), sliver_hole]];
        assert_eq!(*clean(&m, delta), vec![vec![square(-6., 0., 1.)]]);
    }

    #[test]
    fn thin_polygons_and_holes_go_thick_ones_stay() {
        let delta = dust_delta(1.0);
        // A 1 x w rectangle: area w, perimeter 2 + 2w; thin when w <= 2δ / (1 - 2δ).
        let rect = |w: f64| vec![[0.0, 0.0], [1.0, 0.0], [1.0, w], [0.0, w]];
        assert!(clean(&vec![vec![rect(1.9 * delta)]], delta).is_empty());
        assert_eq!(clean(&vec![vec![rect(2.1 * delta)]], delta).len(), 1);
        // A thin hole is filled; the area follows the rings.
        let mut hole = vec![
            [0.2, 0.5],
            [0.8, 0.5],
            [0.8, 0.5 + 1.5 * delta],
            [0.2, 0.5 + 1.5 * delta],
        ];
        hole.reverse();
        let m = vec![vec![square(0., 0., 1.), hole]];
        let c = clean(&m, delta);
        assert_eq!(*c, vec![vec![square(0., 0., 1.)]]);
        assert_eq!(multipolygon_area(&c), 1.0);
    }

    /// A W-shaped ring whose point (2, 0) lies δ/4 above its bottom edge, which runs from
    /// (0, 0) through a point (v) within δ of it: merging v would put (2, 0) on the edge.
    fn w_ring(delta: f64) -> Ring {
        vec![
            [0.0, 0.0],
            [0.4 * delta, -0.4 * delta],
            [4.0, 0.0],
            [4.0, 4.0],
            [2.0, 0.0],
            [0.0, 4.0],
        ]
    }

    #[test]
    fn a_merge_that_would_spoil_a_ring_goes_into_the_runs_last_point() {
        let delta = 0.01;
        let m = vec![vec![w_ring(delta)]];
        assert_eq!(ring_defect(&m[0][0], true), None);
        assert!(has_dust(&m, delta));
        // (0, 0) goes instead of v; the ring starts again at its least point.
        let want = vec![
            [0.0, 4.0],
            [0.4 * delta, -0.4 * delta],
            [4.0, 0.0],
            [4.0, 4.0],
            [2.0, 0.0],
        ];
        assert_eq!(*clean(&m, delta), vec![vec![want.clone()]]);
        assert_eq!(ring_defect(&want, true), None);
    }

    /// suzanne's face 203: a merge beside a vertex the ring shares with another polygon (and a
    /// dust triangle there) goes through: the shared vertex is no new contact.
    #[test]
    fn rings_touching_at_a_vertex_do_not_hold_a_merge_back() {
        let delta = 0.01;
        let a = vec![[0.0, 0.0], [2.0, 0.0], [2.0, 0.004], [2.0, 2.0], [0.0, 2.0]];
        let b = vec![[2.0, 0.0], [3.0, -1.0], [3.0, 0.0]];
        let sliver = vec![[2.0, 0.0], [2.005, 0.0], [2.005, 0.001]];
        let m = vec![vec![a], vec![b.clone()], vec![sliver]];
        let merged = vec![vec![square(0., 0., 2.)], vec![b.clone()]];
        assert_eq!(*clean(&m, delta), merged);
        // Collinear and overlapping beyond the shared vertex: a new contact.
        let along = vec![[2.0, 0.0], [3.0, 0.5], [2.0, 1.0]];
        assert!(new_contact([2.0, 0.0], [2.0, 2.0], [2.0, 0.0], [2.0, 1.0]));
        assert!(!new_contact(
            [2.0, 0.0],
            [2.0, 2.0],
            [2.0, 0.0],
            [2.0, -1.0]
        ));
        assert!(!new_contact([2.0, 0.0], [2.0, 2.0], [3.0, 0.0], [2.0, 0.0]));
        let a = vec![[0.0, 0.0], [2.0, 0.0], [2.0, 0.004], [2.0, 2.0], [0.0, 2.0]];
        let m = vec![vec![a], vec![along]];
        assert_eq!(*clean(&m, delta), m);
    }

    #[test]
    fn a_merge_that_would_meet_another_ring_is_undone() {
        let delta = 0.25;
        // The bottom edge's dip, and a second polygon touching y = 0 from below at (2, 0)...
        let r = vec![[0.0, 0.0], [0.125, 0.0625], [4.0, 0.0], [4.0, 4.0]];
        let below = vec![[1.0, -10.0], [3.0, -10.0], [2.0, 0.0]];
        let m = vec![vec![r.clone()], vec![below.clone()]];
        assert!(ring_defect(&r, true).is_none() && ring_defect(&below, true).is_none());
        // ...so the merged edge (0,0)-(4,0) would touch it: the run goes into its last point.
        let last = vec![[0.125, 0.0625], [4.0, 0.0], [4.0, 4.0]];
        assert_eq!(*clean(&m, delta), vec![vec![last], vec![below.clone()]]);
        // A third polygon on that edge's replacement, (4,4)-(0.125,0.0625): kept as it was.
        let third = vec![[1.0, 9.0], [2.0625, 2.03125], [3.0, 9.0]];
        let m = vec![vec![r.clone()], vec![below], vec![third]];
        assert_eq!(*clean(&m, delta), m);
        // Alone, the run goes into its first point.
        let alone = vec![vec![r]];
        assert_eq!(
            *clean(&alone, delta),
            vec![vec![vec![[0.0, 0.0], [4.0, 0.0], [4.0, 4.0]]]]
        );
    }
}
