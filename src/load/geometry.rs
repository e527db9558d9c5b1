//! Geometry nodes of scene files (`box`, `polyhedron`, `prism`, `antiprism`, `mesh`, inline
//! `vertices` + `face`) built into leaf objects in their final frame, through cleanup.

use std::collections::{HashMap, HashSet};
use std::path::{Path, PathBuf};
use std::sync::Arc;

use super::args::{integer, quoted_list, Node};
use super::mesh_file::{load_mesh, MeshFile};
use super::transform::mirrors;
use crate::count::Count;
use crate::error::{Error, Location, Pos, Result, Warning, Warnings};
use crate::geom::MAX_COORD;
use crate::geom::{Box3, PolyMesh, M4, P3};
use crate::primitives;
use crate::progress::{Phase, Progress, Stage};
use crate::scene::cleanup::{cleanup, FaceShape, Origin};
use crate::scene::{Mesh, Object, Texture, TextureFrame};

/// The names of the geometry nodes (each may carry `name=`).
pub(super) const GEOMETRY_NODES: [&str; 6] = [
    "box",
    "polyhedron",
    "prism",
    "antiprism",
    "mesh",
    "vertices",
];

/// True when `name` is a geometry node (`face` belongs to `vertices`).
pub(super) fn is_geometry(name: &str) -> bool {
    GEOMETRY_NODES.contains(&name)
}

/// Mesh files already loaded, by canonical path: each file's content as one shared prototype.
#[derive(Debug, Default)]
pub(super) struct MeshCache {
    files: HashMap<PathBuf, Arc<Object>>,
    /// The directory (canonical) every file a scene refers to must lie under, if any.
    pub root: Option<PathBuf>,
}

impl MeshCache {
    /// An empty cache whose files must lie under `root` (canonical), if given.
    pub(super) fn confined(root: Option<PathBuf>) -> MeshCache {
        MeshCache {
            files: HashMap::new(),
            root,
        }
    }
}

/// What one object's geometry is built with: its file, the transform to the final frame,
/// and where warnings and loaded meshes go.
pub(super) struct GeomCtx<'a> {
    /// Directory that relative mesh paths start from.
    pub dir: &'a Path,
    /// Transform from the object's coordinates to the frame it is stored in.
    pub xf: &'a M4,
    /// Warnings of the whole load.
    pub warnings: &'a mut Warnings,
    /// Mesh files loaded so far.
    pub meshes: &'a mut MeshCache,
    /// Where the load is (mesh files count their bytes and faces).
    pub progress: &'a Progress,
}

/// One built geometry node: a leaf object (a mesh, or an instance of a mesh file) with the
/// name it gets when it becomes a subobject.
pub(super) struct Geometry {
    /// The node kind (`box`, `mesh`, ...), for default names.
    pub kind: &'static str,
    /// The `name=` property, if given.
    pub name: Option<String>,
    /// Where the node is.
    pub loc: Location,
    /// The leaf object (its name is set by the caller).
    pub object: Object,
}

/// Builds the geometry node `n` (one of [`GEOMETRY_NODES`]); `faces` are the object's `face`
/// nodes, used by `vertices`.
pub(super) fn build(n: &Node, faces: &[Node], cx: &mut GeomCtx) -> Result<Geometry> {
    n.check_props(&["name"])?;
    let name = n.string_prop("name")?.map(str::to_string);
    let (kind, object) = match n.name() {
        "box" => ("box", primitive_leaf(n, box_mesh(n)?, cx)?),
        "polyhedron" => ("polyhedron", primitive_leaf(n, polyhedron(n)?, cx)?),
        "prism" => (
            "prism",
            primitive_leaf(n, sided(n, primitives::prism)?, cx)?,
        ),
        "antiprism" => (
            "antiprism",
            primitive_leaf(n, sided(n, primitives::antiprism)?, cx)?,
        ),
        "mesh" => ("mesh", mesh_node(n, cx)?),
        "vertices" => ("vertices", inline(n, faces, cx)?),
        other => return Err(n.parse_err(format!("`{other}` is not a geometry node"))),
    };
    Ok(Geometry {
        kind,
        name,
        loc: n.loc(),
        object,
    })
}

