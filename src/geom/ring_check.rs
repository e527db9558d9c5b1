//! Exact validity of emitted rings: simple (no edge meets another except its neighbours at
//! their shared vertex), no repeated point, nonzero area, outer rings counter-clockwise and
//! holes clockwise. Decided with exact orient2d only; and the repair of rings that the
//! rounding from the boolean engine's integer grid back to f64 spoiled.
//!
//! The integer grid is finer than f64 near the face (boolean.rs), so a sliver one or two
//! grid units wide rounds to a ring that folds back on itself or crosses itself, enclosing
//! an area of the order of one ulp times its length. [`repair`] removes, from a ring that is
//! not valid, points a few ulps from the next and spikes (a zero-width tail that rounding
//! turned into a fold or a crossing), and drops a ring that is still not valid when its area is within
//! that rounding ([`SLIVER_ULPS`] ulps of the largest coordinate times its perimeter): such a
//! ring was a zero-width sliver before the rounding. A ring that is not valid and not such a
//! sliver is kept as it is (never seen; the ring tests would report it).

use super::poly2::{ring_area, MultiPolygon, Polygon, Pt2, Ring};
use super::predicates::orient2d;

/// What is wrong with a ring.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum RingDefect {
    /// Fewer than three points.
    TooShort,
    /// Two vertices at the same point.
    RepeatedPoint,
    /// Two edges meet other than neighbours at their shared vertex (crossing, touching, or
    /// folding back along each other).
    SelfCrossing,
    /// The ring encloses no area.
    ZeroArea,
    /// Counter-clockwise where clockwise is due, or the reverse.
    WrongOrientation,
}

/// The first defect of a ring that should turn counter-clockwise (`ccw`) or clockwise.
pub(crate) fn ring_defect(r: &[Pt2], ccw: bool) -> Option<RingDefect> {
    if r.len() < 3 {
        return Some(RingDefect::TooShort);
    }
    let mut sorted: Vec<Pt2> = r.to_vec();
    sorted.sort_by(|a, b| a[0].total_cmp(&b[0]).then(a[1].total_cmp(&b[1])));
    if sorted.windows(2).any(|w| w[0] == w[1]) {
        return Some(RingDefect::RepeatedPoint);
    }
    if crossing(r) {
        return Some(RingDefect::SelfCrossing);
    }
    // A simple ring's orientation is that of the turn at its least point (exact).
    let n = r.len();
    let k = (0..n)
        .min_by(|&i, &j| {
            r[i][0]
                .total_cmp(&r[j][0])
                .then(r[i][1].total_cmp(&r[j][1]))
        })
        .unwrap_or(0);
    let turn = orient2d(r[(k + n - 1) % n], r[k], r[(k + 1) % n]);
    if turn == 0.0 {
        // The least point of a simple ring with distinct points is a strict corner unless
        // every point is collinear.
        return Some(RingDefect::ZeroArea);
    }
    ((turn > 0.0) != ccw).then_some(RingDefect::WrongOrientation)
}

#[cfg(test)]
/// Every defect of a multipolygon's rings: (polygon, ring, defect), outer rings CCW first,
/// holes CW after.
pub(crate) fn multipolygon_defects(m: &MultiPolygon) -> Vec<(usize, usize, RingDefect)> {
    let mut out = Vec::new();
    for (p, poly) in m.iter().enumerate() {
        for (k, r) in poly.iter().enumerate() {
            if let Some(d) = ring_defect(r, k == 0) {
                out.push((p, k, d));
            }
        }
    }
    out
}

/// A ring that is not valid after the rounding is dropped when |area| is at most this many
/// ulps (2^-52) of the largest coordinate magnitude times the ring's perimeter.
pub(crate) const SLIVER_ULPS: f64 = 8.0;

