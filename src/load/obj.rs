//! Wavefront OBJ loading: vertices and polygonal faces, split into groups by `o` and `g`.

use std::path::Path;

use super::mesh_file::{coord_problem, finish, stem_name, MeshFile, MeshGroup};
use super::text::{decode, Word, Words};
use crate::count::{Count, Cursor};
use crate::error::{Error, Result};
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
    let text = decode(path, bytes, 1)?;
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    let mut parser = ObjParser::new(path);
    let mut words = Words::new(text, 1).with_continuation().with_comment(b'#');
    let mut cursor = Cursor::new(done);
    while words.next_line() {
        cursor.at(words.consumed());
        if let Some(keyword) = words.next_in_line() {
            parser.statement(keyword, &mut words)?;
        }
    }
    cursor.finish(bytes.len());
    let groups = parser.into_groups();
    finish(path, groups)
}

/// The state of an OBJ parse: all vertices so far, and the groups.
struct ObjParser<'p> {
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
    /// Reused buffer of a face's global indices.
    face: Vec<u32>,
}

impl<'p> ObjParser<'p> {
    fn new(path: &'p Path) -> Self {
        ObjParser {
            path,
            vertices: Vec::new(),
            slot: Vec::new(),
            groups: Vec::new(),
            current: MeshGroup::new(stem_name(path)),
            current_id: 0,
            face: Vec::new(),
        }
    }

    /// Handles one statement whose keyword has been read.
    fn statement(&mut self, keyword: Word, words: &mut Words) -> Result<()> {
        match keyword.text {
            "v" => self.vertex(words),
            "f" => self.face(keyword, words),
            "o" | "g" => {
                self.start_group(words);
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
    fn vertex(&mut self, words: &mut Words) -> Result<()> {
        let mut c = [0.0; 3];
        for (k, slot) in c.iter_mut().enumerate() {
            let Some(w) = words.next_in_line() else {
                let axis = ["x", "y", "z"][k];
                return Err(Error::parse(
                    words.here(self.path),
                    format!("missing {axis} coordinate"),
                ));
            };
            *slot = self.coordinate(w)?;
        }
        if self.vertices.len() >= u32::MAX as usize {
            return Err(Error::invalid(words.here(self.path), "too many vertices"));
        }
        self.vertices.push(P3::new(c[0], c[1], c[2]));
        self.slot.push((u32::MAX, 0));
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
    fn face(&mut self, keyword: Word, words: &mut Words) -> Result<()> {
        self.face.clear();
        while let Some(w) = words.next_in_line() {
            let i = self.reference(w)?;
            self.face.push(i);
        }
        let n = self.face.len();
        if n < 3 {
            let msg = format!("face has {n} vertices; a face needs at least 3");
            return Err(Error::invalid(keyword.loc(self.path), msg));
        }
        self.add_face(keyword);
        Ok(())
    }

    /// The global 0-based vertex index of one face vertex reference.
    fn reference(&self, w: Word) -> Result<u32> {
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
        let n = self.vertices.len() as i64;
        let resolved = if i > 0 { i - 1 } else { n + i };
        if i == 0 {
            Err(Error::invalid(
                w.loc(self.path),
                "vertex index 0 (OBJ indices start at 1)",
            ))
        } else if resolved < 0 || resolved >= n {
            let msg = format!(
                "vertex index {i} is out of range: {n} vertices are defined before this face"
            );
            Err(Error::invalid(w.loc(self.path), msg))
        } else {
            Ok(resolved as u32)
        }
    }

    /// Adds the face in `self.face` to the current group, reindexed to the group's vertices.
    fn add_face(&mut self, keyword: Word) {
        let id = self.current_id;
        let mesh = &mut self.current.mesh;
        let mut local = Vec::with_capacity(self.face.len());
        for &g in &self.face {
            let s = &mut self.slot[g as usize];
            if s.0 != id {
                *s = (id, mesh.vertices.len() as u32);
                mesh.vertices.push(self.vertices[g as usize]);
            }
            local.push(s.1);
        }
        mesh.faces.push(local);
        self.current.face_pos.push(keyword.pos());
    }

    /// `o NAME` or `g NAME`: starts a new group (named after the file if the name is missing).
    fn start_group(&mut self, words: &mut Words) {
        let mut name = String::new();
        while let Some(w) = words.next_in_line() {
            if !name.is_empty() {
                name.push(' ');
            }
            name.push_str(w.text);
        }
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
