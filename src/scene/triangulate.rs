//! Ear-clipping triangulation of a simple polygon in space (used to split non-planar faces).

use crate::geom::convexity::{is_convex_ccw, Strictness};
use crate::geom::poly2::ring_area;
use crate::geom::{orient2d, P3, V3};

/// Polygons of up to this many corners are clipped by the plain search with exact
/// predicates; larger ones by earcut's ear clipping over a z-order index, near-linear in
/// the corner count (a million-corner polygon is normal input), its result checked.
const SMALL: usize = 64;

/// Triangulates the polygon `pts` (simple, not necessarily planar or convex), projected along
/// the dominant axis of `normal`. Returns index triples into `pts`, each counter-clockwise
/// seen from the side `normal` points to. Falls back to a fan if the polygon is not simple.
pub(crate) fn ear_clip(pts: &[P3], normal: &V3) -> Vec<[usize; 3]> {
    ear_clip_simple(pts, normal).unwrap_or_else(|| {
        let (_, _, flip) = projection_axes(normal);
        fan(pts.len(), flip)
    })
}

/// [`ear_clip`], or None where it would fall back to a fan: no ear was found, so the
/// polygon, projected along the dominant axis of `normal`, is not simple. Every decision is
/// an exact orient2d on input coordinates.
pub(crate) fn ear_clip_simple(pts: &[P3], normal: &V3) -> Option<Vec<[usize; 3]>> {
    let (ax, ay, flip) = projection_axes(normal);
    let p2: Vec<[f64; 2]> = pts.iter().map(|p| [p[ax], p[ay]]).collect();
    if pts.len() > SMALL {
        if strictly_convex(&p2, flip) {
            return Some(balanced(pts.len()));
        }
        // None unless earcut's triangles provably tile the ring: treated as not simple (safe:
        // such a mesh is never culled).
        return earcut_checked(&p2, flip).filter(|t| tiles_exactly(&p2, t, flip));
    }
    let mut ring: Vec<usize> = (0..pts.len()).collect();
    if flip {
        ring.reverse();
    }
    let mut tris = Vec::with_capacity(pts.len().saturating_sub(2));
    while ring.len() > 3 {
        match find_ear(&p2, &ring) {
            Some(i) => {
                let n = ring.len();
                tris.push([ring[(i + n - 1) % n], ring[i], ring[(i + 1) % n]]);
                ring.remove(i);
            }
            None => return None,
        }
    }
    tris.push([ring[0], ring[1], ring[2]]);
    if flip {
        for t in &mut tris {
            t.swap(1, 2);
        }
    }
    Some(tris)
}

/// Exact: `pts`, projected along the dominant axis of `normal` as [`ear_clip_simple`]
/// projects it, is a strictly convex ring winding the way `normal` says.
pub(crate) fn strictly_convex_face(pts: &[P3], normal: &V3) -> bool {
    let (ax, ay, flip) = projection_axes(normal);
    let project = |p: &P3| [p[ax], p[ay]];
    // Counter-clockwise in projection: reversed where the projection flips.
    let p2: Vec<[f64; 2]> = if flip {
        pts.iter().rev().map(project).collect()
    } else {
        pts.iter().map(project).collect()
    };
    is_convex_ccw(&p2, Strictness::Strict)
}

/// Coordinate axes to project on (dropping the normal's dominant axis), and whether the
/// projection reverses orientation.
pub(crate) fn projection_axes(n: &V3) -> (usize, usize, bool) {
    let a = n.abs();
    let drop = if a.x >= a.y && a.x >= a.z {
        0
    } else if a.y >= a.z {
        1
    } else {
        2
    };
    let (ax, ay) = [(1, 2), (2, 0), (0, 1)][drop];
    (ax, ay, n[drop] < 0.0)
}

