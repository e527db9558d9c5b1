//! The five Platonic solids, as orbits of one or two seed points.

use super::orbit::{orbit, Group};
use super::{golden_ratio, unit_solid, Build};
use crate::geom::PolyMesh;

/// The Platonic solids by name.
pub(super) static SOLIDS: [(&str, Build); 5] = [
    ("tetrahedron", tetrahedron),
    ("cube", cube),
    ("octahedron", octahedron),
    ("dodecahedron", dodecahedron),
    ("icosahedron", icosahedron),
];

/// Tetrahedron {3,3}: (1, 1, 1) with an even number of sign changes (alternate cube corners).
fn tetrahedron() -> PolyMesh {
    unit_solid(orbit(Group::FullTetrahedral, &[[1.0, 1.0, 1.0]]))
}

/// Cube {4,3}: (±1, ±1, ±1).
fn cube() -> PolyMesh {
    unit_solid(orbit(Group::FullOctahedral, &[[1.0, 1.0, 1.0]]))
}

/// Octahedron {3,4}: the permutations of (±1, 0, 0).
fn octahedron() -> PolyMesh {
    unit_solid(orbit(Group::FullOctahedral, &[[1.0, 0.0, 0.0]]))
}

/// Dodecahedron {5,3}: (±1, ±1, ±1) and the cyclic permutations of (0, ±1/φ, ±φ).
fn dodecahedron() -> PolyMesh {
    let phi = golden_ratio();
    let seeds = [[1.0, 1.0, 1.0], [0.0, 1.0 / phi, phi]];
    unit_solid(orbit(Group::Pyritohedral, &seeds))
}

/// Icosahedron {3,5}: the cyclic permutations of (0, ±1, ±φ).
fn icosahedron() -> PolyMesh {
    unit_solid(orbit(Group::Pyritohedral, &[[0.0, 1.0, golden_ratio()]]))
}

#[cfg(test)]
mod tests {
    use super::super::checks::{assert_counts, assert_uniform, Known};
    use super::*;

    const TABLE: [Known; 5] = [
        ("tetrahedron", 4, &[(3, 4)]),
        ("cube", 8, &[(4, 6)]),
        ("octahedron", 6, &[(3, 8)]),
        ("dodecahedron", 20, &[(5, 12)]),
        ("icosahedron", 12, &[(3, 20)]),
    ];

    #[test]
    fn platonic_solids_are_uniform() {
        for (name, build) in &SOLIDS {
            assert_uniform(name, &build());
        }
    }

    #[test]
    fn platonic_counts_match_the_table() {
        assert_counts(&SOLIDS, &TABLE);
    }
}
