//! A small glTF 2.0 writer for tests: meshes of triangles, a node tree, cameras, written as
//! `.glb`, as `.gltf` with a base64 data URI, or as `.gltf` beside a `.bin` file.

use std::fmt::Write as _;

/// A unit cube's 8 corners and 12 outward (counter-clockwise seen from outside) triangles.
pub fn unit_cube_triangles() -> (Vec<[f32; 3]>, Vec<[u32; 3]>) {
    let p = (0..8)
        .map(|k| [(k & 1) as f32, ((k >> 1) & 1) as f32, ((k >> 2) & 1) as f32])
        .collect();
    let quads = [
        [0, 2, 3, 1],
        [4, 5, 7, 6],
        [0, 1, 5, 4],
        [2, 6, 7, 3],
        [0, 4, 6, 2],
        [1, 3, 7, 5],
    ];
    let t = quads
        .iter()
        .flat_map(|q| [[q[0], q[1], q[2]], [q[0], q[2], q[3]]])
        .collect();
    (p, t)
}

/// A mesh of one indexed TRIANGLES primitive.
#[derive(Debug, Clone, Default)]
pub struct GltfMesh {
    /// The mesh's name (none when empty).
    pub name: String,
    /// Vertex positions.
    pub positions: Vec<[f32; 3]>,
    /// Triangles, counter-clockwise seen from outside.
    pub triangles: Vec<[u32; 3]>,
}

/// A node: a name, a transform, an optional mesh and camera, children.
#[derive(Debug, Clone, Default)]
pub struct GltfNode {
    /// The node's name, if any.
    pub name: Option<String>,
    /// The mesh it places, if any.
    pub mesh: Option<usize>,
    /// The camera on it, if any.
    pub camera: Option<usize>,
    /// Translation.
    pub translation: Option<[f64; 3]>,
    /// Rotation quaternion (x, y, z, w).
    pub rotation: Option<[f64; 4]>,
    /// Scale.
    pub scale: Option<[f64; 3]>,
    /// A column-major matrix (instead of the TRS properties).
    pub matrix: Option<[f64; 16]>,
    /// Child nodes.
    pub children: Vec<usize>,
}

/// A whole document.
#[derive(Debug, Clone, Default)]
pub struct Gltf {
    /// The meshes.
    pub meshes: Vec<GltfMesh>,
    /// The nodes.
    pub nodes: Vec<GltfNode>,
    /// The top nodes of the one scene.
    pub roots: Vec<usize>,
    /// Cameras as JSON objects (`{"type":"perspective","perspective":{...}}`).
    pub cameras: Vec<String>,
    /// More top-level members, as `"key": value` JSON text (materials, extensions, ...).
    pub extra: Vec<String>,
}

/// A JSON number for `x` (Rust's shortest round-trip decimal).
fn num(x: f64) -> String {
    format!("{x:?}")
}

/// Numbers as a JSON array.
fn nums(v: &[f64]) -> String {
    let items: Vec<String> = v.iter().map(|&x| num(x)).collect();
    format!("[{}]", items.join(","))
}

/// A JSON string.
pub fn json_string(s: &str) -> String {
    let mut o = String::from("\"");
    for c in s.chars() {
        match c {
            '"' => o.push_str("\\\""),
            '\\' => o.push_str("\\\\"),
            c if (c as u32) < 0x20 => {
                let _ = write!(o, "\\u{:04x}", c as u32);
            }
            c => o.push(c),
        }
    }
    o.push('"');
    o
}

