//! An INBOX carried through an instance's transform: exact for axis-preserving transforms,
//! otherwise the largest axis-aligned box inside the transformed (parallelepiped) box.

use nalgebra::Matrix3;

use crate::geom::{Box3, M4, V3};

use super::halfspace::{largest_box, HalfSpace};
use super::solid::shrink;

/// Relative shrink of the optimised box; its corners are then checked, mapped back, to lie
/// inside the original box by at least [`CHECK`] of its size (f64 inverse-map error is far
/// below that for any sane transform).
const SHRINK: f64 = 1e-7;
/// Relative clearance required of the mapped-back corners.
const CHECK: f64 = 1e-9;

/// An axis-aligned box inside the image of `b` under the affine transform `m` (None when
/// `m` is singular or not affine, or the result fails its check).
pub(crate) fn place_box(b: &Box3, m: &M4) -> Option<Box3> {
    if !b.has_interior() || m[(3, 0)] != 0.0 || m[(3, 1)] != 0.0 || m[(3, 2)] != 0.0 {
        return None;
    }
    let lin: Matrix3<f64> = m.fixed_view::<3, 3>(0, 0).into_owned();
    if axis_preserving(&lin) {
        return Some(b.transformed(m));
    }
    let inv = lin.try_inverse()?;
    let t = V3::new(m[(0, 3)], m[(1, 3)], m[(2, 3)]);
    let planes = parallelepiped(b, &inv, &t);
    let centre = m.transform_point(&b.center());
    let out = shrink(&largest_box(&planes, &centre)?, SHRINK);
    let size = b.size();
    let ok = out.corners().iter().all(|c| {
        let y = inv * (c.coords - t);
        (0..3).all(|i| {
            let tol = CHECK * size[i];
            y[i] >= b.lo[i] + tol && y[i] <= b.hi[i] - tol
        })
    });
    ok.then_some(out)
}

/// True when every row and column of `lin` has exactly one non-zero entry.
fn axis_preserving(lin: &Matrix3<f64>) -> bool {
    let nz = |r: usize, c: usize| lin[(r, c)] != 0.0;
    (0..3).all(|r| (0..3).filter(|&c| nz(r, c)).count() == 1)
        && (0..3).all(|c| (0..3).filter(|&r| nz(r, c)).count() == 1)
}

/// The six half-spaces of the image of `b` under x = L y + t, given L⁻¹: lo ≤ L⁻¹(x − t) ≤ hi.
fn parallelepiped(b: &Box3, inv: &Matrix3<f64>, t: &V3) -> Vec<HalfSpace> {
    let mut planes = Vec::with_capacity(6);
    for i in 0..3 {
        let row: V3 = inv.row(i).transpose();
        let shift = row.dot(t);
        planes.push(HalfSpace {
            normal: row,
            offset: b.hi[i] + shift,
        });
        planes.push(HalfSpace {
            normal: -row,
            offset: -b.lo[i] - shift,
        });
    }
    planes
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::P3;

    fn unit() -> Box3 {
        Box3::new(P3::new(-1., -1., -1.), P3::new(1., 1., 1.))
    }

    #[test]
    fn translation_and_scale_are_exact() {
        let m = nalgebra::Translation3::new(5., 0., 1.).to_homogeneous()
            * nalgebra::Matrix4::new_nonuniform_scaling(&V3::new(2., 3., 0.5));
        assert_eq!(place_box(&unit(), &m), Some(unit().transformed(&m)));
    }

    #[test]
    fn rotation_about_z_keeps_full_height() {
        let r = nalgebra::Rotation3::from_axis_angle(&V3::z_axis(), std::f64::consts::FRAC_PI_4);
        let m = r.to_homogeneous();
        let b = place_box(&unit(), &m).unwrap();
        // A square of half-size 1 turned by 45° holds an axis-aligned square of half-size
        // 1/√2 (side √2); the height stays 2.
        assert!((b.size()[2] - 2.0).abs() < 1e-5, "{b:?}");
        assert!((b.size()[0] - 2f64.sqrt()).abs() < 1e-4, "{b:?}");
        assert!(b.center().coords.norm() < 1e-6);
    }
}
