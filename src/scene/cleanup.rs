//! Cleanup on load: turns a raw [`PolyMesh`] into a [`Mesh`] the paper allows, reporting each repair.
//!
//! Errors: non-finite or huge coordinates, indices out of range. Repairs (each a warning):
//! duplicate vertices merged, faces with fewer than 3 distinct vertices or zero area dropped,
//! non-planar faces reported or split. Deviation = largest distance of a vertex from the
//! face's Newell plane through its centroid, relative to the face's diameter:
//! - up to [`PLANAR_TOL`] (1e-9): planar;
//! - up to [`SPLIT_TOL`] (0.25): warped; kept as one face with a warning (a modelled quad
//!   stays a quad, as in suzanne.obj, whose quads deviate up to 0.12); visibility uses the
//!   plane through three well-spread vertices, so its answer is exact for that plane;
//! - beyond: split into planar triangles (ear clipping) with a warning.

use std::path::Path;

use rayon::prelude::*;

use crate::count::Count;
use crate::error::{Error, Location, Pos, Result, Warning, Warnings};
use crate::geom::{newell, PolyMesh, MAX_COORD, P3, V3};

use super::object::{Face, Mesh};
use super::topology::is_closed_oriented;

/// Relative distance from the face plane above which a face counts as non-planar.
pub(crate) const PLANAR_TOL: f64 = 1e-9;
/// Relative distance from the face plane above which a non-planar face is split.
pub(crate) const SPLIT_TOL: f64 = 0.25;
/// Relative area (|vector area| / diameter²) below which a face counts as zero-area.
pub(crate) const AREA_TOL: f64 = 1e-14;

/// Where each face came from, for messages.
pub(crate) struct Origin<'a> {
    /// The source file.
    pub file: &'a Path,
    /// The position of each face (may be empty: then the file is named alone).
    pub face_pos: &'a [Pos],
}

impl Origin<'_> {
    fn at(&self, face: usize) -> Location {
        let pos = self.face_pos.get(face).copied().unwrap_or(Pos::File);
        Location {
            file: self.file.to_path_buf(),
            pos,
        }
    }
}

/// Checks and repairs `raw`, returning the clean mesh; warnings are appended to `warnings`.
/// The faces cleaned go to `done` as they are, once per chunk of faces.
pub(crate) fn cleanup(
    raw: &PolyMesh,
    origin: &Origin,
    warnings: &mut Warnings,
    done: Count,
) -> Result<Mesh> {
    check_coordinates(raw, origin)?;
    check_indices(raw, origin)?;
    let (vertices, remap) = merge_duplicate_vertices(&raw.vertices);
    let merged = raw.vertices.len() - vertices.len();
    if merged > 0 {
        warnings.push(Warning {
            location: Location::file(origin.file),
            message: format!("merged {merged} duplicate vertices"),
        });
    }
    let clean_chunk = |(c, chunk): (usize, &[Vec<u32>])| {
        let mut part = (Vec::with_capacity(chunk.len()), Warnings::new());
        for (k, f) in chunk.iter().enumerate() {
            let idx: Vec<u32> = f.iter().map(|&v| remap[v as usize]).collect();
            let at = || origin.at(c * CLEANED_CHUNK + k);
            clean_face(idx, &vertices, at, &mut part.0, &mut part.1);
        }
        done.add(chunk.len());
        part
    };
    // A big mesh in chunks of faces on all threads, joined in order: the same faces and
    // warnings (a small one stays off the thread pool).
    let parts: Vec<(Vec<Face>, Warnings)> = if raw.faces.len() > CLEANED_CHUNK {
        raw.faces
            .par_chunks(CLEANED_CHUNK)
            .enumerate()
            .map(clean_chunk)
            .collect()
    } else {
        vec![clean_chunk((0, &raw.faces[..]))]
    };
    // Moved to their places on all threads (the list's pages first touched there), a few
    // parts a thread at a time, each freed once moved: the parts and the list are not all
    // live at once (on one thread, a part at a time, as before).
    let mut faces = Vec::with_capacity(parts.iter().map(|p| p.0.len()).sum());
    let mut parts = parts.into_iter();
    let wave = 2 * rayon::current_num_threads();
    loop {
        let mut moved: Vec<Vec<Face>> = Vec::with_capacity(wave);
        for (f, w) in parts.by_ref().take(wave) {
            moved.push(f);
            warnings.extend(w);
        }
        if moved.is_empty() {
            break;
        }
        let slices = moved.iter_mut().map(|f| &mut f[..]).collect();
        crate::chunked::extend_taken(&mut faces, slices);
    }
    let (vertices, faces) = drop_unused_vertices(vertices, faces);
    let closed = is_closed_oriented(&faces);
    Ok(Mesh {
        vertices,
        faces,
        closed,
        solidity: None,
        caps: Vec::new(),
        proven: None,
        pieces: None,
    })
}

