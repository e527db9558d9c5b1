//! `kepler info`: the object tree with face/vertex counts, CBOX, every object's INBOX
//! (computed here even where a render would skip it, or a reason why there is none), and
//! whether each mesh is a proven solid whose back faces are culled, or why not.

use std::path::PathBuf;
use std::process::ExitCode;

use anyhow::Result;
use clap::Args;
use kepler_hsr::emit::json::{json_string, num};
use kepler_hsr::geom::Box3;
use kepler_hsr::prepare::{HierarchyKind, ObjectTree};
use kepler_hsr::scene::{Content, Mesh, Object, Solidity};
use std::sync::Arc;

use super::{load, out};

/// Arguments of `kepler info`.
#[derive(Args, Debug)]
pub(crate) struct InfoArgs {
    /// Scene file (.kdl) or mesh (.obj, .stl, .ply).
    pub(crate) scene: PathBuf,
    /// Print JSON instead of the tree.
    #[arg(long)]
    pub(crate) json: bool,
    /// Write a picture of each mesh's components, one colour per leaf component (SVG).
    #[arg(long, value_name = "F")]
    pub(crate) components: Option<PathBuf>,
    /// Pixels along the longer side of the --components picture.
    #[arg(long, value_name = "PX", default_value_t = 800)]
    pub(crate) size: u32,
    #[command(flatten)]
    pub(crate) camera: super::CameraArgs,
    /// Do not print warnings.
    #[arg(long, short)]
    pub(crate) quiet: bool,
}

/// Runs `kepler info`.
pub(crate) fn run(a: InfoArgs, opts: &kepler_hsr::LoadOptions) -> Result<ExitCode> {
    let mut scene = load(&a.scene, a.quiet, opts)?;
    // The render skips INBOXes where they cannot help (one object); info always shows them.
    kepler_hsr::prepare::compute_inboxes(&mut scene.root, Default::default());
    if let Some(f) = &a.components {
        let camera = a.camera.camera(&scene)?;
        super::write(
            f,
            super::components::components_svg(&scene, &camera, a.size)?,
        )?;
    }
    if a.json {
        out(&object_json(&scene.root, "scene"));
    } else {
        out(&format!(
            "{}: {} faces, {} vertices",
            a.scene.display(),
            scene.face_count(),
            scene.root.vertex_count()
        ));
        print_tree(&scene.root, "scene", 0);
    }
    Ok(ExitCode::SUCCESS)
}

fn kind(o: &Object) -> String {
    match &o.content {
        Content::Mesh(_) => "mesh".into(),
        Content::Subobjects(s) => format!("{} subobjects", s.len()),
        Content::Instance(i) => format!(
            "instance of {}",
            if i.prototype.name.is_empty() {
                "?"
            } else {
                &i.prototype.name
            }
        ),
    }
}

fn fmt_box(b: &Box3) -> String {
    if b.is_empty() {
        return "empty".into();
    }
    format!(
        "[{} {} {}]..[{} {} {}] vol {}",
        g(b.lo.x),
        g(b.lo.y),
        g(b.lo.z),
        g(b.hi.x),
        g(b.hi.y),
        g(b.hi.z),
        g(b.volume())
    )
}

fn g(x: f64) -> String {
    let s = format!("{x:.6}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    if s == "-0" {
        "0".into()
    } else {
        s.to_string()
    }
}

/// The mesh of a leaf (an instance's prototype leaf); None for a group.
fn leaf_mesh(o: &Object) -> Option<&Mesh> {
    match &o.content {
        Content::Mesh(m) => Some(m),
        Content::Subobjects(_) => None,
        Content::Instance(i) => leaf_mesh(&i.prototype),
    }
}

