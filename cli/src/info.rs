//! `kepler info`: the object tree with face/vertex counts, CBOX, INBOX and closedness.

use std::path::PathBuf;
use std::process::ExitCode;

use anyhow::Result;
use clap::Args;
use kepler_hsr::emit::json::{json_string, num};
use kepler_hsr::geom::Box3;
use kepler_hsr::scene::{Content, Object};

use super::{load, out};

/// Arguments of `kepler info`.
#[derive(Args, Debug)]
pub(crate) struct InfoArgs {
    /// Scene file (.kdl) or mesh (.obj, .stl, .ply).
    pub(crate) scene: PathBuf,
    /// Print JSON instead of the tree.
    #[arg(long)]
    pub(crate) json: bool,
    /// Do not print warnings.
    #[arg(long, short)]
    pub(crate) quiet: bool,
}

/// Runs `kepler info`.
pub(crate) fn run(a: InfoArgs, opts: &kepler_hsr::LoadOptions) -> Result<ExitCode> {
    let scene = load(&a.scene, a.quiet, opts)?;
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
    out(&format!("{indent}  cbox  {}", fmt_box(&o.cbox)));
    if let Some(ib) = &o.inbox {
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
    for s in o.subobjects() {
        print_tree(s, &s.name, depth + 1);
    }
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
    format!(
        "{{\"name\":{},\"kind\":{},\"faces\":{},\"vertices\":{},\"closed\":{},\"cbox\":{},\"inbox\":{},\"subobjects\":[{}]}}",
        json_string(name),
        json_string(&kind(o)),
        o.face_count(),
        o.vertex_count(),
        o.is_closed(),
        box_json(&o.cbox),
        o.inbox.as_ref().map_or("null".into(), box_json),
        subs.join(",")
    )
}