fn find_ear(p: &[[f64; 2]], ring: &[usize]) -> Option<usize> {
    let n = ring.len();
    (0..n).find(|&i| {
        let (a, b, c) = (p[ring[(i + n - 1) % n]], p[ring[i]], p[ring[(i + 1) % n]]);
        if orient2d(a, b, c) <= 0.0 {
            return false;
        }
        ring.iter().all(|&k| {
            let q = p[k];
            q == a
                || q == b
                || q == c
                || !(orient2d(a, b, q) >= 0.0
                    && orient2d(b, c, q) >= 0.0
                    && orient2d(c, a, q) >= 0.0)
        })
    })
}

/// Earcut's triangles of the ring `p` (counter-clockwise in projection unless `flip`),
/// oriented like the ring; None unless every triangle turns the ring's way (or not at all)
/// and their areas add up to the ring's.
fn earcut_checked(p: &[[f64; 2]], flip: bool) -> Option<Vec<[usize; 3]>> {
    let mut idx: Vec<u32> = Vec::with_capacity(3 * p.len());
    earcut::Earcut::new().earcut(p.iter().copied(), &[] as &[u32], &mut idx);
    let want = if flip { -1.0 } else { 1.0 };
    let mut tris = Vec::with_capacity(idx.len() / 3);
    let mut sum = 0.0;
    for t in idx.chunks_exact(3) {
        let mut t = [t[0] as usize, t[1] as usize, t[2] as usize];
        let o = orient2d(p[t[0]], p[t[1]], p[t[2]]);
        if o * want < 0.0 {
            t.swap(1, 2);
        }
        sum += ring_area(&[p[t[0]], p[t[1]], p[t[2]]]).abs();
        tris.push(t);
    }
    let area = ring_area(p);
    let consistent = area * want > 0.0 && (sum - area.abs()).abs() <= 1e-9 * area.abs();
    consistent.then_some(tris)
}

/// True when the triangles tile the ring exactly: each turns the ring's way strictly (exact
/// orient2d), and their directed edges cancel pairwise except the ring's own edges, each
/// once. Then every point is covered by as many triangles as the ring winds round it, so a
/// simple ring is covered once and nothing outside it is covered.
fn tiles_exactly(p: &[[f64; 2]], tris: &[[usize; 3]], flip: bool) -> bool {
    use std::collections::HashMap;
    let n = p.len();
    let want = if flip { -1.0 } else { 1.0 };
    let mut edges: HashMap<(usize, usize), i32> = HashMap::with_capacity(3 * tris.len());
    for t in tris {
        if orient2d(p[t[0]], p[t[1]], p[t[2]]) * want <= 0.0 {
            return false;
        }
        for k in 0..3 {
            let (a, b) = (t[k], t[(k + 1) % 3]);
            if a < b {
                *edges.entry((a, b)).or_default() += 1;
            } else {
                *edges.entry((b, a)).or_default() -= 1;
            }
        }
    }
    // The ring's own edges: triangles turning the ring's way run them in its direction.
    for i in 0..n {
        let (a, b) = (i, (i + 1) % n);
        if a < b {
            *edges.entry((a, b)).or_default() -= 1;
        } else {
            *edges.entry((b, a)).or_default() += 1;
        }
    }
    edges.values().all(|&c| c == 0)
}

/// Exact: the ring turns strictly the ring's way (left, or right when `flip`) at every
/// corner and winds once ([`Strictness::Strict`]; a clockwise ring is tested reversed, which
/// reverses every turn and keeps the winding count). Any three of its corners then make a
/// proper triangle.
fn strictly_convex(p: &[[f64; 2]], flip: bool) -> bool {
    if flip {
        let back: Vec<[f64; 2]> = p.iter().rev().copied().collect();
        is_convex_ccw(&back, Strictness::Strict)
    } else {
        is_convex_ccw(p, Strictness::Strict)
    }
}

