//! Wavefront OBJ loading: vertices and polygonal faces, split into groups by `o` and `g`.

use std::ops::Range;
use std::path::Path;

use rayon::prelude::*;

use super::mesh_file::{coord_problem, finish, stem_name, MeshFile, MeshGroup};
use super::text::{decode, Word, Words};
use crate::count::{Count, Cursor};
use crate::error::{Error, Pos, Result};
use crate::geom::P3;
use crate::renumber::Renumbering;

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
    parse_obj_in(path, bytes, done, chunk_bytes(bytes.len()))
}

/// Most text a thread parses at a time (cut at a logical line's end at or after it).
const CHUNK_BYTES: usize = 1 << 20;

/// Least text a thread parses at a time (a file of up to 64 KiB is one chunk).
const MIN_CHUNK_BYTES: usize = 64 << 10;

/// The chunk size for a file of `len` bytes: [`CHUNKS_AT_ONCE`] chunks where that keeps
/// them between [`MIN_CHUNK_BYTES`] and [`CHUNK_BYTES`]. A mid-sized mesh (nefertiti's
/// 3.7 MB) was four chunks of 1 MiB: four threads parsed it, whatever the machine had. The
/// result does not depend on the size (a test parses in chunks of every size).
fn chunk_bytes(len: usize) -> usize {
    (len / CHUNKS_AT_ONCE).clamp(MIN_CHUNK_BYTES, CHUNK_BYTES)
}

/// Chunks parsed side by side before they are joined (the parsed chunks held at once).
const CHUNKS_AT_ONCE: usize = 64;

/// [`parse_obj`] with chunks of about `chunk_bytes`: the text is cut at logical line ends,
/// the chunks checked as text and parsed on all threads, each not knowing the lines and
/// vertices before it, and joined in file order on all threads by the group-and-reindex
/// join, which places them. A chunk that stopped at an error, or whose references do not all
/// resolve once placed, is parsed again knowing its place, exactly as one parse from the
/// start would parse it: the result, errors included, is that of one parse.
fn parse_obj_in(path: &Path, bytes: &[u8], done: Count, chunk_bytes: usize) -> Result<MeshFile> {
    let body = bytes.strip_prefix("\u{feff}".as_bytes()).unwrap_or(bytes);
    let cuts = chunk_cuts(body, chunk_bytes);
    let texts = chunk_texts(path, bytes, body, &cuts)?;
    let mut joined = ObjJoin::new(path);
    let mut cursor = Cursor::new(done);
    let mut at = 0;
    for batch in texts.chunks(CHUNKS_AT_ONCE) {
        let parsed: Vec<ObjChunk> = batch
            .par_iter()
            .map(|t| ObjChunk::parse(path, t, None))
            .collect();
        joined.join(parsed, batch)?;
        at += batch.iter().map(|t| t.len()).sum::<usize>();
        cursor.at(at);
    }
    cursor.finish(bytes.len());
    finish(path, joined.into_groups())
}

/// The chunks of `body` (the file `bytes` after any byte-order mark) between the `cuts`,
/// each checked as text on all threads; where one is not text, the whole file's error (at
/// its first byte that is not text: a cut follows a line feed, which no UTF-8 sequence
/// holds, so a chunk is text exactly when its part of the file is).
fn chunk_texts<'a>(
    path: &Path,
    bytes: &'a [u8],
    body: &'a [u8],
    cuts: &[usize],
) -> Result<Vec<&'a str>> {
    let texts: Vec<Option<&str>> = cuts
        .par_windows(2)
        .map(|w| {
            let b = &body[w[0]..w[1]];
            if b.contains(&0) {
                None
            } else {
                std::str::from_utf8(b).ok()
            }
        })
        .collect();
    if texts.iter().all(Option::is_some) {
        return Ok(texts.into_iter().flatten().collect());
    }
    let text = decode(path, bytes, 1)?;
    let body = &text[bytes.len() - body.len()..];
    Ok(cuts.windows(2).map(|w| &body[w[0]..w[1]]).collect())
}