impl Gltf {
    /// The binary buffer (positions then indices of each mesh, 4-byte aligned) and the JSON
    /// document whose one buffer has `uri` (none: a GLB's BIN chunk).
    pub fn json_and_bin(&self, uri: Option<&str>) -> (String, Vec<u8>) {
        let mut bin = Vec::new();
        let (mut views, mut accs, mut meshes) = (Vec::new(), Vec::new(), Vec::new());
        for m in &self.meshes {
            let (mut lo, mut hi) = ([f32::MAX; 3], [f32::MIN; 3]);
            let off = bin.len();
            for p in &m.positions {
                for k in 0..3 {
                    lo[k] = lo[k].min(p[k]);
                    hi[k] = hi[k].max(p[k]);
                    bin.extend_from_slice(&p[k].to_le_bytes());
                }
            }
            views.push(format!(
                r#"{{"buffer":0,"byteOffset":{off},"byteLength":{}}}"#,
                bin.len() - off
            ));
            let lo: Vec<f64> = lo.iter().map(|&x| f64::from(x)).collect();
            let hi: Vec<f64> = hi.iter().map(|&x| f64::from(x)).collect();
            accs.push(format!(
                r#"{{"bufferView":{},"componentType":5126,"count":{},"type":"VEC3","min":{},"max":{}}}"#,
                views.len() - 1,
                m.positions.len(),
                nums(&lo),
                nums(&hi)
            ));
            let off = bin.len();
            for t in &m.triangles {
                for i in t {
                    bin.extend_from_slice(&i.to_le_bytes());
                }
            }
            views.push(format!(
                r#"{{"buffer":0,"byteOffset":{off},"byteLength":{}}}"#,
                bin.len() - off
            ));
            accs.push(format!(
                r#"{{"bufferView":{},"componentType":5125,"count":{},"type":"SCALAR"}}"#,
                views.len() - 1,
                m.triangles.len() * 3
            ));
            let name = if m.name.is_empty() {
                String::new()
            } else {
                format!(r#""name":{},"#, json_string(&m.name))
            };
            meshes.push(format!(
                r#"{{{name}"primitives":[{{"attributes":{{"POSITION":{}}},"indices":{}}}]}}"#,
                accs.len() - 2,
                accs.len() - 1
            ));
        }
        let nodes: Vec<String> = self.nodes.iter().map(node_json).collect();
        let uri = uri.map_or(String::new(), |u| format!(r#","uri":{}"#, json_string(u)));
        let mut parts = vec![
            r#""asset":{"version":"2.0","generator":"kepler-testkit"}"#.to_string(),
            r#""scene":0"#.to_string(),
            format!(
                r#""scenes":[{{"nodes":[{}]}}]"#,
                self.roots
                    .iter()
                    .map(|r| r.to_string())
                    .collect::<Vec<_>>()
                    .join(",")
            ),
            format!(r#""nodes":[{}]"#, nodes.join(",\n")),
            format!(r#""meshes":[{}]"#, meshes.join(",\n")),
            format!(r#""accessors":[{}]"#, accs.join(",\n")),
            format!(r#""bufferViews":[{}]"#, views.join(",\n")),
            format!(r#""buffers":[{{"byteLength":{}{uri}}}]"#, bin.len()),
        ];
        if !self.cameras.is_empty() {
            parts.push(format!(r#""cameras":[{}]"#, self.cameras.join(",")));
        }
        parts.extend(self.extra.iter().cloned());
        (format!("{{\n{}\n}}\n", parts.join(",\n")), bin)
    }

    /// The document as a `.glb` file.
    pub fn glb(&self) -> Vec<u8> {
        let (json, bin) = self.json_and_bin(None);
        glb(&json, &bin)
    }

    /// The document as a `.gltf` file with its buffer in a base64 data URI.
    pub fn gltf_embedded(&self) -> String {
        let (_, bin) = self.json_and_bin(None);
        let uri = format!("data:application/octet-stream;base64,{}", base64(&bin));
        self.json_and_bin(Some(&uri)).0
    }
}

/// A GLB file of the JSON `json` and the BIN chunk `bin` (both padded to 4 bytes).
pub fn glb(json: &str, bin: &[u8]) -> Vec<u8> {
    let mut j = json.as_bytes().to_vec();
    while !j.len().is_multiple_of(4) {
        j.push(b' ');
    }
    let mut b = bin.to_vec();
    while !b.len().is_multiple_of(4) {
        b.push(0);
    }
    let total = 12 + 8 + j.len() + if b.is_empty() { 0 } else { 8 + b.len() };
    let mut out = Vec::with_capacity(total);
    out.extend_from_slice(b"glTF");
    out.extend_from_slice(&2u32.to_le_bytes());
    out.extend_from_slice(&(total as u32).to_le_bytes());
    out.extend_from_slice(&(j.len() as u32).to_le_bytes());
    out.extend_from_slice(b"JSON");
    out.extend_from_slice(&j);
    if !b.is_empty() {
        out.extend_from_slice(&(b.len() as u32).to_le_bytes());
        out.extend_from_slice(b"BIN\0");
        out.extend_from_slice(&b);
    }
    out
}

/// One node as JSON.
fn node_json(n: &GltfNode) -> String {
    let mut f = Vec::new();
    if let Some(s) = &n.name {
        f.push(format!(r#""name":{}"#, json_string(s)));
    }
    if let Some(m) = n.mesh {
        f.push(format!(r#""mesh":{m}"#));
    }
    if let Some(c) = n.camera {
        f.push(format!(r#""camera":{c}"#));
    }
    if let Some(t) = n.translation {
        f.push(format!(r#""translation":{}"#, nums(&t)));
    }
    if let Some(r) = n.rotation {
        f.push(format!(r#""rotation":{}"#, nums(&r)));
    }
    if let Some(s) = n.scale {
        f.push(format!(r#""scale":{}"#, nums(&s)));
    }
    if let Some(m) = n.matrix {
        f.push(format!(r#""matrix":{}"#, nums(&m)));
    }
    if !n.children.is_empty() {
        let c: Vec<String> = n.children.iter().map(|c| c.to_string()).collect();
        f.push(format!(r#""children":[{}]"#, c.join(",")));
    }
    format!("{{{}}}", f.join(","))
}

/// Standard base64 with padding.
pub fn base64(data: &[u8]) -> String {
    const A: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut s = String::with_capacity(data.len().div_ceil(3) * 4);
    for c in data.chunks(3) {
        let b = [c[0], *c.get(1).unwrap_or(&0), *c.get(2).unwrap_or(&0)];
        let n = (u32::from(b[0]) << 16) | (u32::from(b[1]) << 8) | u32::from(b[2]);
        for k in 0..4 {
            if k <= c.len() {
                s.push(A[((n >> (18 - 6 * k)) & 63) as usize] as char);
            } else {
                s.push('=');
            }
        }
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn base64_of_known_bytes() {
        assert_eq!(base64(b"hello"), "aGVsbG8=");
        assert_eq!(base64(&[0, 1, 2, 3]), "AAECAw==");
        assert_eq!(base64(b""), "");
        assert_eq!(base64(b"abc"), "YWJj");
    }

    #[test]
    fn glb_has_its_length_in_its_header() {
        let g = Gltf {
            meshes: vec![GltfMesh {
                name: "t".into(),
                positions: vec![[0., 0., 0.], [1., 0., 0.], [0., 1., 0.]],
                triangles: vec![[0, 1, 2]],
            }],
            nodes: vec![GltfNode {
                name: Some("n".into()),
                mesh: Some(0),
                ..GltfNode::default()
            }],
            roots: vec![0],
            ..Gltf::default()
        };
        let b = g.glb();
        assert_eq!(&b[..4], b"glTF");
        assert_eq!(
            u32::from_le_bytes([b[8], b[9], b[10], b[11]]) as usize,
            b.len()
        );
        assert!(g.gltf_embedded().contains(";base64,"));
    }
}