/// How a leaf's back faces are treated: culled on a proven solid, or why not.
fn cull_text(o: &Object) -> Option<String> {
    if let Content::Subobjects(_) = o.content {
        return None;
    }
    // None for an instance of a group.
    let mesh = leaf_mesh(o);
    let s = mesh.and_then(|m| m.solidity);
    if let Some((m, p)) = mesh.and_then(|m| Some((m, m.proven.as_ref()?))) {
        return Some(format!(
            "back faces culled on {} of {} pieces ({} of {} faces{}); not on the rest: {}",
            p.proven,
            p.pieces,
            p.proven_faces(),
            p.faces.len(),
            match m.caps.len() {
                0 => String::new(),
                k => format!(", except near {k} cap triangles"),
            },
            s.map_or(String::new(), Solidity::reason)
        ));
    }
    Some(match s {
        Some(Solidity::Solid) => "solid: back faces culled".into(),
        Some(s @ Solidity::Capped(_)) => s.reason(),
        Some(s) => format!("back faces not culled: {}", s.reason()),
        None => "back faces not culled: not prepared".into(),
    })
}

/// Why an object has no INBOX.
fn no_inbox_reason(o: &Object) -> String {
    match &o.content {
        Content::Mesh(m) if !m.closed => "open or inconsistent surface: no inside".into(),
        Content::Mesh(_) => "no box found inside".into(),
        Content::Subobjects(_) => "no subobject has an INBOX".into(),
        Content::Instance(i) if i.prototype.inbox.is_none() => {
            format!("its prototype has none ({})", no_inbox_reason(&i.prototype))
        }
        Content::Instance(_) => "no box fits inside the placed prototype's INBOX".into(),
    }
}

fn print_tree(o: &Object, name: &str, depth: usize) {
    let indent = "  ".repeat(depth);
    out(&format!(
        "{indent}{name} ({}): {} faces, {} vertices, {}",
        kind(o),
        o.face_count(),
        o.vertex_count(),
        if o.is_closed() {
            "closed solid"
        } else {
            "open"
        }
    ));
    if let Some(c) = cull_text(o) {
        out(&format!("{indent}  {c}"));
    }
    out(&format!("{indent}  cbox  {}", fmt_box(&o.cbox)));
    match &o.inbox {
        Some(ib) => {
            let ratio = if o.cbox.volume() > 0.0 {
                ib.volume() / o.cbox.volume()
            } else {
                0.0
            };
            out(&format!(
                "{indent}  inbox {} ({:.1}% of cbox)",
                fmt_box(ib),
                100.0 * ratio
            ));
        }
        None => out(&format!("{indent}  inbox none: {}", no_inbox_reason(o))),
    }
    if let Content::Mesh(m) = &o.content {
        print_hierarchy(o, m, &indent);
    }
    for s in o.subobjects() {
        print_tree(s, &s.name, depth + 1);
    }
}

/// Most component lines printed per mesh.
const MAX_COMPONENT_LINES: usize = 40;

/// The object tree of a mesh: the prepared one, or one built here for a mesh too small to
/// get one (the view splits those at the median per view).
fn tree_of(o: &Object, m: &Mesh) -> (Arc<ObjectTree>, bool) {
    match &o.tree {
        Some(t) => (t.clone(), true),
        None => (
            Arc::new(ObjectTree::build(m, HierarchyKind::Simplify)),
            false,
        ),
    }
}

fn print_hierarchy(o: &Object, m: &Mesh, indent: &str) {
    let (t, prepared) = tree_of(o, m);
    let s = t.shape();
    let c = &t.components;
    out(&format!(
        "{indent}  hierarchy {}{}: {} nodes, depth {}, {} leaves, {} upper nodes; {} levels, cell widths [{}], clusters [{}], components per level [{}]",
        t.kind.name(),
        if prepared {
            ""
        } else {
            " (built here: the view splits this mesh per view)"
        },
        s.nodes,
        s.depth,
        s.leaves,
        s.component_nodes,
        c.widths.len(),
        c.widths.iter().map(|w| g(*w)).collect::<Vec<_>>().join(", "),
        c.clusters.iter().map(usize::to_string).collect::<Vec<_>>().join(", "),
        c.per_level.iter().map(usize::to_string).collect::<Vec<_>>().join(", "),
    ));
    let mut lines = 0;
    let mut stack = vec![(0u32, 0usize)];
    while let Some((k, d)) = stack.pop() {
        let node = &c.nodes[k as usize];
        if lines == MAX_COMPONENT_LINES {
            out(&format!(
                "{indent}    ... ({} components in all)",
                c.nodes.len()
            ));
            break;
        }
        out(&format!(
            "{indent}    {}component {k} (level {}): {} faces",
            "  ".repeat(d),
            node.level,
            node.faces.len()
        ));
        lines += 1;
        stack.extend(node.children.iter().rev().map(|&ch| (ch, d + 1)));
    }
}

