//! Section views: the scene cut once, before the view, by planes that each remove the side
//! their normal points to.
//!
//! Why here, before the view and on the scene: every later stage (cull, screen pieces, view
//! tree, visibility, the line drawing's edges and intersection curves, the exact checker)
//! then sees one consistent, cut geometry, and no stage learns about sections beyond a few
//! flags. What the cut keeps of the global face order:
//!
//! - A leaf with no vertex strictly on a removed side is kept as it is (its instance, INBOX,
//!   object tree and proven solidity included): a point on a plane stays.
//! - A leaf with such a vertex is rebuilt in world coordinates: each face clipped against each
//!   plane (sides decided exactly, every new corner the exact crossing of an edge rounded
//!   once: [`crate::geom::plane_cut`]); a face left with no area keeps its place in the face
//!   order with no pieces ([`SectionInfo::removed`]), so surviving faces keep their ids and a
//!   section JSON diffs cleanly against the uncut one. Its INBOX, object tree and proven
//!   solidity are dropped (back faces are not culled on a cut leaf: nothing would prove the
//!   cut surface closed by its section face exactly, rounded crossings and all).
//! - A group keeps its INBOX only when it is in world coordinates and all eight corners lie
//!   on the kept side of every plane, decided exactly; a cut instance loses its own.
//! - A closed solid that is cut (topologically closed, or closed by the prepare stage's caps,
//!   whose triangles are cut too) gets section faces: the edges of its cut surface (faces,
//!   caps and earlier planes' section faces) left unpaired on the plane, chained into loops
//!   and reversed, counter-clockwise seen from the normal; a loop turning the other way is a
//!   hole of the smallest outer loop around it, and a region with holes is triangulated (a
//!   face has no holes). They are appended after all the scene's faces, in leaf order, in a
//!   top-level group `section` whose tree repeats the cut leaves' paths.
//! - An open mesh gets no section face: the drawing shows its cut edges on the section pen.

use std::collections::{HashMap, HashSet};
use std::sync::Arc;

use crate::error::{Error, Result};
use crate::geom::plane_cut::{crossing, side, CutPlane};
use crate::geom::{Box3, M4, MAX_COORD, P3, V3};
use crate::scene::section_info::SectionInfo;
use crate::scene::style::Style;
use crate::scene::{Content, Face, FaceIndices, Mesh, Object, Scene};

/// Checks the planes a render is asked to cut with: finite, within the coordinate limit,
/// normals not zero.
pub(crate) fn check_planes(planes: &[(P3, V3)]) -> Result<Vec<CutPlane>> {
    planes
        .iter()
        .enumerate()
        .map(|(k, (p, n))| {
            let bad = |why: &str| {
                Err(Error::Usage(format!(
                    "section {} ({},{},{},{},{},{}): {why}",
                    k + 1,
                    p.x,
                    p.y,
                    p.z,
                    n.x,
                    n.y,
                    n.z
                )))
            };
            if !p.iter().chain(n.iter()).all(|x| x.is_finite()) {
                return bad("a number is not finite");
            }
            if p.iter().chain(n.iter()).any(|x| x.abs() > MAX_COORD) {
                return bad("a number is beyond 1e12, the limit scene coordinates have");
            }
            if n.iter().all(|&x| x == 0.0) {
                return bad("the normal is zero");
            }
            Ok(CutPlane {
                point: *p,
                normal: *n,
            })
        })
        .collect()
}

/// `scene` cut by `planes` (checked by [`check_planes`]).
pub(crate) fn cut_scene(scene: &Scene, planes: &[CutPlane]) -> Scene {
    let mut c = Cutter {
        planes,
        face: 0,
        removed: Vec::new(),
        cut_leaves: Vec::new(),
        sections: Vec::new(),
        on_cut: vec![HashSet::new(); planes.len()],
    };
    let first_face = scene.face_count() as u32;
    let mut root = c.object(&scene.root, &M4::identity(), &mut Vec::new());
    root.name = scene.root.name.clone();
    let sections = std::mem::take(&mut c.sections);
    if !sections.is_empty() {
        let taken: Vec<&str> = root.subobjects().iter().map(|o| o.name.as_str()).collect();
        let mut name = "section".to_string();
        let mut k = 1;
        while taken.contains(&name.as_str()) {
            k += 1;
            name = format!("section-{k}");
        }
        let group = section_tree(&name, sections);
        root = match root.content {
            Content::Subobjects(mut subs) => {
                let inbox = root.inbox;
                subs.push(group);
                let mut g = Object::group(root.name, subs);
                g.inbox = inbox;
                g
            }
            _ => Object::group("", vec![root, group]),
        };
    }
    let mut out = scene.with_root(root);
    out.section = Some(Arc::new(SectionInfo {
        first_face,
        removed: c.removed,
        cut_leaves: c.cut_leaves,
        on_cut: c.on_cut,
    }));
    out
}

