//! Transform nodes of scene files (`translate`, `rotate`, `scale`, `matrix`) as affine 4x4 matrices.

use super::args::Node;
use crate::error::Result;
use crate::geom::{Box3, M4, V3};

/// The names of the transform nodes.
pub(super) const TRANSFORM_NODES: [&str; 4] = ["translate", "rotate", "scale", "matrix"];

/// Relative determinant below which a linear part counts as singular.
const SINGULAR_TOL: f64 = 1e-12;

/// True when `name` is a transform node.
pub(super) fn is_transform(name: &str) -> bool {
    TRANSFORM_NODES.contains(&name)
}

/// The product of `nodes`' transforms, applied in the order written: for nodes T1, T2, ...
/// the result is ... * T2 * T1 (T1 acts on a point first).
pub(super) fn compose(nodes: &[Node]) -> Result<M4> {
    let mut m = M4::identity();
    for n in nodes {
        m = parse(n)? * m;
    }
    Ok(m)
}

/// One transform node as a matrix.
pub(super) fn parse(n: &Node) -> Result<M4> {
    n.no_children()?;
    match n.name() {
        "translate" => translate(n),
        "rotate" => rotate(n),
        "scale" => scale(n),
        "matrix" => matrix(n),
        other => Err(n.parse_err(format!("`{other}` is not a transform"))),
    }
}

fn translate(n: &Node) -> Result<M4> {
    n.check_props(&[])?;
    let v = n.numbers(&[3], "numbers (X Y Z)")?;
    Ok(M4::new_translation(&V3::new(v[0], v[1], v[2])))
}

fn scale(n: &Node) -> Result<M4> {
    n.check_props(&[])?;
    let v = n.numbers(&[1, 3], "numbers (S, or SX SY SZ)")?;
    let s = if v.len() == 1 {
        V3::new(v[0], v[0], v[0])
    } else {
        V3::new(v[0], v[1], v[2])
    };
    let m = M4::new_nonuniform_scaling(&s);
    check_invertible(n, &m)?;
    Ok(m)
}

fn rotate(n: &Node) -> Result<M4> {
    n.check_props(&["axis", "ax", "ay", "az"])?;
    let deg = n.numbers(&[1], "number (the angle in degrees)")?[0];
    let axis = rotation_axis(n)?;
    Ok(rotation(deg, &axis))
}

/// The axis of a `rotate` node: `axis="x"|"y"|"z"`, or `ax= ay= az=` (missing ones are 0).
fn rotation_axis(n: &Node) -> Result<V3> {
    let named = n.string_prop("axis")?;
    let parts = [
        n.number_prop("ax")?,
        n.number_prop("ay")?,
        n.number_prop("az")?,
    ];
    let has_parts = parts.iter().any(Option::is_some);
    match (named, has_parts) {
        (Some(_), true) => {
            Err(n
                .parse_err("`rotate` takes either axis=\"x\"|\"y\"|\"z\" or ax= ay= az=, not both"))
        }
        (Some("x"), false) => Ok(V3::x()),
        (Some("y"), false) => Ok(V3::y()),
        (Some("z"), false) => Ok(V3::z()),
        (Some(other), false) => Err(n.parse_err(format!(
            "unknown axis {other:?}: expected \"x\", \"y\" or \"z\" (or ax= ay= az= for any axis)"
        ))),
        (None, false) => Err(n.parse_err(
            "`rotate` needs an axis: axis=\"x\"|\"y\"|\"z\", or ax= ay= az= for any axis",
        )),
        (None, true) => {
            let v = V3::new(
                parts[0].unwrap_or(0.0),
                parts[1].unwrap_or(0.0),
                parts[2].unwrap_or(0.0),
            );
            let len = v.norm();
            if len == 0.0 || !len.is_finite() {
                return Err(n.invalid("the rotation axis (ax, ay, az) is zero"));
            }
            Ok(v / len)
        }
    }
}

