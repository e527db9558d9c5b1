//! One-way imports: a test that fails when a module of the crate imports a later stage.
//!
//! Every `crate::NAME` path in src (use lines and inline paths, outside comments, string and
//! character literals and `#[cfg(test)]` items) is checked against [`RANKS`]: a module may
//! name its own module, modules of a lower rank, and those of rank [`ANYWHERE`]. A root
//! re-export (`crate::Error`) counts as the module it comes from. Tests may reach any stage
//! to build their fixtures, so `#[cfg(test)]` items are not checked.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// Rank of a module that any other may import.
const ANYWHERE: u32 = u32::MAX;

/// The top-level modules in the order data flows: each may import only lower ranks.
const RANKS: &[(&str, u32)] = &[
    ("error", 0),      // errors and warnings: the foundation, importing nothing
    ("geom", 1),       // points, boxes and the one home of predicates: the foundation
    ("scene", 2),      // the database every stage reads: imports only the foundation
    ("primitives", 3), // named solids as meshes, built from geometry; load names them
    ("load", 4),       // stage 1: scene and mesh files to a scene
    ("prepare", 5),    // stage 2: solidity, INBOXes and object trees, once per scene
    ("tribox", 6),     // triboxes and interference: walks prepare's trees; view's LOD uses it
    ("view", 7),       // stage 3: a camera, the cull, screen faces and the view tree
    ("visibility", 8), // stage 4: VISFAC, the visible part of every face
    ("exact", 9),      // the independent checker: reads views, visibility and prepare's numbers
    ("query", 9),      // Franklin's queries by path and point: over views, visibility and triboxes
    ("emit", 10),      // stage 5: hidden lines, plots and the writers
    ("check", 10),     // checking a render: the exact checker and golden comparison
    ("pipeline", 11),  // runs the stages after prepare as one call
    ("describe", 11),  // a prepared scene described (`kepler info`): reads every stage's facts
    ("tests", 99),     // the unit tests gathered in src/tests: fixtures may reach any stage
    ("count", 0),      // units of work done, per chunk: all an algorithm is handed, never a bar
    ("renumber", 1),   // indices renumbered by first use on all threads: imports only chunked
    ("chunked", 0),    // big lists built in fixed chunks on all threads: imports nothing of ours
    ("rank_sort", 0),  // a stable sort by small whole-number ranks on all threads: imports nothing
    ("progress", 1),   // stages and phases a watcher reads: entered by the stage entry points
];

/// The rank of a top-level module, if it has one.
fn rank(module: &str) -> Option<u32> {
    RANKS.iter().find(|(m, _)| *m == module).map(|&(_, r)| r)
}

/// `src` with comments, string literals and character literals blanked to spaces (line
/// breaks kept, so that line numbers stay right).
fn strip(src: &str) -> String {
    let c: Vec<char> = src.chars().collect();
    let mut out = String::with_capacity(src.len());
    let mut i = 0;
    while i < c.len() {
        let end = literal_end(&c, i);
        if end > i {
            out.extend(
                c[i..end]
                    .iter()
                    .map(|&x| if x == '\n' { '\n' } else { ' ' }),
            );
            i = end;
        } else {
            out.push(c[i]);
            i += 1;
        }
    }
    out
}

/// The end of the comment or literal that starts at `i`, or `i` when none does.
fn literal_end(c: &[char], i: usize) -> usize {
    let at = |k: usize| c.get(k).copied();
    match (at(i), at(i + 1)) {
        (Some('/'), Some('/')) => (i..c.len()).find(|&k| c[k] == '\n').unwrap_or(c.len()),
        (Some('/'), Some('*')) => find_from(c, i + 2, &['*', '/']).map_or(c.len(), |k| k + 2),
        (Some('r'), Some('"' | '#')) if !ident_char(i.checked_sub(1).and_then(at)) => {
            raw_string_end(c, i + 1).unwrap_or(i)
        }
        (Some('"'), _) => quoted_end(c, i, '"'),
        (Some('\''), Some('\\')) => quoted_end(c, i, '\''),
        (Some('\''), Some(_)) if at(i + 2) == Some('\'') => i + 3,
        _ => i,
    }
}

/// True for a character that can be part of an identifier.
fn ident_char(x: Option<char>) -> bool {
    x.is_some_and(|x| x.is_alphanumeric() || x == '_')
}

/// The first index at or after `from` where `pat` starts.
fn find_from(c: &[char], from: usize, pat: &[char]) -> Option<usize> {
    (from..c.len()).find(|&k| c[k..].starts_with(pat))
}

