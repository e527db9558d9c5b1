//! The patch cover test: whether occluder regions, taken together, cover a face — decided
//! exactly from the boundary of their sum, before (and instead of) the boolean call.
//!
//! Why it is exact. Let every region G_i be a convex counter-clockwise ring (checked
//! exactly: it turns, and every point lies on the closed left side of every edge), so its
//! winding number is ≥ 1 inside its hull and 0 outside. The sum of the regions' boundaries is
//! a 1-cycle whose winding number around a point x (off every edge) is w(x) = Σ wind_i(x) ≥ 0,
//! and w(x) ≥ 1 exactly where x lies in some G_i. A segment used forward and backward equally
//! often has coefficient 0 in that cycle and can be dropped without changing w; what is left
//! (the "kept" segments, compared bit for bit) contains the cycle's support. w is constant on
//! every connected set that meets no kept segment. F (a convex ring) has a connected interior;
//! if no kept segment meets it, and one region's interior meets F's interior (where w ≥ 1),
//! then w ≥ 1 on all of F's interior off the edges, so F's interior lies in the union of the
//! closed regions, and so does F (the union is closed). Every test is a sign of `orient2d`.

use crate::geom::hull2::has_turn;
use crate::geom::orient2d;
use crate::geom::poly2::{half_changes, Pt2};

use super::occlusion::separated_convex;

/// A directed boundary segment, and its orientation (+1 as stored, -1 reversed).
type Seg = (Pt2, Pt2, i32);

/// True when `r` is a convex counter-clockwise ring with area (exact): it makes a proper
/// turn and every point lies on the closed left side of every edge.
///
/// In O(n): with repeated points dropped, every corner turns left or goes straight on (never
/// back: a spike is a half turn), some corner turns, and the edge directions wind round once
/// ([`half_changes`]); the ring then bounds a convex region, which is the closed-left-side
/// condition (the quadratic definition is the test below's reference).
pub fn is_convex_ccw_exact(r: &[Pt2]) -> bool {
    let mut d: Vec<Pt2> = Vec::with_capacity(r.len());
    for &p in r {
        if d.last() != Some(&p) {
            d.push(p);
        }
    }
    while d.len() > 1 && d.first() == d.last() {
        d.pop();
    }
    let n = d.len();
    n >= 3
        && has_turn(&d)
        && (0..n).all(|i| {
            let (a, b, c) = (d[i], d[(i + 1) % n], d[(i + 2) % n]);
            let o = orient2d(a, b, c);
            o > 0.0 || (o == 0.0 && !reverses(a, b, c))
        })
        && half_changes(&d) == 2
}

/// For collinear a, b, c (a ≠ b, b ≠ c): true when c lies back toward a from b (exact: the
/// signs of coordinate differences along an axis where a and b differ).
fn reverses(a: Pt2, b: Pt2, c: Pt2) -> bool {
    let k = if a[0] != b[0] { 0 } else { 1 };
    (b[k] > a[k]) != (c[k] > b[k])
}

/// True when the union of `regions` covers all of the convex counter-clockwise ring `f`
/// (exact; false when it cannot show it: the caller then clips). Regions that are not convex
/// counter-clockwise rings are left out (leaving one out only makes the test stricter).
/// `segs` is a reusable buffer.
pub fn regions_cover<'a>(
    regions: impl Iterator<Item = &'a [Pt2]> + Clone,
    f: &[Pt2],
    segs: &mut Vec<Seg>,
) -> bool {
    if !is_convex_ccw_exact(f) {
        return false;
    }
    let usable = regions.filter(|r| is_convex_ccw_exact(r));
    // A seed: a region whose interior meets F's (for convex rings with area, "not separated").
    if !usable.clone().any(|r| !separated_convex(r, f)) {
        return false;
    }
    segs.clear();
    for r in usable {
        let n = r.len();
        for i in 0..n {
            let (p, q) = (r[i], r[(i + 1) % n]);
            if p == q {
                continue;
            }
            // Undirected key: the lesser point first, the sign records the direction.
            if less(&p, &q) {
                segs.push((p, q, 1));
            } else {
                segs.push((q, p, -1));
            }
        }
    }
    segs.sort_unstable_by(|a, b| cmp_pt(&a.0, &b.0).then(cmp_pt(&a.1, &b.1)));
    let mut i = 0;
    while i < segs.len() {
        let (p, q) = (segs[i].0, segs[i].1);
        let mut net = 0;
        let mut j = i;
        while j < segs.len() && segs[j].0 == p && segs[j].1 == q {
            net += segs[j].2;
            j += 1;
        }
        if net != 0 && meets_interior(p, q, f) {
            return false;
        }
        i = j;
    }
    true
}

