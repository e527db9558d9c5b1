//! glTF 2.0 input (`.gltf` with its buffers, `.glb`): the default scene's node tree as the
//! object tree. Nodes become objects named after them, a mesh placed by several nodes one
//! prototype with an instance per node, a mesh placed once a leaf in its final frame; a camera
//! on a node is the scene's camera. Materials, textures, animations and skins are left out
//! with one note.
//!
//! Read by hand over `serde_json` rather than with the `gltf` crate: every error names the
//! JSON path of the value at fault (`nodes[3].mesh: mesh 7 does not exist`), buffers are
//! found and bounded by the loader's own rules, and no dependency is added.

use std::path::Path;
use std::sync::Arc;

use super::geometry::UniqueNames;
use super::gltf_accessor::Arrays;
use super::gltf_buffers::{is_glb, split_glb, Buffers};
use super::gltf_json::J;
use super::gltf_mesh::{read_mesh, Skipped};
use super::gltf_nodes::{check_affine, children, local_matrix, MAX_NODE_DEPTH};
use super::transform::mirrors;
use super::LoadOptions;
use crate::error::{Error, Location, Result, Warning, Warnings};
use crate::geom::{Box3, PolyMesh, M4, MAX_COORD, P3, V3};
use crate::progress::{Phase, Progress, Stage};
use crate::scene::cleanup::{cleanup, Origin};
use crate::scene::{CameraSpec, Object, Scene};

/// Extensions a file may require that change nothing kepler reads (looks and lights).
const HARMLESS: [&str; 4] = [
    "KHR_materials_",
    "KHR_texture_",
    "KHR_lights_punctual",
    "EXT_texture_",
];

/// Loads the glTF file at `path` (`.gltf` or `.glb`, told apart by its first bytes).
pub(super) fn load_gltf(
    path: &Path,
    opts: &LoadOptions,
    warnings: &mut Warnings,
    progress: &Progress,
) -> Result<Scene> {
    let bytes = super::read::read_mesh_bytes(path, None, progress)?;
    let (json, bin) = if is_glb(&bytes) {
        split_glb(path, &bytes)?
    } else {
        (bytes.as_slice(), None)
    };
    progress.enter_phase(Stage::Load, Phase::Parse, bytes.len());
    let value = parse_json(path, json, bin.is_some())?;
    let root_dir = opts
        .include_root
        .as_deref()
        .map(super::confine::canonical_root)
        .transpose()?;
    let top = J::top(&value, path);
    check_asset(&top)?;
    let arrays = Arrays {
        accessors: top.list("accessors")?,
        views: top.list("bufferViews")?,
        buffers: top.list("buffers")?,
    };
    let mut buffers = Buffers::new(path, bin, root_dir, arrays.buffers.len(), progress);
    let mut b = Builder::new(&top, &arrays, &mut buffers, warnings, progress)?;
    let objects = b.scene_objects()?;
    let camera = b.camera.take();
    b.note_ignored(&top)?;
    if objects.is_empty() {
        return Err(Error::invalid(
            Location::file(path),
            "the default scene has no triangles",
        ));
    }
    let root = Object::group("", objects);
    opts.check(&root, "the scene", &Location::file(path))?;
    let mut scene = Scene::new(root, path.to_path_buf());
    if let Some((spec, at)) = camera {
        scene.camera = Some(spec);
        scene.camera_at = Some(at);
    }
    Ok(scene)
}

/// The JSON document, or a parse error at its line and column.
fn parse_json(path: &Path, json: &[u8], glb: bool) -> Result<serde_json::Value> {
    serde_json::from_slice(json).map_err(|e| {
        let what = if glb { "the JSON chunk: " } else { "" };
        Error::parse(
            Location::line(path, e.line(), e.column()),
            format!("{what}invalid glTF JSON: {e}"),
        )
    })
}

