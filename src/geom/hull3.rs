//! The one 3D convex hull (quickhull with conflict lists and exact `orient3d`): its outward
//! triangles, its volume (tribox's H(S), the tightest convex bound) and its facets as
//! polygons (the named solids of `primitives`).

use crate::geom::key_hash::KeyMap;
use std::collections::HashSet;

use crate::geom::{orient3d, P3, V3};

/// A hull triangle: corners counter-clockwise from outside, the neighbour across each edge
/// (v\[i\], v\[i+1\]), and the points still outside it.
#[derive(Debug, Clone)]
struct Tri {
    v: [u32; 3],
    nb: [usize; 3],
    outside: Vec<u32>,
    alive: bool,
}

/// The convex hull of `points` as outward triangles (indices into `points`). Empty when the
/// points do not span a volume (fewer than four, or all coplanar).
pub(crate) fn convex_hull(points: &[P3]) -> Vec<[u32; 3]> {
    let Some(start) = initial_tetrahedron(points) else {
        return Vec::new();
    };
    let mut h = Hull {
        pts: points,
        tris: Vec::new(),
    };
    h.seed(start);
    let mut queue: Vec<usize> = (0..4).collect();
    while let Some(f) = queue.pop() {
        if !h.tris[f].alive || h.tris[f].outside.is_empty() {
            continue;
        }
        let p = h.furthest(f);
        queue.extend(h.add_point(f, p));
    }
    h.tris.iter().filter(|t| t.alive).map(|t| t.v).collect()
}

/// Volume of the convex hull (0 when flat).
pub fn hull_volume(points: &[P3]) -> f64 {
    let tris = convex_hull(points);
    let Some(r) = tris.first().map(|t| points[t[0] as usize]) else {
        return 0.0;
    };
    tris.iter()
        .map(|t| {
            let [a, b, c] = t.map(|i| points[i as usize] - r);
            a.dot(&b.cross(&c))
        })
        .sum::<f64>()
        / 6.0
}

/// Points within this fraction of the set's radius of a plane count as lying on it (for
/// [`hull_facets`]).
const RELATIVE_TOLERANCE: f64 = 1e-9;

/// The facets of the convex hull of `points`, each a single polygon holding every point on its
/// plane (within a tolerance relative to the set's radius), counter-clockwise seen from
/// outside; ordered by their three least point indices.
///
/// Meant for the vertex sets of convex uniform solids: every point must be a hull vertex (no
/// point inside a facet or the solid). Each facet is taken from the plane through its three
/// least points, so that the coplanar triangles of the exact hull, whose planes differ by
/// rounding, give one polygon.
pub(crate) fn hull_facets(points: &[P3]) -> Vec<Vec<u32>> {
    let radius = points.iter().map(|p| p.coords.norm()).fold(0.0, f64::max);
    let tolerance = RELATIVE_TOLERANCE * radius;
    let mut triples: Vec<[usize; 3]> = convex_hull(points)
        .iter()
        .filter_map(|t| {
            let (on, _) = supporting_plane(points, t.map(|i| i as usize), tolerance)?;
            (on.len() >= 3).then(|| [on[0], on[1], on[2]].map(|i| i as usize))
        })
        .collect();
    triples.sort_unstable();
    triples.dedup();
    let mut seen = HashSet::new();
    let mut facets = Vec::new();
    for triple in triples {
        let Some((on, outward)) = supporting_plane(points, triple, tolerance) else {
            continue;
        };
        if seen.insert(on.clone()) {
            facets.push(counter_clockwise(points, on, &outward));
        }
    }
    facets
}

/// The points on the plane through the three points (in index order) and its outward normal,
/// if that plane supports the set.
fn supporting_plane(
    points: &[P3],
    [a, b, c]: [usize; 3],
    tolerance: f64,
) -> Option<(Vec<u32>, V3)> {
    let normal = (points[b] - points[a])
        .cross(&(points[c] - points[a]))
        .try_normalize(0.0)?;
    let offset = normal.dot(&points[a].coords);
    let (mut above, mut below) = (false, false);
    let mut on_plane = Vec::new();
    for (i, p) in points.iter().enumerate() {
        let height = normal.dot(&p.coords) - offset;
        if height > tolerance {
            above = true;
        } else if height < -tolerance {
            below = true;
        } else {
            on_plane.push(i as u32);
        }
        if above && below {
            return None;
        }
    }
    Some((on_plane, if above { -normal } else { normal }))
}

