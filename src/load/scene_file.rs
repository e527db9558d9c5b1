//! The KDL scene file: cameras, includes, prototypes, objects and instances into a [`Scene`].
//!
//! The format is documented in `docs/scene-format.md`. In short: an `object` holds geometry
//! nodes, subobjects, transforms and an optional `inbox`; a `prototype` is an object drawn only
//! where an `instance` places it. An object's transforms are baked into its geometry at load;
//! an instance keeps its transform and shares its prototype.

use std::collections::{HashMap, HashSet};
use std::path::{Path, PathBuf};
use std::sync::Arc;

use super::args::{quoted_list, Node};
use super::camera_node::parse_camera;
use super::confine;
use super::geometry::{self, is_geometry, GeomCtx, MeshCache};
use super::limits::LoadOptions;
use super::section_node::parse_section;
use super::source::Source;
use super::style_node::parse_style;
use super::transform::{compose, is_transform, transform_box};
use crate::error::{Error, Location, Result, Warning, Warnings};
use crate::geom::MAX_COORD;
use crate::geom::{Box3, M4, P3, V3};
use crate::progress::{Progress, Stage};
use crate::scene::{CameraSpec, Object, Scene};

/// The nodes allowed at the top level of a scene file.
const TOP_NODES: [&str; 6] = [
    "camera",
    "section",
    "include",
    "prototype",
    "object",
    "instance",
];

/// Loads the scene file at `path` (and the files it includes and the meshes it uses).
/// Repairs made on the way are appended to `warnings`. An instance, object or scene with
/// more faces than `opts.max_faces` is an error at its node, found from counts before
/// anything is expanded. The scene file's nodes go to `progress` as the load stage as a
/// whole, each mesh file in it by its phases (read, parse, cleanup).
pub(crate) fn load_scene_file(
    path: &Path,
    opts: &LoadOptions,
    warnings: &mut Warnings,
    progress: &Progress,
) -> Result<Scene> {
    progress.enter(Stage::Load, 0);
    let mut loader = Loader {
        opts: opts.clone(),
        warnings,
        progress,
        meshes: MeshCache::confined(
            opts.include_root
                .as_deref()
                .map(confine::canonical_root)
                .transpose()?,
        ),
        prototypes: HashMap::new(),
        defining: Vec::new(),
        stack: Vec::new(),
        loaded: HashSet::new(),
        camera: None,
        sections: Vec::new(),
    };
    let placed = loader.file(path, None)?;
    if placed.is_empty() {
        return Err(Error::parse(
            Location::line(path, 1, 1),
            "the scene has no objects: add an `object` or `instance` node",
        ));
    }
    check_unique(&placed)?;
    let objects = placed.into_iter().map(|p| p.object).collect();
    Ok(Scene {
        root: Object::group("", objects),
        camera_at: loader.camera.as_ref().map(|c| c.1.clone()),
        camera: loader.camera.map(|c| c.0),
        source: path.to_path_buf(),
        section: None,
        sections: loader.sections,
        styles: Vec::new(),
    })
}

/// An object with the position of the node that made it (for duplicate-name messages).
struct Placed {
    object: Object,
    loc: Location,
}

/// A defined prototype and where.
struct Prototype {
    object: Arc<Object>,
    loc: Location,
    /// How many prototypes deep its instances go (0: it places none).
    depth: usize,
}

/// The deepest chain of prototypes placing prototypes accepted (bounds the recursion of the
/// later stages, which walk instances recursively).
pub(crate) const MAX_PROTOTYPE_DEPTH: usize = 64;

/// A file being loaded, and the include node in it that is being followed, if any.
struct Open {
    canonical: PathBuf,
    shown: PathBuf,
    include_at: Option<Location>,
}

/// The state of one load.
struct Loader<'w> {
    opts: LoadOptions,
    warnings: &'w mut Warnings,
    /// Where the load is.
    progress: &'w Progress,
    meshes: MeshCache,
    prototypes: HashMap<String, Prototype>,
    /// Prototypes whose bodies are being read (to explain self-reference), with the depth
    /// of the deepest prototype each places so far.
    defining: Vec<(String, usize)>,
    /// The include chain from the top file.
    stack: Vec<Open>,
    /// Files already loaded (an include of one again is skipped).
    loaded: HashSet<PathBuf>,
    camera: Option<(CameraSpec, Location)>,
    /// The top file's `section` planes, in order.
    sections: Vec<(P3, V3)>,
}

/// What an object's `{ ... }` block holds, sorted by role.
#[derive(Default)]
struct Body<'a> {
    transforms: Vec<Node<'a>>,
    inbox: Option<Node<'a>>,
    style: Option<Node<'a>>,
    faces: Vec<Node<'a>>,
    /// Geometry nodes, `object` and `instance` nodes, in source order.
    parts: Vec<Node<'a>>,
}

