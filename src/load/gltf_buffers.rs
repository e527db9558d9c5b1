//! glTF's binary data: the .glb container (a header, then a JSON and a BIN chunk) and the
//! buffers a document names, from the GLB, from `data:` URIs (base64) or from files beside it.
//!
//! A buffer file is found as a scene file's mesh files are (docs/scene-format.md): relative
//! to the glTF file (or absolute), a regular file of bounded size, under `--include-root`
//! when one is given. Other URI schemes (`http:`, `file:`) are refused.

use std::borrow::Cow;
use std::path::{Path, PathBuf};

use super::gltf_json::J;
use crate::error::{Error, Location, Result};
use crate::progress::Progress;

/// "glTF", the GLB magic, little-endian.
const GLB_MAGIC: u32 = 0x4654_6C67;
/// The JSON chunk's type.
const CHUNK_JSON: u32 = 0x4E4F_534A;
/// The BIN chunk's type.
const CHUNK_BIN: u32 = 0x004E_4942;

/// True when `bytes` start as a GLB file does.
pub(super) fn is_glb(bytes: &[u8]) -> bool {
    bytes.len() >= 4 && u32_at(bytes, 0) == GLB_MAGIC
}

/// The little-endian u32 at `at` (which the caller has checked is in range).
fn u32_at(bytes: &[u8], at: usize) -> u32 {
    let mut b = [0u8; 4];
    b.copy_from_slice(&bytes[at..at + 4]);
    u32::from_le_bytes(b)
}

/// The JSON chunk and the BIN chunk (if any) of a GLB file; every length checked against the
/// bytes present, errors at the byte where the header or chunk is.
pub(super) fn split_glb<'b>(path: &Path, bytes: &'b [u8]) -> Result<(&'b [u8], Option<&'b [u8]>)> {
    let err = |at: usize, msg: String| Error::invalid(Location::byte(path, at as u64), msg);
    if bytes.len() < 12 {
        return Err(err(
            0,
            format!(
                "GLB header: the file has {} bytes, a header needs 12",
                bytes.len()
            ),
        ));
    }
    let version = u32_at(bytes, 4);
    if version != 2 {
        return Err(err(
            4,
            format!("GLB header: version {version}, only glTF 2 is read"),
        ));
    }
    let length = u32_at(bytes, 8) as usize;
    if length != bytes.len() {
        return Err(err(
            8,
            format!(
                "GLB header: the length field says {length} bytes, the file has {}",
                bytes.len()
            ),
        ));
    }
    let mut at = 12;
    let mut chunks: Vec<(u32, &[u8], usize)> = Vec::new();
    while at < bytes.len() {
        if bytes.len() - at < 8 {
            return Err(err(at, "GLB chunk: truncated chunk header".into()));
        }
        let len = u32_at(bytes, at) as usize;
        let kind = u32_at(bytes, at + 4);
        let start = at + 8;
        if len > bytes.len() - start {
            return Err(err(
                at,
                format!(
                    "GLB chunk {}: its length is {len} bytes, only {} follow",
                    chunks.len(),
                    bytes.len() - start
                ),
            ));
        }
        chunks.push((kind, &bytes[start..start + len], at));
        at = start + len;
    }
    let Some(&(kind, json, _)) = chunks.first() else {
        return Err(err(12, "GLB: no JSON chunk".into()));
    };
    if kind != CHUNK_JSON {
        return Err(err(12, "GLB: the first chunk is not the JSON chunk".into()));
    }
    let bin = match chunks.get(1) {
        Some(&(CHUNK_BIN, b, _)) => Some(b),
        Some(&(_, _, at)) => {
            return Err(err(at, "GLB: the second chunk is not a BIN chunk".into()));
        }
        None => None,
    };
    Ok((json, bin))
}

/// The buffers of one document, each loaded when first used.
pub(super) struct Buffers<'a> {
    /// The glTF file.
    file: &'a Path,
    /// The GLB's BIN chunk, if any.
    bin: Option<&'a [u8]>,
    /// The canonical `--include-root`, if given.
    root: Option<PathBuf>,
    /// Buffers loaded so far, by index.
    loaded: Vec<Option<Cow<'a, [u8]>>>,
    /// Where the load is.
    progress: &'a Progress,
}

