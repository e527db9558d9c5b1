//! Mesh builders as OBJ text: a test writes the file and hands it to the loader or the CLI,
//! so it reaches the library only through its public ways in.

use std::fmt::Write as _;

/// OBJ text of points and faces (faces index `points` from 0).
pub fn obj_text(points: &[[f64; 3]], faces: &[&[u32]]) -> String {
    let mut s = String::new();
    for p in points {
        let _ = writeln!(s, "v {} {} {}", p[0], p[1], p[2]);
    }
    for f in faces {
        s.push('f');
        for k in f.iter() {
            let _ = write!(s, " {}", k + 1);
        }
        s.push('\n');
    }
    s
}

/// OBJ text of an axis-aligned box, faces wound outwards.
pub fn cuboid_obj(lo: [f64; 3], hi: [f64; 3]) -> String {
    let corner = |i: usize| {
        let pick = |k: usize| if i >> k & 1 == 1 { hi[k] } else { lo[k] };
        [pick(0), pick(1), pick(2)]
    };
    let points: Vec<[f64; 3]> = (0..8).map(corner).collect();
    obj_text(
        &points,
        &[
            &[0, 2, 3, 1],
            &[4, 5, 7, 6],
            &[0, 1, 5, 4],
            &[2, 6, 7, 3],
            &[0, 4, 6, 2],
            &[1, 3, 7, 5],
        ],
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_triangle_is_written_one_based() {
        let t = obj_text(&[[0., 0., 0.], [1., 0., 0.], [0., 1., 0.]], &[&[0, 1, 2]]);
        assert_eq!(t, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
        assert_eq!(cuboid_obj([0.; 3], [1.; 3]).lines().count(), 14);
    }
}
