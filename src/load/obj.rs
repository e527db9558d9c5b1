//! Wavefront OBJ loading: vertices and polygonal faces, split into groups by `o` and `g`.

use std::path::Path;

use rayon::prelude::*;

use super::mesh_file::{coord_problem, finish, stem_name, MeshFile, MeshGroup};
use super::text::{decode, Word, Words};
use crate::count::{Count, Cursor};
use crate::error::{Error, Pos, Result};
use crate::geom::P3;

/// Statements that are read and ignored (texture coordinates, normals, materials, smoothing, lines, points).
const IGNORED: [&str; 8] = ["vt", "vn", "vp", "usemtl", "mtllib", "s", "l", "p"];

/// Parses OBJ text. Faces keep their polygons; each `o`/`g` group gets its own vertex list
/// holding the vertices its faces use, in order of first use. Faces before any `o`/`g` go to a
/// group named after the file stem; groups without faces are dropped.
///
/// # Errors
/// [`Error::Parse`] for malformed text (bad numbers, unknown statements, invalid UTF-8) and
/// [`Error::Invalid`] for bad values (index 0 or out of range, faces with fewer than 3
/// vertices, NaN or huge coordinates, no faces at all), each at the offending `file:line:col`.
///
/// The bytes parsed go to `done` as it goes, once per step of bytes.
pub(crate) fn parse_obj(path: &Path, bytes: &[u8], done: Count) -> Result<MeshFile> {
    parse_obj_in(path, bytes, done, CHUNK_BYTES)
}

/// Text a thread parses at a time (cut at a logical line's end at or after it).
const CHUNK_BYTES: usize = 1 << 20;

/// Chunks parsed side by side before they are joined (the parsed chunks held at once).
const CHUNKS_AT_ONCE: usize = 64;

/// [`parse_obj`] with chunks of about `chunk_bytes`: the text is cut at logical line ends,
/// the chunks parsed on all threads, each not knowing the lines and vertices before it, and
/// joined in file order by the one group-and-reindex pass, which places them. A chunk that
/// stopped at an error, or whose references do not all resolve once placed, is parsed again
/// knowing its place, exactly as one parse from the start would parse it: the result,
/// errors included, is that of one parse.
fn parse_obj_in(path: &Path, bytes: &[u8], done: Count, chunk_bytes: usize) -> Result<MeshFile> {
    let text = decode(path, bytes, 1)?;
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    let cuts = chunk_cuts(text, chunk_bytes);
    let mut joined = ObjJoin::new(path);
    let mut cursor = Cursor::new(done);
    for batch in cuts.windows(2).collect::<Vec<_>>().chunks(CHUNKS_AT_ONCE) {
        let parsed: Vec<ObjChunk> = batch
            .par_iter()
            .map(|w| ObjChunk::parse(path, &text[w[0]..w[1]], None))
            .collect();
        for (chunk, w) in parsed.into_iter().zip(batch) {
            joined.join(chunk, &text[w[0]..w[1]])?;
        }
        cursor.at(batch.last().map_or(0, |w| w[1]));
    }
    cursor.finish(bytes.len());
    finish(path, joined.into_groups())
}

/// Byte offsets cutting `text` into chunks of about `size`, each ending at the end of a
/// logical line (after a LF whose physical line does not end in the continuation `\`);
/// first 0, last the text's length.
fn chunk_cuts(text: &str, size: usize) -> Vec<usize> {
    let b = text.as_bytes();
    let mut cuts = vec![0];
    let mut at = size;
    while at < b.len() {
        let Some(nl) = b[at..].iter().position(|&c| c == b'\n').map(|k| at + k) else {
            break;
        };
        let line_start = b[..nl]
            .iter()
            .rposition(|&c| c == b'\n' || c == b'\r')
            .map_or(0, |k| k + 1);
        let line = &text[line_start..nl];
        if line.trim_end().ends_with('\\') {
            at = nl + 1;
            continue;
        }
        cuts.push(nl + 1);
        at = nl + 1 + size;
    }
    cuts.push(b.len());
    cuts.dedup();
    cuts
}

/// Where a chunk is in its file: its first line, and the vertices defined before it.
#[derive(Debug, Clone, Copy)]
struct Place {
    first_line: usize,
    before: usize,
}

/// A face's vertex reference as a chunk read it: `2 g` for global index g (a positive
/// reference), `2 r + 1` for index r counted from the chunk's first vertex (a negative
/// reference, r maybe negative: a vertex of an earlier chunk).
type Reference = i64;