impl Loader<'_> {
    /// Loads one file; `at` is the include node that asked for it (None for the top file).
    /// Returns the file's objects (with those of files it includes).
    fn file(&mut self, path: &Path, at: Option<&Location>) -> Result<Vec<Placed>> {
        let canonical = std::fs::canonicalize(path).map_err(|e| {
            let loc = at.cloned().unwrap_or_else(|| Location::file(path));
            let msg = format!("cannot read {}: {e}", path.display());
            Error::Io(loc, std::io::Error::new(e.kind(), msg))
        })?;
        if let Some(k) = self.stack.iter().position(|o| o.canonical == canonical) {
            return Err(self.cycle_error(k, path));
        }
        if self.loaded.contains(&canonical) {
            return Ok(Vec::new());
        }
        if let Some(at) = at {
            confine::check_under(self.meshes.root.as_deref(), path, &canonical, at)?;
        }
        let src = Source::read(path, at)?;
        let doc = src.parse()?;
        self.stack.push(Open {
            canonical: canonical.clone(),
            shown: path.to_path_buf(),
            include_at: None,
        });
        let nodes: Vec<Node> = doc.iter().map(|n| Node::new(&src, n)).collect();
        let result = self.top_nodes(&nodes, at.is_none());
        self.stack.pop();
        self.loaded.insert(canonical);
        result
    }

    /// The error for an include that re-enters `stack[k]`: reported at the include in that
    /// file which starts the cycle, naming the chain.
    fn cycle_error(&self, k: usize, path: &Path) -> Error {
        let mut chain: Vec<String> = self.stack[k..]
            .iter()
            .map(|o| o.shown.display().to_string())
            .collect();
        chain.push(path.display().to_string());
        let loc = self.stack[k]
            .include_at
            .clone()
            .unwrap_or_else(|| Location::file(path));
        Error::invalid(loc, format!("include cycle: {}", chain.join(" includes ")))
    }

    fn top_nodes(&mut self, nodes: &[Node], top: bool) -> Result<Vec<Placed>> {
        let mut placed: Vec<Placed> = Vec::new();
        let later = prototype_definitions(nodes);
        let mut faces = 0usize;
        for n in nodes {
            // The scene so far, with everything this node adds (includes too).
            let before = placed.len();
            match n.name() {
                "camera" => self.camera_node(n, top)?,
                "section" => {
                    let plane = parse_section(n)?;
                    if top {
                        self.sections.push(plane);
                    } else {
                        self.warnings.push(Warning {
                            location: n.loc(),
                            message: "the section of an included file is ignored".into(),
                        });
                    }
                }
                "include" => placed.extend(self.include(n)?),
                "prototype" => self.prototype(n, &later)?,
                "object" => {
                    let object = self.object(n, &M4::identity(), &later)?;
                    placed.push(Placed {
                        object,
                        loc: n.loc(),
                    });
                }
                "instance" => {
                    let object = self.instance(n, &M4::identity(), &later)?;
                    placed.push(Placed {
                        object,
                        loc: n.loc(),
                    });
                }
                other => return Err(top_level_error(n, other)),
            }
            for p in &placed[before..] {
                faces = faces.saturating_add(p.object.face_count());
            }
            if faces > self.opts.max_faces {
                let so_far = Object::group("", placed.drain(..).map(|p| p.object).collect());
                return Err(Error::invalid(
                    n.loc(),
                    format!(
                        "with this node the scene has {} faces once its instances are placed, more than the limit of {} (--max-faces){}",
                        faces,
                        self.opts.max_faces,
                        chain_note(&so_far)
                    ),
                ));
            }
        }
        Ok(placed)
    }

    fn camera_node(&mut self, n: &Node, top: bool) -> Result<()> {
        let spec = parse_camera(n)?;
        if !top {
            self.warnings.push(Warning {
                location: n.loc(),
                message: "the camera of an included file is ignored".into(),
            });
            return Ok(());
        }
        if let Some((_, first)) = &self.camera {
            return Err(n.parse_err(format!("a second camera (the first is at {first})")));
        }
        self.camera = Some((spec, n.loc()));
        Ok(())
    }

    fn include(&mut self, n: &Node) -> Result<Vec<Placed>> {
        n.check_props(&[])?;
        n.no_children()?;
        let rel = n.one_string("string (the path of a scene file)")?;
        let path = n.src.path.parent().unwrap_or(Path::new("")).join(rel);
        let at = n.loc();
        if self.stack.len() > confine::MAX_INCLUDE_DEPTH {
            return Err(Error::invalid(
                at,
                format!(
                    "includes nested more than {} deep",
                    confine::MAX_INCLUDE_DEPTH
                ),
            ));
        }
        confine::check_scene_name(&path, &at)?;
        if let Some(open) = self.stack.last_mut() {
            open.include_at = Some(at.clone());
        }
        self.file(&path, Some(&at)).map_err(|e| {
            // An include cycle is reported in a file still open, naming the whole chain.
            let open = e
                .location()
                .is_some_and(|l| self.stack.iter().any(|o| o.shown == l.file));
            if open {
                e
            } else {
                e.via(&at)
            }
        })
    }

    fn prototype(&mut self, n: &Node, later: &HashMap<String, Location>) -> Result<()> {
        let name = object_name(n, &[])?;
        if let Some(p) = self.prototypes.get(&name) {
            return Err(n.parse_err(format!(
                "prototype {name:?} is defined twice (first at {})",
                p.loc
            )));
        }
        self.defining.push((name.clone(), 0));
        let object = self.body(n, name.clone(), &M4::identity(), later);
        let depth = self.defining.pop().map_or(0, |d| d.1);
        self.prototypes.insert(
            name,
            Prototype {
                object: Arc::new(object?),
                loc: n.loc(),
                depth,
            },
        );
        Ok(())
    }

    /// An `object NAME { ... }` node, built in the frame `xf` maps into.
    fn object(&mut self, n: &Node, xf: &M4, later: &HashMap<String, Location>) -> Result<Object> {
        let name = object_name(n, &[])?;
        self.body(n, name, xf, later)
    }

    /// The block of an object or prototype: its parts in the frame `xf * (own transforms)`.
    fn body(
        &mut self,
        n: &Node,
        name: String,
        xf: &M4,
        later: &HashMap<String, Location>,
    ) -> Result<Object> {
        let body = sort_body(n)?;
        let xf = xf * compose(&body.transforms)?;
        let mut geoms = Vec::new();
        let mut subs = Vec::new();
        for p in &body.parts {
            match p.name() {
                "object" => subs.push((self.object(p, &xf, later)?, p.loc())),
                "instance" => subs.push((self.instance(p, &xf, later)?, p.loc())),
                _ => geoms.push(self.geometry(p, &body.faces, &xf)?),
            }
        }
        let mut object = assemble(n, name, geoms, subs)?;
        self.opts.check(
            &object,
            &format!("{} {:?}", n.name(), object.name),
            &n.loc(),
        )?;
        if let Some(ib) = &body.inbox {
            object.inbox = self.checked_inbox(ib, &xf, &object)?;
        }
        if let Some(st) = &body.style {
            object.style = Some(parse_style(st)?);
        }
        Ok(object)
    }

    fn geometry(&mut self, n: &Node, faces: &[Node], xf: &M4) -> Result<geometry::Geometry> {
        let dir = n.src.path.parent().unwrap_or(Path::new("")).to_path_buf();
        let mut cx = GeomCtx {
            dir: &dir,
            xf,
            warnings: self.warnings,
            meshes: &mut self.meshes,
            progress: self.progress,
        };
        geometry::build(n, faces, &mut cx)
    }

    /// An `instance NAME of=PROTOTYPE { transforms, inbox }` node.
    fn instance(&mut self, n: &Node, xf: &M4, later: &HashMap<String, Location>) -> Result<Object> {
        let name = object_name(n, &["of"])?;
        let Some(of) = n.prop("of") else {
            return Err(n.parse_err("`instance` needs of=\"PROTOTYPE\""));
        };
        let proto_name = super::args::string(n.src, of)?;
        let proto = self.find_prototype(proto_name, n, later)?;
        let mut transforms = Vec::new();
        let mut inbox = None;
        let mut style = None;
        for c in n.children_or_none() {
            match c.name() {
                t if is_transform(t) => transforms.push(c),
                "inbox" => set_once(&mut inbox, c)?,
                "style" => set_once(&mut style, c)?,
                other => {
                    return Err(c.parse_err(format!(
                    "unknown node `{other}` in `instance`: expected a transform ({}) or `inbox`",
                    quoted_list(&super::transform::TRANSFORM_NODES)
                )))
                }
            }
        }
        let m = xf * compose(&transforms)?;
        let mut object = Object::instance(name, proto.clone(), m);
        self.opts
            .check(&object, &format!("instance {:?}", object.name), &n.loc())?;
        check_placed(n, &object.cbox)?;
        object.inbox = match &inbox {
            Some(ib) => self.checked_inbox(ib, &m, &object)?,
            None => proto.inbox.and_then(|b| transform_box(&b, &m)),
        };
        if let Some(st) = &style {
            object.style = Some(parse_style(st)?);
        }
        Ok(object)
    }

    fn find_prototype(
        &mut self,
        name: &str,
        n: &Node,
        later: &HashMap<String, Location>,
    ) -> Result<Arc<Object>> {
        if let Some(p) = self.prototypes.get(name) {
            let depth = p.depth + 1;
            if depth > MAX_PROTOTYPE_DEPTH {
                return Err(n.invalid(format!(
                    "prototypes are nested more than {MAX_PROTOTYPE_DEPTH} deep here"
                )));
            }
            if let Some(current) = self.defining.last_mut() {
                current.1 = current.1.max(depth);
            }
            return Ok(p.object.clone());
        }
        let msg = if self.defining.iter().any(|d| d.0 == name) {
            format!("prototype {name:?} cannot place itself (it is still being defined)")
        } else if let Some(at) = later.get(name) {
            format!("prototype {name:?} is used before its definition at {at}")
        } else {
            let mut known: Vec<&str> = self.prototypes.keys().map(String::as_str).collect();
            known.sort_unstable();
            if known.is_empty() {
                format!("unknown prototype {name:?}: no prototype is defined before this point")
            } else {
                format!(
                    "unknown prototype {name:?}: the defined ones are {}",
                    quoted_list(&known)
                )
            }
        };
        let at = n.prop("of").map_or_else(|| n.loc(), |e| n.src.entry_loc(e));
        Err(Error::parse(at, msg))
    }

    /// An `inbox X0 Y0 Z0 X1 Y1 Z1` node in coordinates that `xf` maps into the stored frame;
    /// None (with a warning) when `xf` does not keep boxes axis-aligned.
    fn inbox(&mut self, n: &Node, xf: &M4, cbox: &Box3) -> Result<Option<Box3>> {
        n.check_props(&[])?;
        n.no_children()?;
        let v = n.numbers(&[6], "numbers (X0 Y0 Z0 X1 Y1 Z1)")?;
        let (a, b) = (P3::new(v[0], v[1], v[2]), P3::new(v[3], v[4], v[5]));
        let local = Box3::new(a.inf(&b), a.sup(&b));
        let Some(placed) = transform_box(&local, xf) else {
            self.warnings.push(Warning {
                location: n.loc(),
                message: "INBOX dropped: the transforms turn it off the axes".into(),
            });
            return Ok(None);
        };
        if !contains_loosely(cbox, &placed) {
            return Err(n.invalid(format!(
                "the INBOX {:?}..{:?} is not inside the object's CBOX {:?}..{:?}",
                placed.lo.coords.as_slice(),
                placed.hi.coords.as_slice(),
                cbox.lo.coords.as_slice(),
                cbox.hi.coords.as_slice()
            )));
        }
        Ok(Some(placed.intersection_with(cbox)))
    }

    /// The explicit INBOX `n` of `object`, checked to lie inside one of its closed solids
    /// (as a computed one is proven); kept shrunk by the check's margin.
    fn checked_inbox(&mut self, n: &Node, xf: &M4, object: &Object) -> Result<Option<Box3>> {
        let Some(b) = self.inbox(n, xf, &object.cbox)? else {
            return Ok(None);
        };
        match crate::scene::contain::inside(object, &b) {
            Ok(shrunk) => Ok(Some(shrunk)),
            Err(why) => Err(n.invalid(format!(
                "the INBOX {:?}..{:?} is not inside the object: {why}",
                b.lo.coords.as_slice(),
                b.hi.coords.as_slice()
            ))),
        }
    }
}

