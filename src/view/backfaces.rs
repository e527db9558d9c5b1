//! Which back faces of a leaf the view may cull: all of a proven solid's, a capped open
//! mesh's away from the caps that face the viewer (the argument: [`mod@crate::prepare::solidity::caps`]),
//! or those of the proven pieces of a mesh that is not a solid as a whole, away from their
//! caps ([`mod@crate::prepare::solidity::pieces`]).

use crate::geom::grid::{per_side, Cells};
use crate::geom::{orient2d, orient3d, Rect, P3};
use crate::scene::Leaf;

use super::camera::{Camera, Projection};
use super::screen::{Facing, Piece};

/// How a leaf's back faces are treated in one view.
#[derive(Debug, Clone)]
pub(crate) enum BackCull<'a> {
    /// Two-sided: no back face is culled.
    None,
    /// A proven solid seen from outside its convex hull: every back face is culled.
    All,
    /// A capped open mesh seen from outside its capped hull: a back face is culled unless
    /// its screen rectangle touches a window (a cap not strictly facing away).
    AwayFrom(CapWindows),
    /// Some pieces of the mesh proven, seen from outside its hull (and its caps' hull): a
    /// back face on one of them is culled unless its screen rectangle touches a window of
    /// their caps.
    Pieces {
        /// By face of the leaf: on a proven piece.
        proven: &'a [bool],
        /// The leaf's first face in the global order.
        first_face: u32,
        /// The windows of the proven pieces' caps.
        windows: CapWindows,
    },
}

impl<'a> BackCull<'a> {
    /// The treatment of `leaf` in `camera`'s view; `all_in_front` says every vertex of the
    /// leaf is in front of the near plane (always, orthographic).
    pub(crate) fn of_leaf(leaf: &Leaf<'a>, camera: &Camera, all_in_front: bool) -> BackCull<'a> {
        if !all_in_front {
            return BackCull::None;
        }
        if leaf.mesh.cullable() {
            return BackCull::All;
        }
        let proven = leaf.mesh.proven.as_ref();
        if !leaf.mesh.capped() && proven.is_none() {
            return BackCull::None;
        }
        let Some(windows) = CapWindows::new(&leaf.mesh.caps, leaf, camera) else {
            return BackCull::None;
        };
        match proven {
            Some(p) => BackCull::Pieces {
                proven: &p.faces,
                first_face: leaf.first_face as u32,
                windows,
            },
            None => BackCull::AwayFrom(windows),
        }
    }

    /// True when `piece` (described, facing decided) may be culled.
    pub(crate) fn culls(&self, piece: &Piece) -> bool {
        piece.facing == Facing::Back
            && match self {
                BackCull::None => false,
                BackCull::All => true,
                BackCull::AwayFrom(w) => !w.touches(&piece.rect),
                BackCull::Pieces {
                    proven,
                    first_face,
                    windows,
                } => proven[(piece.face.0 - first_face) as usize] && !windows.touches(&piece.rect),
            }
    }
}

/// The screen rectangles of the caps that are not strictly back-facing, padded for the
/// rounding of the projection, binned in a uniform grid.
#[derive(Debug, Clone)]
pub(crate) struct CapWindows {
    /// Union of the windows.
    frame: Rect,
    /// The grid's cells over the frame.
    grid: Cells,
    /// Window rectangles.
    rects: Vec<Rect>,
    /// Windows by cell, row-major.
    cells: Vec<Vec<u32>>,
}

impl CapWindows {
    /// The windows of `caps` (prototype coordinates) placed by `leaf` in `camera`'s view;
    /// None when a cap corner is behind the near plane (perspective) or not finite: then the
    /// eye may be inside the capped solid's hull and nothing is culled.
    pub(crate) fn new(caps: &[[P3; 3]], leaf: &Leaf, camera: &Camera) -> Option<CapWindows> {
        let mirrors = leaf.mirrors();
        let persp = camera.projection == Projection::Perspective;
        let mut rects = Vec::new();
        for t in caps {
            let mut w = t.map(|p| leaf.transform.transform_point(&p));
            if mirrors {
                w.swap(1, 2);
            }
            let h = w.map(|p| camera.clip_coords(&p));
            if persp && h.iter().any(|h| h[3] < camera.near || h[3].is_nan()) {
                return None;
            }
            let s = h.map(|h| {
                if persp {
                    [h[0] / h[3], h[1] / h[3]]
                } else {
                    [h[0], h[1]]
                }
            });
            if s.iter().flatten().any(|c| !c.is_finite()) {
                return None;
            }
            let rect = Rect::of_points(s.iter());
            let size = rect.longer_side();
            let mag = s.iter().flatten().fold(0.0f64, |m, c| m.max(c.abs()));
            if strictly_back(&s, size, mag, &w, camera.eye) {
                continue;
            }
            rects.push(rect.padded(1e-12 * (mag + size)));
        }
        Some(CapWindows::binned(rects))
    }

