//! A `kepler-visible/1` document read back: every face's object and visible region by id, and
//! the camera matrix it was made with.

use std::collections::BTreeMap;
use std::path::Path;

use serde_json::Value;

use crate::error::{Error, Location, Result};
use crate::geom::poly2::{MultiPolygon, Pt2};

/// One face of a visible-polygon set.
#[derive(Debug, Clone, PartialEq)]
pub struct SetFace {
    /// The object path the face belongs to.
    pub object: String,
    /// The face's visible region.
    pub visible: MultiPolygon,
    /// True for a face a section cut made (`"section": true`).
    pub section: bool,
}

/// A `kepler-visible/1` set: faces by id and the flattened camera matrix (row by row).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct VisibleSet {
    /// Faces by id.
    pub faces: BTreeMap<u64, SetFace>,
    /// The camera matrix, row by row, when the document has one.
    pub matrix: Option<Vec<f64>>,
}

impl VisibleSet {
    /// Reads and parses a `kepler-visible/1` file ([`VisibleSet::parse`]); an unreadable file
    /// is an error naming it.
    pub fn read(path: &Path) -> Result<VisibleSet> {
        let text = std::fs::read_to_string(path).map_err(|e| Error::Io(Location::file(path), e))?;
        VisibleSet::parse(&text, path)
    }

    /// Parses a `kepler-visible/1` document; errors name `path` and the line and column: of
    /// the syntax error, or of the face that is wrong.
    pub fn parse(text: &str, path: &Path) -> Result<VisibleSet> {
        let at = |line, col, msg: String| Error::parse(Location::line(path, line, col), msg);
        let v: Value = serde_json::from_str(text).map_err(|e| {
            let msg = e.to_string();
            let msg = msg.split(" at line ").next().unwrap_or_default();
            at(
                e.line().max(1),
                e.column().max(1),
                format!("not JSON: {msg}"),
            )
        })?;
        if v.get("format").and_then(Value::as_str) != Some("kepler-visible/1") {
            return Err(at(
                1,
                1,
                "not a kepler-visible/1 file (no \"format\": \"kepler-visible/1\")".into(),
            ));
        }
        let matrix = v
            .pointer("/camera/matrix")
            .and_then(Value::as_array)
            .map(|rows| {
                rows.iter()
                    .flat_map(|r| r.as_array().cloned().unwrap_or_default())
                    .filter_map(|x| x.as_f64())
                    .collect()
            });
        let list = v
            .get("faces")
            .and_then(Value::as_array)
            .ok_or_else(|| at(1, 1, "no \"faces\" list".into()))?;
        let mut faces = BTreeMap::new();
        for (i, f) in list.iter().enumerate() {
            let bad = |msg: String| {
                let (line, col) =
                    element_offset(text, "faces", i).map_or((1, 1), |off| line_col(text, off));
                at(line, col, format!("faces[{i}]{msg}"))
            };
            let id = f
                .get("id")
                .and_then(Value::as_u64)
                .ok_or_else(|| bad(": no integer \"id\"".into()))?;
            let object = f
                .get("object")
                .and_then(Value::as_str)
                .unwrap_or("")
                .to_string();
            let visible = multipolygon(f.get("visible")).ok_or_else(|| {
                bad(format!(
                    " (id {id}): \"visible\" is not a multipolygon of finite [x, y] points"
                ))
            })?;
            let section = f.get("section").and_then(Value::as_bool) == Some(true);
            let face = SetFace {
                object,
                visible,
                section,
            };
            if faces.insert(id, face).is_some() {
                return Err(bad(format!(": id {id} appears twice")));
            }
        }
        Ok(VisibleSet { faces, matrix })
    }
}

/// The byte offset where element `index` of the array under the top-level key `key` starts,
/// in a text that is valid JSON.
fn element_offset(text: &str, key: &str, index: usize) -> Option<usize> {
    let b = text.as_bytes();
    let skip_space = |mut j: usize| {
        while j < b.len() && b[j].is_ascii_whitespace() {
            j += 1;
        }
        j
    };
    let (mut depth, mut i, mut array, mut commas, mut starts) = (0usize, 0, None, 0, false);
    while i < b.len() {
        if starts && !b[i].is_ascii_whitespace() {
            if commas == index {
                return Some(i);
            }
            starts = false;
        }
        match b[i] {
            b'"' => {
                let end = string_end(b, i)?;
                if depth == 1 && array.is_none() && text.get(i + 1..end) == Some(key) {
                    let colon = skip_space(end + 1);
                    let open = skip_space(colon + 1);
                    if b.get(colon) == Some(&b':') && b.get(open) == Some(&b'[') {
                        (depth, array, starts, i) = (2, Some(2), true, open + 1);
                        continue;
                    }
                }
                i = end;
            }
            b'{' | b'[' => depth += 1,
            b'}' | b']' if Some(depth) == array => return None,
            b'}' | b']' => depth = depth.saturating_sub(1),
            b',' if Some(depth) == array => (commas, starts) = (commas + 1, true),
            _ => {}
        }
        i += 1;
    }
    None
}