/// The group of section objects: one leaf per cut solid, under groups repeating its path.
fn section_tree(name: &str, mut leaves: Vec<(Vec<String>, Mesh)>) -> Object {
    let mut subs = Vec::new();
    let mut rest = leaves.drain(..).peekable();
    while let Some((mut path, mesh)) = rest.next() {
        if path.len() <= 1 {
            let leaf = path.pop().unwrap_or_else(|| "section".into());
            subs.push(Object::from_mesh(leaf, mesh));
            continue;
        }
        // The following leaves under the same first name go into one group (leaf order is
        // depth-first, so they are consecutive).
        let head = path.remove(0);
        let mut below = vec![(path, mesh)];
        while let Some((p, _)) = rest.peek() {
            if p.len() > 1 && p[0] == head {
                let (mut p, m) = rest.next().unwrap_or_default();
                p.remove(0);
                below.push((p, m));
            } else {
                break;
            }
        }
        subs.push(section_tree(&head, below));
    }
    Object::group(name, subs)
}

/// The walk that cuts the tree, in global face order.
struct Cutter<'p> {
    planes: &'p [CutPlane],
    /// The global id of the next face.
    face: u32,
    removed: Vec<u32>,
    cut_leaves: Vec<std::ops::Range<u32>>,
    /// Section faces of each cut solid: its path and a mesh of them.
    sections: Vec<(Vec<String>, Mesh)>,
    /// By plane, the points on it in cut leaves: corners on it and crossings made.
    on_cut: Vec<HashSet<[u64; 3]>>,
}

