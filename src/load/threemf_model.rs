//! A 3MF model part (core specification) as the object tree: each build item an object, an
//! object's components its subobjects, an object placed twice or more a prototype with an
//! instance per placement, one placed once built in its final frame. Errors name the part and
//! the XML line and column.
//!
//! 3MF transforms are 12 numbers `m00 m01 m02 m10 m11 m12 m20 m21 m22 m30 m31 m32` applied to
//! row vectors: `[x y z 1]` times the 4×4 matrix whose rows are `m0* 0`, `m1* 0`, `m2* 0`,
//! `m3* 1`, so `x' = m00 x + m10 y + m20 z + m30`.

use std::collections::HashMap;
use std::path::Path;
use std::sync::Arc;

use roxmltree::{Document, Node};

use super::geometry::UniqueNames;
use super::mesh_file::coord_problem;
use super::transform::mirrors;
use crate::error::{Error, Location, Result, Warnings};
use crate::geom::{Box3, PolyMesh, M4, MAX_COORD, P3};
use crate::progress::{Phase, Progress, Stage};
use crate::scene::cleanup::{cleanup, Origin};
use crate::scene::names::printable;
use crate::scene::{Mesh, Object};

/// The 3MF core namespace.
const CORE: &str = "http://schemas.microsoft.com/3dmanufacturing/core/2015/02";

/// Extensions a model may require that change no geometry read here.
const HARMLESS: [&str; 2] = [
    "http://schemas.microsoft.com/3dmanufacturing/material/2015/02",
    "http://schemas.microsoft.com/3dmanufacturing/production/2015/06",
];

/// The production extension's namespace (its `path` attribute names another part).
const PRODUCTION: &str = "http://schemas.microsoft.com/3dmanufacturing/production/2015/06";

/// The deepest nesting of components followed.
const MAX_COMPONENT_DEPTH: usize = super::kdl::MAX_DEPTH;

/// Where errors go: the 3MF file, the part, and the XML's positions.
struct Ctx<'d> {
    file: &'d Path,
    part: &'d str,
    doc: &'d Document<'d>,
}

impl Ctx<'_> {
    /// An error at node `n`: `file: part:line:col: msg`.
    fn err(&self, n: Node, msg: impl std::fmt::Display) -> Error {
        let p = self.doc.text_pos_at(n.range().start);
        Error::invalid(
            Location::file(self.file),
            format!("{}:{}:{}: {msg}", self.part, p.row, p.col),
        )
    }

    /// The attribute `name` of `n`, required.
    fn attr<'a>(&self, n: Node<'a, '_>, name: &str) -> Result<&'a str> {
        n.attribute(name).ok_or_else(|| {
            self.err(
                n,
                format!("<{}> needs the attribute {name}", n.tag_name().name()),
            )
        })
    }

    /// The attribute `name` of `n` as a number.
    fn number(&self, n: Node, name: &str) -> Result<f64> {
        let s = self.attr(n, name)?;
        s.trim().parse::<f64>().map_err(|_| {
            self.err(
                n,
                format!("{name}=\"{}\" is not a number", printable(short(s))),
            )
        })
    }

    /// The attribute `name` of `n` as an index or id.
    fn index(&self, n: Node, name: &str) -> Result<u32> {
        let s = self.attr(n, name)?;
        s.trim().parse::<u32>().map_err(|_| {
            self.err(
                n,
                format!(
                    "{name}=\"{}\" is not a non-negative integer",
                    printable(short(s))
                ),
            )
        })
    }
}

/// At most 40 characters of `s`, for messages.
fn short(s: &str) -> &str {
    match s.char_indices().nth(40) {
        Some((i, _)) => &s[..i],
        None => s,
    }
}

/// True when `n` is the core element `name` (or the element in no namespace).
fn is(n: Node, name: &str) -> bool {
    n.is_element()
        && n.tag_name().name() == name
        && n.tag_name().namespace().is_none_or(|ns| ns == CORE)
}

