//! A screen segment against a closed region: the parameter intervals where it lies in the
//! region or on its boundary, from exact crossings (orient2d) and exact location tests.

use super::region::Region;
use crate::geom::poly2::{MultiPolygon, Pt2, Side};
use crate::geom::{orient2d, Rect};

/// A closed parameter interval [t0, t1] along a segment a → b (point a + t (b - a)).
pub(crate) type Interval = [f64; 2];

/// Relative distance under which a point counts as on a region's boundary: the regions come
/// from a fixed i64 grid that may move a boundary point by a few units in the last place.
const BOUNDARY_EPS: f64 = 1e-12;

/// Point at parameter `t` of the segment a → b (exactly a at 0 and b at 1).
pub(crate) fn at(a: Pt2, b: Pt2, t: f64) -> Pt2 {
    if t == 1.0 {
        return b;
    }
    [a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])]
}

/// The sub-intervals of [0, 1] where the segment a → b lies in the closed region `m`, sorted
/// and disjoint (touching intervals merged). A zero-length segment gives nothing.
pub(crate) fn intervals_in(a: Pt2, b: Pt2, m: &MultiPolygon) -> Vec<Interval> {
    intervals_in_region(a, b, &Region::new(m))
}

/// [`intervals_in`] for a region already indexed (many segments against one large region).
pub(crate) fn intervals_in_region(a: Pt2, b: Pt2, region: &Region) -> Vec<Interval> {
    if a == b || region.is_empty() {
        return Vec::new();
    }
    let sb = Rect::of_points([a, b].iter());
    let mb = region.rect();
    let scale = [a[0], a[1], b[0], b[1], mb.xmin, mb.ymin, mb.xmax, mb.ymax]
        .iter()
        .fold(0.0f64, |s, x| s.max(x.abs()));
    let eps = BOUNDARY_EPS * scale.max(f64::MIN_POSITIVE);
    if !sb.overlaps_closed(&mb.padded(eps)) {
        return Vec::new();
    }
    let mut ts = vec![0.0, 1.0];
    for [c, d] in region.edges_near(&sb.padded(eps)) {
        splits(a, b, c, d, &sb, eps, &mut ts);
    }
    ts.sort_by(f64::total_cmp);
    ts.dedup();
    let mut out: Vec<Interval> = Vec::new();
    for w in ts.windows(2) {
        let mid = at(a, b, 0.5 * (w[0] + w[1]));
        // The local test first: a piece along the boundary (every edge of the face itself)
        // needs no ray, whose cost grows with the boundary it crosses (a 100k-point star).
        if region.near_boundary(mid, eps) || region.locate(mid) != Side::Outside {
            push_merged(&mut out, [w[0], w[1]]);
        }
    }
    out
}

/// Adds the parameters where ring edge c → d crosses or touches the segment a → b.
fn splits(a: Pt2, b: Pt2, c: Pt2, d: Pt2, sb: &Rect, eps: f64, ts: &mut Vec<f64>) {
    if !Rect::of_points([c, d].iter()).overlaps_closed(&sb.padded(eps)) {
        return;
    }
    let (oc, od) = (orient2d(a, b, c), orient2d(a, b, d));
    let mut push = |t: f64| {
        if t > 0.0 && t < 1.0 {
            ts.push(t);
        }
    };
    // A ring vertex on the segment's line, or within eps of it (grid-snapped boundaries),
    // splits it there: a boundary running along the segment may end at that vertex, whichever
    // side of the line rounding put it on.
    if oc == 0.0 || dist_to_line(a, b, c) <= eps {
        push(param(a, b, c));
    }
    if od == 0.0 || dist_to_line(a, b, d) <= eps {
        push(param(a, b, d));
    }
    if oc == 0.0 || od == 0.0 || (oc > 0.0) == (od > 0.0) {
        return;
    }
    let (oa, ob) = (orient2d(c, d, a), orient2d(c, d, b));
    if oa != 0.0 && ob != 0.0 && (oa > 0.0) != (ob > 0.0) {
        push(oa / (oa - ob));
    }
}

