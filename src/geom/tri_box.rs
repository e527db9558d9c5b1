//! Whether a triangle meets an axis-aligned box: the separating-axis test in f64, used to
//! prove a box clear of a mesh's faces (INBOX growth and the check of an explicit INBOX).

use super::{P3, V3};

/// Separating-axis test: does triangle `t` meet the closed box with centre `c` and
/// half-sizes `h`? (Akenine-Möller's 13 axes.)
pub(crate) fn tri_meets_box(t: &[P3; 3], c: &P3, h: &V3) -> bool {
    let v = [t[0] - c, t[1] - c, t[2] - c];
    let e = [v[1] - v[0], v[2] - v[1], v[0] - v[2]];
    let separated = |a: &V3| {
        let p = v.map(|x| a.dot(&x));
        let r = h.x * a.x.abs() + h.y * a.y.abs() + h.z * a.z.abs();
        p.iter().fold(f64::INFINITY, |m, &x| m.min(x)) > r
            || p.iter().fold(f64::NEG_INFINITY, |m, &x| m.max(x)) < -r
    };
    let axes = [V3::x(), V3::y(), V3::z()];
    if axes.iter().any(&separated) || separated(&e[0].cross(&e[1])) {
        return false;
    }
    !axes
        .iter()
        .any(|a| e.iter().any(|ed| separated(&a.cross(ed))))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn triangle_box_overlap() {
        let t = [
            P3::new(0., 0., 0.),
            P3::new(2., 0., 0.),
            P3::new(0., 2., 0.),
        ];
        let h = V3::new(0.1, 0.1, 0.1);
        assert!(tri_meets_box(&t, &P3::new(0.5, 0.5, 0.05), &h));
        assert!(!tri_meets_box(&t, &P3::new(0.5, 0.5, 0.5), &h));
        assert!(!tri_meets_box(&t, &P3::new(1.2, 1.2, 0.0), &h));
        assert!(tri_meets_box(&t, &P3::new(0.95, 0.95, 0.0), &h));
    }
}