fn box_mesh(n: &Node) -> Result<PolyMesh> {
    n.no_children()?;
    let v = n.numbers(&[6], "numbers (X0 Y0 Z0 X1 Y1 Z1)")?;
    let (a, b) = (P3::new(v[0], v[1], v[2]), P3::new(v[3], v[4], v[5]));
    if let Some(axis) = (0..3).find(|&i| a[i] == b[i]) {
        return Err(n.invalid(format!(
            "the box is flat: both corners have {} = {}",
            ["x", "y", "z"][axis],
            a[axis]
        )));
    }
    Ok(primitives::cuboid(a.inf(&b), a.sup(&b)))
}

fn polyhedron(n: &Node) -> Result<PolyMesh> {
    n.no_children()?;
    let name = n.one_string("string (the solid's name)")?;
    primitives::by_name(name).ok_or_else(|| {
        n.parse_err(format!(
            "unknown polyhedron {name:?}: expected one of {}",
            quoted_list(&primitives::names())
        ))
    })
}

fn sided(n: &Node, make: fn(u32) -> Option<PolyMesh>) -> Result<PolyMesh> {
    n.no_children()?;
    let arg = n.check_count(&[1], "integer (the number of sides)")?[0];
    let sides = integer(n.src, arg)?;
    let max = primitives::MAX_SIDES;
    let bad = || {
        Error::invalid(
            n.src.entry_loc(arg),
            format!("`{}` needs 3 to {max} sides, not {sides}", n.name()),
        )
    };
    let k = u32::try_from(sides).map_err(|_| bad())?;
    make(k).ok_or_else(bad)
}

/// A leaf from a primitive solid: transformed, then cleaned (faces located at the node).
fn primitive_leaf(n: &Node, raw: PolyMesh, cx: &mut GeomCtx) -> Result<Object> {
    let pos = vec![pos_of(&n.loc()); raw.faces.len()];
    let mesh = clean_transformed(n, raw, &pos, &[], cx)?;
    Ok(Object::from_mesh("", mesh))
}

fn pos_of(loc: &Location) -> Pos {
    loc.pos
}

/// `mesh PATH`: an instance of the file's shared content.
fn mesh_node(n: &Node, cx: &mut GeomCtx) -> Result<Object> {
    n.no_children()?;
    let rel = n.one_string("string (the mesh file's path)")?;
    let path = cx.dir.join(rel);
    let proto = mesh_prototype(&path, &n.loc(), cx)?;
    let object = Object::instance("", proto, *cx.xf);
    check_cbox(n, &object.cbox)?;
    Ok(object)
}

/// The content of the mesh file at `path`, loaded and cleaned once per canonical path (into
/// the context's cache, with its warnings and progress); `at` is the node that asked for it
/// (where a missing file is reported).
fn mesh_prototype(path: &Path, at: &Location, cx: &mut GeomCtx) -> Result<Arc<Object>> {
    let cache = &mut *cx.meshes;
    let canonical = std::fs::canonicalize(path).map_err(|e| {
        let msg = format!("cannot read mesh file {}: {e}", path.display());
        Error::Io(at.clone(), std::io::Error::new(e.kind(), msg))
    })?;
    if let Some(p) = cache.files.get(&canonical) {
        return Ok(p.clone());
    }
    super::confine::check_under(cache.root.as_deref(), path, &canonical, at)?;
    let file = load_mesh(path, Some(at), cx.progress).map_err(|e| e.via(at))?;
    let mut objects = mesh_file_objects(&file, cx.warnings, cx.progress).map_err(|e| e.via(at))?;
    file.free();
    // Back to the scene file's nodes.
    cx.progress.enter(Stage::Load, 0);
    let proto = if objects.len() == 1 {
        objects.pop().map(Arc::new)
    } else {
        None
    };
    let proto = proto.unwrap_or_else(|| Arc::new(Object::group(stem(path), objects)));
    cache.files.insert(canonical, proto.clone());
    Ok(proto)
}

fn stem(path: &Path) -> String {
    path.file_stem()
        .map_or_else(|| "mesh".into(), |s| s.to_string_lossy().into_owned())
}

