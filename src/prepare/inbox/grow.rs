//! INBOX of a non-convex closed mesh: a box grown from seed points while no face meets it.
//!
//! Proof of containment: a box that no face touches lies wholly inside or wholly outside the
//! solid (it is connected and meets no boundary); its centre's winding number decides which.
//! "No face touches" is tested on the box grown by a margin of [`MARGIN`] times the mesh's
//! size with a separating-axis test in f64: the rounding error of those dot products is
//! below 1e-14 of the size, far under the margin, so a face reported clear truly is.

use rayon::prelude::*;

use crate::geom::box_tree::BoxTree;
use crate::geom::tri_box::tri_meets_box;
use crate::geom::triangle::closest_on_triangle;
use crate::geom::{Box3, P3, V3};

use super::solid::Triangles;

/// Clearance kept between the box and every face, relative to the mesh's size.
pub(crate) const MARGIN: f64 = 1e-9;
/// Seed grid points per axis (cell centres), besides the CBOX centre and the vertex centroid.
const GRID: usize = 4;
/// Largest triangles from which a ray is cast inward to find a seed.
const RAY_SEEDS: usize = 16;
/// How many inside seeds are grown (the largest result is kept).
const GROWN_SEEDS: usize = 3;
/// Bisection steps per side.
const BISECT: usize = 22;
/// Rounds of growing all six sides.
const ROUNDS: usize = 3;
/// Triangles per chunk of the winding-number sum.
const INSIDE_CHUNK: usize = 4096;

/// Triangles with their bounding boxes, for clearance tests.
struct Field<'a> {
    tris: &'a Triangles,
    boxes: Vec<Box3>,
    /// A tree over `boxes`: each test looks at the triangles near the box only.
    tree: BoxTree,
    margin: f64,
    /// Where boxes must stay (then `tris` need only hold the triangles meeting it).
    region: Option<Box3>,
}

/// The largest box a search finds inside the closed mesh with triangles `tris`, among boxes
/// grown from points near `centroid` and on a grid over `cbox`. None when no seed is inside.
pub(crate) fn grown_inbox(tris: &Triangles, cbox: &Box3, centroid: &P3) -> Option<Box3> {
    let scale = cbox.size().iter().fold(0.0f64, |a, &b| a.max(b));
    let field = Field::new(tris, MARGIN * scale, None);
    let mut points = seed_points(cbox, centroid);
    points.extend(ray_seeds(tris, RAY_SEEDS));
    field.grow_seeds(points, tris, cbox)
}

/// An INBOX within `region` (a part of the closed mesh's CBOX, such as a component's CBOX):
/// the largest box grown inside `region` from seeds on a grid over it and at `centroid`,
/// touching no face. Only the faces meeting `region` can touch such a box, so only they are
/// tested; the seed's winding number is taken over every triangle. `scale` is the mesh's size
/// (the clearance margin is relative to it).
pub(crate) fn grown_inbox_in(
    tris: &Triangles,
    region: &Box3,
    centroid: &P3,
    scale: f64,
) -> Option<Box3> {
    let margin = MARGIN * scale;
    let m = V3::new(3.0 * margin, 3.0 * margin, 3.0 * margin);
    let reach = Box3::new(region.lo - m, region.hi + m);
    let near = Triangles {
        tris: tris
            .tris
            .iter()
            .filter(|t| {
                let b = Box3::from_points(t.iter());
                (0..3).all(|i| b.lo[i] <= reach.hi[i] && b.hi[i] >= reach.lo[i])
            })
            .copied()
            .collect(),
        flipped: tris.flipped,
    };
    let field = Field::new(&near, margin, Some(*region));
    let points = seed_points(region, centroid)
        .into_iter()
        .filter(|p| region.contains(p))
        .collect();
    field.grow_seeds(points, tris, region)
}

fn cube(p: &P3, r: f64) -> Box3 {
    let d = V3::new(r, r, r);
    Box3::new(p - d, p + d)
}

