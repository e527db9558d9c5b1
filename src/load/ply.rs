//! PLY loading: a text header describing elements, then an ASCII or binary (little- or big-endian) body.

use std::path::Path;

use super::mesh_file::{coord_problem, finish, stem_name, MeshFile, MeshGroup};
use super::text::{decode, Word, Words};
use crate::count::{Count, Cursor};
use crate::error::{Error, Location, Pos, Result};
use crate::geom::P3;

/// Parses a PLY file into one group named after the file stem: vertices from element `vertex`
/// (properties `x`, `y`, `z` of any numeric type), faces from the list property
/// `vertex_indices` (or `vertex_index`) of element `face`. Other elements and properties are
/// read and skipped. All vertices are kept, used or not.
///
/// # Errors
/// [`Error::Parse`] for a malformed header or body (at `file:line:col`, or at the byte offset
/// in a binary body), truncated data and missing elements or properties; [`Error::Invalid`] for
/// indices out of range, faces with fewer than 3 vertices and NaN or huge coordinates.
///
/// The bytes parsed go to `done` as it goes, once per step of bytes.
pub(crate) fn parse_ply(path: &Path, bytes: &[u8], done: Count) -> Result<MeshFile> {
    let mut cursor = Cursor::new(done);
    let header = parse_header(path, bytes)?;
    let roles = Roles::find(path, &header)?;
    let body = bytes.get(header.body..).unwrap_or_default();
    let group = match header.encoding {
        Encoding::Ascii => {
            let text = decode(path, body, header.body_line)?;
            let words = Words::new(text, header.body_line);
            read_body(
                path,
                &header,
                &roles,
                AsciiBody {
                    path,
                    words,
                    last: None,
                    start: header.body,
                },
                bytes.len(),
                &mut cursor,
            )?
        }
        Encoding::Little | Encoding::Big => {
            let big = header.encoding == Encoding::Big;
            let b = BinaryBody {
                path,
                bytes,
                pos: header.body,
                last: header.body,
                big,
            };
            read_body(path, &header, &roles, b, bytes.len(), &mut cursor)?
        }
    };
    cursor.finish(bytes.len());
    finish(path, vec![group])
}

/// A PLY scalar type.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Scalar {
    I8,
    U8,
    I16,
    U16,
    I32,
    U32,
    F32,
    F64,
}

impl Scalar {
    /// The type named `s` (old and new PLY spellings).
    fn from_name(s: &str) -> Option<Self> {
        Some(match s {
            "char" | "int8" => Scalar::I8,
            "uchar" | "uint8" => Scalar::U8,
            "short" | "int16" => Scalar::I16,
            "ushort" | "uint16" => Scalar::U16,
            "int" | "int32" => Scalar::I32,
            "uint" | "uint32" => Scalar::U32,
            "float" | "float32" => Scalar::F32,
            "double" | "float64" => Scalar::F64,
            _ => return None,
        })
    }

    /// Size in bytes in a binary body.
    fn size(self) -> usize {
        match self {
            Scalar::I8 | Scalar::U8 => 1,
            Scalar::I16 | Scalar::U16 => 2,
            Scalar::I32 | Scalar::U32 | Scalar::F32 => 4,
            Scalar::F64 => 8,
        }
    }

    /// The range of an integer type; `None` for floating-point types.
    fn int_range(self) -> Option<(i64, i64)> {
        match self {
            Scalar::I8 => Some((i8::MIN.into(), i8::MAX.into())),
            Scalar::U8 => Some((0, u8::MAX.into())),
            Scalar::I16 => Some((i16::MIN.into(), i16::MAX.into())),
            Scalar::U16 => Some((0, u16::MAX.into())),
            Scalar::I32 => Some((i32::MIN.into(), i32::MAX.into())),
            Scalar::U32 => Some((0, u32::MAX.into())),
            Scalar::F32 | Scalar::F64 => None,
        }
    }

    /// The value of this type stored in `b` (exactly [`Scalar::size`] bytes).
    fn decode(self, b: &[u8], big: bool) -> f64 {
        macro_rules! num {
            ($t:ty) => {{
                let a = b.try_into().unwrap_or_default();
                (if big {
                    <$t>::from_be_bytes(a)
                } else {
                    <$t>::from_le_bytes(a)
                }) as f64
            }};
        }
        match self {
            Scalar::I8 => num!(i8),
            Scalar::U8 => num!(u8),
            Scalar::I16 => num!(i16),
            Scalar::U16 => num!(u16),
            Scalar::I32 => num!(i32),
            Scalar::U32 => num!(u32),
            Scalar::F32 => num!(f32),
            Scalar::F64 => num!(f64),
        }
    }
}

/// What a property holds: one scalar, or a list (length of type `count`, items of type `item`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Kind {
    Scalar(Scalar),
    List { count: Scalar, item: Scalar },
}

