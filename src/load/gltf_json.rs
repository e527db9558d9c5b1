//! glTF's JSON read with the path of every value (`nodes[3].mesh`), so that each error names
//! the file and the place in it.

use std::path::Path;

use serde_json::Value;

use crate::error::{Error, Location, Result};

/// A value of a glTF document and where it is: the file and the JSON path from the top.
#[derive(Debug, Clone)]
pub(super) struct J<'a> {
    /// The value.
    pub v: &'a Value,
    /// Its JSON path (`nodes[3].mesh`; "" for the top).
    pub path: String,
    /// The glTF file.
    pub file: &'a Path,
}

impl<'a> J<'a> {
    /// The top of the document of `file`.
    pub(super) fn top(v: &'a Value, file: &'a Path) -> J<'a> {
        J {
            v,
            path: String::new(),
            file,
        }
    }

    /// An error about this value: `file: path: msg`.
    pub(super) fn err(&self, msg: impl std::fmt::Display) -> Error {
        let at = if self.path.is_empty() {
            "the top object"
        } else {
            &self.path
        };
        Error::invalid(Location::file(self.file), format!("{at}: {msg}"))
    }

    /// The member `key` of this object, if present (and not null).
    pub(super) fn get(&self, key: &str) -> Option<J<'a>> {
        let v = self.v.as_object()?.get(key)?;
        if v.is_null() {
            return None;
        }
        let path = if self.path.is_empty() {
            key.to_string()
        } else {
            format!("{}.{key}", self.path)
        };
        Some(J {
            v,
            path,
            file: self.file,
        })
    }

    /// The member `key`, or an error saying it is missing.
    pub(super) fn req(&self, key: &str) -> Result<J<'a>> {
        self.get(key).ok_or_else(|| {
            let missing = J {
                v: self.v,
                path: if self.path.is_empty() {
                    key.to_string()
                } else {
                    format!("{}.{key}", self.path)
                },
                file: self.file,
            };
            missing.err("required but missing")
        })
    }

    /// The elements of this array, each with its path.
    pub(super) fn items(&self) -> Result<Vec<J<'a>>> {
        let a = self
            .v
            .as_array()
            .ok_or_else(|| self.err(format!("expected an array, found {}", kind(self.v))))?;
        Ok(a.iter()
            .enumerate()
            .map(|(i, v)| J {
                v,
                path: format!("{}[{i}]", self.path),
                file: self.file,
            })
            .collect())
    }

    /// The elements of the array member `key` (none when it is absent).
    pub(super) fn list(&self, key: &str) -> Result<Vec<J<'a>>> {
        self.get(key).map_or(Ok(Vec::new()), |a| a.items())
    }

    /// A non-negative integer (an index, a count or a byte length).
    pub(super) fn uint(&self) -> Result<u64> {
        self.v.as_u64().ok_or_else(|| {
            self.err(format!(
                "expected a non-negative integer, found {}",
                shown(self.v)
            ))
        })
    }

    /// An index into the top-level array `array` of length `len`.
    pub(super) fn index(&self, array: &str, len: usize) -> Result<usize> {
        let i = self.uint()?;
        if i < len as u64 {
            return Ok(i as usize);
        }
        let what = match array {
            "meshes" => "mesh",
            a => a.strip_suffix('s').unwrap_or(a),
        };
        Err(self.err(format!(
            "{what} {i} does not exist (the file has {len} {array})"
        )))
    }

    /// The member `key` as a non-negative integer, `default` when absent.
    pub(super) fn uint_or(&self, key: &str, default: u64) -> Result<u64> {
        self.get(key).map_or(Ok(default), |j| j.uint())
    }

    /// A number.
    pub(super) fn number(&self) -> Result<f64> {
        let x = self
            .v
            .as_f64()
            .ok_or_else(|| self.err(format!("expected a number, found {}", shown(self.v))))?;
        if x.is_finite() {
            Ok(x)
        } else {
            Err(self.err("the number is not finite"))
        }
    }

    /// An array of exactly `n` numbers.
    pub(super) fn numbers(&self, n: usize) -> Result<Vec<f64>> {
        let items = self.items()?;
        if items.len() != n {
            return Err(self.err(format!("expected {n} numbers, found {}", items.len())));
        }
        items.iter().map(J::number).collect()
    }

    /// A string.
    pub(super) fn str(&self) -> Result<&'a str> {
        self.v
            .as_str()
            .ok_or_else(|| self.err(format!("expected a string, found {}", shown(self.v))))
    }

    /// The member `key` as a string, if present.
    pub(super) fn opt_str(&self, key: &str) -> Result<Option<&'a str>> {
        self.get(key).map(|j| j.str()).transpose()
    }
}

/// What kind of JSON value `v` is, for messages.
fn kind(v: &Value) -> &'static str {
    match v {
        Value::Null => "null",
        Value::Bool(_) => "a boolean",
        Value::Number(_) => "a number",
        Value::String(_) => "a string",
        Value::Array(_) => "an array",
        Value::Object(_) => "an object",
    }
}

/// `v` for a message: a number shown, anything else by kind (never a long quote).
fn shown(v: &Value) -> String {
    match v {
        Value::Number(n) => n.to_string(),
        v => kind(v).to_string(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn paths_name_the_place() {
        let v: Value = serde_json::from_str(r#"{"nodes":[{},{"mesh":7,"m":-1}]}"#).unwrap();
        let f = Path::new("m.gltf");
        let top = J::top(&v, f);
        let nodes = top.list("nodes").unwrap();
        let mesh = nodes[1].get("mesh").unwrap();
        assert_eq!(mesh.path, "nodes[1].mesh");
        let e = mesh.index("meshes", 2).unwrap_err().to_string();
        assert_eq!(
            e,
            "m.gltf: nodes[1].mesh: mesh 7 does not exist (the file has 2 meshes)"
        );
        let e = nodes[1].req("m").unwrap().uint().unwrap_err().to_string();
        assert_eq!(
            e,
            "m.gltf: nodes[1].m: expected a non-negative integer, found -1"
        );
        let e = nodes[0].req("x").unwrap_err().to_string();
        assert_eq!(e, "m.gltf: nodes[0].x: required but missing");
        assert!(top.list("scenes").unwrap().is_empty());
        let e = top
            .req("nodes")
            .unwrap()
            .numbers(3)
            .unwrap_err()
            .to_string();
        assert!(e.contains("nodes: expected 3 numbers, found 2"), "{e}");
    }
}