fn check_coordinates(raw: &PolyMesh, origin: &Origin) -> Result<()> {
    let bad = |v: &P3| v.iter().any(|c| !c.is_finite() || c.abs() > MAX_COORD);
    let first = crate::chunked::position_first(raw.vertices.len(), |i| bad(&raw.vertices[i]));
    let Some(i) = first else {
        return Ok(());
    };
    Err(Error::invalid(
        Location::file(origin.file),
        format!(
            "vertex {} has coordinate {:?}: not finite or above {MAX_COORD:e}",
            i + 1,
            raw.vertices[i].coords.as_slice()
        ),
    ))
}

fn check_indices(raw: &PolyMesh, origin: &Origin) -> Result<()> {
    let n = raw.vertices.len();
    let bad = |i: usize| raw.faces[i].iter().any(|&k| k as usize >= n);
    if let Some(i) = crate::chunked::position_first(raw.faces.len(), bad) {
        let f = &raw.faces[i];
        if let Some(&k) = f.iter().find(|&&k| k as usize >= n) {
            return Err(Error::invalid(
                origin.at(i),
                format!("face uses vertex index {k}, but there are {n} vertices"),
            ));
        }
    }
    Ok(())
}

/// The paper's FLATTEN step 4: sort the vertex list to find duplicates, combine them, and
/// return the unique vertices (in order of first occurrence) with the old-to-new index map.
pub(crate) fn merge_duplicate_vertices(verts: &[P3]) -> (Vec<P3>, Vec<u32>) {
    // -0.0 and +0.0 are the same coordinate: fold -0 into +0 (x + 0.0) both for sorting and
    // for grouping, so that equal points always sit next to each other in the sorted order.
    let folded = |p: &P3| [p.x + 0.0, p.y + 0.0, p.z + 0.0];
    let key = |p: &P3| folded(p).map(f64::to_bits);
    // By x, y, z in f64::total_cmp's order, then index: a total order, the same sorted on
    // any number of threads.
    let total = |x: f64| {
        let b = x.to_bits() as i64;
        b ^ ((((b >> 63) as u64) >> 1) as i64)
    };
    let mut order: Vec<u32> = crate::chunked::map(verts.len(), |i| i as u32);
    crate::scene::topology::sort_by_key(&mut order, |&a| {
        (folded(&verts[a as usize]).map(total), a)
    });
    if verts.len() > MERGED_CHUNK && rayon::current_num_threads() > 1 {
        return merge_sorted(verts, &order, |a, b| key(&verts[a]) == key(&verts[b]));
    }
    // First occurrence of each coordinate value.
    let mut rep = vec![0u32; verts.len()];
    let mut i = 0;
    while i < order.len() {
        let k = key(&verts[order[i] as usize]);
        let mut j = i;
        while j < order.len() && key(&verts[order[j] as usize]) == k {
            rep[order[j] as usize] = order[i];
            j += 1;
        }
        i = j;
    }
    let mut new_index = vec![u32::MAX; verts.len()];
    let mut out = Vec::new();
    let mut remap = vec![0u32; verts.len()];
    for v in 0..verts.len() {
        let r = rep[v] as usize;
        if new_index[r] == u32::MAX {
            new_index[r] = out.len() as u32;
            out.push(verts[r]);
        }
        remap[v] = new_index[r];
    }
    (out, remap)
}

