//! Caps for open meshes: each hole closed by virtual triangles so that back faces away from
//! the holes can be proven hidden, decided exactly once per prototype.
//!
//! An open mesh M (its only defect: some edges used by one face) has holes bounded by its
//! boundary edges. Each hole gets a CAP: a fan of triangles from a new vertex at the centroid
//! of its boundary loop, the loop followed against its faces' direction, so that every
//! boundary edge is used once more, the other way, and the caps orient like the faces they
//! close. A fan first, rather than ear clipping: a scanned hole is far from planar, and ear
//! clipping a loop in space needs a projection in which it is simple (often none exists);
//! the fan needs nothing, and what it gets wrong (a cap through the mesh, a flat fan
//! triangle) is caught exactly — such holes are then ear-clipped along their Newell normal
//! where that projection is simple (the bunny's two deepest holes). The capped surface
//! S = M ∪ caps is kept only when it passes the very tests that prove a solid
//! ([`super::solidity`]): closed and consistently oriented, non-degenerate, no two
//! triangles crossing, every piece of positive volume.
//!
//! A hole of zero area (a T-junction crack, `slits.rs`: what dropping a zero-area
//! triangle leaves) is not capped but closed, by splitting the triangle edge across it.
//!
//! # Why back faces away from the caps are hidden
//!
//! Let w(x) be the winding number of the piece of S that holds f (pieces are edge-connected,
//! a cap joins the piece of its hole; other pieces may pass through it, caps included, and
//! play no part): an integer off that piece, ≥ 0, 0 at the eye (orthographic: at
//! infinity; perspective: when every vertex of M and of the caps is in front of the near
//! plane the eye is outside S's convex hull — the rule the view already uses for solids).
//! Take p on a strictly back-facing face f of M. The segment from p toward the eye starts
//! where w ≥ 1 (just past f's outer side is the inside of f's piece) and ends where w = 0,
//! so it crosses the piece from inside to outside at some point q nearer than p: on a face g
//! that is not strictly back-facing (front-facing, or seen edge-on where the segment runs
//! in g's plane), and q projects onto p's screen point. The view
//! ([`crate::view::caps`]) culls f only when no cap triangle that is not strictly
//! back-facing has a screen rectangle touching f's (closed test, padded by a relative
//! margin for the rounding of the projection). Then g is not a cap: it is a face of M, in
//! front of p, never culled (front faces never are; an edge-on g covers only a segment of
//! the screen, no area). So p is hidden by M itself, and any point behind p that f would
//! hide is hidden by g as well: f is neither visible nor a needed occluder. A back face
//! whose rectangle touches a front-facing or edge-on cap keeps two sides.
//!
//! The same holds piece by piece: the view splits a warped face into the triangles S was
//! proven with; a mirrored placement reverses faces and caps alike (w keeps its sign); and
//! near-plane clipping never happens on a leaf that culls, since every vertex of M and the
//! caps must be in front of the near plane.

use std::collections::HashMap;

use rayon::prelude::*;

use crate::chunked::CHUNK;
use crate::count::Span;
use crate::geom::{newell, orient3d, P3};
#[cfg(test)]
use crate::scene::topology::Topology;
use crate::scene::topology::Traversals;
use crate::scene::triangulate::ear_clip_simple;
use crate::scene::{CapFailure, Face, Mesh, Solidity};

use super::pieces::Crossings;
use super::slits::close_slits;
#[cfg(test)]
use super::solidity;
use super::{degenerate, examine_until, Surface, NO_GROUP};

/// The caps of an open mesh that capping made a solid.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Caps {
    /// Number of holes (boundary loops), one cap each.
    pub loops: u32,
    /// The cap triangles, counter-clockwise seen from outside the capped solid.
    pub triangles: Vec<[P3; 3]>,
}

/// How one hole is capped.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Way {
    /// A fan from a new vertex at the loop's centroid.
    Fan,
    /// Exact ear clipping of the loop projected along its Newell normal's dominant axis (no
    /// new vertex); only where that projection is simple.
    Ears,
}