fn hierarchy_json(o: &Object) -> String {
    let Content::Mesh(m) = &o.content else {
        return String::new();
    };
    let (t, prepared) = tree_of(o, m);
    let s = t.shape();
    let c = &t.components;
    let list = |v: Vec<String>| v.join(",");
    format!(
        ",\"hierarchy\":{{\"kind\":{},\"prepared\":{},\"nodes\":{},\"depth\":{},\"leaves\":{},\"upper_nodes\":{},\"levels\":{},\"cell_widths\":[{}],\"clusters\":[{}],\"components_per_level\":[{}],\"leaf_components\":{}}}",
        json_string(t.kind.name()),
        prepared,
        s.nodes,
        s.depth,
        s.leaves,
        s.component_nodes,
        c.widths.len(),
        list(c.widths.iter().map(|w| num(*w)).collect()),
        list(c.clusters.iter().map(usize::to_string).collect()),
        list(c.per_level.iter().map(usize::to_string).collect()),
        c.leaves().len(),
    )
}

fn box_json(b: &Box3) -> String {
    if b.is_empty() {
        return "null".into();
    }
    format!(
        "{{\"lo\":[{},{},{}],\"hi\":[{},{},{}],\"volume\":{}}}",
        num(b.lo.x),
        num(b.lo.y),
        num(b.lo.z),
        num(b.hi.x),
        num(b.hi.y),
        num(b.hi.z),
        num(b.volume())
    )
}

fn object_json(o: &Object, name: &str) -> String {
    let subs: Vec<String> = o
        .subobjects()
        .iter()
        .map(|s| object_json(s, &s.name))
        .collect();
    let inbox = match &o.inbox {
        Some(b) => box_json(b),
        None => format!("null,\"inbox_reason\":{}", json_string(&no_inbox_reason(o))),
    };
    let solid = match o.content {
        Content::Subobjects(_) => String::new(),
        _ => {
            // None for an instance of a group.
            let mesh = leaf_mesh(o);
            let s = mesh.and_then(|m| m.solidity);
            let proven = mesh.and_then(|m| m.proven.as_ref());
            format!(
                ",\"solidity\":{},\"culled_back_faces\":{}{}{}",
                json_string(s.map_or("unprepared", Solidity::word)),
                s.is_some_and(|s| s.is_solid() || s.is_capped()) || proven.is_some(),
                match s {
                    Some(Solidity::Capped(n)) => format!(",\"caps\":{n}"),
                    _ => String::new(),
                },
                match proven {
                    Some(p) => format!(
                        ",\"proven_pieces\":{},\"pieces\":{},\"proven_faces\":{}",
                        p.proven,
                        p.pieces,
                        p.proven_faces()
                    ),
                    None => String::new(),
                }
            )
        }
    };
    format!(
        "{{\"name\":{},\"kind\":{},\"faces\":{},\"vertices\":{},\"closed\":{}{solid},\"cbox\":{},\"inbox\":{inbox}{},\"subobjects\":[{}]}}",
        json_string(name),
        json_string(&kind(o)),
        o.face_count(),
        o.vertex_count(),
        o.is_closed(),
        box_json(&o.cbox),
        hierarchy_json(o),
        subs.join(",")
    )
}