/// Vertices per chunk of [`merge_sorted`].
const MERGED_CHUNK: usize = crate::chunked::CHUNK;

/// [`merge_duplicate_vertices`]' result on all threads, from the vertices' indices sorted so
/// that equal vertices (`same`) are neighbours, each run led by its least index: each run's
/// leader found by fixed chunks of the order, the leaders numbered by fixed chunks of the
/// vertices (a count a chunk, then the numbers from the chunks' bases).
fn merge_sorted(
    verts: &[P3],
    order: &[u32],
    same: impl Fn(usize, usize) -> bool + Sync,
) -> (Vec<P3>, Vec<u32>) {
    use std::sync::atomic::{AtomicU32, Ordering::Relaxed};
    let n = verts.len();
    let leader: Vec<AtomicU32> = crate::chunked::map(n, |_| AtomicU32::new(0));
    order
        .par_chunks(MERGED_CHUNK)
        .enumerate()
        .for_each(|(c, part)| {
            // The run holding the chunk's first place may start in an earlier chunk.
            let mut start = c * MERGED_CHUNK;
            while start > 0 && same(order[start - 1] as usize, order[start] as usize) {
                start -= 1;
            }
            let mut lead = order[start];
            for (j, &v) in part.iter().enumerate() {
                let i = c * MERGED_CHUNK + j;
                if i > 0 && !same(order[i - 1] as usize, v as usize) {
                    lead = v;
                }
                leader[v as usize].store(lead, Relaxed);
            }
        });
    let rep: Vec<u32> = crate::chunked::map(n, |v| leader[v].load(Relaxed));
    drop(leader);
    let counts: Vec<u32> = rep
        .par_chunks(MERGED_CHUNK)
        .enumerate()
        .map(|(c, r)| {
            let first = c * MERGED_CHUNK;
            (r.iter().enumerate())
                .filter(|&(j, &l)| l as usize == first + j)
                .count() as u32
        })
        .collect();
    let mut bases = Vec::with_capacity(counts.len());
    let mut base = 0;
    for k in counts {
        bases.push(base);
        base += k;
    }
    let mut new_index = crate::chunked::map(n, |_| 0u32);
    new_index
        .par_chunks_mut(MERGED_CHUNK)
        .zip(bases)
        .enumerate()
        .for_each(|(c, (ni, mut next))| {
            for (j, x) in ni.iter_mut().enumerate() {
                if rep[c * MERGED_CHUNK + j] as usize == c * MERGED_CHUNK + j {
                    *x = next;
                    next += 1;
                }
            }
        });
    let out = crate::chunked::flat_map(n, MERGED_CHUNK, |r, out| {
        out.extend(r.filter(|&v| rep[v] as usize == v).map(|v| verts[v]));
    });
    let remap = crate::chunked::map(n, |v| new_index[rep[v] as usize]);
    (out, remap)
}

/// The vertices the faces use, in order of first use, the faces renumbered to them (on all
/// threads for a big mesh).
fn drop_unused_vertices(vertices: Vec<P3>, mut faces: Vec<Face>) -> (Vec<P3>, Vec<Face>) {
    let mut numbers = crate::renumber::Renumbering::default();
    numbers.grow(vertices.len());
    let used = numbers.renumber(0, &mut [&mut faces[..]], 0, |f| &mut f.vertices[..]);
    let mut out = Vec::new();
    crate::chunked::extend_map(&mut out, used.len(), |k| vertices[used[k] as usize]);
    (out, faces)
}

