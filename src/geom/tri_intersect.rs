//! Exact intersection tests of closed triangles and segments in space (robust orient3d and
//! orient2d only: no tolerance), shared by interference and the solidity test.

use super::{orient2d, orient3d, P3};

/// Exact closed intersection test of two non-degenerate triangles: they meet exactly when an
/// edge of one meets the other (non-coplanar), or in the plane's 2D test (coplanar).
pub(crate) fn triangles_intersect(t: &[P3; 3], u: &[P3; 3]) -> bool {
    // Closed projections strictly apart (along either triangle's dominant axis) mean the
    // triangles are apart: a cheap first test (orient2d), and one that needs no exact zero
    // of orient3d where a triangle stands on another's plane (a prism's side on its cap).
    let apart = |(x, y): (usize, usize)| {
        projections_apart(&t.map(|p| [p[x], p[y]]), &u.map(|p| [p[x], p[y]]))
    };
    let (at, au) = (plane_axes(t), plane_axes(u));
    !(apart(at) || (au != at && apart(au))) && meet(t, u)
}

/// [`triangles_intersect`] without its first test.
fn meet(t: &[P3; 3], u: &[P3; 3]) -> bool {
    let su = t.map(|p| orient3d(&u[0], &u[1], &u[2], &p));
    if su.iter().all(|&s| s > 0.0) || su.iter().all(|&s| s < 0.0) {
        return false;
    }
    let st = u.map(|p| orient3d(&t[0], &t[1], &t[2], &p));
    if st.iter().all(|&s| s > 0.0) || st.iter().all(|&s| s < 0.0) {
        return false;
    }
    if su.iter().all(|&s| s == 0.0) {
        let (x, y) = plane_axes(u);
        let a = t.map(|p| [p[x], p[y]]);
        let b = u.map(|p| [p[x], p[y]]);
        return triangles_2d(&a, &b);
    }
    // The sides of each triangle's corners against the other's plane are already known.
    (0..3).any(|i| {
        let j = (i + 1) % 3;
        segment_meets_triangle_sided(&t[i], &t[j], su[i], su[j], u)
    }) || (0..3).any(|i| {
        let j = (i + 1) % 3;
        segment_meets_triangle_sided(&u[i], &u[j], st[i], st[j], t)
    })
}

/// Exact: some edge of one projected triangle (with area) has the whole other strictly on
/// its outer side, so the closed projections do not meet.
fn projections_apart(a: &[[f64; 2]; 3], b: &[[f64; 2]; 3]) -> bool {
    let outside = |p: &[[f64; 2]; 3], q: &[[f64; 2]; 3]| {
        let turn = orient2d(p[0], p[1], p[2]);
        turn != 0.0
            && (0..3).any(|i| {
                let (e, f) = (p[i], p[(i + 1) % 3]);
                q.iter().all(|&r| orient2d(e, f, r) * turn < 0.0)
            })
    };
    outside(a, b) || outside(b, a)
}

/// The two coordinates kept when projecting a triangle's plane along its dominant axis.
pub(crate) fn plane_axes(t: &[P3; 3]) -> (usize, usize) {
    let n = (t[1] - t[0]).cross(&(t[2] - t[0])).abs();
    if n.x >= n.y && n.x >= n.z {
        (1, 2)
    } else if n.y >= n.z {
        (2, 0)
    } else {
        (0, 1)
    }
}

/// Exact: the closed segment pq meets the closed triangle t.
pub(crate) fn segment_meets_triangle(p: &P3, q: &P3, t: &[P3; 3]) -> bool {
    let (sp, sq) = (
        orient3d(&t[0], &t[1], &t[2], p),
        orient3d(&t[0], &t[1], &t[2], q),
    );
    segment_meets_triangle_sided(p, q, sp, sq, t)
}

