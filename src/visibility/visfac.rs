//! VISFAC and VISFAC2: the visibility texture polygon (VTP) of one face against an object.
//!
//! VTP(F) starts as F. The object's tree is walked front to back: a subtree whose CBOX
//! cannot hide F is skipped; a subtree whose INBOX hides all of F empties the VTP at once;
//! at the leaves each face's occluding region is collected, a single face covering all of F
//! empties the VTP at once, regions that together cover F (shown exactly from their
//! boundary, [`super::cover`]) empty it without clipping, and otherwise the regions are
//! subtracted from F in one batched boolean call.

use crate::geom::boolean::subtract;
use crate::geom::hull2::covers_convex;
use crate::geom::poly2::{MultiPolygon, Pt2, Ring};
use crate::geom::{Corners, Rect};
use crate::view::ring_index::INDEXED_ABOVE;
use crate::view::tree::{BoundProbe, NodeKind, ScreenInbox};
use crate::view::{Facing, PieceId, View};

use super::cover::{regions_cover, CoverScratch};
use super::occlusion::{occluder_region, separated_convex, Occlusion, Target};
use super::stats::Counters;

/// The paper's VISFAC answer: what an object does to a face.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Verdict {
    /// The object hides none of the face.
    Visible,
    /// The object hides all of the face.
    Hidden,
    /// The object hides part of the face.
    Mixed,
}

/// A face's visibility texture polygon, in screen space.
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum Vtp {
    /// Nothing hides the face: the VTP is the face itself.
    Whole,
    /// Nothing of the face is visible.
    Empty,
    /// The visible part: a multipolygon strictly smaller than the face.
    Part(MultiPolygon),
}

/// Reusable buffers of one worker.
#[derive(Debug, Default)]
pub(crate) struct Scratch {
    stack: Vec<u32>,
    /// Occluder regions with the piece each came from.
    occluders: Vec<(PieceId, Ring)>,
    /// Buffers of the cover test.
    cover: CoverScratch,
    /// The regions in piece order, for the boolean call.
    clips: Vec<Ring>,
    sides: Vec<f64>,
    ring: Ring,
    /// A long occluder cut to F's rectangle: its corners' offsets in the piece, then the
    /// indices of their points in the screen faces' tables.
    cut: Vec<u32>,
    cut_at: Vec<u32>,
}

/// Outcome of the walk.
enum Walk {
    /// Keep going.
    Open,
    /// The VTP became empty.
    Emptied,
}

/// True when the INBOX (a solid box inside its object) hides all of F: F lies entirely
/// behind the box's farthest corner, and inside its projected outline.
pub(crate) fn inbox_hides(ib: &ScreenInbox, rect: &Rect, zmax: f64, ring: &[Pt2]) -> bool {
    zmax < ib.zmin && ib.rect.contains_rect(rect) && covers_convex(&ib.hull, ring)
}

/// VISFAC(A, F): the VTP of piece `f` against the subtree at node `a` (the whole scene when
/// `a` is the root). `f` must be able to show something (not edge-on, clipped or culled).
pub(crate) fn visfac(
    view: &View,
    a: u32,
    f: PieceId,
    scratch: &mut Scratch,
    stats: &mut Counters,
) -> Vtp {
    let target = Target::new(&view.screen, f);
    scratch.occluders.clear();
    stats.faces_walked += 1;
    if let Walk::Emptied = visfac2(view, a, &target, scratch, stats) {
        return Vtp::Empty;
    }
    if scratch.occluders.is_empty() {
        stats.faces_whole += 1;
        return Vtp::Whole;
    }
    let regions = scratch.occluders.iter().map(|(_, r)| r.as_slice());
    if regions_cover(regions, &target.ring, &mut scratch.cover) {
        stats.emptied_by_patch += 1;
        return Vtp::Empty;
    }
    // The walk's order depends on the tree; the boolean call gets the occluders in piece
    // order, so the result is the same bytes whatever tree found them. Each is cut to F's
    // rectangle only now (most faces never get here); a region with no area inside it
    // hides nothing of F (nor did it take part in the cover test: it has no seed and no
    // edge across F).
    scratch.occluders.sort_unstable_by_key(|(g, _)| *g);
    scratch.clips.clear();
    scratch.clips.extend(
        scratch
            .occluders
            .drain(..)
            .map(|(_, r)| target.rect.clip_ring(&r))
            .filter(|c| c.len() >= 3),
    );
    if scratch.clips.is_empty() {
        stats.faces_whole += 1;
        return Vtp::Whole;
    }
    stats.faces_clipped += 1;
    stats.occluders += scratch.clips.len() as u64;
    let rest = subtract(&target.ring, &target.rect, &scratch.clips);
    if rest.is_empty() {
        Vtp::Empty
    } else {
        Vtp::Part(rest)
    }
}