/// One chunk of OBJ text parsed: its vertices, its faces' references, where its groups
/// start, and whether it stopped at an error.
struct ObjChunk {
    vertices: Vec<P3>,
    /// Every face's references, face after face.
    corners: Vec<Reference>,
    /// Where each face's corners end in `corners`.
    face_ends: Vec<u32>,
    /// The chunk's vertices defined before each face.
    face_defined: Vec<u32>,
    /// Each face's position (its keyword's; lines counted from the chunk's first unless
    /// parsed at a known place).
    face_pos: Vec<Pos>,
    /// Groups started (`o`/`g`): before which face of the chunk, and the name given.
    groups: Vec<(usize, String)>,
    /// The first error met; nothing after it was parsed.
    error: Option<Error>,
    /// Lines the chunk spans (the next chunk's first line is this far on).
    lines: usize,
}

impl ObjChunk {
    /// Parses `text`, at its `place` in the file when known (references then resolved and
    /// checked, errors placed), else as if it were a file's start.
    fn parse(path: &Path, text: &str, place: Option<Place>) -> ObjChunk {
        let mut c = ObjChunk {
            vertices: Vec::new(),
            corners: Vec::new(),
            face_ends: Vec::new(),
            face_defined: Vec::new(),
            face_pos: Vec::new(),
            groups: Vec::new(),
            error: None,
            lines: 0,
        };
        let first_line = place.map_or(1, |p| p.first_line);
        let p = ObjParser {
            path,
            before: place.map(|p| p.before),
        };
        let mut words = Words::new(text, first_line)
            .with_continuation()
            .with_comment(b'#');
        while words.next_line() {
            if let Some(keyword) = words.next_in_line() {
                if let Err(e) = p.statement(&mut c, keyword, &mut words) {
                    c.error = Some(e);
                    break;
                }
            }
        }
        c.lines = words.line() - first_line;
        c
    }
}

/// The parse of one chunk: where errors are reported, and the vertices before the chunk
/// when known.
struct ObjParser<'p> {
    path: &'p Path,
    before: Option<usize>,
}

impl ObjParser<'_> {
    /// Handles one statement whose keyword has been read.
    fn statement(&self, c: &mut ObjChunk, keyword: Word, words: &mut Words) -> Result<()> {
        match keyword.text {
            "v" => self.vertex(c, words),
            "f" => self.face(c, keyword, words),
            "o" | "g" => {
                c.groups.push((c.face_ends.len(), group_name(words)));
                Ok(())
            }
            k if IGNORED.contains(&k) => Ok(()),
            k => Err(Error::parse(
                keyword.loc(self.path),
                format!("unknown OBJ statement '{}'", k.escape_debug()),
            )),
        }
    }

    /// `v x y z [w]`: extra values (w, vertex colours) are ignored.
    fn vertex(&self, c: &mut ObjChunk, words: &mut Words) -> Result<()> {
        let mut xyz = [0.0; 3];
        for (k, slot) in xyz.iter_mut().enumerate() {
            let Some(w) = words.next_in_line() else {
                let axis = ["x", "y", "z"][k];
                return Err(Error::parse(
                    words.here(self.path),
                    format!("missing {axis} coordinate"),
                ));
            };
            *slot = self.coordinate(w)?;
        }
        if self.before.unwrap_or(0) + c.vertices.len() >= u32::MAX as usize {
            return Err(Error::invalid(words.here(self.path), "too many vertices"));
        }
        c.vertices.push(P3::new(xyz[0], xyz[1], xyz[2]));
        Ok(())
    }

    /// A coordinate word: a finite number of reasonable size.
    fn coordinate(&self, w: Word) -> Result<f64> {
        let v: f64 = w.text.parse().map_err(|_| {
            Error::parse(
                w.loc(self.path),
                format!("invalid number '{}'", w.text.escape_debug()),
            )
        })?;
        match coord_problem(v) {
            Some(msg) => Err(Error::invalid(w.loc(self.path), msg)),
            None => Ok(v),
        }
    }

    /// `f v1 v2 v3 ...`, each reference `v`, `v/vt`, `v//vn` or `v/vt/vn`, possibly negative.
    fn face(&self, c: &mut ObjChunk, keyword: Word, words: &mut Words) -> Result<()> {
        let start = c.corners.len();
        let defined = c.vertices.len();
        while let Some(w) = words.next_in_line() {
            let r = self.reference(w, defined)?;
            c.corners.push(r);
        }
        let n = c.corners.len() - start;
        if n < 3 {
            let msg = format!("face has {n} vertices; a face needs at least 3");
            return Err(Error::invalid(keyword.loc(self.path), msg));
        }
        c.face_ends.push(c.corners.len() as u32);
        c.face_defined.push(defined as u32);
        c.face_pos.push(keyword.pos());
        Ok(())
    }

    /// One face vertex reference, the chunk's first `defined` vertices being defined before
    /// the face: resolved to a global index and checked when the chunk's place is known.
    fn reference(&self, w: Word, defined: usize) -> Result<Reference> {
        let mut parts = w.text.split('/');
        let v = parts.next().unwrap_or_default();
        let bad = || {
            Error::parse(
                w.loc(self.path),
                format!("invalid vertex reference '{}'", w.text.escape_debug()),
            )
        };
        if parts.count() > 2 {
            return Err(bad());
        }
        let i: i64 = v.parse().map_err(|_| bad())?;
        let n = (self.before.unwrap_or(0) + defined) as i64;
        let resolved = if i > 0 { i - 1 } else { n + i };
        if i == 0 {
            Err(Error::invalid(
                w.loc(self.path),
                "vertex index 0 (OBJ indices start at 1)",
            ))
        } else if resolved < 0 || resolved >= n {
            // Unplaced, a reference may name a vertex of an earlier chunk: left to the join.
            match self.before {
                None if i.unsigned_abs() <= u64::from(u32::MAX) => Ok(if i > 0 {
                    2 * resolved
                } else {
                    2 * resolved + 1
                }),
                _ => {
                    let msg = format!(
                        "vertex index {i} is out of range: {n} vertices are defined before this face"
                    );
                    Err(Error::invalid(w.loc(self.path), msg))
                }
            }
        } else if i > 0 || self.before.is_some() {
            Ok(2 * resolved)
        } else {
            Ok(2 * resolved + 1)
        }
    }
}