/// Byte offsets cutting `text` into chunks of about `size`, each ending at the end of a
/// logical line (after a LF whose physical line does not end in the continuation `\`);
/// first 0, last the text's length.
fn chunk_cuts(b: &[u8], size: usize) -> Vec<usize> {
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
        // A line that is not text is cut anyway: the file is refused.
        let continued = std::str::from_utf8(&b[line_start..nl])
            .is_ok_and(|line| line.trim_end().ends_with('\\'));
        if continued {
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

/// A face's vertex reference as a chunk read it: below `RELATIVE`, the global index (a
/// positive reference, or any reference of a placed chunk); from `RELATIVE` on, a negative
/// reference `-(k + 1)` as `RELATIVE + k`, counted back from the vertices defined before the
/// face (maybe a vertex of an earlier chunk). A file within the size limit has far fewer
/// vertices than `RELATIVE`; a reference that does not fit has the chunk parsed at its place.
const RELATIVE: u32 = 1 << 31;

/// One chunk of OBJ text parsed: its vertices, its faces' references, where its groups
/// start, and whether it stopped at an error.
struct ObjChunk {
    vertices: Vec<P3>,
    /// Every face's references (see [`RELATIVE`]), a list a face.
    faces: Vec<Vec<u32>>,
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
    /// A reference did not fit [`RELATIVE`]'s code: the chunk must be parsed at its place.
    unfit: bool,
    /// The references of the face being read.
    scratch: Vec<u32>,
}

impl ObjChunk {
    /// Parses `text`, at its `place` in the file when known (references then resolved and
    /// checked, errors placed), else as if it were a file's start.
    fn parse(path: &Path, text: &str, place: Option<Place>) -> ObjChunk {
        let mut c = ObjChunk {
            vertices: Vec::new(),
            faces: Vec::new(),
            face_defined: Vec::new(),
            face_pos: Vec::new(),
            groups: Vec::new(),
            error: None,
            lines: 0,
            unfit: false,
            scratch: Vec::new(),
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

    /// Frees what the chunk holds once joined.
    fn free(&mut self) {
        self.vertices = Vec::new();
        self.faces = Vec::new();
        self.face_defined = Vec::new();
        self.face_pos = Vec::new();
    }

    /// Rewrites the references of this chunk, parsed without its place, to global indices,
    /// `before` vertices being defined before it, and moves its faces' lines down by
    /// `shift`; false (the chunk left half rewritten) when a reference does not name a
    /// vertex defined before its face.
    fn resolve(&mut self, before: usize, shift: usize) -> bool {
        if self.unfit {
            return false;
        }
        for (f, &d) in self.faces.iter_mut().zip(&self.face_defined) {
            let defined = before + d as usize;
            for r in f.iter_mut() {
                let g = if *r < RELATIVE {
                    *r as usize
                } else {
                    let back = (*r - RELATIVE) as usize + 1;
                    match defined.checked_sub(back) {
                        Some(g) => g,
                        None => return false,
                    }
                };
                if g >= defined {
                    return false;
                }
                *r = g as u32;
            }
        }
        for p in &mut self.face_pos {
            if let Pos::Line { line, .. } = p {
                *line += shift;
            }
        }
        true
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
                c.groups.push((c.faces.len(), group_name(words)));
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
        let defined = c.vertices.len();
        c.scratch.clear();
        while let Some(w) = words.next_in_line() {
            let r = self.reference(w, defined, &mut c.unfit)?;
            c.scratch.push(r);
        }
        let n = c.scratch.len();
        if n < 3 {
            let msg = format!("face has {n} vertices; a face needs at least 3");
            return Err(Error::invalid(keyword.loc(self.path), msg));
        }
        c.faces.push(c.scratch.clone());
        c.face_defined.push(defined as u32);
        c.face_pos.push(keyword.pos());
        Ok(())
    }

    /// One face vertex reference, the chunk's first `defined` vertices being defined before
    /// the face: resolved to a global index and checked when the chunk's place is known, else
    /// coded as [`RELATIVE`] says (`unfit` set where it cannot be).
    fn reference(&self, w: Word, defined: usize, unfit: &mut bool) -> Result<u32> {
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
            return Err(Error::invalid(
                w.loc(self.path),
                "vertex index 0 (OBJ indices start at 1)",
            ));
        }
        let in_range = 0 <= resolved && resolved < n;
        if self.before.is_some() || (!in_range && i.unsigned_abs() > u64::from(u32::MAX)) {
            if !in_range {
                let msg = format!(
                    "vertex index {i} is out of range: {n} vertices are defined before this face"
                );
                return Err(Error::invalid(w.loc(self.path), msg));
            }
            if self.before.is_some() {
                return Ok(resolved as u32);
            }
        }
        // Unplaced, a reference may name a vertex of an earlier chunk: left to the join.
        let code = if i > 0 {
            i - 1
        } else {
            i64::from(RELATIVE) + (-i - 1)
        };
        let fits = if i > 0 {
            code < i64::from(RELATIVE)
        } else {
            code <= i64::from(u32::MAX)
        };
        if !fits {
            *unfit = true;
            return Ok(0);
        }
        Ok(code as u32)
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
    /// The vertices' indices in the groups that used them (a round a group).
    numbers: Renumbering,
    /// Finished groups.
    groups: Vec<MeshGroup>,
    /// The group receiving faces.
    current: MeshGroup,
    /// The current group's id (its round in `numbers`).
    current_id: u32,
    /// The line the next chunk starts on.
    line: usize,
}

/// A step of a batch's join: a group started, or a run of a chunk's faces.
enum Step {
    Group(String),
    Faces(usize, Range<usize>),
}

impl<'p> ObjJoin<'p> {
    fn new(path: &'p Path) -> Self {
        ObjJoin {
            path,
            vertices: Vec::new(),
            numbers: Renumbering::default(),
            groups: Vec::new(),
            current: MeshGroup::new(stem_name(path)),
            current_id: 0,
            line: 1,
        }
    }

    /// Adds the next chunks (of `texts`), parsed without their places: their vertices,
    /// groups and faces; or, from the first that stopped at an error or has a reference that
    /// does not resolve, the chunks parsed again at their places, up to the error such a
    /// parse stops at.
    fn join(&mut self, mut chunks: Vec<ObjChunk>, texts: &[&str]) -> Result<()> {
        let mut places = Vec::with_capacity(chunks.len());
        let (mut line, mut before) = (self.line, self.vertices.len());
        for c in &chunks {
            places.push(Place {
                first_line: line,
                before,
            });
            line += c.lines;
            before += c.vertices.len();
        }
        // Lines read from each chunk's start are moved to its place.
        let resolved: Vec<bool> = chunks
            .par_iter_mut()
            .zip(&places)
            .map(|(c, p)| c.error.is_none() && c.resolve(p.before, p.first_line - 1))
            .collect();
        let (mut line, mut before) = (self.line, self.vertices.len());
        let mut again = false;
        for (k, c) in chunks.iter_mut().enumerate() {
            // After a chunk parsed again, the places of those after it may have moved.
            again |= !resolved[k];
            if again {
                let place = Place {
                    first_line: line,
                    before,
                };
                *c = ObjChunk::parse(self.path, texts[k], Some(place));
                if let Some(e) = c.error.take() {
                    return Err(e);
                }
            }
            line += c.lines;
            before += c.vertices.len();
        }
        self.line = line;
        let vertices: Vec<&[P3]> = chunks.iter().map(|c| &c.vertices[..]).collect();
        crate::chunked::extend_concat(&mut self.vertices, &vertices);
        self.numbers.grow(self.vertices.len());
        let mut steps = Vec::new();
        for (k, c) in chunks.iter_mut().enumerate() {
            let mut start = 0;
            for (at, name) in std::mem::take(&mut c.groups) {
                steps.push(Step::Faces(k, start..at));
                steps.push(Step::Group(name));
                start = at;
            }
            steps.push(Step::Faces(k, start..c.faces.len()));
        }
        // On one thread, each chunk is joined and freed in turn (the same numbers: a
        // group's round goes on over runs), so that the chunks and the groups are not all
        // live at once.
        let one_thread = rayon::current_num_threads() == 1;
        let mut run = Vec::new();
        for step in steps {
            match step {
                Step::Faces(k, r) => {
                    let last = r.end == chunks[k].faces.len();
                    if !r.is_empty() {
                        run.push((k, r));
                    }
                    if one_thread && last {
                        self.add_run(&mut chunks, &std::mem::take(&mut run));
                        chunks[k].free();
                    }
                }
                Step::Group(name) => {
                    self.add_run(&mut chunks, &std::mem::take(&mut run));
                    self.start_group(name);
                }
            }
        }
        self.add_run(&mut chunks, &run);
        chunks.into_par_iter().for_each(drop);
        Ok(())
    }

    /// Adds a run of faces to the current group (the chunk and range of each part, one part
    /// a chunk, in order), reindexed to the group's vertices.
    fn add_run(&mut self, chunks: &mut [ObjChunk], run: &[(usize, Range<usize>)]) {
        if run.is_empty() {
            return;
        }
        let mut faces: Vec<&mut [Vec<u32>]> = Vec::with_capacity(run.len());
        let mut pos: Vec<&[Pos]> = Vec::with_capacity(run.len());
        let mut parts = run.iter().peekable();
        for (k, c) in chunks.iter_mut().enumerate() {
            if let Some((_, r)) = parts.next_if(|p| p.0 == k) {
                faces.push(&mut c.faces[r.clone()]);
                pos.push(&c.face_pos[r.clone()]);
            }
        }
        let mesh = &mut self.current.mesh;
        let next = mesh.vertices.len() as u32;
        let new = self
            .numbers
            .renumber(self.current_id, &mut faces, next, |f| &mut f[..]);
        let all = &self.vertices;
        crate::chunked::extend_map(&mut mesh.vertices, new.len(), |k| all[new[k] as usize]);
        crate::chunked::extend_taken(&mut mesh.faces, faces);
        crate::chunked::extend_concat(&mut self.current.face_pos, &pos);
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

    #[test]
    fn a_mid_sized_file_is_cut_for_every_thread_and_a_big_one_in_mebibytes() {
        // Nefertiti's 3.7 MB: 56 chunks, not 4; a 561 MB terrain keeps 1 MiB chunks; a
        // small file is one chunk of at least 64 KiB.
        let chunks = |len: usize| len.div_ceil(chunk_bytes(len));
        assert_eq!(chunks(3_660_678), 56);
        assert_eq!(chunk_bytes(561_213_527), CHUNK_BYTES);
        assert_eq!(chunk_bytes(2_000), MIN_CHUNK_BYTES);
        assert_eq!(chunks(2_000), 1);
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
        assert_eq!(chunk_cuts(t.as_bytes(), 1), [0, 12, 21, t.len()]);
    }

    /// A grid big enough to be renumbered on all threads, in three groups (one continued
    /// over batches of chunks), with negative references and vertices defined among the
    /// faces: joined on three threads in small chunks, it is the one parse on one thread.
    #[test]
    fn a_big_file_joined_on_several_threads_is_the_one_parse() {
        let n = 150;
        let total = (n + 1) * (n + 1);
        let mut t = String::new();
        for j in 0..=n {
            for i in 0..=n {
                t.push_str(&format!("v {i} {j} {}\n", (i * j) % 7));
            }
        }
        for j in 0..n {
            match j {
                3 => t.push_str("g first\n"),
                140 => t.push_str("o last\n"),
                _ if j % 50 == 7 => t.push_str("v 9 9 9\n"),
                _ => {}
            }
            for i in 0..n {
                let a = j * (n + 1) + i + 1;
                let q = [a, a + 1, a + n + 2, a + n + 1];
                if j % 2 == 0 {
                    t.push_str(&format!("f {} {} {} {}\n", q[0], q[1], q[2], q[3]));
                } else {
                    // Counted back from the vertices defined so far.
                    let defined = (total + j / 50 + usize::from(j % 50 > 7)) as i64;
                    let r: Vec<i64> = q.iter().map(|&v| v as i64 - defined - 1).collect();
                    t.push_str(&format!("f {} {} {} {}\n", r[0], r[1], r[2], r[3]));
                }
            }
        }
        let path = Path::new("dir/m.obj");
        let one = crate::chunked::pool(1)
            .install(|| parse_obj_in(path, t.as_bytes(), Count::NONE, usize::MAX))
            .unwrap();
        let many = crate::chunked::pool(3)
            .install(|| parse_obj_in(path, t.as_bytes(), Count::NONE, 4096))
            .unwrap();
        assert!(t.len() / 4096 > 2 * CHUNKS_AT_ONCE);
        let sizes: Vec<usize> = one.groups.iter().map(|g| g.mesh.faces.len()).collect();
        assert_eq!(sizes, [3 * n, 137 * n, 10 * n]);
        assert_eq!(one, many);
        // The big group's first face uses its first vertices.
        assert_eq!(one.groups[1].mesh.faces[0], [0, 1, 2, 3]);
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
