//! The whole-scene pass: every face's VTP, in parallel over faces. Subtrees the view stage
//! culled (HIDDEN by inboxes) have no pieces, so the pass never touches their faces.

use std::sync::atomic::{AtomicUsize, Ordering};

use rayon::prelude::*;

use crate::geom::poly2::{canonicalize, multipolygon_area, MultiPolygon};
use crate::view::{Facing, View};

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

/// Nothing visible: the VTP of a face in a hidden subtree.
static HIDDEN: FaceVisibility = FaceVisibility {
    visible: Vec::new(),
    area: 0.0,
    projected_area: 0.0,
};

/// The visible-polygon set of a view: the faces the pass solved (a warped face's planar
/// pieces merged), by ascending global id; faces of culled subtrees are absent (empty).
#[derive(Debug, Clone)]
pub struct Visibility {
    ids: Vec<u32>,
    faces: Vec<FaceVisibility>,
    face_count: usize,
    /// What the pass did.
    pub counters: Counters,
}

impl Visibility {
    /// Face `id`'s visibility; empty (with no projected area) for a face of a culled subtree.
    pub fn face(&self, id: usize) -> &FaceVisibility {
        if self.ids.len() == self.face_count {
            return self.faces.get(id).unwrap_or(&HIDDEN);
        }
        match self.ids.binary_search(&(id as u32)) {
            Ok(k) => &self.faces[k],
            Err(_) => &HIDDEN,
        }
    }

    /// The solved faces with their global ids, ascending.
    pub fn iter(&self) -> impl Iterator<Item = (usize, &FaceVisibility)> + '_ {
        self.ids.iter().map(|&i| i as usize).zip(self.faces.iter())
    }

    /// Every face's visibility by global id, solved or not.
    pub fn by_id(&self) -> Vec<&FaceVisibility> {
        (0..self.face_count).map(|id| self.face(id)).collect()
    }

    /// Number of faces in the scene (solved or not).
    pub fn face_count(&self) -> usize {
        self.face_count
    }

    /// Number of faces the pass solved.
    pub fn solved_count(&self) -> usize {
        self.faces.len()
    }

    /// Total visible area.
    pub fn total_area(&self) -> f64 {
        self.faces.iter().map(|f| f.area).sum()
    }
}

/// Below this many pieces the pass runs on the calling thread.
const SEQUENTIAL_BELOW: usize = 64;

/// Computes every face's VTP against the whole scene.
pub fn solve(view: &View, opts: PassOptions) -> Visibility {
    solve_counted(view, opts, None)
}

/// [`solve`], adding 1 to `done` as each of the `view.screen.faces.len()` face pieces is
/// finished (for a progress bar; one relaxed atomic add per piece, the result is the same).
pub fn solve_counted(view: &View, opts: PassOptions, done: Option<&AtomicUsize>) -> Visibility {
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
    // solved on this thread: waking the pool would cost more than the work.
    let solve = |scratch: &mut Scratch, f| {
        let r = solve_face(&view_used, root, f, scratch);
        if let Some(d) = done {
            d.fetch_add(1, Ordering::Relaxed);
        }
        r
    };
    let results: Vec<(FaceVisibility, Counters)> = if sf.faces.len() < SEQUENTIAL_BELOW {
        let mut scratch = Scratch::default();
        (0..sf.faces.len())
            .map(|f| solve(&mut scratch, f))
            .collect()
    } else {
        (0..sf.faces.len())
            .into_par_iter()
            .map_init(Scratch::default, solve)
            .collect()
    };
    for (_, c) in &results {
        counters += *c;
    }
    let ids: Vec<u32> = sf
        .leaves
        .iter()
        .flat_map(|l| l.first_face..l.first_face + l.face_count)
        .collect();
    let merge = |&id: &u32| {
        let r = sf.piece_range(id..id + 1);
        merge_pieces(&results[r.start as usize..r.end as usize], sf, r)
    };
    let faces = if ids.len() < SEQUENTIAL_BELOW {
        ids.iter().map(merge).collect()
    } else {
        ids.par_iter().map(merge).collect()
    };
    Visibility {
        ids,
        faces,
        face_count: sf.face_count(),
        counters,
    }
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