    /// The grid over `rects`.
    fn binned(rects: Vec<Rect>) -> CapWindows {
        let frame = rects.iter().fold(Rect::EMPTY, |f, r| f.union(r));
        let grid = Cells::square(&frame, per_side(rects.len() as f64, 64));
        let mut w = CapWindows {
            frame,
            grid,
            rects,
            cells: vec![Vec::new(); grid.len()],
        };
        for (k, r) in w.rects.iter().enumerate() {
            let ((x0, y0), (x1, y1)) = w.span(r);
            for y in y0..=y1 {
                for x in x0..=x1 {
                    w.cells[y * grid.nx + x].push(k as u32);
                }
            }
        }
        w
    }

    /// The cells a rectangle covers, least and greatest (clamped to the grid; the cell of a
    /// point is monotone in its coordinates, so two rectangles sharing a point share a cell).
    fn span(&self, r: &Rect) -> ((usize, usize), (usize, usize)) {
        (
            self.grid.coords([r.xmin, r.ymin]),
            self.grid.coords([r.xmax, r.ymax]),
        )
    }

    /// True when `r` touches some window (closed test).
    pub(crate) fn touches(&self, r: &Rect) -> bool {
        if !self.frame.overlaps_closed(r) {
            return false;
        }
        let ((x0, y0), (x1, y1)) = self.span(r);
        (y0..=y1).any(|y| {
            (x0..=x1).any(|x| {
                self.cells[y * self.grid.nx + x]
                    .iter()
                    .any(|&k| self.rects[k as usize].overlaps_closed(r))
            })
        })
    }

    #[cfg(test)]
    /// Number of windows.
    pub(crate) fn len(&self) -> usize {
        self.rects.len()
    }
}

/// True when a cap triangle is strictly back-facing beyond doubt: clockwise in projection by
/// more than the projection's rounding could turn (a relative bound, generous), and not
/// containing the eye in its plane.
fn strictly_back(s: &[[f64; 2]; 3], size: f64, mag: f64, world: &[P3; 3], eye: Option<P3>) -> bool {
    let turn = orient2d(s[0], s[1], s[2]);
    let bound = 64.0 * f64::EPSILON * (mag + size) * size;
    turn < -bound && eye.is_none_or(|e| orient3d(&world[0], &world[1], &world[2], &e) != 0.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn grid_finds_every_touching_window() {
        // Windows on a diagonal; queries anywhere: the grid agrees with a plain scan.
        let rects: Vec<Rect> = (0..50)
            .map(|i| {
                let x = i as f64 * 0.37;
                Rect::new(x, x * 0.5, x + 0.3, x * 0.5 + 0.2)
            })
            .collect();
        let w = CapWindows::binned(rects.clone());
        assert_eq!(w.len(), 50);
        let mut rng = crate::geom::rng::XorShift::new(3);
        for _ in 0..2000 {
            let (x, y) = (rng.unit() * 20.0 - 1.0, rng.unit() * 10.0 - 1.0);
            let q = Rect::new(x, y, x + rng.unit() * 0.5, y + rng.unit() * 0.5);
            let plain = rects.iter().any(|r| r.overlaps_closed(&q));
            assert_eq!(w.touches(&q), plain, "{q:?}");
        }
        // Touching at a corner counts.
        assert!(w.touches(&Rect::new(0.3, 0.2, 0.31, 0.25)));
        assert!(!CapWindows::binned(Vec::new()).touches(&q0()));
    }

    fn q0() -> Rect {
        Rect::new(0.0, 0.0, 1.0, 1.0)
    }
}