/// Rotation by `deg` degrees about the unit vector `axis` through the origin, right-handed
/// (counter-clockwise seen from the axis' tip). Multiples of 90° are exact.
pub(super) fn rotation(deg: f64, axis: &V3) -> M4 {
    let (s, c) = sin_cos_deg(deg);
    let k = axis;
    let t = 1.0 - c;
    let r = nalgebra::Matrix3::new(
        c + t * k.x * k.x,
        t * k.x * k.y - s * k.z,
        t * k.x * k.z + s * k.y,
        t * k.y * k.x + s * k.z,
        c + t * k.y * k.y,
        t * k.y * k.z - s * k.x,
        t * k.z * k.x - s * k.y,
        t * k.z * k.y + s * k.x,
        c + t * k.z * k.z,
    );
    r.to_homogeneous()
}

/// Sine and cosine of an angle in degrees, exact at multiples of 90°.
fn sin_cos_deg(deg: f64) -> (f64, f64) {
    let r = deg.rem_euclid(360.0);
    if r == 0.0 {
        (0.0, 1.0)
    } else if r == 90.0 {
        (1.0, 0.0)
    } else if r == 180.0 {
        (0.0, -1.0)
    } else if r == 270.0 {
        (-1.0, 0.0)
    } else {
        r.to_radians().sin_cos()
    }
}

fn matrix(n: &Node) -> Result<M4> {
    n.check_props(&[])?;
    let v = n.numbers(&[12, 16], "numbers (3x4 or 4x4, row-major)")?;
    let mut m = M4::identity();
    for (k, x) in v.iter().enumerate() {
        m[(k / 4, k % 4)] = *x;
    }
    if m.row(3) != nalgebra::RowVector4::new(0.0, 0.0, 0.0, 1.0) {
        return Err(n.invalid(
            "the matrix is not affine: its last row must be 0 0 0 1 (projective maps are not allowed)",
        ));
    }
    check_invertible(n, &m)?;
    Ok(m)
}

/// An error when the linear part of `m` is singular (relative to its rows' lengths).
fn check_invertible(n: &Node, m: &M4) -> Result<()> {
    let lin = m.fixed_view::<3, 3>(0, 0);
    let det = lin.determinant();
    let scale: f64 = (0..3).map(|i| lin.row(i).norm()).product();
    if !det.is_finite() || det.abs() <= SINGULAR_TOL * scale {
        return Err(n.invalid(format!(
            "the transform is singular (determinant {det:e}): it would flatten the object"
        )));
    }
    Ok(())
}

/// True when `m` maps axis-aligned boxes to axis-aligned boxes exactly: its linear part has
/// exactly one nonzero entry in each row (a scaled permutation).
pub(super) fn is_axis_preserving(m: &M4) -> bool {
    (0..3).all(|i| (0..3).filter(|&j| m[(i, j)] != 0.0).count() == 1)
}

/// `b` carried by `m` when `m` is axis-preserving (the image is then exactly a box).
pub(super) fn transform_box(b: &Box3, m: &M4) -> Option<Box3> {
    is_axis_preserving(m).then(|| b.transformed(m))
}

/// True when `m` mirrors (negative determinant of its linear part).
pub(super) fn mirrors(m: &M4) -> bool {
    m.fixed_view::<3, 3>(0, 0).determinant() < 0.0
}

#[cfg(test)]
mod tests {
    use std::path::Path;

    use super::super::source::Source;
    use super::*;
    use crate::geom::P3;

    fn composed(text: &str) -> Result<M4> {
        let src = Source::new(Path::new("t.kdl"), text.to_string());
        let doc = src.parse().unwrap();
        let nodes: Vec<Node> = doc.iter().map(|n| Node::new(&src, n)).collect();
        compose(&nodes)
    }

    fn close(a: P3, b: P3) -> bool {
        (a - b).norm() < 1e-12
    }