/// Repairs the rings of a multipolygon made by the boolean engine (see the module
/// documentation): every ring comes out valid or is a kept, reported defect. Returns the
/// number of rings dropped.
pub(crate) fn repair(m: &mut MultiPolygon) -> usize {
    let mut dropped = 0;
    for poly in m.iter_mut() {
        for (k, r) in poly.iter_mut().enumerate() {
            if ring_defect(r, k == 0).is_some() {
                remove_spikes(r);
                if ring_defect(r, k == 0).is_some() && is_sliver(r) {
                    r.clear();
                } else if ring_defect(r, k == 0).is_some() {
                    nudge(r, k == 0);
                }
            }
        }
        if poly.first().is_some_and(Vec::is_empty) {
            dropped += poly.len();
            poly.clear();
        } else {
            let before = poly.len();
            poly.retain(|r| !r.is_empty());
            dropped += before - poly.len();
        }
    }
    m.retain(|p: &Polygon| !p.is_empty());
    dropped
}

/// True when the ring's area is within rounding of zero for its length.
fn is_sliver(r: &Ring) -> bool {
    let n = r.len();
    if n < 3 {
        return true;
    }
    let scale = r
        .iter()
        .fold(0.0f64, |m, p| m.max(p[0].abs()).max(p[1].abs()));
    let perimeter: f64 = (0..n)
        .map(|i| {
            let (a, b) = (r[i], r[(i + 1) % n]);
            (b[0] - a[0]).hypot(b[1] - a[1])
        })
        .sum();
    ring_area(r).abs() <= SLIVER_ULPS * f64::EPSILON * scale * perimeter
}

/// Removes points within rounding (δ = [`SLIVER_ULPS`] ulps of the ring's largest
/// coordinate) of the next, and spikes: a vertex whose neighbours lie within δ of each other,
/// or whose edges fold back exactly along each other; until none is left. Each removal
/// moves the boundary by at most δ.
fn remove_spikes(r: &mut Ring) {
    let scale = r
        .iter()
        .fold(0.0f64, |m, p| m.max(p[0].abs()).max(p[1].abs()));
    let delta = SLIVER_ULPS * f64::EPSILON * scale;
    let near = |a: Pt2, b: Pt2| (a[0] - b[0]).abs() <= delta && (a[1] - b[1]).abs() <= delta;
    let mut changed = true;
    while changed && r.len() >= 3 {
        changed = false;
        let n = r.len();
        for i in 0..n {
            let (p, v, q) = (r[(i + n - 1) % n], r[i], r[(i + 1) % n]);
            let spike = near(v, q)
                || near(p, q)
                || (orient2d(p, v, q) == 0.0 && v != p && v != q && same_direction(v, p, q));
            if spike {
                r.remove(i);
                changed = true;
                break;
            }
        }
    }
    if r.len() < 3 {
        r.clear();
    }
}

/// Most ulps a vertex is moved by [`nudge`].
pub(crate) const NUDGE_ULPS: u32 = 4;

/// Mends a ring that crosses itself only because a vertex was rounded onto the wrong side of
/// an edge within an ulp or two of it (seen on the town: a vertex 4.9e-18 past an edge at
/// coordinates near 0.32): tries moving one endpoint of a crossing pair of edges by 1 to
/// [`NUDGE_ULPS`] ulps in each of eight directions, and keeps the first move that leaves the
/// ring valid (exact [`ring_defect`]). The boundary moves by at most √2·NUDGE_ULPS ulps, within
/// output rounding. A ring no such move mends is left as it was.
fn nudge(r: &mut Ring, ccw: bool) {
    let Some((i, j)) = crossing_pair(r) else {
        return;
    };
    let n = r.len();
    let step = |x: f64, k: i64| {
        let mut y = x;
        for _ in 0..k.unsigned_abs() {
            y = if k > 0 { y.next_up() } else { y.next_down() };
        }
        y
    };
    for v in [i, (i + 1) % n, j, (j + 1) % n] {
        let p = r[v];
        for k in 1..=i64::from(NUDGE_ULPS) {
            for (dx, dy) in [
                (1, 0),
                (-1, 0),
                (0, 1),
                (0, -1),
                (1, 1),
                (1, -1),
                (-1, 1),
                (-1, -1),
            ] {
                r[v] = [step(p[0], dx * k), step(p[1], dy * k)];
                if ring_defect(r, ccw).is_none() {
                    return;
                }
            }
        }
        r[v] = p;
    }
}

