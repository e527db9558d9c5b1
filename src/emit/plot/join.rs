//! Joining polylines end to end so that a plotter lifts its pen as rarely as possible.
//!
//! First at exactly equal end points: the polylines are the edges of a graph on their end
//! points, and an Euler-trail cover of each connected part draws it with the fewest strokes
//! there can be — one for a part whose points all have even degree, half the number of
//! odd-degree points otherwise (Hierholzer's algorithm after pairing the odd points through
//! one virtual point). Then within a tolerance: stroke ends closer than it are joined, closest
//! pairs first, the gap drawn as a straight piece. Deterministic: everything is taken in input
//! order, ties broken by index. A gap is bridged only where the caller allows it (no other
//! line runs along it: a line is drawn once).

use crate::count::Span;
use crate::geom::key_hash::{point_key as key, KeyMap};
use crate::geom::poly2::{dist, Pt2};

use super::lone::lone;

/// Joins polylines (each of two points or more) at exactly equal ends, then, when
/// `tolerance > 0`, at ends closer than `tolerance` where `bridge(p, q)` allows drawing the
/// gap from p to q.
///
/// The pairs tried go to `span`: its first half when the lines are joined at equal ends,
/// the rest as the near pairs are tried, in chunks (none: [`Span::NONE`]).
pub(crate) fn join(
    lines: Vec<Vec<Pt2>>,
    tolerance: f64,
    bridge: &mut dyn FnMut(Pt2, Pt2) -> bool,
    span: Span,
) -> Vec<Vec<Pt2>> {
    let lines: Vec<Vec<Pt2>> = lines.into_iter().filter(|l| l.len() >= 2).collect();
    let trails = euler_trails(lines);
    span.reach(0.5);
    let joined = if tolerance > 0.0 {
        join_near(trails, tolerance, bridge, span.span(0.5, 1.0))
    } else {
        trails
    };
    span.finish();
    joined
}

/// [`join`]'s strokes, in its order, where most lines meet no other: the lines with no other
/// line's end within `tolerance` of their ends ([`lone`]) are passed through as they are,
/// and only the others are joined, each line taking the place [`join`] gives it (the Euler
/// walk takes a line drawn alone when its first point's virtual edge comes, the near join at
/// its index), so the joins' bridges and the strokes' order are [`join`]'s.
pub(crate) fn join_sparse(
    lines: Vec<Vec<Pt2>>,
    tolerance: f64,
    bridge: &mut dyn FnMut(Pt2, Pt2) -> bool,
    span: Span,
) -> Vec<Vec<Pt2>> {
    let lines: Vec<Vec<Pt2>> = lines.into_iter().filter(|l| l.len() >= 2).collect();
    let alone = lone(&lines, tolerance);
    // The others, with their indices among all.
    let mut others: Vec<Vec<Pt2>> = Vec::new();
    let mut index: Vec<usize> = Vec::new();
    let mut lines: Vec<Option<Vec<Pt2>>> = lines
        .into_iter()
        .zip(&alone)
        .enumerate()
        .map(|(i, (l, &a))| {
            if a {
                return Some(l);
            }
            others.push(l);
            index.push(i);
            None
        })
        .collect();
    let walked = euler_walk(others);
    span.reach(0.5);
    // The trails in `join`'s order: those through the virtual point by their first points'
    // first slots (a line alone at its start, slot 2i), then the closed ones.
    let slot = |k: usize| {
        let s = walked.first_seen[k];
        2 * index[s / 2] + s % 2
    };
    let mut order: Vec<Trail> = Vec::with_capacity(lines.len());
    let mut k = 0;
    for (i, l) in lines.iter().enumerate() {
        if l.is_none() {
            continue;
        }
        while k < walked.through_virtual && slot(k) < 2 * i {
            order.push(Trail::Joined(k));
            k += 1;
        }
        order.push(Trail::Alone(i));
    }
    order.extend((k..walked.trails.len()).map(Trail::Joined));
    let mut trails: Vec<Option<Vec<Pt2>>> = walked.trails.into_iter().map(Some).collect();
    if tolerance <= 0.0 {
        let out = order
            .iter()
            .filter_map(|t| match *t {
                Trail::Alone(i) => lines[i].take(),
                Trail::Joined(k) => trails[k].take(),
            })
            .collect();
        span.finish();
        return out;
    }
    // Where each joined trail sits among all, then the near join of those alone.
    let mut place = vec![0; trails.len()];
    for (p, t) in order.iter().enumerate() {
        if let Trail::Joined(k) = *t {
            place[k] = p;
        }
    }
    let mut at = Vec::new();
    let joined = join_near_at(
        trails.iter_mut().filter_map(Option::take).collect(),
        tolerance,
        bridge,
        span.span(0.5, 1.0),
        &mut at,
    );
    let mut joined = joined.into_iter().zip(at).peekable();
    let mut out = Vec::with_capacity(order.len());
    for (p, t) in order.iter().enumerate() {
        while let Some((l, _)) = joined.next_if(|&(_, k)| place[k] < p) {
            out.push(l);
        }
        if let Trail::Alone(i) = *t {
            out.extend(lines[i].take());
        }
    }
    out.extend(joined.map(|(l, _)| l));
    span.finish();
    out
}

