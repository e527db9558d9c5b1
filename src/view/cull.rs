//! HIDDEN subtrees found from boxes alone, before any face is projected: an object whose
//! projected CBOX lies behind and inside the projected INBOX of another object (paper 001,
//! VISOBJ with inboxes), so the work that follows tracks the visible scene, not the whole.
//!
//! The walk goes down the object tree from the root. At each group it projects the INBOXes
//! of the children (the occluders of that level), then tests every child's CBOX against the
//! occluders of its own level and of every level above; a hidden child is recorded with its
//! face range and never entered. Faces of hidden subtrees are never projected and never take
//! part in the pass: their VTPs are empty, exactly as the full computation would find them.
//!
//! Why it is exact: an inbox lies inside the solid of its object; every point behind it along
//! a ray is behind that solid's front surface. A CBOX whose every corner projects inside the
//! inbox's screen hull, with every corner's screen depth below the least depth of the inbox's
//! corners, is therefore hidden everywhere. Projections of boxes
//! are convex, so testing corners is enough (perspective: only when every corner of both boxes
//! is in front of the near plane).

use crate::geom::hull2::{convex_hull, covers_convex};
use crate::geom::poly2::Pt2;
use crate::geom::{Box3, Rect, M4};
use crate::prepare::trees::bvtree::{HierarchyKind, ObjectTree};
use crate::scene::section_info::SectionInfo;
use crate::scene::{Content, FaceId, Leaf, Object, Scene};

use super::camera::{Camera, Projection};

/// Most occluders tried per level for one object (the largest first): pruning is optional,
/// so a cap only trades pruning for time, never correctness.
const MAX_TESTS_PER_LEVEL: usize = 64;

/// An object found HIDDEN as a whole, with its place in the global face order.
#[derive(Debug, Clone, Copy)]
pub(crate) struct HiddenObject<'a> {
    /// The object (a shared prototype's part appears once per placement, told apart by
    /// `first_face`).
    pub object: &'a Object,
    /// Its first face.
    pub first_face: FaceId,
    /// Its number of faces (instances expanded).
    pub face_count: u32,
}

/// The result of culling a scene for one camera.
#[derive(Debug, Clone, Default)]
pub(crate) struct Cull<'a> {
    /// The leaves outside every hidden subtree, in global face order.
    pub leaves: Vec<Leaf<'a>>,
    /// Hidden objects, in global face order (disjoint: a hidden object's parts are not listed).
    pub hidden: Vec<HiddenObject<'a>>,
    /// For each leaf in `leaves`, its faces (local indices, ascending) in components of its
    /// object tree found HIDDEN (paper 002's components as subobjects); empty when none.
    pub hidden_parts: Vec<Vec<u32>>,
    /// Components found HIDDEN.
    pub components_hidden: u64,
    /// Number of faces in the scene.
    pub face_count: u32,
    /// Objects whose CBOX was tested against occluders.
    pub objects_tested: u64,
    /// Faces a section cut removed whole, among `hidden_parts`.
    pub removed: u64,
}

