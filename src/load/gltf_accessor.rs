//! glTF accessors read: vertex positions (FLOAT VEC3) and vertex indices (unsigned SCALAR),
//! every range checked against the buffer view and the buffer before a byte is read.

use super::gltf_buffers::Buffers;
use super::gltf_json::J;
use super::mesh_file::coord_problem;
use crate::error::Result;
use crate::geom::P3;

/// The component types of glTF accessors.
const BYTE: u64 = 5120;
const UNSIGNED_BYTE: u64 = 5121;
const SHORT: u64 = 5122;
const UNSIGNED_SHORT: u64 = 5123;
const UNSIGNED_INT: u64 = 5125;
const FLOAT: u64 = 5126;

/// The document's accessor, buffer view and buffer arrays.
pub(super) struct Arrays<'a> {
    /// `accessors`.
    pub accessors: Vec<J<'a>>,
    /// `bufferViews`.
    pub views: Vec<J<'a>>,
    /// `buffers`.
    pub buffers: Vec<J<'a>>,
}

/// An accessor's elements located in its buffer: `count` elements of `size` bytes, `stride`
/// apart, the first at `start`.
struct Located<'b> {
    bytes: &'b [u8],
    start: usize,
    stride: usize,
    size: usize,
    count: usize,
}

impl Located<'_> {
    /// The bytes of element `k`.
    fn element(&self, k: usize) -> &[u8] {
        let at = self.start + k * self.stride;
        &self.bytes[at..at + self.size]
    }
}

/// The accessor `acc` (`accessors[i]`), checked to be of `ty` with a component type among
/// `types`: its component type and its elements located in the buffer.
fn locate<'b>(
    acc: &J,
    ty: &str,
    types: &[u64],
    arrays: &Arrays,
    buffers: &'b mut Buffers,
) -> Result<(u64, Located<'b>)> {
    if let Some(s) = acc.get("sparse") {
        return Err(s.err("sparse accessors are not supported"));
    }
    let t = acc.req("type")?;
    if t.str()? != ty {
        return Err(t.err(format!("expected \"{ty}\", found \"{}\"", t.str()?)));
    }
    let ct = acc.req("componentType")?;
    let comp = ct.uint()?;
    if !types.contains(&comp) {
        return Err(ct.err(format!(
            "component type {comp} is not read here (expected {})",
            names(types)
        )));
    }
    let count = acc.req("count")?.uint()?;
    let Some(view_j) = acc.get("bufferView") else {
        return Err(acc.err("an accessor without a bufferView (all zeros) is not supported"));
    };
    let view = &arrays.views[view_j.index("bufferViews", arrays.views.len())?];
    let buf_j = view.req("buffer")?;
    let b = buf_j.index("buffers", arrays.buffers.len())?;
    let size = comp_size(comp) * if ty == "VEC3" { 3 } else { 1 };
    let view_off = view.uint_or("byteOffset", 0)?;
    let view_len = view.req("byteLength")?.uint()?;
    let stride = match view.get("byteStride") {
        Some(s) => {
            let v = s.uint()?;
            if !(4..=252).contains(&v) || v % 4 != 0 || v < size {
                return Err(s.err(format!(
                    "byte stride {v} is not a multiple of 4 in 4..252 of at least the element size {size}"
                )));
            }
            v
        }
        None => size,
    };
    let acc_off = acc.uint_or("byteOffset", 0)?;
    // The accessor's last byte within the view, and the view's within the buffer.
    let span = (count > 0).then(|| {
        (count - 1)
            .checked_mul(stride)
            .and_then(|x| x.checked_add(acc_off))
            .and_then(|x| x.checked_add(size))
    });
    let end = match span {
        None => acc_off,
        Some(Some(e)) => e,
        Some(None) => u64::MAX,
    };
    if end > view_len {
        return Err(acc.err(format!(
            "{count} elements of {size} bytes, {stride} apart from byte {acc_off}, need {end} bytes; \
             bufferView {} has {view_len}",
            view_j.v
        )));
    }
    let bytes = buffers.get(b, &arrays.buffers[b])?;
    let view_end = view_off.saturating_add(view_len);
    if view_end > bytes.len() as u64 {
        return Err(view.err(format!(
            "bytes {view_off}..{view_end} of buffer {b}, which has {} bytes",
            bytes.len()
        )));
    }
    let located = Located {
        bytes,
        start: (view_off + acc_off) as usize,
        stride: stride as usize,
        size: size as usize,
        count: count as usize,
    };
    Ok((comp, located))
}

/// Bytes per component of type `comp`.
fn comp_size(comp: u64) -> u64 {
    match comp {
        BYTE | UNSIGNED_BYTE => 1,
        SHORT | UNSIGNED_SHORT => 2,
        _ => 4,
    }
}

/// The component types `types` named for a message.
fn names(types: &[u64]) -> String {
    let name = |t: &u64| match *t {
        UNSIGNED_BYTE => "5121 UNSIGNED_BYTE",
        UNSIGNED_SHORT => "5123 UNSIGNED_SHORT",
        UNSIGNED_INT => "5125 UNSIGNED_INT",
        FLOAT => "5126 FLOAT",
        _ => "?",
    };
    types.iter().map(name).collect::<Vec<_>>().join(", ")
}

/// The positions of the accessor `acc` (FLOAT VEC3, finite and within the coordinate limit).
pub(super) fn positions(acc: &J, arrays: &Arrays, buffers: &mut Buffers) -> Result<Vec<P3>> {
    let (comp, at) = locate(acc, "VEC3", &[FLOAT, UNSIGNED_BYTE, UNSIGNED_SHORT], arrays, buffers)
        .and_then(|(c, l)| {
            if c == FLOAT {
                Ok((c, l))
            } else {
                Err(acc.req("componentType")?.err(
                    "positions must be FLOAT (5126); quantized positions (KHR_mesh_quantization) are not read",
                ))
            }
        })?;
    debug_assert_eq!(comp, FLOAT);
    let mut out = Vec::with_capacity(at.count);
    for k in 0..at.count {
        let e = at.element(k);
        let mut c = [0.0f64; 3];
        for (i, slot) in c.iter_mut().enumerate() {
            let mut b = [0u8; 4];
            b.copy_from_slice(&e[4 * i..4 * i + 4]);
            let x = f64::from(f32::from_le_bytes(b));
            if let Some(problem) = coord_problem(x) {
                return Err(acc.err(format!("position {k}: {problem}")));
            }
            *slot = x;
        }
        out.push(P3::new(c[0], c[1], c[2]));
    }
    Ok(out)
}

/// The indices of the accessor `acc` (an unsigned SCALAR), each below `vertices`.
pub(super) fn indices(
    acc: &J,
    vertices: usize,
    arrays: &Arrays,
    buffers: &mut Buffers,
) -> Result<Vec<u32>> {
    let types = [UNSIGNED_BYTE, UNSIGNED_SHORT, UNSIGNED_INT];
    let (comp, at) = locate(acc, "SCALAR", &types, arrays, buffers)?;
    let mut out = Vec::with_capacity(at.count);
    for k in 0..at.count {
        let e = at.element(k);
        let i = match comp {
            UNSIGNED_BYTE => u32::from(e[0]),
            UNSIGNED_SHORT => u32::from(u16::from_le_bytes([e[0], e[1]])),
            _ => u32::from_le_bytes([e[0], e[1], e[2], e[3]]),
        };
        if i as usize >= vertices {
            return Err(acc.err(format!(
                "index {k} is {i}, but the positions have only {vertices} vertices"
            )));
        }
        out.push(i);
    }
    Ok(out)
}
