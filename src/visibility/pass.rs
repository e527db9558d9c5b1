//! The whole-scene pass: every face's VTP, in parallel over faces. Subtrees the view stage
//! culled (HIDDEN by inboxes) have no pieces, so the pass never touches their faces.

use std::sync::{Arc, Mutex};

use rayon::prelude::*;

use crate::count::Count;
use crate::geom::boolean;
use crate::geom::poly2::{
    canonicalize, multipolygon_area, ring_area, start_at_least, MultiPolygon,
};
use crate::geom::ring_check::{repair, ring_defect};
use crate::geom::Rect;
use crate::scene::FaceId;
use crate::view::{Facing, PieceId, ScreenFaces, View};

use super::result::{whole_region, Solved, Visibility};
use super::stats::Counters;
use super::visfac::{visfac, Scratch, Vtp};

/// Options of the pass.
#[derive(Debug, Clone, Copy)]
pub(crate) struct PassOptions {
    /// Use INBOXes (VISFAC2's complete-hide test and hidden-subtree pruning).
    pub use_inbox: bool,
}

impl Default for PassOptions {
    fn default() -> Self {
        PassOptions { use_inbox: true }
    }
}

/// Below this many pieces the pass runs on the calling thread.
const SEQUENTIAL_BELOW: usize = 64;

/// Most pieces one task of the pass solves in a row. Rayon splits a range only so many
/// times unless a thread steals, so a thread may be left with a quarter of the pieces in
/// one run that no other thread can take a part of: where the work per piece varies (a
/// mesh's far side behind its near one), the others then wait. Nefertiti on two threads
/// showed the visibility stage 1-44% serial from run to run, and in tasks of 1,024 pieces
/// still 8-11% in most runs: its costliest faces lie together (pieces 22,173-22,269 take
/// 1-13 ms each, one task of 1,024 about 80 ms). In tasks of this size the last one holds
/// the others up for about as long as its costliest piece. (One thread has no one to wait:
/// its tasks stay as long as rayon makes them, each a worker's buffers the fewer.)
const MOST_PIECES_A_TASK: usize = 128;

/// Computes every face's VTP against the whole scene.
///
/// Each of the `view.screen.pieces.len()` pieces goes to `done` as it is finished (one
/// add per piece: a piece is a whole visibility solve; the result is the same).
pub(crate) fn solve(view: &View, opts: PassOptions, done: Count) -> Visibility {
    let mut counters = Counters {
        subtrees_tested: view.culled.tested,
        subtrees_hidden: view.culled.subtrees,
        faces_in_hidden_subtrees: view.culled.faces,
        ..Counters::default()
    };
    let view_used: std::borrow::Cow<View> = if opts.use_inbox {
        std::borrow::Cow::Borrowed(view)
    } else {
        std::borrow::Cow::Owned(without_inboxes(view))
    };
    let root = view_used.tree.root();
    let sf = &view.screen;
    // Only projected leaves have pieces: the pass's work is theirs alone. A few pieces are
    // solved on this thread: waking the pool would cost more than the work. Each worker
    // sums its counters and adds them in when it is done (sums of integers: the same
    // totals in any order), so no counters are kept per piece.
    let total = Mutex::new(Counters::default());
    let solve = |w: &mut Worker, f| {
        let r = solve_face(&view_used, root, f, &mut w.scratch, &mut w.counters);
        done.add(1);
        r
    };
    let results: Vec<Solved> = if sf.pieces.len() < SEQUENTIAL_BELOW {
        let mut w = Worker::new(&total);
        sf.piece_ids().map(|p| solve(&mut w, p)).collect()
    } else {
        (0..sf.pieces.len() as u32)
            .into_par_iter()
            .with_max_len(if rayon::current_num_threads() > 1 {
                MOST_PIECES_A_TASK
            } else {
                usize::MAX
            })
            .map_init(|| Worker::new(&total), |w, p| solve(w, PieceId(p)))
            .collect()
    };
    counters += total.into_inner().unwrap_or_else(|e| e.into_inner());
    let ids: Vec<FaceId> = sf
        .leaves
        .iter()
        .flat_map(|l| FaceId::each(&l.faces()))
        .collect();
    let faces = by_face(results, &ids, sf);
    Visibility::new(ids, faces, Arc::clone(&view.screen), counters)
}

/// A worker of the pass: its buffers, and the counters of the pieces it solved, added to
/// `into` when it is dropped.
struct Worker<'a> {
    scratch: Scratch,
    counters: Counters,
    into: &'a Mutex<Counters>,
}

impl<'a> Worker<'a> {
    fn new(into: &'a Mutex<Counters>) -> Self {
        Worker {
            scratch: Scratch::default(),
            counters: Counters::default(),
            into,
        }
    }
}

impl Drop for Worker<'_> {
    fn drop(&mut self) {
        let mut total = self.into.lock().unwrap_or_else(|e| e.into_inner());
        *total += self.counters;
    }
}