#[cfg(test)]
/// Caps the holes of `mesh` (which must be open and otherwise consistent:
/// [`Topology::Open`]) and decides exactly whether the capped surface is a solid. Every hole
/// is first fanned; holes whose fan crosses the mesh or another cap, or has a flat
/// triangle, are ear-clipped instead. The caps are tested first (each cap triangle against
/// every triangle: cheap, and where capping fails it fails here), at most [`ATTEMPTS`]
/// times; only caps that pass go on to the one test of the whole surface (every pair of the
/// mesh's own triangles).
pub(crate) fn cap_holes(mesh: &Mesh) -> Result<Caps, CapFailure> {
    capping(mesh, Span::NONE).map_err(|(why, _)| why)
}

/// A capped surface that is not a solid as a whole.
#[derive(Debug)]
pub(crate) struct Failed {
    /// The capped mesh: the mesh's faces (cracks closed, same indices), then the caps.
    pub(crate) mesh: Mesh,
    /// Its surface, as tested.
    pub(crate) surface: Surface,
    /// Crossing pairs of its faces found by the test that failed: some of them (at least one
    /// of each cap that crosses), or all of them when `complete`.
    pub(crate) crossing: Vec<[u32; 2]>,
    /// `crossing` holds every crossing pair: capping failed only on pairs of the mesh's own
    /// triangles (every pair with a cap found apart, every piece outward), so the pieces
    /// need no second test.
    pub(crate) complete: bool,
}

impl Failed {
    /// What its test knows of the crossing pairs.
    pub(crate) fn crossings(&self) -> Crossings<'_> {
        if self.complete {
            Crossings::All(&self.crossing)
        } else {
            Crossings::Some(&self.crossing)
        }
    }
}

/// A failure to cap, with the capped surface that failed where one was built and tested
/// (so that [`super::pieces`] can still prove its pieces one by one).
pub(crate) type Refused = (CapFailure, Option<Box<Failed>>);

#[cfg(test)]
/// [`cap_holes`], saying on failure which capped surface failed, filling `span` as it goes
/// (each attempt less of it than the last: most meshes cap at the first).
pub(crate) fn capping(mesh: &Mesh, span: Span) -> Result<Caps, Refused> {
    let traversals = Traversals::of(&mesh.faces);
    if traversals.topology() != Topology::Open {
        return Err((CapFailure::Inconsistent, None));
    }
    capping_open(mesh, &traversals, span)
}