/// The child elements of `n` that are the core element `name`.
fn kids<'a, 'i>(n: Node<'a, 'i>, name: &'a str) -> impl Iterator<Item = Node<'a, 'i>> + 'a {
    n.children().filter(move |c| is(*c, name))
}

/// One `<object>` of the resources.
struct Resource<'a, 'i> {
    node: Node<'a, 'i>,
    name: Option<&'a str>,
}

/// Reads the model part `part` (its XML `xml`) of the 3MF file `file` into the scene's root.
pub(super) fn read_model(
    file: &Path,
    part: &str,
    xml: &[u8],
    warnings: &mut Warnings,
    progress: &Progress,
) -> Result<Object> {
    let text = std::str::from_utf8(xml).map_err(|e| {
        Error::invalid(
            Location::file(file),
            format!("{part}: invalid UTF-8 at byte {}", e.valid_up_to()),
        )
    })?;
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    let doc = Document::parse(text).map_err(|e| {
        let p = e.pos();
        Error::parse(
            Location::file(file),
            format!("{part}:{}:{}: {e}", p.row, p.col),
        )
    })?;
    let cx = Ctx {
        file,
        part,
        doc: &doc,
    };
    let model = doc.root_element();
    if !is(model, "model") {
        return Err(cx.err(model, "the root element is not a 3MF <model>"));
    }
    check_required(&cx, model)?;
    let res = kids(model, "resources")
        .next()
        .ok_or_else(|| cx.err(model, "the model has no <resources>"))?;
    let mut objects: HashMap<u32, Resource> = HashMap::new();
    for o in kids(res, "object") {
        let id = cx.index(o, "id")?;
        let r = Resource {
            node: o,
            name: o.attribute("name"),
        };
        if objects.insert(id, r).is_some() {
            return Err(cx.err(o, format!("a second object with id {id}")));
        }
    }
    let build = kids(model, "build")
        .next()
        .ok_or_else(|| cx.err(model, "the model has no <build>"))?;
    let mut b = Builder {
        cx: &cx,
        objects: &objects,
        uses: HashMap::new(),
        protos: HashMap::new(),
        warnings,
        progress,
    };
    b.count_uses(build)?;
    let mut names = UniqueNames::default();
    let mut out = Vec::new();
    for item in kids(build, "item") {
        let xf = transform(&cx, item)?;
        if let Some(o) = b.place(item, &xf, &mut names)? {
            out.push(o);
        }
    }
    if out.is_empty() {
        return Err(cx.err(build, "the build has no item with triangles"));
    }
    Ok(Object::group("", out))
}

/// An error when the model requires an extension that changes its geometry.
fn check_required(cx: &Ctx, model: Node) -> Result<()> {
    let Some(req) = model.attribute("requiredextensions") else {
        return Ok(());
    };
    for prefix in req.split_whitespace() {
        let ns = model.lookup_namespace_uri(Some(prefix));
        if !ns.is_some_and(|ns| HARMLESS.contains(&ns)) {
            return Err(cx.err(
                model,
                format!(
                    "the model requires extension {} ({}), which kepler does not read",
                    printable(short(prefix)),
                    printable(ns.unwrap_or("an unknown namespace"))
                ),
            ));
        }
    }
    Ok(())
}

/// The 12-number `transform` attribute of `n` as a column-vector matrix (identity when absent).
fn transform(cx: &Ctx, n: Node) -> Result<M4> {
    let Some(s) = n.attribute("transform") else {
        return Ok(M4::identity());
    };
    let v: Vec<f64> = s
        .split_whitespace()
        .map(|w| w.parse::<f64>().ok().filter(|x| x.is_finite()))
        .collect::<Option<_>>()
        .filter(|v: &Vec<f64>| v.len() == 12)
        .ok_or_else(|| cx.err(n, "transform= needs 12 finite numbers"))?;
    // Row-vector convention: the matrix is the transpose of glTF's and nalgebra's.
    let m = M4::new(
        v[0], v[3], v[6], v[9], //
        v[1], v[4], v[7], v[10], //
        v[2], v[5], v[8], v[11], //
        0.0, 0.0, 0.0, 1.0,
    );
    let det = m.fixed_view::<3, 3>(0, 0).determinant();
    if !(det.is_finite() && det != 0.0) {
        return Err(cx.err(n, "the transform is singular: it flattens the geometry"));
    }
    Ok(m)
}

/// The state of building the objects.
struct Builder<'c, 'a, 'i> {
    cx: &'c Ctx<'c>,
    objects: &'c HashMap<u32, Resource<'a, 'i>>,
    /// How often each object is placed (by build items and components), all told.
    uses: HashMap<u32, usize>,
    /// Objects placed more than once, as prototypes.
    protos: HashMap<u32, Option<Arc<Object>>>,
    warnings: &'c mut Warnings,
    progress: &'c Progress,
}

