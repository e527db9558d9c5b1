//! The test kit's generator gives the numbers of the library's own, so a seed names the same
//! case in a unit test, an integration test and the library's searches.

use crate::geom::rng::XorShift;
use kepler_testkit::Rng;

#[test]
fn the_kits_rng_is_the_librarys() {
    for seed in [0, 1, 7, 0x9e37_79b9_7f4a_7c15] {
        let (mut ours, mut kit) = (XorShift::new(seed), Rng::new(seed));
        for _ in 0..1000 {
            assert_eq!(ours.next_u64(), kit.next_u64(), "seed {seed}");
        }
        let (mut ours, mut kit) = (XorShift::new(seed), Rng::new(seed));
        assert_eq!(ours.unit(), kit.unit());
        assert_eq!(ours.range(-2.0, 3.0), kit.range(-2.0, 3.0));
        assert_eq!(ours.below(17), kit.below(17));
    }
}
