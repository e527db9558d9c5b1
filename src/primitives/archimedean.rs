//! The thirteen Archimedean solids, as orbits of seed points under a point group of the cube.
//!
//! Coordinates are the standard closed forms (before scaling to unit edges), with φ the golden
//! ratio. The two snub solids are chiral; each doc comment says which hand is built.

use super::orbit::{orbit, Group};
use super::{golden_ratio, unit_solid, Build};
use crate::geom::PolyMesh;

/// The Archimedean solids by name.
pub(super) static SOLIDS: [(&str, Build); 13] = [
    ("truncated_tetrahedron", truncated_tetrahedron),
    ("cuboctahedron", cuboctahedron),
    ("truncated_cube", truncated_cube),
    ("truncated_octahedron", truncated_octahedron),
    ("rhombicuboctahedron", rhombicuboctahedron),
    ("truncated_cuboctahedron", truncated_cuboctahedron),
    ("snub_cube", snub_cube),
    ("icosidodecahedron", icosidodecahedron),
    ("truncated_dodecahedron", truncated_dodecahedron),
    ("truncated_icosahedron", truncated_icosahedron),
    ("rhombicosidodecahedron", rhombicosidodecahedron),
    ("truncated_icosidodecahedron", truncated_icosidodecahedron),
    ("snub_dodecahedron", snub_dodecahedron),
];

/// The real root of x³ + p·x + q = 0 when it is the only one (4p³ + 27q² > 0), by Cardano.
fn cardano_root(p: f64, q: f64) -> f64 {
    let s = (q * q / 4.0 + p * p * p / 27.0).sqrt();
    (-q / 2.0 + s).cbrt() + (-q / 2.0 - s).cbrt()
}

/// The tribonacci constant t, real root of t³ = t² + t + 1: (1 + ∛(19 + 3√33) + ∛(19 − 3√33))/3.
fn tribonacci_constant() -> f64 {
    1.0 / 3.0 + cardano_root(-4.0 / 3.0, -38.0 / 27.0)
}

/// Truncated tetrahedron 3.6.6: the permutations of (±3, ±1, ±1) with an even number of minus
/// signs.
fn truncated_tetrahedron() -> PolyMesh {
    unit_solid(orbit(Group::FullTetrahedral, &[[3.0, 1.0, 1.0]]))
}

/// Cuboctahedron 3.4.3.4: the permutations of (±1, ±1, 0).
fn cuboctahedron() -> PolyMesh {
    unit_solid(orbit(Group::FullOctahedral, &[[1.0, 1.0, 0.0]]))
}

/// Truncated cube 3.8.8: the permutations of (±(√2 − 1), ±1, ±1).
fn truncated_cube() -> PolyMesh {
    let seed = [2f64.sqrt() - 1.0, 1.0, 1.0];
    unit_solid(orbit(Group::FullOctahedral, &[seed]))
}

/// Truncated octahedron 4.6.6: the permutations of (0, ±1, ±2).
fn truncated_octahedron() -> PolyMesh {
    unit_solid(orbit(Group::FullOctahedral, &[[0.0, 1.0, 2.0]]))
}

/// Rhombicuboctahedron 3.4.4.4: the permutations of (±1, ±1, ±(1 + √2)).
fn rhombicuboctahedron() -> PolyMesh {
    let seed = [1.0, 1.0, 1.0 + 2f64.sqrt()];
    unit_solid(orbit(Group::FullOctahedral, &[seed]))
}

/// Truncated cuboctahedron 4.6.8: the permutations of (±1, ±(1 + √2), ±(1 + 2√2)).
fn truncated_cuboctahedron() -> PolyMesh {
    let r2 = 2f64.sqrt();
    let seed = [1.0, 1.0 + r2, 1.0 + 2.0 * r2];
    unit_solid(orbit(Group::FullOctahedral, &[seed]))
}

