//! The `kepler-visible/1` visible-polygon set: canonical JSON (same input, same bytes).
//!
//! Faces by id, one per line; rings start at their least point (x, then y); numbers in the
//! shortest form that reads back to the same f64, with -0 written as 0. A perspective camera
//! also carries `near` (the near plane, the least w' kept by clipping) and `eye`. Rounding
//! dust is left out by the rule of [`super::dust`] (ring points a few ulps apart merged,
//! regions of area within the rounding of zero dropped); each face's `area` is that of the
//! rings written.

use std::borrow::Cow;
use std::fmt::Write as _;
use std::io;

use rayon::prelude::*;

use super::dust::{clean, dust_delta, extent_with};
use crate::count::Count;
use crate::geom::poly2::{multipolygon_area, Pt2};
use crate::scene::flatten::write_num;
use crate::scene::FaceId;
use crate::view::{Projection, View};
use crate::visibility::{FaceVisibility, Visibility};

/// Polylines of a line drawing, in screen space.
#[derive(Debug, Clone, Default, PartialEq)]
pub(crate) struct Lines {
    /// Visible polylines.
    pub visible: Vec<Vec<Pt2>>,
    /// Hidden polylines.
    pub hidden: Vec<Vec<Pt2>>,
}

/// Shortest round-trip form of a finite number, -0 as 0.
pub(crate) fn num(x: f64) -> String {
    crate::scene::flatten::num(x)
}

fn point(s: &mut String, p: &Pt2) {
    s.push('[');
    write_num(s, p[0]);
    s.push(',');
    write_num(s, p[1]);
    s.push(']');
}

fn ring(s: &mut String, r: &[Pt2]) {
    s.push('[');
    for (i, p) in r.iter().enumerate() {
        if i > 0 {
            s.push(',');
        }
        point(s, p);
    }
    s.push(']');
}

fn list<T>(s: &mut String, items: &[T], mut each: impl FnMut(&mut String, &T)) {
    s.push('[');
    for (i, it) in items.iter().enumerate() {
        if i > 0 {
            s.push(',');
        }
        each(s, it);
    }
    s.push(']');
}

/// The JSON document for a view's visible-polygon set (faces with nothing visible, or only
/// rounding dust, left out), with `lines` when given.
///
/// The solved faces written go to `done`, once per chunk of faces.
pub(crate) fn to_json(view: &View, vis: &Visibility, lines: Option<&Lines>, done: Count) -> String {
    let mut out = Sink {
        s: String::with_capacity(256 + vis.solved_count() * 128),
        to: None,
        ..Sink::default()
    };
    match json_into(&mut out, view, vis, lines, done) {
        Ok(()) => out.s,
        Err(_) => unreachable!("a string takes every write"),
    }
}

/// [`to_json`] written to `w` as it is made, in pieces of about [`SPILL_AT`] bytes: the
/// document is never held whole (ten million faces make over a gigabyte of text). The bytes
/// are those of [`to_json`].
///
/// The solved faces written go to `done`, once per chunk of faces.
pub(crate) fn write_json(
    view: &View,
    vis: &Visibility,
    lines: Option<&Lines>,
    w: &mut dyn io::Write,
    done: Count,
) -> io::Result<()> {
    write_json_spilling(view, vis, lines, w, done, SPILL_AT)
}

/// [`write_json`], writing whenever `spill_at` bytes are gathered.
fn write_json_spilling(
    view: &View,
    vis: &Visibility,
    lines: Option<&Lines>,
    w: &mut dyn io::Write,
    done: Count,
    spill_at: usize,
) -> io::Result<()> {
    let mut out = Sink {
        s: String::with_capacity(spill_at.min(SPILL_AT) + (SPILL_AT >> 4)),
        to: Some((w, spill_at)),
        ..Sink::default()
    };
    json_into(&mut out, view, vis, lines, done)?;
    out.spill_all()
}

/// How much text [`write_json`] gathers before it writes.
pub(crate) const SPILL_AT: usize = 1 << 20;

/// A piece of text this long is written as it lies rather than gathered: a task's faces
/// (about a hundred kilobytes) are, so the document's bytes are copied once, not twice.
const DIRECT: usize = 1 << 16;

