//! The occlusion rule: face G hides of face F the part of G's projection where G is in front
//! of F's plane. Sides are decided exactly (robust orient3d) on world coordinates, so
//! coplanar faces, shared edges and shared vertices are recognised without tolerances.

use crate::geom::construct::plane_crossing;
use crate::geom::hull2::has_turn;
use crate::geom::poly2::Pt2;
use crate::geom::{orient2d, orient3d_refs, Corners, Rect, P3};
use crate::scene::FaceId;
use crate::view::{Facing, PieceId, ScreenFaces};

/// The face being solved, prepared once for all its occluders.
#[derive(Debug, Clone)]
pub(crate) struct Target {
    /// The piece (piece order follows global face order: it decides coplanar ties, the
    /// earlier face is in front).
    pub piece: PieceId,
    /// The face the piece belongs to: a face never hides itself.
    pub face: FaceId,
    /// World reference triple of F's plane.
    pub refs: [P3; 3],
    /// Sign making orient3d positive on the viewer's side: -(turn of refs on screen) * sign(det M).
    pub front_sign: f64,
    /// F's projected ring, counter-clockwise.
    pub ring: Vec<Pt2>,
    /// F's screen rectangle.
    pub rect: Rect,
    /// F's least depth.
    pub zmin: f64,
    /// F's greatest depth.
    pub zmax: f64,
    /// True when `ring` is convex.
    pub convex: bool,
}

impl Target {
    /// Prepares piece `p` (which must not be edge-on or clipped).
    pub(crate) fn new(sf: &ScreenFaces, p: PieceId) -> Target {
        let pc = sf.piece(p);
        Target {
            piece: p,
            face: pc.face,
            refs: sf.plane_refs(p),
            front_sign: sf.front_sign(p),
            ring: sf.ring_ccw(p),
            rect: pc.rect,
            zmin: pc.zmin,
            zmax: pc.zmax,
            convex: pc.convex,
        }
    }

    /// Exact side of world point `p`: > 0 in front of F's plane (toward the viewer), < 0 behind, 0 on it.
    #[inline]
    pub(crate) fn side(&self, p: &P3) -> f64 {
        orient3d_refs(&self.refs, p) * self.front_sign
    }
}

/// What G does to F.
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum Occlusion {
    /// G hides nothing of F (behind it, coplanar and later, or no area in front).
    Nothing,
    /// G hides F within this projected region (counter-clockwise; may extend beyond F).
    Region(Vec<Pt2>),
}

/// The region of the screen where piece `g` is in front of target F's plane, from the
/// piece's screen and world points `pts` and `world`: all of them (`sf.pts(g)`,
/// `sf.world_pts(g)`), or a cut of them that is the same inside F's rectangle
/// ([`crate::view::ring_index`]).
pub(crate) fn occluder_region(
    sf: &ScreenFaces,
    g: PieceId,
    pts: Corners<[f64; 3]>,
    world: Corners,
    t: &Target,
    sides: &mut Vec<f64>,
) -> Occlusion {
    sides.clear();
    sides.extend(world.iter().map(|p| t.side(p)));
    let any_front = sides.iter().any(|&s| s > 0.0);
    let any_behind = sides.iter().any(|&s| s < 0.0);
    let mut ring: Vec<Pt2> = if !any_front {
        let coplanar = !any_behind;
        if coplanar && g < t.piece {
            pts.iter().map(|p| [p[0], p[1]]).collect()
        } else {
            return Occlusion::Nothing;
        }
    } else if !any_behind {
        pts.iter().map(|p| [p[0], p[1]]).collect()
    } else {
        front_part(sf, pts, world, sides, &t.refs)
    };
    // A region with no proper turn (all points equal or collinear) has no area: it hides nothing.
    if ring.len() < 3 || !has_turn(&ring) {
        return Occlusion::Nothing;
    }
    if sf.piece(g).facing == Facing::Back {
        ring.reverse();
    }
    Occlusion::Region(ring)
}

/// The part of a piece's projection (screen points `pts`, world points `world`) on the
/// non-negative side of the plane through `refs`, cut where the side changes sign. Each cut
/// is the exact crossing of the world edge with the plane, seen through the camera matrix,
/// rounded once or within the filter's bound ([`crate::geom::construct::plane_crossing`]):
/// accurate whatever the angle between the edge and the plane.
fn front_part(
    sf: &ScreenFaces,
    pts: Corners<[f64; 3]>,
    world: Corners,
    sides: &[f64],
    refs: &[P3; 3],
) -> Vec<Pt2> {
    let n = pts.len();
    let mut out = Vec::with_capacity(n + 2);
    for i in 0..n {
        let j = (i + 1) % n;
        let (sa, sb) = (sides[i], sides[j]);
        if sa >= 0.0 {
            out.push([pts[i][0], pts[i][1]]);
        }
        if (sa > 0.0 && sb < 0.0) || (sa < 0.0 && sb > 0.0) {
            let cut = match sf.camera {
                Some(cam) => plane_crossing(refs, &world[i], &world[j], &cam.matrix),
                None => {
                    let t = sa / (sa - sb);
                    let (a, b) = (pts[i], pts[j]);
                    [a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])]
                }
            };
            out.push(cut);
        }
    }
    out
}

