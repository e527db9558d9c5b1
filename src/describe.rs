//! A prepared scene described for people and scripts (`kepler info`): the object tree with
//! face and vertex counts, CBOX, every object's INBOX (or why it has none), whether each mesh
//! is a proven solid whose back faces are culled (or why not), and each mesh's object tree.

use std::sync::Arc;

use rayon::prelude::*;

use crate::emit::write::json::{json_string, num};
use crate::geom::Box3;
use crate::prepare::{HierarchyKind, ObjectTree};
use crate::scene::names::printable;
use crate::scene::{Content, Mesh, Object, Scene, Solidity};
use crate::view::up::axis_name;

impl Scene {
    /// The object tree as indented text, one block per object (`kepler info`). Prepare the
    /// scene first (with [`crate::PrepareOptions::every_inbox`] to see every INBOX).
    pub fn describe(&self) -> String {
        let mut out = Vec::new();
        print_tree(&mut out, &self.root, "scene", 0);
        out.push(self.up_line());
        out.join("\n")
    }

    /// The object tree as one JSON object (`kepler info --json`), the root object with an
    /// `"up"` member: the up a render without camera flags uses.
    pub fn describe_json(&self) -> String {
        let mut root = object_json(&self.root, "scene");
        root.pop();
        root.push_str(&format!(",\"up\":{}}}", self.up_json()));
        root
    }

    /// The up a render without camera flags uses, and why, for people.
    fn up_line(&self) -> String {
        if let Some(up) = self.camera_up() {
            return format!("up: {} (the scene camera's)", axis_name(&up));
        }
        let v = self.auto_up_verdict();
        if !v.based {
            return format!(
                "up: {} (auto: no base fills a quarter of the shadow along any axis; the default)",
                axis_name(&v.up)
            );
        }
        format!(
            "up: {} (auto: it stands on a base filling {:.0}% of its shadow along that axis)",
            axis_name(&v.up),
            100.0 * fill_of(&v.fill, &v.up)
        )
    }

    /// [`Scene::up_line`] as JSON: `{"axis": "+Z", "vector": [0,0,1], "from": "auto" or
    /// "camera", "fill": {"+X": .., "-X": .., ...}}` (fill for auto only).
    fn up_json(&self) -> String {
        let (up, from, fill) = match self.camera_up() {
            Some(up) => (up, "camera", String::new()),
            None => {
                let v = self.auto_up_verdict();
                let names = ["+X", "-X", "+Y", "-Y", "+Z", "-Z"];
                let parts: Vec<String> = names
                    .iter()
                    .zip(v.fill)
                    .map(|(n, f)| format!("\"{n}\":{}", num(f)))
                    .collect();
                (v.up, "auto", format!(",\"fill\":{{{}}}", parts.join(",")))
            }
        };
        format!(
            "{{\"axis\":{},\"vector\":[{},{},{}],\"from\":\"{from}\"{fill}}}",
            json_string(&axis_name(&up)),
            num(up.x),
            num(up.y),
            num(up.z)
        )
    }
}

/// The fill of the base under `up` (an axis direction), from the six fills of the auto rule.
fn fill_of(fill: &[f64; 6], up: &crate::geom::V3) -> f64 {
    let k = (0..3).find(|&k| up[k] != 0.0).unwrap_or(1);
    fill[2 * k + usize::from(up[k] < 0.0)]
}

fn kind(o: &Object) -> String {
    match &o.content {
        Content::Mesh(_) => "mesh".into(),
        Content::Subobjects(s) => format!("{} subobjects", s.len()),
        Content::Instance(i) => format!(
            "instance of {}",
            if i.prototype.name.is_empty() {
                "?".into()
            } else {
                printable(&i.prototype.name)
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

fn print_tree(out: &mut Vec<String>, o: &Object, name: &str, depth: usize) {
    let indent = "  ".repeat(depth);
    out.push(format!(
        "{indent}{} ({}): {} faces, {} vertices, {}",
        printable(name),
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
        out.push(format!("{indent}  {c}"));
    }
    out.push(format!("{indent}  cbox  {}", fmt_box(&o.cbox)));
    match &o.inbox {
        Some(ib) => {
            let ratio = if o.cbox.volume() > 0.0 {
                ib.volume() / o.cbox.volume()
            } else {
                0.0
            };
            out.push(format!(
                "{indent}  inbox {} ({:.1}% of cbox)",
                fmt_box(ib),
                100.0 * ratio
            ));
        }
        None => out.push(format!("{indent}  inbox none: {}", no_inbox_reason(o))),
    }
    if let Content::Mesh(m) = &o.content {
        print_hierarchy(out, o, m, &indent);
    }
    // Subtrees described side by side (a mesh's object tree is built here when it has none:
    // the cost of `info`), put together in order.
    let parts: Vec<Vec<String>> = o
        .subobjects()
        .par_iter()
        .with_min_len(PARALLEL_CHUNK)
        .map(|s| {
            let mut part = Vec::new();
            print_tree(&mut part, s, &s.name, depth + 1);
            part
        })
        .collect();
    out.extend(parts.into_iter().flatten());
}

/// Subobjects described per task, at least (describing one takes microseconds).
const PARALLEL_CHUNK: usize = 64;

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

fn print_hierarchy(out: &mut Vec<String>, o: &Object, m: &Mesh, indent: &str) {
    let (t, prepared) = tree_of(o, m);
    let s = t.shape();
    let c = &t.components;
    out.push(format!(
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
            out.push(format!(
                "{indent}    ... ({} components in all)",
                c.nodes.len()
            ));
            break;
        }
        out.push(format!(
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
        .par_iter()
        .with_min_len(PARALLEL_CHUNK)
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