/// A property declared in the header.
#[derive(Debug)]
struct Property {
    name: String,
    kind: Kind,
    /// Where it is declared.
    pos: Pos,
}

/// An element declared in the header.
#[derive(Debug)]
struct Element {
    name: String,
    count: u64,
    props: Vec<Property>,
    /// Where it is declared.
    pos: Pos,
}

/// How the body is stored.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Encoding {
    Ascii,
    Little,
    Big,
}

/// A parsed PLY header.
#[derive(Debug)]
struct Header {
    encoding: Encoding,
    elements: Vec<Element>,
    /// Byte offset of the body.
    body: usize,
    /// Line number of the body's first line (for ASCII bodies).
    body_line: usize,
    /// Where `end_header` is.
    end: Pos,
}

/// The byte offset just after the `end_header` line, if there is one.
fn header_end(bytes: &[u8]) -> Option<usize> {
    let mut start = 0;
    while start < bytes.len() {
        let rest = bytes.get(start..).unwrap_or_default();
        let nl = rest.iter().position(|&b| b == b'\n');
        let end = nl.map_or(bytes.len(), |i| start + i);
        if bytes.get(start..end).unwrap_or_default().trim_ascii() == b"end_header" {
            return Some(nl.map_or(end, |_| end + 1));
        }
        start = end + 1;
    }
    None
}

/// Parses the header, up to and including `end_header`.
fn parse_header(path: &Path, bytes: &[u8]) -> Result<Header> {
    let body = header_end(bytes);
    let text = decode(
        path,
        bytes.get(..body.unwrap_or(bytes.len())).unwrap_or_default(),
        1,
    )?;
    let mut hp = HeaderParser {
        path,
        words: Words::new(text, 1),
        encoding: None,
        elements: Vec::new(),
    };
    hp.magic()?;
    loop {
        if !hp.words.next_line() {
            let msg = "unexpected end of file: the PLY header has no 'end_header'";
            return Err(Error::parse(hp.words.here(path), msg));
        }
        let Some(kw) = hp.words.next_in_line() else {
            continue;
        };
        match kw.text {
            "format" => hp.format(kw)?,
            "comment" | "obj_info" => {}
            "element" => hp.element(kw)?,
            "property" => hp.property(kw)?,
            "end_header" => return hp.finish(kw, body.unwrap_or(bytes.len())),
            k => {
                let msg = format!("unknown PLY header keyword '{}'", k.escape_debug());
                return Err(Error::parse(kw.loc(path), msg));
            }
        }
    }
}

/// The state of a header parse.
struct HeaderParser<'a> {
    path: &'a Path,
    words: Words<'a>,
    encoding: Option<Encoding>,
    elements: Vec<Element>,
}

impl<'a> HeaderParser<'a> {
    /// The first line: exactly `ply`.
    fn magic(&mut self) -> Result<()> {
        self.words.next_line();
        let first = self.words.next_in_line();
        if first.is_some_and(|w| w.text == "ply" && w.line() == 1)
            && self.words.next_in_line().is_none()
        {
            Ok(())
        } else {
            let msg = "not a PLY file: the first line must be 'ply'";
            Err(Error::parse(Location::line(self.path, 1, 1), msg))
        }
    }