/// A trail of [`join_sparse`]: a line alone (its index) or one the Euler walk made (its
/// index among the walk's trails).
#[derive(Clone, Copy)]
enum Trail {
    Alone(usize),
    Joined(usize),
}

/// An edge of the end-point graph: a polyline, or a virtual edge to the pairing point.
#[derive(Clone, Copy)]
struct GraphEdge {
    ends: [usize; 2],
    line: Option<usize>,
}

/// The fewest trails that draw every polyline once, joined at exactly equal end points.
fn euler_trails(lines: Vec<Vec<Pt2>>) -> Vec<Vec<Pt2>> {
    euler_walk(lines).trails
}

/// [`euler_trails`]' trails, with where the first ones start.
struct Walked {
    /// The trails, in the order they are walked.
    trails: Vec<Vec<Pt2>>,
    /// How many of them the circuit through the virtual point gave (the first ones): those
    /// come in order of their first points' first appearance among the lines' ends.
    through_virtual: usize,
    /// For each of those, the end slot (2i start, 2i + 1 end of line i) where its first
    /// point first appears.
    first_seen: Vec<usize>,
}

/// The trails of [`euler_trails`], and where those through the virtual point start.
fn euler_walk(mut lines: Vec<Vec<Pt2>>) -> Walked {
    let mut ids: KeyMap<(u64, u64), usize> = KeyMap::default();
    // Each node's first end slot.
    let mut seen_at: Vec<usize> = Vec::new();
    let mut node = |p: Pt2, slot: usize| {
        let n = ids.len();
        let id = *ids.entry(key(p)).or_insert(n);
        if id == n {
            seen_at.push(slot);
        }
        id
    };
    let mut edges: Vec<GraphEdge> = lines
        .iter()
        .enumerate()
        .map(|(i, l)| GraphEdge {
            ends: [node(l[0], 2 * i), node(l[l.len() - 1], 2 * i + 1)],
            line: Some(i),
        })
        .collect();
    let nodes = ids.len();
    let virt = nodes;
    let mut degree = vec![0usize; nodes + 1];
    for e in &edges {
        degree[e.ends[0]] += 1;
        degree[e.ends[1]] += 1;
    }
    for (n, d) in degree.iter().enumerate().take(nodes) {
        if d % 2 == 1 {
            edges.push(GraphEdge {
                ends: [n, virt],
                line: None,
            });
        }
    }
    // Each node's edges in edge order, side by side (a counting sort: no list per node).
    let mut at = vec![0usize; nodes + 2];
    for e in &edges {
        at[e.ends[0] + 1] += 1;
        if e.ends[1] != e.ends[0] {
            at[e.ends[1] + 1] += 1;
        }
    }
    for v in 0..=nodes {
        at[v + 1] += at[v];
    }
    let mut fill = at.clone();
    let mut list = vec![0usize; at[nodes + 1]];
    for (k, e) in edges.iter().enumerate() {
        for (i, &v) in e.ends.iter().enumerate() {
            if i == 0 || v != e.ends[0] {
                list[fill[v]] = k;
                fill[v] += 1;
            }
        }
    }
    let adj = Adjacency { at, list };
    let mut used = vec![false; edges.len()];
    let mut next = vec![0usize; nodes + 1];
    let mut out = Vec::new();
    // Start at the virtual point first (its circuit covers every part with odd points), then
    // at each remaining polyline's first end in input order.
    let starts =
        std::iter::once(virt).chain(edges.iter().filter_map(|e| e.line.map(|_| e.ends[0])));
    let (mut stack, mut circuit) = (Vec::new(), Vec::new());
    let mut first_nodes = Vec::new();
    let mut through_virtual = 0;
    for start in starts {
        // Most starts are on lines drawn already: nothing to walk.
        if next[start] == adj.of(start).len() {
            continue;
        }
        hierholzer(
            start,
            &edges,
            &adj,
            (&mut used, &mut next),
            (&mut stack, &mut circuit),
        );
        split_at_virtual(&circuit, &edges, &mut lines, (&mut out, &mut first_nodes));
        if start == virt {
            through_virtual = out.len();
        }
    }
    let first_seen = first_nodes[..through_virtual]
        .iter()
        .map(|&v| seen_at[v])
        .collect();
    Walked {
        trails: out,
        through_virtual,
        first_seen,
    }
}