/// The groups of a mesh file as cleaned leaf objects, named after the groups (`/` becomes
/// `_`; repeated names get `.2`, `.3`, ...); the load's phase [`Phase::Cleanup`], counting
/// faces in `progress`.
pub(super) fn mesh_file_objects(
    file: &MeshFile,
    warnings: &mut Warnings,
    progress: &Progress,
) -> Result<Vec<Object>> {
    let faces = file.groups.iter().map(|g| g.mesh.faces.len()).sum();
    progress.enter_phase(Stage::Load, Phase::Cleanup, faces);
    let mut names = UniqueNames::default();
    let mut out = Vec::with_capacity(file.groups.len());
    for g in &file.groups {
        let origin = Origin {
            file: &file.path,
            face_pos: &g.face_pos,
        };
        let mesh = cleanup(&g.mesh, &origin, warnings, progress.count())?;
        let name = names.make(&g.name.replace('/', "_"));
        out.push(Object::from_mesh(name, mesh));
    }
    Ok(out)
}

/// Names made unique as they come, in time linear in the names (4,000 groups all named `g`
/// once took 90 s, a scan of every name taken for every candidate suffix).
#[derive(Debug, Default)]
pub(super) struct UniqueNames {
    taken: HashSet<String>,
    /// For a base name met again, the next suffix to try.
    next: HashMap<String, u64>,
}

impl UniqueNames {
    /// `base` (`mesh` when empty), or `base.2`, `base.3`, ... whichever is not taken first;
    /// then taken.
    pub(super) fn make(&mut self, base: &str) -> String {
        let base = if base.is_empty() { "mesh" } else { base };
        let name = if self.taken.contains(base) {
            let k = self.next.entry(base.to_string()).or_insert(2);
            loop {
                let c = format!("{base}.{k}");
                *k += 1;
                if !self.taken.contains(&c) {
                    break c;
                }
            }
        } else {
            base.to_string()
        };
        self.taken.insert(name.clone());
        name
    }
}

/// An error when a placed box leaves the coordinate range.
fn check_cbox(n: &Node, b: &Box3) -> Result<()> {
    let ok = |p: &P3| p.iter().all(|c| c.is_finite() && c.abs() <= MAX_COORD);
    if b.is_empty() || (ok(&b.lo) && ok(&b.hi)) {
        return Ok(());
    }
    Err(n.invalid(format!(
        "after the transforms the geometry reaches {:?}..{:?}, beyond the coordinate limit {MAX_COORD:e}",
        b.lo.coords.as_slice(),
        b.hi.coords.as_slice()
    )))
}

/// Transforms `raw` by the context's transform (reversing faces if it mirrors), checks the
/// coordinates, cleans it up and attaches the markings `textures` (by input face).
fn clean_transformed(
    n: &Node,
    mut raw: PolyMesh,
    face_pos: &[Pos],
    textures: &[Option<Texture>],
    cx: &mut GeomCtx,
) -> Result<Mesh> {
    let local = raw.clone();
    for v in &mut raw.vertices {
        *v = cx.xf.transform_point(v);
    }
    check_cbox(n, &Box3::from_points(raw.vertices.iter()))?;
    if mirrors(cx.xf) {
        for f in &mut raw.faces {
            f.reverse();
        }
    }
    let origin = Origin {
        file: &n.src.path,
        face_pos,
    };
    let mut mesh = cleanup(&raw, &origin, cx.warnings, Count::NONE)?;
    for (i, tex) in textures.iter().enumerate() {
        if let Some(t) = tex {
            attach(&local, &raw, i, t, &mut mesh, cx, &origin);
        }
    }
    Ok(mesh)
}

/// Attaches the markings of input face `i` to the cleaned face made from it, re-expressed in
/// that face's texture frame; warns when the face did not survive cleanup whole.
fn attach(
    local: &PolyMesh,
    placed: &PolyMesh,
    i: usize,
    tex: &Texture,
    mesh: &mut Mesh,
    cx: &mut GeomCtx,
    origin: &Origin,
) {
    let target = dedup_cycle(placed.face_points(i).copied().collect());
    let found = mesh.faces.iter().position(|f| {
        f.texture.is_none()
            && f.vertices.len() == target.len()
            && f.vertices
                .iter()
                .zip(&target)
                .all(|(&k, p)| mesh.vertices[k as usize] == *p)
    });
    let local_pts: Vec<P3> = local.face_points(i).copied().collect();
    let frames = found.and_then(|_| Some((frame_of(&local_pts)?, frame_of(&target)?)));
    let (Some(k), Some((from, to))) = (found, frames) else {
        cx.warnings.push(Warning {
            location: Location {
                file: origin.file.to_path_buf(),
                pos: origin.face_pos.get(i).copied().unwrap_or(Pos::File),
            },
            message: "the face's markings were dropped with it (it was degenerate or split)".into(),
        });
        return;
    };
    let mut t = tex.clone();
    for st in &mut t.points {
        let world = cx.xf.transform_point(&from.to_world(*st));
        *st = to.to_texture(&world);
    }
    mesh.faces[k].texture = Some(Arc::new(t));
}