impl<'a> Buffers<'a> {
    /// The buffers of `file` (with its GLB BIN chunk, if any), `count` of them.
    pub(super) fn new(
        file: &'a Path,
        bin: Option<&'a [u8]>,
        root: Option<PathBuf>,
        count: usize,
        progress: &'a Progress,
    ) -> Self {
        Buffers {
            file,
            bin,
            root,
            loaded: (0..count).map(|_| None).collect(),
            progress,
        }
    }

    /// The bytes of buffer `i` (described by `buf`, `buffers[i]`), at least its `byteLength`
    /// of them (exactly that many are returned).
    pub(super) fn get(&mut self, i: usize, buf: &J) -> Result<&[u8]> {
        if self.loaded[i].is_none() {
            let b = self.load(i, buf)?;
            self.loaded[i] = Some(b);
        }
        Ok(self.loaded[i].as_deref().unwrap_or_default())
    }

    /// Loads buffer `i`: its bytes cut to its `byteLength`.
    fn load(&self, i: usize, buf: &J) -> Result<Cow<'a, [u8]>> {
        let len = buf.req("byteLength")?;
        let want = len.uint()?;
        let (bytes, from): (Cow<'a, [u8]>, String) = match buf.get("uri") {
            None => match (i, self.bin) {
                (0, Some(b)) => (Cow::Borrowed(b), "the GLB's BIN chunk".into()),
                _ => {
                    return Err(buf.err(
                        "the buffer has no uri (only buffer 0 of a .glb may use its BIN chunk)",
                    ))
                }
            },
            Some(uri) => {
                let u = uri.str()?;
                match u.strip_prefix("data:") {
                    Some(data) => (Cow::Owned(data_uri(&uri, data)?), "its data URI".into()),
                    None => {
                        let (b, p) = self.file_buffer(&uri, u)?;
                        (Cow::Owned(b), p.display().to_string())
                    }
                }
            }
        };
        if (bytes.len() as u64) < want {
            return Err(len.err(format!(
                "the buffer should have {want} bytes, {from} has only {}",
                bytes.len()
            )));
        }
        Ok(match bytes {
            Cow::Borrowed(b) => Cow::Borrowed(&b[..want as usize]),
            Cow::Owned(mut b) => {
                b.truncate(want as usize);
                Cow::Owned(b)
            }
        })
    }

    /// The bytes of the file a buffer's relative `uri` names, and its path.
    fn file_buffer(&self, uri: &J, u: &str) -> Result<(Vec<u8>, PathBuf)> {
        if has_scheme(u) {
            return Err(uri.err(format!(
                "{}: only relative file paths and data: URIs are read",
                crate::scene::names::printable(u)
            )));
        }
        let rel = percent_decode(u).ok_or_else(|| uri.err("a bad %-escape in the URI"))?;
        let dir = self.file.parent().unwrap_or(Path::new(""));
        let path = dir.join(&rel);
        let canonical = std::fs::canonicalize(&path).map_err(|e| {
            let msg = format!("cannot read buffer file {}: {e}", path.display());
            Error::Io(
                Location::file(self.file),
                std::io::Error::new(e.kind(), format!("{}: {msg}", uri.path)),
            )
        })?;
        let at = Location::file(self.file);
        super::confine::check_under(self.root.as_deref(), &path, &canonical, &at).map_err(|e| {
            match e {
                Error::Invalid(_, m) => uri.err(m),
                e => e,
            }
        })?;
        const MAX: u64 = super::read::MAX_MESH_BYTES;
        let bytes = super::read::read_file(&path, None, MAX, self.progress.count())
            .map_err(|e| uri.err(e))?;
        Ok((bytes, path))
    }
}

/// True when `u` starts with a URI scheme (`http:`, `file:`, ...), not a relative path.
fn has_scheme(u: &str) -> bool {
    let Some(colon) = u.find(':') else {
        return false;
    };
    let scheme = &u[..colon];
    scheme.len() > 1
        && scheme.starts_with(|c: char| c.is_ascii_alphabetic())
        && scheme
            .chars()
            .all(|c| c.is_ascii_alphanumeric() || "+-.".contains(c))
}

