//! The up axis of a scene without a camera (`--up auto`): the axis direction it stands on.
//!
//! The rule: a mesh stands on its flattest, widest base. For each of the six directions ±X,
//! ±Y, ±Z taken as up, the *base* is the convex hull of the vertices within 1% of the scene's
//! extent from its lowest point, and its *fill* the base's area over the area of the convex
//! hull of all vertices seen along that axis (the scene's shadow). An axis has a base when
//! one of its two directions fills at least a quarter of the shadow. The up is
//!
//! 1. +Y (the OBJ/glTF convention) when no axis has a base;
//! 2. else the axis with the largest fill; axes within 10% of it tie, and a tie goes to the
//!    axis whose extent stands out most from the other two (a slab's thin axis, a tall prism's
//!    long one: |ln(e / √(e₁e₂))| largest), then to Y, Z, X in that order;
//! 3. on that axis, the direction whose base is at the bottom: + unless the − direction's
//!    base fills clearly more (the + one under 90% of it).
//!
//! Busts and statues stand on a cut base, scanned animals on their feet, a teapot on its
//! bottom; a round or irregular mesh (a sphere, a head) has no base and keeps +Y.

use crate::geom::hull2::convex_hull;
use crate::geom::poly2::{ring_area, Pt2};
use crate::geom::{P3, V3};
use crate::scene::Scene;

/// Depth of the base slab, as a fraction of the scene's extent along the axis.
const SLAB: f64 = 0.01;

/// Least fill of a base (its hull over the shadow's).
const MIN_FILL: f64 = 0.25;

/// Fills within this ratio of the best tie.
const TIE: f64 = 0.9;

/// Oddness values (natural log of extent ratios) within this of the largest tie.
const ODD_TIE: f64 = 0.05;

/// The auto rule's verdict and what it saw.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct AutoUp {
    /// The unit axis direction chosen.
    pub up: V3,
    /// Fill of the base for +X, −X, +Y, −Y, +Z, −Z as up.
    pub fill: [f64; 6],
    /// True when some axis has a base; false when +Y is the fallback.
    pub based: bool,
}