/// An error unless the document says glTF 2 and requires only extensions kepler can ignore.
fn check_asset(top: &J) -> Result<()> {
    if !top.v.is_object() {
        return Err(top.err("a glTF document is a JSON object"));
    }
    let version = top.req("asset")?.req("version")?;
    if !version.str()?.starts_with("2.") {
        return Err(version.err(format!(
            "glTF version {}: only glTF 2.x is read",
            crate::scene::names::printable(version.str()?)
        )));
    }
    for e in top.list("extensionsRequired")? {
        let name = e.str()?;
        if !HARMLESS.iter().any(|h| name.starts_with(h)) {
            return Err(e.err(format!(
                "the file requires extension {} (compressed or extended geometry), which kepler does not read; export uncompressed triangle meshes",
                crate::scene::names::printable(name)
            )));
        }
    }
    Ok(())
}

/// The state of building a scene's objects.
struct Builder<'a, 'b> {
    file: &'a Path,
    nodes: Vec<J<'a>>,
    children: Vec<Vec<usize>>,
    meshes: Vec<J<'a>>,
    cameras: Vec<J<'a>>,
    /// Nodes of the default scene that place each mesh.
    uses: Vec<usize>,
    /// Each mesh as read, once read (no faces: nothing to draw).
    raw: Vec<Option<Arc<PolyMesh>>>,
    /// Each mesh placed more than once, as its prototype.
    protos: Vec<Option<Arc<Object>>>,
    arrays: &'b Arrays<'a>,
    buffers: &'b mut Buffers<'a>,
    warnings: &'b mut Warnings,
    progress: &'b Progress,
    skipped: Skipped,
    /// The first camera met on a node, and where.
    camera: Option<(CameraSpec, Location)>,
    /// Cameras on nodes after the first.
    more_cameras: usize,
    /// The default scene's top nodes.
    roots: Vec<usize>,
    /// The default scene's index, if the file has scenes.
    scene: Option<usize>,
}

impl<'a, 'b> Builder<'a, 'b> {
    fn new(
        top: &J<'a>,
        arrays: &'b Arrays<'a>,
        buffers: &'b mut Buffers<'a>,
        warnings: &'b mut Warnings,
        progress: &'b Progress,
    ) -> Result<Self> {
        let nodes = top.list("nodes")?;
        let children = children(&nodes)?;
        let meshes = top.list("meshes")?;
        let mut b = Builder {
            file: top.file,
            uses: vec![0; meshes.len()],
            raw: vec![None; meshes.len()],
            protos: vec![None; meshes.len()],
            nodes,
            children,
            meshes,
            cameras: top.list("cameras")?,
            arrays,
            buffers,
            warnings,
            progress,
            skipped: Skipped::default(),
            camera: None,
            more_cameras: 0,
            roots: Vec::new(),
            scene: None,
        };
        b.pick_scene(top)?;
        b.count_uses()?;
        Ok(b)
    }

    /// The default scene (`scene`, else the first) and its top nodes; without scenes, every
    /// node that has no parent.
    fn pick_scene(&mut self, top: &J<'a>) -> Result<()> {
        let scenes = top.list("scenes")?;
        let pick = match top.get("scene") {
            Some(s) => Some(s.index("scenes", scenes.len())?),
            None => (!scenes.is_empty()).then_some(0),
        };
        let Some(s) = pick else {
            let mut child = vec![false; self.nodes.len()];
            for &k in self.children.iter().flatten() {
                child[k] = true;
            }
            self.roots = (0..self.nodes.len()).filter(|&k| !child[k]).collect();
            return Ok(());
        };
        self.scene = Some(s);
        let mut seen = vec![false; self.nodes.len()];
        for k in self.children.iter().flatten() {
            seen[*k] = true;
        }
        for n in scenes[s].list("nodes")? {
            let k = n.index("nodes", self.nodes.len())?;
            if seen[k] {
                return Err(n.err(format!(
                    "node {k} is a child of another node or listed twice, not a top node"
                )));
            }
            seen[k] = true;
            self.roots.push(k);
        }
        Ok(())
    }

    /// Counts the nodes below the default scene that place each mesh, checking depth.
    fn count_uses(&mut self) -> Result<()> {
        let mut stack: Vec<(usize, usize)> = self.roots.iter().map(|&r| (r, 1)).collect();
        while let Some((k, depth)) = stack.pop() {
            let n = &self.nodes[k];
            if depth > MAX_NODE_DEPTH {
                return Err(n.err(format!("nodes are nested more than {MAX_NODE_DEPTH} deep")));
            }
            if let Some(m) = n.get("mesh") {
                self.uses[m.index("meshes", self.meshes.len())?] += 1;
            }
            stack.extend(self.children[k].iter().map(|&c| (c, depth + 1)));
        }
        Ok(())
    }

