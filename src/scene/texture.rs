//! Face texture: the paper's local 2-D coordinate system of a face plane, and surface markings.

use crate::geom::{P3, V3};

/// Markings drawn on a face, in the face's texture coordinates: points, lines between
/// them, and polygons over them (the paper's texture components 2-4).
#[derive(Debug, Clone, Default, PartialEq)]
pub(crate) struct Texture {
    /// The point set.
    pub points: Vec<[f64; 2]>,
    /// Lines as pairs of point indices.
    pub lines: Vec<[u32; 2]>,
    /// Polygons as point index lists.
    pub polygons: Vec<Vec<u32>>,
}

/// The texture coordinate system of a plane (the paper's component 1): origin at the point
/// of the plane nearest the world origin, a horizontal unit x-vector (no world z component),
/// and the parity that makes the y-vector's z component positive. A horizontal plane uses
/// x = (1,0,0), y = (0,1,0). The paper's vertical axis is world z.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct TextureFrame {
    /// The origin: the plane's point nearest (0,0,0).
    pub origin: P3,
    /// Unit x-vector, in the plane, horizontal.
    pub x: V3,
    /// Unit y-vector, in the plane.
    pub y: V3,
}

/// Cosine-free tolerance for "horizontal": the unit normal's horizontal part is below this.
const HORIZONTAL_EPS: f64 = 1e-12;

impl TextureFrame {
    /// The frame of the plane through `point` with (not necessarily unit) normal `normal`.
    /// Returns None for a zero normal.
    pub(crate) fn of_plane(point: &P3, normal: &V3) -> Option<Self> {
        let len = normal.norm();
        if len == 0.0 || !len.is_finite() {
            return None;
        }
        let n = normal / len;
        let d = n.dot(&point.coords);
        let origin = P3::from(n * d);
        let h = (n.x * n.x + n.y * n.y).sqrt();
        if h <= HORIZONTAL_EPS {
            return Some(TextureFrame {
                origin,
                x: V3::x(),
                y: V3::y(),
            });
        }
        // Horizontal direction in the plane: perpendicular to n and to world z.
        let x = V3::new(-n.y, n.x, 0.0) / h;
        let mut y = n.cross(&x);
        if y.z < 0.0 {
            y = -y;
        }
        Some(TextureFrame { origin, x, y })
    }

    /// World point of texture coordinates (s, t).
    pub(crate) fn to_world(self, st: [f64; 2]) -> P3 {
        self.origin + self.x * st[0] + self.y * st[1]
    }

    /// Texture coordinates of a world point (projected onto the plane).
    pub(crate) fn to_texture(self, p: &P3) -> [f64; 2] {
        let d = p - self.origin;
        [d.dot(&self.x), d.dot(&self.y)]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn vertical_wall_frame() {
        // The plane y = 2: normal (0,1,0). Origin (0,2,0); x horizontal; y = +z.
        let f = TextureFrame::of_plane(&P3::new(5., 2., 7.), &V3::new(0., 3., 0.)).unwrap();
        assert_eq!(f.origin, P3::new(0., 2., 0.));
        assert!(f.x.z == 0.0 && (f.x.norm() - 1.0).abs() < 1e-15);
        assert!((f.y - V3::z()).norm() < 1e-15);
        let p = P3::new(1.5, 2.0, -3.0);
        let st = f.to_texture(&p);
        assert!((f.to_world(st) - p).norm() < 1e-14);
    }

    #[test]
    fn horizontal_face_case() {
        let f = TextureFrame::of_plane(&P3::new(1., 1., 4.), &V3::new(0., 0., -2.)).unwrap();
        assert_eq!((f.x, f.y), (V3::x(), V3::y()));
        assert_eq!(f.origin, P3::new(0., 0., 4.));
    }

    #[test]
    fn parity_makes_y_point_up() {
        for n in [
            V3::new(1., 1., 1.),
            V3::new(-1., 2., -3.),
            V3::new(0.3, -0.2, 0.9),
        ] {
            let f = TextureFrame::of_plane(&P3::new(1., 2., 3.), &n).unwrap();
            assert!(f.y.z > 0.0, "{n:?}");
            assert!(f.x.dot(&n).abs() < 1e-14 && f.y.dot(&n).abs() < 1e-14 && f.x.z == 0.0);
            // The origin is the nearest point: it is parallel to the normal.
            assert!(f.origin.coords.cross(&n).norm() < 1e-12);
        }
        assert!(TextureFrame::of_plane(&P3::origin(), &V3::zeros()).is_none());
    }
}