/// [`segment_meets_triangle`] given the sides `sp`, `sq` of p and q (orient3d against t's
/// plane, as that function computes them).
fn segment_meets_triangle_sided(p: &P3, q: &P3, sp: f64, sq: f64, t: &[P3; 3]) -> bool {
    if (sp > 0.0 && sq > 0.0) || (sp < 0.0 && sq < 0.0) {
        return false;
    }
    if sp == 0.0 && sq == 0.0 {
        let (x, y) = plane_axes(t);
        let tri = t.map(|v| [v[x], v[y]]);
        let (a, b) = ([p[x], p[y]], [q[x], q[y]]);
        return point_in_triangle_2d(a, &tri)
            || (0..3).any(|i| segments_2d(a, b, tri[i], tri[(i + 1) % 3]));
    }
    let s = [
        orient3d(p, q, &t[0], &t[1]),
        orient3d(p, q, &t[1], &t[2]),
        orient3d(p, q, &t[2], &t[0]),
    ];
    s.iter().all(|&v| v >= 0.0) || s.iter().all(|&v| v <= 0.0)
}

/// Exact: `p` lies in the closed triangle `t` (either orientation).
pub(crate) fn point_in_triangle_2d(p: [f64; 2], t: &[[f64; 2]; 3]) -> bool {
    let s = [
        orient2d(t[0], t[1], p),
        orient2d(t[1], t[2], p),
        orient2d(t[2], t[0], p),
    ];
    s.iter().all(|&v| v >= 0.0) || s.iter().all(|&v| v <= 0.0)
}

/// Closed segments ab and cd meet.
pub(crate) fn segments_2d(a: [f64; 2], b: [f64; 2], c: [f64; 2], d: [f64; 2]) -> bool {
    let (d1, d2) = (orient2d(c, d, a), orient2d(c, d, b));
    let (d3, d4) = (orient2d(a, b, c), orient2d(a, b, d));
    if ((d1 > 0.0 && d2 < 0.0) || (d1 < 0.0 && d2 > 0.0))
        && ((d3 > 0.0 && d4 < 0.0) || (d3 < 0.0 && d4 > 0.0))
    {
        return true;
    }
    let on = |p: [f64; 2], q: [f64; 2], r: [f64; 2]| {
        r[0] >= p[0].min(q[0])
            && r[0] <= p[0].max(q[0])
            && r[1] >= p[1].min(q[1])
            && r[1] <= p[1].max(q[1])
    };
    (d1 == 0.0 && on(c, d, a))
        || (d2 == 0.0 && on(c, d, b))
        || (d3 == 0.0 && on(a, b, c))
        || (d4 == 0.0 && on(a, b, d))
}

fn triangles_2d(a: &[[f64; 2]; 3], b: &[[f64; 2]; 3]) -> bool {
    (0..3).any(|i| (0..3).any(|j| segments_2d(a[i], a[(i + 1) % 3], b[j], b[(j + 1) % 3])))
        || point_in_triangle_2d(a[0], b)
        || point_in_triangle_2d(b[0], a)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::rng::XorShift;

    #[test]
    fn the_projection_test_never_changes_the_answer() {
        // Small integer coordinates: many triangles touch, share planes, lie on each other.
        let mut rng = XorShift::new(5);
        let mut point = || {
            P3::new(
                rng.below(3) as f64,
                rng.below(3) as f64,
                rng.below(3) as f64,
            )
        };
        let (mut meets, mut apart) = (0, 0);
        for _ in 0..20000 {
            let t = [point(), point(), point()];
            let u = [point(), point(), point()];
            let flat = |t: &[P3; 3]| (t[1] - t[0]).cross(&(t[2] - t[0])).norm() == 0.0;
            if flat(&t) || flat(&u) {
                continue;
            }
            let m = meet(&t, &u);
            assert_eq!(triangles_intersect(&t, &u), m, "{t:?} {u:?}");
            meets += usize::from(m);
            apart += usize::from(!m);
        }
        assert!(meets > 1000 && apart > 1000, "{meets} {apart}");
    }
}
