//! The face limit of a load: scene sizes are known from counts that multiply through the
//! instance tree, so a scene too large to render is refused before anything is expanded,
//! naming the prototype chain that makes it so.

use crate::error::{Error, Location, Result};
use crate::scene::{Content, Object};

/// The default limit on a scene's faces, instances expanded: what a render fits in memory on
/// the machine kepler is developed on (24 GiB, at about 1.5 KB per face at the peak of a
/// render, measured on large meshes and instanced scenes), with room to spare.
pub(crate) const DEFAULT_MAX_FACES: usize = 12_000_000;

/// What a load accepts.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct LoadOptions {
    /// The most faces the scene may have once its instances are expanded.
    pub max_faces: usize,
    /// The directory every file a scene file refers to (includes, meshes) must lie under,
    /// symlinks and `..` resolved (`--include-root`); `None` allows any path.
    pub include_root: Option<std::path::PathBuf>,
}

impl Default for LoadOptions {
    fn default() -> Self {
        LoadOptions {
            max_faces: DEFAULT_MAX_FACES,
            include_root: None,
        }
    }
}

impl LoadOptions {
    /// The default limit on a scene's faces, instances expanded: what a render fits in memory
    /// on the machine kepler is developed on (24 GiB), with room to spare.
    pub const DEFAULT_MAX_FACES: usize = DEFAULT_MAX_FACES;

    /// An error at `at` when `object` (what `what` calls it) expands to more faces than the
    /// limit, naming its prototype chain.
    pub(crate) fn check(&self, object: &Object, what: &str, at: &Location) -> Result<()> {
        let n = object.face_count();
        if n <= self.max_faces {
            return Ok(());
        }
        let chain = prototype_chain(object);
        let via = if chain.is_empty() {
            String::new()
        } else {
            format!(" (prototype chain: {chain})")
        };
        Err(Error::invalid(
            at.clone(),
            format!(
                "{what} has {} faces once its instances are placed{via}, more than the limit of {} (--max-faces)",
                count(n),
                self.max_faces
            ),
        ))
    }
}

/// A face count for messages (`usize::MAX` is where the saturating count stopped).
fn count(n: usize) -> String {
    if n == usize::MAX {
        format!("at least {n}")
    } else {
        n.to_string()
    }
}

/// The prototypes along the heaviest path below `object`, outermost first, each with its
/// face count: `p40 (1099511627776 faces) > p39 (549755813888) > ...`; long chains are cut
/// in the middle.
pub(crate) fn prototype_chain(object: &Object) -> String {
    let mut links: Vec<String> = Vec::new();
    let mut cur = object;
    for _ in 0..256 {
        match &cur.content {
            Content::Instance(i) => {
                let p = &i.prototype;
                let name = if p.name.is_empty() { "?" } else { &p.name };
                let unit = if links.is_empty() { " faces" } else { "" };
                links.push(format!("{name} ({}{unit})", count(p.face_count())));
                cur = p;
            }
            Content::Subobjects(s) => match s.iter().max_by_key(|c| c.face_count()) {
                Some(heaviest) => cur = heaviest,
                None => break,
            },
            Content::Mesh(_) => break,
        }
    }
    if links.len() > 8 {
        let tail = links.split_off(links.len() - 2);
        links.truncate(5);
        links.push("...".into());
        links.extend(tail);
    }
    links.join(" > ")
}

#[cfg(test)]
mod tests {
    use std::path::Path;
    use std::sync::Arc;

    use super::*;
    use crate::geom::{M4, V3};
    use crate::scene::testing::unit_cube;

    /// Prototypes p0 (a cube) .. pN, each placing the previous one twice.
    fn doubling(n: usize) -> Arc<Object> {
        let mut cube = unit_cube();
        cube.name = "p0".into();
        let mut p = Arc::new(cube);
        for k in 1..=n {
            let a = Object::instance("a", p.clone(), M4::identity());
            let b = Object::instance("b", p.clone(), M4::new_translation(&V3::new(2.0, 0., 0.)));
            p = Arc::new(Object::group(format!("p{k}"), vec![a, b]));
        }
        p
    }

    #[test]
    fn counts_multiply_without_expanding() {
        let p = doubling(100);
        assert_eq!(p.face_count(), usize::MAX);
        let p = doubling(40);
        assert_eq!(p.face_count(), 6 << 40);
        assert_eq!(p.vertex_count(), 8 << 40);
        let top = Object::instance("top", p, M4::identity());
        let at = Location::line(Path::new("s.kdl"), 9, 3);
        let e = LoadOptions::default()
            .check(&top, "instance \"top\"", &at)
            .unwrap_err()
            .to_string();
        assert_eq!(
            e,
            "s.kdl:9:3: instance \"top\" has 6597069766656 faces once its instances are placed \
             (prototype chain: p40 (6597069766656 faces) > p39 (3298534883328) > p38 (1649267441664) \
             > p37 (824633720832) > p36 (412316860416) > ... > p1 (12) > p0 (6)), more than the \
             limit of 12000000 (--max-faces)"
        );
        let small = LoadOptions {
            max_faces: 1 << 50,
            ..LoadOptions::default()
        };
        assert!(small.check(&top, "x", &at).is_ok());
    }
}