/// The CBOX centre, the vertex centroid and the centres of a GRID³ grid of cells.
fn seed_points(cbox: &Box3, centroid: &P3) -> Vec<P3> {
    let mut pts = vec![cbox.center(), *centroid];
    let s = cbox.size();
    let at = |i: usize, k: usize| cbox.lo[i] + s[i] * (k as f64 + 0.5) / GRID as f64;
    for x in 0..GRID {
        for y in 0..GRID {
            for z in 0..GRID {
                pts.push(P3::new(at(0, x), at(1, y), at(2, z)));
            }
        }
    }
    pts
}

/// Midpoints of inward rays cast from the centroids of the `count` largest triangles to the
/// next triangle they hit: inside points in the thick parts, even of thin, tilted solids.
fn ray_seeds(tris: &Triangles, count: usize) -> Vec<P3> {
    let area = |t: &[P3; 3]| (t[1] - t[0]).cross(&(t[2] - t[0])).norm();
    let mut order: Vec<usize> = (0..tris.tris.len()).collect();
    order.sort_by(|&a, &b| area(&tris.tris[b]).total_cmp(&area(&tris.tris[a])));
    order
        .iter()
        .take(count)
        .filter_map(|&k| {
            let t = &tris.tris[k];
            let origin = P3::from((t[0].coords + t[1].coords + t[2].coords) / 3.0);
            let dir = -(t[1] - t[0]).cross(&(t[2] - t[0])).try_normalize(0.0)?;
            let hit = tris
                .tris
                .iter()
                .enumerate()
                .filter(|&(j, _)| j != k)
                .filter_map(|(_, u)| ray_hit(&origin, &dir, u))
                .filter(|&d| d > 0.0)
                .fold(f64::INFINITY, f64::min);
            hit.is_finite().then(|| origin + dir * (0.5 * hit))
        })
        .collect()
}

/// Distance along a unit ray to a triangle (Möller–Trumbore), if it hits.
fn ray_hit(o: &P3, d: &V3, t: &[P3; 3]) -> Option<f64> {
    let (e1, e2) = (t[1] - t[0], t[2] - t[0]);
    let p = d.cross(&e2);
    let det = e1.dot(&p);
    if det == 0.0 {
        return None;
    }
    let s = o - t[0];
    let u = s.dot(&p) / det;
    let q = s.cross(&e1);
    let v = d.dot(&q) / det;
    (u >= 0.0 && v >= 0.0 && u + v <= 1.0).then(|| e2.dot(&q) / det)
}

/// True when the winding number of the triangles around `p` is a positive integer (p must
/// be clear of every face, so the sum is far from a half-integer).
///
/// The sum is taken in fixed chunks in parallel, then over the chunks in order: the same
/// bits whatever the thread count.
fn inside(tris: &Triangles, p: &P3) -> bool {
    let chunk = |c: &[[P3; 3]]| {
        c.iter()
            .map(|t| solid_angle(&(t[0] - p), &(t[1] - p), &(t[2] - p)))
            .sum::<f64>()
    };
    let parts: Vec<f64> = tris.tris.par_chunks(INSIDE_CHUNK).map(chunk).collect();
    let w: f64 = parts.iter().sum::<f64>() / (4.0 * std::f64::consts::PI);
    w.round() >= 1.0 && (w - w.round()).abs() < 0.25
}

/// Signed solid angle of a triangle seen from the origin (Van Oosterom–Strackee).
fn solid_angle(a: &V3, b: &V3, c: &V3) -> f64 {
    let (la, lb, lc) = (a.norm(), b.norm(), c.norm());
    let num = a.dot(&b.cross(c));
    let den = la * lb * lc + a.dot(b) * lc + a.dot(c) * lb + b.dot(c) * la;
    2.0 * num.atan2(den)
}

