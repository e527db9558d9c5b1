//! A glTF mesh read into one polygon mesh: its triangle primitives (lists, strips and fans,
//! indexed or not) joined, vertices in order of first use as an OBJ group's are.

use super::gltf_accessor::{indices, positions, Arrays};
use super::gltf_buffers::Buffers;
use super::gltf_json::J;
use crate::error::Result;
use crate::geom::PolyMesh;

/// The primitive modes.
const TRIANGLES: u64 = 4;
const TRIANGLE_STRIP: u64 = 5;
const TRIANGLE_FAN: u64 = 6;

/// What a mesh's reading left out, for the load's one note about it.
#[derive(Debug, Default)]
pub(super) struct Skipped {
    /// Point and line primitives.
    pub lines: usize,
    /// Morph targets.
    pub targets: usize,
}

/// The triangles of the glTF mesh `mesh` (`meshes[i]`) as one polygon mesh (no faces when
/// it has no triangle primitive).
pub(super) fn read_mesh(
    mesh: &J,
    arrays: &Arrays,
    buffers: &mut Buffers,
    skipped: &mut Skipped,
) -> Result<PolyMesh> {
    let mut out = PolyMesh::default();
    let prims = mesh.req("primitives")?.items()?;
    for p in &prims {
        let mode_j = p.get("mode");
        let mode = mode_j.as_ref().map_or(Ok(TRIANGLES), J::uint)?;
        match mode {
            0..=3 => {
                skipped.lines += 1;
                continue;
            }
            TRIANGLES | TRIANGLE_STRIP | TRIANGLE_FAN => {}
            m => {
                let at = mode_j.as_ref().unwrap_or(p);
                return Err(at.err(format!("unknown primitive mode {m}")));
            }
        }
        if p.get("targets").is_some() {
            skipped.targets += 1;
        }
        primitive(p, mode, arrays, buffers, &mut out)?;
    }
    Ok(out)
}

/// Appends the triangles of primitive `p` of `mode` to `out`.
fn primitive(
    p: &J,
    mode: u64,
    arrays: &Arrays,
    buffers: &mut Buffers,
    out: &mut PolyMesh,
) -> Result<()> {
    let pos_j = p.req("attributes")?.req("POSITION")?;
    let acc = &arrays.accessors[pos_j.index("accessors", arrays.accessors.len())?];
    let pts = positions(acc, arrays, buffers)?;
    let idx = match p.get("indices") {
        Some(i) => {
            let acc = &arrays.accessors[i.index("accessors", arrays.accessors.len())?];
            indices(acc, pts.len(), arrays, buffers)?
        }
        None => (0..pts.len() as u32).collect(),
    };
    if mode == TRIANGLES && idx.len() % 3 != 0 {
        return Err(p.err(format!(
            "a TRIANGLES primitive with {} vertices, not a multiple of 3",
            idx.len()
        )));
    }
    // Each position's vertex in `out`, given at its first use.
    let mut slot = vec![u32::MAX; pts.len()];
    let mut corner = |i: u32, out: &mut PolyMesh| -> Result<u32> {
        let s = &mut slot[i as usize];
        if *s == u32::MAX {
            if out.vertices.len() >= u32::MAX as usize - 1 {
                return Err(p.err("too many vertices"));
            }
            *s = out.vertices.len() as u32;
            out.vertices.push(pts[i as usize]);
        }
        Ok(*s)
    };
    for t in triangles(mode, &idx) {
        let f = [corner(t[0], out)?, corner(t[1], out)?, corner(t[2], out)?];
        out.faces.push(f.to_vec());
    }
    Ok(())
}

/// The triangles of a primitive of `mode` over the vertex sequence `idx` (strips and fans
/// alternate or keep their winding as glTF says; a strip's or fan's triangles with a repeated
/// vertex, used there to join pieces, are left out).
fn triangles(mode: u64, idx: &[u32]) -> Vec<[u32; 3]> {
    let n = idx.len();
    match mode {
        TRIANGLES => idx.chunks_exact(3).map(|t| [t[0], t[1], t[2]]).collect(),
        TRIANGLE_STRIP => (0..n.saturating_sub(2))
            .map(|i| {
                if i % 2 == 0 {
                    [idx[i], idx[i + 1], idx[i + 2]]
                } else {
                    [idx[i + 1], idx[i], idx[i + 2]]
                }
            })
            .filter(|t| t[0] != t[1] && t[1] != t[2] && t[0] != t[2])
            .collect(),
        _ => (1..n.saturating_sub(1))
            .map(|i| [idx[i], idx[i + 1], idx[0]])
            .filter(|t| t[0] != t[1] && t[1] != t[2] && t[0] != t[2])
            .collect(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn strips_and_fans_keep_their_winding() {
        assert_eq!(
            triangles(TRIANGLES, &[0, 1, 2, 2, 1, 3]),
            [[0, 1, 2], [2, 1, 3]]
        );
        // A strip of a quad 0 1 2 3: (0,1,2) then (2,1,3), both counter-clockwise.
        assert_eq!(
            triangles(TRIANGLE_STRIP, &[0, 1, 2, 3]),
            [[0, 1, 2], [2, 1, 3]]
        );
        assert_eq!(
            triangles(TRIANGLE_STRIP, &[0, 1, 2, 2, 3, 4]),
            [[0, 1, 2], [3, 2, 4]]
        );
        assert_eq!(
            triangles(TRIANGLE_FAN, &[0, 1, 2, 3]),
            [[1, 2, 0], [2, 3, 0]]
        );
        assert!(triangles(TRIANGLE_FAN, &[0, 1]).is_empty());
    }
}