/// False only when segment pq provably misses the interior of convex ring `f` (exact: some
/// edge line of F, or pq's own line, has F on one closed side and pq on the other).
fn meets_interior(p: Pt2, q: Pt2, f: &[Pt2]) -> bool {
    let n = f.len();
    let by_edge = (0..n).any(|i| {
        let (a, b) = (f[i], f[(i + 1) % n]);
        a != b && orient2d(a, b, p) <= 0.0 && orient2d(a, b, q) <= 0.0
    });
    if by_edge {
        return false;
    }
    let left = f.iter().all(|&x| orient2d(p, q, x) >= 0.0);
    let right = f.iter().all(|&x| orient2d(p, q, x) <= 0.0);
    !(left || right)
}

fn cmp_pt(a: &Pt2, b: &Pt2) -> std::cmp::Ordering {
    a[0].total_cmp(&b[0]).then(a[1].total_cmp(&b[1]))
}

fn less(a: &Pt2, b: &Pt2) -> bool {
    cmp_pt(a, b) == std::cmp::Ordering::Less
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::boolean::subtract;
    use crate::geom::poly2::Ring;
    use crate::geom::Rect;

    /// The definition: a turn, and every point on the closed left side of every edge.
    fn convex_by_definition(r: &[Pt2]) -> bool {
        let n = r.len();
        n >= 3
            && has_turn(r)
            && (0..n).all(|i| {
                let (p, q) = (r[i], r[(i + 1) % n]);
                p == q || r.iter().all(|&x| orient2d(p, q, x) >= 0.0)
            })
    }

    #[test]
    fn the_linear_convexity_test_agrees_with_the_definition() {
        let mut rng = crate::geom::rng::XorShift::new(11);
        let grid =
            |rng: &mut crate::geom::rng::XorShift| [rng.below(4) as f64, rng.below(4) as f64];
        let mut agree_convex = 0;
        for k in 0..20000 {
            let n = 3 + k % 6;
            let r: Vec<Pt2> = (0..n).map(|_| grid(&mut rng)).collect();
            let (fast, slow) = (is_convex_ccw_exact(&r), convex_by_definition(&r));
            assert_eq!(fast, slow, "{r:?}");
            agree_convex += usize::from(fast);
        }
        assert!(agree_convex > 100, "{agree_convex}");
        // A pentagram turns left at every corner but winds twice; a spike goes back.
        let star: Vec<Pt2> = (0..5)
            .map(|k| {
                let a = std::f64::consts::TAU * (2 * k) as f64 / 5.0;
                [a.cos(), a.sin()]
            })
            .collect();
        assert!(!is_convex_ccw_exact(&star) && !convex_by_definition(&star));
        assert!(!crate::geom::poly2::is_convex_ccw(&star));
        let spike = [[0.0, 0.0], [2.0, 0.0], [1.0, 0.0], [1.0, 1.0]];
        assert!(!is_convex_ccw_exact(&spike) && !convex_by_definition(&spike));
    }

    fn covers(regions: &[Ring], f: &[Pt2]) -> bool {
        regions_cover(regions.iter().map(Vec::as_slice), f, &mut Vec::new())
    }

    /// The unit square as two triangles sharing its diagonal.
    fn square_halves() -> Vec<Ring> {
        vec![
            vec![[0., 0.], [1., 0.], [1., 1.]],
            vec![[0., 0.], [1., 1.], [0., 1.]],
        ]
    }

    #[test]
    fn two_halves_cover_a_triangle_across_their_diagonal() {
        let f = [[0.1, 0.2], [0.9, 0.1], [0.5, 0.9]];
        assert!(covers(&square_halves(), &f));
        // One half alone does not.
        assert!(!covers(&square_halves()[..1], &f));
    }

    #[test]
    fn a_face_reaching_outside_is_not_covered() {
        let f = [[0.1, 0.2], [1.5, 0.1], [0.5, 0.9]];
        assert!(!covers(&square_halves(), &f));
        // Touching the boundary from inside is still covered (closed regions).
        let g = [[0., 0.], [1., 0.], [1., 1.]];
        assert!(covers(&square_halves(), &g));
    }

    #[test]
    fn a_hole_in_a_ring_of_triangles_is_seen() {
        // Four triangles around the square [0,3]^2 leaving the middle [1,2]^2 open.
        let ring: Vec<Ring> = vec![
            vec![[0., 0.], [3., 0.], [2., 1.], [1., 1.]],
            vec![[3., 0.], [3., 3.], [2., 2.], [2., 1.]],
            vec![[3., 3.], [0., 3.], [1., 2.], [2., 2.]],
            vec![[0., 3.], [0., 0.], [1., 1.], [1., 2.]],
        ];
        let inside_hole = [[1.2, 1.2], [1.8, 1.2], [1.5, 1.8]];
        assert!(!covers(&ring, &inside_hole));
        let across = [[0.2, 0.2], [2.8, 0.2], [1.5, 0.8]];
        assert!(covers(&ring, &across));
        let over_hole = [[0.5, 0.5], [2.5, 0.5], [1.5, 2.5]];
        assert!(!covers(&ring, &over_hole));
    }

    #[test]
    fn clockwise_or_degenerate_regions_are_left_out() {
        let cw: Vec<Ring> = square_halves()
            .into_iter()
            .map(|mut r| {
                r.reverse();
                r
            })
            .collect();
        let f = [[0.1, 0.2], [0.9, 0.1], [0.5, 0.9]];
        assert!(!covers(&cw, &f));
        let flat = vec![vec![[0., 0.], [1., 1.], [2., 2.]]];
        assert!(!covers(&flat, &f));
    }

    /// Property: on random fans of triangles, whenever the test says "covered" the exact
    /// boolean leaves nothing; and a fan's own triangles are covered by the fan.
    #[test]
    fn agrees_with_the_boolean_on_random_fans() {
        let mut seed = 0x9e37_79b9_7f4a_7c15_u64;
        let mut rnd = || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            (seed >> 11) as f64 / (1u64 << 53) as f64
        };
        let (mut said, mut checked) = (0, 0);
        for _ in 0..400 {
            // A fan around a centre: a star-shaped patch of triangles sharing edges exactly.
            let c = [rnd(), rnd()];
            let k = 3 + (rnd() * 6.0) as usize;
            let mut angles: Vec<f64> = (0..k).map(|_| rnd() * std::f64::consts::TAU).collect();
            angles.sort_by(f64::total_cmp);
            let pts: Vec<Pt2> = angles
                .iter()
                .map(|a| {
                    let r = 0.3 + rnd();
                    [c[0] + r * a.cos(), c[1] + r * a.sin()]
                })
                .collect();
            // Counter-clockwise triangles only, as the pass gives them (a gap wider than a half
            // turn would make a clockwise one, which NonZero fill would subtract).
            let fan: Vec<Ring> = (0..k)
                .map(|i| vec![c, pts[i], pts[(i + 1) % k]])
                .filter(|t| orient2d(t[0], t[1], t[2]) > 0.0)
                .collect();
            let f: Vec<Pt2> = (0..3)
                .map(|_| [c[0] + rnd() - 0.5, c[1] + rnd() - 0.5])
                .collect();
            let mut f = f;
            if orient2d(f[0], f[1], f[2]) < 0.0 {
                f.reverse();
            }
            if orient2d(f[0], f[1], f[2]) == 0.0 {
                continue;
            }
            for t in &fan {
                assert!(covers(&fan, t), "a fan covers its own triangle");
            }
            checked += 1;
            if covers(&fan, &f) {
                said += 1;
                let rect = Rect::of_points(fan.iter().flatten().chain(f.iter()));
                let rest = subtract(&f, &rect, &fan);
                assert!(rest.is_empty(), "covered, yet the boolean leaves {rest:?}");
            }
        }
        assert!(said > 20 && said < checked, "{said} of {checked} covered");
    }
}