/// The rest of an `o NAME` or `g NAME` line: the group's name ("" when missing).
fn group_name(words: &mut Words) -> String {
    let mut name = String::new();
    while let Some(w) = words.next_in_line() {
        if !name.is_empty() {
            name.push(' ');
        }
        name.push_str(w.text);
    }
    name
}

/// The chunks joined in file order: all vertices so far, and the groups.
struct ObjJoin<'p> {
    path: &'p Path,
    /// Every `v` so far (OBJ indices are global).
    vertices: Vec<P3>,
    /// Per global vertex: the id of the last group that used it, and its index in that group.
    slot: Vec<(u32, u32)>,
    /// Finished groups.
    groups: Vec<MeshGroup>,
    /// The group receiving faces.
    current: MeshGroup,
    /// The current group's id (for `slot`).
    current_id: u32,
    /// The line the next chunk starts on.
    line: usize,
}

impl<'p> ObjJoin<'p> {
    fn new(path: &'p Path) -> Self {
        ObjJoin {
            path,
            vertices: Vec::new(),
            slot: Vec::new(),
            groups: Vec::new(),
            current: MeshGroup::new(stem_name(path)),
            current_id: 0,
            line: 1,
        }
    }

    /// Adds the next chunk (of `text`), parsed without its place: its vertices, groups and
    /// faces, or, where it stopped at an error or a reference does not resolve, the same
    /// chunk parsed again at its place, up to the error that parse stops at.
    fn join(&mut self, c: ObjChunk, text: &str) -> Result<()> {
        let place = Place {
            first_line: self.line,
            before: self.vertices.len(),
        };
        let globals = match c.error {
            None => self.resolve(&c, place.before),
            Some(_) => None,
        };
        // Lines read from the chunk's start are moved to its place.
        let (c, globals, shift) = match globals {
            Some(g) => (c, g, place.first_line - 1),
            None => {
                let c = ObjChunk::parse(self.path, text, Some(place));
                let g = c.corners.iter().map(|&r| (r / 2) as u32).collect();
                (c, g, 0)
            }
        };
        self.line += c.lines;
        self.vertices.extend_from_slice(&c.vertices);
        self.slot.resize(self.vertices.len(), (u32::MAX, 0));
        let mut groups = c.groups.into_iter().peekable();
        let mut start = 0;
        for (k, &end) in c.face_ends.iter().enumerate() {
            while let Some((_, name)) = groups.next_if(|g| g.0 == k) {
                self.start_group(name);
            }
            let pos = match c.face_pos[k] {
                Pos::Line { line, col } => Pos::Line {
                    line: line + shift,
                    col,
                },
                p => p,
            };
            self.add_face(&globals[start..end as usize], pos);
            start = end as usize;
        }
        for (_, name) in groups {
            self.start_group(name);
        }
        c.error.map_or(Ok(()), Err)
    }