    #[test]
    fn order_is_as_written() {
        // (1,0,0) scaled by 2 -> (2,0,0); rotated 90 about z -> (0,2,0); moved -> (10,2,0).
        let m = composed("scale 2; rotate 90 axis=\"z\"; translate 10 0 0").unwrap();
        assert_eq!(
            m.transform_point(&P3::new(1., 0., 0.)),
            P3::new(10., 2., 0.)
        );
        // The other order: moved first, then scaled, then rotated.
        let m = composed("translate 10 0 0; scale 2; rotate 90 axis=z").unwrap();
        assert_eq!(
            m.transform_point(&P3::new(1., 0., 0.)),
            P3::new(0., 22., 0.)
        );
        assert!(is_axis_preserving(&m));
    }

    #[test]
    fn rotations_are_right_handed() {
        let p = |t: &str, q: P3| composed(t).unwrap().transform_point(&q);
        assert_eq!(
            p("rotate 90 axis=x", P3::new(0., 1., 0.)),
            P3::new(0., 0., 1.)
        );
        assert_eq!(
            p("rotate 90 axis=y", P3::new(0., 0., 1.)),
            P3::new(1., 0., 0.)
        );
        assert_eq!(
            p("rotate -90 axis=z", P3::new(1., 0., 0.)),
            P3::new(0., -1., 0.)
        );
        // 120 degrees about (1,1,1) permutes the axes: x -> y.
        let q = p("rotate 120 ax=1 ay=1 az=1", P3::new(1., 0., 0.));
        assert!(close(q, P3::new(0., 1., 0.)), "{q}");
        let q = p("rotate 30 az=2", P3::new(2., 0., 0.));
        assert!(close(q, P3::new(3f64.sqrt(), 1., 0.)), "{q}");
        assert!(!is_axis_preserving(&composed("rotate 30 axis=y").unwrap()));
    }

    #[test]
    fn matrices_and_scales() {
        let m = composed("matrix 1 0 0 5  0 2 0 6  0 0 3 7").unwrap();
        assert_eq!(
            m.transform_point(&P3::new(1., 1., 1.)),
            P3::new(6., 8., 10.)
        );
        let m16 = composed("matrix 1 0 0 5 0 2 0 6 0 0 3 7 0 0 0 1").unwrap();
        assert_eq!(m, m16);
        let m = composed("scale 1 -1 2").unwrap();
        assert!(mirrors(&m));
        assert_eq!(
            m.transform_point(&P3::new(1., 1., 1.)),
            P3::new(1., -1., 2.)
        );
    }

    #[test]
    fn bad_transforms_are_errors() {
        let err = |t: &str| composed(t).unwrap_err().to_string();
        assert!(err("matrix 1 0 0 0 0 1 0 0 1 0 0 0").contains("singular"));
        assert!(err("scale 0").starts_with("t.kdl:1:1: the transform is singular"));
        assert!(err("matrix 1 0 0 0 0 1 0 0 0 0 1 0 0 0 1 1").contains("not affine"));
        assert!(err("rotate 10").contains("needs an axis"));
        assert!(err("rotate 10 axis=w").contains("unknown axis"));
        assert!(err("rotate 10 axis=x ax=1").contains("not both"));
        assert!(err("rotate 10 ax=0").contains("zero"));
        assert!(err("translate 1 2").contains("takes 3 numbers"));
        assert!(err("scale 1 2").contains("takes 1 or 3 numbers"));
        assert!(err("translate 1 2 3 foo=1").contains("unknown property `foo`"));
    }

    #[test]
    fn boxes_follow_axis_preserving_maps() {
        let b = Box3::new(P3::new(0., 0., 0.), P3::new(1., 2., 3.));
        let m = composed("rotate 90 axis=z; translate 10 0 0").unwrap();
        assert_eq!(
            transform_box(&b, &m),
            Some(Box3::new(P3::new(8., 0., 0.), P3::new(10., 1., 3.)))
        );
        assert_eq!(
            transform_box(&b, &composed("rotate 45 axis=z").unwrap()),
            None
        );
    }
}
