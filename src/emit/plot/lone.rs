//! Lines a join leaves as they are: no end of another line within the join's tolerance of
//! either of their ends (and their own two ends not one point), so neither the join at equal
//! ends nor the join within the tolerance can touch them. Hidden dashes are nearly all such
//! lines ([`super::join::join_sparse`] joins only the others).

use rayon::prelude::*;

use crate::geom::grid::{per_side, Cells};
use crate::geom::key_hash::point_key as key;
use crate::geom::poly2::{dist, Pt2};
use crate::geom::Rect;

/// Whether each line (two points or more) is alone: no end of another line at distance
/// `tol` (≥ 0) or less from either of its ends, as [`dist`] measures it, and its two ends
/// not the same point. From a uniform grid of cells no smaller than `tol`, each end looked
/// for in its cell and the eight round it.
pub(crate) fn lone(lines: &[Vec<Pt2>], tol: f64) -> Vec<bool> {
    let pts: Vec<Pt2> = lines.iter().flat_map(|l| [l[0], l[l.len() - 1]]).collect();
    let b = Rect::of_points(pts.iter());
    // About an end a cell, but no cell smaller than `tol` (with a margin for rounding), so
    // that ends within `tol` are in neighbouring cells.
    let mut n = per_side(pts.len() as f64, 2048);
    let side = b.longer_side();
    if tol > 0.0 && side.is_finite() {
        n = n.min(((side / (tol * (1.0 + 1e-6))).floor() as usize).max(1));
    }
    let grid = Cells::square(&b, n);
    // The ends cell by cell.
    let (start, in_cells) = grid.buckets(&pts);
    // Ends within `tol` of p lie in its cell, or in a neighbouring one where p is that close
    // to the side between them (a margin for rounding).
    let margin = tol * (1.0 + 1e-6) + 1e-9 * grid.cell;
    let reach = |v: f64, o: f64, c: usize| {
        let inside = v - (o + c as f64 * grid.cell);
        let lo = if c > 0 && inside <= margin { c - 1 } else { c };
        let hi = if c + 1 < n && grid.cell - inside <= margin {
            c + 1
        } else {
            c
        };
        lo..=hi
    };
    let near = |s: usize| {
        let p = pts[s];
        let (cx, cy) = grid.coords(p);
        let (xs, ys) = (
            reach(p[0], grid.origin[0], cx),
            reach(p[1], grid.origin[1], cy),
        );
        ys.into_iter().any(|y| {
            xs.clone().any(|x| {
                let c = y * n + x;
                in_cells[start[c] as usize..start[c + 1] as usize]
                    .iter()
                    .any(|&t| t as usize / 2 != s / 2 && dist(p, pts[t as usize]) <= tol)
            })
        })
    };
    // Each line on its own: the same answer on any number of threads.
    (0..lines.len())
        .into_par_iter()
        .map(|i| {
            let (a, z) = (2 * i, 2 * i + 1);
            key(pts[a]) != key(pts[z]) && !near(a) && !near(z)
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_line_is_alone_without_another_end_within_the_tolerance() {
        let lines = vec![
            vec![[0.0, 0.0], [1.0, 0.0]],  // 0: its end 0.04 from 1's start
            vec![[1.04, 0.0], [2.0, 0.0]], // 1
            vec![[5.0, 5.0], [6.0, 5.0]],  // 2: alone
            vec![[6.0, 5.06], [7.0, 5.0]], // 3: 0.06 from 2's end: alone at 0.05
            vec![[9.0, 9.0], [9.0, 9.0]],  // 4: its ends one point
            vec![[3.0, 3.0], [4.0, 4.0]],  // 5: shares an end with 6
            vec![[4.0, 4.0], [3.0, 5.0]],  // 6
            vec![[8.0, 0.0], [8.01, 0.0]], // 7: its own ends close: alone
        ];
        let want = [false, false, true, true, false, false, false, true];
        assert_eq!(lone(&lines, 0.05), want);
        // No tolerance: only shared ends count.
        let want = [true, true, true, true, false, false, false, true];
        assert_eq!(lone(&lines, 0.0), want);
        // A tolerance wider than the picture: one cell.
        assert_eq!(lone(&lines, 100.0), [false; 8]);
    }

    #[test]
    fn lone_lines_are_those_a_brute_force_finds() {
        let mut rng = crate::geom::rng::XorShift::new(5);
        let mut lines: Vec<Vec<Pt2>> = (0..2000)
            .map(|_| {
                let a = [rng.range(0.0, 50.0), rng.range(0.0, 50.0)];
                vec![
                    a,
                    [a[0] + rng.range(-1.0, 1.0), a[1] + rng.range(-1.0, 1.0)],
                ]
            })
            .collect();
        // Some shared ends.
        for k in 0..100 {
            let p = lines[k][1];
            lines[k + 1000][0] = p;
        }
        for tol in [0.0, 0.05, 0.3, 1.5] {
            let got = lone(&lines, tol);
            for (i, l) in lines.iter().enumerate() {
                let ends = |l: &Vec<Pt2>| [l[0], l[l.len() - 1]];
                let near = lines.iter().enumerate().any(|(j, m)| {
                    j != i
                        && ends(l)
                            .iter()
                            .any(|&p| ends(m).iter().any(|&q| dist(p, q) <= tol))
                });
                assert_eq!(
                    got[i],
                    !near && key(l[0]) != key(l[1]),
                    "line {i}, tol {tol}"
                );
            }
        }
    }
}