impl<'a> Cull<'a> {
    /// No culling: every leaf of the scene.
    pub(crate) fn none(scene: &'a Scene) -> Cull<'a> {
        Cull {
            leaves: scene.leaves(),
            hidden: Vec::new(),
            hidden_parts: Vec::new(),
            components_hidden: 0,
            face_count: scene.face_count() as u32,
            objects_tested: 0,
            removed: 0,
        }
    }

    /// Culls `scene` for `camera` with the inboxes the prepare stage computed.
    pub(crate) fn new(scene: &'a Scene, camera: &Camera) -> Cull<'a> {
        let mut w = Walker {
            camera,
            levels: Vec::new(),
            path: Vec::new(),
            out: Cull::default(),
        };
        let n = w.object(&scene.root, &M4::identity(), 0);
        w.out.face_count = n;
        w.out
    }

    /// Faces in hidden subtrees and hidden components.
    pub(crate) fn hidden_faces(&self) -> u64 {
        self.hidden.iter().map(|h| h.face_count as u64).sum::<u64>()
            + self
                .hidden_parts
                .iter()
                .map(|p| p.len() as u64)
                .sum::<u64>()
            - self.removed
    }

    /// Also hides the faces a section cut removed whole (they keep their ids, get no
    /// pieces, and are not counted as culled).
    pub(crate) fn hide_removed(&mut self, info: &SectionInfo) {
        if info.removed.is_empty() {
            return;
        }
        self.hidden_parts.resize(self.leaves.len(), Vec::new());
        for (k, leaf) in self.leaves.iter().enumerate() {
            let first = leaf.first_face as u32;
            let faces = first..first + leaf.mesh.faces.len() as u32;
            let mut removed: Vec<u32> = info.removed_in(faces).collect();
            if removed.is_empty() {
                continue;
            }
            self.removed += removed.len() as u64;
            removed.extend_from_slice(&self.hidden_parts[k]);
            removed.sort_unstable();
            removed.dedup();
            self.hidden_parts[k] = removed;
        }
    }

    /// The hidden faces (local indices, ascending) of leaf `k`.
    pub(crate) fn hidden_in_leaf(&self, k: usize) -> &[u32] {
        self.hidden_parts.get(k).map_or(&[], Vec::as_slice)
    }
}

/// A projected INBOX: a convex screen hull in front of everything behind its least depth.
struct Occluder {
    hull: Vec<Pt2>,
    rect: Rect,
    area: f64,
    zmin: f64,
    /// Index of its object among the level's children.
    owner: usize,
}

/// A projected CBOX.
struct Projected {
    corners: [Pt2; 8],
    rect: Rect,
    zmin: f64,
    zmax: f64,
}

struct Walker<'a, 'c> {
    camera: &'c Camera,
    /// Occluders of every group on the path from the root, largest first in each.
    levels: Vec<Vec<Occluder>>,
    path: Vec<&'a str>,
    out: Cull<'a>,
}

impl<'a> Walker<'a, '_> {
    /// Visits `obj` placed by `xf` whose first face is `first`; returns its face count.
    fn object(&mut self, obj: &'a Object, xf: &M4, first: u32) -> u32 {
        match &obj.content {
            Content::Mesh(m) => {
                let hidden = match obj.tree.as_deref() {
                    Some(t) if t.kind == HierarchyKind::Simplify => self.components(t, xf),
                    _ => Vec::new(),
                };
                self.out.leaves.push(Leaf {
                    path: self.path.join("/"),
                    mesh: m,
                    transform: *xf,
                    first_face: first as usize,
                });
                self.out.hidden_parts.push(hidden);
                m.faces.len() as u32
            }
            Content::Instance(i) => self.object(&i.prototype, &(xf * i.transform), first),
            Content::Subobjects(subs) => self.group(subs, xf, first),
        }
    }

    fn group(&mut self, subs: &'a [Object], xf: &M4, first: u32) -> u32 {
        let mut level: Vec<Occluder> = subs
            .iter()
            .enumerate()
            .filter_map(|(k, s)| self.occluder(s, xf, k))
            .collect();
        level.sort_by(|a, b| b.area.total_cmp(&a.area).then(a.owner.cmp(&b.owner)));
        self.levels.push(level);
        let mut f = first;
        for (k, s) in subs.iter().enumerate() {
            self.path.push(&s.name);
            if self.is_hidden(s, xf, k) {
                let n = s.face_count() as u32;
                self.out.hidden.push(HiddenObject {
                    object: s,
                    first_face: FaceId(f),
                    face_count: n,
                });
                f += n;
            } else {
                f += self.object(s, xf, f);
            }
            self.path.pop();
        }
        self.levels.pop();
        f - first
    }

    /// The projected inbox of `s` (its own, or its prototype's placed), if it has one wholly
    /// in front of the near plane.
    fn occluder(&self, s: &Object, xf: &M4, owner: usize) -> Option<Occluder> {
        let (b, m) = match (&s.inbox, &s.content) {
            (Some(b), _) => (*b, *xf),
            (None, Content::Instance(i)) => (i.prototype.inbox?, xf * i.transform),
            _ => return None,
        };
        self.occluder_of(&b, &m, owner)
    }

    /// Box `b` placed by `m` as an occluder (None when it has no interior or a corner is not
    /// in front of the near plane).
    fn occluder_of(&self, b: &Box3, m: &M4, owner: usize) -> Option<Occluder> {
        if !b.has_interior() {
            return None;
        }
        let p = self.project(b, m)?;
        let hull = convex_hull(p.corners.to_vec());
        if hull.len() < 3 {
            return None;
        }
        let rect = Rect::of_points(hull.iter());
        Some(Occluder {
            area: rect.area(),
            hull,
            rect,
            zmin: p.zmin,
            owner,
        })
    }

    /// True when the CBOX of child `k` lies behind and inside an occluder of some level.
    fn is_hidden(&mut self, s: &Object, xf: &M4, k: usize) -> bool {
        self.box_hidden(&s.cbox, xf, Some(k))
    }

    /// True when box `b` placed by `xf` lies behind and inside an occluder of some level (not
    /// one of the innermost level's owned by `own`).
    fn box_hidden(&mut self, b: &Box3, xf: &M4, own: Option<usize>) -> bool {
        if b.is_empty() {
            return false;
        }
        let Some(p) = self.project(b, xf) else {
            return false;
        };
        self.out.objects_tested += 1;
        let need = p.rect.area();
        let innermost = self.levels.len().wrapping_sub(1);
        self.levels.iter().enumerate().any(|(li, level)| {
            level
                .iter()
                .take_while(|o| o.area >= need)
                .filter(|o| !(li == innermost && Some(o.owner) == own))
                .take(MAX_TESTS_PER_LEVEL)
                .any(|o| {
                    p.zmax < o.zmin
                        && o.rect.contains_rect(&p.rect)
                        && covers_convex(&o.hull, &p.corners)
                })
        })
    }

    /// The faces (local, ascending) of the components of a mesh's object tree whose CBOX is
    /// HIDDEN by an inbox: those of other objects on the path and the components' own (any
    /// box inside the closed solid hides what lies behind it, the solid's own faces too).
    /// Only the upper BV-tree (components and their merges) is tested.
    fn components(&mut self, t: &ObjectTree, xf: &M4) -> Vec<u32> {
        let mut own: Vec<Occluder> = t
            .nodes
            .iter()
            .filter_map(|n| n.inbox)
            .filter_map(|b| self.occluder_of(&b, xf, usize::MAX))
            .collect();
        own.sort_by(|a, b| b.area.total_cmp(&a.area));
        if own.is_empty() && self.levels.iter().all(Vec::is_empty) {
            return Vec::new();
        }
        self.levels.push(own);
        let mut hidden = Vec::new();
        let mut stack: Vec<u32> = t.nodes[0].children.map_or(Vec::new(), |c| c.to_vec());
        while let Some(n) = stack.pop() {
            let node = &t.nodes[n as usize];
            if !node.component {
                continue;
            }
            if self.box_hidden(&node.cbox, xf, None) {
                hidden.extend_from_slice(t.faces_of(n));
                self.out.components_hidden += 1;
            } else if let Some(c) = node.children {
                stack.extend(c);
            }
        }
        self.levels.pop();
        hidden.sort_unstable();
        hidden
    }

    /// The 8 corners of `b` placed by `m`, projected, with their bounds; None when a corner is
    /// not in front of the near plane (perspective).
    fn project(&self, b: &Box3, m: &M4) -> Option<Projected> {
        let cam = self.camera;
        let world = b.corners().map(|c| m.transform_point(&c));
        if cam.projection == Projection::Perspective && !world.iter().all(|c| cam.in_front(c)) {
            return None;
        }
        let s = world.map(|c| cam.project(&c));
        let corners = s.map(|q| [q[0], q[1]]);
        Some(Projected {
            rect: Rect::of_points(corners.iter()),
            zmin: s.iter().map(|q| q[2]).fold(f64::INFINITY, f64::min),
            zmax: s.iter().map(|q| q[2]).fold(f64::NEG_INFINITY, f64::max),
            corners,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::V3;
    use crate::scene::testing::warped_scene;
    use crate::view::{PieceId, View};

    #[test]
    fn a_box_behind_the_wall_is_hidden_and_later_faces_keep_their_ids() {
        let mut scene = warped_scene();
        crate::prepare::prepare(
            &mut scene,
            &crate::PrepareOptions::default(),
            &crate::Progress::default(),
        );
        let camera = Camera::orthographic(V3::new(0., 0., -1.), V3::y()).unwrap();
        let cull = Cull::new(&scene, &camera);
        assert_eq!(cull.hidden.len(), 1);
        let h = cull.hidden[0];
        assert_eq!(
            (h.object.name.as_str(), h.first_face, h.face_count),
            ("hidden", FaceId(7), 6)
        );
        assert_eq!(cull.leaves.len(), 3);
        assert_eq!(cull.face_count, 19);
        let view = View::from_cull(&scene, camera, &cull, &crate::Progress::default());
        let sf = &view.screen;
        // The hidden box's faces have no pieces; the faces after it keep their global ids
        // while their pieces close up (2 for the bent quad + 6 for the wall = 8 before them).
        assert_eq!(sf.face_count(), 19);
        assert!((7..13).all(|f| sf.pieces_of(FaceId(f)).count() == 0));
        assert_eq!(sf.pieces.len(), 14);
        for f in 13..19 {
            let p: Vec<PieceId> = sf.pieces_of(FaceId(f)).collect();
            assert_eq!(p, [PieceId(f - 5)]);
            assert_eq!(sf.piece(p[0]).face, FaceId(f));
            assert_eq!(sf.leaf_of_face(FaceId(f)).path, "beside");
        }
        let hidden = view.tree.object("hidden").unwrap();
        assert_eq!(hidden.faces, FaceId(7)..FaceId(13));
        assert!(
            matches!(&view.tree.nodes[hidden.node as usize].kind, super::super::tree::NodeKind::Leaf(r) if r.is_empty())
        );
        assert_eq!(
            view.tree.object("beside").unwrap().faces,
            FaceId(13)..FaceId(19)
        );
        assert_eq!(view.culled.faces, 6);
    }
}
