//! Ear-clipping triangulation of a simple polygon in space (used to split non-planar faces).

use crate::geom::{P3, V3};

/// Triangulates the polygon `pts` (simple, not necessarily planar or convex), projected along
/// the dominant axis of `normal`. Returns index triples into `pts`, each counter-clockwise
/// seen from the side `normal` points to. Falls back to a fan if the polygon is not simple.
pub fn ear_clip(pts: &[P3], normal: &V3) -> Vec<[usize; 3]> {
    ear_clip_simple(pts, normal).unwrap_or_else(|| {
        let (_, _, flip) = projection_axes(normal);
        fan(pts.len(), flip)
    })
}

/// [`ear_clip`], or None where it would fall back to a fan: no ear was found, so the
/// polygon, projected along the dominant axis of `normal`, is not simple. Every decision is
/// an exact orient2d on input coordinates.
pub fn ear_clip_simple(pts: &[P3], normal: &V3) -> Option<Vec<[usize; 3]>> {
    let (ax, ay, flip) = projection_axes(normal);
    let p2: Vec<[f64; 2]> = pts.iter().map(|p| [p[ax], p[ay]]).collect();
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

/// Coordinate axes to project on (dropping the normal's dominant axis), and whether the
/// projection reverses orientation.
fn projection_axes(n: &V3) -> (usize, usize, bool) {
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

fn orient(a: [f64; 2], b: [f64; 2], c: [f64; 2]) -> f64 {
    robust::orient2d(
        robust::Coord { x: a[0], y: a[1] },
        robust::Coord { x: b[0], y: b[1] },
        robust::Coord { x: c[0], y: c[1] },
    )
}

fn find_ear(p: &[[f64; 2]], ring: &[usize]) -> Option<usize> {
    let n = ring.len();
    (0..n).find(|&i| {
        let (a, b, c) = (p[ring[(i + n - 1) % n]], p[ring[i]], p[ring[(i + 1) % n]]);
        if orient(a, b, c) <= 0.0 {
            return false;
        }
        ring.iter().all(|&k| {
            let q = p[k];
            q == a
                || q == b
                || q == c
                || !(orient(a, b, q) >= 0.0 && orient(b, c, q) >= 0.0 && orient(c, a, q) >= 0.0)
        })
    })
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
}
