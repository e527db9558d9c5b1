//! The ZIP container of 3MF files, read just enough: the central directory, and a named
//! entry stored or deflated, inflated under a size limit checked while inflating (a zip bomb
//! stops at the limit, not at the memory's end) and checked against its CRC-32.
//!
//! Written here rather than taken from the `zip` crate: 3MF needs this much and no more,
//! and every length is checked against the bytes present, each error naming the byte.

use std::path::Path;

use crate::error::{Error, Location, Result};

/// The end of central directory record's signature.
const EOCD: u32 = 0x0605_4b50;
/// A central directory entry's signature.
const CENTRAL: u32 = 0x0201_4b50;
/// A local file header's signature.
const LOCAL: u32 = 0x0403_4b50;

/// One entry of the central directory.
#[derive(Debug, Clone)]
pub(super) struct Entry {
    /// The entry's name (a part name without its leading `/`).
    pub name: String,
    method: u16,
    flags: u16,
    crc: u32,
    packed: u64,
    size: u64,
    /// Where its local header is.
    local: u64,
}

/// An archive in memory: its bytes and its entries.
pub(super) struct Archive<'b> {
    file: &'b Path,
    bytes: &'b [u8],
    /// The entries, in central directory order.
    pub entries: Vec<Entry>,
}

/// The little-endian u16 at `at`, if in range.
fn u16_at(b: &[u8], at: usize) -> Option<u16> {
    Some(u16::from_le_bytes(b.get(at..at + 2)?.try_into().ok()?))
}

/// The little-endian u32 at `at`, if in range.
fn u32_at(b: &[u8], at: usize) -> Option<u32> {
    Some(u32::from_le_bytes(b.get(at..at + 4)?.try_into().ok()?))
}

impl<'b> Archive<'b> {
    /// The archive in `bytes` (the file `file`), its central directory read and checked.
    pub(super) fn open(file: &'b Path, bytes: &'b [u8]) -> Result<Archive<'b>> {
        let err = |at: usize, msg: &str| Error::invalid(Location::byte(file, at as u64), msg);
        let eocd = find_eocd(bytes).ok_or_else(|| {
            err(
                0,
                "not a ZIP archive (no end of central directory record); a 3MF file is a ZIP",
            )
        })?;
        let short = || err(eocd, "truncated end of central directory record");
        let count = u16_at(bytes, eocd + 10).ok_or_else(short)?;
        let cd_size = u32_at(bytes, eocd + 12).ok_or_else(short)?;
        let cd_off = u32_at(bytes, eocd + 16).ok_or_else(short)?;
        if count == 0xFFFF || cd_off == 0xFFFF_FFFF || cd_size == 0xFFFF_FFFF {
            return Err(err(eocd, "ZIP64 archives are not read"));
        }
        let cd_end = cd_off as u64 + cd_size as u64;
        if cd_end > eocd as u64 {
            return Err(err(
                eocd,
                "the central directory lies beyond the end of the archive",
            ));
        }
        let mut entries = Vec::new();
        let mut at = cd_off as usize;
        for _ in 0..count {
            let (entry, next) = central_entry(bytes, at)
                .ok_or_else(|| err(at, "a bad central directory entry (signature or lengths)"))?;
            if next as u64 > cd_end {
                return Err(err(at, "a central directory entry runs past the directory"));
            }
            entries.push(entry);
            at = next;
        }
        Ok(Archive {
            file,
            bytes,
            entries,
        })
    }

    /// The entry named `name` (ASCII case ignored, as part names are compared), if any.
    pub(super) fn find(&self, name: &str) -> Option<&Entry> {
        let name = name.trim_start_matches('/');
        self.entries
            .iter()
            .find(|e| e.name.eq_ignore_ascii_case(name))
    }

    /// The contents of `e`, of at most `limit` bytes once inflated.
    pub(super) fn read(&self, e: &Entry, limit: u64) -> Result<Vec<u8>> {
        let at = e.local as usize;
        let err = |msg: String| {
            Error::invalid(
                Location::byte(self.file, at as u64),
                format!("/{}: {msg}", e.name),
            )
        };
        if e.flags & 1 != 0 {
            return Err(err("the entry is encrypted".into()));
        }
        if e.size > limit {
            return Err(err(format!(
                "it is {} bytes once inflated, more than the limit of {limit}",
                e.size
            )));
        }
        let b = self.bytes;
        let bad_local = || err("a bad local header (signature or lengths)".into());
        if u32_at(b, at) != Some(LOCAL) {
            return Err(bad_local());
        }
        let n = u16_at(b, at + 26).ok_or_else(bad_local)? as usize;
        let x = u16_at(b, at + 28).ok_or_else(bad_local)? as usize;
        let start = at + 30 + n + x;
        let data = start
            .checked_add(e.packed as usize)
            .and_then(|end| b.get(start..end))
            .ok_or_else(|| {
                err(format!(
                    "its {} packed bytes run past the end of the file",
                    e.packed
                ))
            })?;
        let out = match e.method {
            0 => data.to_vec(),
            8 => miniz_oxide::inflate::decompress_to_vec_with_limit(data, e.size as usize)
                .map_err(|x| {
                    let why = match x.status {
                        miniz_oxide::inflate::TINFLStatus::HasMoreOutput => format!(
                            "it inflates to more than the {} bytes its header says",
                            e.size
                        ),
                        s => format!("bad deflate data ({s:?})"),
                    };
                    err(why)
                })?,
            m => {
                return Err(err(format!(
                    "compression method {m} is not read (only stored and deflated)"
                )))
            }
        };
        if out.len() as u64 != e.size {
            return Err(err(format!(
                "it has {} bytes, its header says {}",
                out.len(),
                e.size
            )));
        }
        if crc32(&out) != e.crc {
            return Err(err(
                "its CRC-32 does not match: the archive is damaged".into()
            ));
        }
        Ok(out)
    }
}