/// The index of the quote closing the string that opens at `open`.
fn string_end(b: &[u8], open: usize) -> Option<usize> {
    let mut j = open + 1;
    while j < b.len() {
        match b[j] {
            b'\\' => j += 2,
            b'"' => return Some(j),
            _ => j += 1,
        }
    }
    None
}

/// The 1-based line and column (characters) of a byte offset.
fn line_col(text: &str, offset: usize) -> (usize, usize) {
    let before = &text[..offset];
    let line = before.matches('\n').count() + 1;
    let col = before.rsplit('\n').next().map_or(0, |l| l.chars().count()) + 1;
    (line, col)
}

/// A multipolygon from JSON: polygons of rings of finite [x, y] points.
fn multipolygon(v: Option<&Value>) -> Option<MultiPolygon> {
    let list = |v: &Value| v.as_array().cloned();
    list(v?)?
        .iter()
        .map(|poly| {
            list(poly)?
                .iter()
                .map(|ring| list(ring)?.iter().map(point).collect::<Option<Vec<Pt2>>>())
                .collect::<Option<Vec<_>>>()
        })
        .collect()
}

/// A finite [x, y] point from JSON.
fn point(p: &Value) -> Option<Pt2> {
    match p.as_array()?.as_slice() {
        [x, y] => {
            let q = [x.as_f64()?, y.as_f64()?];
            q.iter().all(|c| c.is_finite()).then_some(q)
        }
        _ => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(text: &str) -> Result<VisibleSet> {
        VisibleSet::parse(text, Path::new("g.json"))
    }

    #[test]
    fn parse_errors_are_clear() {
        assert!(parse("{").is_err());
        let e = parse(r#"{"format":"kepler-visible/1","faces":[{"id":0,"visible":[[[1]]]}]}"#)
            .unwrap_err();
        assert!(e.to_string().contains("faces[0]"), "{e}");
        assert!(e.to_string().starts_with("g.json:1:"), "{e}");
        let s = parse(
            r#"{"format":"kepler-visible/1","faces":[{"id":3,"object":"a","visible":[[[[0,0],[1,0],[0,1]]]]}]}"#,
        )
        .unwrap();
        assert_eq!(s.faces[&3].visible[0][0].len(), 3);
    }

    #[test]
    fn errors_name_the_line() {
        let e = parse("{\n\"format\": \"kepler-visible/1\",\n\"faces\": [1,,]}").unwrap_err();
        assert!(e.to_string().starts_with("g.json:3:"), "{e}");
        assert!(!e.to_string().contains(" at line "), "{e}");
        let text = "{\"format\":\"kepler-visible/1\",\"x\":{\"faces\":[0]},\n\"faces\":[\n{\"id\":0,\"visible\":[]},\n  {\"id\":\"a]\\\"\",\"visible\":[]}]}";
        let e = parse(text).unwrap_err();
        assert!(e.to_string().starts_with("g.json:4:3: faces[1]"), "{e}");
        let e = parse("{\"faces\":[]}").unwrap_err();
        assert!(e.to_string().starts_with("g.json:1:1: not a kepler"), "{e}");
        let e = VisibleSet::read(Path::new("/nonexistent/g.json")).unwrap_err();
        assert!(e.to_string().starts_with("/nonexistent/g.json: "), "{e}");
        assert_eq!(element_offset("{\"faces\":[1, 2]}", "faces", 1), Some(13));
        assert_eq!(element_offset("{\"faces\":[1, 2]}", "faces", 2), None);
    }

    #[test]
    fn repeated_ids_are_refused() {
        let e = parse(r#"{"format":"kepler-visible/1","faces":[{"id":1,"visible":[]},{"id":1,"visible":[]}]}"#)
            .unwrap_err();
        assert!(e.to_string().contains("appears twice"), "{e}");
    }
}
