//! A bounding-box tree over boxes in space (median splits): which boxes meet a query box,
//! and the least of a bounded per-box quantity, in time that follows the answer, not the
//! count of boxes (a face of 65536 corners makes 65534 triangles).

use super::Box3;

/// Boxes per leaf.
const LEAF: usize = 8;

/// A node: its bounds, and either children (`left`, `left + 1`) or a range of `order`.
#[derive(Debug, Clone)]
struct Node {
    bounds: Box3,
    /// Leaf: start in `order`; inner: index of the first child.
    first: u32,
    /// Leaf: number of boxes; inner: 0.
    count: u32,
}

/// A tree over a slice of boxes (kept by the caller; items are their indices).
#[derive(Debug, Clone)]
pub(crate) struct BoxTree {
    nodes: Vec<Node>,
    order: Vec<u32>,
}

impl BoxTree {
    /// The tree of `boxes` (empty boxes are left out).
    pub(crate) fn new(boxes: &[Box3]) -> BoxTree {
        let mut order: Vec<u32> = (0..boxes.len() as u32)
            .filter(|&i| !boxes[i as usize].is_empty())
            .collect();
        let mut nodes = Vec::with_capacity(2 * order.len() / LEAF + 1);
        if !order.is_empty() {
            nodes.push(Node {
                bounds: Box3::empty(),
                first: 0,
                count: 0,
            });
            let n = order.len();
            split(boxes, &mut order, 0, n, 0, &mut nodes);
        }
        BoxTree { nodes, order }
    }

    /// True when `f` holds for some box (index into the slice the tree was built on) that
    /// meets the closed box `q`; boxes are visited in a fixed order, and the walk stops at
    /// the first for which `f` holds.
    pub(crate) fn any_meeting(
        &self,
        boxes: &[Box3],
        q: &Box3,
        mut f: impl FnMut(u32) -> bool,
    ) -> bool {
        if self.nodes.is_empty() {
            return false;
        }
        let mut stack = vec![0u32];
        while let Some(k) = stack.pop() {
            let node = &self.nodes[k as usize];
            if !meets(&node.bounds, q) {
                continue;
            }
            if node.count == 0 {
                stack.extend([node.first + 1, node.first]);
                continue;
            }
            let items = &self.order[node.first as usize..(node.first + node.count) as usize];
            if items.iter().any(|&i| meets(&boxes[i as usize], q) && f(i)) {
                return true;
            }
        }
        false
    }

    /// The least of `value(i, r)` over all boxes, where `bound(b)` is a lower bound of
    /// every value of a box within `b`, `value` may return anything not less than the
    /// current least `r` for a box it need not look at, and boxes whose bound is not below
    /// the current least are skipped (they cannot lower it). Starts from `r`.
    pub(crate) fn least(
        &self,
        mut r: f64,
        bound: impl Fn(&Box3) -> f64,
        mut value: impl FnMut(u32, f64) -> f64,
    ) -> f64 {
        if self.nodes.is_empty() {
            return r;
        }
        let mut stack = vec![0u32];
        while let Some(k) = stack.pop() {
            let node = &self.nodes[k as usize];
            if bound(&node.bounds) >= r {
                continue;
            }
            if node.count == 0 {
                // The nearer child last, so it is taken first.
                let (a, b) = (node.first, node.first + 1);
                let (da, db) = (
                    bound(&self.nodes[a as usize].bounds),
                    bound(&self.nodes[b as usize].bounds),
                );
                stack.extend(if da <= db { [b, a] } else { [a, b] });
                continue;
            }
            for &i in &self.order[node.first as usize..(node.first + node.count) as usize] {
                r = r.min(value(i, r));
            }
        }
        r
    }
}

/// Fills node `at` with boxes `order[lo..hi]`, splitting at the median centre along the
/// longest side of their centres' bounds.
fn split(
    boxes: &[Box3],
    order: &mut [u32],
    lo: usize,
    hi: usize,
    at: usize,
    nodes: &mut Vec<Node>,
) {
    let items = &mut order[lo..hi];
    let bounds = items
        .iter()
        .fold(Box3::empty(), |b, &i| b.union(&boxes[i as usize]));
    if items.len() <= LEAF {
        nodes[at] = Node {
            bounds,
            first: lo as u32,
            count: items.len() as u32,
        };
        return;
    }
    let centres = items.iter().fold(Box3::empty(), |mut b, &i| {
        b.add_point(&boxes[i as usize].center());
        b
    });
    let size = centres.size();
    let axis = (0..3).fold(0, |a, k| if size[k] > size[a] { k } else { a });
    let mid = items.len() / 2;
    items.select_nth_unstable_by(mid, |&a, &b| {
        let (ca, cb) = (
            boxes[a as usize].center()[axis],
            boxes[b as usize].center()[axis],
        );
        ca.total_cmp(&cb).then(a.cmp(&b))
    });
    let first = nodes.len();
    let blank = Node {
        bounds: Box3::empty(),
        first: 0,
        count: 0,
    };
    nodes.push(blank.clone());
    nodes.push(blank);
    nodes[at] = Node {
        bounds,
        first: first as u32,
        count: 0,
    };
    split(boxes, order, lo, lo + mid, first, nodes);
    split(boxes, order, lo + mid, hi, first + 1, nodes);
}

/// True when the closed boxes share a point.
fn meets(a: &Box3, b: &Box3) -> bool {
    (0..3).all(|i| a.lo[i] <= b.hi[i] && b.lo[i] <= a.hi[i])
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::rng::XorShift;
    use crate::geom::P3;

    fn random_boxes(rng: &mut XorShift, n: usize) -> Vec<Box3> {
        (0..n)
            .map(|_| {
                let p = P3::new(rng.unit(), rng.unit(), rng.unit());
                let s = 0.05 * rng.unit() * rng.unit();
                Box3::new(p, P3::new(p.x + s, p.y + 2.0 * s, p.z + s))
            })
            .collect()
    }

    #[test]
    fn queries_agree_with_a_scan() {
        let mut rng = XorShift::new(3);
        let boxes = random_boxes(&mut rng, 3000);
        let tree = BoxTree::new(&boxes);
        for q in random_boxes(&mut rng, 200) {
            let q = Box3::new(q.lo, P3::new(q.hi.x + 0.1, q.hi.y, q.hi.z + 0.05));
            let mut seen = Vec::new();
            assert!(!tree.any_meeting(&boxes, &q, |i| {
                seen.push(i);
                false
            }));
            seen.sort_unstable();
            let want: Vec<u32> = (0..boxes.len() as u32)
                .filter(|&i| meets(&boxes[i as usize], &q))
                .collect();
            assert_eq!(seen, want);
            // The least L-infinity distance from a point to the boxes.
            let p = q.center();
            let dist =
                |b: &Box3| (0..3).fold(0.0f64, |d, k| d.max(b.lo[k] - p[k]).max(p[k] - b.hi[k]));
            let scan = boxes.iter().map(dist).fold(f64::INFINITY, f64::min);
            let fast = tree.least(f64::INFINITY, dist, |i, _| dist(&boxes[i as usize]));
            assert_eq!(fast, scan);
        }
        assert!(!BoxTree::new(&[]).any_meeting(&[], &boxes[0], |_| true));
    }
}