/// The texture frame of a polygon's plane (Newell normal through its first corner).
fn frame_of(pts: &[P3]) -> Option<TextureFrame> {
    let first = pts.first()?;
    TextureFrame::of_plane(first, &FaceShape::of(pts).normal)
}

/// Removes cyclically repeated consecutive points, as cleanup does with indices.
fn dedup_cycle(mut pts: Vec<P3>) -> Vec<P3> {
    pts.dedup();
    while pts.len() > 1 && pts.first() == pts.last() {
        pts.pop();
    }
    pts
}

/// Inline geometry: `vertices { v X Y Z ... }` and the object's `face I J K ... { markings }`.
fn inline(n: &Node, faces: &[Node], cx: &mut GeomCtx) -> Result<Object> {
    let mut vertices = Vec::new();
    for v in n.children()? {
        if v.name() != "v" {
            return Err(v.parse_err(format!(
                "unknown node `{}` in `vertices`: expected `v X Y Z`",
                v.name()
            )));
        }
        v.check_props(&[])?;
        v.no_children()?;
        let c = v.numbers(&[3], "numbers (X Y Z)")?;
        vertices.push(P3::new(c[0], c[1], c[2]));
    }
    let mut raw = PolyMesh::new(vertices, Vec::with_capacity(faces.len()));
    let mut pos = Vec::with_capacity(faces.len());
    let mut textures = Vec::with_capacity(faces.len());
    for f in faces {
        raw.faces.push(face_indices(f, raw.vertices.len())?);
        pos.push(pos_of(&f.loc()));
        textures.push(markings(f)?);
    }
    if raw.faces.is_empty() {
        return Err(n.parse_err("`vertices` without any `face` node in the same object"));
    }
    let mesh = clean_transformed(n, raw, &pos, &textures, cx)?;
    Ok(Object::from_mesh("", mesh))
}

/// The vertex indices of a `face` node: at least 3, each below `count`.
fn face_indices(f: &Node, count: usize) -> Result<Vec<u32>> {
    f.check_props(&[])?;
    let args = f.args();
    if args.len() < 3 {
        return Err(f.invalid(format!(
            "a face needs at least 3 vertex indices, found {}",
            args.len()
        )));
    }
    args.iter()
        .map(|e| {
            let k = integer(f.src, e)?;
            if k < 0 || k >= count as i128 {
                return Err(Error::invalid(
                    f.src.entry_loc(e),
                    format!(
                        "vertex index {k} is out of range: there are {count} vertices (0 to {})",
                        count as i128 - 1
                    ),
                ));
            }
            Ok(k as u32)
        })
        .collect()
}

/// The markings of a `face` node (`point S T`, `line S0 T0 S1 T1`, `polygon S0 T0 S1 T1 ...`).
fn markings(f: &Node) -> Result<Option<Texture>> {
    let children = f.children_or_none();
    if children.is_empty() {
        return Ok(None);
    }
    let mut t = Texture::default();
    for m in children {
        m.check_props(&[])?;
        m.no_children()?;
        let st = |t: &mut Texture, c: &[f64]| {
            let first = t.points.len() as u32;
            t.points.extend(c.chunks(2).map(|p| [p[0], p[1]]));
            first..t.points.len() as u32
        };
        match m.name() {
            "point" => {
                st(&mut t, &m.numbers(&[2], "numbers (S T)")?);
            }
            "line" => {
                let r = st(&mut t, &m.numbers(&[4], "numbers (S0 T0 S1 T1)")?);
                t.lines.push([r.start, r.start + 1]);
            }
            "polygon" => {
                let c = polygon_numbers(&m)?;
                let r = st(&mut t, &c);
                t.polygons.push(r.collect());
            }
            other => {
                return Err(m.parse_err(format!(
                    "unknown marking `{other}`: expected `point`, `line` or `polygon`"
                )))
            }
        }
    }
    Ok(Some(t))
}

fn polygon_numbers(m: &Node) -> Result<Vec<f64>> {
    let count = m.args().len();
    if count < 6 || count % 2 == 1 {
        return Err(m.parse_err(format!(
            "`polygon` takes pairs of numbers (S T) for at least 3 corners, found {count} numbers"
        )));
    }
    m.numbers(&[count], "numbers")
}

