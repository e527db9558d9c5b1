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
    /// Parses a `kepler-visible/1` document; errors name `path` and the JSON place.
    pub fn parse(text: &str, path: &Path) -> Result<VisibleSet> {
        let bad = |msg: String| Error::parse(Location::file(path), msg);
        let v: Value = serde_json::from_str(text).map_err(|e| bad(format!("not JSON: {e}")))?;
        if v.get("format").and_then(Value::as_str) != Some("kepler-visible/1") {
            return Err(bad(
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
            .ok_or_else(|| bad("no \"faces\" list".into()))?;
        let mut faces = BTreeMap::new();
        for (i, f) in list.iter().enumerate() {
            let id = f
                .get("id")
                .and_then(Value::as_u64)
                .ok_or_else(|| bad(format!("faces[{i}]: no integer \"id\"")))?;
            let object = f
                .get("object")
                .and_then(Value::as_str)
                .unwrap_or("")
                .to_string();
            let visible = multipolygon(f.get("visible")).ok_or_else(|| {
                bad(format!(
                    "faces[{i}] (id {id}): \"visible\" is not a multipolygon"
                ))
            })?;
            if faces.insert(id, SetFace { object, visible }).is_some() {
                return Err(bad(format!("faces[{i}]: id {id} appears twice")));
            }
        }
        Ok(VisibleSet { faces, matrix })
    }
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
        assert!(e.to_string().starts_with("g.json"), "{e}");
        let s = parse(
            r#"{"format":"kepler-visible/1","faces":[{"id":3,"object":"a","visible":[[[[0,0],[1,0],[0,1]]]]}]}"#,
        )
        .unwrap();
        assert_eq!(s.faces[&3].visible[0][0].len(), 3);
    }

    #[test]
    fn repeated_ids_are_refused() {
        let e = parse(r#"{"format":"kepler-visible/1","faces":[{"id":1,"visible":[]},{"id":1,"visible":[]}]}"#)
            .unwrap_err();
        assert!(e.to_string().contains("appears twice"), "{e}");
    }
}
