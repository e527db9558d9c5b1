//! STL loading, ASCII and binary: triangles welded into one indexed mesh by exact vertex equality.

use std::path::Path;

use super::mesh_file::{coord_problem, finish, stem_name, MeshFile, MeshGroup};
use super::text::{decode, Word, Words};
use crate::count::{Count, Cursor};
use crate::error::{Error, Location, Pos, Result};
use crate::geom::key_hash::KeyMap;
use crate::geom::P3;

/// Size of the binary header: 80 bytes of text and a little-endian u32 triangle count.
const HEADER: u64 = 84;
/// Size of one binary triangle: normal, three vertices (f32 each) and a u16 attribute.
const TRIANGLE: u64 = 50;

/// Parses an STL file, binary or ASCII, into one group named after the file stem.
///
/// The file is binary when its size is exactly `84 + 50 * count` (even if the header starts
/// with `solid`), ASCII when it starts with `solid` and holds text, and an error otherwise.
/// Facet normals are ignored. Vertices with bitwise-equal coordinates (after -0.0 becomes 0.0)
/// are shared.
///
/// # Errors
/// [`Error::Parse`] for malformed ASCII (at `file:line:col`) or a binary size that disagrees
/// with the triangle count (at the byte offset of the first incomplete triangle);
/// [`Error::Invalid`] for NaN or huge coordinates and facets with fewer than 3 vertices.
///
/// The bytes parsed go to `done` as it goes, once per step of bytes.
pub(crate) fn parse_stl(path: &Path, bytes: &[u8], done: Count) -> Result<MeshFile> {
    let len = bytes.len() as u64;
    let count = triangle_count(bytes);
    let mut cursor = Cursor::new(done);
    let group = match count {
        Some(n) if len == HEADER + TRIANGLE * n => binary(path, bytes, n, &mut cursor)?,
        _ if starts_with_solid(bytes) && !bytes.contains(&0) => ascii(path, bytes, &mut cursor)?,
        Some(n) => return Err(size_mismatch(path, len, n)),
        None if starts_with_solid(bytes) => {
            let nul = bytes.iter().position(|&b| b == 0).unwrap_or(0) as u64;
            return Err(Error::parse(
                Location::byte(path, nul),
                "NUL byte in an ASCII STL file",
            ));
        }
        None => {
            let msg = format!(
                "not an STL file: it does not start with 'solid' and its {len} bytes are too few for a binary STL header"
            );
            return Err(Error::parse(Location::byte(path, 0), msg));
        }
    };
    cursor.finish(bytes.len());
    finish(path, vec![group])
}

/// The triangle count of a binary header, if the file is long enough to have one.
fn triangle_count(bytes: &[u8]) -> Option<u64> {
    let b: [u8; 4] = bytes.get(80..84)?.try_into().ok()?;
    Some(u64::from(u32::from_le_bytes(b)))
}

/// Whether the file starts (after blanks) with the ASCII STL keyword `solid`, in any case.
fn starts_with_solid(bytes: &[u8]) -> bool {
    let start = bytes
        .iter()
        .position(|b| !b.is_ascii_whitespace())
        .unwrap_or(bytes.len());
    bytes
        .get(start..start + 5)
        .is_some_and(|k| k.eq_ignore_ascii_case(b"solid"))
}

/// The error for a binary STL whose size disagrees with its triangle count, at the first
/// incomplete triangle (truncated file) or at the first extra byte.
fn size_mismatch(path: &Path, len: u64, count: u64) -> Error {
    let need = HEADER + TRIANGLE * count;
    let msg = format!("file is {len} bytes, header says {count} triangles needing {need}");
    if len < need {
        let whole = (len - HEADER) / TRIANGLE;
        Error::parse(
            Location::byte(path, HEADER + TRIANGLE * whole),
            format!("{msg}: truncated binary STL"),
        )
    } else {
        Error::parse(
            Location::byte(path, need),
            format!("{msg}: trailing bytes after the last triangle"),
        )
    }
}