impl Cutter<'_> {
    /// `obj`, living in the frame `xf` maps to world, as an object of a world-frame parent.
    fn object(&mut self, obj: &Object, xf: &M4, path: &mut Vec<String>) -> Object {
        if !self.touches(obj, xf) {
            self.face += obj.face_count() as u32;
            if *xf == M4::identity() {
                return obj.clone();
            }
            return Object::instance(obj.name.clone(), Arc::new(obj.clone()), *xf);
        }
        let mut out = self.content(&obj.name, &obj.content, xf, path);
        out.style = chain(obj.style, out.style);
        out.inbox = obj
            .inbox
            .filter(|b| *xf == M4::identity() && self.box_kept(b));
        out
    }

    /// An object named `name` of `content` living in the frame `xf`, in world coordinates.
    fn content(
        &mut self,
        name: &str,
        content: &Content,
        xf: &M4,
        path: &mut Vec<String>,
    ) -> Object {
        match content {
            Content::Mesh(m) => Object::from_mesh(name, self.leaf(m, xf, path)),
            Content::Subobjects(subs) => {
                let subs = subs
                    .iter()
                    .map(|s| {
                        path.push(s.name.clone());
                        let o = self.object(s, xf, path);
                        path.pop();
                        o
                    })
                    .collect();
                Object::group(name, subs)
            }
            Content::Instance(i) => {
                let mut o = self.content(name, &i.prototype.content, &(xf * i.transform), path);
                o.style = chain(i.prototype.style, o.style);
                o
            }
        }
    }

    /// True when some vertex below `obj` may lie strictly on a removed side (a box test
    /// first, with a wide margin for the rounding of placed points; then every vertex).
    fn touches(&self, obj: &Object, xf: &M4) -> bool {
        if obj.cbox.is_empty() || obj.face_count() == 0 {
            return false;
        }
        let corners: Vec<P3> = obj
            .cbox
            .corners()
            .iter()
            .map(|c| xf.transform_point(c))
            .collect();
        let far = |pl: &CutPlane| {
            let scale = corners
                .iter()
                .map(|c| c.coords.abs().max())
                .fold(pl.point.coords.abs().max(), f64::max)
                * pl.normal.abs().max();
            corners
                .iter()
                .all(|c| (c - pl.point).dot(&pl.normal) < -1e-9 * scale.max(1e-300))
        };
        if self.planes.iter().all(far) {
            return false;
        }
        let mut any = false;
        obj.for_each_mesh(xf, &mut |_, mesh, m| {
            any = any
                || mesh.vertices.iter().any(|v| {
                    let w = m.transform_point(v);
                    self.planes.iter().any(|pl| side(&w, pl).is_gt())
                });
        });
        any
    }

    /// True when every corner of `b` (world coordinates) is on the kept side of every plane.
    fn box_kept(&self, b: &Box3) -> bool {
        b.corners()
            .iter()
            .all(|c| self.planes.iter().all(|pl| !side(c, pl).is_gt()))
    }

    /// The mesh of a cut leaf in world coordinates; records its removed faces, its range and
    /// its section faces.
    fn leaf(&mut self, m: &Mesh, xf: &M4, path: &[String]) -> Mesh {
        let first = self.face;
        self.face += m.faces.len() as u32;
        self.cut_leaves.push(first..self.face);
        let mirrors = xf.fixed_view::<3, 3>(0, 0).determinant() < 0.0;
        let world: Vec<P3> = m.vertices.iter().map(|v| xf.transform_point(v)).collect();
        let ring = |idx: &mut dyn Iterator<Item = P3>| {
            let mut r: Vec<P3> = idx.collect();
            if mirrors {
                r.reverse();
            }
            r
        };
        let mut faces: Vec<Vec<P3>> = m
            .faces
            .iter()
            .map(|f| ring(&mut f.vertices.iter().map(|&k| world[k as usize])))
            .collect();
        let closed = m.closed || m.capped();
        let mut caps: Vec<Vec<P3>> = if m.capped() {
            m.caps
                .iter()
                .map(|t| ring(&mut t.iter().map(|p| xf.transform_point(p))))
                .collect()
        } else {
            Vec::new()
        };
        let mut secs: Vec<Vec<P3>> = Vec::new();
        for (pk, pl) in self.planes.iter().enumerate() {
            let hit = |r: &Vec<P3>| r.iter().any(|p| side(p, pl).is_gt());
            if !faces.iter().chain(&caps).chain(&secs).any(hit) {
                continue;
            }
            let mut on = HashSet::new();
            for r in faces
                .iter_mut()
                .chain(caps.iter_mut())
                .chain(secs.iter_mut())
            {
                *r = clip(r, pl, &mut on);
            }
            if closed {
                let loops = open_loops(faces.iter().chain(&caps).chain(&secs), &on);
                secs.extend(section_faces(loops, pl));
            }
            self.on_cut[pk].extend(on);
            secs.retain(|r| r.len() >= 3);
        }
        // The mesh: vertices once each (by exact coordinates), faces in their places.
        let mut verts = VertexSet::default();
        let mut out_faces = Vec::with_capacity(m.faces.len());
        for (k, (f, r)) in m.faces.iter().zip(&faces).enumerate() {
            if r.len() >= 3 {
                let idx: FaceIndices = r.iter().map(|p| verts.index(p)).collect();
                let same = idx.len() == f.vertices.len() && {
                    let orig = ring(&mut f.vertices.iter().map(|&k| world[k as usize]));
                    orig.iter().zip(r).all(|(a, b)| a == b)
                };
                out_faces.push(Face {
                    vertices: idx,
                    texture: if same { f.texture.clone() } else { None },
                });
            } else {
                // Wholly removed: its place kept, its corners as they were, never projected.
                self.removed.push(first + k as u32);
                let orig = ring(&mut f.vertices.iter().map(|&k| world[k as usize]));
                out_faces.push(Face::new(
                    orig.iter().map(|p| verts.index(p)).collect::<FaceIndices>(),
                ));
            }
        }
        if !secs.is_empty() {
            let mut sv = VertexSet::default();
            let sf = secs
                .iter()
                .map(|r| Face::new(r.iter().map(|p| sv.index(p)).collect::<FaceIndices>()))
                .collect();
            let mesh = Mesh {
                vertices: sv.points,
                faces: sf,
                ..Mesh::default()
            };
            self.sections.push((path.to_vec(), mesh));
        }
        Mesh {
            vertices: verts.points,
            faces: out_faces,
            ..Mesh::default()
        }
    }
}

/// An outer style then an inner one (the inner's fields win).
fn chain(outer: Option<Style>, inner: Option<Style>) -> Option<Style> {
    match (outer, inner) {
        (Some(o), Some(i)) => Some(o.then(&i)),
        (o, i) => i.or(o),
    }
}