impl<'a, 'i> Builder<'_, 'a, 'i> {
    /// The object `ref_node`'s `objectid` names.
    fn resource(&self, ref_node: Node) -> Result<(u32, &Resource<'a, 'i>)> {
        let id = self.cx.index(ref_node, "objectid")?;
        if let Some(p) = ref_node.attribute((PRODUCTION, "path")) {
            if !p.eq_ignore_ascii_case(self.cx.part) {
                return Err(self.cx.err(
                    ref_node,
                    format!(
                        "the object is in another part ({}), which kepler does not read",
                        printable(short(p))
                    ),
                ));
            }
        }
        match self.objects.get(&id) {
            Some(r) => Ok((id, r)),
            None => Err(self.cx.err(
                ref_node,
                format!("object {id} does not exist in <resources>"),
            )),
        }
    }

    /// Counts each object's placements (once per reference, as an object's tree is met once
    /// per reference), refusing cycles of components and trees of components deeper than
    /// [`MAX_COMPONENT_DEPTH`] (by their height, however the objects are shared).
    fn count_uses(&mut self, build: Node) -> Result<()> {
        let mut heights: HashMap<u32, Option<usize>> = HashMap::new();
        for item in kids(build, "item") {
            let (id, _) = self.resource(item)?;
            *self.uses.entry(id).or_default() += 1;
            self.visit(id, &mut heights, 1)?;
        }
        Ok(())
    }

    /// Counts the references below object `id` once (its components), depth first, and
    /// returns its height (1 for a mesh); `depth` is where the walk met it.
    fn visit(
        &mut self,
        id: u32,
        heights: &mut HashMap<u32, Option<usize>>,
        depth: usize,
    ) -> Result<usize> {
        let node = self.objects[&id].node;
        let deep = |h: usize| h + depth > MAX_COMPONENT_DEPTH + 1;
        let too_deep = || {
            self.cx.err(
                node,
                format!("components are nested more than {MAX_COMPONENT_DEPTH} deep"),
            )
        };
        match heights.get(&id) {
            Some(Some(h)) if deep(*h) => return Err(too_deep()),
            Some(Some(h)) => return Ok(*h),
            Some(None) => {
                return Err(self.cx.err(
                    node,
                    format!("object {id} contains itself through its components"),
                ))
            }
            None => {}
        }
        if depth > MAX_COMPONENT_DEPTH {
            return Err(too_deep());
        }
        heights.insert(id, None);
        let mut height = 1;
        for comps in kids(node, "components") {
            for c in kids(comps, "component") {
                let (cid, _) = self.resource(c)?;
                *self.uses.entry(cid).or_default() += 1;
                height = height.max(1 + self.visit(cid, heights, depth + 1)?);
            }
        }
        if deep(height) {
            return Err(too_deep());
        }
        heights.insert(id, Some(height));
        Ok(height)
    }

    /// The object that `at` (an item or a component) places with `xf`, named in `names`
    /// (None when it has no triangles).
    fn place(&mut self, at: Node, xf: &M4, names: &mut UniqueNames) -> Result<Option<Object>> {
        let (id, r) = self.resource(at)?;
        let base = match r.name {
            Some(n) if !n.is_empty() => n.replace('/', "_"),
            _ => format!("object{id}"),
        };
        let object = if self.uses.get(&id).copied().unwrap_or(0) > 1 {
            let proto = match self.protos.get(&id) {
                Some(p) => p.clone(),
                None => {
                    let p = self.build(id, &M4::identity())?.map(Arc::new);
                    self.protos.insert(id, p.clone());
                    p
                }
            };
            match proto {
                Some(p) => {
                    let o = Object::instance(String::new(), p, *xf);
                    check_box(self.cx, at, &o.cbox)?;
                    Some(o)
                }
                None => None,
            }
        } else {
            self.build(id, xf)?
        };
        Ok(object.map(|mut o| {
            o.name = names.make(&base);
            o
        }))
    }

    /// Object `id` built with `xf` into its final frame (None when it has no triangles).
    fn build(&mut self, id: u32, xf: &M4) -> Result<Option<Object>> {
        let r = &self.objects[&id];
        let (node, name) = (r.node, r.name.unwrap_or("").to_string());
        if let Some(mesh) = kids(node, "mesh").next() {
            let m = self.mesh(mesh, xf)?;
            return Ok(m.map(|m| Object::from_mesh(name, m)));
        }
        let mut names = UniqueNames::default();
        let mut subs = Vec::new();
        for comps in kids(node, "components") {
            for c in kids(comps, "component") {
                let cxf = xf * transform(self.cx, c)?;
                if let Some(o) = self.place(c, &cxf, &mut names)? {
                    subs.push(o);
                }
            }
        }
        Ok((!subs.is_empty()).then(|| Object::group(name, subs)))
    }

    /// The `<mesh>` element's triangles placed by `xf` and cleaned (None without triangles).
    fn mesh(&mut self, mesh: Node, xf: &M4) -> Result<Option<Mesh>> {
        let cx = self.cx;
        let mut raw = PolyMesh::default();
        if let Some(vs) = kids(mesh, "vertices").next() {
            for v in kids(vs, "vertex") {
                let mut c = [0.0; 3];
                for (k, a) in ["x", "y", "z"].iter().enumerate() {
                    let x = cx.number(v, a)?;
                    if let Some(problem) = coord_problem(x) {
                        return Err(cx.err(v, format!("{a}: {problem}")));
                    }
                    c[k] = x;
                }
                raw.vertices.push(P3::new(c[0], c[1], c[2]));
            }
        }
        let n = raw.vertices.len();
        if let Some(ts) = kids(mesh, "triangles").next() {
            for t in kids(ts, "triangle") {
                let mut f = Vec::with_capacity(3);
                for a in ["v1", "v2", "v3"] {
                    let i = cx.index(t, a)?;
                    if i as usize >= n {
                        return Err(cx.err(t, format!("{a}={i}: the mesh has only {n} vertices")));
                    }
                    f.push(i);
                }
                raw.faces.push(f);
            }
        }
        if raw.faces.is_empty() {
            return Ok(None);
        }
        if *xf != M4::identity() {
            for v in &mut raw.vertices {
                *v = xf.transform_point(v);
            }
            if mirrors(xf) {
                for f in &mut raw.faces {
                    f.reverse();
                }
            }
        }
        check_box(cx, mesh, &Box3::from_points(raw.vertices.iter()))?;
        compact(&mut raw);
        self.progress
            .enter_phase(Stage::Load, Phase::Cleanup, raw.faces.len());
        let origin = Origin {
            file: cx.file,
            face_pos: &[],
        };
        cleanup(&raw, &origin, self.warnings, self.progress.count()).map(Some)
    }
}