    /// The objects of the default scene's top nodes.
    fn scene_objects(&mut self) -> Result<Vec<Object>> {
        let mut names = UniqueNames::default();
        let mut out = Vec::new();
        for r in self.roots.clone() {
            if let Some(o) = self.node(r, &M4::identity(), &mut names)? {
                out.push(o);
            }
        }
        Ok(out)
    }

    /// The object of node `k` under a parent whose transform to the scene is `parent` (None
    /// when nothing below it has faces); its name made unique in `names`.
    fn node(&mut self, k: usize, parent: &M4, names: &mut UniqueNames) -> Result<Option<Object>> {
        let n = self.nodes[k].clone();
        let world = parent * local_matrix(&n)?;
        check_affine(&n, &world)?;
        if let Some(c) = n.get("camera") {
            self.camera_at(&c, &world)?;
        }
        let base = match n.opt_str("name")? {
            Some(s) if !s.is_empty() => s.replace('/', "_"),
            _ => format!("node{k}"),
        };
        let mut below = UniqueNames::default();
        let mut subs = Vec::new();
        let leaf_name = if self.children[k].is_empty() {
            None
        } else {
            Some(self.mesh_name(&n)?)
        };
        if let Some(m) = n.get("mesh") {
            let name = leaf_name.as_deref().map(|l| below.make(l));
            if let Some(leaf) = self.mesh_leaf(&n, &m, &world, name.unwrap_or_default())? {
                subs.push(leaf);
            }
        }
        for c in self.children[k].clone() {
            if let Some(o) = self.node(c, &world, &mut below)? {
                subs.push(o);
            }
        }
        let name = names.make(&base);
        Ok(match subs.len() {
            0 => None,
            1 if self.children[k].is_empty() => subs.pop().map(|mut o| {
                o.name = name;
                o
            }),
            _ => Some(Object::group(name, subs)),
        })
    }

    /// The name of the leaf of a node's mesh when the node also has children: the mesh's
    /// name, else `mesh`.
    fn mesh_name(&self, n: &J) -> Result<String> {
        let Some(m) = n.get("mesh") else {
            return Ok(String::new());
        };
        let i = m.index("meshes", self.meshes.len())?;
        Ok(match self.meshes[i].opt_str("name")? {
            Some(s) if !s.is_empty() => s.replace('/', "_"),
            _ => "mesh".into(),
        })
    }

    /// The leaf placing mesh `m` (the node's `mesh`) with `world`: an instance of its
    /// prototype when the mesh is placed more than once, else the mesh in its final frame.
    fn mesh_leaf(&mut self, n: &J, m: &J, world: &M4, name: String) -> Result<Option<Object>> {
        let i = m.index("meshes", self.meshes.len())?;
        let raw = self.raw_mesh(i)?;
        if raw.faces.is_empty() {
            return Ok(None);
        }
        if self.uses[i] > 1 {
            let proto = match &self.protos[i] {
                Some(p) => p.clone(),
                None => {
                    let mesh = self.clean(&raw)?;
                    let pname = self.mesh_name_of(i)?;
                    let p = Arc::new(Object::from_mesh(pname, mesh));
                    self.protos[i] = Some(p.clone());
                    p
                }
            };
            let o = Object::instance(name, proto, *world);
            check_box(n, &o.cbox)?;
            return Ok(Some(o));
        }
        let mut placed = (*raw).clone();
        if *world != M4::identity() {
            for v in &mut placed.vertices {
                *v = world.transform_point(v);
            }
            if mirrors(world) {
                for f in &mut placed.faces {
                    f.reverse();
                }
            }
        }
        check_box(n, &Box3::from_points(placed.vertices.iter()))?;
        Ok(Some(Object::from_mesh(name, self.clean(&placed)?)))
    }

    /// Mesh `i`'s name (`mesh{i}` when it has none).
    fn mesh_name_of(&self, i: usize) -> Result<String> {
        Ok(match self.meshes[i].opt_str("name")? {
            Some(s) if !s.is_empty() => s.replace('/', "_"),
            _ => format!("mesh{i}"),
        })
    }