/// The edges at each node of the end-point graph, in edge order.
struct Adjacency {
    /// Node v's edges are `list[at[v]..at[v + 1]]`.
    at: Vec<usize>,
    list: Vec<usize>,
}

impl Adjacency {
    fn of(&self, v: usize) -> &[usize] {
        &self.list[self.at[v]..self.at[v + 1]]
    }
}

/// One Euler circuit from `start` over unused edges, into `circuit`: the edges in order, each
/// with the node it is entered from. `used` and `next` (each node's next edge to try) carry
/// over from circuit to circuit; `stack` is a buffer.
fn hierholzer(
    start: usize,
    edges: &[GraphEdge],
    adj: &Adjacency,
    (used, next): (&mut [bool], &mut [usize]),
    (stack, circuit): (&mut Vec<Step>, &mut Vec<(usize, usize)>),
) {
    stack.clear();
    stack.push((start, None));
    circuit.clear();
    while let Some(&(v, _)) = stack.last() {
        let mut advanced = false;
        let around = adj.of(v);
        while next[v] < around.len() {
            let k = around[next[v]];
            next[v] += 1;
            if used[k] {
                continue;
            }
            used[k] = true;
            let e = edges[k];
            let w = if e.ends[0] == v { e.ends[1] } else { e.ends[0] };
            stack.push((w, Some((k, v))));
            advanced = true;
            break;
        }
        if !advanced {
            if let Some((_, Some(step))) = stack.pop() {
                circuit.push(step);
            }
        }
    }
    circuit.reverse();
}

/// A node on the walk, with the edge it was reached by and the node before.
type Step = (usize, Option<(usize, usize)>);