/// A triangulation of a strictly convex ring whose triangles are balanced: the triangle of
/// corners 0, n/3, 2n/3, then each arc split at its middle corner, recursively. A straight
/// line meets O(log n) of its triangles' boxes near any point, where a fan's all share one
/// corner (the broad phase of the solidity test would pair every two of them).
/// Corners in ring order make triangles turning the ring's way (counter-clockwise seen from
/// the normal, as [`ear_clip_simple`] promises). For any ring, convex or not, the triangles'
/// boundaries add up to the ring's (each chord is run once each way), so as a 2-chain they
/// are the fan's: the same signed areas, volumes and winding numbers, with small boxes.
pub(crate) fn balanced(n: usize) -> Vec<[usize; 3]> {
    let mut tris = Vec::with_capacity(n - 2);
    let (a, b) = (n / 3, 2 * n / 3);
    tris.push([0, a, b]);
    let mut arcs = vec![(0, a), (a, b), (b, n)];
    while let Some((i, j)) = arcs.pop() {
        if j - i < 2 {
            continue;
        }
        let m = (i + j) / 2;
        tris.push([i, m, j % n]);
        arcs.push((i, m));
        arcs.push((m, j));
    }
    tris
}

fn fan(n: usize, flip: bool) -> Vec<[usize; 3]> {
    (1..n - 1)
        .map(|i| if flip { [0, i + 1, i] } else { [0, i, i + 1] })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn l_shape_gives_four_ccw_triangles_of_full_area() {
        let pts: Vec<P3> = [(0., 0.), (2., 0.), (2., 1.), (1., 1.), (1., 2.), (0., 2.)]
            .iter()
            .map(|&(x, y)| P3::new(x, y, 0.0))
            .collect();
        let tris = ear_clip(&pts, &V3::z());
        assert_eq!(tris.len(), 4);
        let mut area = 0.0;
        for t in &tris {
            let a2 = (pts[t[1]] - pts[t[0]]).cross(&(pts[t[2]] - pts[t[0]])).z;
            assert!(a2 > 0.0);
            area += a2 / 2.0;
        }
        assert!((area - 3.0).abs() < 1e-15);
    }

    /// The triangles cover the polygon exactly: each turns the normal's way and their areas
    /// add up to the polygon's.
    fn assert_covers(pts: &[P3], tris: &[[usize; 3]], normal: &V3) {
        assert_eq!(tris.len(), pts.len() - 2);
        let mut area = 0.0;
        for t in tris {
            let a2 = (pts[t[1]] - pts[t[0]])
                .cross(&(pts[t[2]] - pts[t[0]]))
                .dot(normal);
            assert!(a2 >= 0.0, "{t:?}");
            area += a2 / 2.0;
        }
        let want = crate::geom::newell(pts).dot(normal) / 2.0;
        assert!((area - want).abs() <= 1e-9 * want, "{area} vs {want}");
    }

    #[test]
    fn large_polygons_take_the_near_linear_path() {
        // A 4096-gon (convex) and a 3000-point star (non-convex), both ways round.
        let n = 4096;
        let circle: Vec<P3> = (0..n)
            .map(|k| {
                let a = k as f64 * std::f64::consts::TAU / n as f64;
                P3::new(a.cos(), a.sin(), 0.25)
            })
            .collect();
        let star: Vec<P3> = (0..3000)
            .map(|k| {
                let a = k as f64 * std::f64::consts::TAU / 3000.0;
                let r = if k % 2 == 0 { 1.0 } else { 0.3 };
                P3::new(r * a.cos(), 0.5, r * a.sin())
            })
            .collect();
        for pts in [circle, star] {
            let normal = crate::geom::newell(&pts).normalize();
            let (ax, ay, flip) = projection_axes(&normal);
            let p2: Vec<[f64; 2]> = pts.iter().map(|p| [p[ax], p[ay]]).collect();
            assert!(earcut_checked(&p2, flip).is_some());
            assert_covers(&pts, &ear_clip(&pts, &normal), &normal);
            let rev: Vec<P3> = pts.iter().rev().copied().collect();
            assert_covers(&rev, &ear_clip(&rev, &-normal), &-normal);
        }
    }

    #[test]
    fn clockwise_seen_from_normal_is_handled() {
        let pts: Vec<P3> = [(0., 0.), (0., 1.), (1., 1.), (1., 0.)]
            .iter()
            .map(|&(x, y)| P3::new(x, y, 0.0))
            .collect();
        for t in ear_clip(&pts, &-V3::z()) {
            assert!((pts[t[1]] - pts[t[0]]).cross(&(pts[t[2]] - pts[t[0]])).z < 0.0);
        }
    }

    #[test]
    fn big_polygons_are_proven_tiled_or_refused() {
        let n = 200;
        let ring = |k: usize| -> Vec<P3> {
            (0..n)
                .map(|i| {
                    let a = (k * i) as f64 * std::f64::consts::TAU / n as f64;
                    P3::new(a.cos(), a.sin(), 0.0)
                })
                .collect()
        };
        // A convex 200-gon, wound either way about its normal.
        let round = ring(1);
        let mut back = round.clone();
        back.reverse();
        for (pts, normal) in [(&round, V3::z()), (&back, -V3::z())] {
            let t = ear_clip_simple(pts, &normal).expect("simple");
            assert_eq!(t.len(), n - 2);
        }
        // The same corners visited in a star order cross themselves: refused.
        let star = ring(67);
        assert!(ear_clip_simple(&star, &V3::z()).is_none());
    }

    #[test]
    fn strictly_convex_rings_get_balanced_triangles_that_tile_them() {
        let ring = |n: usize, k: usize| -> Vec<[f64; 2]> {
            (0..n)
                .map(|i| {
                    let a = (k * i) as f64 * std::f64::consts::TAU / n as f64;
                    [a.cos(), a.sin()]
                })
                .collect()
        };
        for n in [65, 100, 4096] {
            let round = ring(n, 1);
            assert!(strictly_convex(&round, false));
            assert!(!strictly_convex(&round, true));
            let t = balanced(n);
            assert_eq!(t.len(), n - 2);
            // An independent check: the edges cancel and every triangle turns left.
            assert!(tiles_exactly(&round, &t, false));
            let back: Vec<[f64; 2]> = round.iter().rev().copied().collect();
            assert!(strictly_convex(&back, true));
            assert!(tiles_exactly(&back, &balanced(n), true));
            // Wound twice (every turn is still left): not convex.
            if n % 2 == 1 {
                assert!(!strictly_convex(&ring(n, 2), false));
            }
        }
        // A reflex corner, and three collinear corners, are refused.
        let mut dent = ring(100, 1);
        dent[10] = [0.5 * dent[10][0], 0.5 * dent[10][1]];
        assert!(!strictly_convex(&dent, false));
        let mut flat = ring(100, 1);
        flat[1] = [
            (flat[0][0] + flat[2][0]) / 2.0,
            (flat[0][1] + flat[2][1]) / 2.0,
        ];
        let exact_mid = orient2d(flat[0], flat[1], flat[2]) == 0.0;
        assert_eq!(
            strictly_convex(&flat, false),
            !exact_mid && orient2d(flat[0], flat[1], flat[2]) > 0.0
        );
        // Through ear_clip_simple, seen from either side.
        let pts: Vec<P3> = ring(500, 1)
            .iter()
            .map(|p| P3::new(p[0], 0.3, p[1]))
            .collect();
        let normal = crate::geom::newell(&pts).normalize();
        assert_covers(
            &pts,
            &ear_clip_simple(&pts, &normal).expect("convex"),
            &normal,
        );
        let rev: Vec<P3> = pts.iter().rev().copied().collect();
        assert_covers(
            &rev,
            &ear_clip_simple(&rev, &-normal).expect("convex"),
            &-normal,
        );
    }
}
