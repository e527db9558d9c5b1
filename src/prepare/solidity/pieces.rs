//! Solids piece by piece: where a mesh as a whole is not a proven solid, the edge-connected
//! pieces of it that are, so that their back faces may still be culled.
//!
//! The culling argument ([`super`], docs/numerics.md "Back-face culling") never looks past
//! one piece: a back face of piece P is hidden by a front face of P whenever P alone is
//! closed, embedded and outward (its winding number w_P is 0 or +1, and 0 at the eye).
//! Another piece that crosses itself, is inside out or has a flat face says nothing about
//! P. So a character mesh whose body folds through itself (ogre: 686 crossing pairs, all
//! on the body) still culls its armour, eyes and teeth, and a scan with one bad shell culls
//! the rest.
//!
//! The test of each piece is the whole mesh's, complete: every face triangulated (a face
//! that is not simple, or has a flat triangle, fails its piece), every pair of triangles of
//! one piece tested for crossing, every piece's signed volume decided exactly. For an open
//! mesh it runs on the capped surface capping last built ([`crate::prepare::solidity::caps`]): a piece
//! is then proven with its caps, and only the caps of proven pieces are kept (a cap of
//! another piece plays no part in P's argument).

use crate::count::Span;
use crate::geom::P3;
use crate::scene::{Mesh, ProvenPieces};

use super::Surface;

/// What a test of the whole surface already knows of its crossing pairs of faces.
#[derive(Debug, Clone, Copy)]
pub(crate) enum Crossings<'a> {
    /// Every crossing pair: the pieces need no test of their own.
    All(&'a [[u32; 2]]),
    /// Some crossing pairs: their pieces fail, the others are tested.
    Some(&'a [[u32; 2]]),
}

/// The proven pieces of `mesh`, a closed, consistently oriented mesh whose first `n` faces
/// are the original mesh's (the rest: caps, triangles), tested on its `surface`; with the
/// caps of the proven pieces. `crossing`: what is known of the crossing pairs (not tested
/// again). None when no piece is proven. A test of the pieces fills `span`.
pub(crate) fn proven_pieces(
    mesh: &Mesh,
    surface: &Surface,
    n: usize,
    crossing: Crossings,
    span: Span,
) -> Option<(ProvenPieces, Vec<[P3; 3]>)> {
    let piece = |f: u32| surface.piece(f);
    let mut good = vec![true; surface.pieces.count];
    for &f in &surface.flat {
        good[piece(f)] = false;
    }
    // Both faces of a pair are on one piece.
    let (Crossings::All(known) | Crossings::Some(known)) = crossing;
    known.iter().for_each(|&[f, _]| good[piece(f)] = false);
    if let Crossings::Some(_) = crossing {
        // Every pair of the pieces not yet failed (pairs never leave a piece).
        let found = surface.crossing(mesh, |f| good[piece(f)], span);
        found.iter().for_each(|&[f, _]| good[piece(f)] = false);
    }
    let good = surface.outward(mesh, |k| good[k]);
    let proven = good.iter().filter(|&&g| g).count();
    if proven == 0 {
        return None;
    }
    let caps = mesh.faces[n..]
        .iter()
        .enumerate()
        .filter(|&(k, _)| good[piece((n + k) as u32)])
        .map(|(_, f)| {
            let v = &f.vertices;
            [0, 1, 2].map(|i| mesh.vertices[v[i] as usize])
        })
        .collect();
    let faces = (0..n as u32).map(|f| good[piece(f)]).collect();
    Some((
        ProvenPieces {
            faces,
            pieces: surface.pieces.count as u32,
            proven: proven as u32,
        },
        caps,
    ))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::count::Span;
    use crate::prepare::solidity::caps::tests::{box_with_chimney, cube_without};
    use crate::prepare::solidity::decide;
    use crate::prepare::solidity::tests::crossing_piece;
    use crate::scene::{CapFailure, Face, Solidity};

    /// `b`'s faces after `a`'s, its vertices moved by `dx` along x.
    fn beside(a: &Mesh, b: &Mesh, dx: f64) -> Mesh {
        let off = a.vertices.len() as u32;
        let mut m = a.clone();
        m.vertices
            .extend(b.vertices.iter().map(|p| P3::new(p.x + dx, p.y, p.z)));
        m.faces.extend(b.faces.iter().map(|f| {
            Face::new(
                f.vertices
                    .iter()
                    .map(|v| v + off)
                    .collect::<crate::scene::FaceIndices>(),
            )
        }));
        m
    }

    #[test]
    fn a_closed_mesh_culls_its_proven_piece_only() {
        let mut m = beside(&cube_without(&[]), &crossing_piece(), 3.0);
        decide(&mut m, crate::count::Count::NONE);
        assert!(matches!(m.solidity, Some(Solidity::SelfIntersecting(_))));
        let p = m.proven.as_ref().expect("the cube is proven");
        assert_eq!((p.proven, p.pieces), (1, 2));
        assert_eq!(p.faces, [[true; 6].as_slice(), &[false; 6]].concat());
        assert!(m.caps.is_empty());
        // The crossing piece alone: nothing proven.
        let mut alone = crossing_piece();
        decide(&mut alone, crate::count::Count::NONE);
        assert_eq!(alone.proven, None);
    }

    #[test]
    fn an_open_mesh_culls_its_capped_proven_piece_only() {
        // An open box (caps into a solid) beside a box whose chimney rises through its mouth
        // (its cap crosses its own piece).
        let mut m = beside(&cube_without(&[1]), &box_with_chimney(1.5), 3.0);
        decide(&mut m, crate::count::Count::NONE);
        assert!(matches!(
            m.solidity,
            Some(Solidity::Open(CapFailure::SelfIntersecting(_)))
        ));
        let p = m
            .proven
            .as_ref()
            .expect("the open box is proven with its cap");
        assert_eq!((p.proven, p.pieces), (1, 2));
        assert_eq!(p.faces, [[true; 5].as_slice(), &[false; 13]].concat());
        // Only the open box's cap is kept: a fan of four in its mouth, z = 1, x in [0, 1].
        assert_eq!(m.caps.len(), 4);
        assert!(m.caps.iter().flatten().all(|q| q.z == 1.0 && q.x <= 1.0));
    }

    #[test]
    fn pieces_from_a_known_crossing_list_match_a_fresh_test() {
        let m = beside(&cube_without(&[]), &crossing_piece(), 3.0);
        let e = super::super::examine(&m);
        let surface = e.surface.as_ref().expect("closed");
        let span = Span::NONE;
        let fresh = proven_pieces(&m, surface, m.faces.len(), Crossings::Some(&[]), span);
        let known = proven_pieces(
            &m,
            surface,
            m.faces.len(),
            Crossings::All(&e.crossing),
            span,
        );
        assert!(!e.crossing.is_empty());
        assert_eq!(fresh, known);
        // Some of the pairs: their piece fails, the rest is tested.
        let some = proven_pieces(
            &m,
            surface,
            m.faces.len(),
            Crossings::Some(&e.crossing[..1]),
            span,
        );
        assert_eq!(fresh, some);
    }
}
