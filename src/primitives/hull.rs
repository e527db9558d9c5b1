//! A small convex hull for points in convex position, giving each facet as one polygon.

use std::collections::HashSet;

use crate::geom::{P3, V3};

/// Points within this fraction of the set's radius of a plane count as lying on it.
const RELATIVE_TOLERANCE: f64 = 1e-9;

/// The facets of the convex hull of `points`, each a single polygon holding every point on its
/// plane, counter-clockwise seen from outside.
///
/// Meant for the vertex sets of convex uniform solids: every point must be a hull vertex (no
/// point inside a facet or the solid). Brute force over point triples, fine for a few hundred.
pub(super) fn hull_facets(points: &[P3]) -> Vec<Vec<u32>> {
    let radius = points.iter().map(|p| p.coords.norm()).fold(0.0, f64::max);
    let tolerance = RELATIVE_TOLERANCE * radius;
    let mut seen = HashSet::new();
    let mut facets = Vec::new();
    let n = points.len();
    for a in 0..n {
        for b in a + 1..n {
            for c in b + 1..n {
                let Some(facet) = supported_facet(points, [a, b, c], tolerance) else {
                    continue;
                };
                let mut key = facet.clone();
                key.sort_unstable();
                if seen.insert(key) {
                    facets.push(facet);
                }
            }
        }
    }
    facets
}

/// The facet on the plane through the three points, if that plane supports the set.
fn supported_facet(points: &[P3], [a, b, c]: [usize; 3], tolerance: f64) -> Option<Vec<u32>> {
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
    let outward = if above { -normal } else { normal };
    Some(counter_clockwise(points, on_plane, &outward))
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

#[cfg(test)]
mod tests {
    use super::*;

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
}