/// Reads `count` binary triangles (the size has been checked).
fn binary(path: &Path, bytes: &[u8], count: u64, cursor: &mut Cursor) -> Result<MeshGroup> {
    let mut welder = Welder::with_capacity(count as usize);
    let mut group = MeshGroup::new(stem_name(path));
    group.mesh.faces.reserve(count as usize);
    group.face_pos.reserve(count as usize);
    for t in 0..count {
        let off = HEADER + TRIANGLE * t;
        cursor.at(off as usize);
        let mut face = Vec::with_capacity(3);
        for v in 0..3 {
            let p = binary_vertex(path, bytes, off, v)?;
            let i = welder
                .index(p)
                .map_err(|_| Error::invalid(Location::byte(path, off), "too many vertices"))?;
            face.push(i);
        }
        group.mesh.faces.push(face);
        group.face_pos.push(Pos::Byte(off));
    }
    group.mesh.vertices = welder.vertices;
    Ok(group)
}

/// Vertex `v` (0..3) of the binary triangle at byte `off`, checked.
fn binary_vertex(path: &Path, bytes: &[u8], off: u64, v: u64) -> Result<P3> {
    let mut c = [0.0; 3];
    for (k, slot) in c.iter_mut().enumerate() {
        let at = (off + 12 + 12 * v + 4 * k as u64) as usize;
        let b: [u8; 4] = bytes
            .get(at..at + 4)
            .and_then(|s| s.try_into().ok())
            .ok_or_else(|| Error::parse(Location::byte(path, off), "truncated triangle"))?;
        let x = f64::from(f32::from_le_bytes(b));
        if let Some(problem) = coord_problem(x) {
            let t = (off - HEADER) / TRIANGLE;
            let msg = format!(
                "triangle {t}, vertex {v}, {}: {problem}",
                ["x", "y", "z"][k]
            );
            return Err(Error::invalid(Location::byte(path, off), msg));
        }
        *slot = x;
    }
    Ok(P3::new(c[0], c[1], c[2]))
}

/// Reads an ASCII STL: `solid`, facets, `endsolid` (several solids in a row are merged).
fn ascii(path: &Path, bytes: &[u8], cursor: &mut Cursor) -> Result<MeshGroup> {
    let text = decode(path, bytes, 1)?;
    let mut p = AsciiStl {
        path,
        words: Words::new(text, 1),
        welder: Welder::with_capacity(0),
        group: MeshGroup::new(stem_name(path)),
        face: Vec::new(),
    };
    p.expect("solid")?;
    p.words.next_line();
    loop {
        cursor.at(p.words.consumed());
        let w = p.next("'facet' or 'endsolid'")?;
        if is(w, "facet") {
            p.facet(w)?;
        } else if is(w, "endsolid") {
            p.words.next_line();
            match p.words.next_word() {
                None => break,
                Some(w) if is(w, "solid") => {
                    p.words.next_line();
                }
                Some(w) => return Err(p.unexpected(w, "'solid' or the end of the file")),
            }
        } else {
            return Err(p.unexpected(w, "'facet' or 'endsolid'"));
        }
    }
    p.group.mesh.vertices = p.welder.vertices;
    Ok(p.group)
}

/// Whether word `w` is keyword `k` (ASCII STL keywords are case-insensitive).
fn is(w: Word, k: &str) -> bool {
    w.text.eq_ignore_ascii_case(k)
}

/// The state of an ASCII STL parse.
struct AsciiStl<'a> {
    path: &'a Path,
    words: Words<'a>,
    welder: Welder,
    group: MeshGroup,
    /// Reused buffer of the current facet's vertex indices.
    face: Vec<u32>,
}