/// [`capping`] of a mesh whose edge topology the caller has found [`Topology::Open`] in
/// `traversals` (its faces'): the holes are read from them, and each capped mesh's
/// traversals are these with the caps' merged in (no edge of the mesh sorted again).
pub(crate) fn capping_open(
    mesh: &Mesh,
    traversals: &Traversals,
    span: Span,
) -> Result<Caps, Refused> {
    let refuse = |why| (why, None);
    let failed = |mesh, surface: Option<Surface>, crossing| {
        surface.map(|surface| {
            Box::new(Failed {
                mesh,
                surface,
                crossing,
                complete: false,
            })
        })
    };
    if flat(&mesh.vertices) {
        // A sheet in one plane: whatever caps it, nothing is enclosed.
        return Err(refuse(CapFailure::InsideOut));
    }
    let (slits, loops): (Vec<Vec<u32>>, Vec<Vec<u32>>) =
        loops_of_steps(&traversals.once(&mesh.faces))
            .into_iter()
            .partition(|l| slit(mesh, l));
    let closed;
    let closed_traversals;
    let (mesh, traversals) = if slits.is_empty() {
        (mesh, traversals)
    } else {
        // T-junction cracks are closed by splitting the edges across them, not capped.
        closed = Mesh {
            vertices: mesh.vertices.clone(),
            faces: close_slits(mesh, &slits).ok_or(refuse(CapFailure::Slit))?,
            ..Mesh::default()
        };
        closed_traversals = Traversals::of(&closed.faces);
        (&closed, &closed_traversals)
    };
    let holes = (loops.len() + slits.len()) as u32;
    let n = mesh.faces.len() as u32;
    span.reach(ATTEMPT_SPANS[0]);
    let mut ways = vec![Way::Fan; loops.len()];
    // The holes whose caps are tested: all at first; after a test that reached the crossing
    // stage, only the re-capped ones (every other pair with a cap was found apart already).
    let mut suspect: Vec<bool> = vec![true; loops.len()];
    for attempt in 1..=ATTEMPTS {
        let part = span.span(ATTEMPT_SPANS[attempt - 1], ATTEMPT_SPANS[attempt]);
        let (caps, loop_of, centres) = caps_of(mesh, &loops, &ways);
        if traversals.not_closed_with(&caps) {
            // Open or inconsistent with any caps: refused as `examine` would refuse the
            // capped mesh (a terrain's ear-clipped rim repeats its corner triangles), without
            // making it.
            return Err(refuse(CapFailure::Inconsistent));
        }
        let capped = with_caps(mesh, caps, centres);
        part.reach(0.1);
        // A hole's cap is settled by its first crossing: the retry needs only which holes
        // cross (a height field's fan crosses it along O(sqrt F) triangles each).
        let hole_of: Vec<u32> = crate::chunked::map(capped.faces.len(), |f| {
            match (f as u32).checked_sub(n).map(|k| loop_of[k as usize]) {
                Some(l) if suspect[l] => l as u32,
                _ => NO_GROUP,
            }
        });
        let e = examine_until(
            &capped,
            traversals.with_faces(&capped.faces[n as usize..]),
            |f| f >= n && suspect[loop_of[(f - n) as usize]],
            Some(&hole_of),
            part.span(0.1, 1.0),
        );
        let cap = |f: u32| f.checked_sub(n).map(|k| loop_of[k as usize]);
        let reached_crossings = !matches!(e.solidity, Solidity::Degenerate);
        let mut retry: Vec<usize> = match e.solidity {
            Solidity::Solid => {
                let surface = e.surface.expect("a solid was tested");
                let rest = span.span(ATTEMPT_SPANS[attempt], 1.0);
                return whole(mesh, capped, surface, holes, rest);
            }
            Solidity::Degenerate => {
                if e.degenerate.iter().any(|&f| f < n) {
                    return Err((
                        CapFailure::MeshDegenerate,
                        failed(capped, e.surface, e.crossing),
                    ));
                }
                e.degenerate.iter().filter_map(|&f| cap(f)).collect()
            }
            Solidity::SelfIntersecting(_) => e
                .crossing
                .iter()
                .flatten()
                .filter_map(|&f| cap(f))
                .collect(),
            Solidity::InsideOut => {
                return Err((CapFailure::InsideOut, failed(capped, e.surface, e.crossing)))
            }
            Solidity::Open(_) | Solidity::Capped(_) | Solidity::Inconsistent => {
                return Err(refuse(CapFailure::Inconsistent))
            }
        };
        retry.sort_unstable();
        retry.dedup();
        // Every hole in the failure must be re-capped, or the failure stands (a pair left
        // out would not be tested again).
        let fixable = |l: &usize| ways[*l] == Way::Fan && ears(mesh, &loops[*l]).is_some();
        if retry.is_empty() || !retry.iter().all(fixable) || attempt == ATTEMPTS {
            let why = match e.solidity {
                Solidity::SelfIntersecting(_) => CapFailure::SelfIntersecting(retry.len() as u64),
                _ => CapFailure::Degenerate,
            };
            return Err((why, failed(capped, e.surface, e.crossing)));
        }
        // Its million corner lists freed on all threads.
        crate::chunked::drop_all(capped.faces);
        if reached_crossings {
            suspect.iter_mut().for_each(|s| *s = false);
        }
        for l in retry {
            ways[l] = Way::Ears;
            suspect[l] = true;
        }
    }
    // The last attempt returns above.
    Err(refuse(CapFailure::Inconsistent))
}

/// The whole capped surface decided, its caps found apart from everything and the rest of
/// [`examine`] passed (closed, non-degenerate, pieces of positive volume): only the mesh's
/// own pairs of triangles are left to test, on the `surface` already built (filling
/// `span`). The caps, or why not.
fn whole(
    mesh: &Mesh,
    capped: Mesh,
    surface: Surface,
    loops: u32,
    span: Span,
) -> Result<Caps, Refused> {
    let n = mesh.faces.len() as u32;
    let c = surface.crossing(&capped, |f| f < n, span);
    if !c.is_empty() {
        let why = CapFailure::MeshSelfIntersecting(c.len() as u64);
        let failed = Failed {
            mesh: capped,
            surface,
            crossing: c,
            complete: true,
        };
        return Err((why, Some(Box::new(failed))));
    }
    let triangles = capped.faces[n as usize..]
        .iter()
        .map(|f| f.vertices.iter().map(|&v| capped.vertices[v as usize]))
        .map(|mut t| [(); 3].map(|_| t.next().expect("a triangle")))
        .collect();
    crate::chunked::drop_all(capped.faces);
    Ok(Caps { loops, triangles })
}

