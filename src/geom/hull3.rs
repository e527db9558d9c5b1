//! Convex hulls of large point sets (quickhull with conflict lists and exact `orient3d`), to
//! compare tribox volumes with: the paper's H(S), the tightest convex bound.

use std::collections::HashMap;

use crate::geom::{orient3d, P3};

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
pub fn convex_hull(points: &[P3]) -> Vec<[u32; 3]> {
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
        let mut by_edge: HashMap<(u32, u32), (usize, usize)> = HashMap::new();
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
        let mut by_start: HashMap<u32, usize> = HashMap::new();
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
    fn flat_and_tiny_sets_have_no_volume() {
        let flat: Vec<P3> = (0..10)
            .map(|i| P3::new(i as f64, (i * i) as f64, 2.0))
            .collect();
        assert_eq!(hull_volume(&flat), 0.0);
        assert_eq!(hull_volume(&flat[..3]), 0.0);
    }
}