impl<'a> AsciiStl<'a> {
    /// The next word, or an end-of-file error saying what was `expected`.
    fn next(&mut self, expected: &str) -> Result<Word<'a>> {
        self.words.next_word().ok_or_else(|| {
            Error::parse(
                self.words.here(self.path),
                format!("unexpected end of file: expected {expected}"),
            )
        })
    }

    /// The error for word `w` where `expected` should be.
    fn unexpected(&self, w: Word, expected: &str) -> Error {
        Error::parse(
            w.loc(self.path),
            format!("expected {expected}, found '{}'", w.text.escape_debug()),
        )
    }

    /// Reads keyword `k` or fails.
    fn expect(&mut self, k: &str) -> Result<Word<'a>> {
        let quoted = format!("'{k}'");
        let w = self.next(&quoted)?;
        if is(w, k) {
            Ok(w)
        } else {
            Err(self.unexpected(w, &quoted))
        }
    }

    /// The rest of a facet after its `facet` keyword.
    fn facet(&mut self, facet: Word) -> Result<()> {
        self.expect("normal")?;
        for _ in 0..3 {
            self.next("a normal component")?;
        }
        self.expect("outer")?;
        self.expect("loop")?;
        self.face.clear();
        loop {
            let w = self.next("'vertex' or 'endloop'")?;
            if is(w, "vertex") {
                if self.face.len() == 3 {
                    return Err(Error::invalid(
                        w.loc(self.path),
                        "a fourth vertex: an ASCII STL facet is a triangle (3 vertices)",
                    ));
                }
                let p = self.point()?;
                let i = self
                    .welder
                    .index(p)
                    .map_err(|_| Error::invalid(w.loc(self.path), "too many vertices"))?;
                self.face.push(i);
            } else if is(w, "endloop") {
                break;
            } else {
                return Err(self.unexpected(w, "'vertex' or 'endloop'"));
            }
        }
        self.expect("endfacet")?;
        let n = self.face.len();
        if n < 3 {
            let msg = format!("facet has {n} vertices; a facet is a triangle (3 vertices)");
            return Err(Error::invalid(facet.loc(self.path), msg));
        }
        self.group.mesh.faces.push(self.face.clone());
        self.group.face_pos.push(facet.pos());
        Ok(())
    }

    /// Three checked coordinates.
    fn point(&mut self) -> Result<P3> {
        let mut c = [0.0; 3];
        for slot in &mut c {
            let w = self.next("a coordinate")?;
            let x: f64 = w.text.parse().map_err(|_| {
                Error::parse(
                    w.loc(self.path),
                    format!("invalid number '{}'", w.text.escape_debug()),
                )
            })?;
            if let Some(problem) = coord_problem(x) {
                return Err(Error::invalid(w.loc(self.path), problem));
            }
            *slot = x;
        }
        Ok(P3::new(c[0], c[1], c[2]))
    }
}

/// The exact bits of a point, with -0.0 made 0.0, as a hash key.
#[derive(Clone, Copy, PartialEq, Eq, Hash)]
struct Key(u64, u64, u64);

impl Key {
    fn of(p: &P3) -> Self {
        let bits = |x: f64| if x == 0.0 { 0 } else { x.to_bits() };
        Key(bits(p.x), bits(p.y), bits(p.z))
    }
}

/// Shares vertices with bitwise-equal coordinates.
struct Welder {
    index: KeyMap<Key, u32>,
    vertices: Vec<P3>,
}

impl Welder {
    /// A welder expecting about `triangles` triangles.
    fn with_capacity(triangles: usize) -> Self {
        let n = triangles / 2 + 1;
        Welder {
            index: KeyMap::with_capacity_and_hasher(n, Default::default()),
            vertices: Vec::with_capacity(n),
        }
    }

    /// The index of `p`, added if new; an error beyond `u32` indices.
    fn index(&mut self, p: P3) -> std::result::Result<u32, TooMany> {
        let next = u32::try_from(self.vertices.len()).map_err(|_| TooMany)?;
        let i = *self.index.entry(Key::of(&p)).or_insert(next);
        if i == next {
            self.vertices.push(p);
        }
        Ok(i)
    }
}