/// `" (prototype chain: ...)"` for an object that has one, else nothing.
fn chain_note(o: &Object) -> String {
    let chain = super::limits::prototype_chain(o);
    if chain.is_empty() {
        chain
    } else {
        format!(" (prototype chain: {chain})")
    }
}

/// Box helpers local to the loader.
trait BoxExt {
    fn intersection_with(&self, o: &Box3) -> Box3;
}

impl BoxExt for Box3 {
    fn intersection_with(&self, o: &Box3) -> Box3 {
        Box3::new(self.lo.sup(&o.lo), self.hi.inf(&o.hi))
    }
}

/// Containment with a rounding allowance of 1e-9 of the outer box's size.
fn contains_loosely(outer: &Box3, inner: &Box3) -> bool {
    let s = outer.size();
    let tol = 1e-9 * s.iter().fold(0.0f64, |a, &b| a.max(b));
    (0..3).all(|i| outer.lo[i] - tol <= inner.lo[i] && inner.hi[i] <= outer.hi[i] + tol)
}

/// An error when a placed instance leaves the coordinate range.
fn check_placed(n: &Node, b: &Box3) -> Result<()> {
    let ok = |p: &P3| p.iter().all(|c| c.is_finite() && c.abs() <= MAX_COORD);
    if b.is_empty() || (ok(&b.lo) && ok(&b.hi)) {
        return Ok(());
    }
    Err(n.invalid(format!(
        "the placed prototype reaches beyond the coordinate limit {MAX_COORD:e}"
    )))
}