/// True when two edges of the ring (distinct points) meet other than neighbours at their
/// shared vertex. Edges are swept in order of their least x.
fn crossing(r: &[Pt2]) -> bool {
    crossing_pair(r).is_some()
}

/// The first two edges (by their first points' indices) of the ring that meet other than
/// neighbours at their shared vertex, as [`crossing`] finds them.
fn crossing_pair(r: &[Pt2]) -> Option<(usize, usize)> {
    let n = r.len();
    let edge = |i: usize| (r[i], r[(i + 1) % n]);
    let mut order: Vec<usize> = (0..n).collect();
    let xmin = |i: usize| r[i][0].min(r[(i + 1) % n][0]);
    let xmax = |i: usize| r[i][0].max(r[(i + 1) % n][0]);
    order.sort_by(|&a, &b| xmin(a).total_cmp(&xmin(b)));
    for (s, &i) in order.iter().enumerate() {
        for &j in &order[s + 1..] {
            if xmin(j) > xmax(i) {
                break;
            }
            let (a, b) = edge(i);
            let (c, d) = edge(j);
            let neighbours = (i + 1) % n == j || (j + 1) % n == i;
            if neighbours {
                // Adjacent edges share one vertex; they must not fold back along each other.
                let (shared, p, q) = if (i + 1) % n == j {
                    (b, a, d)
                } else {
                    (a, b, c)
                };
                if orient2d(p, shared, q) == 0.0 && same_direction(shared, p, q) {
                    return Some((i, j));
                }
                if n == 3 {
                    continue;
                }
            } else if segments_meet(a, b, c, d) {
                return Some((i, j));
            }
        }
    }
    None
}

/// For collinear p, v, q (both distinct from v): p and q lie on the same side of v.
pub(crate) fn same_direction(v: Pt2, p: Pt2, q: Pt2) -> bool {
    let k = if p[0] != v[0] { 0 } else { 1 };
    (p[k] > v[k]) == (q[k] > v[k])
}