    /// The next word of the line, or an error at the end of the line saying what is `missing`.
    fn word(&mut self, missing: &str) -> Result<Word<'a>> {
        self.words
            .next_in_line()
            .ok_or_else(|| Error::parse(self.words.here(self.path), format!("missing {missing}")))
    }

    /// `format ENCODING 1.0`.
    fn format(&mut self, kw: Word) -> Result<()> {
        if self.encoding.is_some() {
            return Err(Error::parse(kw.loc(self.path), "duplicate 'format' line"));
        }
        let w = self.word("format (ascii, binary_little_endian or binary_big_endian)")?;
        let encoding = match w.text {
            "ascii" => Encoding::Ascii,
            "binary_little_endian" => Encoding::Little,
            "binary_big_endian" => Encoding::Big,
            f => {
                return Err(Error::parse(
                    w.loc(self.path),
                    format!("unknown PLY format '{}'", f.escape_debug()),
                ))
            }
        };
        let v = self.word("format version")?;
        if !matches!(v.text, "1.0" | "1") {
            let msg = format!(
                "unsupported PLY version '{}' (expected 1.0)",
                v.text.escape_debug()
            );
            return Err(Error::parse(v.loc(self.path), msg));
        }
        self.encoding = Some(encoding);
        Ok(())
    }

    /// `element NAME COUNT`.
    fn element(&mut self, kw: Word) -> Result<()> {
        let name = self.word("element name")?;
        if self.elements.iter().any(|e| e.name == name.text) {
            let msg = format!("duplicate element '{}'", name.text.escape_debug());
            return Err(Error::parse(name.loc(self.path), msg));
        }
        let c = self.word("element count")?;
        let count: u64 = c.text.parse().map_err(|_| {
            Error::parse(
                c.loc(self.path),
                format!("invalid element count '{}'", c.text.escape_debug()),
            )
        })?;
        self.elements.push(Element {
            name: name.text.to_string(),
            count,
            props: Vec::new(),
            pos: kw.pos(),
        });
        Ok(())
    }

    /// A scalar type word.
    fn scalar(&mut self) -> Result<Scalar> {
        let w = self.word("property type")?;
        Scalar::from_name(w.text).ok_or_else(|| {
            Error::parse(
                w.loc(self.path),
                format!("unknown PLY type '{}'", w.text.escape_debug()),
            )
        })
    }

    /// `property TYPE NAME` or `property list COUNT_TYPE ITEM_TYPE NAME`.
    fn property(&mut self, kw: Word) -> Result<()> {
        if self.elements.is_empty() {
            return Err(Error::parse(
                kw.loc(self.path),
                "property declared before any element",
            ));
        }
        let kind = if self
            .words
            .clone()
            .next_in_line()
            .is_some_and(|w| w.text == "list")
        {
            self.words.next_in_line();
            let at = self.words.clone().next_in_line();
            let count = self.scalar()?;
            if count.int_range().is_none() {
                let loc = at.map_or_else(|| self.words.here(self.path), |w| w.loc(self.path));
                return Err(Error::parse(
                    loc,
                    "a list's length type must be an integer type",
                ));
            }
            Kind::List {
                count,
                item: self.scalar()?,
            }
        } else {
            Kind::Scalar(self.scalar()?)
        };
        let name = self.word("property name")?.text.to_string();
        if let Some(e) = self.elements.last_mut() {
            e.props.push(Property {
                name,
                kind,
                pos: kw.pos(),
            });
        }
        Ok(())
    }

    /// At `end_header`: the complete header, its body starting at byte `body`.
    fn finish(self, kw: Word, body: usize) -> Result<Header> {
        let Some(encoding) = self.encoding else {
            return Err(Error::parse(
                kw.loc(self.path),
                "the PLY header has no 'format' line",
            ));
        };
        let elements = self.elements;
        Ok(Header {
            encoding,
            elements,
            body,
            body_line: kw.line() + 1,
            end: kw.pos(),
        })
    }
}

/// Which element and properties hold the vertices and faces.
struct Roles {
    vertex: usize,
    xyz: [usize; 3],
    face: usize,
    indices: usize,
}

impl Roles {
    /// Finds the vertex coordinates and face index lists, or says what is missing.
    fn find(path: &Path, h: &Header) -> Result<Roles> {
        let at = |pos: Pos| Location {
            file: path.to_path_buf(),
            pos,
        };
        let element = |name: &str| {
            h.elements
                .iter()
                .position(|e| e.name == name)
                .ok_or_else(|| {
                    Error::parse(
                        at(h.end),
                        format!("the PLY header declares no '{name}' element"),
                    )
                })
        };
        let vertex = element("vertex")?;
        let ve = &h.elements[vertex];
        if ve.count > u64::from(u32::MAX) + 1 {
            return Err(Error::invalid(
                at(ve.pos),
                format!("too many vertices ({})", ve.count),
            ));
        }
        let mut xyz = [0; 3];
        for (slot, axis) in xyz.iter_mut().zip(["x", "y", "z"]) {
            let p = ve.props.iter().position(|p| p.name == axis);
            *slot = match p.map(|p| (p, ve.props[p].kind)) {
                Some((p, Kind::Scalar(_))) => p,
                Some((p, Kind::List { .. })) => {
                    let msg = format!("vertex property '{axis}' must be a scalar, not a list");
                    return Err(Error::parse(at(ve.props[p].pos), msg));
                }
                None => {
                    let msg = format!("element 'vertex' has no property '{axis}'");
                    return Err(Error::parse(at(ve.pos), msg));
                }
            };
        }
        let face = element("face")?;
        let fe = &h.elements[face];
        let p = fe
            .props
            .iter()
            .position(|p| p.name == "vertex_indices" || p.name == "vertex_index");
        let Some(indices) = p else {
            let msg = "element 'face' has no list property 'vertex_indices' (or 'vertex_index')";
            return Err(Error::parse(at(fe.pos), msg));
        };
        let prop = &fe.props[indices];
        match prop.kind {
            Kind::List { item, .. } if item.int_range().is_some() => Ok(Roles {
                vertex,
                xyz,
                face,
                indices,
            }),
            _ => {
                let msg = format!("face property '{}' must be a list of integers", prop.name);
                Err(Error::parse(at(prop.pos), msg))
            }
        }
    }
}