/// How many capped surfaces [`cap_holes`] decides at most.
pub(crate) const ATTEMPTS: usize = 3;

/// Where each attempt's part of the capping's progress starts and ends (fractions: the
/// holes' loops found first; a capping that succeeds tests the whole from its attempt's end
/// on). Measured on open meshes (bunny, ogre, a terrain), the loops take a fifth to two
/// fifths of the time, the first attempt a quarter to two fifths, and the whole test, where
/// it runs, two fifths to a half.
const ATTEMPT_SPANS: [f64; ATTEMPTS + 1] = [0.25, 0.55, 0.7, 0.8];

/// Exact: every point lies on one plane (through the first point, the farthest from it,
/// and the farthest from the line through those two; or all on one line). On all threads
/// where there are many points: the farthest is the last of the farthest either way.
fn flat(pts: &[P3]) -> bool {
    let Some(&a) = pts.first() else {
        return true;
    };
    let many = pts.len() > CHUNK;
    let far = |d: &(dyn Fn(&P3) -> f64 + Sync)| {
        let last_farthest =
            |(i, p): &(usize, &P3), (j, q): &(usize, &P3)| d(p).total_cmp(&d(q)).then(i.cmp(j));
        let found = if many {
            pts.par_iter()
                .with_min_len(CHUNK)
                .enumerate()
                .max_by(last_farthest)
        } else {
            pts.iter().enumerate().max_by(last_farthest)
        };
        found.map_or(a, |(_, p)| *p)
    };
    let all = |f: &(dyn Fn(&P3) -> bool + Sync)| {
        if many {
            pts.par_iter().with_min_len(CHUNK).all(f)
        } else {
            pts.iter().all(f)
        }
    };
    let b = far(&|p| (p - a).norm_squared());
    let c = far(&|p| (p - a).cross(&(b - a)).norm_squared());
    degenerate(&[a, b, c]) && all(&|&p| degenerate(&[a, b, p]))
        || all(&|p| orient3d(&a, &b, &c, p) == 0.0)
}

/// Exact: every corner of the loop lies on one line (no triangle on them has area).
fn slit(mesh: &Mesh, lp: &[u32]) -> bool {
    let p = |k: usize| mesh.vertices[lp[k] as usize];
    (2..lp.len()).all(|k| degenerate(&[p(0), p(1), p(k)]))
}

/// The caps of the holes, each its way (a fan's triangles number its centre after the
/// mesh's vertices and the fans before it), the loop of each cap face, and the fans' centres.
fn caps_of(mesh: &Mesh, loops: &[Vec<u32>], ways: &[Way]) -> (Vec<Face>, Vec<usize>, Vec<P3>) {
    let (mut caps, mut loop_of, mut centres) = (Vec::new(), Vec::new(), Vec::new());
    for (l, (lp, way)) in loops.iter().zip(ways).enumerate() {
        let tris: Vec<[u32; 3]> = match way {
            Way::Fan => {
                let ci = (mesh.vertices.len() + centres.len()) as u32;
                centres.push(centroid(lp.iter().map(|&v| &mesh.vertices[v as usize])));
                (0..lp.len())
                    .map(|i| [ci, lp[i], lp[(i + 1) % lp.len()]])
                    .collect()
            }
            Way::Ears => ears(mesh, lp).expect("only simple loops are ear-clipped"),
        };
        for t in tris {
            caps.push(Face::new(t));
            loop_of.push(l);
        }
    }
    (caps, loop_of, centres)
}

/// The mesh with `caps` ([`caps_of`]) after its faces and their `centres` after its vertices.
fn with_caps(mesh: &Mesh, caps: Vec<Face>, centres: Vec<P3>) -> Mesh {
    // Made at their full length: the caps appended without moving the mesh's faces.
    let mut vertices = Vec::with_capacity(mesh.vertices.len() + centres.len());
    crate::chunked::extend_concat(&mut vertices, &[&mesh.vertices]);
    vertices.extend(centres);
    let mut faces = Vec::with_capacity(mesh.faces.len() + caps.len());
    crate::chunked::extend_concat(&mut faces, &[&mesh.faces]);
    faces.extend(caps);
    Mesh {
        vertices,
        faces,
        ..Mesh::default()
    }
}

