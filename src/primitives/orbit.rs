//! Vertex sets as orbits of seed points under groups of signed permutations of the axes.

use crate::geom::P3;

/// A group of signed permutations of the coordinate axes, i.e. a point group of the cube.
#[derive(Debug, Clone, Copy)]
pub(super) enum Group {
    /// All 48 signed permutations: the full octahedral group O_h.
    FullOctahedral,
    /// The 24 rotations among them: the chiral octahedral group O.
    ChiralOctahedral,
    /// Any permutation with an even number of sign changes: the full tetrahedral group T_d.
    FullTetrahedral,
    /// Cyclic (even) permutations with any sign changes: the pyritohedral group T_h.
    Pyritohedral,
    /// Cyclic permutations with an even number of sign changes: the chiral tetrahedral group T.
    ChiralTetrahedral,
}

impl Group {
    /// Whether the group holds a signed permutation of the given parities.
    fn contains(self, odd_permutation: bool, odd_sign_changes: bool) -> bool {
        match self {
            Group::FullOctahedral => true,
            Group::ChiralOctahedral => odd_permutation == odd_sign_changes,
            Group::FullTetrahedral => !odd_sign_changes,
            Group::Pyritohedral => !odd_permutation,
            Group::ChiralTetrahedral => !odd_permutation && !odd_sign_changes,
        }
    }
}

/// The permutations of three axes, each with its parity (true when odd).
const PERMUTATIONS: [([usize; 3], bool); 6] = [
    ([0, 1, 2], false),
    ([1, 2, 0], false),
    ([2, 0, 1], false),
    ([1, 0, 2], true),
    ([0, 2, 1], true),
    ([2, 1, 0], true),
];

/// The distinct images of the `seeds` under `group`, seed by seed.
pub(super) fn orbit(group: Group, seeds: &[[f64; 3]]) -> Vec<P3> {
    let mut points: Vec<P3> = Vec::new();
    for seed in seeds {
        for (permutation, odd_permutation) in PERMUTATIONS {
            for signs in 0..8u32 {
                if !group.contains(odd_permutation, signs.count_ones() % 2 == 1) {
                    continue;
                }
                let image = P3::from(std::array::from_fn(|axis| {
                    let x = seed[permutation[axis]];
                    if signs >> axis & 1 == 1 {
                        -x
                    } else {
                        x
                    }
                }));
                if !points.contains(&image) {
                    points.push(image);
                }
            }
        }
    }
    points
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn group_orders() {
        let generic = [[1.0, 2.0, 3.0]];
        let order = |g| orbit(g, &generic).len();
        assert_eq!(order(Group::FullOctahedral), 48);
        assert_eq!(order(Group::ChiralOctahedral), 24);
        assert_eq!(order(Group::FullTetrahedral), 24);
        assert_eq!(order(Group::Pyritohedral), 24);
        assert_eq!(order(Group::ChiralTetrahedral), 12);
    }

    #[test]
    fn repeated_images_are_dropped() {
        assert_eq!(orbit(Group::FullOctahedral, &[[1.0, 0.0, 0.0]]).len(), 6);
        assert_eq!(orbit(Group::Pyritohedral, &[[1.0, 1.0, 1.0]]).len(), 8);
    }
}
