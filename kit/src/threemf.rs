//! A small 3MF writer for tests: objects (meshes or components) and build items as the model
//! part's XML, packed in a stored (uncompressed) ZIP with the package's relationships.

use std::fmt::Write as _;

/// One `<object>`: a mesh, or components placing other objects.
#[derive(Debug, Clone, Default)]
pub struct ThreeMfObject {
    /// The object's id.
    pub id: u32,
    /// Its `name` attribute, if any.
    pub name: Option<String>,
    /// Vertices of its mesh (empty for an object of components).
    pub vertices: Vec<[f64; 3]>,
    /// Triangles of its mesh.
    pub triangles: Vec<[u32; 3]>,
    /// Components: an object id and a transform (12 numbers, 3MF's row-vector order).
    pub components: Vec<(u32, Option<[f64; 12]>)>,
}

/// XML text with `&`, `<`, `>` and `"` escaped.
fn esc(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

/// The ` transform="..."` attribute of `t` (nothing for None).
fn transform_attr(t: &Option<[f64; 12]>) -> String {
    match t {
        None => String::new(),
        Some(t) => {
            let v: Vec<String> = t.iter().map(|x| format!("{x}")).collect();
            format!(r#" transform="{}""#, v.join(" "))
        }
    }
}

/// The model part: `objects` as resources, `items` (object id, transform) as the build.
pub fn model_xml(objects: &[ThreeMfObject], items: &[(u32, Option<[f64; 12]>)]) -> String {
    let mut s = String::from(
        "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<model unit=\"millimeter\" xml:lang=\"en-US\" \
         xmlns=\"http://schemas.microsoft.com/3dmanufacturing/core/2015/02\">\n<resources>\n",
    );
    for o in objects {
        let name = o
            .name
            .as_ref()
            .map_or(String::new(), |n| format!(r#" name="{}""#, esc(n)));
        let _ = writeln!(s, r#"<object id="{}"{name} type="model">"#, o.id);
        if o.components.is_empty() {
            s.push_str("<mesh>\n<vertices>\n");
            for v in &o.vertices {
                let _ = writeln!(s, r#"<vertex x="{}" y="{}" z="{}"/>"#, v[0], v[1], v[2]);
            }
            s.push_str("</vertices>\n<triangles>\n");
            for t in &o.triangles {
                let _ = writeln!(
                    s,
                    r#"<triangle v1="{}" v2="{}" v3="{}"/>"#,
                    t[0], t[1], t[2]
                );
            }
            s.push_str("</triangles>\n</mesh>\n");
        } else {
            s.push_str("<components>\n");
            for (id, t) in &o.components {
                let _ = writeln!(s, r#"<component objectid="{id}"{}/>"#, transform_attr(t));
            }
            s.push_str("</components>\n");
        }
        s.push_str("</object>\n");
    }
    s.push_str("</resources>\n<build>\n");
    for (id, t) in items {
        let _ = writeln!(s, r#"<item objectid="{id}"{}/>"#, transform_attr(t));
    }
    s.push_str("</build>\n</model>\n");
    s
}

/// A 3MF package holding the model part `model` at `/3D/3dmodel.model`.
pub fn threemf(model: &str) -> Vec<u8> {
    let types = r#"<?xml version="1.0" encoding="UTF-8"?>
<Types xmlns="http://schemas.openxmlformats.org/package/2006/content-types"><Default Extension="rels" ContentType="application/vnd.openxmlformats-package.relationships+xml"/><Default Extension="model" ContentType="application/vnd.ms-package.3dmanufacturing-3dmodel+xml"/></Types>"#;
    let rels = r#"<?xml version="1.0" encoding="UTF-8"?>
<Relationships xmlns="http://schemas.openxmlformats.org/package/2006/relationships"><Relationship Target="/3D/3dmodel.model" Id="rel0" Type="http://schemas.microsoft.com/3dmanufacturing/2013/01/3dmodel"/></Relationships>"#;
    zip_stored(&[
        ("[Content_Types].xml", types.as_bytes()),
        ("_rels/.rels", rels.as_bytes()),
        ("3D/3dmodel.model", model.as_bytes()),
    ])
}

/// A ZIP archive of `entries` (name, contents), stored without compression.
pub fn zip_stored(entries: &[(&str, &[u8])]) -> Vec<u8> {
    let mut out = Vec::new();
    let mut central = Vec::new();
    for (name, data) in entries {
        let off = out.len() as u32;
        let crc = crc32(data);
        let local = |sig: u32, out: &mut Vec<u8>| {
            out.extend_from_slice(&sig.to_le_bytes());
        };
        local(0x0403_4b50, &mut out);
        out.extend_from_slice(&[20, 0, 0, 0, 0, 0, 0, 0, 0, 0]);
        out.extend_from_slice(&crc.to_le_bytes());
        out.extend_from_slice(&(data.len() as u32).to_le_bytes());
        out.extend_from_slice(&(data.len() as u32).to_le_bytes());
        out.extend_from_slice(&(name.len() as u16).to_le_bytes());
        out.extend_from_slice(&0u16.to_le_bytes());
        out.extend_from_slice(name.as_bytes());
        out.extend_from_slice(data);
        local(0x0201_4b50, &mut central);
        central.extend_from_slice(&[20, 0, 20, 0, 0, 0, 0, 0, 0, 0, 0, 0]);
        central.extend_from_slice(&crc.to_le_bytes());
        central.extend_from_slice(&(data.len() as u32).to_le_bytes());
        central.extend_from_slice(&(data.len() as u32).to_le_bytes());
        central.extend_from_slice(&(name.len() as u16).to_le_bytes());
        central.extend_from_slice(&[0; 12]);
        central.extend_from_slice(&off.to_le_bytes());
        central.extend_from_slice(name.as_bytes());
    }
    let cd_off = out.len() as u32;
    out.extend_from_slice(&central);
    out.extend_from_slice(&0x0605_4b50u32.to_le_bytes());
    out.extend_from_slice(&[0, 0, 0, 0]);
    let n = entries.len() as u16;
    out.extend_from_slice(&n.to_le_bytes());
    out.extend_from_slice(&n.to_le_bytes());
    out.extend_from_slice(&(central.len() as u32).to_le_bytes());
    out.extend_from_slice(&cd_off.to_le_bytes());
    out.extend_from_slice(&0u16.to_le_bytes());
    out
}

/// The CRC-32 (IEEE) of `data`.
fn crc32(data: &[u8]) -> u32 {
    let mut crc = !0u32;
    for &x in data {
        crc ^= u32::from(x);
        for _ in 0..8 {
            crc = if crc & 1 != 0 {
                0xEDB8_8320 ^ (crc >> 1)
            } else {
                crc >> 1
            };
        }
    }
    !crc
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn crc_and_zip_layout() {
        assert_eq!(crc32(b"123456789"), 0xCBF4_3926);
        let z = zip_stored(&[("a.txt", b"hi")]);
        assert_eq!(&z[..4], &[0x50, 0x4b, 3, 4]);
        assert_eq!(&z[z.len() - 22..z.len() - 18], &[0x50, 0x4b, 5, 6]);
    }
}
