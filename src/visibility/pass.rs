//! The whole-scene pass: every face's VTP, in parallel over faces, with whole subtrees found
//! HIDDEN by inboxes skipped before any of their faces is touched.

use std::sync::atomic::{AtomicUsize, Ordering};

use rayon::prelude::*;

use crate::geom::poly2::{canonicalize, multipolygon_area, MultiPolygon};
use crate::view::{Facing, View};

use super::occlusion::{covers_convex, rects_overlap};
use super::stats::Counters;
use super::visfac::{visfac, Scratch, Vtp};

/// Options of the pass.
#[derive(Debug, Clone, Copy)]
pub struct PassOptions {
    /// Use INBOXes (VISFAC2's complete-hide test and hidden-subtree pruning).
    pub use_inbox: bool,
}

impl Default for PassOptions {
    fn default() -> Self {
        PassOptions { use_inbox: true }
    }
}

/// The visible part of one face.
#[derive(Debug, Clone, PartialEq)]
pub struct FaceVisibility {
    /// Visible region in screen space (canonical: rings start at their least point).
    pub visible: MultiPolygon,
    /// Its area.
    pub area: f64,
    /// The face's projected area (0 when edge-on or clipped).
    pub projected_area: f64,
}

impl FaceVisibility {
    /// The result for a visible region: canonicalised, with its area measured.
    fn new(mut visible: MultiPolygon, projected_area: f64) -> Self {
        canonicalize(&mut visible);
        let area = multipolygon_area(&visible);
        FaceVisibility {
            visible,
            area,
            projected_area,
        }
    }
}

/// The visible-polygon set of a view.
#[derive(Debug, Clone)]
pub struct Visibility {
    /// One entry per face, by global face id (a warped face's planar pieces merged).
    pub faces: Vec<FaceVisibility>,
    /// What the pass did.
    pub counters: Counters,
}

/// Computes every face's VTP against the whole scene.
pub fn solve(view: &View, opts: PassOptions) -> Visibility {
    solve_counted(view, opts, None)
}

/// [`solve`], adding 1 to `done` as each of the `view.screen.faces.len()` face pieces is
/// finished (for a progress bar; one relaxed atomic add per piece, the result is the same).
pub fn solve_counted(view: &View, opts: PassOptions, done: Option<&AtomicUsize>) -> Visibility {
    let mut counters = Counters::default();
    let hidden = if opts.use_inbox {
        hidden_subtrees(view, &mut counters)
    } else {
        vec![false; view.screen.faces.len()]
    };
    let view_used: std::borrow::Cow<View> = if opts.use_inbox {
        std::borrow::Cow::Borrowed(view)
    } else {
        std::borrow::Cow::Owned(without_inboxes(view))
    };
    let root = view_used.tree.root();
    let sf = &view.screen;
    let results: Vec<(FaceVisibility, Counters)> = (0..sf.faces.len())
        .into_par_iter()
        .map_init(Scratch::default, |scratch, f| {
            let r = solve_face(&view_used, root, f, hidden[f], scratch);
            if let Some(d) = done {
                d.fetch_add(1, Ordering::Relaxed);
            }
            r
        })
        .collect();
    for (_, c) in &results {
        counters += *c;
    }
    let faces = (0..sf.face_count() as u32)
        .into_par_iter()
        .map(|id| {
            let r = sf.piece_range(id..id + 1);
            merge_pieces(&results[r.start as usize..r.end as usize], sf, r)
        })
        .collect();
    Visibility { faces, counters }
}

/// One face's visibility from its pieces' (a planar face is one piece; the pieces of a warped
/// face have disjoint interiors, so their union is exact and their areas add).
fn merge_pieces(
    pieces: &[(FaceVisibility, Counters)],
    sf: &crate::view::ScreenFaces,
    r: std::ops::Range<u32>,
) -> FaceVisibility {
    if pieces.len() == 1 {
        return pieces[0].0.clone();
    }
    let projected_area = pieces.iter().map(|p| p.0.projected_area).sum();
    let parts: Vec<MultiPolygon> = pieces
        .iter()
        .filter(|p| !p.0.visible.is_empty())
        .map(|p| p.0.visible.clone())
        .collect();
    let visible = match parts.len() {
        0 => Vec::new(),
        1 => parts[0].clone(),
        _ => {
            let empty = crate::geom::poly2::EMPTY_RECT;
            let rect = r.fold(empty, |acc, p| {
                crate::view::tree::union_rect(&acc, &sf.faces[p as usize].rect)
            });
            super::clip::union(&parts, &rect)
        }
    };
    FaceVisibility::new(visible, projected_area)
}

fn without_inboxes(view: &View) -> View {
    let mut v = view.clone();
    for n in &mut v.tree.nodes {
        n.inbox = None;
    }
    v.tree.inboxes.clear();
    v
}