/// Cuts a circuit at its virtual edges into polylines of the real ones, onto `out`, and the
/// node each starts at onto `first`; each line is taken from `lines` (a line drawn alone is
/// moved, turned where walked backwards).
fn split_at_virtual(
    circuit: &[(usize, usize)],
    edges: &[GraphEdge],
    lines: &mut [Vec<Pt2>],
    (out, first): (&mut Vec<Vec<Pt2>>, &mut Vec<usize>),
) {
    // A circuit through the virtual point starts right after a virtual edge once rotated.
    let first_virtual = circuit.iter().position(|&(k, _)| edges[k].line.is_none());
    let rot = first_virtual.map_or(0, |i| i + 1);
    let at = |idx: usize| circuit[(idx + rot) % circuit.len()];
    // The run of real edges from `from`, cut where a virtual edge comes.
    let mut from = 0;
    for idx in 0..=circuit.len() {
        let cut = idx == circuit.len() || edges[at(idx).0].line.is_none();
        if !cut {
            continue;
        }
        if idx > from {
            let trail = trail((from..idx).map(at), edges, lines);
            if trail.len() > 1 {
                out.push(trail);
                first.push(at(from).1);
            }
        }
        from = idx + 1;
    }
}

/// The polyline of a run of real edges (each with the node it is entered from), taken from
/// `lines`: one line is moved, several are joined end to end.
fn trail(
    mut run: impl ExactSizeIterator<Item = (usize, usize)>,
    edges: &[GraphEdge],
    lines: &mut [Vec<Pt2>],
) -> Vec<Pt2> {
    let line = |k: usize| edges[k].line.unwrap_or(usize::MAX);
    if run.len() == 1 {
        let (k, from) = run.next().unwrap_or((0, 0));
        let mut l = std::mem::take(&mut lines[line(k)]);
        if edges[k].ends[0] != from {
            l.reverse();
        }
        return l;
    }
    let mut cur: Vec<Pt2> = Vec::new();
    for (k, from) in run {
        let l = &lines[line(k)];
        // The line's points in the direction walked, its first one only to start.
        let skip = usize::from(!cur.is_empty());
        if edges[k].ends[0] == from {
            cur.extend(l.iter().skip(skip));
        } else {
            cur.extend(l.iter().rev().skip(skip));
        }
    }
    cur
}

/// Joins stroke ends closer than `tol` where `bridge` allows, closest pairs first; a stroke
/// is never joined to itself. Fills `span` as the pairs are tried.
fn join_near(
    lines: Vec<Vec<Pt2>>,
    tol: f64,
    bridge: &mut dyn FnMut(Pt2, Pt2) -> bool,
    span: Span,
) -> Vec<Vec<Pt2>> {
    join_near_at(lines, tol, bridge, span, &mut Vec::new())
}