/// Removes repeated consecutive vertices (cyclically).
fn dedup_cyclic(mut idx: Vec<u32>) -> Vec<u32> {
    idx.dedup();
    while idx.len() > 1 && idx.first() == idx.last() {
        idx.pop();
    }
    idx
}

/// The first vertex of `idx` (in corner order) that appears again later.
fn repeated(idx: &[u32]) -> u32 {
    let mut seen = std::collections::HashSet::with_capacity(idx.len());
    idx.iter()
        .copied()
        .find(|&k| !seen.insert(k))
        .unwrap_or(idx[0])
}

/// Faces per chunk of [`cleanup`].
const CLEANED_CHUNK: usize = 4096;

/// Cleans one face into `out`; `loc` gives its place, made only for a warning.
fn clean_face(
    idx: Vec<u32>,
    verts: &[P3],
    loc: impl Fn() -> Location,
    out: &mut Vec<Face>,
    warnings: &mut Warnings,
) {
    let idx = dedup_cyclic(idx);
    let mut distinct = idx.clone();
    distinct.sort_unstable();
    distinct.dedup();
    if distinct.len() < 3 {
        warnings.push(Warning {
            location: loc(),
            message: format!("face has {} distinct vertices; dropped", distinct.len()),
        });
        return;
    }
    if distinct.len() < idx.len() {
        // Not silent (issue 32): peers (assimp's validation) warn of a polygon that visits a
        // vertex twice; it is kept as written, as the region it winds round.
        let twice = repeated(&idx);
        let p = verts[twice as usize];
        warnings.push(Warning {
            location: loc(),
            message: format!(
                "face passes through the vertex at ({}, {}, {}) more than once ({} corners, {} distinct); kept as written",
                p.x,
                p.y,
                p.z,
                idx.len(),
                distinct.len()
            ),
        });
    }
    let pts: Vec<P3> = idx.iter().map(|&k| verts[k as usize]).collect();
    let shape = FaceShape::of(&pts);
    if shape.area2 <= AREA_TOL * shape.diameter * shape.diameter {
        warnings.push(Warning {
            location: loc(),
            message: "face has zero area; dropped".into(),
        });
        return;
    }
    if shape.deviation <= PLANAR_TOL * shape.diameter {
        out.push(Face::new(idx));
        return;
    }
    if shape.deviation <= SPLIT_TOL * shape.diameter {
        warnings.push(Warning {
            location: loc(),
            message: format!(
                "face is not planar (a vertex is {:.2e} of its diameter off its plane); kept as one face (split above {SPLIT_TOL})",
                shape.deviation / shape.diameter
            ),
        });
        out.push(Face::new(idx));
        return;
    }
    let tris = super::triangulate::ear_clip(&pts, &shape.normal);
    let before = out.len();
    for t in tris {
        let tri = [idx[t[0]], idx[t[1]], idx[t[2]]];
        let s = FaceShape::of(&tri.map(|k| verts[k as usize]));
        if s.area2 > AREA_TOL * s.diameter * s.diameter {
            out.push(Face::new(tri));
        }
    }
    warnings.push(Warning {
        location: loc(),
        message: format!(
            "face is not planar (a vertex is {:.2e} of its diameter off its plane, above {SPLIT_TOL}); split into {} triangles",
            shape.deviation / shape.diameter,
            out.len() - before
        ),
    });
}

/// Size, orientation and flatness of a polygon in space.
#[derive(Debug, Clone, Copy)]
pub(crate) struct FaceShape {
    /// Newell normal (twice the vector area).
    pub normal: V3,
    /// |normal|: twice the area.
    pub area2: f64,
    /// Largest distance between two vertices' bounding-box corners (box diagonal).
    pub diameter: f64,
    /// Largest distance of a vertex from the Newell plane through the centroid.
    pub deviation: f64,
}