/// Where the text goes: all kept in `s`, or `s` written to the writer of `to` whenever it
/// is as long as `to`'s length.
struct Sink<'w> {
    s: String,
    to: Option<(&'w mut dyn io::Write, usize)>,
    /// Faces formatted between two writes (on all threads).
    batch_faces: usize,
    /// Faces one thread formats at a time.
    task_faces: usize,
}

impl Default for Sink<'_> {
    fn default() -> Self {
        Sink {
            s: String::new(),
            to: None,
            batch_faces: BATCH_FACES,
            task_faces: TASK_FACES,
        }
    }
}

/// Faces formatted between two writes: a batch's text (about 150 bytes a face) is held.
const BATCH_FACES: usize = 1 << 16;

/// Faces one thread formats at a time.
const TASK_FACES: usize = 1 << 10;

impl Sink<'_> {
    /// Writes out the text gathered so far once it is long enough (kept when in memory).
    fn spill(&mut self) -> io::Result<()> {
        match &self.to {
            Some((_, at)) if self.s.len() >= *at => self.spill_all(),
            _ => Ok(()),
        }
    }

    /// Appends `t`: a piece of at least [`DIRECT`] bytes (or as long as a spill) is written
    /// straight from where it lies, after the text gathered before it, not copied first.
    fn put(&mut self, t: &str) -> io::Result<()> {
        match &self.to {
            Some((_, at)) if t.len() >= DIRECT.min(*at) => {
                self.spill_all()?;
                let (w, _) = self.to.as_mut().expect("a writer");
                w.write_all(t.as_bytes())
            }
            _ => {
                self.s.push_str(t);
                self.spill()
            }
        }
    }

    /// Writes out all the text gathered so far (kept when in memory).
    fn spill_all(&mut self) -> io::Result<()> {
        if let Some((w, _)) = self.to.as_mut() {
            w.write_all(self.s.as_bytes())?;
            self.s.clear();
        }
        Ok(())
    }
}

/// Faces per task of the regions' extent.
const EXTENT_TASK: usize = 1 << 12;

/// The document, into `out` piece by piece.
fn json_into(
    out: &mut Sink,
    view: &View,
    vis: &Visibility,
    lines: Option<&Lines>,
    done: Count,
) -> io::Result<()> {
    head(&mut out.s, view);
    out.s.push_str("},\n\"faces\":[");
    // Each leaf's path as a JSON string, once.
    let paths: Vec<String> = view
        .screen
        .leaves
        .iter()
        .map(|l| json_string(&l.path))
        .collect();
    let ids = vis.ids();
    // The greatest coordinate of every region, on all threads (a greatest is the same in
    // any order).
    let delta = dust_delta(
        (0..ids.len())
            .into_par_iter()
            .with_min_len(EXTENT_TASK)
            .map(|k| vis.at(k).fold_points(0.0, extent_with))
            .reduce(|| 0.0, f64::max),
    );
    let (batch_faces, task_faces) = (out.batch_faces, out.task_faces);
    // Formatted on all threads a task of faces at a time, a batch of tasks between writes
    // (the text held is two batches'), joined in face order: the bytes of one thread.
    let format = |lo: usize, hi: usize| -> Vec<String> {
        let tasks: Vec<usize> = (lo..hi).step_by(task_faces).collect();
        tasks
            .par_iter()
            .map(|&a| {
                let b = (a + task_faces).min(hi);
                let mut s = String::new();
                for (k, &id) in (a..b).zip(&ids[a..b]) {
                    face_entry(&mut s, view, &paths, delta, id, vis.at(k));
                }
                s
            })
            .collect()
    };
    let batches: Vec<usize> = (0..ids.len()).step_by(batch_faces).collect();
    let end_of = |b: usize| (b + batch_faces).min(ids.len());
    let mut first = true;
    let mut wrote = |out: &mut Sink, b: usize, texts: Vec<String>| {
        put(out, &texts, &mut first)?;
        done.add(end_of(b) - b);
        Ok::<(), io::Error>(())
    };
    // Each batch is formatted on the pool while this thread writes the one before: the
    // writes (a file's, on this thread alone) no longer leave the pool idle, and two
    // batches' text is held at most. On a thread of the pool as well: waiting at the
    // scope's end, this thread takes up the formatting itself when no other thread has.
    let mut texts = match batches.first() {
        Some(&b) => format(b, end_of(b)),
        None => Vec::new(),
    };
    for (i, &b) in batches.iter().enumerate() {
        let mut next = Vec::new();
        rayon::in_place_scope(|s| {
            if let Some(&c) = batches.get(i + 1) {
                let (next, format) = (&mut next, &format);
                s.spawn(move |_| *next = format(c, end_of(c)));
            }
            wrote(out, b, std::mem::take(&mut texts))
        })?;
        texts = next;
    }
    out.s.push_str("\n]");
    if let Some(l) = lines {
        out.s.push_str(",\n\"lines\":{\"visible\":");
        rings(out, &l.visible)?;
        out.s.push_str(",\n\"hidden\":");
        rings(out, &l.hidden)?;
        out.s.push('}');
    }
    out.s.push_str("}\n");
    Ok(())
}