/// Snub cube 3.3.3.3.4, with t the tribonacci constant: the images of (1, 1/t, t) under the
/// 24 rotations of the cube, i.e. the even permutations of (±1, ±1/t, ±t) with an even number of
/// minus signs and the odd permutations with an odd number.
///
/// Handedness: this is the hand that has a vertex on the ray through (1, 1/t, t); the mirror
/// image (e.g. x ↦ −x) is the other snub cube.
fn snub_cube() -> PolyMesh {
    let t = tribonacci_constant();
    unit_solid(orbit(Group::ChiralOctahedral, &[[1.0, 1.0 / t, t]]))
}

/// Icosidodecahedron 3.5.3.5: the cyclic permutations of (0, 0, ±φ) and of
/// (±1/2, ±φ/2, ±φ²/2).
fn icosidodecahedron() -> PolyMesh {
    let phi = golden_ratio();
    let seeds = [[0.0, 0.0, phi], [0.5, phi / 2.0, phi * phi / 2.0]];
    unit_solid(orbit(Group::Pyritohedral, &seeds))
}

/// Truncated dodecahedron 3.10.10: the cyclic permutations of (0, ±1/φ, ±(2 + φ)),
/// (±1/φ, ±φ, ±2φ) and (±φ, ±2, ±(φ + 1)).
fn truncated_dodecahedron() -> PolyMesh {
    let phi = golden_ratio();
    let seeds = [
        [0.0, 1.0 / phi, 2.0 + phi],
        [1.0 / phi, phi, 2.0 * phi],
        [phi, 2.0, phi + 1.0],
    ];
    unit_solid(orbit(Group::Pyritohedral, &seeds))
}

/// Truncated icosahedron 5.6.6: the cyclic permutations of (0, ±1, ±3φ), (±1, ±(2 + φ), ±2φ)
/// and (±φ, ±2, ±φ³).
fn truncated_icosahedron() -> PolyMesh {
    let phi = golden_ratio();
    let seeds = [
        [0.0, 1.0, 3.0 * phi],
        [1.0, 2.0 + phi, 2.0 * phi],
        [phi, 2.0, phi.powi(3)],
    ];
    unit_solid(orbit(Group::Pyritohedral, &seeds))
}

/// Rhombicosidodecahedron 3.4.5.4: the cyclic permutations of (±1, ±1, ±φ³), (±φ², ±φ, ±2φ)
/// and (±(2 + φ), 0, ±φ²).
fn rhombicosidodecahedron() -> PolyMesh {
    let phi = golden_ratio();
    let seeds = [
        [1.0, 1.0, phi.powi(3)],
        [phi * phi, phi, 2.0 * phi],
        [2.0 + phi, 0.0, phi * phi],
    ];
    unit_solid(orbit(Group::Pyritohedral, &seeds))
}

/// Truncated icosidodecahedron 4.6.10: the cyclic permutations of (±1/φ, ±1/φ, ±(3 + φ)),
/// (±2/φ, ±φ, ±(1 + 2φ)), (±1/φ, ±φ², ±(3φ − 1)), (±(2φ − 1), ±2, ±(2 + φ)) and (±φ, ±3, ±2φ).
fn truncated_icosidodecahedron() -> PolyMesh {
    let phi = golden_ratio();
    let seeds = [
        [1.0 / phi, 1.0 / phi, 3.0 + phi],
        [2.0 / phi, phi, 1.0 + 2.0 * phi],
        [1.0 / phi, phi * phi, 3.0 * phi - 1.0],
        [2.0 * phi - 1.0, 2.0, 2.0 + phi],
        [phi, 3.0, 2.0 * phi],
    ];
    unit_solid(orbit(Group::Pyritohedral, &seeds))
}