#[cfg(test)]
mod tests {
    use super::super::source::Source;
    use super::*;
    use crate::geom::V3;

    struct Built {
        warnings: Warnings,
        result: Result<Geometry>,
    }

    fn build_first(text: &str, xf: M4) -> Built {
        let src = Source::new(Path::new("g.kdl"), text.to_string());
        let doc = src.parse().unwrap();
        let nodes: Vec<Node> = doc.iter().map(|n| Node::new(&src, n)).collect();
        let faces: Vec<Node> = nodes
            .iter()
            .copied()
            .filter(|n| n.name() == "face")
            .collect();
        let mut warnings = Vec::new();
        let mut meshes = MeshCache::default();
        let progress = Progress::new();
        let mut cx = GeomCtx {
            dir: Path::new("."),
            xf: &xf,
            warnings: &mut warnings,
            meshes: &mut meshes,
            progress: &progress,
        };
        let result = build(&nodes[0], &faces, &mut cx);
        Built { warnings, result }
    }

    fn mesh_of(g: &Geometry) -> &Mesh {
        g.object.mesh().expect("a leaf mesh")
    }

    #[test]
    fn box_corners_any_order_and_transformed() {
        let xf = M4::new_translation(&V3::new(10., 0., 0.));
        let b = build_first("box 1 2 3 0 0 0 name=\"b\"", xf);
        let g = b.result.unwrap();
        assert_eq!((g.kind, g.name.as_deref()), ("box", Some("b")));
        let m = mesh_of(&g);
        assert_eq!((m.vertices.len(), m.faces.len(), m.closed), (8, 6, true));
        assert_eq!(
            g.object.cbox,
            Box3::new(P3::new(10., 0., 0.), P3::new(11., 2., 3.))
        );
        assert!(b.warnings.is_empty());
        let e = build_first("box 0 0 0 1 0 1", M4::identity()).result;
        assert!(e.err().unwrap().to_string().contains("flat"));
    }

    #[test]
    fn mirrored_box_stays_closed_and_outward() {
        let xf = M4::new_nonuniform_scaling(&V3::new(-1., 1., 1.));
        let g = build_first("box 0 0 0 1 1 1", xf).result.unwrap();
        let m = mesh_of(&g);
        assert!(m.closed);
        // Every face's normal points away from the centre (-0.5, 0.5, 0.5).
        let c = P3::new(-0.5, 0.5, 0.5);
        for f in &m.faces {
            let pts: Vec<P3> = f.vertices.iter().map(|&k| m.vertices[k as usize]).collect();
            let nrm = FaceShape::of(&pts).normal;
            assert!(nrm.dot(&(pts[0] - c)) > 0.0);
        }
    }

    #[test]
    fn solids_by_name_and_sides() {
        let g = build_first("polyhedron \"cube\"", M4::identity())
            .result
            .unwrap();
        assert_eq!(mesh_of(&g).faces.len(), 6);
        let e = build_first("polyhedron \"cubee\"", M4::identity()).result;
        let e = e.err().unwrap().to_string();
        assert!(
            e.starts_with("g.kdl:1:1: unknown polyhedron \"cubee\": expected one of `tetrahedron`"),
            "{e}"
        );
        assert!(e.contains("`snub_dodecahedron`"), "{e}");
        let g = build_first("antiprism 5", M4::identity()).result.unwrap();
        assert_eq!(mesh_of(&g).faces.len(), 12);
        for bad in ["prism 0", "prism -3", "prism 2", "antiprism 99999999999"] {
            let e = build_first(bad, M4::identity())
                .result
                .err()
                .unwrap()
                .to_string();
            assert!(e.contains("sides"), "{bad}: {e}");
            assert!(e.starts_with("g.kdl:1:"), "{e}");
        }
        let e = build_first("prism 3.5", M4::identity())
            .result
            .err()
            .unwrap();
        assert!(e.to_string().contains("expected an integer"));
    }