/// Appends face entries `texts` to `out` (the document's first without its ",", which
/// `first` tells), writing as it goes.
fn put(out: &mut Sink, texts: &[String], first: &mut bool) -> io::Result<()> {
    for t in texts.iter().filter(|t| !t.is_empty()) {
        // Every entry starts ",\n"; the document's first starts "\n".
        let t = if *first { &t[1..] } else { t };
        *first = false;
        out.put(t)?;
    }
    Ok(())
}

/// Face `id`'s entry, ",\n" first, when it shows (not only rounding dust, not occlude-only).
fn face_entry(
    s: &mut String,
    view: &View,
    paths: &[String],
    delta: f64,
    id: FaceId,
    f: FaceVisibility,
) {
    let region = f.visible();
    let visible = clean(&region, delta);
    // An occlude-only object hides what is behind it but is not listed.
    if visible.is_empty() || view.screen.occlude_only(id) {
        return;
    }
    let area = match &visible {
        Cow::Borrowed(_) => f.area,
        Cow::Owned(m) => multipolygon_area(m),
    };
    let leaf = view.screen.leaf_index_of_face(id);
    let _ = write!(s, ",\n{{\"id\":{id},\"object\":{},", paths[leaf as usize]);
    // Faces made by a section cut say so; others are as they always were.
    if view.screen.is_section(id) {
        s.push_str("\"section\":true,");
    }
    s.push_str("\"area\":");
    write_num(s, area);
    s.push_str(",\"visible\":");
    list(s, &visible, |s, poly| list(s, poly, |s, r| ring(s, r)));
    s.push('}');
}

/// The format tag and the camera, up to the camera's closing brace.
fn head(s: &mut String, view: &View) {
    s.push_str("{\"format\":\"kepler-visible/1\",\n\"camera\":{\"projection\":");
    s.push_str(match view.camera.projection {
        Projection::Orthographic => "\"orthographic\"",
        Projection::Perspective => "\"perspective\"",
    });
    s.push_str(",\"matrix\":[");
    for r in 0..4 {
        if r > 0 {
            s.push(',');
        }
        let row: Vec<f64> = (0..4).map(|c| view.camera.matrix[(r, c)]).collect();
        list(s, &row, |s, x| s.push_str(&num(*x)));
    }
    s.push(']');
    if view.camera.projection == Projection::Perspective {
        // The near plane (least w') and the eye: the clipping reproduces from the file alone.
        let _ = write!(s, ",\"near\":{}", num(view.camera.near));
        if let Some(e) = view.camera.eye {
            s.push_str(",\"eye\":");
            list(s, &[e.x, e.y, e.z], |s, x| s.push_str(&num(*x)));
        }
    }
}

/// A list of polylines, spilled polyline by polyline (as [`list`] of [`ring`]s).
fn rings(out: &mut Sink, items: &[Vec<Pt2>]) -> io::Result<()> {
    out.s.push('[');
    for (i, r) in items.iter().enumerate() {
        if i > 0 {
            out.s.push(',');
        }
        ring(&mut out.s, r);
        out.spill()?;
    }
    out.s.push(']');
    Ok(())
}

