//! The one convexity test of planar rings, with a named strictness: what each caller may
//! accept (degenerate rings, collinear corners, or only proper turns) is said at the call.

use super::hull2::has_turn;
use super::poly2::Pt2;
use super::predicates::orient2d;

/// How strictly [`is_convex_ccw`] reads "convex counter-clockwise". Every variant is exact
/// (signs of `orient2d` and of coordinate differences).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Strictness {
    /// Every corner turns properly left and the ring winds round once. Repeated points and
    /// collinear corners are refused; any three corners then make a proper triangle.
    Strict,
    /// The ring bounds a convex region with area, counter-clockwise: with repeated points
    /// dropped, every corner turns left or goes straight on (never back: a spike is a half
    /// turn), some corner turns properly, and the ring winds round once. Equivalently: every
    /// point lies on the closed left side of every edge, and the ring makes a proper turn.
    AllowCollinear,
    /// No corner turns right (collinear corners, repeated points and spikes allowed) and the
    /// edge directions change half at most twice: accepts every ring of
    /// [`Strictness::AllowCollinear`] and also degenerate ones without area (a point, a
    /// segment run out and back).
    AllowDegenerate,
}

/// True when the ring `r` (last point not repeated) is convex and counter-clockwise in the
/// sense `strictness` names. O(n).
#[inline]
pub(crate) fn is_convex_ccw(r: &[Pt2], strictness: Strictness) -> bool {
    match strictness {
        Strictness::Strict => strictly_convex(r),
        Strictness::AllowCollinear => convex_with_area(r),
        Strictness::AllowDegenerate => turns_all(r, |o, _| o >= 0.0) && half_changes(r) <= 2,
    }
}

/// True when `keep(orient, corner)` holds at every corner (a, b, c) of the ring.
fn turns_all(r: &[Pt2], keep: impl Fn(f64, [Pt2; 3]) -> bool) -> bool {
    let n = r.len();
    (0..n).all(|i| {
        let (a, b, c) = (r[i], r[(i + 1) % n], r[(i + 2) % n]);
        keep(orient2d(a, b, c), [a, b, c])
    })
}

/// [`Strictness::Strict`]. Strict turns leave no zero-length edge, so each turn is less than
/// half a turn and the edge directions rotate monotonically; two changes of half then mean
/// one winding.
fn strictly_convex(r: &[Pt2]) -> bool {
    turns_all(r, |o, _| o > 0.0) && half_changes(r) == 2
}

/// [`Strictness::AllowCollinear`]: repeated points dropped (in a buffer on the stack for
/// short rings), then no right turn, no turning back, some proper turn, one winding.
fn convex_with_area(r: &[Pt2]) -> bool {
    // A triangle: its one orientation (a repeated point makes it 0).
    if let [a, b, c] = r {
        return orient2d(*a, *b, *c) > 0.0;
    }
    let mut buf = [[0.0; 2]; SHORT];
    let mut long = Vec::new();
    let d: &mut [Pt2] = if r.len() <= SHORT {
        &mut buf[..r.len()]
    } else {
        long.resize(r.len(), [0.0; 2]);
        &mut long
    };
    let mut n = 0;
    for &p in r {
        if n == 0 || d[n - 1] != p {
            d[n] = p;
            n += 1;
        }
    }
    while n > 1 && d[0] == d[n - 1] {
        n -= 1;
    }
    let d = &d[..n];
    n >= 3
        && has_turn(d)
        && turns_all(d, |o, [a, b, c]| {
            o > 0.0 || (o == 0.0 && !reverses(a, b, c))
        })
        && half_changes(d) == 2
}

/// Rings up to this length are checked in a buffer on the stack.
const SHORT: usize = 16;

/// For collinear a, b, c (a ≠ b, b ≠ c): true when c lies back toward a from b (exact: the
/// signs of coordinate differences along an axis where a and b differ).
fn reverses(a: Pt2, b: Pt2, c: Pt2) -> bool {
    let k = if a[0] != b[0] { 0 } else { 1 };
    (b[k] > a[k]) != (c[k] > b[k])
}