/// The loop ear-clipped (exact predicates) along its Newell normal, oriented like the loop;
/// None when its projection is not simple.
fn ears(mesh: &Mesh, lp: &[u32]) -> Option<Vec<[u32; 3]>> {
    let pts: Vec<P3> = lp.iter().map(|&v| mesh.vertices[v as usize]).collect();
    let tris = ear_clip_simple(&pts, &newell(&pts))?;
    Some(tris.iter().map(|t| t.map(|i| lp[i])).collect())
}

/// The mean of the points.
fn centroid<'a>(pts: impl ExactSizeIterator<Item = &'a P3>) -> P3 {
    let n = pts.len() as f64;
    let sum = pts.fold(crate::geom::V3::zeros(), |s, p| s + p.coords);
    P3::from(sum / n)
}

/// The holes' boundaries as simple loops of vertices, each following its boundary edges
/// backwards (a boundary edge a→b of a face gives the loop step b→a), so that a fan over a
/// loop uses each boundary edge once the other way. A vertex on several holes (or met twice
/// on one) splits the walk into simple loops; in-degree equals out-degree at every vertex
/// of a consistent surface's boundary, so every walk closes. Deterministic: loops start at
/// their least edge in the faces' order.
#[cfg(test)]
pub(crate) fn boundary_loops(faces: &[Face]) -> Vec<Vec<u32>> {
    loops_of_steps(&Traversals::of(faces).once(faces))
}