/// The name argument of `object`, `prototype` or `instance` (other properties: `props`).
fn object_name(n: &Node, props: &[&str]) -> Result<String> {
    n.check_props(props)?;
    let name = n.one_string("string (the name)")?;
    if name.is_empty() || name.contains('/') {
        return Err(Error::parse(
            n.src.entry_loc(n.args()[0]),
            format!("the name {name:?} must be nonempty and without '/' (paths use it)"),
        ));
    }
    Ok(name.to_string())
}

/// The names and positions of the `prototype` nodes of a file (for "used before defined").
fn prototype_definitions(nodes: &[Node]) -> HashMap<String, Location> {
    let mut out = HashMap::new();
    for n in nodes.iter().filter(|n| n.name() == "prototype") {
        if let Some(Ok(name)) = n.args().first().map(|e| super::args::string(n.src, e)) {
            out.entry(name.to_string()).or_insert_with(|| n.loc());
        }
    }
    out
}

fn top_level_error(n: &Node, name: &str) -> Error {
    let hint = if is_geometry(name) || is_transform(name) || name == "inbox" || name == "face" {
        format!("`{name}` belongs inside an `object` or `prototype` block")
    } else if is_word(name) {
        format!(
            "unknown node `{name}`: expected {}",
            quoted_list(&TOP_NODES)
        )
    } else {
        // Not quoted: a file that is not a scene may start with anything, a secret too.
        format!(
            "this is not a scene node: expected {}",
            quoted_list(&TOP_NODES)
        )
    };
    n.parse_err(hint)
}

/// True for a short name of lowercase letters, digits, `-` and `_`: a mistyped node, quoted.
fn is_word(name: &str) -> bool {
    name.len() <= 24
        && name
            .bytes()
            .all(|b| b.is_ascii_lowercase() || b.is_ascii_digit() || b == b'-' || b == b'_')
}

/// Sorts an object's block by role, checking what may appear once.
fn sort_body<'a>(n: &Node<'a>) -> Result<Body<'a>> {
    let mut b = Body::default();
    let mut vertices: Option<Node> = None;
    for c in n.children()? {
        match c.name() {
            t if is_transform(t) => b.transforms.push(c),
            "inbox" => set_once(&mut b.inbox, c)?,
            "style" => set_once(&mut b.style, c)?,
            "face" => b.faces.push(c),
            "vertices" => {
                set_once(&mut vertices, c)?;
                b.parts.push(c);
            }
            "object" | "instance" => b.parts.push(c),
            g if is_geometry(g) => b.parts.push(c),
            "camera" | "include" | "prototype" => {
                return Err(c.parse_err(format!("`{}` is allowed only at the top level", c.name())))
            }
            other => return Err(c.parse_err(body_hint(n.name(), other))),
        }
    }
    if let (Some(f), None) = (b.faces.first(), &vertices) {
        return Err(f.parse_err("`face` needs a `vertices` node in the same object"));
    }
    Ok(b)
}

