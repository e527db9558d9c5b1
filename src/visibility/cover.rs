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
//!
//! The argument holds for any subset of the regions (a subset that covers F covers it), so
//! where a second layer's boundary crosses F the regions making that part of the boundary are
//! left out, and the layer in front is tested alone ([`regions_cover`]).

use crate::geom::convexity::{is_convex_ccw, Strictness::AllowCollinear};
use crate::geom::orient2d;
use crate::geom::poly2::Pt2;

use super::occlusion::separated_convex;

/// A directed boundary segment, its orientation (+1 as stored, -1 reversed) and its region.
type Seg = (Pt2, Pt2, i32, u32);

/// Reusable buffers of the cover test.
#[derive(Debug, Default)]
pub(crate) struct CoverScratch {
    segs: Vec<Seg>,
    /// Per group of equal segments (in `segs` order): its first segment.
    group_start: Vec<u32>,
    /// Per group: whether it meets F's interior, once asked.
    meets: Vec<Option<bool>>,
    broken: Vec<bool>,
    /// Each region's groups (CSR: `region_at[k]..region_at[k + 1]` in `region_groups`).
    region_at: Vec<u32>,
    region_groups: Vec<u32>,
    /// Where each region's next group goes while `region_groups` is filled.
    fill: Vec<u32>,
    dead: Vec<bool>,
    stack: Vec<u32>,
}

/// True when the union of `regions` covers all of the convex counter-clockwise ring `f`
/// (exact; false when it cannot show it: the caller then clips). Regions that are not convex
/// counter-clockwise rings are left out (leaving one out only makes the test stricter).
///
/// Where the boundary of the sum crosses F, the regions that make that part of it are left
/// out too: an occluder of a second layer whose edge crosses F falls away, and the layer in
/// front of it, which alone covers F, is shown to. A group of equal segments that meets F's
/// interior is *broken* when its net use is not zero or one of its regions is left out; every
/// region of a broken group is left out. The regions left out are the least set closed under
/// that rule (the rule only grows with the set), so they do not depend on the regions'
/// order; and every group that meets F keeps all its regions (net zero) or none.
pub(crate) fn regions_cover<'a>(
    regions: impl Iterator<Item = &'a [Pt2]> + Clone,
    f: &[Pt2],
    b: &mut CoverScratch,
) -> bool {
    if !is_convex_ccw(f, AllowCollinear) {
        return false;
    }
    let usable: Vec<&[Pt2]> = regions
        .filter(|r| is_convex_ccw(r, AllowCollinear))
        .collect();
    // A seed: a region whose interior meets F's (for convex rings with area, "not separated").
    // The regions before the first seed are known not to be seeds.
    let is_seed = |k: usize| !separated_convex(usable[k], f);
    let Some(first_seed) = (0..usable.len()).find(|&k| is_seed(k)) else {
        return false;
    };
    collect_segments(&usable, b);
    group_segments(b, usable.len());
    b.dead.clear();
    b.dead.resize(usable.len(), false);
    b.stack.clear();
    for g in 0..b.group_start.len() - 1 {
        let range = b.group_start[g] as usize..b.group_start[g + 1] as usize;
        let net: i32 = b.segs[range].iter().map(|s| s.2).sum();
        if net != 0 && b.meets(g, f) {
            b.break_group(g);
        }
    }
    while let Some(k) = b.stack.pop() {
        let k = k as usize;
        for i in b.region_at[k] as usize..b.region_at[k + 1] as usize {
            let g = b.region_groups[i] as usize;
            if !b.broken[g] && b.meets(g, f) {
                b.break_group(g);
            }
        }
    }
    (first_seed..usable.len()).any(|k| !b.dead[k] && (k == first_seed || is_seed(k)))
}

/// Every region's edges, undirected (the lesser point first, the sign records the
/// direction), with the region's index, sorted so that equal segments are adjacent.
fn collect_segments(usable: &[&[Pt2]], b: &mut CoverScratch) {
    b.segs.clear();
    for (k, r) in usable.iter().enumerate() {
        let n = r.len();
        for i in 0..n {
            let (p, q) = (r[i], r[(i + 1) % n]);
            if p == q {
                continue;
            }
            if less(&p, &q) {
                b.segs.push((p, q, 1, k as u32));
            } else {
                b.segs.push((q, p, -1, k as u32));
            }
        }
    }
    b.segs
        .sort_unstable_by(|a, c| cmp_pt(&a.0, &c.0).then(cmp_pt(&a.1, &c.1)));
}

/// The groups of equal segments, and each region's groups.
fn group_segments(b: &mut CoverScratch, regions: usize) {
    b.group_start.clear();
    for (i, s) in b.segs.iter().enumerate() {
        if i == 0 || (b.segs[i - 1].0, b.segs[i - 1].1) != (s.0, s.1) {
            b.group_start.push(i as u32);
        }
    }
    b.group_start.push(b.segs.len() as u32);
    let groups = b.group_start.len() - 1;
    b.meets.clear();
    b.meets.resize(groups, None);
    b.broken.clear();
    b.broken.resize(groups, false);
    b.region_at.clear();
    b.region_at.resize(regions + 1, 0);
    for s in &b.segs {
        b.region_at[s.3 as usize + 1] += 1;
    }
    for k in 0..regions {
        b.region_at[k + 1] += b.region_at[k];
    }
    b.region_groups.clear();
    b.region_groups.resize(b.segs.len(), 0);
    b.fill.clone_from(&b.region_at);
    for g in 0..groups {
        for s in &b.segs[b.group_start[g] as usize..b.group_start[g + 1] as usize] {
            let k = s.3 as usize;
            b.region_groups[b.fill[k] as usize] = g as u32;
            b.fill[k] += 1;
        }
    }
}