/// [`boundary_loops`] of the boundary edges `once` ([`Traversals::once`]: each `a → b` of
/// its face, in face order).
fn loops_of_steps(once: &[(u32, u32)]) -> Vec<Vec<u32>> {
    // Loop steps b→a for each boundary edge a→b, in face order.
    let steps: Vec<(u32, u32)> = once.iter().map(|&(a, b)| (b, a)).collect();
    let mut out_of: HashMap<u32, Vec<usize>> = HashMap::new();
    for (k, &(from, _)) in steps.iter().enumerate().rev() {
        out_of.entry(from).or_default().push(k);
    }
    let mut used = vec![false; steps.len()];
    let mut loops = Vec::new();
    for start in 0..steps.len() {
        if used[start] {
            continue;
        }
        // Walk until back at the first vertex, cutting off a simple loop whenever a vertex
        // repeats.
        let mut path: Vec<u32> = vec![steps[start].0];
        let mut at: HashMap<u32, usize> = HashMap::from([(steps[start].0, 0)]);
        let mut k = start;
        loop {
            used[k] = true;
            let next = steps[k].1;
            if let Some(&i) = at.get(&next) {
                for v in &path[i + 1..] {
                    at.remove(v);
                }
                loops.push(path.split_off(i));
                path.push(next);
                if i == 0 {
                    break;
                }
            } else {
                at.insert(next, path.len());
                path.push(next);
            }
            let outs = out_of.get_mut(&next).expect("a consistent boundary closes");
            k = loop {
                let c = outs.pop().expect("a consistent boundary closes");
                if !used[c] {
                    break c;
                }
            };
        }
    }
    loops
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    /// A dome over `n` by `n` cells, two triangles each, its rim flat at height 0: an open
    /// mesh of one hole that caps into a solid (the two corner triangles lying flat in the
    /// rim, which the cap would cover, left out).
    fn height_field(n: u32) -> Mesh {
        let f = |k: u32| (std::f64::consts::PI * k as f64 / n as f64).sin();
        let rim = move |(x, y): (u32, u32)| x == 0 || x == n || y == 0 || y == n;
        let h = move |x: u32, y: u32| {
            if rim((x, y)) {
                0.0
            } else {
                10.0 * f(x) * f(y) + ((x * 7 + y * 13) % 5) as f64 * 0.01
            }
        };
        let vertices = (0..=n)
            .flat_map(|y| (0..=n).map(move |x| P3::new(x as f64, y as f64, h(x, y))))
            .collect();
        let at = |(x, y): (u32, u32)| y * (n + 1) + x;
        let faces = (0..n)
            .flat_map(|y| (0..n).map(move |x| (x, y)))
            .flat_map(|(x, y)| {
                [
                    [(x, y), (x + 1, y), (x + 1, y + 1)],
                    [(x, y), (x + 1, y + 1), (x, y + 1)],
                ]
            })
            .filter(|t| !t.iter().all(|&p| rim(p)))
            .map(|t| Face::new(t.map(at)))
            .collect();
        Mesh {
            vertices,
            faces,
            ..Mesh::default()
        }
    }

    #[test]
    fn capping_on_several_threads_is_the_one_thread_capping() {
        // Many chunks of faces: the edges, the faces copied and the triangles are made in
        // chunks on three threads.
        let mesh = height_field(100);
        assert!(mesh.faces.len() > 2 * crate::chunked::CHUNK);
        let pool = crate::chunked::pool;
        let one = pool(1).install(|| cap_holes(&mesh));
        assert!(matches!(one, Ok(Caps { loops: 1, .. })), "{one:?}");
        assert_eq!(pool(3).install(|| cap_holes(&mesh)), one);
        let loops = pool(1).install(|| boundary_loops(&mesh.faces));
        assert_eq!(pool(3).install(|| boundary_loops(&mesh.faces)), loops);
    }

    /// The unit cube's faces, outward, and its corners; `skip` faces left out.
    pub(crate) fn cube_without(skip: &[usize]) -> Mesh {
        let v: Vec<P3> = (0..8)
            .map(|i| P3::new((i & 1) as f64, ((i >> 1) & 1) as f64, ((i >> 2) & 1) as f64))
            .collect();
        let faces: [[u32; 4]; 6] = [
            [0, 2, 3, 1], // z = 0
            [4, 5, 7, 6], // z = 1
            [0, 1, 5, 4], // y = 0
            [2, 6, 7, 3], // y = 1
            [0, 4, 6, 2], // x = 0
            [1, 3, 7, 5], // x = 1
        ];
        Mesh {
            vertices: v,
            faces: faces
                .iter()
                .enumerate()
                .filter(|(k, _)| !skip.contains(k))
                .map(|(_, f)| Face::new(f))
                .collect(),
            ..Mesh::default()
        }
    }

    #[test]
    fn whole_cube_is_solid_and_the_open_box_caps() {
        assert_eq!(solidity(&cube_without(&[])), Solidity::Solid);
        let open = cube_without(&[1]);
        assert_eq!(
            solidity(&open),
            Solidity::Open(CapFailure::NotTried),
            "capping is the prepare stage's second step"
        );
        let loops = boundary_loops(&open.faces);
        // The missing top z = 1 is the loop 4→5→7→6 reversed: its cap is that face again.
        assert_eq!(loops.len(), 1);
        let mut l = loops[0].clone();
        let k = l.iter().position(|&v| v == 4).unwrap();
        l.rotate_left(k);
        assert_eq!(l, vec![4, 5, 7, 6]);
        let caps = cap_holes(&open).unwrap();
        assert_eq!(caps.loops, 1);
        assert_eq!(caps.triangles.len(), 4);
        // Every cap triangle faces +z (outward), from the centre of the missing face.
        for t in &caps.triangles {
            assert_eq!(t[0], P3::new(0.5, 0.5, 1.0));
            let n = (t[1] - t[0]).cross(&(t[2] - t[0]));
            assert!(n.z > 0.0 && n.x == 0.0 && n.y == 0.0, "{t:?}");
        }
    }

    #[test]
    fn a_tube_caps_at_both_ends_and_two_holes_sharing_a_corner_split() {
        let tube = cube_without(&[0, 1]);
        let caps = cap_holes(&tube).unwrap();
        assert_eq!(caps.loops, 2);
        assert_eq!(caps.triangles.len(), 8);
        // Two triangles of a square wall, meeting only at a corner of each, leave holes that
        // meet at that corner: the walk splits them into simple loops.
        let v = vec![
            P3::new(0., 0., 0.),
            P3::new(1., 0., 0.),
            P3::new(0., 1., 0.),
            P3::new(-1., 0., 0.),
            P3::new(0., -1., 0.),
        ];
        let faces = vec![Face::new(vec![0, 1, 2]), Face::new(vec![0, 3, 4])];
        let loops = boundary_loops(&faces);
        assert_eq!(loops.len(), 2, "{loops:?}");
        assert!(loops.iter().all(|l| l.len() == 3));
        let m = Mesh {
            vertices: v,
            faces,
            ..Mesh::default()
        };
        // Flat: each cap would lie on its triangle, enclosing nothing.
        assert_eq!(cap_holes(&m), Err(CapFailure::InsideOut));
    }

    #[test]
    fn inward_open_box_is_refused() {
        let mut m = cube_without(&[1]);
        for f in &mut m.faces {
            f.vertices.reverse();
        }
        assert_eq!(cap_holes(&m), Err(CapFailure::InsideOut));
    }

    #[test]
    fn a_cap_through_another_piece_is_kept() {
        // The open box holds a closed tetrahedron that pokes up through its mouth, touching
        // nothing. The mouth's cap crosses the tetrahedron, but that is another piece: each
        // piece bounds its own inside, and the culling argument is piece by piece.
        let mut m = cube_without(&[1]);
        let a = m.vertices.len() as u32;
        m.vertices.extend([
            P3::new(0.3, 0.3, 0.5),
            P3::new(0.7, 0.3, 0.5),
            P3::new(0.5, 0.7, 0.5),
            P3::new(0.5, 0.5, 1.5),
        ]);
        for f in [[0, 2, 1], [0, 1, 3], [1, 2, 3], [2, 0, 3]] {
            m.faces.push(Face::new(
                f.iter()
                    .map(|k| a + k)
                    .collect::<crate::scene::FaceIndices>(),
            ));
        }
        assert_eq!(solidity(&m), Solidity::Open(CapFailure::NotTried));
        assert_eq!(cap_holes(&m).map(|c| c.loops), Ok(1));
    }

    /// An open box whose floor has a square hole into a closed chimney (a pocket of the
    /// outside) that rises to height `top`: one piece, embedded, open only at the mouth.
    pub(crate) fn box_with_chimney(top: f64) -> Mesh {
        let ring = |h: f64, lo: f64, hi: f64| {
            [[lo, lo], [hi, lo], [hi, hi], [lo, hi]].map(|[x, y]| P3::new(x, y, h))
        };
        let vertices: Vec<P3> = [
            ring(0.0, 0.0, 1.0), // O 0..4: the floor's outer corners
            ring(0.0, 0.4, 0.6), // I 4..8: the hole in the floor
            ring(1.0, 0.0, 1.0), // T 8..12: the mouth
            ring(top, 0.4, 0.6), // C 12..16: the chimney's top
        ]
        .concat();
        let (o, i, t, c) = (0u32, 4u32, 8u32, 12u32);
        let mut faces = Vec::new();
        for k in 0..4u32 {
            let l = (k + 1) % 4;
            faces.push(Face::new(vec![o + k, i + k, i + l, o + l])); // floor, facing -z
            faces.push(Face::new(vec![o + k, o + l, t + l, t + k])); // wall, outward
            faces.push(Face::new(vec![i + l, i + k, c + k, c + l])); // chimney, inward
        }
        faces.push(Face::new(vec![c, c + 3, c + 2, c + 1])); // chimney top, facing -z
        Mesh {
            vertices,
            faces,
            ..Mesh::default()
        }
    }

    #[test]
    fn a_cap_through_its_own_piece_is_refused() {
        // The chimney rises through the mouth: any cap of the mouth (fan or ears, both in
        // z = 1) crosses its walls, and they are of the same piece.
        let m = box_with_chimney(1.5);
        assert_eq!(solidity(&m), Solidity::Open(CapFailure::NotTried));
        let r = cap_holes(&m);
        assert!(
            matches!(r, Err(CapFailure::SelfIntersecting(n)) if n > 0),
            "{r:?}"
        );
        // With the chimney's top lowered into the box, the same mesh caps.
        assert_eq!(cap_holes(&box_with_chimney(0.9)).map(|c| c.loops), Ok(1));
    }

    #[test]
    fn a_hole_whose_fan_crosses_the_walls_is_ear_clipped() {
        // An L-shaped prism open at the top: the centroid of the mouth's corners lies in the
        // notch, outside the L, so the fan crosses the walls; ear clipping the L works.
        let l = [[0., 0.], [3., 0.], [3., 1.], [1., 1.], [1., 3.], [0., 3.]];
        let mut vertices: Vec<P3> = l.iter().map(|p| P3::new(p[0], p[1], 0.0)).collect();
        vertices.extend(l.iter().map(|p| P3::new(p[0], p[1], 1.0)));
        let mut faces = vec![Face::new(
            (0..6).rev().collect::<crate::scene::FaceIndices>(),
        )]; // floor, facing -z
        for i in 0..6u32 {
            let j = (i + 1) % 6;
            faces.push(Face::new(vec![i, j, j + 6, i + 6]));
        }
        let m = Mesh {
            vertices,
            faces,
            ..Mesh::default()
        };
        let caps = cap_holes(&m).unwrap();
        assert_eq!(caps.loops, 1);
        assert_eq!(caps.triangles.len(), 4, "ear clipping, not a fan of 6");
        for t in &caps.triangles {
            assert!(t.iter().all(|p| p.z == 1.0 && m.vertices.contains(p)));
            assert!((t[1] - t[0]).cross(&(t[2] - t[0])).z > 0.0, "outward: +z");
        }
    }

    #[test]
    fn a_t_junction_crack_is_closed_by_splitting_the_edge_across_it() {
        // A tetrahedron whose face 1-2-3 is split at the midpoint 4 of edge 1-2 while the
        // face across that edge is not: the hole 1, 2, 4 has its corners on one line.
        let vertices = vec![
            P3::new(0., 0., 0.),
            P3::new(1., 0., 0.),
            P3::new(0., 1., 0.),
            P3::new(0., 0., 1.),
            P3::new(0.5, 0.5, 0.),
        ];
        let faces = [[0, 2, 1], [0, 1, 3], [1, 4, 3], [4, 2, 3], [2, 0, 3]]
            .iter()
            .map(Face::new)
            .collect();
        let m = Mesh {
            vertices,
            faces,
            ..Mesh::default()
        };
        let loops = boundary_loops(&m.faces);
        assert_eq!(loops.len(), 1);
        assert!(slit(&m, &loops[0]));
        // The face 0-2-1 gets the corner 4 on its edge 2-1: closed, no cap needed.
        let closed = close_slits(&m, &loops).unwrap();
        assert_eq!(closed[0].vertices[..], [0, 2, 4, 1]);
        assert_eq!(
            cap_holes(&m),
            Ok(Caps {
                loops: 1,
                triangles: vec![]
            })
        );
        // The same crack along a quad is refused (a polygon split anew could be another
        // surface than the view's pieces of it).
        let mut quad = m.clone();
        quad.vertices.push(P3::new(0.2, 0.2, -0.5));
        quad.faces[0] = Face::new(vec![0, 5, 2, 1]);
        quad.faces.push(Face::new(vec![5, 0, 2]));
        let slits = boundary_loops(&quad.faces);
        assert_eq!(slits.len(), 1);
        assert!(slit(&quad, &slits[0]));
        assert!(close_slits(&quad, &slits).is_none());
        assert_eq!(cap_holes(&quad), Err(CapFailure::Slit));
        assert!(!slit(
            &cube_without(&[1]),
            &boundary_loops(&cube_without(&[1]).faces)[0]
        ));
    }

    #[test]
    fn many_points_are_flat_alike_on_one_thread_and_on_three() {
        // Points on a tilted plane past a chunk, then one lifted off it at either end, then
        // all on one line: the answers of one thread and of three agree, and are right.
        let n = 3 * CHUNK + 5;
        let on_plane = |k: usize| {
            let (x, y) = ((k % 97) as f64, (k / 97) as f64);
            P3::new(x, y, 2.0 * x - 3.0 * y + 1.0)
        };
        let plane: Vec<P3> = (0..n).map(on_plane).collect();
        let mut first_lifted = plane.clone();
        first_lifted[1].z += 0.5;
        let mut last_lifted = plane.clone();
        last_lifted[n - 1].z -= 1e-9;
        let line: Vec<P3> = (0..n)
            .map(|k| P3::new(k as f64, 2.0 * k as f64, 7.0))
            .collect();
        for (pts, want) in [
            (plane, true),
            (first_lifted, false),
            (last_lifted, false),
            (line, true),
        ] {
            for threads in [1, 3] {
                assert_eq!(crate::chunked::pool(threads).install(|| flat(&pts)), want);
            }
        }
    }

    #[test]
    fn a_flat_sheet_is_refused_at_once() {
        let mut m = cube_without(&[1, 2, 3, 4, 5]);
        assert!(flat(&m.vertices[..4]) && !flat(&m.vertices));
        m.vertices.truncate(4);
        m.faces = vec![Face::new(vec![0, 2, 3, 1])];
        assert!(flat(&m.vertices));
        assert_eq!(cap_holes(&m), Err(CapFailure::InsideOut));
        assert!(flat(&[
            P3::new(0., 0., 0.),
            P3::new(1., 1., 1.),
            P3::new(2., 2., 2.)
        ]));
    }
}