/// The central directory entry at `at` and where the next one starts.
fn central_entry(b: &[u8], at: usize) -> Option<(Entry, usize)> {
    if u32_at(b, at)? != CENTRAL {
        return None;
    }
    let n = u16_at(b, at + 28)? as usize;
    let x = u16_at(b, at + 30)? as usize;
    let c = u16_at(b, at + 32)? as usize;
    let name = b.get(at + 46..at + 46 + n)?;
    let entry = Entry {
        name: String::from_utf8_lossy(name).into_owned(),
        flags: u16_at(b, at + 8)?,
        method: u16_at(b, at + 10)?,
        crc: u32_at(b, at + 16)?,
        packed: u64::from(u32_at(b, at + 20)?),
        size: u64::from(u32_at(b, at + 24)?),
        local: u64::from(u32_at(b, at + 42)?),
    };
    Some((entry, at + 46 + n + x + c))
}

/// Where the end of central directory record starts (searched back over a comment).
fn find_eocd(b: &[u8]) -> Option<usize> {
    let last = b.len().checked_sub(22)?;
    let first = last.saturating_sub(0xFFFF);
    (first..=last).rev().find(|&i| {
        u32_at(b, i) == Some(EOCD) && u16_at(b, i + 20).map(usize::from) == Some(b.len() - i - 22)
    })
}

/// The CRC-32 (IEEE) of `data`.
pub(crate) fn crc32(data: &[u8]) -> u32 {
    let table: Vec<u32> = (0..256u32)
        .map(|mut c| {
            for _ in 0..8 {
                c = if c & 1 != 0 {
                    0xEDB8_8320 ^ (c >> 1)
                } else {
                    c >> 1
                };
            }
            c
        })
        .collect();
    let mut crc = !0u32;
    for &x in data {
        crc = table[((crc ^ u32::from(x)) & 0xFF) as usize] ^ (crc >> 8);
    }
    !crc
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn crc32_of_known_strings() {
        assert_eq!(crc32(b""), 0);
        assert_eq!(crc32(b"123456789"), 0xCBF4_3926);
    }

    #[test]
    fn not_a_zip_is_refused() {
        let e = Archive::open(Path::new("a.3mf"), b"hello, this is not a zip file at all")
            .err()
            .unwrap()
            .to_string();
        assert!(e.starts_with("a.3mf: byte 0: not a ZIP archive"), "{e}");
    }
}