    /// The global indices of an unplaced chunk's references, `before` vertices being
    /// defined before it; None when one does not name a vertex defined before its face.
    fn resolve(&self, c: &ObjChunk, before: usize) -> Option<Vec<u32>> {
        let mut out = Vec::with_capacity(c.corners.len());
        let mut start = 0;
        for (k, &end) in c.face_ends.iter().enumerate() {
            let defined = (before + c.face_defined[k] as usize) as i64;
            for &r in &c.corners[start..end as usize] {
                let g = if r & 1 == 0 {
                    r / 2
                } else {
                    (r - 1) / 2 + before as i64
                };
                if g < 0 || g >= defined {
                    return None;
                }
                out.push(g as u32);
            }
            start = end as usize;
        }
        Some(out)
    }

    /// Adds a face (global vertex indices) to the current group, reindexed to the group's
    /// vertices.
    fn add_face(&mut self, face: &[u32], pos: Pos) {
        let id = self.current_id;
        let mesh = &mut self.current.mesh;
        let mut local = Vec::with_capacity(face.len());
        for &g in face {
            let s = &mut self.slot[g as usize];
            if s.0 != id {
                *s = (id, mesh.vertices.len() as u32);
                mesh.vertices.push(self.vertices[g as usize]);
            }
            local.push(s.1);
        }
        mesh.faces.push(local);
        self.current.face_pos.push(pos);
    }

    /// `o NAME` or `g NAME`: starts a new group (named after the file if the name is missing).
    fn start_group(&mut self, mut name: String) {
        if name.is_empty() {
            name = stem_name(self.path);
        }
        let done = std::mem::replace(&mut self.current, MeshGroup::new(name));
        if !done.mesh.faces.is_empty() {
            self.groups.push(done);
        }
        self.current_id = self.current_id.wrapping_add(1);
    }