/// Points numbered once each by their exact coordinates (−0 and +0 alike).
#[derive(Default)]
struct VertexSet {
    points: Vec<P3>,
    at: HashMap<[u64; 3], u32>,
}

impl VertexSet {
    fn index(&mut self, p: &P3) -> u32 {
        let n = self.points.len() as u32;
        let k = *self.at.entry(key(p)).or_insert(n);
        if k == n {
            self.points.push(*p);
        }
        k
    }
}

/// A point's exact coordinates as a hash key (−0 as +0).
pub(crate) fn key(p: &P3) -> [u64; 3] {
    [
        (p.x + 0.0).to_bits(),
        (p.y + 0.0).to_bits(),
        (p.z + 0.0).to_bits(),
    ]
}

/// `ring` clipped to the kept side of `pl` (Sutherland–Hodgman with exact sides): points on
/// the plane stay, each edge that crosses gets its exact crossing rounded once. Empty when
/// nothing with area is left.
///
/// The points on the plane (corners on it, crossings made) are added to `on`.
fn clip(ring: &[P3], pl: &CutPlane, on: &mut HashSet<[u64; 3]>) -> Vec<P3> {
    let s: Vec<i8> = ring.iter().map(|p| side(p, pl) as i8).collect();
    for (p, _) in ring.iter().zip(&s).filter(|(_, &x)| x == 0) {
        on.insert(key(p));
    }
    if s.iter().all(|&x| x <= 0) {
        return ring.to_vec();
    }
    if s.iter().all(|&x| x >= 0) {
        return Vec::new();
    }
    let n = ring.len();
    let mut out: Vec<P3> = Vec::with_capacity(n + 2);
    for i in 0..n {
        let j = (i + 1) % n;
        if s[i] <= 0 {
            out.push(ring[i]);
        }
        if s[i] * s[j] < 0 {
            let x = crossing(&ring[i], &ring[j], pl);
            on.insert(key(&x));
            out.push(x);
        }
    }
    out.dedup();
    while out.len() > 1 && out.first() == out.last() {
        out.pop();
    }
    if out.len() < 3 {
        out.clear();
    }
    out
}

/// The edges of `rings` (one closed, consistently oriented surface) that no other edge pairs
/// the other way, with both ends on the plane (in `on`: corners on it, crossings made by the
/// cut, which are rounded and so not exactly on it), chained into closed loops (in ring
/// direction). A chain that does not close is dropped.
fn open_loops<'a>(
    rings: impl Iterator<Item = &'a Vec<P3>>,
    on: &HashSet<[u64; 3]>,
) -> Vec<Vec<P3>> {
    // Net count of each undirected edge, + for least-key-first traversals.
    let mut net: HashMap<EdgeKey, (i32, P3, P3)> = HashMap::new();
    let mut order: Vec<EdgeKey> = Vec::new();
    for r in rings {
        for i in 0..r.len() {
            let (a, b) = (r[i], r[(i + 1) % r.len()]);
            let (ka, kb) = (key(&a), key(&b));
            if ka == kb {
                continue;
            }
            let (k, d, lo, hi) = if ka < kb {
                ((ka, kb), 1, a, b)
            } else {
                ((kb, ka), -1, b, a)
            };
            let e = net.entry(k).or_insert_with(|| {
                order.push(k);
                (0, lo, hi)
            });
            e.0 += d;
        }
    }
    // The unpaired directed edges on the plane, in order of first appearance.
    let mut edges: Vec<(P3, P3)> = Vec::new();
    for k in &order {
        let (c, lo, hi) = net[k];
        if c == 0 || !on.contains(&k.0) || !on.contains(&k.1) {
            continue;
        }
        let (a, b) = if c > 0 { (lo, hi) } else { (hi, lo) };
        for _ in 0..c.unsigned_abs() {
            edges.push((a, b));
        }
    }
    let mut from: HashMap<[u64; 3], Vec<usize>> = HashMap::new();
    for (i, (a, _)) in edges.iter().enumerate() {
        from.entry(key(a)).or_default().push(i);
    }
    let mut used = vec![false; edges.len()];
    let mut loops = Vec::new();
    for s in 0..edges.len() {
        if used[s] {
            continue;
        }
        used[s] = true;
        let start = key(&edges[s].0);
        let mut ring = vec![edges[s].0];
        let mut at = edges[s].1;
        let mut closed = false;
        for _ in 0..edges.len() {
            if key(&at) == start {
                closed = true;
                break;
            }
            ring.push(at);
            let next = from
                .get(&key(&at))
                .and_then(|v| v.iter().copied().find(|&i| !used[i]));
            let Some(i) = next else { break };
            used[i] = true;
            at = edges[i].1;
        }
        if closed && ring.len() >= 3 {
            loops.push(ring);
        }
    }
    loops
}