/// VISFAC2(A, F): walks A's tree, collecting occluder regions into `scratch.occluders`.
fn visfac2(view: &View, a: u32, t: &Target, scratch: &mut Scratch, stats: &mut Counters) -> Walk {
    let tree = &view.tree;
    let probe = BoundProbe::new(&t.rect, t.zmin);
    scratch.stack.clear();
    scratch.stack.push(a);
    while let Some(n) = scratch.stack.pop() {
        let node = &tree.nodes[n as usize];
        stats.nodes_visited += 1;
        if !node.rect.overlaps(&t.rect) || node.zmax < t.zmin {
            stats.skipped_by_cbox += 1;
            continue;
        }
        if let Some(ib) = node.inbox {
            if inbox_hides(&tree.inboxes[ib as usize], &t.rect, t.zmax, &t.ring) {
                stats.emptied_by_inbox += 1;
                return Walk::Emptied;
            }
        }
        match &node.kind {
            NodeKind::Inner(r) => {
                // Children are stored front to back; push in reverse so the front one pops first.
                scratch
                    .stack
                    .extend(tree.children[r.start as usize..r.end as usize].iter().rev());
            }
            NodeKind::Leaf(r) => {
                let range = r.start as usize..r.end as usize;
                for (&g, b) in tree.pieces[range.clone()]
                    .iter()
                    .zip(&tree.piece_bounds[range])
                {
                    if b.face == t.face || !b.may_meet(&probe) {
                        continue;
                    }
                    // The coarse bounds passed: the exact ones decide.
                    let pc = view.screen.piece(g);
                    if !pc.rect.overlaps(&t.rect) || pc.zmax < t.zmin {
                        continue;
                    }
                    if let Walk::Emptied = examine(view, g, t, scratch, stats) {
                        return Walk::Emptied;
                    }
                }
            }
        }
    }
    Walk::Open
}

/// One candidate occluder at a leaf (its bounds already overlap F's, in front of F's back).
fn examine(
    view: &View,
    g: PieceId,
    t: &Target,
    scratch: &mut Scratch,
    stats: &mut Counters,
) -> Walk {
    let sf = &view.screen;
    let sg = sf.piece(g);
    stats.faces_examined += 1;
    // A long ring is cut to what matters inside F's rectangle (the same region there).
    let (pts, world) = match sf.ring_index(g) {
        Some(index) => {
            index.cut(&t.rect, &mut scratch.cut);
            let all = sf.corners(g);
            scratch.cut_at.clear();
            scratch
                .cut_at
                .extend(scratch.cut.iter().map(|&i| all[i as usize]));
            (
                Corners::new(&scratch.cut_at, &sf.points),
                Corners::new(&scratch.cut_at, &sf.world),
            )
        }
        None => (sf.pts(g), sf.world_pts(g)),
    };
    // Convex regions (every triangle, every convex face cut by a plane) get exact quick tests;
    // separation of G's projection (cheaper than classifying its vertices) comes first,
    // unless F's ring is long (the test costs F's length; classifying costs G's).
    let convex = sg.convex;
    if convex && t.convex && t.ring.len() <= INDEXED_ABOVE {
        scratch.ring.clear();
        scratch.ring.extend(pts.iter().map(|p| [p[0], p[1]]));
        if sg.facing == Facing::Back {
            scratch.ring.reverse();
        }
        if separated_convex(&scratch.ring, &t.ring) {
            return Walk::Open;
        }
    }
    let Occlusion::Region(region) = occluder_region(sf, g, pts, world, t, &mut scratch.sides)
    else {
        return Walk::Open;
    };
    if convex && covers_convex(&region, &t.ring) {
        stats.emptied_by_face += 1;
        return Walk::Emptied;
    }
    scratch.occluders.push((g, region));
    Walk::Open
}