/// A source of body values, ASCII or binary.
trait Body {
    /// Moves to the next element instance; false at the end of the data.
    fn begin(&mut self) -> bool;
    /// The next value, read as type `ty`; `None` if the data (or the instance's line) ends first.
    fn value(&mut self, ty: Scalar) -> Result<Option<f64>>;
    /// Skips `n` values of type `ty`; false if the data ends first.
    fn skip(&mut self, ty: Scalar, n: u64) -> Result<bool>;
    /// Checks that the element instance is over.
    fn end(&mut self, what: &str) -> Result<()>;
    /// Where the last value read is.
    fn last_pos(&self) -> Pos;
    /// The file offset read up to (for progress).
    fn offset(&self) -> usize;
    /// The error for data ending before `what`.
    fn missing(&self, what: &str) -> Error;
}

/// An ASCII body: one element instance per line, values separated by blanks.
struct AsciiBody<'a> {
    path: &'a Path,
    words: Words<'a>,
    last: Option<Word<'a>>,
    /// The file offset of the body's first byte.
    start: usize,
}

impl Body for AsciiBody<'_> {
    fn begin(&mut self) -> bool {
        self.words.next_line()
    }

    fn value(&mut self, ty: Scalar) -> Result<Option<f64>> {
        let Some(w) = self.words.next_in_line() else {
            return Ok(None);
        };
        self.last = Some(w);
        let bad = |what: &str| {
            Error::parse(
                w.loc(self.path),
                format!("{what} '{}'", w.text.escape_debug()),
            )
        };
        match ty.int_range() {
            Some((lo, hi)) => {
                let v: i64 = w.text.parse().map_err(|_| bad("invalid integer"))?;
                if v < lo || v > hi {
                    return Err(bad(&format!(
                        "value out of range [{lo}, {hi}] of its type:"
                    )));
                }
                Ok(Some(v as f64))
            }
            None => Ok(Some(w.text.parse().map_err(|_| bad("invalid number"))?)),
        }
    }

    fn skip(&mut self, ty: Scalar, n: u64) -> Result<bool> {
        for _ in 0..n {
            if self.value(ty)?.is_none() {
                return Ok(false);
            }
        }
        Ok(true)
    }

    fn end(&mut self, what: &str) -> Result<()> {
        match self.words.next_in_line() {
            None => Ok(()),
            Some(w) => {
                let msg = format!(
                    "unexpected '{}' after the last property of {what}",
                    w.text.escape_debug()
                );
                Err(Error::parse(w.loc(self.path), msg))
            }
        }
    }

    fn last_pos(&self) -> Pos {
        self.last.map_or(Pos::File, |w| w.pos())
    }

    fn offset(&self) -> usize {
        self.start + self.words.consumed()
    }

    fn missing(&self, what: &str) -> Error {
        let msg = if self.words.at_end() {
            format!("unexpected end of file: expected {what}")
        } else {
            format!("line ends before {what}")
        };
        Error::parse(self.words.here(self.path), msg)
    }
}

/// A binary body: values back to back, little- or big-endian.
struct BinaryBody<'a> {
    path: &'a Path,
    /// The whole file (positions are file offsets).
    bytes: &'a [u8],
    pos: usize,
    last: usize,
    big: bool,
}

impl Body for BinaryBody<'_> {
    fn begin(&mut self) -> bool {
        true
    }

    fn value(&mut self, ty: Scalar) -> Result<Option<f64>> {
        let end = self.pos + ty.size();
        let Some(b) = self.bytes.get(self.pos..end) else {
            return Ok(None);
        };
        self.last = self.pos;
        self.pos = end;
        Ok(Some(ty.decode(b, self.big)))
    }

    fn skip(&mut self, ty: Scalar, n: u64) -> Result<bool> {
        let size = ty.size() as u64;
        let left = (self.bytes.len() - self.pos.min(self.bytes.len())) as u64;
        let fit = n.min(left / size);
        self.pos += (fit * size) as usize;
        Ok(fit == n)
    }

    fn end(&mut self, _what: &str) -> Result<()> {
        Ok(())
    }

    fn last_pos(&self) -> Pos {
        Pos::Byte(self.last as u64)
    }

    fn offset(&self) -> usize {
        self.pos
    }

    fn missing(&self, what: &str) -> Error {
        let msg = format!(
            "unexpected end of file in {what} (the file is {} bytes)",
            self.bytes.len()
        );
        Error::parse(Location::byte(self.path, self.pos as u64), msg)
    }
}