fn body_hint(parent: &str, name: &str) -> String {
    format!(
        "unknown node `{name}` in `{parent}`: expected a geometry node ({}), `face`, `object`, `instance`, a transform ({}) or `inbox`",
        quoted_list(&geometry::GEOMETRY_NODES),
        quoted_list(&super::transform::TRANSFORM_NODES)
    )
}

/// Stores `c` in `slot`, or fails when the slot is taken.
fn set_once<'a>(slot: &mut Option<Node<'a>>, c: Node<'a>) -> Result<()> {
    if let Some(first) = slot {
        return Err(c.parse_err(format!(
            "`{}` given twice (first at {})",
            c.name(),
            first.loc()
        )));
    }
    *slot = Some(c);
    Ok(())
}

/// The object from its parts: a leaf when it has exactly one geometry node and no
/// subobjects, otherwise a group of geometry leaves (named) then subobjects.
fn assemble(
    n: &Node,
    name: String,
    mut geoms: Vec<geometry::Geometry>,
    subs: Vec<(Object, Location)>,
) -> Result<Object> {
    if geoms.len() == 1 && subs.is_empty() {
        let mut leaf = geoms.remove(0).object;
        leaf.name = name;
        return Ok(leaf);
    }
    if geoms.is_empty() && subs.is_empty() {
        return Err(n.parse_err(format!(
            "{} {name:?} is empty: give it geometry or subobjects",
            n.name()
        )));
    }
    let mut placed = Vec::with_capacity(geoms.len() + subs.len());
    let mut counts: HashMap<&str, usize> = HashMap::new();
    for g in geoms {
        let k = counts.entry(g.kind).or_insert(0);
        *k += 1;
        let default = match *k {
            1 => g.kind.to_string(),
            k => format!("{}.{k}", g.kind),
        };
        let mut object = g.object;
        object.name = g.name.unwrap_or(default);
        placed.push(Placed { object, loc: g.loc });
    }
    placed.extend(subs.into_iter().map(|(object, loc)| Placed { object, loc }));
    check_unique(&placed)?;
    Ok(Object::group(
        name,
        placed.into_iter().map(|p| p.object).collect(),
    ))
}