/// `raw`'s vertices renumbered in order of first use by its faces, unused ones dropped (as
/// an OBJ group's are).
fn compact(raw: &mut PolyMesh) {
    let mut slot = vec![u32::MAX; raw.vertices.len()];
    let mut vertices = Vec::with_capacity(raw.vertices.len());
    for f in &mut raw.faces {
        for i in f.iter_mut() {
            let s = &mut slot[*i as usize];
            if *s == u32::MAX {
                *s = vertices.len() as u32;
                vertices.push(raw.vertices[*i as usize]);
            }
            *i = *s;
        }
    }
    raw.vertices = vertices;
}

/// An error at `n` when a placed box leaves the coordinate range.
fn check_box(cx: &Ctx, n: Node, b: &Box3) -> Result<()> {
    let ok = |p: &P3| p.iter().all(|c| c.is_finite() && c.abs() <= MAX_COORD);
    if b.is_empty() || (ok(&b.lo) && ok(&b.hi)) {
        return Ok(());
    }
    Err(cx.err(
        n,
        format!("after the transforms the mesh is beyond the coordinate limit {MAX_COORD:e}"),
    ))
}

#[cfg(test)]
mod tests {
    use std::fmt::Write as _;

    use super::*;

    fn model(body: &str) -> String {
        format!(
            r#"<?xml version="1.0" encoding="UTF-8"?>
<model unit="millimeter" xmlns="{CORE}">
{body}
</model>"#
        )
    }