/// Reads every element of the body, keeping vertices and faces.
fn read_body<B: Body>(
    path: &Path,
    h: &Header,
    roles: &Roles,
    body: B,
    file_len: usize,
    cursor: &mut Cursor,
) -> Result<MeshGroup> {
    let cap = |n: u64| n.min(file_len as u64) as usize;
    let mut r = BodyReader {
        path,
        body,
        group: MeshGroup::new(stem_name(path)),
        nverts: h.elements[roles.vertex].count,
    };
    r.group.mesh.vertices.reserve(cap(r.nverts));
    for (ei, el) in h.elements.iter().enumerate() {
        if el.props.is_empty() {
            continue;
        }
        if ei == roles.face {
            r.group.mesh.faces.reserve(cap(el.count));
            r.group.face_pos.reserve(cap(el.count));
        }
        for i in 0..el.count {
            let role = match ei {
                _ if ei == roles.vertex => Role::Vertex(roles.xyz),
                _ if ei == roles.face => Role::Face(roles.indices),
                _ => Role::Other,
            };
            r.instance(el, i, role)?;
            cursor.at(r.body.offset());
        }
    }
    Ok(r.group)
}

/// What an element instance contributes.
#[derive(Clone, Copy)]
enum Role {
    /// A vertex, its coordinates being these properties.
    Vertex([usize; 3]),
    /// A face, its indices being this list property.
    Face(usize),
    /// Nothing.
    Other,
}

/// The state of reading a body.
struct BodyReader<'a, B> {
    path: &'a Path,
    body: B,
    group: MeshGroup,
    /// The declared number of vertices (the bound for indices).
    nverts: u64,
}