/// How often the direction of the ring's edges (zero-length edges skipped) passes between
/// the upper half-turn of directions (y > 0, or y = 0 and x > 0) and the lower one, round
/// the ring. Exact (signs of differences of floats). A ring that turns one way at every
/// corner, each turn less than half a turn, winds round once exactly when this is 2: the
/// edge directions then rotate monotonically and pass each half's boundary once per turn.
/// Reversing the ring reverses every edge, which swaps the halves: the count is the same.
pub(crate) fn half_changes(r: &[Pt2]) -> usize {
    let n = r.len();
    let mut upper = (0..n).filter_map(|i| {
        let (a, b) = (r[i], r[(i + 1) % n]);
        (a != b).then(|| b[1] > a[1] || (b[1] == a[1] && b[0] > a[0]))
    });
    let Some(first) = upper.next() else {
        return 0;
    };
    let (mut last, mut changes) = (first, 0);
    for u in upper {
        changes += usize::from(u != last);
        last = u;
    }
    changes + usize::from(last != first)
}

#[cfg(test)]
mod tests {
    use super::*;
    use Strictness::*;

    fn square(s: f64) -> Vec<Pt2> {
        vec![[0., 0.], [s, 0.], [s, s], [0., s]]
    }

    /// The definition of [`Strictness::AllowCollinear`]: a turn, and every point on the
    /// closed left side of every edge.
    fn convex_by_definition(r: &[Pt2]) -> bool {
        let n = r.len();
        n >= 3
            && has_turn(r)
            && (0..n).all(|i| {
                let (p, q) = (r[i], r[(i + 1) % n]);
                p == q || r.iter().all(|&x| orient2d(p, q, x) >= 0.0)
            })
    }

    #[test]
    fn allow_collinear_agrees_with_the_definition() {
        let mut rng = crate::geom::rng::XorShift::new(11);
        let grid =
            |rng: &mut crate::geom::rng::XorShift| [rng.below(4) as f64, rng.below(4) as f64];
        let mut agree_convex = 0;
        for k in 0..20000 {
            let n = 3 + k % 6;
            let r: Vec<Pt2> = (0..n).map(|_| grid(&mut rng)).collect();
            let (fast, slow) = (is_convex_ccw(&r, AllowCollinear), convex_by_definition(&r));
            assert_eq!(fast, slow, "{r:?}");
            agree_convex += usize::from(fast);
            // The strictnesses nest.
            assert!(!is_convex_ccw(&r, Strict) || fast, "{r:?}");
            assert!(!fast || is_convex_ccw(&r, AllowDegenerate), "{r:?}");
        }
        assert!(agree_convex > 100, "{agree_convex}");
    }

    #[test]
    fn what_each_strictness_accepts() {
        let cases: [(&str, Vec<Pt2>, [bool; 3]); 7] = [
            ("square", square(1.), [true, true, true]),
            (
                "clockwise",
                square(1.).into_iter().rev().collect(),
                [false; 3],
            ),
            (
                "collinear",
                vec![[0., 0.], [1., 0.], [2., 0.], [2., 2.], [0., 2.]],
                [false, true, true],
            ),
            (
                "repeated",
                vec![[0., 0.], [2., 0.], [2., 0.], [2., 2.], [0., 2.]],
                [false, true, true],
            ),
            ("segment", vec![[0., 0.], [1., 0.]], [false, false, true]),
            (
                "spike",
                vec![[0., 0.], [2., 0.], [1., 0.], [1., 1.]],
                [false, false, false],
            ),
            (
                "dent",
                vec![[0., 0.], [2., 0.], [1., 0.5], [2., 2.], [0., 2.]],
                [false; 3],
            ),
        ];
        for (name, r, want) in cases {
            let got = [Strict, AllowCollinear, AllowDegenerate].map(|s| is_convex_ccw(&r, s));
            assert_eq!(got, want, "{name}");
        }
        // A pentagram turns left at every corner but winds twice.
        let star: Vec<Pt2> = (0..5)
            .map(|k| {
                let a = std::f64::consts::TAU * (2 * k) as f64 / 5.0;
                [a.cos(), a.sin()]
            })
            .collect();
        for s in [Strict, AllowCollinear, AllowDegenerate] {
            assert!(!is_convex_ccw(&star, s), "{s:?}");
        }
    }
}
