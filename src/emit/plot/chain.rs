//! Joining segments into long polylines (at exactly equal end points) and ordering polylines
//! greedily (nearest next start, reversal allowed) so that a pen plotter lifts the pen little.
//! The drawing's own per-object order; pictures refine it across whole layers ([`super::tour`]).

use crate::geom::grid::{per_side, Cells};
use crate::geom::key_hash::{point_key as key, KeyMap};
use crate::geom::poly2::Pt2;

/// Joins segments into polylines: each polyline follows unused segments that share an end
/// point exactly, forward then backward. Deterministic (segments taken in input order).
pub(crate) fn chain(segments: &[[Pt2; 2]]) -> Vec<Vec<Pt2>> {
    let mut at: KeyMap<(u64, u64), Vec<usize>> = KeyMap::default();
    for (i, s) in segments.iter().enumerate() {
        at.entry(key(s[0])).or_default().push(i);
        if key(s[1]) != key(s[0]) {
            at.entry(key(s[1])).or_default().push(i);
        }
    }
    let mut used = vec![false; segments.len()];
    let mut out = Vec::new();
    for i in 0..segments.len() {
        if used[i] {
            continue;
        }
        used[i] = true;
        let mut line = vec![segments[i][0], segments[i][1]];
        extend(&mut line, segments, &at, &mut used);
        line.reverse();
        extend(&mut line, segments, &at, &mut used);
        out.push(line);
    }
    out
}

/// Extends `line` at its last point with unused segments.
fn extend(
    line: &mut Vec<Pt2>,
    segments: &[[Pt2; 2]],
    at: &KeyMap<(u64, u64), Vec<usize>>,
    used: &mut [bool],
) {
    loop {
        let Some(&end) = line.last() else { return };
        let next = at
            .get(&key(end))
            .and_then(|v| v.iter().copied().find(|&j| !used[j]));
        let Some(j) = next else { return };
        used[j] = true;
        let s = segments[j];
        line.push(if key(s[0]) == key(end) { s[1] } else { s[0] });
    }
}

/// Orders polylines greedily from the first one: next is the one whose start or end is
/// nearest the pen (reversed when its end is nearer). A uniform grid keeps it near-linear.
pub(crate) fn order(mut lines: Vec<Vec<Pt2>>) -> Vec<Vec<Pt2>> {
    lines.retain(|l| !l.is_empty());
    if lines.len() < 3 {
        return lines;
    }
    let ends: Vec<[Pt2; 2]> = lines.iter().map(|l| [l[0], l[l.len() - 1]]).collect();
    greedy(&ends, 0)
        .into_iter()
        .map(|(i, rev)| {
            let mut l = std::mem::take(&mut lines[i]);
            if rev {
                l.reverse();
            }
            l
        })
        .collect()
}

/// Greedy nearest-neighbour order of strokes given by their (start, end) points, from
/// stroke `first`: each next stroke is the one with an end nearest the pen, reversed (`true`)
/// when that is its end. Ties go to the lower index.
pub(crate) fn greedy(ends: &[[Pt2; 2]], first: usize) -> Vec<(usize, bool)> {
    if ends.is_empty() {
        return Vec::new();
    }
    let mut grid = Grid::new(ends);
    let mut used = vec![false; ends.len()];
    let mut out = Vec::with_capacity(ends.len());
    let (mut cur, mut reversed) = (first.min(ends.len() - 1), false);
    loop {
        used[cur] = true;
        out.push((cur, reversed));
        let pen = ends[cur][usize::from(!reversed)];
        match grid.nearest(pen, ends, &used) {
            Some((n, rev)) => (cur, reversed) = (n, rev),
            None => break,
        }
    }
    out
}

/// A uniform grid over stroke end points.
struct Grid {
    frame: Cells,
    cells: Vec<Vec<(usize, bool)>>,
}

impl Grid {
    fn new(ends: &[[Pt2; 2]]) -> Grid {
        let b = crate::geom::Rect::of_points(ends.iter().flatten());
        let frame = Cells::square(&b, per_side(ends.len() as f64, 1024));
        let mut g = Grid {
            frame,
            cells: vec![Vec::new(); frame.len()],
        };
        for (i, [s, e]) in ends.iter().enumerate() {
            let c = g.frame.index(*s);
            g.cells[c].push((i, false));
            let c = g.frame.index(*e);
            g.cells[c].push((i, true));
        }
        g
    }

    /// Nearest unused end point: (stroke, true when it is the stroke's end). Entries of used
    /// strokes are dropped lazily.
    fn nearest(&mut self, p: Pt2, ends: &[[Pt2; 2]], used: &[bool]) -> Option<(usize, bool)> {
        let (cx, cy) = self.frame.coords(p);
        let (n, side) = (self.frame.nx, self.frame.cell);
        let mut best: Option<(f64, usize, bool)> = None;
        for r in 0..n {
            // Every point in ring r is at least (r - 1) cells away.
            if let Some((d, _, _)) = best {
                if r > 1 && d < ((r - 1) as f64 * side).powi(2) {
                    break;
                }
            }
            let mut any_cell = false;
            for y in cy.saturating_sub(r)..=(cy + r).min(n - 1) {
                for x in cx.saturating_sub(r)..=(cx + r).min(n - 1) {
                    if x.abs_diff(cx) != r && y.abs_diff(cy) != r {
                        continue;
                    }
                    any_cell = true;
                    let cell = &mut self.cells[y * n + x];
                    cell.retain(|&(i, _)| !used[i]);
                    for &(i, rev) in cell.iter() {
                        let q = ends[i][usize::from(rev)];
                        let d = (q[0] - p[0]).powi(2) + (q[1] - p[1]).powi(2);
                        if best.is_none_or(|(bd, bi, br)| (d, i, rev) < (bd, bi, br)) {
                            best = Some((d, i, rev));
                        }
                    }
                }
            }
            if !any_cell {
                break;
            }
        }
        best.map(|(_, i, rev)| (i, rev))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn chains_segments_in_any_direction() {
        let s = [
            [[1., 0.], [2., 0.]],
            [[5., 5.], [6., 6.]],
            [[0., 0.], [1., 0.]],
            [[3., 0.], [2., 0.]],
        ];
        let c = chain(&s);
        assert_eq!(c.len(), 2);
        let long = c.iter().find(|l| l.len() == 4).unwrap();
        let mut xs: Vec<f64> = long.iter().map(|p| p[0]).collect();
        if xs[0] > xs[3] {
            xs.reverse();
        }
        assert_eq!(xs, vec![0., 1., 2., 3.]);
    }

    #[test]
    fn closed_loop_chains_to_one_line() {
        let s = [
            [[0., 0.], [1., 0.]],
            [[1., 0.], [1., 1.]],
            [[1., 1.], [0., 0.]],
        ];
        let c = chain(&s);
        assert_eq!(c.len(), 1);
        assert_eq!(c[0].len(), 4);
        assert_eq!(c[0][0], c[0][3]);
    }

    #[test]
    fn order_picks_nearest_and_reverses() {
        let lines = vec![
            vec![[0., 0.], [1., 0.]],
            vec![[10., 0.], [11., 0.]],
            vec![[3., 0.], [1.5, 0.]],
        ];
        let o = order(lines);
        assert_eq!(
            o,
            vec![
                vec![[0., 0.], [1., 0.]],
                vec![[1.5, 0.], [3., 0.]],
                vec![[10., 0.], [11., 0.]],
            ]
        );
    }
}