impl CoverScratch {
    /// Whether group `g`'s segment meets the interior of `f` (decided once).
    fn meets(&mut self, g: usize, f: &[Pt2]) -> bool {
        let s = self.segs[self.group_start[g] as usize];
        *self.meets[g].get_or_insert_with(|| meets_interior(s.0, s.1, f))
    }

    /// Marks group `g` broken and leaves out each of its regions not yet left out.
    fn break_group(&mut self, g: usize) {
        self.broken[g] = true;
        for i in self.group_start[g] as usize..self.group_start[g + 1] as usize {
            let k = self.segs[i].3;
            if !self.dead[k as usize] {
                self.dead[k as usize] = true;
                self.stack.push(k);
            }
        }
    }
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

    fn covers(regions: &[Ring], f: &[Pt2]) -> bool {
        regions_cover(
            regions.iter().map(Vec::as_slice),
            f,
            &mut CoverScratch::default(),
        )
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
    fn a_second_layer_crossing_the_face_falls_away() {
        let f = [[0.1, 0.2], [0.9, 0.1], [0.5, 0.9]];
        // A triangle behind the square (a second layer) with an edge across F: the sum's
        // boundary crosses F, so the regions together cannot be shown to cover it, but the
        // square without that triangle can.
        let mut layers = square_halves();
        layers.push(vec![[0.5, 0.0], [1.5, 0.5], [0.5, 0.6]]);
        assert!(covers(&layers, &f));
        // The triangle alone is no cover, and the square's halves are still needed.
        assert!(!covers(&layers[1..], &f));
        // A second layer with a hole over F takes nothing away from the layer that covers F.
        let hole = [[0.45, 0.3], [0.55, 0.3], [0.5, 0.4]];
        assert!(!covers(&layers[2..], &hole));
        assert!(covers(&layers, &hole));
    }

    #[test]
    fn a_region_sharing_a_broken_segment_falls_with_it() {
        // The square's diagonal meets F; a copy of one half makes the diagonal's net use
        // nonzero, so every region on it falls, the square's halves too: no proof (the rule
        // gives up rather than guess which copy to keep).
        let f = [[0.1, 0.2], [0.9, 0.1], [0.5, 0.9]];
        let mut twice = square_halves();
        twice.push(twice[0].clone());
        assert!(!covers(&twice, &f));
        // F away from the diagonal is still covered by the copy's half.
        let g = [[0.6, 0.1], [0.9, 0.1], [0.9, 0.4]];
        assert!(covers(&twice, &g));
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

    /// A random fan around a random centre: a star-shaped patch of counter-clockwise
    /// triangles sharing edges exactly, as the pass gives them.
    fn random_fan(rng: &mut crate::geom::rng::XorShift) -> Vec<Ring> {
        let c = [rng.unit(), rng.unit()];
        let k = 3 + rng.below(6);
        let mut angles: Vec<f64> = (0..k)
            .map(|_| rng.range(0.0, std::f64::consts::TAU))
            .collect();
        angles.sort_by(f64::total_cmp);
        let pts: Vec<Pt2> = angles
            .iter()
            .map(|a| {
                let r = 0.3 + rng.unit();
                [c[0] + r * a.cos(), c[1] + r * a.sin()]
            })
            .collect();
        (0..k)
            .map(|i| vec![c, pts[i], pts[(i + 1) % k]])
            .filter(|t| orient2d(t[0], t[1], t[2]) > 0.0)
            .collect()
    }

    /// A random counter-clockwise triangle with area near `c`.
    fn random_triangle(rng: &mut crate::geom::rng::XorShift, c: Pt2, size: f64) -> Option<Ring> {
        let mut t: Ring = (0..3)
            .map(|_| [c[0] + rng.range(-size, size), c[1] + rng.range(-size, size)])
            .collect();
        match orient2d(t[0], t[1], t[2]) {
            o if o > 0.0 => Some(t),
            o if o < 0.0 => {
                t.reverse();
                Some(t)
            }
            _ => None,
        }
    }

    /// Properties on random layers: a fan over F with stray triangles behind it (their edges
    /// crossing F and the fan) — whenever the test says "covered" the exact boolean leaves
    /// nothing; a fan that covers F alone still covers it with the strays (they share no
    /// edge with it); and the answer does not depend on the regions' order.
    #[test]
    fn layers_agree_with_the_boolean_and_keep_the_front_cover() {
        let mut rng = crate::geom::rng::XorShift::new(0x5eed_1a7e);
        let (mut front, mut said, mut checked) = (0, 0, 0);
        for _ in 0..600 {
            let fan = random_fan(&mut rng);
            let c = fan[0][0];
            let Some(f) = random_triangle(&mut rng, c, 0.5) else {
                continue;
            };
            let mut all = fan.clone();
            for _ in 0..rng.below(5) {
                all.extend(random_triangle(&mut rng, c, 0.8));
            }
            checked += 1;
            let covered = covers(&all, &f);
            if covers(&fan, &f) {
                front += 1;
                assert!(
                    covered,
                    "strays behind took the fan's cover away: {all:?} {f:?}"
                );
            }
            let mut reversed = all.clone();
            reversed.reverse();
            assert_eq!(covers(&reversed, &f), covered, "order changed the answer");
            if covered {
                said += 1;
                let rect = Rect::of_points(all.iter().flatten().chain(f.iter()));
                let rest = subtract(&f, &rect, &all);
                assert!(rest.is_empty(), "covered, yet the boolean leaves {rest:?}");
            }
        }
        assert!(
            front > 20 && said >= front && said < checked,
            "{front} {said} {checked}"
        );
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