    fn read(xml: &str) -> Result<Object> {
        read_model(
            Path::new("t.3mf"),
            "/3D/3dmodel.model",
            xml.as_bytes(),
            &mut Vec::new(),
            &Progress::default(),
        )
    }

    const TRI: &str = r#"<object id="1" name="tri" type="model"><mesh><vertices>
<vertex x="0" y="0" z="0"/><vertex x="1" y="0" z="0"/><vertex x="0" y="1" z="0"/>
</vertices><triangles><triangle v1="0" v2="1" v3="2"/></triangles></mesh></object>"#;

    #[test]
    fn transforms_are_row_vector_matrices() {
        // m30 m31 m32 = (10, 20, 30) translate; the 3x3 part maps x to y (a quarter turn).
        let xml = model(&format!(
            r#"<resources>{TRI}</resources><build><item objectid="1" transform="0 1 0 -1 0 0 0 0 1 10 20 30"/></build>"#
        ));
        let root = read(&xml).unwrap();
        let o = &root.subobjects()[0];
        assert_eq!(o.name, "tri");
        let v = o.vertices();
        // (1,0,0) -> x' = m00*1 + m30 = 10, y' = m01*1 + m31 = 21.
        assert!(v.contains(&P3::new(10., 21., 30.)), "{v:?}");
        // (0,1,0) -> x' = m10 + m30 = 9, y' = m11 + m31 = 20.
        assert!(v.contains(&P3::new(9., 20., 30.)), "{v:?}");
    }

    #[test]
    fn an_object_placed_twice_is_a_prototype() {
        let xml = model(&format!(
            r#"<resources>{TRI}<object id="2" name="pair"><components>
<component objectid="1"/><component objectid="1" transform="1 0 0 0 1 0 0 0 1 5 0 0"/>
</components></object></resources><build><item objectid="2"/></build>"#
        ));
        let root = read(&xml).unwrap();
        let pair = &root.subobjects()[0];
        assert_eq!(pair.name, "pair");
        let subs = pair.subobjects();
        assert_eq!(subs.len(), 2);
        assert_eq!(
            (subs[0].name.as_str(), subs[1].name.as_str()),
            ("tri", "tri.2")
        );
        let (crate::scene::Content::Instance(a), crate::scene::Content::Instance(b)) =
            (&subs[0].content, &subs[1].content)
        else {
            panic!("not instances");
        };
        assert!(Arc::ptr_eq(&a.prototype, &b.prototype));
        assert_eq!(subs[1].cbox.lo, P3::new(5., 0., 0.));
    }

    #[test]
    fn errors_name_the_part_and_line() {
        let xml = model(
            r#"<resources><object id="1"><mesh><vertices><vertex x="0" y="0" z="0"/></vertices>
<triangles><triangle v1="0" v2="1" v3="2"/></triangles></mesh></object></resources>
<build><item objectid="1"/></build>"#,
        );
        let e = read(&xml).unwrap_err().to_string();
        assert_eq!(
            e,
            "t.3mf: /3D/3dmodel.model:4:12: v2=1: the mesh has only 1 vertices"
        );
        let xml = model(&format!(
            r#"<resources>{TRI}<object id="2"><components><component objectid="3"/></components></object>
<object id="3"><components><component objectid="2"/></components></object></resources>
<build><item objectid="2"/></build>"#
        ));
        let e = read(&xml).unwrap_err().to_string();
        assert!(e.contains("contains itself through its components"), "{e}");
        // A chain of 200 objects, each also a direct component of a hub listed deepest
        // first: every object is met shallow, but the chain is 200 deep.
        let mut objects = TRI.replace("id=\"1\"", "id=\"1000\"");
        for k in 1..=200 {
            let below = if k == 200 { 1000 } else { k + 1 };
            let _ = write!(
                objects,
                "<object id=\"{k}\"><components><component objectid=\"{below}\"/></components></object>"
            );
        }
        let hub: String = (1..=200)
            .rev()
            .map(|k| format!("<component objectid=\"{k}\"/>"))
            .collect();
        let xml = model(&format!(
            "<resources>{objects}<object id=\"999\"><components>{hub}</components></object></resources><build><item objectid=\"999\"/></build>"
        ));
        let e = read(&xml).unwrap_err().to_string();
        assert!(e.contains("components are nested more than 64 deep"), "{e}");
    }
}
