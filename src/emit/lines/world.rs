//! World-space polygons of every face (unclipped, in mesh vertex order), with their leaf and vertex indices.

use std::collections::HashMap;

use rayon::prelude::*;

use crate::chunked;
use crate::count::Count;
use crate::geom::{Box3, Corners, P3, V3};
use crate::scene::topology::{edge_pieces, Pieces};
use crate::scene::{Face, Leaf, Mesh, Scene};
use crate::view::ScreenFaces;

/// Faces per chunk of a leaf's world faces made on all threads.
const CHUNK: usize = chunked::CHUNK;

/// The corners of `faces`, by fixed chunk of [`CHUNK`] faces (on all threads for a big mesh).
fn corners_by_chunk(faces: &[Face]) -> Vec<usize> {
    let of = |c: &[Face]| c.iter().map(|f| f.vertices.len()).sum();
    if faces.len() <= CHUNK || rayon::current_num_threads() == 1 {
        return faces.chunks(CHUNK).map(of).collect();
    }
    faces.par_chunks(CHUNK).map(of).collect()
}

/// One face in world space: its corners are a run of [`WorldFaces::vertices`], each the
/// index of a point of its leaf in the world's point space (see [`WorldFaces::points_of`]),
/// so that a scene's faces cost no allocation each.
#[derive(Debug, Clone)]
pub(crate) struct WorldFace {
    /// Index of the leaf object in [`Scene::leaves`] order.
    pub leaf: u32,
    /// Number of corners.
    pub len: u32,
    /// First corner in [`WorldFaces::vertices`].
    pub first: usize,
    /// Newell normal of the points (twice the vector area; zero for a degenerate face).
    pub normal: V3,
}

/// Every face of a scene in world space, by global face id.
///
/// A leaf's world points (its vertices placed by its transform, once a vertex) are the screen
/// faces' own when the view projected the leaf (the same points, made by the same
/// transform), so that the drawing does not hold them twice; the other leaves' are made here.
#[derive(Debug, Clone, Default)]
pub(crate) struct WorldFaces<'s> {
    /// Faces by global id.
    pub faces: Vec<WorldFace>,
    /// The first part of the point space: world points shared with the screen faces
    /// ([`ScreenFaces::world`]), or none.
    pub shared: &'s [P3],
    /// The second part of the point space: the world points of the leaves the screen faces
    /// do not hold, leaf after leaf, vertex after vertex.
    pub points: Vec<P3>,
    /// By leaf: where its vertices' points start in the point space.
    pub leaf_first: Vec<usize>,
    /// The corners' vertex indices in their leaf mesh, face after face.
    pub vertices: Vec<u32>,
    /// Object path of every leaf, in [`Scene::leaves`] order.
    pub paths: Vec<String>,
    /// By face: a number shared by exactly the faces of one edge-connected piece of a leaf
    /// that the prepare stage proved free of self-intersection (two of its faces meet only
    /// in shared vertices and edges), [`NO_PIECE`] elsewhere.
    pub clean_piece: Vec<u32>,
    /// What a section cut did, when the scene is cut.
    pub section: Option<std::sync::Arc<crate::scene::section_info::SectionInfo>>,
}

/// [`WorldFaces::clean_piece`] of a face on no piece proven free of self-intersection.
pub(crate) const NO_PIECE: u32 = u32::MAX;