/// The rule of the module for these world points.
pub(crate) fn auto_up(points: &[P3]) -> AutoUp {
    let mut fill = [0.0; 6];
    let fallback = AutoUp {
        up: V3::y(),
        fill,
        based: false,
    };
    if points.is_empty() {
        return fallback;
    }
    let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
    for p in points {
        for k in 0..3 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    let ext: [f64; 3] = std::array::from_fn(|k| hi[k] - lo[k]);
    if ext.iter().any(|e| !e.is_finite()) {
        return fallback;
    }
    for k in 0..3 {
        let (a, b) = ((k + 1) % 3, (k + 2) % 3);
        let flat = |p: &P3| -> Pt2 { [p[a], p[b]] };
        let shadow = hull_area(points.iter().map(flat).collect());
        if shadow.is_nan() || shadow <= 0.0 {
            continue;
        }
        let depth = SLAB * ext[k];
        let bottom = hull_area(
            points
                .iter()
                .filter(|p| p[k] <= lo[k] + depth)
                .map(flat)
                .collect(),
        );
        let top = hull_area(
            points
                .iter()
                .filter(|p| p[k] >= hi[k] - depth)
                .map(flat)
                .collect(),
        );
        fill[2 * k] = bottom / shadow;
        fill[2 * k + 1] = top / shadow;
    }
    let score = |k: usize| fill[2 * k].max(fill[2 * k + 1]);
    let best = (0..3).map(score).fold(0.0, f64::max);
    if best < MIN_FILL {
        return AutoUp { fill, ..fallback };
    }
    let tied: Vec<usize> = (0..3).filter(|&k| score(k) >= TIE * best).collect();
    let odd = |k: usize| {
        let (e1, e2) = (ext[(k + 1) % 3], ext[(k + 2) % 3]);
        let r = ext[k] / (e1 * e2).sqrt();
        if r.is_finite() && r > 0.0 {
            r.ln().abs()
        } else {
            f64::INFINITY
        }
    };
    let most = tied.iter().map(|&k| odd(k)).fold(0.0, f64::max);
    // Preference among equals: Y, Z, X.
    let axis = [1, 2, 0]
        .into_iter()
        .find(|k| tied.contains(k) && odd(*k) >= most - ODD_TIE)
        .unwrap_or(1);
    let (plus, minus) = (fill[2 * axis], fill[2 * axis + 1]);
    let sign = if plus < TIE * minus { -1.0 } else { 1.0 };
    let mut up = V3::zeros();
    up[axis] = sign;
    AutoUp {
        up,
        fill,
        based: true,
    }
}

/// Area of the convex hull of `pts`.
fn hull_area(pts: Vec<Pt2>) -> f64 {
    let h = convex_hull(pts);
    if h.len() < 3 {
        0.0
    } else {
        ring_area(&h).abs()
    }
}

/// The rotation taking +Y to the unit vector `up` by the least angle (a half turn about X for
/// −Y), as a function on vectors. Exact for the six axis directions.
pub(crate) fn from_y(up: V3) -> impl Fn(V3) -> V3 {
    let u = up.try_normalize(0.0).unwrap_or_else(V3::y);
    let c = u.y;
    let m = if c <= -1.0 + 1e-12 {
        nalgebra::Matrix3::from_diagonal(&V3::new(1.0, -1.0, -1.0))
    } else {
        let v = V3::y().cross(&u);
        let k = v.cross_matrix();
        nalgebra::Matrix3::identity() + k + k * k / (1.0 + c)
    };
    move |x| m * x
}

/// A unit up vector as people write it: `+Z`, or its three numbers.
pub(crate) fn axis_name(up: &V3) -> String {
    for (k, n) in ["X", "Y", "Z"].iter().enumerate() {
        let mut e = V3::zeros();
        e[k] = 1.0;
        if *up == e {
            return format!("+{n}");
        }
        if *up == -e {
            return format!("-{n}");
        }
    }
    format!("{},{},{}", up.x, up.y, up.z)
}

impl Scene {
    /// The up axis `--up auto` chooses for this scene: the axis direction it stands on (see
    /// the rule in `src/view/up.rs`: the base of largest fill among ±X, ±Y, ±Z, +Y when none
    /// fills a quarter of the scene's shadow).
    pub fn auto_up(&self) -> V3 {
        self.auto_up_verdict().up
    }

    /// The auto rule's verdict with the fills it saw.
    pub(crate) fn auto_up_verdict(&self) -> AutoUp {
        let pts: Vec<P3> = self
            .leaves()
            .iter()
            .flat_map(|l| l.world_vertices().collect::<Vec<_>>())
            .collect();
        auto_up(&pts)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The corners of the box [0, x] × [0, y] × [0, z].
    fn cuboid(x: f64, y: f64, z: f64, at: [f64; 3]) -> Vec<P3> {
        (0..8)
            .map(|k| {
                P3::new(
                    at[0] + if k & 1 == 0 { 0.0 } else { x },
                    at[1] + if k & 2 == 0 { 0.0 } else { y },
                    at[2] + if k & 4 == 0 { 0.0 } else { z },
                )
            })
            .collect()
    }

    /// Points on a sphere of radius r about c (latitude-longitude grid, poles included).
    fn sphere(c: [f64; 3], r: f64) -> Vec<P3> {
        let mut out = Vec::new();
        for i in 0..=12 {
            let th = std::f64::consts::PI * i as f64 / 12.0;
            for j in 0..24 {
                let ph = std::f64::consts::TAU * j as f64 / 24.0;
                out.push(P3::new(
                    c[0] + r * th.sin() * ph.cos(),
                    c[1] + r * th.sin() * ph.sin(),
                    c[2] + r * th.cos(),
                ));
            }
        }
        out
    }

    /// Swaps axes so that the +Z of a Z-up model becomes `up` (a proper rotation).
    fn stand(points: &[P3], f: impl Fn(&P3) -> P3) -> Vec<P3> {
        points.iter().map(f).collect()
    }

    #[test]
    fn a_cube_and_a_sphere_keep_plus_y() {
        let c = auto_up(&cuboid(1., 1., 1., [0.; 3]));
        assert_eq!(c.up, V3::y());
        assert!(c.based && c.fill.iter().all(|f| (*f - 1.0).abs() < 1e-12));
        let s = auto_up(&sphere([0.; 3], 1.0));
        assert_eq!(s.up, V3::y());
        assert!(!s.based);
        assert_eq!(auto_up(&[]).up, V3::y());
    }

    #[test]
    fn a_flat_slab_lies_on_its_broad_face() {
        assert_eq!(auto_up(&cuboid(5., 5., 0.5, [0.; 3])).up, V3::z());
        assert_eq!(auto_up(&cuboid(0.5, 5., 5., [0.; 3])).up, V3::x());
        assert_eq!(auto_up(&cuboid(5., 0.5, 4., [0.; 3])).up, V3::y());
        // A sheet of no thickness too.
        let sheet = vec![
            P3::new(0., 0., 0.),
            P3::new(2., 0., 0.),
            P3::new(2., 3., 0.),
            P3::new(0., 3., 0.),
        ];
        assert_eq!(auto_up(&sheet).up, V3::z());
    }

    #[test]
    fn a_tall_prism_stands_on_its_end() {
        assert_eq!(auto_up(&cuboid(1., 1., 5., [0.; 3])).up, V3::z());
        assert_eq!(auto_up(&cuboid(6., 1., 1.2, [0.; 3])).up, V3::x());
        assert_eq!(auto_up(&cuboid(1., 4., 1., [0.; 3])).up, V3::y());
    }

    /// A bust: a square plinth, a wider block of shoulders, a round head on top (Z-up).
    fn bust() -> Vec<P3> {
        let mut p = cuboid(2., 2., 0.6, [-1., -1., 0.]);
        p.extend(cuboid(3., 1.6, 1.2, [-1.5, -0.8, 0.6]));
        p.extend(sphere([0., 0., 2.6], 0.8));
        p
    }

    #[test]
    fn a_bust_stands_on_its_plinth_whichever_way_it_was_saved() {
        let b = bust();
        let v = auto_up(&b);
        assert_eq!(v.up, V3::z(), "{v:?}");
        // Y-up: (x, y, z) -> (x, z, -y); upside down; lying along -X.
        let y = stand(&b, |p| P3::new(p.x, p.z, -p.y));
        assert_eq!(auto_up(&y).up, V3::y());
        let down = stand(&b, |p| P3::new(p.x, -p.y, -p.z));
        assert_eq!(auto_up(&down).up, -V3::z());
        let x = stand(&b, |p| P3::new(-p.z, p.y, p.x));
        assert_eq!(auto_up(&x).up, -V3::x());
    }

    #[test]
    fn the_rotation_from_y_is_exact_on_axes() {
        for (up, img_z) in [
            (V3::y(), V3::z()),
            (V3::z(), -V3::y()),
            (-V3::z(), V3::y()),
            (V3::x(), V3::z()),
            (-V3::x(), V3::z()),
            (-V3::y(), -V3::z()),
        ] {
            let r = from_y(up);
            assert_eq!(r(V3::y()), up);
            assert_eq!(r(V3::z()), img_z, "{up:?}");
        }
        let u = V3::new(1., 2., 3.).normalize();
        let r = from_y(u);
        assert!((r(V3::y()) - u).norm() < 1e-15);
        assert!((r(V3::x()).dot(&u)).abs() < 1e-15);
        assert_eq!(axis_name(&-V3::z()), "-Z");
        assert_eq!(axis_name(&V3::y()), "+Y");
    }
}