/// An undirected edge by its ends' exact coordinates, least first.
type EdgeKey = ([u64; 3], [u64; 3]);

/// An outer loop of a section: its points, in plane coordinates, its area and its holes.
struct Outer {
    ring: Vec<P3>,
    flat: Vec<[f64; 2]>,
    area: f64,
    holes: Vec<Vec<P3>>,
}

/// A basis (u, w) of the plane with (u, w, n) right-handed.
fn plane_basis(n: &V3) -> (V3, V3) {
    let n = n.normalize();
    let axis = if n.x.abs() <= n.y.abs() && n.x.abs() <= n.z.abs() {
        V3::x()
    } else if n.y.abs() <= n.z.abs() {
        V3::y()
    } else {
        V3::z()
    };
    let u = n.cross(&axis).normalize();
    (u, n.cross(&u))
}

/// Signed area of a 2D ring (positive counter-clockwise).
fn area2(r: &[[f64; 2]]) -> f64 {
    let n = r.len();
    (0..n)
        .map(|i| {
            let (a, b) = (r[i], r[(i + 1) % n]);
            a[0] * b[1] - a[1] * b[0]
        })
        .sum::<f64>()
        / 2.0
}

/// True when `p` is inside the 2D ring `r` (even-odd).
fn inside(p: [f64; 2], r: &[[f64; 2]]) -> bool {
    let mut c = false;
    let n = r.len();
    for i in 0..n {
        let (a, b) = (r[i], r[(i + 1) % n]);
        if (a[1] > p[1]) != (b[1] > p[1]) {
            let x = a[0] + (p[1] - a[1]) / (b[1] - a[1]) * (b[0] - a[0]);
            if p[0] < x {
                c = !c;
            }
        }
    }
    c
}

/// The section faces of the loops of one plane: each loop reversed (so counter-clockwise
/// seen from the normal for an outer boundary); holes go to the smallest outer loop around
/// them; an outer loop with holes is triangulated.
fn section_faces(loops: Vec<Vec<P3>>, pl: &CutPlane) -> Vec<Vec<P3>> {
    let (u, w) = plane_basis(&pl.normal);
    let flat = |r: &[P3]| -> Vec<[f64; 2]> {
        r.iter()
            .map(|p| {
                let d = p - pl.point;
                [d.dot(&u), d.dot(&w)]
            })
            .collect()
    };
    let mut outers: Vec<Outer> = Vec::new();
    let mut holes: Vec<(Vec<P3>, Vec<[f64; 2]>)> = Vec::new();
    for mut l in loops {
        l.reverse();
        let f = flat(&l);
        let a = area2(&f);
        if a > 0.0 {
            outers.push(Outer {
                ring: l,
                flat: f,
                area: a,
                holes: Vec::new(),
            });
        } else if a < 0.0 {
            holes.push((l, f));
        }
    }
    for (h, f) in holes {
        let around = outers
            .iter()
            .enumerate()
            .filter(|(_, o)| inside(f[0], &o.flat))
            .min_by(|a, b| a.1.area.total_cmp(&b.1.area))
            .map(|(k, _)| k);
        if let Some(k) = around {
            outers[k].holes.push(h);
        }
    }
    let mut out = Vec::new();
    for Outer {
        ring: outer,
        holes: hs,
        ..
    } in outers
    {
        if hs.is_empty() {
            out.push(outer);
            continue;
        }
        let mut pts = outer.clone();
        let mut starts = Vec::new();
        for h in &hs {
            starts.push(pts.len() as u32);
            pts.extend(h.iter().copied());
        }
        let f = flat(&pts);
        let mut idx: Vec<u32> = Vec::new();
        earcut::Earcut::new().earcut(f.iter().copied(), &starts, &mut idx);
        for t in idx.chunks_exact(3) {
            let tri: Vec<[f64; 2]> = t.iter().map(|&i| f[i as usize]).collect();
            let a = area2(&tri);
            if a == 0.0 {
                continue;
            }
            let mut r: Vec<P3> = t.iter().map(|&i| pts[i as usize]).collect();
            if a < 0.0 {
                r.reverse();
            }
            out.push(r);
        }
    }
    out
}
