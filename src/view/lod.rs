//! Level-of-detail substitution ("model no more than a scene needs"): every object whose
//! projected size is under a number of pixels is replaced by its tribox, or by the union of
//! its hierarchical triboxes at the shallowest cut whose error is under a pixel tolerance —
//! the paper's ideographs. The substitute is an ordinary leaf object: it takes part in
//! visibility like any other.
//!
//! Pixels are those of the picture: the drawing's screen bounds (here the projection of every
//! vertex) framed with its margin, `size` pixels along the longer side ([`Frame`]). An object's projected size is the longer
//! side of the screen rectangle of its vertices.
//!
//! A mesh with an object tree (paper 002) is drawn as the triboxes of a cut through its
//! components where they are tighter than its one tribox (a cow's legs apart from its body).
//!
//! An object is replaced only when its substitute has fewer faces than it (a box stays a
//! box). Triboxes are taken in the frame of the object's parent (the frame of its CBOX), merged up
//! the tree for groups; an instance gets its prototype's tribox transformed (conservative,
//! computed once per prototype).

use std::collections::HashMap;
use std::sync::Arc;

use crate::geom::{PolyMesh, Rect, M4};
use crate::scene::cleanup::{cleanup, Origin};
use crate::scene::{Content, Mesh, Object, Scene};
use crate::tribox::{Hierarchy, HierarchyOptions, Tribox};

use super::camera::Camera;
use super::frame::Frame;

/// What to substitute.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LodOptions {
    /// Objects whose projected size is under this many pixels are substituted.
    pub px: f64,
    /// The picture's size in pixels along its longer side.
    pub size: u32,
    /// If set, leaf meshes are drawn as hierarchical triboxes at the shallowest cut whose
    /// error is at most this many pixels (otherwise as one tribox).
    pub error_px: Option<f64>,
    /// Subdivision parameters for `error_px`.
    pub hierarchy: HierarchyOptions,
    /// Outward simplification of each tribox, in pixels (faces thinner vanish).
    pub simplify_px: f64,
}

impl LodOptions {
    /// Substitute objects under `px` pixels of a `size`-pixel picture by single triboxes.
    pub fn new(px: f64, size: u32) -> Self {
        LodOptions {
            px,
            size,
            error_px: None,
            hierarchy: HierarchyOptions::default(),
            simplify_px: 0.25,
        }
    }
}

/// What a substitution did.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct LodStats {
    /// Objects replaced (a replaced group counts once).
    pub objects_replaced: usize,
    /// Triboxes drawn in their place.
    pub triboxes: usize,
    /// Faces of the original scene (instances expanded).
    pub faces_in_scene: usize,
    /// Faces of the scene as substituted: what the view and visibility stages model.
    pub faces_modelled: usize,
    /// Pixels per screen unit of the picture.
    pub px_per_unit: f64,
}

/// The scene with every object under `opts.px` pixels replaced by its tribox substitute.
pub(crate) fn substitute(scene: &Scene, camera: &Camera, opts: &LodOptions) -> (Scene, LodStats) {
    let ppu = scene_pixels_per_unit(scene, camera, opts.size);
    let mut s = Substituter {
        camera,
        opts,
        ppu,
        protos: HashMap::new(),
        stats: LodStats {
            faces_in_scene: scene.face_count(),
            px_per_unit: ppu,
            ..LodStats::default()
        },
    };
    let root = match &scene.root.content {
        // The root's children are the scene's objects; the root itself is never replaced.
        Content::Subobjects(subs) => {
            let subs = subs
                .iter()
                .map(|o| s.object(o, &M4::identity()).0)
                .collect();
            let mut root = Object::group(scene.root.name.clone(), subs);
            root.inbox = scene.root.inbox;
            root
        }
        _ => s.object(&scene.root, &M4::identity()).0,
    };
    let mut out = Scene {
        root,
        camera: scene.camera.clone(),
        camera_at: scene.camera_at.clone(),
        source: scene.source.clone(),
        section: None,
        sections: scene.sections.clone(),
        styles: scene.styles.clone(),
    };
    out.root.cbox = scene.root.cbox.union(&out.root.cbox);
    s.stats.faces_modelled = out.face_count();
    (out, s.stats)
}

/// Pixels per screen unit for the whole scene's projection.
pub(crate) fn scene_pixels_per_unit(scene: &Scene, camera: &Camera, size: u32) -> f64 {
    let mut pts = Vec::new();
    for leaf in scene.leaves() {
        for v in &leaf.mesh.vertices {
            let w = leaf.transform.transform_point(v);
            if camera.in_front(&w) {
                let s = camera.project(&w);
                pts.push([s[0], s[1]]);
            }
        }
    }
    Frame::of(camera, Rect::of_points(pts.iter())).pixels_per_unit(size)
}

struct Substituter<'a> {
    camera: &'a Camera,
    opts: &'a LodOptions,
    ppu: f64,
    /// Triboxes of prototypes, by address.
    protos: HashMap<usize, Tribox>,
    stats: LodStats,
}

