//! VISOBJ: what object A does to object B (VISIBLE, HIDDEN or MIXED), from VISFAC on B's faces.

use crate::scene::FaceId;
use crate::view::{Facing, View};

use super::stats::Counters;
use super::visfac::{visfac, Scratch, Verdict, Vtp};

/// VISOBJ(A, B) for the objects at `a` (a node) and with faces `b_faces` (a global id range).
/// Faces of B seen edge-on show nothing and are left out; with no face left, VISIBLE.
pub(crate) fn visobj(view: &View, a: u32, b_faces: std::ops::Range<FaceId>) -> Verdict {
    let mut scratch = Scratch::default();
    let mut stats = Counters::default();
    let (mut any_visible, mut any_hidden, mut any_mixed) = (false, false, false);
    for f in view.screen.pieces_in(b_faces) {
        if !matches!(view.screen.piece(f).facing, Facing::Front | Facing::Back) {
            continue;
        }
        match visfac(view, a, f, &mut scratch, &mut stats) {
            Vtp::Whole => any_visible = true,
            Vtp::Empty => any_hidden = true,
            Vtp::Part(_) => any_mixed = true,
        }
    }
    match (any_visible, any_hidden, any_mixed) {
        (_, _, true) | (true, true, _) => Verdict::Mixed,
        (false, true, false) => Verdict::Hidden,
        _ => Verdict::Visible,
    }
}