impl<'a> Field<'a> {
    fn new(tris: &'a Triangles, margin: f64, region: Option<Box3>) -> Field<'a> {
        let boxes: Vec<Box3> = tris
            .tris
            .iter()
            .map(|t| Box3::from_points(t.iter()))
            .collect();
        Field {
            tris,
            tree: BoxTree::new(&boxes),
            boxes,
            margin,
            region,
        }
    }

    /// The largest box grown within `cbox` from the clearest seeds inside the solid of `all`
    /// (the winding number is taken over every triangle, not only the field's).
    fn grow_seeds(&self, points: Vec<P3>, all: &Triangles, cbox: &Box3) -> Option<Box3> {
        let mut seeds: Vec<(f64, P3)> = points
            .into_iter()
            .map(|p| (self.clearance(&p), p))
            .filter(|(r, _)| *r > 0.0)
            .collect();
        seeds.sort_by(|a, b| b.0.total_cmp(&a.0));
        seeds
            .iter()
            .filter_map(|(r, p)| {
                let b = cube(p, 0.99 * r);
                (self.free(&b) && inside(all, p)).then_some(b)
            })
            .take(GROWN_SEEDS)
            .map(|b| self.grow(b, cbox))
            .max_by(|a, b| a.volume().total_cmp(&b.volume()))
    }

    /// A lower bound of the L∞ distance from `p` to every face, less the margin: per face
    /// the larger of the L∞ distance to its bounding box and its Euclidean distance / √3.
    /// The least over faces is taken in the tree: a node no nearer (L∞) than the least so
    /// far cannot lower it, so the answer is the plain minimum's, bit for bit.
    fn clearance(&self, p: &P3) -> f64 {
        let away = |b: &Box3| (0..3).fold(0.0f64, |d, i| d.max(b.lo[i] - p[i]).max(p[i] - b.hi[i]));
        let r = self.tree.least(f64::INFINITY, away, |k, r| {
            let d = away(&self.boxes[k as usize]);
            if d >= r {
                return d;
            }
            let t = &self.tris.tris[k as usize];
            d.max((closest_on_triangle(p, &t[0], &t[1], &t[2]) - p).norm() / 3f64.sqrt())
        });
        r - 2.0 * self.margin
    }

    /// True when no triangle meets `b` grown by the margin.
    fn free(&self, b: &Box3) -> bool {
        if self.region.is_some_and(|r| !r.contains_box(b)) {
            return false;
        }
        let m = V3::new(self.margin, self.margin, self.margin);
        let e = Box3::new(b.lo - m, b.hi + m);
        let c = e.center();
        let h = (e.hi - e.lo) * 0.5;
        !self.tree.any_meeting(&self.boxes, &e, |k| {
            tri_meets_box(&self.tris.tris[k as usize], &c, &h)
        })
    }

    /// Grows `b` (free) uniformly, then side by side, by bisection, staying inside `cbox`.
    fn grow(&self, mut b: Box3, cbox: &Box3) -> Box3 {
        let reach = cbox.size().iter().fold(0.0f64, |a, &x| a.max(x));
        let uniform = |t: f64| {
            let d = V3::new(t, t, t);
            Box3::new(b.lo - d, b.hi + d)
        };
        let t = self.largest(reach, &uniform);
        b = uniform(t);
        for _ in 0..ROUNDS {
            for side in 0..6 {
                let (i, hi) = (side % 3, side >= 3);
                let room = if hi {
                    cbox.hi[i] - b.hi[i]
                } else {
                    b.lo[i] - cbox.lo[i]
                };
                let moved = |t: f64| {
                    let mut c = b;
                    if hi {
                        c.hi[i] += t;
                    } else {
                        c.lo[i] -= t;
                    }
                    c
                };
                let t = self.largest(room.max(0.0), &moved);
                b = moved(t);
            }
        }
        b
    }

    /// The largest t in [0, max] (by bisection) with `make(t)` free; `make(0)` must be free.
    fn largest(&self, max: f64, make: &dyn Fn(f64) -> Box3) -> f64 {
        if max <= 0.0 {
            return 0.0;
        }
        if self.free(&make(max)) {
            return max;
        }
        let (mut ok, mut bad) = (0.0, max);
        for _ in 0..BISECT {
            let mid = 0.5 * (ok + bad);
            if self.free(&make(mid)) {
                ok = mid;
            } else {
                bad = mid;
            }
        }
        ok
    }
}