/// Snub dodecahedron 3.3.3.3.5, with ξ the real root of ξ³ − 2ξ = φ, α = ξ − 1/ξ and
/// β = ξφ + φ² + φ/ξ: the cyclic permutations, with an even number of minus signs, of
/// (2α, 2, 2β), (α + β/φ + φ, −αφ + β + 1/φ, α/φ + βφ − 1),
/// (−α/φ + βφ + 1, −α + β/φ − φ, αφ + β − 1/φ), (−α/φ + βφ − 1, α − β/φ − φ, αφ + β + 1/φ)
/// and (α + β/φ − φ, αφ − β + 1/φ, α/φ + βφ + 1).
///
/// Handedness: this is the hand that has a vertex on the ray through (2α, 2, 2β); its mirror
/// image (e.g. x ↦ −x) is the other snub dodecahedron.
fn snub_dodecahedron() -> PolyMesh {
    let phi = golden_ratio();
    let xi = cardano_root(-2.0, -phi);
    let (a, b) = (xi - 1.0 / xi, xi * phi + phi * phi + phi / xi);
    let seeds = [
        [2.0 * a, 2.0, 2.0 * b],
        [
            a + b / phi + phi,
            -a * phi + b + 1.0 / phi,
            a / phi + b * phi - 1.0,
        ],
        [
            -a / phi + b * phi + 1.0,
            -a + b / phi - phi,
            a * phi + b - 1.0 / phi,
        ],
        [
            -a / phi + b * phi - 1.0,
            a - b / phi - phi,
            a * phi + b + 1.0 / phi,
        ],
        [
            a + b / phi - phi,
            a * phi - b + 1.0 / phi,
            a / phi + b * phi + 1.0,
        ],
    ];
    unit_solid(orbit(Group::ChiralTetrahedral, &seeds))
}

#[cfg(test)]
mod tests {
    use super::super::checks::{assert_counts, assert_uniform, Known};
    use super::*;
    use crate::geom::V3;

    const TABLE: [Known; 13] = [
        ("truncated_tetrahedron", 12, &[(3, 4), (6, 4)]),
        ("cuboctahedron", 12, &[(3, 8), (4, 6)]),
        ("truncated_cube", 24, &[(3, 8), (8, 6)]),
        ("truncated_octahedron", 24, &[(4, 6), (6, 8)]),
        ("rhombicuboctahedron", 24, &[(3, 8), (4, 18)]),
        ("truncated_cuboctahedron", 48, &[(4, 12), (6, 8), (8, 6)]),
        ("snub_cube", 24, &[(3, 32), (4, 6)]),
        ("icosidodecahedron", 30, &[(3, 20), (5, 12)]),
        ("truncated_dodecahedron", 60, &[(3, 20), (10, 12)]),
        ("truncated_icosahedron", 60, &[(5, 12), (6, 20)]),
        ("rhombicosidodecahedron", 60, &[(3, 20), (4, 30), (5, 12)]),
        (
            "truncated_icosidodecahedron",
            120,
            &[(4, 30), (6, 20), (10, 12)],
        ),
        ("snub_dodecahedron", 60, &[(3, 80), (5, 12)]),
    ];

    #[test]
    fn archimedean_solids_are_uniform() {
        for (name, build) in &SOLIDS {
            assert_uniform(name, &build());
        }
    }

    #[test]
    fn archimedean_counts_match_the_table() {
        assert_counts(&SOLIDS, &TABLE);
    }

    #[test]
    fn cubic_constants() {
        let t = tribonacci_constant();
        assert!((t.powi(3) - t * t - t - 1.0).abs() < 1e-14);
        let (phi, xi) = (golden_ratio(), cardano_root(-2.0, -golden_ratio()));
        assert!((xi.powi(3) - 2.0 * xi - phi).abs() < 1e-14);
    }

    #[test]
    fn snub_handedness_is_as_documented() {
        let t = tribonacci_constant();
        let phi = golden_ratio();
        let xi = cardano_root(-2.0, -phi);
        let (a, b) = (xi - 1.0 / xi, xi * phi + phi * phi + phi / xi);
        for (mesh, ray) in [
            (snub_cube(), V3::new(1.0, 1.0 / t, t)),
            (snub_dodecahedron(), V3::new(2.0 * a, 2.0, 2.0 * b)),
        ] {
            let on_ray = |v: &V3| v.normalize().dot(&ray.normalize()) > 1.0 - 1e-12;
            assert!(mesh.vertices.iter().any(|p| on_ray(&p.coords)));
            assert!(!mesh
                .vertices
                .iter()
                .any(|p| on_ray(&V3::new(-p.x, p.y, p.z))));
        }
    }
}