impl FaceShape {
    /// Measures the polygon `pts`.
    pub(crate) fn of(pts: &[P3]) -> Self {
        let n = pts.len();
        let normal = newell(pts);
        let bbox = crate::geom::Box3::from_points(pts.iter());
        let diameter = (bbox.hi - bbox.lo).norm();
        let area2 = normal.norm();
        let centroid = pts.iter().fold(V3::zeros(), |s, p| s + p.coords) / n as f64;
        let deviation = if area2 > 0.0 {
            let u = normal / area2;
            pts.iter()
                .map(|p| (p.coords - centroid).dot(&u).abs())
                .fold(0.0, f64::max)
        } else {
            0.0
        };
        FaceShape {
            normal,
            area2,
            diameter,
            deviation,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn origin() -> Origin<'static> {
        Origin {
            file: Path::new("t.obj"),
            face_pos: &[],
        }
    }

    fn quad_mesh(z: f64) -> PolyMesh {
        PolyMesh::new(
            vec![
                P3::new(0., 0., 0.),
                P3::new(1., 0., 0.),
                P3::new(1., 1., z),
                P3::new(0., 1., 0.),
            ],
            vec![vec![0, 1, 2, 3]],
        )
    }

    #[test]
    fn planar_quad_is_kept() {
        let mut w = Vec::new();
        let m = cleanup(
            &quad_mesh(0.0),
            &origin(),
            &mut w,
            crate::count::Count::NONE,
        )
        .unwrap();
        assert_eq!(m.faces.len(), 1);
        assert!(w.is_empty());
        assert!(!m.closed);
    }

    #[test]
    fn warped_quad_is_kept_with_warning() {
        let mut w = Vec::new();
        let m = cleanup(
            &quad_mesh(0.1),
            &origin(),
            &mut w,
            crate::count::Count::NONE,
        )
        .unwrap();
        assert_eq!(m.faces.len(), 1);
        assert_eq!(w.len(), 1);
        assert!(
            w[0].message.contains("kept as one face"),
            "{}",
            w[0].message
        );
    }

    #[test]
    fn non_planar_quad_is_split_with_warning() {
        let mut w = Vec::new();
        // A saddle: every vertex 0.5 off the best plane z = 0.5, diameter sqrt(3): 0.29 > 0.25.
        let saddle = PolyMesh::new(
            vec![
                P3::new(0., 0., 0.),
                P3::new(1., 0., 1.),
                P3::new(1., 1., 0.),
                P3::new(0., 1., 1.),
            ],
            vec![vec![0, 1, 2, 3]],
        );
        let m = cleanup(&saddle, &origin(), &mut w, crate::count::Count::NONE).unwrap();
        assert_eq!(m.faces.len(), 2);
        assert_eq!(w.len(), 1);
        assert!(w[0].message.contains("not planar"), "{}", w[0].message);
        // The pieces cover the same boundary vertices.
        let mut used: Vec<u32> = m.faces.iter().flat_map(|f| f.vertices.clone()).collect();
        used.sort();
        used.dedup();
        assert_eq!(used, vec![0, 1, 2, 3]);
    }

    #[test]
    fn a_face_through_one_vertex_twice_is_kept_with_a_warning() {
        let tri = |faces: Vec<Vec<u32>>| {
            PolyMesh::new(
                vec![
                    P3::new(0., 0., 0.),
                    P3::new(1., 0., 0.),
                    P3::new(0., 1., 0.),
                ],
                faces,
            )
        };
        // `f 1 2 1 2 3` and a face winding twice round the triangle.
        for f in [vec![0, 1, 0, 1, 2], vec![0, 1, 2, 0, 1, 2]] {
            let mut w = Vec::new();
            let n = f.len();
            let m = cleanup(&tri(vec![f]), &origin(), &mut w, crate::count::Count::NONE).unwrap();
            assert_eq!(m.faces[0].vertices.len(), n);
            assert_eq!(w.len(), 1, "{w:?}");
            assert_eq!(
                w[0].message,
                format!("face passes through the vertex at (0, 0, 0) more than once ({n} corners, 3 distinct); kept as written")
            );
        }
        // A plain triangle: no warning.
        let mut w = Vec::new();
        cleanup(
            &tri(vec![vec![0, 1, 2]]),
            &origin(),
            &mut w,
            crate::count::Count::NONE,
        )
        .unwrap();
        assert!(w.is_empty(), "{w:?}");
    }

    #[test]
    fn degenerate_faces_dropped_duplicates_merged() {
        let raw = PolyMesh::new(
            vec![
                P3::new(0., 0., 0.),
                P3::new(1., 0., 0.),
                P3::new(0., 1., 0.),
                P3::new(1., 0., 0.),
                P3::new(2., 0., 0.),
            ],
            vec![vec![0, 1, 2], vec![0, 1, 3], vec![0, 1, 4]],
        );
        let mut w = Vec::new();
        let m = cleanup(&raw, &origin(), &mut w, crate::count::Count::NONE).unwrap();
        assert_eq!(m.faces.len(), 1);
        assert_eq!(m.vertices.len(), 3);
        let msgs: Vec<&str> = w.iter().map(|w| w.message.as_str()).collect();
        assert!(
            msgs.iter().any(|m| m.contains("merged 1 duplicate")),
            "{msgs:?}"
        );
        assert!(msgs.iter().any(|m| m.contains("2 distinct")), "{msgs:?}");
        assert!(msgs.iter().any(|m| m.contains("zero area")), "{msgs:?}");
    }

    #[test]
    fn bad_coordinates_and_indices_are_errors() {
        let mut w = Vec::new();
        let nan = PolyMesh::new(vec![P3::new(f64::NAN, 0., 0.)], vec![]);
        assert!(matches!(
            cleanup(&nan, &origin(), &mut w, crate::count::Count::NONE),
            Err(Error::Invalid(..))
        ));
        let huge = PolyMesh::new(vec![P3::new(1e300, 0., 0.)], vec![]);
        assert!(matches!(
            cleanup(&huge, &origin(), &mut w, crate::count::Count::NONE),
            Err(Error::Invalid(..))
        ));
        let oob = PolyMesh::new(vec![P3::origin()], vec![vec![0, 1, 2]]);
        let e = cleanup(
            &oob,
            &Origin {
                file: Path::new("x.obj"),
                face_pos: &[Pos::Line { line: 7, col: 1 }],
            },
            &mut w,
            crate::count::Count::NONE,
        );
        assert!(e.unwrap_err().to_string().starts_with("x.obj:7:1:"));
    }

    #[test]
    fn merge_keeps_first_occurrence_order() {
        let v = [
            P3::new(1., 0., 0.),
            P3::new(0., 0., 0.),
            P3::new(1., 0., 0.),
            P3::new(-0., 0., 0.),
        ];
        let (u, remap) = merge_duplicate_vertices(&v);
        assert_eq!(u, vec![P3::new(1., 0., 0.), P3::new(0., 0., 0.)]);
        assert_eq!(remap, vec![0, 1, 0, 1]);
    }

    #[test]
    fn many_vertices_merge_as_one_at_a_time_would() {
        // Enough to be sorted on all threads: every vertex maps to the first equal one.
        let mut rng = crate::geom::rng::XorShift::new(35);
        let pick = [-1.5, -0.0, 0.0, 0.25, 1e300, -1e-300];
        let v: Vec<P3> = (0..40_000)
            .map(|_| P3::new(pick[rng.below(6)], pick[rng.below(6)], rng.below(3) as f64))
            .collect();
        let (u, remap) = merge_duplicate_vertices(&v);
        let same = |a: &P3, b: &P3| a.x == b.x && a.y == b.y && a.z == b.z;
        let mut firsts: Vec<usize> = Vec::new();
        for (i, p) in v.iter().enumerate() {
            let k = match firsts.iter().position(|&f| same(&v[f], p)) {
                Some(k) => k,
                None => {
                    firsts.push(i);
                    firsts.len() - 1
                }
            };
            assert_eq!(remap[i] as usize, k, "vertex {i}");
        }
        assert_eq!(u.len(), firsts.len());
    }

    #[test]
    fn merging_and_cleaning_on_several_threads_is_the_one_thread_result() {
        let mut rng = crate::geom::rng::XorShift::new(7);
        // Long runs of repeats and single vertices, over several chunks.
        let v: Vec<P3> = (0..5 * MERGED_CHUNK + 11)
            .map(|i| match i % 3 {
                0 => P3::new(rng.below(50) as f64, -0.0, 1.0),
                1 => P3::new(0.0, 0.0, 0.0),
                _ => P3::new(i as f64, rng.below(4) as f64, 0.0),
            })
            .collect();
        let one = crate::chunked::pool(1).install(|| merge_duplicate_vertices(&v));
        let many = crate::chunked::pool(3).install(|| merge_duplicate_vertices(&v));
        assert_eq!(one, many);
        // A 100x100 grid of quads, each with corners of its own (as an STL's), some vertices
        // unused, some faces degenerate: the same mesh and warnings.
        let n = 100u32;
        let (mut vertices, mut faces) = (Vec::new(), Vec::new());
        for j in 0..n {
            for i in 0..n {
                let k = vertices.len() as u32;
                for (di, dj) in [(0, 0), (1, 0), (1, 1), (0, 1)] {
                    let h = ((i + di) * 7 % 5) as f64 * 0.1;
                    vertices.push(P3::new((i + di) as f64, (j + dj) as f64, h));
                }
                vertices.push(P3::new(-1.0, -1.0, (i * j) as f64));
                faces.push(if (i + j) % 97 == 0 {
                    vec![k, k + 1, k]
                } else {
                    vec![k + 3, k + 2, k + 1, k]
                });
            }
        }
        let raw = PolyMesh::new(vertices, faces);
        let clean = |threads| {
            crate::chunked::pool(threads).install(|| {
                let mut w = Vec::new();
                let m = cleanup(&raw, &origin(), &mut w, crate::count::Count::NONE).unwrap();
                (m, w)
            })
        };
        let (one, many) = (clean(1), clean(3));
        assert!(one.1.len() > 100);
        assert_eq!(one, many);
    }

    #[test]
    fn signed_zeros_merge_in_every_coordinate() {
        // The sort must not separate -0 from +0 in x or y with another point between them.
        let v = [
            P3::new(0., 0., 0.),
            P3::new(-0., 0.5, 0.),
            P3::new(0., 1., 0.),
            P3::new(-0., 1., 0.),
            P3::new(0., -0., 2.),
            P3::new(-0., 0., 2.),
        ];
        let (u, remap) = merge_duplicate_vertices(&v);
        assert_eq!(u.len(), 4, "{u:?}");
        assert_eq!(remap, vec![0, 1, 2, 2, 3, 3]);
    }

    #[test]
    fn tetrahedron_with_a_negative_zero_vertex_is_closed() {
        // The case: vertex 5 is vertex 3 written as -0.
        let raw = PolyMesh::new(
            vec![
                P3::new(0., 0., 0.),
                P3::new(1., 0., 0.),
                P3::new(0., 1., 0.),
                P3::new(0., 0., 1.),
                P3::new(-0., 1., 0.),
            ],
            vec![vec![0, 2, 1], vec![0, 1, 3], vec![0, 3, 4], vec![1, 2, 3]],
        );
        let m = cleanup(&raw, &origin(), &mut Vec::new(), crate::count::Count::NONE).unwrap();
        assert_eq!(m.vertices.len(), 4);
        assert!(m.closed);
    }
}