    /// Mesh `i` as read (once).
    fn raw_mesh(&mut self, i: usize) -> Result<Arc<PolyMesh>> {
        if let Some(r) = &self.raw[i] {
            return Ok(r.clone());
        }
        let m = self.meshes[i].clone();
        let r = Arc::new(read_mesh(&m, self.arrays, self.buffers, &mut self.skipped)?);
        self.raw[i] = Some(r.clone());
        Ok(r)
    }

    /// `raw` cleaned as a mesh file's group is.
    fn clean(&mut self, raw: &PolyMesh) -> Result<crate::scene::Mesh> {
        self.progress
            .enter_phase(Stage::Load, Phase::Cleanup, raw.faces.len());
        let origin = Origin {
            file: self.file,
            face_pos: &[],
        };
        cleanup(raw, &origin, self.warnings, self.progress.count())
    }

    /// Takes the camera `c` (a node's `camera`) placed by `world` as the scene's, if it is the first.
    fn camera_at(&mut self, c: &J, world: &M4) -> Result<()> {
        let cam = &self.cameras[c.index("cameras", self.cameras.len())?];
        if self.camera.is_some() {
            self.more_cameras += 1;
            return Ok(());
        }
        let eye = world.transform_point(&P3::origin());
        let dir = world.transform_vector(&-V3::z());
        let up = world.transform_vector(&V3::y());
        let ty = cam.req("type")?;
        let spec = match ty.str()? {
            "perspective" => {
                let yfov = cam.req("perspective")?.req("yfov")?;
                let r = yfov.number()?;
                if !(r > 0.0 && r < std::f64::consts::PI) {
                    return Err(yfov.err(format!("a field of view of {r} radians")));
                }
                CameraSpec::Perspective {
                    eye,
                    target: eye + dir,
                    up,
                    fov_deg: r.to_degrees(),
                }
            }
            "orthographic" => CameraSpec::Orthographic { dir, up },
            other => {
                return Err(ty.err(format!(
                    "unknown camera type {}",
                    crate::scene::names::printable(other)
                )))
            }
        };
        let at = Location::file(self.file);
        self.camera = Some((spec, at));
        Ok(())
    }

    /// One note naming what the load left out: materials, textures, animations, skins, ...
    fn note_ignored(&mut self, top: &J) -> Result<()> {
        let mut parts = Vec::new();
        for key in [
            "materials",
            "textures",
            "images",
            "samplers",
            "animations",
            "skins",
        ] {
            let n = top.list(key)?.len();
            if n > 0 {
                parts.push(format!("{n} {key}"));
            }
        }
        let scenes = top.list("scenes")?.len();
        if scenes > 1 {
            let s = self.scene.unwrap_or(0);
            parts.push(format!(
                "{} scenes other than the default one ({s})",
                scenes - 1
            ));
        }
        let s = &self.skipped;
        if s.lines > 0 {
            parts.push(format!("{} point or line primitives", s.lines));
        }
        if s.targets > 0 {
            parts.push(format!("the morph targets of {} primitives", s.targets));
        }
        if self.more_cameras > 0 {
            parts.push(format!("{} cameras after the first", self.more_cameras));
        }
        if !parts.is_empty() {
            self.warnings.push(Warning {
                location: Location::file(self.file),
                message: format!(
                    "ignored {} (kepler reads the scene's triangles, node tree and camera)",
                    parts.join(", ")
                ),
            });
        }
        Ok(())
    }
}

/// An error at node `n` when a placed box leaves the coordinate range.
fn check_box(n: &J, b: &Box3) -> Result<()> {
    let ok = |p: &P3| p.iter().all(|c| c.is_finite() && c.abs() <= MAX_COORD);
    if b.is_empty() || (ok(&b.lo) && ok(&b.hi)) {
        return Ok(());
    }
    Err(n.err(format!(
        "after the transforms the mesh reaches {:?}..{:?}, beyond the coordinate limit {MAX_COORD:e}",
        b.lo.coords.as_slice(),
        b.hi.coords.as_slice()
    )))
}