    /// All groups, the current one included.
    fn into_groups(mut self) -> Vec<MeshGroup> {
        self.groups.push(self.current);
        self.groups
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::error::Pos;

    fn parse(text: &str) -> Result<MeshFile> {
        parse_obj(Path::new("dir/m.obj"), text.as_bytes(), Count::NONE)
    }

    fn err(text: &str) -> String {
        parse(text).unwrap_err().to_string()
    }

    const SQUARE: &str = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n";

    #[test]
    fn load_obj_keeps_quads_and_names_default_group_after_file() {
        let m = parse(&format!("{SQUARE}f 1 2 3 4\n")).unwrap();
        assert_eq!(m.groups.len(), 1);
        let g = &m.groups[0];
        assert_eq!(g.name, "m");
        assert_eq!(g.mesh.vertices.len(), 4);
        assert_eq!(g.mesh.faces, vec![vec![0, 1, 2, 3]]);
        assert_eq!(g.face_pos, vec![Pos::Line { line: 5, col: 1 }]);
        assert_eq!(g.mesh.vertices[2], P3::new(1.0, 1.0, 0.0));
    }

    #[test]
    fn load_obj_reference_forms_and_negative_indices() {
        let t = format!("{SQUARE}vt 0 0\nvn 0 0 1\nf 1/1 2/1/1 3//1 -1\nf -4 -3 -2\n");
        let g = &parse(&t).unwrap().groups[0];
        assert_eq!(g.mesh.faces, vec![vec![0, 1, 2, 3], vec![0, 1, 2]]);
    }

    #[test]
    fn load_obj_groups_get_own_vertices_in_first_use_order() {
        let t = format!(
            "{SQUARE}f 1 2 3\no first\n# nothing\ng second part\nf 4 3 1\nf 1 3 2\no\nv 5 5 5\nf 5 1 4\ng empty\n"
        );
        let m = parse(&t).unwrap();
        let names: Vec<_> = m.groups.iter().map(|g| g.name.as_str()).collect();
        assert_eq!(names, ["m", "second part", "m"]);
        let g = &m.groups[1];
        assert_eq!(
            g.mesh.vertices,
            vec![
                P3::new(0., 1., 0.),
                P3::new(1., 1., 0.),
                P3::new(0., 0., 0.),
                P3::new(1., 0., 0.)
            ]
        );
        assert_eq!(g.mesh.faces, vec![vec![0, 1, 2], vec![2, 1, 3]]);
        assert_eq!(
            g.face_pos,
            vec![
                Pos::Line { line: 9, col: 1 },
                Pos::Line { line: 10, col: 1 }
            ]
        );
        let g = &m.groups[2];
        assert_eq!(
            g.mesh.vertices,
            vec![
                P3::new(5., 5., 5.),
                P3::new(0., 0., 0.),
                P3::new(0., 1., 0.)
            ]
        );
        assert_eq!(g.mesh.faces, vec![vec![0, 1, 2]]);
    }

    #[test]
    fn load_obj_ignores_other_statements_comments_crlf_and_w() {
        let t = "# c\r\nmtllib a.mtl\r\nv 0 0 0 1\r\nv 1 0 0 0.5 0.5 0.5\r\nv 0 1 0\r\nusemtl x\r\ns off\r\nvp 1\r\nl 1 2\r\np 1\r\nf 1 2 3 # tri\r\n";
        let g = &parse(t).unwrap().groups[0];
        assert_eq!(g.mesh.faces, vec![vec![0, 1, 2]]);
    }

    #[test]
    fn load_obj_line_continuation() {
        let t = format!("{SQUARE}f 1 2 \\\n  3 4\nf 1 2\\\n4\n");
        let g = &parse(&t).unwrap().groups[0];
        assert_eq!(g.mesh.faces, vec![vec![0, 1, 2, 3], vec![0, 1, 3]]);
        assert_eq!(g.face_pos[1], Pos::Line { line: 7, col: 1 });
    }

    #[test]
    fn load_obj_errors_have_exact_positions() {
        let cases = [
            ("v 1 2 x\n", "dir/m.obj:1:7: invalid number 'x'"),
            ("v 1 2\nf 1 1 1\n", "dir/m.obj:1:6: missing z coordinate"),
            ("v 1 2 3\n  v nan 0 0\n", "dir/m.obj:2:5: coordinate is NaN"),
            ("v 1 -inf 3\n", "dir/m.obj:1:5: coordinate is infinite (-inf)"),
            ("v 1 2e13 3\n", "dir/m.obj:1:5: huge coordinate 2e13 (the limit is 1e12)"),
            ("v 0 0 0\nv 1 0 0\nf 1  2\n", "dir/m.obj:3:1: face has 2 vertices; a face needs at least 3"),
            ("v 0 0 0\nv 1 0 0\n f\n", "dir/m.obj:3:2: face has 0 vertices; a face needs at least 3"),
            ("v 0 0 0\nv 1 0 0\nf 1 2 0\n", "dir/m.obj:3:7: vertex index 0 (OBJ indices start at 1)"),
            (
                "v 0 0 0\nv 1 0 0\nf 1 2 3\n",
                "dir/m.obj:3:7: vertex index 3 is out of range: 2 vertices are defined before this face",
            ),
            (
                "v 0 0 0\nv 1 0 0\nf 1 2 -3\n",
                "dir/m.obj:3:7: vertex index -3 is out of range: 2 vertices are defined before this face",
            ),
            ("v 0 0 0\nf 1 1/2/3/4 1\n", "dir/m.obj:2:5: invalid vertex reference '1/2/3/4'"),
            ("v 0 0 0\nf 1 a 1\n", "dir/m.obj:2:5: invalid vertex reference 'a'"),
            ("v 0 0 0\nf 1 99999999999999999999 1\n", "dir/m.obj:2:5: invalid vertex reference"),
            ("v 0 0 0\n\n\tcurv 1 2\n", "dir/m.obj:3:2: unknown OBJ statement 'curv'"),
            ("v 0 0 0\nv é 0 0\n", "dir/m.obj:2:3: invalid number 'é'"),
            ("v 0 0 0\nvé 0 0\n", "dir/m.obj:2:1: unknown OBJ statement 'vé'"),
            ("v 0 0 0\nv 1 \x00 0\n", "dir/m.obj:2:5: a NUL byte: not a text file?"),
            ("# only comments\no a\n", "dir/m.obj: the file contains no faces"),
        ];
        for (text, want) in cases {
            let got = err(text);
            assert!(got.starts_with(want), "{text:?}\n got: {got}\nwant: {want}");
        }
    }

    #[test]
    fn load_obj_error_kinds() {
        assert!(matches!(
            parse("v 0 0 0\nf 1 1 9\n"),
            Err(Error::Invalid(..))
        ));
        assert!(matches!(parse("v 0 0 nan\n"), Err(Error::Invalid(..))));
        assert!(matches!(parse("v 0 0 z\n"), Err(Error::Parse(..))));
        assert!(matches!(parse("bogus\n"), Err(Error::Parse(..))));
    }

    #[test]
    fn load_obj_invalid_utf8_reports_line() {
        let e = parse_obj(
            Path::new("g.obj"),
            b"v 0 0 0\nv 1 \xfe\xff 0\n",
            Count::NONE,
        )
        .unwrap_err();
        assert!(matches!(e, Error::Parse(..)));
        assert!(e.to_string().starts_with("g.obj:2:5: invalid UTF-8"), "{e}");
    }

    /// Every text of the tests above, parsed in chunks of every size from one byte up:
    /// the same groups, or the same error, as one parse from the start.
    #[test]
    fn parsed_in_chunks_any_text_is_the_same() {
        let mut texts: Vec<String> = vec![
            format!("{SQUARE}f 1 2 3 4\n"),
            format!("{SQUARE}vt 0 0\nvn 0 0 1\nf 1/1 2/1/1 3//1 -1\nf -4 -3 -2\n"),
            format!("{SQUARE}f 1 2 3\no first\n# nothing\ng second part\nf 4 3 1\nf 1 3 2\no\nv 5 5 5\nf 5 1 4\ng empty\n"),
            "# c\r\nv 0 0 0 1\r\nv 1 0 0\rv 0 1 0\r\nf 1 2 3 # tri\r\nf -1 -2 -3".into(),
            format!("{SQUARE}f 1 2 \\\n  3 4\nf 1 2\\\n4\nf 1 \\ \n\\\n 2 3\n"),
            format!("{SQUARE}# a comment \\\nf 1 2 3\n"),
            format!("{SQUARE}f 1 2 3\nf 1 2 5\nv 0 0 x\n"),
            format!("{SQUARE}f 1 2 3\nv 0 0 x\nf 1 2 9\n"),
            format!("{SQUARE}f 1 2\nv 0 0 x\n"),
            format!("{SQUARE}v 2 2 2\nf 5 1 -5\nf 1 2 -6\n"),
        ];
        texts.push(texts.concat());
        for text in &texts {
            let path = Path::new("dir/m.obj");
            let whole = parse_obj_in(path, text.as_bytes(), Count::NONE, usize::MAX);
            for size in 1..text.len() + 2 {
                let chunked = parse_obj_in(path, text.as_bytes(), Count::NONE, size);
                match (&whole, &chunked) {
                    (Ok(a), Ok(b)) => assert_eq!(a, b, "{text:?} in chunks of {size}"),
                    (Err(a), Err(b)) => assert_eq!(a.to_string(), b.to_string(), "{text:?}"),
                    _ => panic!("{text:?} in chunks of {size}: {whole:?} vs {chunked:?}"),
                }
            }
        }
        // Cut only at logical line ends.
        let t = "v 0 0 0\\\n 1\nf 1 1 1\r\nv 2 2 2\n";
        assert_eq!(chunk_cuts(t, 1), [0, 12, 21, t.len()]);
    }

    #[test]
    fn load_obj_bom_is_skipped() {
        let t = format!("\u{feff}{SQUARE}f 1 2 3\n");
        assert_eq!(parse(&t).unwrap().groups[0].mesh.faces.len(), 1);
    }

    #[test]
    fn load_obj_large_grid_is_fast_enough() {
        let n = 100;
        let mut t = String::new();
        for j in 0..=n {
            for i in 0..=n {
                t.push_str(&format!("v {i} {j} 0.5\n"));
            }
        }
        for j in 0..n {
            for i in 0..n {
                let a = j * (n + 1) + i + 1;
                t.push_str(&format!("f {} {} {} {}\n", a, a + 1, a + n + 2, a + n + 1));
            }
        }
        let g = &parse(&t).unwrap().groups[0];
        assert_eq!(g.mesh.faces.len(), n * n);
        assert_eq!(g.mesh.vertices.len(), (n + 1) * (n + 1));
        let corners: Vec<P3> = g.mesh.face_points(n).copied().collect();
        let want = [(0., 1.), (1., 1.), (1., 2.), (0., 2.)].map(|(x, y)| P3::new(x, y, 0.5));
        assert_eq!(corners, want);
    }
}