impl<B: Body> BodyReader<'_, B> {
    /// Reads instance `i` of element `el`.
    fn instance(&mut self, el: &Element, i: u64, role: Role) -> Result<()> {
        let what = |p: Option<&Property>| {
            let item = format!("{} {i} (of {})", el.name, el.count);
            match p {
                Some(p) => format!("property '{}' of {item}", p.name),
                None => item,
            }
        };
        if !self.body.begin() {
            return Err(self.body.missing(&what(None)));
        }
        let mut xyz = [0.0; 3];
        for (pi, p) in el.props.iter().enumerate() {
            match (p.kind, role) {
                (Kind::Scalar(ty), _) => {
                    let v = self.value(ty, || what(Some(p)))?;
                    if let Role::Vertex(axes) = role {
                        if let Some(k) = axes.iter().position(|&a| a == pi) {
                            xyz[k] = self.coordinate(v)?;
                        }
                    }
                }
                (Kind::List { count, item }, Role::Face(list)) if list == pi => {
                    self.face(count, item, || what(Some(p)))?
                }
                (Kind::List { count, item }, _) => {
                    let n = self.length(count, || what(Some(p)))?;
                    if !self.body.skip(item, n)? {
                        return Err(self.body.missing(&what(Some(p))));
                    }
                }
            }
        }
        self.body.end(&what(None))?;
        if let Role::Vertex(_) = role {
            self.group
                .mesh
                .vertices
                .push(P3::new(xyz[0], xyz[1], xyz[2]));
        }
        Ok(())
    }

    /// The next value, or the error for data ending before `what`.
    fn value(&mut self, ty: Scalar, what: impl Fn() -> String) -> Result<f64> {
        match self.body.value(ty)? {
            Some(v) => Ok(v),
            None => Err(self.body.missing(&what())),
        }
    }

    /// A checked coordinate just read.
    fn coordinate(&self, v: f64) -> Result<f64> {
        match coord_problem(v) {
            Some(problem) => Err(Error::invalid(self.here(), problem)),
            None => Ok(v),
        }
    }

    /// Where the last value read is.
    fn here(&self) -> Location {
        Location {
            file: self.path.to_path_buf(),
            pos: self.body.last_pos(),
        }
    }

    /// A list length (of integer type `ty`): not negative.
    fn length(&mut self, ty: Scalar, what: impl Fn() -> String) -> Result<u64> {
        let n = self.value(ty, what)?;
        if n < 0.0 {
            return Err(Error::invalid(
                self.here(),
                format!("negative list length {n}"),
            ));
        }
        Ok(n as u64)
    }

    /// A face's vertex index list.
    fn face(&mut self, count: Scalar, item: Scalar, what: impl Fn() -> String) -> Result<()> {
        let n = self.length(count, &what)?;
        let pos = self.body.last_pos();
        if n < 3 {
            let msg = format!("face has {n} vertices; a face needs at least 3");
            return Err(Error::invalid(self.here(), msg));
        }
        let mut face = Vec::with_capacity(n.min(64) as usize);
        for _ in 0..n {
            let v = self.value(item, &what)?;
            if v < 0.0 || v >= self.nverts as f64 {
                let msg = format!(
                    "vertex index {v} is out of range: the file has {} vertices",
                    self.nverts
                );
                return Err(Error::invalid(self.here(), msg));
            }
            face.push(v as u32);
        }
        self.group.mesh.faces.push(face);
        self.group.face_pos.push(pos);
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(bytes: &[u8]) -> Result<MeshFile> {
        parse_ply(Path::new("p/m.ply"), bytes, Count::NONE)
    }

    fn err(bytes: &[u8]) -> String {
        parse(bytes).unwrap_err().to_string()
    }

    const ASCII: &str = "ply\r\nformat ascii 1.0\r\ncomment made by hand\r\nobj_info x\r\nelement vertex 5\r\nproperty float x\r\nproperty uchar red\r\nproperty double y\r\nproperty int z\r\nelement face 2\r\nproperty list uchar int vertex_indices\r\nproperty uchar flags\r\nelement edge 1\r\nproperty int a\r\nproperty list uint8 float weights\r\nend_header\r\n0 255 0 0\r\n1 0 0 0\r\n1 0 1 0\r\n0 0 1 2\r\n 5e-1 0 0.5 -3\r\n4 0 1 2 3 7\r\n  3 0 2 4 0\r\n7 2 0.5 0.25\r\n";

    fn expect_square(m: &MeshFile) {
        assert_eq!(m.groups.len(), 1);
        let g = &m.groups[0];
        assert_eq!(g.name, "m");
        assert_eq!(g.mesh.vertices.len(), 5);
        assert_eq!(g.mesh.vertices[3], P3::new(0., 1., 2.));
        assert_eq!(g.mesh.vertices[4], P3::new(0.5, 0.5, -3.));
        assert_eq!(g.mesh.faces, vec![vec![0, 1, 2, 3], vec![0, 2, 4]]);
    }

    #[test]
    fn load_ply_ascii() {
        let m = parse(ASCII.as_bytes()).unwrap();
        expect_square(&m);
        assert_eq!(
            m.groups[0].face_pos,
            vec![
                Pos::Line { line: 22, col: 1 },
                Pos::Line { line: 23, col: 3 }
            ]
        );
    }

    /// Little- or big-endian writer of PLY values.
    struct W(Vec<u8>, bool);

    impl W {
        fn put<const N: usize>(&mut self, le: [u8; N], be: [u8; N]) -> &mut Self {
            self.0.extend_from_slice(if self.1 { &be } else { &le });
            self
        }
        fn f32(&mut self, v: f32) -> &mut Self {
            self.put(v.to_le_bytes(), v.to_be_bytes())
        }
        fn f64(&mut self, v: f64) -> &mut Self {
            self.put(v.to_le_bytes(), v.to_be_bytes())
        }
        fn i16(&mut self, v: i16) -> &mut Self {
            self.put(v.to_le_bytes(), v.to_be_bytes())
        }
        fn u8(&mut self, v: u8) -> &mut Self {
            self.put([v], [v])
        }
        fn u16(&mut self, v: u16) -> &mut Self {
            self.put(v.to_le_bytes(), v.to_be_bytes())
        }
        fn u32(&mut self, v: u32) -> &mut Self {
            self.put(v.to_le_bytes(), v.to_be_bytes())
        }
    }

    /// A binary PLY of the same square and triangle as [`ASCII`], and its header length.
    fn binary(big: bool) -> (Vec<u8>, usize) {
        let format = if big {
            "binary_big_endian"
        } else {
            "binary_little_endian"
        };
        let header = format!(
            "ply\nformat {format} 1.0\nelement vertex 5\nproperty float x\nproperty double y\nproperty short z\nproperty uchar red\nelement face 2\nproperty list uchar float texcoord\nproperty list uchar uint vertex_index\nelement extra 1\nproperty list ushort int stuff\nend_header\n"
        );
        let h = header.len();
        let mut w = W(header.into_bytes(), big);
        for (x, y, z) in [
            (0., 0., 0),
            (1., 0., 0),
            (1., 1., 0),
            (0., 1., 2),
            (0.5, 0.5, -3),
        ] {
            w.f32(x).f64(y).i16(z).u8(9);
        }
        w.u8(2).f32(0.5).f32(0.5).u8(4).u32(0).u32(1).u32(2).u32(3);
        w.u8(0).u8(3).u32(0).u32(2).u32(4);
        w.u16(2).u32(7).u32(8);
        (w.0, h)
    }

    #[test]
    fn load_ply_binary_little_and_big_endian() {
        for big in [false, true] {
            let (b, h) = binary(big);
            assert_eq!(b.len(), h + 75 + 26 + 14 + 10);
            let m = parse(&b).unwrap();
            expect_square(&m);
            let f = (h + 75) as u64;
            assert_eq!(
                m.groups[0].face_pos,
                vec![Pos::Byte(f + 9), Pos::Byte(f + 27)]
            );
        }
    }

    #[test]
    fn load_ply_binary_errors_at_byte_offsets() {
        let (b, h) = binary(false);
        let f = h + 75;
        let e = err(&b[..f + 31]);
        let want = format!(
            "p/m.ply: byte {}: unexpected end of file in property 'vertex_index' of face 1 (of 2) (the file is {} bytes)",
            f + 28,
            f + 31
        );
        assert_eq!(e, want);
        let e = err(&b[..h + 20]);
        assert!(
            e.starts_with(&format!(
                "p/m.ply: byte {}: unexpected end of file in property 'y' of vertex 1",
                h + 19
            )),
            "{e}"
        );
        let e = err(&b[..b.len() - 1]);
        assert!(
            e.starts_with(&format!(
                "p/m.ply: byte {}: unexpected end of file in property 'stuff'",
                b.len() - 4
            )),
            "{e}"
        );

        let mut nan = b.clone();
        nan[h + 30..h + 34].copy_from_slice(&f32::NAN.to_le_bytes());
        let e = parse(&nan).unwrap_err();
        assert!(matches!(e, Error::Invalid(..)));
        assert_eq!(
            e.to_string(),
            format!("p/m.ply: byte {}: coordinate is NaN", h + 30)
        );

        let mut bad = b.clone();
        bad[f + 36..f + 40].copy_from_slice(&5u32.to_le_bytes());
        let e = parse(&bad).unwrap_err();
        assert!(matches!(e, Error::Invalid(..)));
        assert_eq!(
            e.to_string(),
            format!(
                "p/m.ply: byte {}: vertex index 5 is out of range: the file has 5 vertices",
                f + 36
            )
        );

        let mut two = b.clone();
        two[f + 27] = 2;
        let e = err(&two);
        assert_eq!(
            e,
            format!(
                "p/m.ply: byte {}: face has 2 vertices; a face needs at least 3",
                f + 27
            )
        );

        let mut big_list = b.clone();
        big_list[f] = 255;
        let e = err(&big_list);
        assert!(
            e.starts_with(&format!(
                "p/m.ply: byte {}: unexpected end of file in property 'texcoord' of face 0",
                b.len() - 1
            )),
            "{e}"
        );
    }

    #[test]
    fn load_ply_header_errors_have_line_and_column() {
        let v = "element vertex 1\nproperty float x\nproperty float y\nproperty float z\n";
        let f = "element face 1\nproperty list uchar int vertex_indices\n";
        let cases = [
            ("PLY\n".to_string(), "p/m.ply:1:1: not a PLY file"),
            ("ply extra\nformat ascii 1.0\n".to_string(), "p/m.ply:1:1: not a PLY file"),
            ("\nply\n".to_string(), "p/m.ply:1:1: not a PLY file"),
            ("ply\nformat ascii 1.0\n".to_string(), "p/m.ply:3:1: unexpected end of file: the PLY header has no 'end_header'"),
            ("ply\nformat ascii 2.0\nend_header\n".to_string(), "p/m.ply:2:14: unsupported PLY version '2.0'"),
            ("ply\nformat text 1.0\nend_header\n".to_string(), "p/m.ply:2:8: unknown PLY format 'text'"),
            ("ply\nformat ascii\nend_header\n".to_string(), "p/m.ply:2:13: missing format version"),
            ("ply\nformat ascii 1.0\nformat ascii 1.0\nend_header\n".to_string(), "p/m.ply:3:1: duplicate 'format' line"),
            (format!("ply\n{v}{f}end_header\n"), "p/m.ply:8:1: the PLY header has no 'format' line"),
            ("ply\nformat ascii 1.0\nelemnt vertex 3\nend_header\n".to_string(), "p/m.ply:3:1: unknown PLY header keyword 'elemnt'"),
            ("ply\nformat ascii 1.0\nelement vertex -3\nend_header\n".to_string(), "p/m.ply:3:16: invalid element count '-3'"),
            ("ply\nformat ascii 1.0\nproperty float x\nend_header\n".to_string(), "p/m.ply:3:1: property declared before any element"),
            (format!("ply\nformat ascii 1.0\n{v}property  float32x w\n{f}end_header\n"), "p/m.ply:7:11: unknown PLY type 'float32x'"),
            (format!("ply\nformat ascii 1.0\n{v}element face 1\nproperty list float int vertex_indices\nend_header\n"), "p/m.ply:8:15: a list's length type must be an integer type"),
            (format!("ply\nformat ascii 1.0\n{v}element face 1\nproperty list uchar float vertex_indices\nend_header\n"), "p/m.ply:8:1: face property 'vertex_indices' must be a list of integers"),
            (format!("ply\nformat ascii 1.0\n{v}element face 1\nproperty int vertex_indices\nend_header\n"), "p/m.ply:8:1: face property 'vertex_indices' must be a list of integers"),
            (format!("ply\nformat ascii 1.0\n{v}element face 1\nproperty list uchar int\nend_header\n"), "p/m.ply:8:24: missing property name"),
            (format!("ply\nformat ascii 1.0\n{v}element face 1\nproperty list uchar int other\nend_header\n"), "p/m.ply:7:1: element 'face' has no list property 'vertex_indices'"),
            (format!("ply\nformat ascii 1.0\n{v}end_header\n"), "p/m.ply:7:1: the PLY header declares no 'face' element"),
            (format!("ply\nformat ascii 1.0\n{f}end_header\n"), "p/m.ply:5:1: the PLY header declares no 'vertex' element"),
            ("ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nelement face 0\nend_header\n".to_string(), "p/m.ply:3:1: element 'vertex' has no property 'z'"),
            ("ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty list uchar float z\nend_header\n".to_string(), "p/m.ply:6:1: vertex property 'z' must be a scalar, not a list"),
            (format!("ply\nformat ascii 1.0\n{v}element vertex 2\nend_header\n"), "p/m.ply:7:9: duplicate element 'vertex'"),
            (format!("ply\nformat ascii 1.0\n{v}{f}end_header\n0 0 0\n"), "p/m.ply:11:1: unexpected end of file: expected property 'vertex_indices' of face 0 (of 1)"),
            (format!("ply\nformat ascii 1.0\n{v}element face 0\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n"), "p/m.ply: the file contains no faces"),
        ];
        for (text, want) in cases {
            let got = err(text.as_bytes());
            assert!(got.starts_with(want), "{text:?}\n got: {got}\nwant: {want}");
        }
    }

    #[test]
    fn load_ply_invalid_utf8_in_header_or_ascii_body() {
        let e = err(b"ply\nformat ascii 1.0\ncomment \x01\xc3\xa9 \xff\nend_header\n");
        assert!(
            e.starts_with("p/m.ply:3:12: invalid UTF-8 (byte 0xFF)"),
            "{e}"
        );
        let e = err(b"ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\nelement face 0\nproperty list uchar int vertex_indices\nend_header\n1 \x80 3\n");
        assert!(
            e.starts_with("p/m.ply:10:3: invalid UTF-8 (byte 0x80)"),
            "{e}"
        );
    }

    #[test]
    fn load_ply_ascii_body_errors_have_line_and_column() {
        let head = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list char int vertex_indices\nproperty uchar c\nend_header\n";
        let ok_v = "0 0 0\n1 0 0\n0 1 0\n";
        let cases = [
            (format!("{head}0 0 0\n1 O 0\n"), "p/m.ply:12:3: invalid number 'O'"),
            (format!("{head}0 0 0\n1 0\n"), "p/m.ply:12:4: unexpected end of file: expected property 'z' of vertex 1 (of 3)"),
            (format!("{head}0 0 0\n1 0 0 7\n"), "p/m.ply:12:7: unexpected '7' after the last property of vertex 1 (of 3)"),
            (format!("{head}0 0 0\n1 0 0\n0 1 nan\n"), "p/m.ply:13:5: coordinate is NaN"),
            (format!("{head}0 0 0\n1 0 0\n0 1 -1e300\n"), "p/m.ply:13:5: huge coordinate -1e300"),
            (format!("{head}{ok_v}3 0 1 2 300\n"), "p/m.ply:14:9: value out of range [0, 255] of its type: '300'"),
            (format!("{head}{ok_v}3 0 1 2.0 3\n"), "p/m.ply:14:7: invalid integer '2.0'"),
            (format!("{head}{ok_v}3 0 1 3 4\n"), "p/m.ply:14:7: vertex index 3 is out of range: the file has 3 vertices"),
            (format!("{head}{ok_v}3 0 -1 2 4\n"), "p/m.ply:14:5: vertex index -1 is out of range"),
            (format!("{head}{ok_v}2 0 1 4\n"), "p/m.ply:14:1: face has 2 vertices; a face needs at least 3"),
            (format!("{head}{ok_v}-1 4\n"), "p/m.ply:14:1: negative list length -1"),
            (format!("{head}{ok_v}3 0 1\n7\n"), "p/m.ply:14:6: line ends before property 'vertex_indices' of face 0 (of 1)"),
            (format!("{head}{ok_v}3 0 1"), "p/m.ply:14:6: unexpected end of file: expected property 'vertex_indices' of face 0 (of 1)"),
            (format!("{head}{ok_v}"), "p/m.ply:14:1: unexpected end of file: expected property 'vertex_indices' of face 0 (of 1)"),
            (format!("{head}{ok_v}\n3 0 1 2 0\n"), "p/m.ply:14:1: line ends before property 'vertex_indices' of face 0 (of 1)"),
        ];
        for (text, want) in cases {
            let got = err(text.as_bytes());
            assert!(got.starts_with(want), "{text:?}\n got: {got}\nwant: {want}");
        }
        assert!(parse(format!("{head}{ok_v}3 0 1 2 255\n\n").as_bytes()).is_ok());
    }
}
