//! Drawing checks shared by the integration tests: pieces of line stroked twice.

use crate::emit::lines::Stroke;
use crate::geom::poly2::Pt2;

/// One straight piece of a stroke.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Seg {
    pub(crate) a: Pt2,
    pub(crate) b: Pt2,
    pub(crate) stroke: usize,
}

/// Every straight piece of the strokes.
pub(crate) fn segments(strokes: &[Stroke]) -> Vec<Seg> {
    strokes
        .iter()
        .enumerate()
        .flat_map(|(k, s)| {
            s.pts.windows(2).map(move |w| Seg {
                a: w[0],
                b: w[1],
                stroke: k,
            })
        })
        .filter(|s| s.a != s.b)
        .collect()
}

/// Pairs of pieces that run along each other (every end of the shorter within `tol` of the
/// longer's line) over more than `tol`, with the length they share: a line stroked twice.
pub(crate) fn double_strokes(strokes: &[Stroke], tol: f64) -> Vec<(Seg, Seg, f64)> {
    let segs = segments(strokes);
    let mut order: Vec<usize> = (0..segs.len()).collect();
    let xmin = |s: &Seg| s.a[0].min(s.b[0]);
    let xmax = |s: &Seg| s.a[0].max(s.b[0]);
    order.sort_by(|&i, &j| xmin(&segs[i]).total_cmp(&xmin(&segs[j])));
    let mut out = Vec::new();
    for (k, &i) in order.iter().enumerate() {
        for &j in &order[k + 1..] {
            if xmin(&segs[j]) > xmax(&segs[i]) + tol {
                break;
            }
            if let Some(len) = shared_length(&segs[i], &segs[j], tol) {
                out.push((segs[i], segs[j], len));
            }
        }
    }
    out
}

/// The length two nearly collinear pieces share, when more than `tol`.
fn shared_length(s: &Seg, t: &Seg, tol: f64) -> Option<f64> {
    let len = |p: Pt2, q: Pt2| (q[0] - p[0]).hypot(q[1] - p[1]);
    let (long, short) = if len(s.a, s.b) >= len(t.a, t.b) {
        (s, t)
    } else {
        (t, s)
    };
    let l = len(long.a, long.b);
    let d = [(long.b[0] - long.a[0]) / l, (long.b[1] - long.a[1]) / l];
    let off = |p: Pt2| ((p[0] - long.a[0]) * d[1] - (p[1] - long.a[1]) * d[0]).abs();
    if off(short.a) > tol || off(short.b) > tol {
        return None;
    }
    let along = |p: Pt2| (p[0] - long.a[0]) * d[0] + (p[1] - long.a[1]) * d[1];
    let (u0, u1) = (along(short.a), along(short.b));
    let shared = u0.max(u1).min(l) - u0.min(u1).max(0.0);
    (shared > tol).then_some(shared)
}