impl<'s> WorldFaces<'s> {
    /// The world polygons of every face of `scene`, in global face order, sharing the points
    /// of `screen` where they are the same (None: every point made here). The faces made go
    /// to `done`, once per chunk.
    pub(crate) fn build(
        scene: &Scene,
        screen: Option<&'s ScreenFaces>,
        done: Count,
    ) -> WorldFaces<'s> {
        let leaves = scene.leaves();
        let corners = leaves
            .iter()
            .map(|l| corners_by_chunk(&l.mesh.faces).iter().sum::<usize>())
            .sum();
        let mut w = WorldFaces {
            faces: Vec::with_capacity(scene.face_count()),
            shared: screen.map_or(&[], |sf| &sf.world[..]),
            vertices: Vec::with_capacity(corners),
            ..Default::default()
        };
        w.clean_piece.reserve_exact(scene.face_count());
        w.section = scene.section.clone();
        let mut next_piece = 0;
        // The projected leaves, in the same global order (a hidden subtree's are absent).
        let mut projected = screen
            .map_or(&[][..], |sf| &sf.leaves[..])
            .iter()
            .peekable();
        // Each mesh's pieces once, however many instances place it.
        let mut pieces_of: HashMap<*const Mesh, Pieces> = HashMap::new();
        for (li, leaf) in leaves.iter().enumerate() {
            clean_pieces(
                leaf.mesh,
                &mut pieces_of,
                &mut w.clean_piece,
                &mut next_piece,
            );
            let held = projected
                .next_if(|l| l.first_face.index() == leaf.first_face)
                .map(|l| l.world_first as usize);
            w.add_leaf(li as u32, leaf, held, done);
        }
        w.points.shrink_to_fit();
        w.paths = leaves.into_iter().map(|l| l.path).collect();
        w
    }

    /// Appends the faces of leaf `li`, its points at `held` in the shared part (or made here),
    /// each with its normal: a big mesh's made in place in fixed chunks of faces on all
    /// threads (a chunk's corners start where the corners of the chunks before it end).
    fn add_leaf(&mut self, li: u32, leaf: &Leaf, held: Option<usize>, done: Count) {
        let first = match held {
            Some(at) => at,
            None => {
                let at = self.shared.len() + self.points.len();
                self.points.extend(leaf.world_vertices());
                at
            }
        };
        self.leaf_first.push(first);
        let faces = &leaf.mesh.faces;
        let n = faces.len();
        let counts = corners_by_chunk(faces);
        let table = table_of(self.shared, &self.points, first);
        let (made, base) = (self.faces.len(), self.vertices.len());
        let placeholder = WorldFace {
            leaf: li,
            len: 0,
            first: 0,
            normal: V3::zeros(),
        };
        let parallel = n > CHUNK && rayon::current_num_threads() > 1;
        // The places first (their pages touched on all threads), then filled chunk by chunk.
        if parallel {
            let places = (0..n).into_par_iter().with_min_len(CHUNK);
            self.faces.par_extend(places.map(|_| placeholder.clone()));
            let corners = (0..counts.iter().sum()).into_par_iter().with_min_len(CHUNK);
            self.vertices.par_extend(corners.map(|_| 0));
        } else {
            self.faces.resize(made + n, placeholder);
            self.vertices.resize(base + counts.iter().sum::<usize>(), 0);
        }
        // Each chunk's faces and corners, the corners from where the chunks before end.
        let mut parts = Vec::with_capacity(counts.len());
        let (mut at, mut rest) = (base, &mut self.vertices[base..]);
        for (c, out) in self.faces[made..].chunks_mut(CHUNK).enumerate() {
            let (here, after) = rest.split_at_mut(counts[c]);
            parts.push((c * CHUNK, at, out, here));
            (at, rest) = (at + counts[c], after);
        }
        let fill = |(start, at, out, corners): (usize, usize, &mut [WorldFace], &mut [u32])| {
            let mut k = 0;
            for (w, f) in out.iter_mut().zip(&faces[start..]) {
                let len = f.vertices.len();
                corners[k..k + len].copy_from_slice(&f.vertices);
                *w = WorldFace {
                    leaf: li,
                    len: len as u32,
                    first: at + k,
                    normal: Corners::new(&f.vertices, table).newell(),
                };
                k += len;
            }
            done.add(out.len());
        };
        if parallel {
            parts.into_par_iter().for_each(fill);
        } else {
            parts.into_iter().for_each(fill);
        }
    }

    /// The world points of face `f`, in mesh order.
    pub(crate) fn points_of(&self, f: usize) -> Corners<'_> {
        let first = self.leaf_first[self.faces[f].leaf as usize];
        Corners::new(
            self.vertices_of(f),
            table_of(self.shared, &self.points, first),
        )
    }

    /// The vertex indices of face `f` in its leaf mesh.
    pub(crate) fn vertices_of(&self, f: usize) -> &[u32] {
        let face = &self.faces[f];
        &self.vertices[face.first..face.first + face.len as usize]
    }

    /// The world bounding box of face `f`: min then max.
    pub(crate) fn bbox_of(&self, f: usize) -> [[f64; 3]; 2] {
        let b = Box3::from_points(self.points_of(f).iter());
        [b.lo.into(), b.hi.into()]
    }
}