impl Substituter<'_> {
    /// `obj` (in the frame that `xf` takes to the world), substituted where small; the flag
    /// tells whether anything below changed (shared prototypes stay shared otherwise).
    fn object(&mut self, obj: &Object, xf: &M4) -> (Object, bool) {
        let size = self.projected_size(obj, xf);
        if size < self.opts.px {
            if let Some(sub) = self.replacement(obj, xf) {
                return (sub, true);
            }
        }
        match &obj.content {
            Content::Mesh(_) => (obj.clone(), false),
            Content::Subobjects(subs) => {
                let (subs, changed): (Vec<Object>, Vec<bool>) =
                    subs.iter().map(|o| self.object(o, xf)).unzip();
                if !changed.contains(&true) {
                    return (obj.clone(), false);
                }
                let mut g = Object::group(obj.name.clone(), subs);
                g.inbox = obj.inbox;
                (g, true)
            }
            Content::Instance(i) => {
                let (proto, changed) = self.object(&i.prototype, &(xf * i.transform));
                if !changed {
                    return (obj.clone(), false);
                }
                let mut o = Object::instance(obj.name.clone(), Arc::new(proto), i.transform);
                o.inbox = obj.inbox;
                (o, true)
            }
        }
    }

    /// Longer side of the object's screen rectangle in pixels (infinite when some vertex is
    /// behind a perspective camera's near plane).
    fn projected_size(&self, obj: &Object, xf: &M4) -> f64 {
        let mut pts = Vec::new();
        let mut behind = false;
        obj.for_each_mesh(xf, &mut |_, mesh, m| {
            for v in &mesh.vertices {
                let w = m.transform_point(v);
                if self.camera.in_front(&w) {
                    let s = self.camera.project(&w);
                    pts.push([s[0], s[1]]);
                } else {
                    behind = true;
                }
            }
        });
        if behind {
            return f64::INFINITY;
        }
        let b = Rect::of_points(pts.iter());
        if b.is_empty() {
            return 0.0;
        }
        b.longer_side() * self.ppu
    }

    /// The substitute leaf of `obj`, in its parent's frame (None when it has no vertices).
    fn replacement(&mut self, obj: &Object, xf: &M4) -> Option<Object> {
        let scale = stretch(xf) * self.ppu; // pixels per unit of the parent frame
        let simplify = self.opts.simplify_px / scale;
        let (poly, triboxes) = match (&obj.content, self.opts.error_px) {
            (Content::Mesh(m), Some(e)) => {
                let h = Hierarchy::build(m, &self.opts.hierarchy);
                let cut = h.cut_within(e / scale);
                (h.cut_mesh(&cut, simplify), cut.len())
            }
            _ => {
                let t = self.tribox(obj);
                if t.is_empty() {
                    return None;
                }
                match component_triboxes(obj, &t) {
                    Some(parts) => {
                        let n = parts.len();
                        let meshes: Vec<PolyMesh> = parts
                            .iter()
                            .map(|p| p.simplified(simplify).boundary().mesh())
                            .collect();
                        (concat(&meshes), n)
                    }
                    None => (t.simplified(simplify).boundary().mesh(), 1),
                }
            }
        };
        let mesh = clean(&poly)?;
        if mesh.faces.len() >= obj.face_count() {
            return None; // the substitute would model more than the object (a box stays a box)
        }
        self.stats.objects_replaced += 1;
        self.stats.triboxes += triboxes;
        Some(Object::from_mesh(obj.name.clone(), mesh))
    }

    /// The tribox of an object in its parent's frame: merged up the tree, transformed for
    /// instances (each prototype's computed once).
    fn tribox(&mut self, obj: &Object) -> Tribox {
        match &obj.content {
            Content::Mesh(m) => Tribox::from_points(m.vertices.iter()),
            Content::Subobjects(subs) => subs
                .iter()
                .fold(Tribox::empty(), |t, s| t.merge(&self.tribox(s))),
            Content::Instance(i) => {
                let key = Arc::as_ptr(&i.prototype) as usize;
                let proto = match self.protos.get(&key) {
                    Some(t) => *t,
                    None => {
                        let t = self.tribox(&i.prototype);
                        self.protos.insert(key, t);
                        t
                    }
                };
                proto.transformed(&i.transform)
            }
        }
    }
}

/// Most triboxes in a component-aware substitute.
pub(crate) const MAX_COMPONENT_TRIBOXES: usize = 8;
/// A component-aware substitute is used when its triboxes' volumes add up to at most this
/// share of the single tribox's volume.
pub(crate) const COMPONENT_GAIN: f64 = 0.8;