/// The coplanar `corners` sorted counter-clockwise around their centroid, seen from the side
/// `outward` points to.
fn counter_clockwise(points: &[P3], mut corners: Vec<u32>, outward: &V3) -> Vec<u32> {
    let at = |i: u32| points[i as usize];
    let sum: V3 = corners.iter().map(|&i| at(i).coords).sum();
    let centroid = P3::from(sum / corners.len() as f64);
    let u = at(corners[0]) - centroid;
    let w = outward.cross(&u);
    let angle = |i: u32| {
        let d = at(i) - centroid;
        w.dot(&d).atan2(u.dot(&d))
    };
    corners.sort_by(|&i, &j| angle(i).total_cmp(&angle(j)));
    corners
}

/// Four points spanning a volume, ordered so that (0, 1, 2) is counter-clockwise from outside.
fn initial_tetrahedron(p: &[P3]) -> Option<[u32; 4]> {
    if p.len() < 4 {
        return None;
    }
    let far = |from: &dyn Fn(&P3) -> f64| -> usize {
        (0..p.len())
            .max_by(|&i, &j| from(&p[i]).total_cmp(&from(&p[j])).then(j.cmp(&i)))
            .unwrap_or(0)
    };
    let a = far(&|q: &P3| -q.x);
    let b = far(&|q: &P3| (q - p[a]).norm_squared());
    let ab = p[b] - p[a];
    let c = far(&|q: &P3| ab.cross(&(q - p[a])).norm_squared());
    let n = ab.cross(&(p[c] - p[a]));
    let d = far(&|q: &P3| n.dot(&(q - p[a])).abs());
    let o = orient3d(&p[a], &p[b], &p[c], &p[d]);
    if o == 0.0 {
        return None;
    }
    let [a, b, c, d] = [a, b, c, d].map(|i| i as u32);
    Some(if o > 0.0 { [a, b, c, d] } else { [a, c, b, d] })
}

struct Hull<'a> {
    pts: &'a [P3],
    tris: Vec<Tri>,
}