/// Exact: closed segments ab and cd share a point.
pub(crate) fn segments_meet(a: Pt2, b: Pt2, c: Pt2, d: Pt2) -> bool {
    let (d1, d2) = (orient2d(c, d, a), orient2d(c, d, b));
    let (d3, d4) = (orient2d(a, b, c), orient2d(a, b, d));
    if d1 * d2 < 0.0 && d3 * d4 < 0.0 {
        return true;
    }
    let within = |p: Pt2, q: Pt2, x: Pt2| {
        x[0] >= p[0].min(q[0])
            && x[0] <= p[0].max(q[0])
            && x[1] >= p[1].min(q[1])
            && x[1] <= p[1].max(q[1])
    };
    (d1 == 0.0 && within(c, d, a))
        || (d2 == 0.0 && within(c, d, b))
        || (d3 == 0.0 && within(a, b, c))
        || (d4 == 0.0 && within(a, b, d))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn defects_of_small_rings() {
        let sq = vec![[0., 0.], [1., 0.], [1., 1.], [0., 1.]];
        assert_eq!(ring_defect(&sq, true), None);
        assert_eq!(ring_defect(&sq, false), Some(RingDefect::WrongOrientation));
        let bow = vec![[0., 0.], [1., 1.], [1., 0.], [0., 1.]];
        assert_eq!(ring_defect(&bow, true), Some(RingDefect::SelfCrossing));
        let flat = vec![[0., 0.], [1., 0.], [2., 0.]];
        assert_eq!(ring_defect(&flat, true), Some(RingDefect::SelfCrossing));
        let spike = vec![[0., 0.], [2., 0.], [1., 0.], [1., 1.]];
        assert_eq!(ring_defect(&spike, true), Some(RingDefect::SelfCrossing));
        let rep = vec![[0., 0.], [1., 0.], [0., 0.], [0., 1.]];
        assert_eq!(ring_defect(&rep, true), Some(RingDefect::RepeatedPoint));
        // A vertex touching a non-adjacent edge.
        let touch = vec![[0., 0.], [4., 0.], [4., 4.], [2., 0.], [0., 4.]];
        assert_eq!(ring_defect(&touch, true), Some(RingDefect::SelfCrossing));
        // Collinear run along an edge is fine.
        let run = vec![[0., 0.], [1., 0.], [2., 0.], [2., 2.]];
        assert_eq!(ring_defect(&run, true), None);
        assert_eq!(ring_defect(&sq[..2], true), Some(RingDefect::TooShort));
        let mut hole = sq.clone();
        hole.reverse();
        let m = vec![vec![
            vec![[-1., -1.], [3., -1.], [3., 3.], [-1., 3.]],
            hole.clone(),
        ]];
        assert!(multipolygon_defects(&m).is_empty());
        let bad = vec![vec![hole.clone(), sq.clone()]];
        assert_eq!(multipolygon_defects(&bad).len(), 2);
    }

    #[test]
    fn rounded_slivers_are_dropped_and_spikes_removed() {
        // The shapes seen on real meshes: a sliver an ulp wide that crosses itself, and one
        // that turns the wrong way.
        let crossing = vec![
            [-4.781022644043009, 0.030847009696926102],
            [-4.758885994916704, 0.033153982256115565],
            [-4.758885994916703, 0.033153982256115565],
            [-4.781022644043009, 0.030847009696926105],
        ];
        let wrong = vec![
            [0.38548164677452557, 20.54857345691632],
            [0.40350662943748633, 20.577477732428036],
            [0.4035066294374849, 20.577477732428033],
        ];
        let sq = vec![[0., 0.], [1., 0.], [1., 1.], [0., 1.]];
        let mut m = vec![
            vec![crossing.clone()],
            vec![wrong],
            vec![sq.clone(), crossing],
        ];
        assert_eq!(repair(&mut m), 3);
        assert_eq!(m, vec![vec![sq.clone()]]);
        // A spike on a square is cut off; a valid ring is left alone.
        let mut spiked = vec![vec![vec![
            [0., 0.],
            [1., 0.],
            [2., 0.],
            [1., 0.],
            [1., 1.],
            [0., 1.],
        ]]];
        assert_eq!(repair(&mut spiked), 0);
        assert!(multipolygon_defects(&spiked).is_empty(), "{spiked:?}");
        // The town's ring (issue 31): a vertex 4.9e-18 past an edge, nudged back by an ulp.
        let town = vec![
            [0.32062538971937826, -0.09843046053439576],
            [0.3207331199762499, -0.22242323366626976],
            [0.3303339966859577, -0.22797442315996175],
            [0.3302317460805324, -0.1137072104645252],
            [0.3206363977018062, -0.1111001626910689],
        ];
        assert_eq!(ring_defect(&town, true), Some(RingDefect::SelfCrossing));
        let mut m = vec![vec![town.clone()]];
        assert_eq!(repair(&mut m), 0);
        assert!(multipolygon_defects(&m).is_empty(), "{m:?}");
        let moved: Vec<usize> = (0..5).filter(|&k| m[0][0][k] != town[k]).collect();
        assert_eq!(moved.len(), 1);
        // A real bow tie is no sliver: kept, and still reported.
        let mut bow = vec![vec![vec![[0., 0.], [2., 2.], [2., 0.], [0., 1.]]]];
        assert_eq!(repair(&mut bow), 0);
        assert_eq!(multipolygon_defects(&bow).len(), 1);
    }
}