/// `u` with its `%XX` escapes decoded (None for a bad escape or bytes that are not UTF-8).
fn percent_decode(u: &str) -> Option<String> {
    let b = u.as_bytes();
    let mut out = Vec::with_capacity(b.len());
    let mut i = 0;
    while i < b.len() {
        if b[i] == b'%' {
            let hex = std::str::from_utf8(b.get(i + 1..i + 3)?).ok()?;
            out.push(u8::from_str_radix(hex, 16).ok()?);
            i += 3;
        } else {
            out.push(b[i]);
            i += 1;
        }
    }
    String::from_utf8(out).ok()
}

/// The bytes of a `data:` URI's content `data` (after `data:`): base64 only.
fn data_uri(uri: &J, data: &str) -> Result<Vec<u8>> {
    let Some((_, b64)) = data.split_once(";base64,") else {
        return Err(uri.err("only base64 data URIs (data:...;base64,...) are read"));
    };
    base64(b64).map_err(|at| {
        uri.err(format!(
            "invalid base64 at character {at} of the data after ';base64,'"
        ))
    })
}

/// Decodes standard base64 (padding optional); the error is the offset of the first bad
/// character.
fn base64(s: &str) -> std::result::Result<Vec<u8>, usize> {
    let b = s.as_bytes();
    let body = b.len() - b.iter().rev().take(2).take_while(|&&c| c == b'=').count();
    if body % 4 == 1 {
        return Err(body);
    }
    let mut out = Vec::with_capacity(body / 4 * 3 + 2);
    let (mut acc, mut bits) = (0u32, 0u32);
    for (i, &c) in b[..body].iter().enumerate() {
        let v = match c {
            b'A'..=b'Z' => c - b'A',
            b'a'..=b'z' => c - b'a' + 26,
            b'0'..=b'9' => c - b'0' + 52,
            b'+' => 62,
            b'/' => 63,
            _ => return Err(i),
        };
        acc = (acc << 6) | u32::from(v);
        bits += 6;
        if bits >= 8 {
            bits -= 8;
            out.push((acc >> bits) as u8);
            acc &= (1 << bits) - 1;
        }
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn base64_decodes_and_locates_bad_characters() {
        assert_eq!(base64("aGVsbG8=").unwrap(), b"hello");
        assert_eq!(base64("aGVsbG8").unwrap(), b"hello");
        assert_eq!(base64("AAECAw==").unwrap(), [0, 1, 2, 3]);
        assert_eq!(base64("").unwrap(), b"");
        assert_eq!(base64("aGV*bG8="), Err(3));
        assert_eq!(base64("aGVsb"), Err(5));
    }

    #[test]
    fn uris() {
        assert!(has_scheme("http://x/y.bin"));
        assert!(has_scheme("file:///etc/passwd"));
        assert!(!has_scheme("a b.bin"));
        assert!(!has_scheme("C:x.bin") || cfg!(not(windows)));
        assert_eq!(percent_decode("a%20b.bin").unwrap(), "a b.bin");
        assert!(percent_decode("a%2").is_none());
        assert!(percent_decode("a%zz").is_none());
    }

    #[test]
    fn glb_lengths_are_checked() {
        let p = Path::new("m.glb");
        let mut g = Vec::new();
        g.extend_from_slice(b"glTF");
        g.extend_from_slice(&2u32.to_le_bytes());
        g.extend_from_slice(&28u32.to_le_bytes());
        g.extend_from_slice(&8u32.to_le_bytes());
        g.extend_from_slice(&CHUNK_JSON.to_le_bytes());
        g.extend_from_slice(b"{}      ");
        let (json, bin) = split_glb(p, &g).unwrap();
        assert_eq!(json, b"{}      ");
        assert!(bin.is_none());
        let mut bad = g.clone();
        bad[12] = 9;
        let e = split_glb(p, &bad).unwrap_err().to_string();
        assert_eq!(
            e,
            "m.glb: byte 12: GLB chunk 0: its length is 9 bytes, only 8 follow"
        );
        let e = split_glb(p, &g[..20]).unwrap_err().to_string();
        assert!(
            e.contains("the length field says 28 bytes, the file has 20"),
            "{e}"
        );
    }
}
