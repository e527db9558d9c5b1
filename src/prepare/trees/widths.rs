//! Cell widths for the simplified models, from the distribution of edge lengths (paper 002
//! section 5): where the frequency of edge lengths changes drastically, a model is locally
//! dense but globally sparse, and that length is a good clustering cell width.
//!
//! The straightforward algorithm used here: a histogram of the face sides' lengths in bins
//! of a quarter octave; a location is drastic where a bin holds at least [`DROP`] times as
//! many sides as the next one (the upper end of that bin is the width). Only drastic
//! simplifications give useful parts, so widths are kept between [`FINEST`] and
//! [`COARSEST`] of the model's diagonal, at least [`SPACING`] apart. Models without such a
//! location (an evenly sampled scan has one peak) get the default widths of [`DEFAULTS`]
//! (fractions of the diagonal) where no drastic width lies near them. At most [`LEVELS`]
//! widths, coarsest first.

use crate::geom::Box3;
use crate::scene::Mesh;

/// Most simplified models (the paper uses fewer than 4).
pub(crate) const LEVELS: usize = 3;
/// A drastic change: this many times the next bin's count.
pub(crate) const DROP: f64 = 4.0;
/// Finest width kept, as a fraction of the diagonal.
pub(crate) const FINEST: f64 = 1.0 / 32.0;
/// Coarsest width kept, as a fraction of the diagonal.
pub(crate) const COARSEST: f64 = 1.0 / 3.0;
/// Least ratio between two widths.
pub(crate) const SPACING: f64 = 1.5;
/// Default widths, fractions of the diagonal, coarsest first.
pub(crate) const DEFAULTS: [f64; LEVELS] = [1.0 / 4.0, 1.0 / 8.0, 1.0 / 16.0];
/// Histogram bins per octave.
const BINS_PER_OCTAVE: f64 = 4.0;

/// The cell widths of the simplified models, coarsest first (empty for a mesh without extent).
pub(crate) fn cell_widths(mesh: &Mesh) -> Vec<f64> {
    let b = Box3::from_points(mesh.vertices.iter());
    let s = b.size();
    let diag = (s[0] * s[0] + s[1] * s[1] + s[2] * s[2]).sqrt();
    if !(diag > 0.0 && diag.is_finite()) {
        return Vec::new();
    }
    let mut widths: Vec<f64> = drastic_lengths(mesh)
        .into_iter()
        .filter(|&w| (FINEST * diag..=COARSEST * diag).contains(&w))
        .collect();
    widths.sort_by(|a, b| b.total_cmp(a));
    let mut kept: Vec<f64> = Vec::new();
    for w in widths {
        if kept.iter().all(|&k| far(k, w)) && kept.len() < LEVELS {
            kept.push(w);
        }
    }
    for d in DEFAULTS {
        let w = d * diag;
        if kept.len() < LEVELS && kept.iter().all(|&k| far(k, w)) {
            kept.push(w);
        }
    }
    kept.sort_by(|a, b| b.total_cmp(a));
    kept
}

fn far(a: f64, b: f64) -> bool {
    a.max(b) >= SPACING * a.min(b)
}

/// Lengths where the histogram of side lengths drops drastically (upper ends of such bins).
pub(crate) fn drastic_lengths(mesh: &Mesh) -> Vec<f64> {
    let mut lengths = Vec::new();
    for f in &mesh.faces {
        let v = &f.vertices;
        for i in 0..v.len() {
            let d = (mesh.vertices[v[(i + 1) % v.len()] as usize] - mesh.vertices[v[i] as usize])
                .norm();
            if d > 0.0 && d.is_finite() {
                lengths.push(d);
            }
        }
    }
    let Some(lo) = lengths.iter().copied().reduce(f64::min) else {
        return Vec::new();
    };
    let bin = |d: f64| ((d / lo).log2() * BINS_PER_OCTAVE).floor() as usize;
    let n = lengths.iter().map(|&d| bin(d)).max().unwrap_or(0) + 2;
    let mut counts = vec![0usize; n];
    for &d in &lengths {
        counts[bin(d)] += 1;
    }
    (0..n - 1)
        .filter(|&i| counts[i] > 0 && counts[i] as f64 >= DROP * counts[i + 1] as f64)
        .map(|i| lo * ((i + 1) as f64 / BINS_PER_OCTAVE).exp2())
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::P3;
    use crate::scene::Face;

    #[test]
    fn dense_detail_on_a_sparse_body_gives_its_drastic_width() {
        // A big triangle (sides 100) and a fan of 40 tiny triangles (sides about 1) at one
        // corner: the histogram drops drastically after the short sides, and again after
        // the long ones.
        let mut vertices = vec![
            P3::new(0., 0., 0.),
            P3::new(100., 0., 0.),
            P3::new(0., 100., 0.),
        ];
        let mut faces = vec![Face::new(vec![0, 1, 2])];
        for i in 0..40 {
            let k = vertices.len() as u32;
            let x = 200.0 + 2.0 * i as f64;
            vertices.extend([
                P3::new(x, 0., 0.),
                P3::new(x + 1., 0., 0.),
                P3::new(x, 1., 0.),
            ]);
            faces.push(Face::new(vec![k, k + 1, k + 2]));
        }
        let m = Mesh {
            vertices,
            faces,
            closed: false,
            solidity: None,
            caps: Vec::new(),
            proven: None,
            pieces: None,
        };
        let d = drastic_lengths(&m);
        assert!(d.iter().any(|&w| (1.4..3.0).contains(&w)), "{d:?}");
        assert!(d.iter().any(|&w| w > 141.0), "{d:?}");
        let w = cell_widths(&m);
        assert!(!w.is_empty() && w.len() <= LEVELS);
        assert!(w.windows(2).all(|p| p[0] >= SPACING * p[1]), "{w:?}");
    }
}