/// An error naming both positions when two siblings share a name.
fn check_unique(placed: &[Placed]) -> Result<()> {
    let mut seen: HashMap<&str, &Location> = HashMap::new();
    for p in placed {
        if let Some(first) = seen.insert(&p.object.name, &p.loc) {
            return Err(Error::parse(
                p.loc.clone(),
                format!(
                    "duplicate name {:?}: a sibling at {first} has it already",
                    p.object.name
                ),
            ));
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::V3;
    use crate::scene::Content;

    /// A fresh directory for one test's files.
    fn dir(test: &str) -> PathBuf {
        let d = std::env::temp_dir().join(format!("kepler-scene-{}-{test}", std::process::id()));
        let _ = std::fs::remove_dir_all(&d);
        std::fs::create_dir_all(&d).unwrap();
        d
    }

    fn write(d: &Path, name: &str, text: &str) -> PathBuf {
        let p = d.join(name);
        std::fs::write(&p, text).unwrap();
        p
    }

    fn load(test: &str, text: &str) -> (Result<Scene>, Warnings) {
        let d = dir(test);
        let p = write(&d, "s.kdl", text);
        let mut w = Vec::new();
        let r = load_scene_file(
            &p,
            &crate::LoadOptions::default(),
            &mut w,
            &crate::Progress::default(),
        );
        (r, w)
    }

    fn ok(test: &str, text: &str) -> Scene {
        load(test, text).0.unwrap()
    }

    /// The error text with the temporary directory cut off.
    fn err(test: &str, text: &str) -> String {
        let e = load(test, text).0.unwrap_err().to_string();
        let d = dir_name(test);
        e.replace(&d, "")
    }

    fn dir_name(test: &str) -> String {
        let d = std::env::temp_dir().join(format!("kepler-scene-{}-{test}", std::process::id()));
        format!("{}/", d.display())
    }

    /// The tree as nested names with kinds: leaf `name`, group `name(...)`, instance `name@`.
    fn tree(o: &Object) -> String {
        match &o.content {
            Content::Mesh(m) => format!("{}[{}]", o.name, m.faces.len()),
            Content::Instance(_) => format!("{}@", o.name),
            Content::Subobjects(s) => {
                let inner: Vec<String> = s.iter().map(tree).collect();
                format!("{}({})", o.name, inner.join(" "))
            }
        }
    }

    #[test]
    fn leaves_groups_and_default_names() {
        let s = ok(
            "names",
            r#"
            object "a" { box 0 0 0 1 1 1 }
            object "b" {
                box 0 0 0 1 1 1
                box 2 0 0 3 1 1
                polyhedron "tetrahedron" name="tet"
                prism 5
                object "sub" { antiprism 4 }
            }
            "#,
        );
        assert_eq!(
            tree(&s.root),
            "(a[6] b(box[6] box.2[6] tet[4] prism[7] sub[10]))"
        );
        assert_eq!(s.root.name, "");
        assert!(s.camera.is_none());
        let paths: Vec<String> = s.leaves().into_iter().map(|l| l.path).collect();
        assert_eq!(
            paths,
            ["a", "b/box", "b/box.2", "b/tet", "b/prism", "b/sub"]
        );
    }

    #[test]
    fn transforms_are_baked_in_order() {
        let s = ok(
            "bake",
            r#"
            object "outer" {
                translate 100 0 0
                object "inner" {
                    vertices { v 1 0 0; v 0 1 0; v 0 0 1 }
                    face 0 1 2
                    scale 2
                    rotate 90 axis="z"
                }
            }
            "#,
        );
        let inner = &s.root.subobjects()[0].subobjects()[0];
        // (1,0,0) -> scale -> (2,0,0) -> rotate z 90 -> (0,2,0) -> outer translate -> (100,2,0).
        assert_eq!(inner.vertices()[0], P3::new(100., 2., 0.));
        assert_eq!(inner.vertices()[1], P3::new(98., 0., 0.));
        assert_eq!(inner.vertices()[2], P3::new(100., 0., 2.));
        assert_eq!(
            inner.cbox,
            Box3::new(P3::new(98., 0., 0.), P3::new(100., 2., 2.))
        );
        assert_eq!(s.root.cbox, inner.cbox);
    }

    #[test]
    fn instances_share_their_prototype() {
        let s = ok(
            "inst",
            r#"
            prototype "house" {
                box 0 0 0 4 3 5
                object "roof" { prism 3; translate 2 3 0 }
                inbox 0.5 0.5 0.5 3.5 2.5 4.5
            }
            object "town" {
                instance "h1" of="house" { translate 10 0 0 }
                instance "h2" of="house" { rotate 90 axis="y"; translate 0 0 -20 }
                instance "h3" of="house" { rotate 30 axis="y" }
            }
            instance "h0" of="house"
            "#,
        );
        assert_eq!(tree(&s.root), "(town(h1@ h2@ h3@) h0@)");
        let town = s.root.subobjects()[0].subobjects();
        let proto = |o: &Object| match &o.content {
            Content::Instance(i) => i.prototype.clone(),
            _ => panic!("not an instance"),
        };
        let p1 = proto(&town[0]);
        assert!(Arc::ptr_eq(&p1, &proto(&town[1])));
        assert!(Arc::ptr_eq(&p1, &proto(&s.root.subobjects()[1])));
        assert_eq!(tree(&p1), "house(box[6] roof[5])");
        // The prototype keeps its own INBOX; placements carry it when axis-preserving.
        let inbox = Box3::new(P3::new(0.5, 0.5, 0.5), P3::new(3.5, 2.5, 4.5));
        assert_eq!(p1.inbox, Some(inbox));
        assert_eq!(
            town[0].inbox,
            Some(Box3::new(P3::new(10.5, 0.5, 0.5), P3::new(13.5, 2.5, 4.5)))
        );
        // rotate 90 about y: (x,y,z) -> (z,y,-x); then z -= 20.
        assert_eq!(
            town[1].inbox,
            Some(Box3::new(
                P3::new(0.5, 0.5, -23.5),
                P3::new(4.5, 2.5, -20.5)
            ))
        );
        assert_eq!(town[2].inbox, None);
        let leaves = s.leaves();
        assert_eq!(leaves[0].path, "town/h1/box");
        assert_eq!(leaves[0].world_vertex(0), P3::new(10., 0., 0.));
    }

    #[test]
    fn inbox_of_an_object_follows_its_transforms() {
        let (s, w) = load(
            "inbox",
            r#"
            object "a" { box 0 0 0 2 2 2; inbox 0.5 0.5 0.5 1.5 1.5 1.5; translate 1 0 0 }
            object "b" { box 0 0 0 2 2 2; inbox 0.5 0.5 0.5 1.5 1.5 1.5; rotate 45 axis="x" }
            "#,
        );
        let s = s.unwrap();
        let objs = s.root.subobjects();
        assert_eq!(
            objs[0].inbox,
            Some(Box3::new(P3::new(1.5, 0.5, 0.5), P3::new(2.5, 1.5, 1.5)))
        );
        assert_eq!(objs[1].inbox, None);
        assert_eq!(w.len(), 1);
        assert!(w[0].message.contains("INBOX dropped"), "{}", w[0]);
        let e = err(
            "inbox2",
            "object \"a\" { box 0 0 0 1 1 1; inbox 0 0 0 2 2 2 }",
        );
        assert!(e.starts_with("s.kdl:1:31: the INBOX"), "{e}");
    }

    #[test]
    fn duplicate_names_name_both_positions() {
        let e = err(
            "dup",
            "object \"a\" { box 0 0 0 1 1 1 }\nobject \"a\" { box 0 0 0 1 1 1 }\n",
        );
        assert_eq!(
            e,
            "s.kdl:2:1: duplicate name \"a\": a sibling at s.kdl:1:1 has it already"
        );
        let e = err(
            "dup2",
            "object \"a\" {\n box 0 0 0 1 1 1\n object \"box\" { box 0 0 0 1 1 1 }\n}\n",
        );
        assert_eq!(
            e,
            "s.kdl:3:2: duplicate name \"box\": a sibling at s.kdl:2:2 has it already"
        );
        let e = err(
            "dup3",
            "prototype \"p\" { prism 3 }\nprototype \"p\" { prism 4 }\n",
        );
        assert_eq!(
            e,
            "s.kdl:2:1: prototype \"p\" is defined twice (first at s.kdl:1:1)"
        );
    }

    #[test]
    fn prototype_errors() {
        let e = err(
            "proto1",
            "object \"a\" {\n  instance \"x\" of=\"nope\"\n}\n",
        );
        assert_eq!(
            e,
            "s.kdl:2:16: unknown prototype \"nope\": no prototype is defined before this point"
        );
        let e = err(
            "proto2",
            "instance \"x\" of=\"p\"\nprototype \"p\" { box 0 0 0 1 1 1 }\n",
        );
        assert_eq!(
            e,
            "s.kdl:1:14: prototype \"p\" is used before its definition at s.kdl:2:1"
        );
        let e = err("proto3", "prototype \"p\" { instance \"q\" of=\"p\" }\n");
        assert!(e.contains("cannot place itself"), "{e}");
        let e = err(
            "proto4",
            "prototype \"p\" { prism 3 }\ninstance \"x\" of=\"q\"\n",
        );
        assert!(e.ends_with("the defined ones are `p`"), "{e}");
        let e = err("proto5", "instance \"x\"\n");
        assert!(e.contains("needs of="), "{e}");
        let mut chain = "prototype \"p0\" { prism 3 }\n".to_string();
        for k in 1..=MAX_PROTOTYPE_DEPTH + 1 {
            chain += &format!(
                "prototype \"p{k}\" {{ instance \"i\" of=\"p{}\" }}\n",
                k - 1
            );
        }
        let e = err("proto6", &chain);
        assert!(
            e.starts_with("s.kdl:66:19: prototypes are nested more than 64 deep"),
            "{e}"
        );
    }

    #[test]
    fn structural_errors() {
        let cases = [
            ("box 0 0 0 1 1 1", "s.kdl:1:1: `box` belongs inside"),
            ("foo 1", "s.kdl:1:1: unknown node `foo`: expected `camera`"),
            ("object \"a\" { }", "s.kdl:1:1: object \"a\" is empty"),
            ("object \"a\"", "s.kdl:1:1: `object` needs a { ... } block"),
            ("object \"a/b\" { prism 3 }", "s.kdl:1:8: the name \"a/b\""),
            (
                "object \"a\" { face 0 1 2 }",
                "s.kdl:1:14: `face` needs a `vertices`",
            ),
            (
                "object \"a\" { cube }",
                "s.kdl:1:14: unknown node `cube` in `object`",
            ),
            (
                "object \"a\" { prism 3; camera { dir 0 0 -1 } }",
                "s.kdl:1:23: `camera` is allowed only",
            ),
            (
                "object \"a\" { prism 3; inbox 0 0 0 0 0 0; inbox 0 0 0 0 0 0 }",
                "s.kdl:1:42: `inbox` given twice",
            ),
            (
                "object \"a\" x=1 { prism 3 }",
                "s.kdl:1:12: unknown property `x` of `object`",
            ),
            (
                "object \"a\" { box 0 0 0 1 1 1 color=\"red\" }",
                "s.kdl:1:30: unknown property `color` of `box`",
            ),
            (
                "camera { dir 0 0 -1 }\ncamera { dir 0 0 -1 }\nobject \"a\" { prism 3 }",
                "s.kdl:2:1: a second camera",
            ),
            (
                "object \"a\" { prism 3; scale 1e7; translate 1e12 0 0 }",
                "s.kdl:1:14: after the transforms",
            ),
            ("// only a comment\n", "s.kdl:1:1: the scene has no objects"),
        ];
        for (text, want) in cases {
            let e = err("structural", text);
            assert!(e.starts_with(want), "{text}\n  got: {e}\n want: {want}");
        }
    }

    #[test]
    fn camera_is_read() {
        let s = ok("cam", "camera { dir -1 -1 -1 }\nobject \"a\" { prism 3 }\n");
        assert_eq!(
            s.camera,
            Some(CameraSpec::Orthographic {
                dir: V3::new(-1., -1., -1.),
                up: V3::y()
            })
        );
    }

    #[test]
    fn includes_bring_prototypes_and_objects() {
        let d = dir("incl");
        std::fs::create_dir_all(d.join("lib")).unwrap();
        write(
            &d,
            "lib/parts.kdl",
            "camera { dir 0 0 -1 }\nprototype \"p\" { prism 3 }\nobject \"from_lib\" { antiprism 3 }\n",
        );
        write(
            &d,
            "lib/more.kdl",
            "include \"parts.kdl\"\nobject \"more\" { prism 6 }\n",
        );
        let top = write(
            &d,
            "top.kdl",
            "include \"lib/parts.kdl\"\ninclude \"lib/more.kdl\"\ninstance \"x\" of=\"p\"\n",
        );
        let mut w = Vec::new();
        let s = load_scene_file(
            &top,
            &crate::LoadOptions::default(),
            &mut w,
            &crate::Progress::default(),
        )
        .unwrap();
        // parts.kdl is read once: more.kdl's include of it is skipped.
        assert_eq!(tree(&s.root), "(from_lib[8] more[8] x@)");
        assert!(s.camera.is_none());
        assert_eq!(w.len(), 1, "{w:?}");
        assert!(w[0].message.contains("camera of an included file"));
    }

    #[test]
    fn include_cycles_and_missing_files() {
        let d = dir("cycle");
        let a = write(&d, "a.kdl", "object \"a\" { prism 3 }\ninclude \"b.kdl\"\n");
        write(&d, "b.kdl", "\n\ninclude \"a.kdl\"\n");
        let mut w = Vec::new();
        let e = load_scene_file(
            &a,
            &crate::LoadOptions::default(),
            &mut w,
            &crate::Progress::default(),
        )
        .unwrap_err()
        .to_string();
        let p = |f: &str| d.join(f).display().to_string();
        assert_eq!(
            e,
            format!(
                "{}:2:1: include cycle: {} includes {} includes {}",
                p("a.kdl"),
                p("a.kdl"),
                p("b.kdl"),
                p("a.kdl")
            )
        );
        let e = err(
            "missing",
            "object \"a\" { prism 3 }\n  include \"nope.kdl\"\n",
        );
        assert!(e.starts_with("s.kdl:2:3: cannot read nope.kdl"), "{e}");
        let e = err("missing2", "object \"a\" { mesh \"nope.obj\" }\n");
        assert!(
            e.starts_with("s.kdl:1:14: cannot read mesh file nope.obj"),
            "{e}"
        );
    }

    #[test]
    fn errors_name_the_chain_of_includes_and_meshes() {
        let d = dir("chain");
        std::fs::create_dir_all(d.join("parts")).unwrap();
        write(
            &d,
            "parts/bad.obj",
            "v 0 0 0\nv 1 0 0\nv 0 1 zero\nf 1 2 3\n",
        );
        write(
            &d,
            "parts/part.kdl",
            "\nobject \"p\" {\n  mesh \"bad.obj\"\n}\n",
        );
        let top = write(
            &d,
            "top.kdl",
            "object \"a\" { prism 3 }\ninclude \"parts/part.kdl\"\n",
        );
        let mut w = Vec::new();
        let e = load_scene_file(
            &top,
            &crate::LoadOptions::default(),
            &mut w,
            &crate::Progress::default(),
        )
        .unwrap_err();
        let p = |f: &str| d.join(f).display().to_string();
        assert_eq!(
            e.to_string(),
            format!(
                "{}:2:1 -> {}:3:3 -> {}:3:7: invalid number 'zero'",
                p("top.kdl"),
                p("parts/part.kdl"),
                p("parts/bad.obj")
            )
        );
        assert_eq!(
            e.location().unwrap().to_string(),
            format!("{}:3:7", p("parts/bad.obj"))
        );
        // A directory, a device, a path with no mesh extension: at the mesh node.
        let e = err("meshdir", "object \"a\" {\n  mesh \".\"\n}\n");
        assert_eq!(
            e,
            "s.kdl:2:3: .: unknown mesh file extension (expected .obj, .stl or .ply)"
        );
        let dd = dir("meshdir2");
        std::fs::create_dir_all(dd.join("d.obj")).unwrap();
        let s = write(&dd, "s.kdl", "object \"a\" { mesh \"d.obj\" }\n");
        let e = load_scene_file(
            &s,
            &crate::LoadOptions::default(),
            &mut w,
            &crate::Progress::default(),
        )
        .unwrap_err()
        .to_string();
        assert!(
            e.ends_with("s.kdl:1:14: cannot read d.obj: it is a directory, not a file")
                || e.contains("s.kdl:1:14: cannot read"),
            "{e}"
        );
        if Path::new("/dev/zero").exists() {
            let e = err("zero", "object \"a\" { mesh \"/dev/zero.obj\" }\n");
            assert!(
                e.starts_with("s.kdl:1:14: cannot read mesh file /dev/zero.obj"),
                "{e}"
            );
        }
    }

    #[test]
    fn mesh_files_are_loaded_once_and_shared() {
        let d = dir("mesh");
        write(
            &d,
            "two.obj",
            "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\no first\nf 1 2 3\no second\nf 1 2 4\no first\nf 1 3 4\n",
        );
        write(&d, "tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
        let top = write(
            &d,
            "s.kdl",
            r#"
            object "p" { mesh "two.obj" }
            object "q" { mesh "./two.obj"; translate 5 0 0 }
            object "r" { mesh "tri.obj"; box 0 0 0 1 1 1 }
            "#,
        );
        let mut w = Vec::new();
        let s = load_scene_file(
            &top,
            &crate::LoadOptions::default(),
            &mut w,
            &crate::Progress::default(),
        )
        .unwrap();
        assert_eq!(tree(&s.root), "(p@ q@ r(mesh@ box[6]))");
        let objs = s.root.subobjects();
        let proto = |o: &Object| match &o.content {
            Content::Instance(i) => i.prototype.clone(),
            _ => panic!("not an instance"),
        };
        assert!(Arc::ptr_eq(&proto(&objs[0]), &proto(&objs[1])));
        assert_eq!(tree(&proto(&objs[0])), "two(first[1] second[1] first.2[1])");
        let paths: Vec<String> = s.leaves().into_iter().map(|l| l.path).collect();
        assert_eq!(
            paths,
            [
                "p/first",
                "p/second",
                "p/first.2",
                "q/first",
                "q/second",
                "q/first.2",
                "r/mesh",
                "r/box"
            ]
        );
        assert_eq!(s.leaves()[3].world_vertex(1), P3::new(6., 0., 0.));
    }

    #[test]
    fn plain_mesh_scene() {
        let d = dir("plain");
        let p = write(&d, "m.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
        let mut w = Vec::new();
        let s = crate::load::load_scene(
            &p,
            &crate::LoadOptions::default(),
            &mut w,
            &crate::Progress::default(),
        )
        .unwrap();
        assert_eq!(tree(&s.root), "(m[1])");
        let e = crate::load::load_scene(
            &d.join("x.txt"),
            &crate::LoadOptions::default(),
            &mut w,
            &crate::Progress::default(),
        )
        .unwrap_err();
        assert!(matches!(e, Error::Usage(_)));
    }
}