/// True when two counter-clockwise convex rings have disjoint interiors: some edge of one
/// has the whole other ring on its outer closed side (exact).
pub(crate) fn separated_convex(a: &[Pt2], b: &[Pt2]) -> bool {
    edge_separates(a, b) || edge_separates(b, a)
}

/// Rings up to this product of sizes are tested edge by edge against every point.
const SMALL: usize = 256;

/// Most candidate edges fully checked in vain before [`edge_separates`] falls back to the
/// plain test (only rounding in the extreme-point walk makes a check fail).
const MAX_VAIN: usize = 8;

/// Whether some edge of `a` has all of `b` on its outer closed side (exact). Small rings are
/// tested edge by edge against every point. For large ones a walk around `b` (rotating
/// calipers: the point of `b` farthest inside each edge of `a` moves forward as the edges
/// turn) finds, in floating point, one candidate point per edge: when the exact predicate
/// puts it strictly inside, the edge does not separate; otherwise the edge is checked
/// exactly against every point. So the answer is exact whatever the walk's rounding, and
/// the cost is O(|a| + |b|) per pair instead of O(|a| |b|) (a 65536-gon against itself).
fn edge_separates(a: &[Pt2], b: &[Pt2]) -> bool {
    let n = a.len();
    let separates = |p: Pt2, q: Pt2| p != q && b.iter().all(|&r| orient2d(p, q, r) <= 0.0);
    if n.saturating_mul(b.len()) <= SMALL {
        return (0..n).any(|i| separates(a[i], a[(i + 1) % n]));
    }
    let m = b.len();
    // How far inside edge p -> q the point r is (floating point, for the walk only).
    let inside = |p: Pt2, q: Pt2, r: Pt2| (q[0] - p[0]) * r[1] - (q[1] - p[1]) * r[0];
    let mut j: Option<usize> = None;
    let (mut steps, mut vain) = (0usize, 0usize);
    for i in 0..n {
        let (p, q) = (a[i], a[(i + 1) % n]);
        if p == q {
            continue;
        }
        let mut k = match j {
            Some(k) => k,
            None => (0..m)
                .max_by(|&x, &y| inside(p, q, b[x]).total_cmp(&inside(p, q, b[y])))
                .unwrap_or(0),
        };
        while steps < 2 * m && inside(p, q, b[(k + 1) % m]) >= inside(p, q, b[k]) {
            k = (k + 1) % m;
            steps += 1;
        }
        j = Some(k);
        if orient2d(p, q, b[k]) > 0.0 {
            continue;
        }
        if separates(p, q) {
            return true;
        }
        vain += 1;
        if vain > MAX_VAIN {
            return (0..n).any(|i| separates(a[i], a[(i + 1) % n]));
        }
    }
    false
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The plain test: every edge of `a` against every point of `b`.
    fn plain(a: &[Pt2], b: &[Pt2]) -> bool {
        let n = a.len();
        (0..n).any(|i| {
            let (p, q) = (a[i], a[(i + 1) % n]);
            p != q && b.iter().all(|&r| orient2d(p, q, r) <= 0.0)
        })
    }

    /// A counter-clockwise regular `n`-gon of radius `r` about `c`, turned by `t`.
    fn ngon(n: usize, r: f64, c: Pt2, t: f64) -> Vec<Pt2> {
        (0..n)
            .map(|k| {
                let a = t + std::f64::consts::TAU * k as f64 / n as f64;
                [c[0] + r * a.cos(), c[1] + r * a.sin()]
            })
            .collect()
    }

    #[test]
    fn the_walk_agrees_with_the_plain_test() {
        // Big rings apart, touching at a vertex, sharing an edge, overlapping, nested, and
        // a quad along one edge of a big ring: the walk must give the plain answer exactly.
        let big = ngon(500, 1.0, [0.0, 0.0], 0.1);
        let mut cases = vec![
            (big.clone(), ngon(300, 1.0, [2.5, 0.3], 0.2)),
            (big.clone(), ngon(300, 1.0, [1.9, 0.0], 0.0)),
            (big.clone(), ngon(300, 0.5, [0.2, 0.1], 0.3)),
            (big.clone(), ngon(400, 3.0, [0.0, 0.0], 0.0)),
        ];
        let (p, q) = (big[7], big[8]);
        let out = [q[0] - p[0], q[1] - p[1]];
        let normal = [out[1], -out[0]];
        let quad = vec![
            q,
            p,
            [p[0] + normal[0], p[1] + normal[1]],
            [q[0] + normal[0], q[1] + normal[1]],
        ];
        cases.push((big.clone(), quad.clone()));
        cases.push((quad, big.clone()));
        for (a, b) in &cases {
            assert_eq!(edge_separates(a, b), plain(a, b));
            assert_eq!(separated_convex(a, b), plain(a, b) || plain(b, a));
        }
        assert!(separated_convex(&cases[0].0, &cases[0].1));
        assert!(!separated_convex(&cases[2].0, &cases[2].1));
        assert!(
            separated_convex(&cases[4].0, &cases[4].1),
            "a quad on an edge"
        );
    }

    #[test]
    fn separation_of_triangles_sharing_an_edge() {
        let f = [[0., 0.], [1., 0.], [0., 1.]];
        let g = [[1., 0.], [1., 1.], [0., 1.]];
        assert!(separated_convex(&f, &g));
        let h = [[0.2, 0.2], [2., 0.2], [0.2, 2.]];
        assert!(!separated_convex(&f, &h));
    }
}