    #[test]
    fn inline_faces_with_errors_at_their_nodes() {
        let text = "vertices { v 0 0 0; v 1 0 0; v 1 1 0; v 0 1 0 }\nface 0 1 2 3\n";
        let g = build_first(text, M4::identity()).result.unwrap();
        let m = mesh_of(&g);
        assert_eq!(m.faces.len(), 1);
        assert_eq!(m.faces[0].vertices[..], [0, 1, 2, 3]);
        let e = build_first(
            "vertices { v 0 0 0; v 1 0 0; v 1 1 0 }\nface 0 1 3\n",
            M4::identity(),
        );
        assert_eq!(
            e.result.err().unwrap().to_string(),
            "g.kdl:2:10: vertex index 3 is out of range: there are 3 vertices (0 to 2)"
        );
        let e = build_first(
            "vertices { v 0 0 0; v 1 0 0 }\n  face 0 1\n",
            M4::identity(),
        );
        assert!(e
            .result
            .err()
            .unwrap()
            .to_string()
            .starts_with("g.kdl:2:3: a face needs at least 3"));
        let e = build_first("vertices { v 0 0 0 }\n", M4::identity());
        assert!(e
            .result
            .err()
            .unwrap()
            .to_string()
            .contains("without any `face`"));
    }

    #[test]
    fn degenerate_face_warns_at_its_line() {
        let text = "vertices { v 0 0 0; v 1 0 0; v 2 0 0; v 0 1 0 }\nface 0 1 3\nface 0 1 2\n";
        let b = build_first(text, M4::identity());
        assert_eq!(mesh_of(&b.result.unwrap()).faces.len(), 1);
        assert_eq!(b.warnings.len(), 1);
        assert_eq!(b.warnings[0].location.to_string(), "g.kdl:3:1");
    }

    #[test]
    fn markings_follow_the_face() {
        // A face in the plane z = 0: its frame is x = (1,0,0), y = (0,1,0) at the origin.
        let text = "vertices { v 0 0 0; v 4 0 0; v 4 4 0; v 0 4 0 }\n\
                    face 0 1 2 3 { line 1 1 3 3; polygon 1 2 2 2 2 3; point 0.5 0.5 }\n";
        let g = build_first(text, M4::identity()).result.unwrap();
        let t = mesh_of(&g).faces[0].texture.clone().unwrap();
        assert_eq!(t.points.len(), 6);
        assert_eq!(t.lines, vec![[0, 1]]);
        assert_eq!(t.polygons, vec![vec![2, 3, 4]]);
        assert_eq!(t.points[0], [1., 1.]);
        // Moved up by 5 and turned to stand in the plane y = 0: the marking stays on the face.
        let xf = M4::new_translation(&V3::new(0., 0., 5.))
            * super::super::transform::rotation(90.0, &V3::x());
        let g = build_first(text, xf).result.unwrap();
        let m = mesh_of(&g);
        let t = m.faces[0].texture.clone().unwrap();
        let pts: Vec<P3> = m.faces[0]
            .vertices
            .iter()
            .map(|&k| m.vertices[k as usize])
            .collect();
        let frame = frame_of(&pts).unwrap();
        let world = frame.to_world(t.points[1]);
        let expect = xf.transform_point(&P3::new(3., 3., 0.));
        assert!((world - expect).norm() < 1e-12, "{world} vs {expect}");
        let e = build_first(
            "vertices { v 0 0 0 }\nface 0 0 0 { circle 1 }",
            M4::identity(),
        );
        assert!(e
            .result
            .err()
            .unwrap()
            .to_string()
            .contains("unknown marking `circle`"));
        let e = build_first(
            "vertices { v 0 0 0 }\nface 0 0 0 { polygon 1 2 3 4 }",
            M4::identity(),
        );
        assert!(e
            .result
            .err()
            .unwrap()
            .to_string()
            .contains("at least 3 corners"));
    }

    #[test]
    fn unique_names() {
        let mut u = UniqueNames::default();
        let got: Vec<String> = ["a", "a.2", "a", "b", "", "", "a", "a.3"]
            .iter()
            .map(|b| u.make(b))
            .collect();
        assert_eq!(
            got,
            ["a", "a.2", "a.3", "b", "mesh", "mesh.2", "a.4", "a.3.2"]
        );
    }

    #[test]
    fn unique_names_take_linear_time() {
        // 200,000 repeats of one name: quadratic was minutes, linear is well under a second
        // even in a debug build.
        let mut u = UniqueNames::default();
        let t = std::time::Instant::now();
        for _ in 0..200_000 {
            u.make("g");
        }
        assert_eq!(u.make("g"), "g.200001");
        assert!(t.elapsed().as_secs() < 20, "{:?}", t.elapsed());
    }
}