/// [`join_near`], with the index of the line each stroke is made at (the first line of its
/// chain met in input order) pushed onto `at`, stroke by stroke.
fn join_near_at(
    mut lines: Vec<Vec<Pt2>>,
    tol: f64,
    bridge: &mut dyn FnMut(Pt2, Pt2) -> bool,
    span: Span,
    at: &mut Vec<usize>,
) -> Vec<Vec<Pt2>> {
    let n = lines.len();
    // End slot 2i is line i's start, 2i + 1 its end.
    let end = |s: usize| {
        let l = &lines[s / 2];
        if s.is_multiple_of(2) {
            l[0]
        } else {
            l[l.len() - 1]
        }
    };
    let cell = |p: Pt2| ((p[0] / tol).floor() as i64, (p[1] / tol).floor() as i64);
    // Every end slot with its cell of side `tol`, sorted: a cell's slots side by side in slot
    // order, each cell's range in a map (no list per cell).
    let mut in_cells: Vec<((i64, i64), usize)> = (0..2 * n).map(|s| (cell(end(s)), s)).collect();
    in_cells.sort_unstable();
    let mut grid: KeyMap<(i64, i64), (usize, usize)> = KeyMap::default();
    for (k, &(c, _)) in in_cells.iter().enumerate() {
        grid.entry(c).or_insert((k, k)).1 = k + 1;
    }
    let mut pairs: Vec<(f64, usize, usize)> = Vec::new();
    for s in 0..2 * n {
        let p = end(s);
        let (cx, cy) = cell(p);
        for dy in -1..=1 {
            for dx in -1..=1 {
                let Some(&(lo, hi)) = grid.get(&(cx + dx, cy + dy)) else {
                    continue;
                };
                for &(_, t) in &in_cells[lo..hi] {
                    let q = end(t);
                    let d = dist(p, q);
                    if t > s && t / 2 != s / 2 && d <= tol {
                        pairs.push((d, s, t));
                    }
                }
            }
        }
    }
    pairs.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)).then(a.2.cmp(&b.2)));
    // link[s]: the end slot s is joined to. Joining must not close a cycle of strokes.
    let mut link = vec![usize::MAX; 2 * n];
    let mut group: Vec<usize> = (0..n).collect();
    fn find(g: &mut [usize], mut i: usize) -> usize {
        while g[i] != i {
            g[i] = g[g[i]];
            i = g[i];
        }
        i
    }
    let tried = span.steps(pairs.len());
    for (k, (_, s, t)) in pairs.into_iter().enumerate() {
        tried.tick(k);
        if link[s] != usize::MAX || link[t] != usize::MAX {
            continue;
        }
        let (gs, gt) = (find(&mut group, s / 2), find(&mut group, t / 2));
        if gs == gt {
            continue;
        }
        let (p, q) = (end(s), end(t));
        if p != q && !bridge(p, q) {
            continue;
        }
        group[gs] = gt;
        link[s] = t;
        link[t] = s;
    }
    // Walk each chain from a line whose start or end is free, in input order.
    let mut done = vec![false; n];
    let mut out = Vec::new();
    for i in 0..n {
        if done[i] {
            continue;
        }
        let free_start = link[2 * i] == usize::MAX;
        let free_end = link[2 * i + 1] == usize::MAX;
        if !free_start && !free_end {
            continue; // inside a chain: reached from one of its ends
        }
        if free_start && free_end {
            // Joined to nothing (most dashes): the line itself.
            done[i] = true;
            out.push(std::mem::take(&mut lines[i]));
            at.push(i);
            continue;
        }
        // Enter line i at its free end.
        let mut slot = if free_start { 2 * i } else { 2 * i + 1 };
        let mut chain: Vec<Pt2> = Vec::new();
        loop {
            let li = slot / 2;
            done[li] = true;
            let l = &lines[li];
            // Its points in the direction walked, the first one only where the chain does
            // not end there already.
            let forward = slot % 2 == 0;
            let first = if forward { l[0] } else { l[l.len() - 1] };
            let skip = usize::from(chain.last() == Some(&first));
            if forward {
                chain.extend(l.iter().skip(skip));
            } else {
                chain.extend(l.iter().rev().skip(skip));
            }
            let exit = slot ^ 1;
            match link[exit] {
                usize::MAX => break,
                t => slot = t,
            }
        }
        out.push(chain);
        at.push(i);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::poly2::polyline_length;
    use std::collections::HashMap;

    #[test]
    fn a_sparse_join_gives_the_join_s_strokes_in_its_order() {
        // Dashed random polylines, some meeting at shared ends (closed ones too), some ends
        // within the tolerance of others: the same strokes, in the same order, with the
        // same bridges asked for in the same order, with and without a tolerance.
        let mut rng = crate::geom::rng::XorShift::new(9);
        let corners: Vec<Pt2> = (0..60)
            .map(|_| [rng.range(0.0, 40.0), rng.range(0.0, 40.0)])
            .collect();
        let mut paths: Vec<Vec<Pt2>> = (0..150)
            .map(|_| {
                let a = corners[rng.below(corners.len())];
                let b = corners[rng.below(corners.len())];
                let m = [
                    (a[0] + b[0]) / 2.0 + rng.range(-2.0, 2.0),
                    (a[1] + b[1]) / 2.0,
                ];
                vec![a, m, b]
            })
            .collect();
        // A closed one, and a short one whose ends lie near another's.
        paths.push(vec![[50.0, 50.0], [53.0, 50.0], [53.0, 53.0], [50.0, 50.0]]);
        paths.push(vec![[60.0, 60.0], [61.0, 60.0]]);
        paths.push(vec![[61.03, 60.0], [64.0, 61.0]]);
        let dashed: Vec<Vec<Pt2>> = paths
            .iter()
            .filter(|p| p[0] != p[p.len() - 1] || p.len() > 2)
            .flat_map(|p| super::super::dash::dashes(p, 2.0, 1.0))
            .collect();
        for tol in [0.0, 0.05, 0.5] {
            let mut asked = (Vec::new(), Vec::new());
            let allow = |log: &mut Vec<(Pt2, Pt2)>, p: Pt2, q: Pt2| {
                log.push((p, q));
                !(p[0] + q[1]).to_bits().is_multiple_of(3)
            };
            let want = join(
                dashed.clone(),
                tol,
                &mut |p, q| allow(&mut asked.0, p, q),
                Span::NONE,
            );
            let got = join_sparse(
                dashed.clone(),
                tol,
                &mut |p, q| allow(&mut asked.1, p, q),
                Span::NONE,
            );
            assert_eq!(got, want, "tolerance {tol}");
            assert_eq!(asked.0, asked.1, "tolerance {tol}");
            assert!(want.len() < dashed.len(), "some joined at {tol}");
        }
    }

    #[test]
    fn a_counted_join_fills_its_share_and_joins_the_same() {
        use crate::count::Share;
        use crate::progress::{Phase, Progress, Stage};
        // A row of unit pieces with small gaps: joined within the tolerance.
        let lines: Vec<Vec<Pt2>> = (0..2500)
            .map(|k| {
                let x = 1.01 * f64::from(k);
                vec![[x, 0.0], [x + 1.0, 0.0]]
            })
            .collect();
        let p = Progress::new();
        p.enter_phase(Stage::Emit, Phase::Join, lines.len());
        let span = Share::new(p.count(), lines.len());
        let counted = join(lines.clone(), 0.05, &mut |_, _| true, span.span(0.0, 1.0));
        assert_eq!(p.counts(), (2500, 2500));
        assert_eq!(counted, join(lines, 0.05, &mut |_, _| true, Span::NONE));
        assert_eq!(counted.len(), 1);
    }

    fn odd_points(lines: &[Vec<Pt2>]) -> usize {
        let mut deg: HashMap<(u64, u64), usize> = HashMap::new();
        for l in lines {
            *deg.entry(key(l[0])).or_default() += 1;
            *deg.entry(key(l[l.len() - 1])).or_default() += 1;
        }
        deg.values().filter(|d| *d % 2 == 1).count()
    }

    fn length(lines: &[Vec<Pt2>]) -> f64 {
        lines.iter().map(|l| polyline_length(l)).sum()
    }

    #[test]
    fn a_square_with_a_tail_is_one_stroke() {
        // Square loop plus a tail from a corner: two odd points, so one trail.
        let s = vec![
            vec![[0., 0.], [1., 0.]],
            vec![[1., 0.], [1., 1.]],
            vec![[1., 1.], [0., 1.]],
            vec![[0., 1.], [0., 0.]],
            vec![[1., 1.], [2., 2.]],
        ];
        let j = join(s.clone(), 0.0, &mut |_, _| true, Span::NONE);
        assert_eq!(j.len(), 1, "{j:?}");
        assert_eq!(j[0].len(), 6);
        assert_eq!(length(&j), length(&s));
    }

    #[test]
    fn a_star_needs_half_its_odd_points() {
        // Six spokes from the centre: seven points, six of degree 1 and the centre of degree 6.
        let s: Vec<Vec<Pt2>> = (0..6)
            .map(|k| {
                let a = k as f64;
                vec![[0., 0.], [a.cos(), a.sin()]]
            })
            .collect();
        let j = join(s.clone(), 0.0, &mut |_, _| true, Span::NONE);
        assert_eq!(j.len(), odd_points(&s) / 2);
        assert_eq!(length(&j), length(&s));
        // Every spoke appears once (as a run of consecutive points).
        let segs: usize = j.iter().map(|l| l.len() - 1).sum();
        assert_eq!(segs, 6);
    }

    #[test]
    fn random_graphs_reach_the_lower_bound() {
        let mut rng = crate::geom::rng::XorShift::new(0x1234_5678_9ABC_DEF1);
        let mut rnd = |n: u64| rng.next_u64() % n;
        for _ in 0..50 {
            let lines: Vec<Vec<Pt2>> = (0..40)
                .map(|_| {
                    let (a, b) = (rnd(12), rnd(12));
                    vec![
                        [a as f64, (a * a) as f64],
                        [0.5, 0.5 + rnd(3) as f64],
                        [b as f64, (b * b) as f64],
                    ]
                })
                .collect();
            let j = join(lines.clone(), 0.0, &mut |_, _| true, Span::NONE);
            // Lower bound per connected part: max(1, odd / 2); over the whole graph the sum.
            let mut parent: HashMap<(u64, u64), (u64, u64)> = HashMap::new();
            fn root(p: &mut HashMap<(u64, u64), (u64, u64)>, k: (u64, u64)) -> (u64, u64) {
                let mut r = k;
                while let Some(&q) = p.get(&r) {
                    if q == r {
                        break;
                    }
                    r = q;
                }
                r
            }
            for l in &lines {
                let (a, b) = (key(l[0]), key(l[l.len() - 1]));
                parent.entry(a).or_insert(a);
                parent.entry(b).or_insert(b);
                let (ra, rb) = (root(&mut parent, a), root(&mut parent, b));
                parent.insert(ra, rb);
            }
            let mut parts: HashMap<(u64, u64), usize> = HashMap::new();
            let mut deg: HashMap<(u64, u64), usize> = HashMap::new();
            for l in &lines {
                *deg.entry(key(l[0])).or_default() += 1;
                *deg.entry(key(l[l.len() - 1])).or_default() += 1;
            }
            let keys: Vec<_> = parent.keys().copied().collect();
            for k in keys {
                let r = root(&mut parent, k);
                *parts.entry(r).or_default() += deg[&k] % 2;
            }
            let bound: usize = parts.values().map(|&odd| (odd / 2).max(1)).sum();
            assert_eq!(j.len(), bound);
            assert!((length(&j) - length(&lines)).abs() < 1e-9 * length(&lines));
        }
    }

    #[test]
    fn near_ends_join_closest_first_and_never_into_a_loop() {
        // Four sides of a unit square, each end a hair from the next side's start: within
        // 0.01 they join into one stroke (three joins; the fourth would close a loop).
        let s = vec![
            vec![[0., 0.], [1., 0.]],
            vec![[1.0 + 1e-3, 0.], [1., 1.]],
            vec![[1., 1.0 + 1e-4], [0., 1.]],
            vec![[0., 1.], [0., 2e-4]],
        ];
        let j = join(s.clone(), 0.01, &mut |_, _| true, Span::NONE);
        assert_eq!(j.len(), 1, "{j:?}");
        // The gaps are drawn: all four sides plus two of the three gaps, and the side that
        // meets its neighbour exactly (2 -> 3) joins without a gap.
        assert_eq!(j[0].len(), 4 + 2 + 1);
        assert_eq!(join(s.clone(), 0.0, &mut |_, _| true, Span::NONE).len(), 3);
        assert_eq!(join(s.clone(), 1e-5, &mut |_, _| true, Span::NONE).len(), 3);
        // Gaps the caller forbids stay open: both ends of the stroke of sides 3 and 4.
        let mut asked = 0;
        let j = join(
            s,
            0.01,
            &mut |p, q| {
                asked += 1;
                ![[1., 1.0 + 1e-4], [0., 2e-4]]
                    .iter()
                    .any(|x| [p, q].contains(x))
            },
            Span::NONE,
        );
        assert_eq!(j.len(), 2, "{j:?}");
        assert!(asked >= 2);
    }
}