/// The pieces' results (in piece order) as one result per face of `ids`: moved where a
/// face is one piece (the usual case: then the whole vector is kept as it is), merged where
/// it has several.
fn by_face(mut results: Vec<Solved>, ids: &[FaceId], sf: &ScreenFaces) -> Vec<Solved> {
    let span = |id: &FaceId| sf.piece_span(*id..id.offset(1));
    if ids.len() == results.len() && ids.iter().all(|id| span(id).len() == 1) {
        return results;
    }
    // Each face's pieces as a slice of their own, split off in order.
    let mut rest: &mut [Solved] = &mut results;
    let mut at = 0;
    let mut slices = Vec::with_capacity(ids.len());
    for id in ids {
        let r = span(id);
        let (skip, tail) = std::mem::take(&mut rest).split_at_mut(r.start - at);
        debug_assert!(skip.is_empty(), "pieces in face order");
        let (mine, tail) = tail.split_at_mut(r.len());
        slices.push((mine, r.clone()));
        rest = tail;
        at = r.end;
    }
    let merge = |(pieces, r): (&mut [Solved], std::ops::Range<usize>)| merge_pieces(pieces, sf, r);
    if ids.len() < SEQUENTIAL_BELOW {
        slices.into_iter().map(merge).collect()
    } else {
        slices.into_par_iter().map(merge).collect()
    }
}

/// One face's visibility from its pieces' (a planar face is one piece; the pieces of a warped
/// face have disjoint interiors, so their union is exact and their areas add). The pieces'
/// regions are taken, not copied; a whole piece's is made from its ring.
fn merge_pieces(pieces: &mut [Solved], sf: &ScreenFaces, r: std::ops::Range<usize>) -> Solved {
    if let [one] = pieces {
        return std::mem::replace(one, Solved::HIDDEN);
    }
    let projected_area = pieces.iter().map(|p| p.projected_area).sum();
    let mut parts: Vec<MultiPolygon> = pieces
        .iter_mut()
        .zip(r.clone())
        .filter(|(p, _)| p.whole || !p.visible.is_empty())
        .map(|(p, k)| match p.whole {
            true => whole_region(sf, PieceId(k as u32)),
            false => std::mem::take(&mut p.visible),
        })
        .collect();
    let visible = match parts.len() {
        0 => Vec::new(),
        1 => parts.pop().unwrap_or_default(),
        _ => {
            // The parts come out of earlier boolean calls on their own grids: a point may sit
            // an ulp outside its piece's rectangle, so take the rectangle of the parts
            // themselves too, padded.
            let rect = sf.pieces[r]
                .iter()
                .fold(Rect::EMPTY, |acc, p| acc.union(&p.rect))
                .union(&Rect::of_points(parts.iter().flatten().flatten().flatten()));
            let rect = rect.padded(1e-9 * rect.longer_side());
            boolean::union(parts.iter().flatten().flatten(), &rect)
        }
    };
    new_result(visible, projected_area)
}

/// The result for a visible region: rings the rounding from the integer grid spoiled
/// repaired ([`repair`]), canonicalised, with its area measured.
fn new_result(mut visible: MultiPolygon, projected_area: f64) -> Solved {
    repair(&mut visible);
    canonicalize(&mut visible);
    let area = multipolygon_area(&visible);
    Solved {
        visible,
        area,
        projected_area,
        whole: false,
    }
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
    f: PieceId,
    scratch: &mut Scratch,
    c: &mut Counters,
) -> Solved {
    let sf = view.screen.piece(f);
    let projected_area = if matches!(sf.facing, Facing::Front | Facing::Back) {
        ccw_area(view, f)
    } else {
        0.0
    };
    let empty = Solved::empty;
    match sf.facing {
        Facing::EdgeOn | Facing::Clipped => {
            c.faces_edge_on += 1;
            return empty(projected_area);
        }
        _ if sf.culled => {
            c.faces_culled += 1;
            return empty(projected_area);
        }
        _ => {}
    }
    let ring = view.screen.ring_ccw(f);
    let visible = match visfac(view, root, f, scratch, c) {
        // The region is the ring, made again when read ([`whole_region`]): only its area
        // is kept, measured from the canonical start (the region's area to the bit: one
        // ring's sums add nothing to it).
        Vtp::Whole if ring_defect(&ring, true).is_none() => {
            let mut ring = ring;
            start_at_least(&mut ring);
            return Solved {
                area: ring_area(&ring),
                visible: Vec::new(),
                projected_area,
                whole: true,
            };
        }
        // A face ring that is not simple (a non-convex face cut by a section plane into
        // parts joined by zero-width bridges, a face written through a vertex twice): its
        // region, the points it winds round, as simple rings.
        Vtp::Whole => {
            let rect = Rect::of_points(ring.iter());
            boolean::union([&ring], &rect.padded(1e-9 * rect.longer_side()))
        }
        Vtp::Empty => Vec::new(),
        Vtp::Part(m) => m,
    };
    new_result(visible, projected_area)
}

/// `ring_area(ring_ccw(f))` without building the ring (same arithmetic, same bits).
fn ccw_area(view: &View, f: PieceId) -> f64 {
    let pts = view.screen.pts(f);
    let n = pts.len();
    if n < 3 {
        return 0.0;
    }
    let back = view.screen.piece(f).facing == Facing::Back;
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
