//! Dashed lines as geometry a plotter draws: each dash its own stroke.
//!
//! The pattern (dash, gap) runs along a whole polyline, round its corners, starting with a
//! dash at its first point; a dash may turn a corner. A polyline shorter than one dash is
//! one dash.

use crate::geom::poly2::{dist, Pt2};

/// The dashes of polyline `pts` with pattern `dash` on, `gap` off (both > 0).
pub(crate) fn dashes(pts: &[Pt2], dash: f64, gap: f64) -> Vec<Vec<Pt2>> {
    let mut out = Vec::new();
    let mut cur: Vec<Pt2> = Vec::new();
    // Distance left in the current phase, and whether the pen is down in it.
    let (mut left, mut down) = (dash, true);
    for w in pts.windows(2) {
        let (a, b) = (w[0], w[1]);
        let len = dist(a, b);
        if len == 0.0 {
            continue;
        }
        let mut t = 0.0; // distance along this segment done
        if down && cur.is_empty() {
            cur.push(a);
        }
        while len - t > left {
            t += left;
            let p = point(a, b, t, len);
            if cur.last() != Some(&p) {
                cur.push(p);
            }
            if down {
                out.push(std::mem::take(&mut cur));
                left = gap;
            } else {
                left = dash;
            }
            down = !down;
        }
        left -= len - t;
        if down && cur.last() != Some(&b) {
            cur.push(b);
        }
    }
    if cur.len() > 1 {
        out.push(cur);
    }
    out
}

/// Point at distance `t` along a → b of length `len` (exactly b at the end).
fn point(a: Pt2, b: Pt2, t: f64, len: f64) -> Pt2 {
    if t >= len {
        return b;
    }
    [
        a[0] + (b[0] - a[0]) * t / len,
        a[1] + (b[1] - a[1]) * t / len,
    ]
}

#[cfg(test)]
mod tests {
    use super::*;

    use crate::geom::poly2::polyline_length as length;

    #[test]
    fn straight_line_dashes() {
        let d = dashes(&[[0., 0.], [10., 0.]], 2.0, 1.0);
        // Dashes at [0,2], [3,5], [6,8], [9,10].
        let starts: Vec<f64> = d.iter().map(|l| l[0][0]).collect();
        assert_eq!(starts, vec![0., 3., 6., 9.]);
        let lens: Vec<f64> = d.iter().map(|l| length(l)).collect();
        assert_eq!(lens, vec![2., 2., 2., 1.]);
    }

    #[test]
    fn dashes_turn_corners_and_keep_their_length() {
        // An L of two 1.5 legs with dash 2, gap 1: the first dash turns the corner.
        let d = dashes(&[[0., 0.], [1.5, 0.], [1.5, 1.5]], 2.0, 1.0);
        assert_eq!(d.len(), 1);
        assert_eq!(d[0], vec![[0., 0.], [1.5, 0.], [1.5, 0.5]]);
        // Total inked length over a long zigzag is dash / (dash + gap) of it, give or take
        // one pattern.
        let zig: Vec<Pt2> = (0..100).map(|k| [f64::from(k), f64::from(k % 2)]).collect();
        let inked: f64 = dashes(&zig, 0.7, 0.3).iter().map(|l| length(l)).sum();
        let total = length(&zig);
        assert!((inked - 0.7 * total).abs() <= 1.0, "{inked} of {total}");
    }

    #[test]
    fn short_line_is_one_dash() {
        assert_eq!(
            dashes(&[[0., 0.], [0.5, 0.]], 2.0, 1.0),
            vec![vec![[0., 0.], [0.5, 0.]]]
        );
    }
}