/// A JSON string literal.
pub(crate) fn json_string(x: &str) -> String {
    serde_json::to_string(x).unwrap_or_else(|_| "\"\"".into())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_are_shortest_round_trip() {
        assert_eq!(num(0.1), "0.1");
        assert_eq!(num(-0.0), "0");
        assert_eq!(num(1e-300), "1e-300");
        assert_eq!(num(2.0), "2");
        for x in [1.0 / 3.0, 12345.678e10, -7.25e-9] {
            assert_eq!(num(x).parse::<f64>().unwrap(), x);
        }
        assert_eq!(json_string("a\"b"), "\"a\\\"b\"");
    }

    /// The three scenes rendered with hidden lines (so that the JSON has `lines`).
    fn rendered() -> Vec<crate::Rendered<'static>> {
        ["polyhedra", "town", "assembly"]
            .into_iter()
            .map(|name| {
                let path = format!("scenes/{name}.kdl");
                let scene = crate::load_scene(
                    path.as_ref(),
                    &crate::LoadOptions::default(),
                    &mut Vec::new(),
                    &crate::Progress::default(),
                )
                .unwrap();
                let scene: &'static crate::Scene = Box::leak(Box::new(scene));
                let opts = crate::RenderOptions {
                    lines: crate::emit::lines::LineOptions {
                        hidden: true,
                        ..Default::default()
                    },
                    outputs: crate::Outputs {
                        drawing: true,
                        ..Default::default()
                    },
                    ..Default::default()
                };
                crate::render(
                    scene,
                    &crate::Camera::three_quarter(),
                    &opts,
                    &crate::Progress::default(),
                )
                .unwrap()
            })
            .collect()
    }

    #[test]
    fn written_in_pieces_the_bytes_are_the_kept_ones() {
        for r in rendered() {
            let lines = r.drawing.as_ref().map(|d| d.lines());
            let kept = to_json(&r.view, &r.visibility, lines.as_ref(), Count::NONE);
            assert!(kept.contains("\"lines\"") && kept.len() > 1000);
            // Spilled after every face and polyline, after every few, and once at the end.
            for spill_at in [1, 700, usize::MAX] {
                let mut w = Vec::new();
                let p = Count::NONE;
                write_json_spilling(&r.view, &r.visibility, lines.as_ref(), &mut w, p, spill_at)
                    .unwrap();
                assert_eq!(String::from_utf8(w).unwrap(), kept, "spilled at {spill_at}");
            }
        }
    }

    #[test]
    fn formatted_in_any_batches_the_bytes_are_the_same() {
        for r in rendered() {
            let kept = to_json(&r.view, &r.visibility, None, Count::NONE);
            for (batch_faces, task_faces) in [(1, 1), (5, 2), (7, 3), (64, 64)] {
                let mut out = Sink {
                    batch_faces,
                    task_faces,
                    ..Sink::default()
                };
                json_into(&mut out, &r.view, &r.visibility, None, Count::NONE).unwrap();
                assert_eq!(
                    out.s, kept,
                    "batches of {batch_faces}, tasks of {task_faces}"
                );
            }
        }
    }

    #[test]
    fn written_from_inside_a_pool_the_bytes_are_the_same() {
        for r in rendered() {
            let kept = to_json(&r.view, &r.visibility, None, Count::NONE);
            for threads in [1, 3] {
                let mut w = Vec::new();
                crate::chunked::pool(threads).install(|| {
                    write_json_spilling(&r.view, &r.visibility, None, &mut w, Count::NONE, 700)
                        .unwrap()
                });
                assert_eq!(String::from_utf8(w).unwrap(), kept, "{threads} threads");
            }
        }
    }

    /// A writer that fails once `room` bytes are taken.
    struct Full {
        room: usize,
    }

    impl io::Write for Full {
        fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
            if buf.len() > self.room {
                return Err(io::Error::new(io::ErrorKind::StorageFull, "full"));
            }
            self.room -= buf.len();
            Ok(buf.len())
        }

        fn flush(&mut self) -> io::Result<()> {
            Ok(())
        }
    }

    #[test]
    fn a_failed_write_is_reported() {
        let r = &rendered()[0];
        let p = Count::NONE;
        for (room, spill_at) in [(0, 1), (500, 1), (500, SPILL_AT)] {
            let mut w = Full { room };
            let e = write_json_spilling(&r.view, &r.visibility, None, &mut w, p, spill_at);
            assert_eq!(e.unwrap_err().kind(), io::ErrorKind::StorageFull);
        }
    }
}