/// The end of the literal quoted by `q` that opens at `i` (backslash escapes honoured).
fn quoted_end(c: &[char], i: usize, q: char) -> usize {
    let mut k = i + 1;
    while k < c.len() && c[k] != q {
        k += if c[k] == '\\' { 2 } else { 1 };
    }
    (k + 1).min(c.len())
}

/// The end of a raw string whose hashes (or quote) start at `i`; None for a raw identifier.
fn raw_string_end(c: &[char], i: usize) -> Option<usize> {
    let hashes = c[i..].iter().take_while(|&&x| x == '#').count();
    if c.get(i + hashes) != Some(&'"') {
        return None;
    }
    let close: Vec<char> = std::iter::once('"').chain(vec!['#'; hashes]).collect();
    Some(find_from(c, i + hashes + 1, &close).map_or(c.len(), |k| k + close.len()))
}

/// `code` (already stripped) with every `#[cfg(test)]` item blanked: up to its `;` or the
/// brace that closes its body.
fn drop_test_items(code: &str) -> String {
    let mut c: Vec<char> = code.chars().collect();
    let pat: Vec<char> = "#[cfg(test)]".chars().collect();
    let mut from = 0;
    while let Some(start) = find_from(&c, from, &pat) {
        let end = item_end(&c, start + pat.len());
        for x in &mut c[start..end] {
            if *x != '\n' {
                *x = ' ';
            }
        }
        from = end;
    }
    c.into_iter().collect()
}

/// The end of the item starting at `i`: after its first `;` outside brackets and braces,
/// or after the brace closing its first `{`.
fn item_end(c: &[char], i: usize) -> usize {
    let (mut braces, mut brackets) = (0usize, 0usize);
    for (k, &x) in c.iter().enumerate().skip(i) {
        match x {
            ';' if braces == 0 && brackets == 0 => return k + 1,
            '(' | '[' => brackets += 1,
            ')' | ']' => brackets = brackets.saturating_sub(1),
            '{' => braces += 1,
            '}' if braces == 1 => return k + 1,
            '}' => braces = braces.saturating_sub(1),
            _ => {}
        }
    }
    c.len()
}

/// Every module or root item a piece of code names through `crate::`, with its line: the
/// first segment of `crate::a::b` and each first segment inside `crate::{a::b, c::{d, e}}`.
fn crate_refs(code: &str) -> Vec<(usize, String)> {
    let mut refs = Vec::new();
    let mut from = 0;
    while let Some(k) = code[from..].find("crate::").map(|k| k + from) {
        from = k + "crate::".len();
        let before = code[..k].chars().next_back();
        if ident_char(before) || before == Some('$') {
            continue;
        }
        let line = code[..k].matches('\n').count() + 1;
        refs.extend(first_segments(&code[from..]).into_iter().map(|s| (line, s)));
    }
    refs
}

/// The names at the head of `rest`: one identifier, or the first segment of each path in a
/// `{...}` group (nested groups skipped).
fn first_segments(rest: &str) -> Vec<String> {
    let ident = |s: &str| -> String { s.chars().take_while(|&x| ident_char(Some(x))).collect() };
    let Some(group) = rest.strip_prefix('{') else {
        return vec![ident(rest)];
    };
    let (mut names, mut depth, mut start) = (Vec::new(), 0usize, true);
    for (k, x) in group.char_indices() {
        match x {
            '{' => depth += 1,
            '}' if depth == 0 => break,
            '}' => depth -= 1,
            ',' if depth == 0 => start = true,
            x if start && !x.is_whitespace() => {
                names.push(ident(&group[k..]));
                start = false;
            }
            _ => {}
        }
    }
    names
}

/// Root re-exports of lib.rs (`pub use MODULE::...;` at the top level): item name to module.
fn root_items(lib: &str) -> BTreeMap<String, String> {
    let mut items = BTreeMap::new();
    for stmt in lib.split(';') {
        let Some(body) = stmt.trim_start().strip_prefix("pub use ") else {
            continue;
        };
        let Some((module, names)) = body.split_once("::") else {
            continue;
        };
        for name in names.split(|x: char| "{},".contains(x)) {
            let name = name.split(" as ").last().unwrap_or("").trim();
            let name = name.rsplit("::").next().unwrap_or("");
            if !name.is_empty() {
                items.insert(name.to_string(), module.trim().to_string());
            }
        }
    }
    items
}