/// More vertices than `u32` indices can address.
#[derive(Debug)]
struct TooMany;

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(bytes: &[u8]) -> Result<MeshFile> {
        parse_stl(Path::new("t/s.stl"), bytes, Count::NONE)
    }

    /// A binary STL with the given header start and triangles.
    pub(crate) fn binary_stl(header: &[u8], tris: &[[[f32; 3]; 3]]) -> Vec<u8> {
        let mut b = vec![b' '; 80];
        b[..header.len()].copy_from_slice(header);
        b.extend_from_slice(&(tris.len() as u32).to_le_bytes());
        for t in tris {
            b.extend_from_slice(&[0; 12]);
            for v in t {
                for c in v {
                    b.extend_from_slice(&c.to_le_bytes());
                }
            }
            b.extend_from_slice(&[0; 2]);
        }
        b
    }

    const TWO: [[[f32; 3]; 3]; 2] = [
        [[0., 0., 0.], [1., 0., 0.], [0., 1., 0.]],
        [[1., 0., 0.], [1., 1., 0.], [-0., 1., 0.]],
    ];

    #[test]
    fn load_stl_binary_shares_vertices() {
        for header in [&b"binary"[..], b"solid but binary"] {
            let m = parse(&binary_stl(header, &TWO)).unwrap();
            assert_eq!(m.groups.len(), 1);
            let g = &m.groups[0];
            assert_eq!(g.name, "s");
            assert_eq!(g.mesh.vertices.len(), 4);
            assert_eq!(g.mesh.faces, vec![vec![0, 1, 2], vec![1, 3, 2]]);
            assert_eq!(g.face_pos, vec![Pos::Byte(84), Pos::Byte(134)]);
            assert_eq!(g.mesh.vertices[3], P3::new(1., 1., 0.));
        }
    }

    #[test]
    fn load_stl_binary_errors_at_byte_offsets() {
        let mut nan = TWO;
        nan[1][2][1] = f32::NAN;
        let e = parse(&binary_stl(b"x", &nan)).unwrap_err();
        assert!(matches!(e, Error::Invalid(..)));
        assert_eq!(
            e.to_string(),
            "t/s.stl: byte 134: triangle 1, vertex 2, y: coordinate is NaN"
        );
        let mut huge = TWO;
        huge[0][0][2] = -1e13;
        let e = parse(&binary_stl(b"x", &huge)).unwrap_err().to_string();
        assert!(
            e.starts_with("t/s.stl: byte 84: triangle 0, vertex 0, z: huge coordinate"),
            "{e}"
        );
        let b = binary_stl(b"x", &TWO);
        let e = parse(&b[..b.len() - 10]).unwrap_err();
        assert!(matches!(e, Error::Parse(..)));
        assert_eq!(
            e.to_string(),
            "t/s.stl: byte 134: file is 174 bytes, header says 2 triangles needing 184: truncated binary STL"
        );
        let mut long = b.clone();
        long.push(0);
        let e = parse(&long).unwrap_err().to_string();
        assert!(e.starts_with("t/s.stl: byte 184: file is 185 bytes"), "{e}");
        let e = parse(b"\x01\x02").unwrap_err().to_string();
        assert!(e.starts_with("t/s.stl: byte 0: not an STL file"), "{e}");
        let e = parse(&binary_stl(b"x", &[])).unwrap_err().to_string();
        assert_eq!(e, "t/s.stl: the file contains no faces");
    }

    #[test]
    fn load_stl_truncated_binary_with_solid_header_is_size_error() {
        let b = binary_stl(b"solid x", &TWO);
        let e = parse(&b[..150]).unwrap_err().to_string();
        assert!(e.starts_with("t/s.stl: byte 134: file is 150 bytes"), "{e}");
    }

    const ASCII: &str = "solid cube part\n  facet normal 0 0 -1\n    outer loop\n      vertex 0 0 0\n      vertex 1 0 0\n      vertex 0 1 0\n    endloop\n  endfacet\n  FACET NORMAL 0 0 1\n    OUTER LOOP\n      VERTEX 1 0 0\n      VERTEX 1 1 0\n      VERTEX -0 1 0\n    ENDLOOP\n  ENDFACET\nendsolid cube part\nsolid two\nfacet normal 0 0 0 outer loop vertex 0 0 0 vertex 0 1 0 vertex 0 0 1 endloop endfacet\nendsolid\n";

    #[test]
    fn load_stl_ascii() {
        let m = parse(ASCII.as_bytes()).unwrap();
        let g = &m.groups[0];
        assert_eq!(g.mesh.vertices.len(), 5);
        assert_eq!(
            g.mesh.faces,
            vec![vec![0, 1, 2], vec![1, 3, 2], vec![0, 2, 4]]
        );
        assert_eq!(g.face_pos[1], Pos::Line { line: 9, col: 3 });
        assert_eq!(g.face_pos[2], Pos::Line { line: 18, col: 1 });
        assert_eq!(g.mesh.vertices[4], P3::new(0., 0., 1.));
    }

    #[test]
    fn load_stl_ascii_errors_have_line_and_column() {
        let head = "solid s\nfacet normal 0 0 1\nouter loop\n";
        let cases = [
            (
                format!("{head}vertex 0 0 0\nvertex 1 0 0\nvertex 0 1,5 0\n"),
                "t/s.stl:6:10: invalid number '1,5'",
            ),
            (
                format!("{head}vertex 0 0 0\nvertex 1 0 0\nvertex 0 1 inf\n"),
                "t/s.stl:6:12: coordinate is infinite (inf)",
            ),
            (
                format!("{head}vertex 0 0 0\nvertex 1 0 0\nendloop\nendfacet\nendsolid\n"),
                "t/s.stl:2:1: facet has 2 vertices",
            ),
            (
                format!("{head}vertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\n"),
                "t/s.stl:8:1: unexpected end of file: expected 'endfacet'",
            ),
            (
                format!("{head}vertex 0 0 0\nvertex 1 0 0\nvertex 0 1"),
                "t/s.stl:6:11: unexpected end of file: expected a coordinate",
            ),
            (
                format!("{head}vertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nvertex 0 2 0\nvertex 1 2 0\nendloop\n"),
                "t/s.stl:7:1: a fourth vertex: an ASCII STL facet is a triangle (3 vertices)",
            ),
            (
                format!("{head}vertex 0 0 0\nnormal 1 0 0\n"),
                "t/s.stl:5:1: expected 'vertex' or 'endloop', found 'normal'",
            ),
            (
                "solid s\nfacet normal 0 0 1\n outer lop\n".to_string(),
                "t/s.stl:3:8: expected 'loop', found 'lop'",
            ),
            (
                "solid s\nendsolid s\nxyz\n".to_string(),
                "t/s.stl:3:1: expected 'solid' or the end of the file, found 'xyz'",
            ),
            (
                "solid s\nface\n".to_string(),
                "t/s.stl:2:1: expected 'facet' or 'endsolid', found 'face'",
            ),
            (
                "solid s\n".to_string(),
                "t/s.stl:2:1: unexpected end of file: expected 'facet' or 'endsolid'",
            ),
            (
                "solid s\nendsolid s\n".to_string(),
                "t/s.stl: the file contains no faces",
            ),
            (
                "solid s\nfacet \u{fffd}\n".to_string(),
                "t/s.stl:2:7: expected 'normal', found '\u{fffd}'",
            ),
        ];
        for (text, want) in cases {
            let got = parse(text.as_bytes()).unwrap_err().to_string();
            assert!(got.starts_with(want), "{text:?}\n got: {got}\nwant: {want}");
        }
        let e = parse(b"solid s\nfacet normal 0 0 1 outer loop vertex 0 0 \xff")
            .unwrap_err()
            .to_string();
        assert!(e.starts_with("t/s.stl:2:42: invalid UTF-8"), "{e}");
        let e = parse(b"solid s\0\nfacet").unwrap_err().to_string();
        assert_eq!(e, "t/s.stl: byte 7: NUL byte in an ASCII STL file");
    }

    #[test]
    fn load_stl_key_hasher_spreads_f32_values() {
        let mut w = Welder::with_capacity(0);
        for i in 0..1000 {
            w.index(P3::new(f64::from(i as f32 * 0.25), 0.0, -0.0))
                .unwrap();
        }
        assert_eq!(w.index(P3::new(0.0, -0.0, 0.0)).unwrap(), 0);
        assert_eq!(w.vertices.len(), 1000);
    }
}
