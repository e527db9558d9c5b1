//! VISP: is a point visible from the standard viewpoint, or hidden by an object?

use crate::geom::poly2::Pt2;
use crate::geom::{orient3d_refs, winding, Rect, P3};
use crate::scene::FaceId;
use crate::view::tree::NodeKind;
use crate::view::{PieceId, View};

use crate::geom::hull2::covers_convex;

/// The paper's VISP answer.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PointVisibility {
    /// Nothing in the object hides the point.
    Visible,
    /// Some face (or inbox) of the object is in front of the point.
    Hidden,
}

/// VISP(A, P): whether world point `p` is hidden by the subtree at node `a`. A face hides P
/// when P is strictly behind its plane and P's projection is strictly inside the face's.
/// `on_face` names the face (global id) P lies on, so that coplanar faces earlier in global order hide it
/// (DESIGN's coplanar rule). A point behind the near plane of a perspective camera is HIDDEN.
pub(crate) fn visp(view: &View, a: u32, p: &P3, on_face: Option<FaceId>) -> PointVisibility {
    if !view.camera.in_front(p) {
        return PointVisibility::Hidden;
    }
    let s = view.camera.project(p);
    let q: Pt2 = [s[0], s[1]];
    let tree = &view.tree;
    let mut stack = vec![a];
    while let Some(n) = stack.pop() {
        let node = &tree.nodes[n as usize];
        // 1. Not hidden by CBOX: the point is outside its outline, or in front of all of it.
        if !node.rect.contains_rect(&Rect::new(q[0], q[1], q[0], q[1])) || node.zmax < s[2] {
            continue;
        }
        // 2. Hidden by INBOX.
        if let Some(ib) = node.inbox {
            let ib = &tree.inboxes[ib as usize];
            if s[2] < ib.zmin && covers_convex(&ib.hull, &[q]) {
                return PointVisibility::Hidden;
            }
        }
        match &node.kind {
            NodeKind::Inner(r) => stack.extend(&tree.children[r.start as usize..r.end as usize]),
            NodeKind::Leaf(r) => {
                // 3. Hidden by a face.
                if tree.pieces[r.start as usize..r.end as usize]
                    .iter()
                    .any(|&g| face_hides(view, g, p, q, on_face))
                {
                    return PointVisibility::Hidden;
                }
            }
        }
    }
    PointVisibility::Visible
}

/// True when piece `g` hides world point `p` (screen point `q`).
pub(crate) fn face_hides(view: &View, g: PieceId, p: &P3, q: Pt2, on_face: Option<FaceId>) -> bool {
    let sf = &view.screen;
    let piece = sf.piece(g);
    // A face never hides itself (nor do the planar pieces of a warped face hide each other).
    if on_face == Some(piece.face) || !piece.rect.contains_strictly(q) {
        return false;
    }
    let side = orient3d_refs(&sf.plane_refs(g), p) * sf.front_sign(g);
    let in_front_of_p = side < 0.0 || (side == 0.0 && on_face.is_some_and(|f| piece.face < f));
    if !in_front_of_p {
        return false;
    }
    let ring: Vec<Pt2> = sf.pts(g).iter().map(|v| [v[0], v[1]]).collect();
    matches!(winding(&ring, q), Some(w) if w != 0)
}