impl Hull<'_> {
    fn at(&self, i: u32) -> &P3 {
        &self.pts[i as usize]
    }

    /// True when point `p` is strictly outside triangle `t`'s plane.
    fn sees(&self, t: usize, p: u32) -> bool {
        let v = self.tris[t].v;
        orient3d(self.at(v[0]), self.at(v[1]), self.at(v[2]), self.at(p)) < 0.0
    }

    /// The tetrahedron's four faces, neighbours linked, every other point assigned.
    fn seed(&mut self, [a, b, c, d]: [u32; 4]) {
        // (a, b, c) is counter-clockwise from outside with d inside; the other faces follow.
        let faces = [[a, b, c], [a, d, b], [b, d, c], [c, d, a]];
        for v in faces {
            self.tris.push(Tri {
                v,
                nb: [usize::MAX; 3],
                outside: Vec::new(),
                alive: true,
            });
        }
        self.link_all(&[0, 1, 2, 3]);
        let skip = [a, b, c, d];
        let candidates: Vec<u32> = (0..self.pts.len() as u32)
            .filter(|i| !skip.contains(i))
            .collect();
        self.assign(&candidates, &[0, 1, 2, 3]);
    }

    /// Links the neighbours among `ids` by their shared edges.
    fn link_all(&mut self, ids: &[usize]) {
        let mut by_edge: KeyMap<(u32, u32), (usize, usize)> = KeyMap::default();
        for &t in ids {
            for i in 0..3 {
                let v = self.tris[t].v;
                by_edge.insert((v[i], v[(i + 1) % 3]), (t, i));
            }
        }
        for &t in ids {
            for i in 0..3 {
                let v = self.tris[t].v;
                if let Some(&(u, _)) = by_edge.get(&(v[(i + 1) % 3], v[i])) {
                    self.tris[t].nb[i] = u;
                }
            }
        }
    }

    /// Gives each point to the first of `faces` it is strictly outside of (or drops it).
    fn assign(&mut self, points: &[u32], faces: &[usize]) {
        for &p in points {
            if let Some(&t) = faces.iter().find(|&&t| self.sees(t, p)) {
                self.tris[t].outside.push(p);
            }
        }
    }

    /// The outside point of `t` furthest from its plane.
    fn furthest(&self, t: usize) -> u32 {
        let v = self.tris[t].v;
        let (a, b, c) = (self.at(v[0]), self.at(v[1]), self.at(v[2]));
        let n = (b - a).cross(&(c - a));
        *self.tris[t]
            .outside
            .iter()
            .max_by(|&&i, &&j| {
                let (di, dj) = (n.dot(&(self.at(i) - a)), n.dot(&(self.at(j) - a)));
                di.total_cmp(&dj).then(j.cmp(&i))
            })
            .expect("non-empty outside set")
    }

    /// Adds point `p`, outside triangle `f`: removes the faces it sees, cones the horizon to
    /// it, and returns the new faces.
    fn add_point(&mut self, f: usize, p: u32) -> Vec<usize> {
        // The visible region, by depth-first search from f.
        let mut visible = vec![f];
        let mut stack = vec![f];
        self.tris[f].alive = false;
        let mut horizon: Vec<(u32, u32, usize)> = Vec::new();
        while let Some(t) = stack.pop() {
            for i in 0..3 {
                let n = self.tris[t].nb[i];
                if !self.tris[n].alive {
                    continue; // visible already (faces of earlier steps are never neighbours)
                }
                if self.sees(n, p) {
                    self.tris[n].alive = false;
                    visible.push(n);
                    stack.push(n);
                } else {
                    let v = self.tris[t].v;
                    horizon.push((v[i], v[(i + 1) % 3], n));
                }
            }
        }
        // New faces over the horizon edges, linked to the outside neighbours and each other.
        let mut new = Vec::with_capacity(horizon.len());
        let mut by_start: KeyMap<u32, usize> = KeyMap::default();
        for &(a, b, n) in &horizon {
            let id = self.tris.len();
            self.tris.push(Tri {
                v: [a, b, p],
                nb: [n, usize::MAX, usize::MAX],
                outside: Vec::new(),
                alive: true,
            });
            let back = (0..3)
                .find(|&i| {
                    let w = self.tris[n].v;
                    w[i] == b && w[(i + 1) % 3] == a
                })
                .expect("horizon edge shared");
            self.tris[n].nb[back] = id;
            by_start.insert(a, id);
            new.push(id);
        }
        for &id in &new {
            let [_, b, _] = self.tris[id].v;
            let next = by_start[&b];
            self.tris[id].nb[1] = next;
            self.tris[next].nb[2] = id;
        }
        let orphans: Vec<u32> = visible
            .iter()
            .flat_map(|&t| std::mem::take(&mut self.tris[t].outside))
            .filter(|&q| q != p)
            .collect();
        self.assign(&orphans, &new);
        new
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::Box3;

    #[test]
    fn cube_with_inner_points_has_unit_volume() {
        let mut pts = Box3::new(P3::new(0., 0., 0.), P3::new(1., 1., 1.))
            .corners()
            .to_vec();
        for i in 0..50 {
            let t = i as f64 / 50.0;
            pts.push(P3::new(t, 0.5, 1.0 - t)); // inside or on faces
            pts.push(P3::new(t, 0.0, 0.3)); // on a face
        }
        let tris = convex_hull(&pts);
        assert!((hull_volume(&pts) - 1.0).abs() < 1e-12);
        // Every point is inside or on every hull plane.
        for t in &tris {
            for q in &pts {
                let [a, b, c] = t.map(|i| &pts[i as usize]);
                assert!(orient3d(a, b, c, q) >= 0.0);
            }
        }
    }

    #[test]
    fn sphere_points_volume_approaches_the_ball() {
        let mut pts = Vec::new();
        let n = 2000;
        for i in 0..n {
            // Fibonacci sphere.
            let z = 1.0 - 2.0 * (i as f64 + 0.5) / n as f64;
            let r = (1.0 - z * z).sqrt();
            let phi = i as f64 * 2.399_963_229_728_653;
            pts.push(P3::new(r * phi.cos(), r * phi.sin(), z));
        }
        let v = hull_volume(&pts);
        let ball = 4.0 / 3.0 * std::f64::consts::PI;
        assert!(v < ball && v > 0.99 * ball, "{v}");
        assert_eq!(convex_hull(&pts).len(), 2 * n - 4);
    }

    #[test]
    fn cube_facets_are_outward_squares() {
        let corners: Vec<P3> = (0..8)
            .map(|i| P3::new((i & 1) as f64, (i >> 1 & 1) as f64, (i >> 2 & 1) as f64))
            .collect();
        let facets = hull_facets(&corners);
        assert_eq!(facets.len(), 6);
        let centre = P3::new(0.5, 0.5, 0.5);
        for facet in &facets {
            assert_eq!(facet.len(), 4);
            let p: Vec<P3> = facet.iter().map(|&i| corners[i as usize]).collect();
            let normal = (p[1] - p[0]).cross(&(p[2] - p[0]));
            assert!(normal.dot(&(p[0] - centre)) > 0.0, "{facet:?} faces inward");
        }
    }

    #[test]
    fn flat_and_tiny_sets_have_no_volume() {
        let flat: Vec<P3> = (0..10)
            .map(|i| P3::new(i as f64, (i * i) as f64, 2.0))
            .collect();
        assert_eq!(hull_volume(&flat), 0.0);
        assert_eq!(hull_volume(&flat[..3]), 0.0);
    }
}