/// Component-aware substitute of a mesh with an object tree (paper 002): the triboxes of a
/// cut through the upper BV-tree (the components and their merges), grown from the root by
/// splitting the node of largest tribox volume, at most [`MAX_COMPONENT_TRIBOXES`]; the cut
/// whose volumes add up least is kept when it is tighter than the single tribox `whole`
/// (at most [`COMPONENT_GAIN`] of its volume). Together the cut's triboxes hold every face.
fn component_triboxes(obj: &Object, whole: &Tribox) -> Option<Vec<Tribox>> {
    let (Content::Mesh(m), Some(t)) = (&obj.content, obj.tree.as_deref()) else {
        return None;
    };
    let tribox = |n: u32| {
        let mut b = Tribox::empty();
        for &f in t.faces_of(n) {
            for &v in &m.faces[f as usize].vertices {
                b.add_point(&m.vertices[v as usize]);
            }
        }
        b
    };
    let volume = |b: &Tribox| b.boundary().volume();
    let whole_volume = volume(whole);
    let mut cut: Vec<(u32, Tribox, f64)> = vec![(0, *whole, whole_volume)];
    let mut best: Option<(f64, Vec<Tribox>)> = None;
    while cut.len() < MAX_COMPONENT_TRIBOXES {
        let Some(k) = (0..cut.len())
            .filter(|&k| {
                t.nodes[cut[k].0 as usize]
                    .children
                    .is_some_and(|c| c.iter().all(|&ch| t.nodes[ch as usize].component))
            })
            .max_by(|&a, &b| cut[a].2.total_cmp(&cut[b].2).then(b.cmp(&a)))
        else {
            break;
        };
        let [l, r] = t.nodes[cut[k].0 as usize].children.unwrap_or([0, 0]);
        cut.swap_remove(k);
        for ch in [l, r] {
            let b = tribox(ch);
            cut.push((ch, b, volume(&b)));
        }
        let total: f64 = cut.iter().map(|c| c.2).sum();
        if best.as_ref().is_none_or(|(v, _)| total < *v) {
            best = Some((total, cut.iter().map(|c| c.1).collect()));
        }
    }
    let (total, parts) = best?;
    (total <= COMPONENT_GAIN * whole_volume).then_some(parts)
}

/// The meshes side by side in one polygon mesh.
fn concat(meshes: &[PolyMesh]) -> PolyMesh {
    let mut out = PolyMesh::new(Vec::new(), Vec::new());
    for m in meshes {
        out.append(m);
    }
    out
}

/// Largest stretch of the linear part of `m` (the largest column length: exact for
/// similarity transforms, an estimate otherwise).
fn stretch(m: &M4) -> f64 {
    (0..3)
        .map(|c| m.fixed_view::<3, 1>(0, c).norm())
        .fold(0.0, f64::max)
        .max(f64::MIN_POSITIVE)
}

/// A substitute polygon mesh through the scene's own cleanup (exact duplicate vertices
/// merged, degenerate faces dropped); None when nothing is left.
fn clean(poly: &PolyMesh) -> Option<Mesh> {
    if poly.faces.is_empty() {
        return None;
    }
    let origin = Origin {
        file: std::path::Path::new("tribox"),
        face_pos: &[],
    };
    let m = cleanup(poly, &origin, &mut Vec::new(), crate::count::Count::NONE).ok()?;
    (!m.faces.is_empty()).then_some(m)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::{P3, V3};
    use crate::primitives;

    fn solid(name: &str, raw: PolyMesh, scale: f64, at: V3) -> Object {
        let raw = PolyMesh::new(
            raw.vertices
                .iter()
                .map(|v| P3::from(v.coords * scale + at))
                .collect(),
            raw.faces,
        );
        Object::from_mesh(name, clean(&raw).unwrap())
    }

    #[test]
    fn small_objects_become_triboxes_and_big_ones_stay() {
        let ball = || primitives::by_name("truncated_icosahedron").unwrap();
        let root = Object::group(
            "",
            vec![
                solid("big", ball(), 10.0, V3::zeros()),
                solid("small", ball(), 0.05, V3::new(20., 0., 0.)),
            ],
        );
        let scene = Scene::new(root, "t".into());
        let cam = Camera::three_quarter();
        let (out, stats) = substitute(&scene, &cam, &LodOptions::new(40.0, 1000));
        assert_eq!(stats.objects_replaced, 1);
        assert_eq!(stats.faces_in_scene, 64);
        assert!(
            stats.faces_modelled < 64 && stats.faces_modelled > 32,
            "{stats:?}"
        );
        let subs = out.root.subobjects();
        assert_eq!(subs[0].face_count(), 32);
        assert!(subs[1].face_count() <= 18);
        assert_eq!(subs[1].name, "small");
        // The substitute holds the original.
        let t = Tribox::from_points(subs[1].vertices());
        for v in scene.root.subobjects()[1].vertices() {
            let mut tt = t;
            for k in 0..9 {
                tt.lo[k] -= 1e-12;
                tt.hi[k] += 1e-12;
            }
            assert!(tt.contains(v));
        }
    }

    #[test]
    fn nothing_changes_under_zero_pixels() {
        let root = Object::group(
            "",
            vec![solid(
                "a",
                primitives::by_name("cube").unwrap(),
                1.0,
                V3::zeros(),
            )],
        );
        let scene = Scene::new(root, "t".into());
        let (out, stats) = substitute(&scene, &Camera::three_quarter(), &LodOptions::new(0.0, 500));
        assert_eq!(stats.objects_replaced, 0);
        assert_eq!(out.face_count(), scene.face_count());
    }
}