/// The imports of `module`'s source `src` that run backwards, or name nothing ranked.
fn violations(module: &str, src: &str, roots: &BTreeMap<String, String>) -> Vec<String> {
    let Some(own) = rank(module) else {
        return vec![format!("{module}: not in RANKS")];
    };
    let code = drop_test_items(&strip(src));
    let mut found = Vec::new();
    for (line, name) in crate_refs(&code) {
        let target = roots.get(&name).map_or(name.as_str(), |m| m.as_str());
        match rank(target) {
            None => found.push(format!("line {line}: crate::{name} has no rank")),
            Some(r) if target != module && r != ANYWHERE && r >= own => found.push(format!(
                "line {line}: crate::{name} ({target}) comes after {module}"
            )),
            _ => {}
        }
    }
    found
}

/// The top-level module a source file under `src` belongs to; None for lib.rs and this file.
fn module_of(src: &Path, file: &Path) -> Option<String> {
    let first = file.strip_prefix(src).ok()?.components().next()?;
    let name = first.as_os_str().to_str()?.trim_end_matches(".rs");
    (name != "lib" && name != "layering").then(|| name.to_string())
}

/// Every `.rs` file below `dir`, sorted.
fn sources(dir: &Path) -> Vec<PathBuf> {
    let mut files = Vec::new();
    for entry in std::fs::read_dir(dir).expect("src is readable") {
        let path = entry.expect("src entries are readable").path();
        if path.is_dir() {
            files.extend(sources(&path));
        } else if path.extension().is_some_and(|e| e == "rs") {
            files.push(path);
        }
    }
    files.sort();
    files
}

#[cfg(test)]
mod tests {
    use super::*;

    fn src_dir() -> PathBuf {
        Path::new(env!("CARGO_MANIFEST_DIR")).join("src")
    }

    fn roots() -> BTreeMap<String, String> {
        root_items(&std::fs::read_to_string(src_dir().join("lib.rs")).unwrap())
    }

    #[test]
    fn no_module_imports_a_later_stage() {
        let (src, roots) = (src_dir(), roots());
        let mut found = Vec::new();
        for file in sources(&src) {
            let Some(module) = module_of(&src, &file) else {
                continue;
            };
            let text = std::fs::read_to_string(&file).unwrap();
            let shown = file.strip_prefix(&src).unwrap().display().to_string();
            found.extend(
                violations(&module, &text, &roots)
                    .into_iter()
                    .map(|v| format!("{shown} {v}")),
            );
        }
        assert!(
            found.is_empty(),
            "imports that run backwards:\n{}",
            found.join("\n")
        );
    }

    #[test]
    fn every_module_has_a_rank() {
        let src = src_dir();
        for file in sources(&src) {
            if let Some(module) = module_of(&src, &file) {
                assert!(rank(&module).is_some(), "{module} is missing from RANKS");
            }
        }
    }

    /// A fixture of scene code: a planted import of view (in a use group) and of visibility
    /// (inline) are caught; geom, progress, comments, strings and a test module are not.
    const PLANTED: &str = r##"//! See crate::pipeline for who calls this.
use crate::geom::{Box3, P3};
use crate::{
    progress::{Phase, Progress},
    view::Camera,
};

/// Uses [`crate::emit`] in a doc link only.
pub fn f(c: &Camera) -> usize {
    let s = "crate::pipeline";
    let r = r#"crate::emit"#;
    let ch = '"';
    crate::visibility::count(c) + s.len() + r.len() + ch.len_utf8()
}

#[cfg(test)]
mod tests {
    use crate::pipeline::render;
    fn g() { let _ = "}"; crate::emit::draw(); }
}

pub const ALSO: usize = crate::error::CODE;
"##;

    #[test]
    fn a_planted_backwards_import_is_caught() {
        let found = violations("scene", PLANTED, &roots());
        assert_eq!(found.len(), 2, "{found:#?}");
        assert!(found[0].starts_with("line 3: crate::view "), "{}", found[0]);
        assert!(
            found[1].starts_with("line 13: crate::visibility "),
            "{}",
            found[1]
        );
        assert!(violations("pipeline", PLANTED, &roots()).is_empty());
    }

    #[test]
    fn root_items_count_as_their_module() {
        let found = violations("geom", "use crate::{Error, Scene};\n", &roots());
        assert_eq!(found.len(), 1, "{found:#?}");
        assert!(
            found[0].contains("(scene) comes after geom"),
            "{}",
            found[0]
        );
    }
}