/// Parameter of the projection of `p` on the line a → b.
fn param(a: Pt2, b: Pt2, p: Pt2) -> f64 {
    let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
    ((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / (dx * dx + dy * dy)
}

/// Distance of `p` from the line through a and b (a != b).
fn dist_to_line(a: Pt2, b: Pt2, p: Pt2) -> f64 {
    let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
    ((p[0] - a[0]) * dy - (p[1] - a[1]) * dx).abs() / dx.hypot(dy)
}

/// Appends an interval, merging it with the last one when they touch.
fn push_merged(out: &mut Vec<Interval>, iv: Interval) {
    match out.last_mut() {
        Some(last) if last[1] >= iv[0] => last[1] = last[1].max(iv[1]),
        _ => out.push(iv),
    }
}

/// Union of interval lists (each sorted and disjoint), sorted and merged.
pub(crate) fn union(lists: &[Vec<Interval>]) -> Vec<Interval> {
    let mut all: Vec<Interval> = lists.iter().flatten().copied().collect();
    all.sort_by(|p, q| p[0].total_cmp(&q[0]));
    let mut out = Vec::with_capacity(all.len());
    for iv in all {
        push_merged(&mut out, iv);
    }
    out
}

/// The complement of sorted, disjoint intervals within [0, 1] (zero-length gaps dropped).
pub(crate) fn complement(ivs: &[Interval]) -> Vec<Interval> {
    let mut out = Vec::new();
    let mut t = 0.0;
    for iv in ivs {
        if iv[0] > t {
            out.push([t, iv[0]]);
        }
        t = t.max(iv[1]);
    }
    if t < 1.0 {
        out.push([t, 1.0]);
    }
    out
}

#[cfg(test)]
mod boundary_split_tests {
    use super::*;

    #[test]
    fn collinear_boundary_ending_at_a_vertex_just_off_the_line() {
        // A VTP triangle one of whose edges runs along the segment from its end b back to
        // t ≈ 0.393, where its vertex lies a few ulps off the segment's line on the same
        // side as the triangle's third vertex: the segment touches the region only from there.
        let m = vec![vec![vec![
            [-0.27933405980619985, 2.7301521038740955],
            [-0.12479158486377023, 2.2570026291621175],
            [0.29767498954861393, 2.5297895212104207],
        ]]];
        let a = [-0.6516453089783969, 2.8594347269495772];
        let b = [0.29767498954861393, 2.5297895212104207];
        let iv = intervals_in(a, b, &m);
        assert_eq!(iv.len(), 1);
        assert!((iv[0][0] - 0.393).abs() < 2e-3 && iv[0][1] == 1.0, "{iv:?}");
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn square(x: f64, y: f64, s: f64) -> MultiPolygon {
        vec![vec![vec![[x, y], [x + s, y], [x + s, y + s], [x, y + s]]]]
    }

    #[test]
    fn crossing_segment_keeps_inside_part() {
        let m = square(0., 0., 2.);
        assert_eq!(intervals_in([-1., 1.], [3., 1.], &m), vec![[0.25, 0.75]]);
        assert!(intervals_in([-1., 3.], [3., 3.], &m).is_empty());
    }

    #[test]
    fn boundary_edge_is_in_closed_region() {
        let m = square(0., 0., 2.);
        assert_eq!(intervals_in([0., 0.], [2., 0.], &m), vec![[0.0, 1.0]]);
        assert_eq!(intervals_in([-2., 0.], [2., 0.], &m), vec![[0.5, 1.0]]);
    }

    #[test]
    fn hole_splits_segment() {
        let mut m = square(0., 0., 4.);
        m[0].push(vec![[1., 1.], [1., 3.], [3., 3.], [3., 1.]]);
        assert_eq!(
            intervals_in([0., 2.], [4., 2.], &m),
            vec![[0.0, 0.25], [0.75, 1.0]]
        );
    }

    #[test]
    fn nearly_collinear_snapped_boundary_counts() {
        // Boundary a hair off the segment (as a snapped grid boundary may be).
        let m = vec![vec![vec![[0., 1e-17], [1., 0.], [1., 1.], [0., 1.]]]];
        assert_eq!(intervals_in([0., 0.], [1., 0.], &m), vec![[0.0, 1.0]]);
    }

    #[test]
    fn union_and_complement() {
        let u = union(&[vec![[0.0, 0.25], [0.5, 0.6]], vec![[0.2, 0.3]]]);
        assert_eq!(u, vec![[0.0, 0.3], [0.5, 0.6]]);
        assert_eq!(complement(&u), vec![[0.3, 0.5], [0.6, 1.0]]);
        assert_eq!(complement(&[]), vec![[0.0, 1.0]]);
        assert!(complement(&[[0.0, 1.0]]).is_empty());
    }
}