fn solve_face(
    view: &View,
    root: u32,
    f: usize,
    hidden: bool,
    scratch: &mut Scratch,
) -> (FaceVisibility, Counters) {
    let mut c = Counters::default();
    let sf = &view.screen.faces[f];
    let projected_area = if matches!(sf.facing, Facing::Front | Facing::Back) {
        ccw_area(view, f)
    } else {
        0.0
    };
    let empty = |area| FaceVisibility {
        visible: Vec::new(),
        area: 0.0,
        projected_area: area,
    };
    match sf.facing {
        Facing::EdgeOn | Facing::Clipped => {
            c.faces_edge_on += 1;
            return (empty(projected_area), c);
        }
        _ if sf.culled => {
            c.faces_culled += 1;
            return (empty(projected_area), c);
        }
        _ if hidden => {
            c.faces_in_hidden_subtrees += 1;
            return (empty(projected_area), c);
        }
        _ => {}
    }
    let ring = view.screen.ring_ccw(f);
    let visible = match visfac(view, root, f, scratch, &mut c) {
        Vtp::Whole => vec![vec![ring]],
        Vtp::Empty => Vec::new(),
        Vtp::Part(m) => m,
    };
    (FaceVisibility::new(visible, projected_area), c)
}

/// `ring_area(ring_ccw(f))` without building the ring (same arithmetic, same bits).
fn ccw_area(view: &View, f: usize) -> f64 {
    let pts = view.screen.pts(f);
    let n = pts.len();
    if n < 3 {
        return 0.0;
    }
    let back = view.screen.faces[f].facing == Facing::Back;
    let at = |i: usize| {
        let p = pts[if back { n - 1 - i } else { i }];
        [p[0], p[1]]
    };
    let o = at(0);
    let mut s = 0.0;
    for i in 1..n - 1 {
        let (a, b) = (at(i), at(i + 1));
        s += (a[0] - o[0]) * (b[1] - o[1]) - (b[0] - o[0]) * (a[1] - o[1]);
    }
    0.5 * s
}

/// Most inboxes tried per object (the largest first): pruning is optional, so a cap only
/// trades pruning for time, never correctness, and keeps the scan linear in the objects.
const MAX_INBOX_TESTS: usize = 64;

/// Marks the faces of every named object whose screen bounds lie behind and inside the
/// projected INBOX of another object: HIDDEN as a whole, without touching its faces.
fn hidden_subtrees(view: &View, counters: &mut Counters) -> Vec<bool> {
    let tree = &view.tree;
    let mut hidden = vec![false; view.screen.faces.len()];
    // Inboxes by decreasing rectangle area: one that covers a rectangle has at least its
    // area, so the scan stops at the first smaller one (same answers as a full scan).
    let area = |r: &[f64; 4]| (r[2] - r[0]).max(0.0) * (r[3] - r[1]).max(0.0);
    let mut order: Vec<(f64, usize)> = tree
        .inboxes
        .iter()
        .enumerate()
        .map(|(k, ib)| (area(&ib.rect), k))
        .collect();
    order.sort_by(|a, b| b.0.total_cmp(&a.0).then(a.1.cmp(&b.1)));
    for obj in &tree.objects {
        let pieces = view.screen.piece_range(obj.faces.clone());
        if pieces.is_empty() || hidden[pieces.start as usize] {
            continue;
        }
        let bounds = match subtree_bounds(view, pieces.clone()) {
            Some(b) => b,
            None => continue,
        };
        let corners = [
            [bounds.0[0], bounds.0[1]],
            [bounds.0[2], bounds.0[1]],
            [bounds.0[2], bounds.0[3]],
            [bounds.0[0], bounds.0[3]],
        ];
        let need = area(&bounds.0);
        let by = order
            .iter()
            .take_while(|(a, _)| *a >= need)
            .take(MAX_INBOX_TESTS)
            .find(|&&(_, k)| {
                let ib = &tree.inboxes[k];
                ib.node != obj.node
                    && bounds.1 < ib.zmin
                    && rects_overlap(&ib.rect, &bounds.0)
                    && covers_convex(&ib.hull, &corners)
            });
        if by.is_some() {
            counters.subtrees_hidden += 1;
            for f in pieces {
                hidden[f as usize] = true;
            }
        }
    }
    hidden
}

/// Screen rectangle and greatest depth of all drawable pieces in a range (None if none).
fn subtree_bounds(view: &View, faces: std::ops::Range<u32>) -> Option<([f64; 4], f64)> {
    let mut rect = crate::geom::poly2::EMPTY_RECT;
    let mut zmax = f64::NEG_INFINITY;
    for f in faces {
        let sf = &view.screen.faces[f as usize];
        if matches!(sf.facing, Facing::Front | Facing::Back) {
            rect = crate::view::tree::union_rect(&rect, &sf.rect);
            zmax = zmax.max(sf.zmax);
        }
    }
    (zmax > f64::NEG_INFINITY).then_some((rect, zmax))
}