/// The points from `at` in the point space of `shared` then `points` (to the end of the part
/// `at` is in: a leaf's points are all in one).
fn table_of<'a>(shared: &'a [P3], points: &'a [P3], at: usize) -> &'a [P3] {
    match at.checked_sub(shared.len()) {
        Some(own) => &points[own..],
        None => &shared[at..],
    }
}

/// Appends a mesh's faces' [`WorldFaces::clean_piece`] numbers to `out`, numbering its
/// pieces from `next` on (its pieces found once, in `pieces_of`). The solidity test examined every pair of triangles of
/// one edge-connected piece (of the capped surface, for a capped mesh: a mesh's piece lies
/// in one of those) and found none meeting other than in shared vertices and edges, when it
/// proved the mesh a solid, capped it, or proved the piece ([`Mesh::proven`]).
fn clean_pieces(
    mesh: &Mesh,
    pieces_of: &mut HashMap<*const Mesh, Pieces>,
    out: &mut Vec<u32>,
    next: &mut u32,
) {
    let n = mesh.faces.len();
    let whole = mesh.cullable() || mesh.capped();
    let proven = mesh.proven.as_ref().filter(|p| p.faces.len() == n);
    if !whole && proven.is_none() {
        out.extend(std::iter::repeat_n(NO_PIECE, n));
        return;
    }
    let base = *next;
    // A solid's pieces as its test found them; others' found here.
    let kept = mesh
        .pieces
        .as_deref()
        .filter(|p| mesh.cullable() && p.of_face.len() == n);
    let pieces = match kept {
        Some(p) => p,
        None => pieces_of
            .entry(mesh as *const Mesh)
            .or_insert_with(|| edge_pieces(&mesh.faces)),
    };
    *next += pieces.count as u32;
    chunked::extend_map(out, n, |f| {
        let clean = whole || proven.is_some_and(|p| p.faces[f]);
        if clean {
            base + pieces.of_face[f]
        } else {
            NO_PIECE
        }
    });
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::emit::lines::intersect::intersection_edges;
    use crate::scene::Object;

    #[test]
    fn square_face_in_world() {
        let scene = crate::scene::testing::unit_square_scene(vec![vec![0, 1, 2, 3]]);
        let w = WorldFaces::build(&scene, None, Count::NONE);
        assert_eq!(w.faces.len(), 1);
        assert_eq!(w.faces[0].normal, V3::new(0., 0., 2.));
        assert_eq!(w.bbox_of(0), [[0., 0., 0.], [1., 1., 0.]]);
        // Not prepared: no piece is known to be free of self-intersection.
        assert_eq!(w.clean_piece, vec![NO_PIECE]);
    }

    /// A wavy field of `n` by `n` cells: quads in even rows, two triangles each in odd
    /// rows (so that chunks of faces hold different numbers of corners).
    fn field(n: u32) -> Mesh {
        let h = |x: u32, y: u32| ((x * 7 + y * 13) % 5) as f64 * 0.1 + (x as f64 * 0.3).sin();
        let vertices = (0..=n)
            .flat_map(|y| (0..=n).map(move |x| P3::new(x as f64, y as f64, h(x, y))))
            .collect();
        let at = |x: u32, y: u32| y * (n + 1) + x;
        let faces = (0..n)
            .flat_map(|y| (0..n).map(move |x| (x, y)))
            .flat_map(|(x, y)| {
                let (a, b, c, d) = (at(x, y), at(x + 1, y), at(x + 1, y + 1), at(x, y + 1));
                if y % 2 == 0 {
                    vec![vec![a, b, c, d]]
                } else {
                    vec![vec![a, b, c], vec![a, c, d]]
                }
            })
            .map(Face::new)
            .collect();
        Mesh {
            vertices,
            faces,
            ..Default::default()
        }
    }

    /// A torus of `n` by `n` cells, two triangles each: a closed solid.
    fn torus(n: u32) -> Mesh {
        let tau = std::f64::consts::TAU;
        let vertices = (0..n * n)
            .map(|k| {
                let (u, v) = (
                    (k % n) as f64 * tau / n as f64,
                    (k / n) as f64 * tau / n as f64,
                );
                let r = 2.0 + 0.5 * v.cos();
                P3::new(r * u.cos(), r * u.sin(), 0.5 * v.sin())
            })
            .collect();
        let at = |i: u32, j: u32| (j % n) * n + i % n;
        let faces = (0..n * n)
            .flat_map(|k| {
                let (i, j) = (k % n, k / n);
                let (a, b, c, d) = (at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
                [vec![a, b, c], vec![a, c, d]]
            })
            .collect();
        Mesh::from_polygons(vertices, faces, &mut Vec::new()).expect("a clean torus")
    }

    /// The world faces of big leaves made in chunks on three threads are the one-thread
    /// faces: corners, their starts (across chunk ends), normals bit for bit, leaves, and the
    /// pieces of a big solid.
    #[test]
    fn world_faces_on_several_threads_are_the_one_thread_faces() {
        let big = Object::from_mesh("big", field(120));
        let n = big.face_count();
        assert!(n > 2 * CHUNK, "{n} faces");
        let kids = vec![
            Object::from_mesh("small", field(3)),
            big,
            crate::scene::testing::cuboid("box", [0., 0., 0.], [1., 2., 3.]),
            Object::from_mesh("ring", torus(100)),
            Object::from_mesh("again", field(70)),
        ];
        let mut scene = Scene::new(Object::group("", kids), "t".into());
        // Prepared: the torus' and the box's faces are on clean pieces.
        crate::prepare::prepare(
            &mut scene,
            &crate::PrepareOptions::default(),
            &crate::Progress::default(),
        );
        let listed = |w: &WorldFaces| {
            let faces: Vec<(u32, u32, usize, [u64; 3])> = w
                .faces
                .iter()
                .map(|f| (f.leaf, f.len, f.first, f.normal.map(f64::to_bits).into()))
                .collect();
            (
                faces,
                w.vertices.clone(),
                w.leaf_first.clone(),
                w.clean_piece.clone(),
            )
        };
        let pool = crate::chunked::pool;
        let one = pool(1).install(|| listed(&WorldFaces::build(&scene, None, Count::NONE)));
        let three = pool(3).install(|| listed(&WorldFaces::build(&scene, None, Count::NONE)));
        assert_eq!(one.0.len(), scene.face_count());
        assert_eq!(one, three);
        let clean = one.3.iter().filter(|&&p| p != NO_PIECE).count();
        assert!(clean > 2 * CHUNK, "{clean} faces on clean pieces");
        // Each face's corners are its mesh face's, from where the one before it ends.
        let meshes: Vec<&Mesh> = scene.leaves().into_iter().map(|l| l.mesh).collect();
        let mut corners = 0;
        for ((leaf, len, first, _), mesh_face) in
            one.0.iter().zip(meshes.iter().flat_map(|m| m.faces.iter()))
        {
            assert_eq!(*first, corners);
            assert_eq!(*len as usize, mesh_face.vertices.len());
            assert_eq!(
                &one.1[*first..*first + *len as usize],
                &mesh_face.vertices[..]
            );
            assert!((*leaf as usize) < meshes.len());
            corners += *len as usize;
        }
    }

    /// The faces' points and normals with the screen's points shared, against the faces made
    /// alone: the same bits (a mirrored instance, a warped face and a perspective view
    /// through the scene's middle among them).
    #[test]
    fn shared_points_are_the_faces_own_bit_for_bit() {
        use crate::geom::{M4, V3};
        use crate::view::{Camera, View};
        use std::sync::Arc;
        let crate::scene::Content::Subobjects(mut kids) =
            crate::scene::testing::warped_scene().root.content
        else {
            panic!("a group");
        };
        let proto = Arc::new(crate::scene::testing::cuboid(
            "p",
            [0., 0., 0.],
            [1., 2., 3.],
        ));
        let mirror = M4::new_nonuniform_scaling(&V3::new(-1., 1., 1.));
        kids.push(Object::instance("mirrored", proto.clone(), mirror));
        kids.push(Object::instance(
            "plain",
            proto,
            M4::new_translation(&V3::new(3., 0., 0.)),
        ));
        let scene = Scene::new(Object::group("", kids), "t".into());
        let alone = WorldFaces::build(&scene, None, Count::NONE);
        let near = Camera::perspective(
            P3::new(0., 0., 1.5),
            P3::new(0., 0., -5.),
            V3::y(),
            90.,
            0.1,
        );
        for camera in [Camera::three_quarter(), near.unwrap()] {
            let view = View::new(&scene, camera);
            let w = WorldFaces::build(&scene, Some(&view.screen), Count::NONE);
            let bits = |p: Corners| -> Vec<[u64; 3]> {
                p.iter()
                    .map(|q| q.coords.map(f64::to_bits).into())
                    .collect()
            };
            let shares = |f: usize| w.leaf_first[w.faces[f].leaf as usize] < w.shared.len();
            for f in 0..alone.faces.len() {
                assert_eq!(bits(w.points_of(f)), bits(alone.points_of(f)), "face {f}");
                assert_eq!(w.vertices_of(f), alone.vertices_of(f));
                assert_eq!(w.faces[f].normal, alone.faces[f].normal);
                assert_eq!(w.bbox_of(f), alone.bbox_of(f));
            }
            // Every leaf is projected in both views (the mirrored box reversed on screen, the
            // warped quad split, faces cut by the near plane): all share, none is copied.
            assert_eq!(alone.faces.len(), 31);
            assert!((0..31).all(shares));
            assert!(w.points.is_empty());
        }
        // With a leaf the view does not hold, that leaf's points are made: the same bits.
        let mut sf =
            std::sync::Arc::unwrap_or_clone(View::new(&scene, Camera::three_quarter()).screen);
        let last = sf.leaves.pop().unwrap();
        let w = WorldFaces::build(&scene, Some(&sf), Count::NONE);
        assert_eq!(w.points.len(), 8);
        assert_eq!(w.leaf_first.last(), Some(&w.shared.len()));
        for f in 0..alone.faces.len() {
            assert_eq!(
                w.points_of(f).to_vec(),
                alone.points_of(f).to_vec(),
                "face {f}"
            );
        }
        assert_eq!(last.face_count, 6);
        assert!(alone.shared.is_empty());
    }

    /// Two tetrahedra in one mesh, the second moved by `shift` (on every axis).
    fn two_tetrahedra(shift: f64) -> Scene {
        let tet = [[0., 0., 0.], [1., 0., 0.], [0., 1., 0.], [0., 0., 1.]];
        let out: [[u32; 3]; 4] = [[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]];
        let mut pts: Vec<P3> = tet.iter().map(|&p| P3::from(p)).collect();
        pts.extend(
            tet.iter()
                .map(|p| P3::new(p[0] + shift, p[1] + shift, p[2] + shift)),
        );
        let faces = (0..2)
            .flat_map(|k| {
                out.iter()
                    .map(move |f| f.iter().map(|v| v + 4 * k).collect())
            })
            .collect();
        let raw = crate::geom::PolyMesh::new(pts, faces);
        let root = Object::group("", vec![crate::scene::testing::leaf("two", &raw)]);
        let mut scene = Scene::new(root, "t".into());
        crate::prepare::prepare(
            &mut scene,
            &crate::PrepareOptions::default(),
            &crate::Progress::default(),
        );
        scene
    }

    #[test]
    fn pieces_of_a_solid_are_clean_and_their_crossings_still_drawn() {
        // A solid of two pieces passing through one another: each piece is free of
        // self-intersection, the pair is not, and its curves are found.
        let scene = two_tetrahedra(0.25);
        assert!(scene.leaves()[0].mesh.cullable());
        let w = WorldFaces::build(&scene, None, Count::NONE);
        assert_eq!(w.clean_piece, [0, 0, 0, 0, 1, 1, 1, 1]);
        let curves = intersection_edges(&w, |_| true, crate::count::Count::NONE);
        assert!(!curves.is_empty());
        assert!(curves.iter().all(|e| e.faces[0].0 < 4 && e.faces[1].0 >= 4));
        // Apart, no curve.
        let w = WorldFaces::build(&two_tetrahedra(3.0), None, Count::NONE);
        assert!(intersection_edges(&w, |_| true, crate::count::Count::NONE).is_empty());
    }

    #[test]
    fn a_piece_crossing_itself_is_not_clean() {
        // A mesh not proven (here: its verdict replaced) has no clean piece: every pair is
        // tested.
        let mut scene = two_tetrahedra(0.25);
        let crate::scene::Content::Subobjects(kids) = &mut scene.root.content else {
            panic!("a group");
        };
        let crate::scene::Content::Mesh(m) = &mut kids[0].content else {
            panic!("a leaf");
        };
        m.solidity = Some(crate::scene::Solidity::InsideOut);
        let w = WorldFaces::build(&scene, None, Count::NONE);
        assert!(w.clean_piece.iter().all(|&k| k == NO_PIECE));
        assert!(!intersection_edges(&w, |_| true, crate::count::Count::NONE).is_empty());
    }
}
