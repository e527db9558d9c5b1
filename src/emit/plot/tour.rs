//! The order a plotter draws a layer's strokes in: as little pen-up travel as we can find.
//!
//! Travel is the sum of distances from each stroke's end to the next stroke's start (as
//! vpype's `stat` counts it); a stroke may be drawn either way. The order starts greedy
//! (nearest next end, from the stroke nearest the page's top-left corner), then local search
//! improves it until no move gains: 2-opt (reverse a run of strokes) and Or-opt (move a run
//! of up to three strokes elsewhere, either way round). Candidates come from each end's
//! nearest neighbours, nearest first, and stop at the first neighbour no nearer than what the
//! move takes away at that end (the usual gain criterion: a 2-opt move that gains has an end
//! whose new edge is shorter than the old one there, and it is found from that end; for
//! Or-opt the bound is the run's removal gain, a heuristic). Then iterated local search: small
//! double-bridge kicks, each followed by local search (its reversals bounded) and kept only
//! when the travel falls, until a fixed number of them or a run of kicks that gain nothing.
//! The open path is closed into a cycle through a depot at distance 0 from everything, so a
//! reversal can always take the shorter side. Deterministic: fixed neighbour lists, a FIFO
//! work queue, ties to the lower index, a seeded generator for the kicks, and fixed budgets
//! of moves and kicks; the kicks are tried on copies of the tour side by side, one a
//! thread, with the tour one copy would find ([`lanes`]). Counting the work done for a
//! progress bar (`plan`) reads nothing the search decides by.

use crate::count::{Span, Steps};
use crate::geom::grid::{per_side, Cells};
use crate::geom::poly2::{dist, Pt2};

use crate::geom::rng::XorShift;
use rayon::prelude::*;

use super::chain::greedy;
use super::pairs::chains;

mod lanes;

use self::lanes::lanes;

/// Nearest neighbours kept per stroke end.
const NEIGHBOURS: usize = 16;

/// Longest run of strokes an Or-opt move carries.
const OR_RUN: usize = 3;

/// Moves allowed per stroke (a bound on the work, never reached in practice).
const MOVES_PER_STROKE: usize = 64;

/// How hard [`plan_steps`] searches a layer.
#[derive(Clone, Copy)]
struct Effort {
    /// Nearest neighbours kept per stroke end (at most [`NEIGHBOURS`]).
    neighbours: usize,
    /// Kicks of the iterated local search per stroke, over at most `kicked_strokes`.
    kicks_per_stroke: usize,
    /// Strokes counted for the number of kicks (a bound on the work for huge layers).
    kicked_strokes: usize,
}

impl Effort {
    /// The kicks of a layer of `strokes` strokes.
    fn kicks(&self, strokes: usize) -> usize {
        self.kicks_per_stroke * strokes.min(self.kicked_strokes)
    }
}

/// The search of a layer with other strokes than hidden dashes.
const FULL: Effort = Effort {
    neighbours: NEIGHBOURS,
    kicks_per_stroke: KICKS_PER_STROKE,
    kicked_strokes: MAX_KICKED_STROKES,
};

/// The search of a layer of hidden dashes only, planned by chains ([`super::pairs`]): ten
/// neighbours, not sixteen, and kicks over at most [`DASH_KICKED_STROKES`] chains, one a
/// chain in a layer of at most [`MANY_DASHES`] dashes.
const DASHES: Effort = Effort {
    neighbours: DASH_NEIGHBOURS,
    kicks_per_stroke: 1,
    kicked_strokes: DASH_KICKED_STROKES,
};

/// [`DASHES`] with [`DASH_KICKS_PER_STROKE`] kicks a chain: a layer of more than
/// [`MANY_DASHES`] dashes.
const MANY_DASHES_EFFORT: Effort = Effort {
    kicks_per_stroke: DASH_KICKS_PER_STROKE,
    ..DASHES
};

/// Dashes in a layer above which its search gets [`DASH_KICKS_PER_STROKE`] kicks a chain,
/// not one. In smaller layers the first local search leaves the kicks little to find: the
/// shared meshes' layers of up to 1,774 dashes (cube, twocubes, suzanne) were −31% to +1.0%
/// against the base with one kick a chain, and four cost twocubes' whole render
/// 60% more CPU, which made it slower than ln's.
const MANY_DASHES: usize = 2000;

/// Nearest neighbours kept per end in a layer of hidden dashes: their nearest ends are
/// mostly dashes of the same or the next line, and ten found tours at most 2.0% longer than
/// sixteen's on the shared meshes' hidden layers (cow; beetle's 3.7% shorter), for 4% less
/// CPU in rocker-arm's whole render. Eight left twocubes' 3.9% longer.
const DASH_NEIGHBOURS: usize = 10;

/// Chains counted for the kicks in a layer of hidden dashes: 1,000 kicks at most with
/// [`DASH_KICKS_PER_STROKE`]. Chosen when a chain had one kick: 250
/// kicks with [`DASH_NEIGHBOURS`] left the shared meshes' hidden layers at most 2.7% longer
/// than 500 kicks with sixteen neighbours (cow), for 10% less CPU in rocker-arm's whole
/// render.
const DASH_KICKED_STROKES: usize = 250;

/// Kicks of the iterated local search per stroke, over at most [`MAX_KICKED_STROKES`].
const KICKS_PER_STROKE: usize = 4;

/// Kicks per stroke (per chain of dashes, [`super::pairs`]) in a layer of more than
/// [`MANY_DASHES`] hidden dashes, over at most [`DASH_KICKED_STROKES`] chains. One kick a
/// chain (docs/history/issue35-hidden2.md, each step checked against the step before) left
/// beetle's hidden layer 7.8% and cow's 5.4% longer than at the base (0030072), over
/// issue 35's bound of 5%; with four, all 15 shared meshes' layers are within it (beetle
/// +4.1%, cow +3.3%), for more emit time (docs/history/issue35-session15.md).
const DASH_KICKS_PER_STROKE: usize = 4;

/// Longest run of positions a move of the kicks' local search may reverse: a kick is local
/// (runs of at most [`KICK_RUN`]), and so is its repair. Unbounded, a move after a kick on a
/// layer of 30,000 dashes reversed thousands of positions, and twice when the kick was
/// undone; bounded, the kicks take a fifth of the time for at most 1.3% more travel on the
/// shared meshes' hidden layers, and layers under 2,000 strokes never reach the bound (the
/// first local search stays unbounded: it mends the greedy order's long jumps).
const KICK_REVERSAL: usize = 1000;

/// Kicks in a row that did not shorten the tour after which the kicks stop: a small layer
/// (the cube's 295 hidden dashes) had 1,180 kicks, most of them after the last that gained.
/// On the shared meshes' layers the tours it stops early are at most 2.8% longer (one
/// layer, of 499 strokes), most of them no longer; big layers gain often enough not to stop.
const KICK_STALL: usize = 300;

/// Strokes counted for the number of kicks (a bound on the work for huge layers).
const MAX_KICKED_STROKES: usize = 500;

/// Longest run a kick moves.
const KICK_RUN: usize = 30;

/// Kicks between two adds to a progress count (a kick with its local search is long).
const KICK_CHUNK: usize = 16;

/// How far into [`plan_tied`]'s span the greedy order ends. This and the two below are
/// estimates, the passes' shares of the planning time on the dashed hidden layers of ogre,
/// bunny and nefertiti; the kicks fill the rest.
const SPAN_GREEDY: f64 = 0.05;

/// How far into [`plan_tied`]'s span the neighbour lists end.
const SPAN_NEIGHBOURS: f64 = 0.5;

/// How far into [`plan_tied`]'s span the first local search ends.
const SPAN_SEARCH: f64 = 0.7;

/// Pen-up travel of strokes drawn in order: Σ |end(i) − start(i+1)| (0 for one stroke or
/// none: a fold from +0, where `sum` of no floats gives −0 and `kepler render --stats`
/// printed "travel -0.0 mm").
pub(crate) fn travel<L: AsRef<[Pt2]>>(lines: &[L]) -> f64 {
    lines
        .windows(2)
        .map(|w| {
            let (a, b) = (w[0].as_ref(), w[1].as_ref());
            dist(a[a.len() - 1], b[0])
        })
        .fold(0.0, |s, d| s + d)
}

/// The drawing order of strokes given by their (start, end) points: (stroke, reversed).
///
/// The work goes to `span` as it is done: by the passes' estimated shares
/// ([`SPAN_NEIGHBOURS`] and the others), and within them by the end slots searched, the
/// strokes the first local search starts from and the kicks made, in chunks (none:
/// [`Span::NONE`]). Nothing is tied (the tests' plan; pictures call [`plan_tied`]).
#[cfg(test)]
pub(crate) fn plan(ends: &[[Pt2; 2]], span: Span) -> Vec<(usize, bool)> {
    plan_tied(ends, &vec![false; ends.len()], span)
}

/// The drawing order of strokes given by their (start, end) points: (stroke, reversed).
/// Strokes that are `tieable` and whose ends are clearly each other's nearest are drawn in a
/// row ([`super::pairs`]): the search plans the chains they make, with fewer kicks when every
/// stroke is tieable (a layer of hidden dashes). The work goes to `span` as `plan` says.
pub(crate) fn plan_tied(ends: &[[Pt2; 2]], tieable: &[bool], span: Span) -> Vec<(usize, bool)> {
    let chains = chains(ends, tieable);
    // A layer of dashes only: fewer neighbours and kicks a stroke.
    let dashes = !tieable.is_empty() && !tieable.contains(&false);
    let effort = if !dashes {
        FULL
    } else if ends.len() > MANY_DASHES {
        MANY_DASHES_EFFORT
    } else {
        DASHES
    };
    let order = if chains.len() == ends.len() {
        plan_steps(ends, effort, span)
    } else {
        chains.expand(&plan_steps(&chains.ends(ends), effort, span))
    };
    span.finish();
    order
}

/// The passes of [`plan_tied`], searching as hard as `effort` says.
fn plan_steps(ends: &[[Pt2; 2]], effort: Effort, span: Span) -> Vec<(usize, bool)> {
    let n = ends.len();
    if n < 3 || 2 * n > u32::MAX as usize {
        // Two slots a stroke must fit a `u32` ([`Near`]); no layer comes near.
        return greedy(ends, 0);
    }
    let home = [0.0, 0.0];
    let first = (0..n)
        .min_by(|&i, &j| {
            let d = |k: usize| dist(ends[k][0], home).min(dist(ends[k][1], home));
            d(i).total_cmp(&d(j)).then(i.cmp(&j))
        })
        .unwrap_or(0);
    // The greedy order and the neighbour lists side by side (neither reads the other).
    let (start, near) = rayon::join(
        || greedy(ends, first),
        || {
            neighbours(
                ends,
                effort.neighbours,
                span.span(SPAN_GREEDY, SPAN_NEIGHBOURS),
            )
        },
    );
    span.reach(SPAN_GREEDY);
    let mut t = Tour::new(ends, &start, &near);
    t.improve(effort, span.span(SPAN_NEIGHBOURS, 1.0));
    t.order()
}

/// Where a node is in the tour.
#[derive(Clone, Copy)]
struct Place {
    /// Its position.
    pos: u32,
    /// Drawn end to start (along the array's forward direction).
    rev: bool,
}

/// Where a kick cuts a tour of `n` positions: after position `p`, the runs of `l1` and `l2`
/// positions that follow swapped (a local double bridge).
#[derive(Clone, Copy)]
struct Bridge {
    p: usize,
    l1: usize,
    l2: usize,
}

impl Bridge {
    /// The next kick of a tour of `n` positions (at least 4) from `rng`: runs of 1 to
    /// [`KICK_RUN`] positions. The kicks depend on nothing but `n` and the generator, so a
    /// layer's are drawn before any is made.
    fn draw(rng: &mut XorShift, n: usize) -> Bridge {
        let most = KICK_RUN.min((n - 2) / 2).max(1);
        let p = rng.below(n);
        let (l1, l2) = (1 + rng.below(most), 1 + rng.below(most));
        Bridge { p, l1, l2 }
    }
}

/// What a kick with its local search did: how much longer the kick made the travel, what
/// the search gained back, and the moves it spent.
struct Trial {
    worse: f64,
    gain: f64,
    moves: usize,
}

/// A cyclic tour: the strokes and the depot (index n), each stroke with its direction.
struct Tour<'a> {
    ends: &'a [[Pt2; 2]],
    /// Node at each position (n is the depot).
    seq: Vec<usize>,
    /// Each node's position and direction, side by side: a reversal updates both.
    place: Vec<Place>,
    /// For each end slot (2i start, 2i + 1 end of stroke i): nearest other strokes' slots.
    near: &'a Near,
    /// Least gain a move must bring (a rounding guard).
    eps: f64,
    /// Reversals made, when they are to be undone.
    log: Option<Vec<(usize, usize)>>,
    /// The reversal log's buffer between kicks.
    spare: Vec<(usize, usize)>,
    /// Strokes in the local search's work queue (all false between searches).
    queued: Vec<bool>,
    /// The local search's work queue, kept for its buffer.
    queue: std::collections::VecDeque<usize>,
    /// Longest run of positions a move may reverse.
    longest: usize,
}

impl<'a> Tour<'a> {
    /// The tour of strokes `ends` in `order`, with their neighbour lists `near`.
    fn new(ends: &'a [[Pt2; 2]], order: &[(usize, bool)], near: &'a Near) -> Tour<'a> {
        let n = ends.len();
        let mut seq: Vec<usize> = order.iter().map(|o| o.0).collect();
        seq.push(n);
        let mut place = vec![Place { pos: 0, rev: false }; n + 1];
        for (k, &v) in seq.iter().enumerate() {
            place[v].pos = k as u32;
        }
        for &(i, r) in order {
            place[i].rev = r;
        }
        let b = crate::geom::Rect::of_points(ends.iter().flatten());
        Tour {
            ends,
            seq,
            place,
            near,
            eps: 1e-12 * b.longer_side().max(f64::MIN_POSITIVE),
            log: None,
            spare: Vec::new(),
            queued: vec![false; n],
            queue: std::collections::VecDeque::new(),
            longest: usize::MAX,
        }
    }

    fn len(&self) -> usize {
        self.seq.len()
    }

    /// Position of node v.
    fn pos(&self, v: usize) -> usize {
        self.place[v].pos as usize
    }

    /// Whether stroke v is drawn end to start (along the array's forward direction).
    fn rev(&self, v: usize) -> bool {
        self.place[v].rev
    }

    fn at(&self, k: isize) -> usize {
        let n = self.len() as isize;
        // Callers step at most a lap either way: a wrap without a division.
        let k = match k {
            k if (0..n).contains(&k) => k,
            k if (-n..0).contains(&k) => k + n,
            k if (n..2 * n).contains(&k) => k - n,
            k => k.rem_euclid(n),
        };
        self.seq[k as usize]
    }

    /// Entry point of node v in the forward direction (None for the depot).
    fn start(&self, v: usize) -> Option<Pt2> {
        (v < self.ends.len()).then(|| self.ends[v][usize::from(self.rev(v))])
    }

    /// The point of end slot s (2i start, 2i + 1 end of stroke i).
    fn slot(&self, s: usize) -> Pt2 {
        self.ends[s / 2][s % 2]
    }

    /// Exit point of node v in the forward direction (None for the depot).
    fn end(&self, v: usize) -> Option<Pt2> {
        (v < self.ends.len()).then(|| self.ends[v][usize::from(!self.rev(v))])
    }

    fn d(p: Option<Pt2>, q: Option<Pt2>) -> f64 {
        match (p, q) {
            (Some(p), Some(q)) => dist(p, q),
            _ => 0.0,
        }
    }

    /// Reverses the cyclic run of positions from `i` forward to `j` (inclusive), flipping the
    /// strokes in it.
    fn reverse(&mut self, i: usize, j: usize) {
        if let Some(log) = &mut self.log {
            log.push((i, j));
        }
        let n = self.len();
        let len = (j + n - i) % n + 1;
        let (mut a, mut b) = (i, j);
        // One pass: each swapped pair takes its new positions, and every stroke in the run
        // turns round (the middle one of an odd run stays where it is).
        for _ in 0..len / 2 {
            self.seq.swap(a, b);
            for (k, v) in [(a, self.seq[a]), (b, self.seq[b])] {
                let at = &mut self.place[v];
                at.pos = k as u32;
                at.rev = !at.rev;
            }
            a = if a + 1 == n { 0 } else { a + 1 };
            b = if b == 0 { n - 1 } else { b - 1 };
        }
        if len % 2 == 1 {
            let at = &mut self.place[self.seq[a]];
            at.rev = !at.rev;
        }
    }

    /// Reverses the run between positions i + 1 and j, or equivalently the rest of the cycle,
    /// whichever is shorter.
    fn two_opt_move(&mut self, i: usize, j: usize) {
        let n = self.len();
        let inner = (j + n - i) % n;
        if inner <= n - inner {
            self.reverse((i + 1) % n, j);
        } else {
            self.reverse((j + 1) % n, i);
        }
    }

    /// Gain of replacing edges (i, i+1) and (j, j+1) by (i, j) and (i+1, j+1).
    fn two_opt_gain(&self, i: usize, j: usize) -> f64 {
        let (a, b) = (self.at(i as isize), self.at(i as isize + 1));
        let (c, d) = (self.at(j as isize), self.at(j as isize + 1));
        if i == j {
            return 0.0;
        }
        Self::d(self.end(a), self.start(b)) + Self::d(self.end(c), self.start(d))
            - Self::d(self.end(a), self.end(c))
            - Self::d(self.start(b), self.start(d))
    }

    /// The best 2-opt move with a new edge at stroke v: (gain, i, j).
    fn best_two_opt(&self, v: usize) -> Option<(f64, usize, usize)> {
        let n = self.len();
        let pv = self.pos(v);
        let mut best: Option<(f64, usize, usize)> = None;
        // Strictly better only: the first of equal gains wins. A move reverses the shorter
        // side of the cycle.
        let mut consider = |g: f64, i: usize, j: usize| {
            let inner = (j + n - i) % n;
            if inner.min(n - inner) > self.longest {
                return;
            }
            if g > self.eps && best.is_none_or(|(bg, _, _)| g > bg) {
                best = Some((g, i, j));
            }
        };
        // New edge end(v) – end(m): positions (pos v, pos m). Only new edges shorter than
        // the edge they replace at v (neighbours come nearest first).
        let (ev, sv) = (self.end(v), self.start(v));
        let out = Self::d(ev, self.start(self.at(pv as isize + 1)));
        for &q in self.near.of(2 * v + usize::from(!self.rev(v))) {
            let (q, m) = (q as usize, q as usize / 2);
            if Self::d(ev, Some(self.slot(q))) >= out {
                break;
            }
            if q % 2 == usize::from(!self.rev(m)) {
                consider(self.two_opt_gain(pv, self.pos(m)), pv, self.pos(m));
            }
        }
        // New edge start(v) – start(m): positions (pos v − 1, pos m − 1).
        let into = Self::d(self.end(self.at(pv as isize - 1)), sv);
        for &q in self.near.of(2 * v + usize::from(self.rev(v))) {
            let (q, m) = (q as usize, q as usize / 2);
            if Self::d(sv, Some(self.slot(q))) >= into {
                break;
            }
            if q % 2 == usize::from(self.rev(m)) {
                let (i, j) = ((pv + n - 1) % n, (self.pos(m) + n - 1) % n);
                consider(self.two_opt_gain(i, j), i, j);
            }
        }
        best
    }

    /// The best Or-opt move of a run starting at stroke v: (gain, run length, edge position p
    /// to insert after, reversed).
    fn best_or_opt(&self, v: usize) -> Option<(f64, usize, usize, bool)> {
        let n = self.len();
        let s0 = self.pos(v);
        let mut best: Option<(f64, usize, usize, bool)> = None;
        // The distances from v's outer end to its neighbours, the same for every run (each
        // run starts at v): taken once, as far as a run first reads them.
        let mut from_v = [f64::NAN; NEIGHBOURS];
        for run in 1..=OR_RUN.min(n.saturating_sub(3)) {
            let s1 = (s0 + run - 1) % n;
            let mut held = [usize::MAX; OR_RUN];
            for (k, h) in held.iter_mut().enumerate().take(run) {
                *h = self.seq[(s0 + k) % n];
            }
            let nodes = &held[..run];
            if nodes.contains(&(n - 1)) {
                break; // the depot never moves
            }
            let (first, last) = (nodes[0], nodes[run - 1]);
            let (prev, next) = (self.at(s0 as isize - 1), self.at(s1 as isize + 1));
            let removed = Self::d(self.end(prev), self.start(first))
                + Self::d(self.end(last), self.start(next))
                - Self::d(self.end(prev), self.start(next));
            if removed <= self.eps {
                continue;
            }
            let (sp, ep) = (self.start(first), self.end(last));
            // The run's two outer ends, each searched from its slot.
            let ends = [
                (2 * first + usize::from(self.rev(first)), sp),
                (2 * last + usize::from(!self.rev(last)), ep),
            ];
            for (e, (slot, at)) in ends.into_iter().enumerate() {
                for (i, &q) in self.near.of(slot).iter().enumerate() {
                    let m = q as usize / 2;
                    let d = if e == 0 && !from_v[i].is_nan() {
                        from_v[i]
                    } else {
                        Self::d(at, Some(self.slot(q as usize)))
                    };
                    if e == 0 {
                        from_v[i] = d;
                    }
                    if d >= removed {
                        break;
                    }
                    if nodes.contains(&m) {
                        continue;
                    }
                    let pm = self.pos(m);
                    for p in [(pm + n - 1) % n, pm] {
                        let (u, w) = (self.seq[p], self.at(p as isize + 1));
                        if nodes.contains(&u) || nodes.contains(&w) {
                            continue;
                        }
                        // The move reverses the shorter way round ([`Tour::or_opt_move`]).
                        let (ahead, behind) = ((p + n - s1) % n, (s0 + n - p - 1) % n);
                        if ahead.min(behind) > self.longest {
                            continue;
                        }
                        let base = Self::d(self.end(u), self.start(w));
                        let fwd = Self::d(self.end(u), sp) + Self::d(ep, self.start(w)) - base;
                        let bwd = Self::d(self.end(u), ep) + Self::d(sp, self.start(w)) - base;
                        for (cost, r) in [(fwd, false), (bwd, true)] {
                            let g = removed - cost;
                            if g > self.eps && best.is_none_or(|(bg, ..)| g > bg) {
                                best = Some((g, run, p, r));
                            }
                        }
                    }
                }
            }
        }
        best
    }

    /// Moves the run of `run` strokes at stroke v's position to just after position p,
    /// reversed when `r`, by reversals over the shorter way round.
    fn or_opt_move(&mut self, v: usize, run: usize, p: usize, r: bool) {
        let n = self.len();
        let s0 = self.pos(v);
        let s1 = (s0 + run - 1) % n;
        // Forward from the run to p: run, Y = (s1+1 ..= p). Rotating [run Y] to [Y run].
        let ahead = (p + n - s1) % n;
        // Backward: X = (p+1 ..= s0-1), rotating [X run] to [run X].
        let behind = (s0 + n - p - 1) % n;
        if ahead <= behind {
            self.reverse(s0, p);
            // Now Y reversed sits at s0 .., the run reversed at the end.
            let y_end = (s0 + ahead - 1) % n;
            if ahead > 0 {
                self.reverse(s0, y_end);
            }
            if !r {
                self.reverse((y_end + 1) % n, p);
            }
        } else {
            let x0 = (p + 1) % n;
            self.reverse(x0, s1);
            // Now the run reversed sits at x0 .., X reversed after it.
            let run_end = (x0 + run - 1) % n;
            if behind > 0 {
                self.reverse((run_end + 1) % n, s1);
            }
            if !r {
                self.reverse(x0, run_end);
            }
        }
    }

    /// Local search until no move gains, then kicks: a local double bridge (two neighbouring
    /// runs of strokes swapped) followed by local search around it, kept only when the whole
    /// brings the travel down, undone otherwise (iterated local search). Fills `span`: the
    /// first search its part up to [`SPAN_SEARCH`], the kicks the rest. The kicks are tried
    /// on as many tours at once as [`lanes`] gives, with the one-tour result
    /// ([`Tour::kicks_in_lanes`]).
    fn improve(&mut self, effort: Effort, span: Span) {
        let strokes = self.ends.len();
        let kicks = effort.kicks(strokes);
        let budget = MOVES_PER_STROKE * strokes;
        self.improve_in(effort, span, budget, lanes(self.len(), kicks));
    }

    /// [`Tour::improve`] within `budget` moves, its kicks tried `lanes` at a time (1: one
    /// after the other).
    fn improve_in(&mut self, effort: Effort, span: Span, mut budget: usize, lanes: usize) {
        let strokes = self.ends.len();
        let all: Vec<usize> = self.seq[..strokes].to_vec();
        let search = (SPAN_SEARCH - SPAN_NEIGHBOURS) / (1.0 - SPAN_NEIGHBOURS);
        let first = span.span(0.0, search).steps(strokes);
        self.local_search(&all, &mut budget, Some(&first));
        span.reach(search);
        if self.len() < 8 {
            return;
        }
        let mut rng = XorShift::new(0x5DEE_CE66_D1CE_5EED);
        let kicks = effort.kicks(strokes);
        let bridges: Vec<Bridge> = (0..kicks)
            .map(|_| Bridge::draw(&mut rng, self.len()))
            .collect();
        let kicked = span.span(search, 1.0).steps(kicks);
        self.longest = KICK_REVERSAL;
        if lanes < 2 {
            self.kicks(&bridges, (0, 0), &mut budget, &kicked);
        } else {
            self.kicks_in_lanes(&bridges, &mut budget, &kicked, lanes);
        }
        span.finish();
    }

    /// The kicks `bridges` from the `k`-th on, one after the other, each kept when it
    /// shortens the tour, until the move budget is spent or [`KICK_STALL`] kicks in a row
    /// gained nothing (`failed` of them before the `k`-th).
    fn kicks(
        &mut self,
        bridges: &[Bridge],
        (mut k, mut failed): (usize, usize),
        budget: &mut usize,
        kicked: &Steps,
    ) {
        while k < bridges.len() && *budget > 0 && failed < KICK_STALL {
            kicked.tick_in(k, KICK_CHUNK);
            let trial = self.try_kick(bridges[k], budget);
            let gains = self.gains(&trial);
            failed = if gains { 0 } else { failed + 1 };
            self.settle(gains, &[]);
            k += 1;
        }
    }

    /// A kick and the local search around it, its reversals logged: what it cost and gained,
    /// and the moves it made out of `budget`.
    fn try_kick(&mut self, bridge: Bridge, budget: &mut usize) -> Trial {
        let mut log = std::mem::take(&mut self.spare);
        log.clear();
        self.log = Some(log);
        let before = *budget;
        let (worse, touched) = self.kick(bridge);
        let gain = self.local_search(&touched, budget, None);
        Trial {
            worse,
            gain,
            moves: before - *budget,
        }
    }

    /// Whether a kick's trial shortened the tour.
    fn gains(&self, trial: &Trial) -> bool {
        trial.gain - trial.worse > self.eps
    }

    /// Ends a kick's trial, if one is under way, and brings the tour to the kept one: the
    /// trial kept as it is (`keep`), or undone and then `replay`'s reversals made.
    fn settle(&mut self, keep: bool, replay: &[(usize, usize)]) {
        let log = self.log.take();
        if !keep {
            for &(i, j) in log.iter().flatten().rev() {
                self.reverse(i, j);
            }
            for &(i, j) in replay {
                self.reverse(i, j);
            }
        }
        if let Some(log) = log {
            self.spare = log;
        }
    }

    /// Local search from the strokes in `queue` until no move gains (or the budget is
    /// spent): the total gain. Counts each stroke looked at in `counted`, when given (the
    /// first search: as many steps as strokes, though strokes a move touches come again).
    fn local_search(&mut self, from: &[usize], budget: &mut usize, counted: Option<&Steps>) -> f64 {
        let strokes = self.ends.len();
        let mut queued = std::mem::take(&mut self.queued);
        let mut queue = std::mem::take(&mut self.queue);
        queue.clear();
        for &v in from {
            if v < strokes && !std::mem::replace(&mut queued[v], true) {
                queue.push_back(v);
            }
        }
        let mut gained = 0.0;
        let mut looked = 0;
        while let Some(v) = queue.pop_front() {
            queued[v] = false;
            if let Some(steps) = counted {
                steps.tick(looked);
                looked += 1;
            }
            if *budget == 0 {
                break;
            }
            // The strokes at the edges a move changes, to look at again (a 2-opt move has
            // five: v is listed twice and queued once).
            let nodes: [usize; 6] = if let Some((g, i, j)) = self.best_two_opt(v) {
                let at = |k: usize| self.at(k as isize);
                let nodes = [at(i), at(i + 1), at(j), at(j + 1), v, v];
                self.two_opt_move(i, j);
                gained += g;
                nodes
            } else if let Some((g, run, p, r)) = self.best_or_opt(v) {
                let s0 = self.pos(v) as isize;
                let (e0, p) = (s0 + run as isize, p as isize);
                let nodes = [s0 - 1, s0, e0 - 1, e0, p, p + 1].map(|k| self.at(k));
                self.or_opt_move(v, run, p as usize, r);
                gained += g;
                nodes
            } else {
                continue;
            };
            *budget -= 1;
            for u in nodes {
                if u < strokes && !queued[u] {
                    queued[u] = true;
                    queue.push_back(u);
                }
            }
        }
        // A spent budget leaves strokes queued: clear them for the next search.
        for &v in &queue {
            queued[v] = false;
        }
        self.queued = queued;
        self.queue = queue;
        gained
    }

    /// Travel of the edge leaving position k.
    fn edge(&self, k: usize) -> f64 {
        Self::d(
            self.end(self.at(k as isize)),
            self.start(self.at(k as isize + 1)),
        )
    }

    /// A local double bridge: the runs B and C after position `bridge.p` swapped. Returns
    /// how much longer the travel got and the strokes at the changed edges.
    fn kick(&mut self, bridge: Bridge) -> (f64, [usize; 6]) {
        let n = self.len();
        let Bridge { p, l1, l2 } = bridge;
        let span = l1 + l2 + 1;
        let cost = |t: &Self| (0..span).map(|k| t.edge((p + k) % n)).sum::<f64>();
        let before = cost(self);
        self.reverse((p + 1) % n, (p + l1 + l2) % n);
        self.reverse((p + 1) % n, (p + l2) % n);
        self.reverse((p + l2 + 1) % n, (p + l1 + l2) % n);
        let after = cost(self);
        let touched = [0, 1, l2, l2 + 1, l1 + l2, l1 + l2 + 1].map(|k| self.seq[(p + k) % n]);
        (after - before, touched)
    }

    /// The strokes in drawing order, starting after the depot.
    fn order(&self) -> Vec<(usize, bool)> {
        let n = self.len();
        let d = self.pos(n - 1);
        (1..n)
            .map(|k| {
                let v = self.seq[(d + k) % n];
                (v, self.rev(v))
            })
            .collect()
    }
}

/// For each end slot, the slots of the nearest ends of other strokes (up to `width`, at
/// most [`NEIGHBOURS`]), nearest first (by distance, then slot: a total order), in one flat
/// table.
struct Near {
    /// The most neighbours a slot has.
    width: usize,
    /// Slot `s`'s neighbours are `slots[s * width ..][.. count[s]]`.
    slots: Vec<u32>,
    /// How many neighbours each slot has (fewer than `width` only in small layers).
    count: Vec<u8>,
}

impl Near {
    /// The neighbours of slot `s`, nearest first.
    fn of(&self, s: usize) -> &[u32] {
        &self.slots[s * self.width..][..usize::from(self.count[s])]
    }
}

/// The nearest ends of one slot, nearest first (by distance, then slot), at most
/// [`NEIGHBOURS`].
pub(super) struct Nearest {
    /// (distance, slot), nearest first; the first `len` are set.
    pub(super) found: [(f64, u32); NEIGHBOURS],
    /// How many are set.
    pub(super) len: usize,
}

/// The candidates of one search for the `k` nearest ends, by squared distance: the `k`
/// least (by squared distance, then slot) in order, and beside them those that might still
/// tie with the k-th once distances are taken (different squares, the same correctly
/// rounded root). Roots are taken and the order by (distance, slot) made only at the end,
/// for the few left, not each time a candidate comes in.
pub(super) struct Candidates {
    /// (squared distance, slot), least first; the first `len` are set.
    kept: [(f64, u32); NEIGHBOURS],
    len: usize,
    k: usize,
    /// Squared distances above this cannot be kept: the k-th's widened by a margin of many
    /// ulps (infinite until `k` are in).
    reject: f64,
    /// Candidates turned away or pushed out, beyond the k-th but maybe within the margin.
    beyond: Vec<(f64, u32)>,
}

impl Candidates {
    /// A buffer for searches (its memory kept from one to the next).
    pub(super) fn new() -> Candidates {
        Candidates {
            kept: [(0.0, 0); NEIGHBOURS],
            len: 0,
            k: 1,
            reject: f64::INFINITY,
            beyond: Vec::new(),
        }
    }

    /// Starts a search for the `k` nearest (1 to [`NEIGHBOURS`]).
    fn start(&mut self, k: usize) {
        self.len = 0;
        self.k = k;
        self.reject = f64::INFINITY;
        self.beyond.clear();
    }

    /// Offers slot `t` at squared distance `d2` (its distance is `d2.sqrt()`, as [`dist`]
    /// computes it).
    #[inline]
    fn offer_squared(&mut self, d2: f64, t: u32) {
        if d2 > self.reject {
            return;
        }
        let k = self.k;
        let before = |a: (f64, u32), b: (f64, u32)| a.0 < b.0 || (a.0 == b.0 && a.1 < b.1);
        if self.len == k && !before((d2, t), self.kept[k - 1]) {
            self.beyond.push((d2, t));
            return;
        }
        if self.len == k {
            self.beyond.push(self.kept[k - 1]);
        }
        let mut i = self.len.min(k - 1);
        while i > 0 && before((d2, t), self.kept[i - 1]) {
            self.kept[i] = self.kept[i - 1];
            i -= 1;
        }
        self.kept[i] = (d2, t);
        self.len = (self.len + 1).min(k);
        if self.len == k {
            // Every square whose root is the k-th's lies within this (the root is
            // correctly rounded; the margin is many ulps).
            self.reject = self.kept[k - 1].0 * (1.0 + 1e-12);
        }
    }

    /// The k-th distance, once `k` are in.
    fn kth(&self) -> Option<f64> {
        (self.len == self.k).then(|| self.kept[self.k - 1].0.sqrt())
    }

    /// The `k` nearest, by distance then slot.
    fn nearest(&mut self) -> Nearest {
        let reject = self.reject;
        self.beyond.retain(|c| c.0 <= reject);
        self.beyond.extend_from_slice(&self.kept[..self.len]);
        let all = &mut self.beyond;
        all.iter_mut().for_each(|c| c.0 = c.0.sqrt());
        let order = |a: &(f64, u32), b: &(f64, u32)| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1));
        // Mostly in order already: the kept come by squared distance, the others are rare.
        if !all.is_sorted_by(|a, b| order(a, b).is_le()) {
            all.sort_unstable_by(order);
        }
        let mut out = Nearest {
            found: [(0.0, 0); NEIGHBOURS],
            len: all.len().min(self.k),
        };
        out.found[..out.len].copy_from_slice(&all[..out.len]);
        out
    }
}

/// Slots a task of the parallel neighbour search takes: a bucket of tasks per thread at
/// least, each long enough to be worth its scheduling.
const NEAR_TASK: usize = 4096;

/// The [`Near`] table of every end slot (2i start, 2i + 1 end of stroke i), at most `k`
/// neighbours each (1 to [`NEIGHBOURS`]); from a uniform grid of about two ends a cell,
/// searched ring by ring. Fills `span` as the slots are searched. The slots are searched in
/// parallel, each on its own: the table is the same for any number of threads. Slots are
/// `u32`: [`plan_steps`] plans no more than `u32::MAX / 2` strokes this way.
fn neighbours(ends: &[[Pt2; 2]], k: usize, span: Span) -> Near {
    let pts: Vec<Pt2> = ends.iter().flatten().copied().collect();
    let buckets = Buckets::new(&pts);
    let k = k.clamp(1, NEIGHBOURS);
    let mut near = Near {
        width: k,
        slots: vec![0; pts.len() * k],
        count: vec![0; pts.len()],
    };
    let searched = span.steps(pts.len());
    near.slots
        .par_chunks_mut(NEAR_TASK * k)
        .zip(near.count.par_chunks_mut(NEAR_TASK))
        .enumerate()
        .for_each(|(task, (rows, counts))| {
            let mut candidates = Candidates::new();
            for (j, count) in counts.iter_mut().enumerate() {
                let s = task * NEAR_TASK + j;
                searched.tick(s);
                let found = buckets.nearest(s, pts[s], k, &mut candidates);
                let row = &mut rows[j * k..][..found.len];
                for (o, f) in row.iter_mut().zip(&found.found) {
                    *o = f.1;
                }
                *count = found.len as u8;
            }
        });
    span.finish();
    near
}

/// The end slots of a layer in grid cells, for [`neighbours`] and [`super::pairs`].
pub(super) struct Buckets {
    grid: Cells,
    /// Cell c's slots are `in_cells[start[c]..start[c + 1]]`.
    start: Vec<u32>,
    /// Each slot with its point, cell by cell.
    in_cells: Vec<(u32, Pt2)>,
}

impl Buckets {
    /// The end slots `pts` (2i start, 2i + 1 end of stroke i) in a uniform grid of about two
    /// ends a cell.
    pub(super) fn new(pts: &[Pt2]) -> Buckets {
        let b = crate::geom::Rect::of_points(pts.iter());
        let grid = Cells::square(&b, per_side(pts.len() as f64 / 2.0, 2048));
        // The cells' slots side by side, in slot order within a cell, each with its point,
        // so a cell's candidates are read in a row.
        let (start, slots) = grid.buckets(pts);
        let in_cells = slots.iter().map(|&s| (s, pts[s as usize])).collect();
        Buckets {
            grid,
            start,
            in_cells,
        }
    }

    /// The nearest `k` (at most [`NEIGHBOURS`]) ends of other strokes than slot `s`'s, at
    /// `p`: ring by ring round its cell.
    pub(super) fn nearest(&self, s: usize, p: Pt2, k: usize, found: &mut Candidates) -> Nearest {
        let (g, cell) = (self.grid.nx, self.grid.cell);
        let (cx, cy) = self.grid.coords(p);
        let k = k.clamp(1, NEIGHBOURS);
        found.start(k);
        // How far p lies inside its cell, in cells: ring r's cells are at least r − 1 and
        // this away (less a margin for the rounding of the cell coordinates).
        let at = |v: f64, o: f64, c: usize| (v - o) / cell - c as f64;
        let (fx, fy) = (
            at(p[0], self.grid.origin[0], cx),
            at(p[1], self.grid.origin[1], cy),
        );
        let inset = (fx.min(1.0 - fx).min(fy).min(1.0 - fy) - 1e-6).max(0.0);
        for r in 0..g {
            // Ring r holds nothing nearer than (r − 1 + inset) cells.
            let clear = (r as f64 - 1.0 + inset) * cell;
            if r > 0 && found.kth().is_some_and(|d| d < clear) {
                break;
            }
            if r > cx.max(cy).max(g - 1 - cx).max(g - 1 - cy) {
                break; // the ring lies wholly outside the grid
            }
            let (y0, y1) = (cy.saturating_sub(r), (cy + r).min(g - 1));
            let (x0, x1) = (cx.saturating_sub(r), (cx + r).min(g - 1));
            // A row's cells are side by side in the table: a full row of the ring is one
            // run of slots, an inner row its two side cells.
            for y in y0..=y1 {
                let row = y * g;
                if y.abs_diff(cy) == r {
                    self.scan(row + x0..=row + x1, s, p, found);
                } else {
                    if let Some(x) = cx.checked_sub(r) {
                        self.scan(row + x..=row + x, s, p, found);
                    }
                    if r > 0 && cx + r < g {
                        self.scan(row + cx + r..=row + cx + r, s, p, found);
                    }
                }
            }
        }
        found.nearest()
    }

    /// Offers the ends in `cells` (a run of cells side by side) but slot `s`'s stroke's.
    #[inline]
    fn scan(
        &self,
        cells: std::ops::RangeInclusive<usize>,
        s: usize,
        p: Pt2,
        found: &mut Candidates,
    ) {
        let slots = self.start[*cells.start()] as usize..self.start[*cells.end() + 1] as usize;
        for &(t, q) in &self.in_cells[slots] {
            if t as usize / 2 != s / 2 {
                let (dx, dy) = (q[0] - p[0], q[1] - p[1]);
                found.offer_squared(dx * dx + dy * dy, t);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn apply(ends: &[[Pt2; 2]], order: &[(usize, bool)]) -> Vec<Vec<Pt2>> {
        order
            .iter()
            .map(|&(i, r)| {
                if r {
                    vec![ends[i][1], ends[i][0]]
                } else {
                    vec![ends[i][0], ends[i][1]]
                }
            })
            .collect()
    }

    pub(super) fn random_strokes(n: usize, seed: u64) -> Vec<[Pt2; 2]> {
        let mut rng = crate::geom::rng::XorShift::new(seed);
        let mut rnd = || rng.range(0.0, 100.0);
        (0..n)
            .map(|_| {
                let a = [rnd(), rnd()];
                [a, [a[0] + rnd() * 0.05, a[1] + rnd() * 0.05]]
            })
            .collect()
    }

    #[test]
    fn plan_is_a_permutation_and_beats_greedy() {
        // 6,000 strokes: the kicks' reversals reach their bound.
        for (n, seed) in [(3, 1), (10, 2), (200, 3), (2000, 4), (6000, 5)] {
            let ends = random_strokes(n, seed);
            let p = plan(&ends, Span::NONE);
            let mut seen: Vec<usize> = p.iter().map(|o| o.0).collect();
            seen.sort_unstable();
            assert_eq!(seen, (0..n).collect::<Vec<_>>());
            let g = travel(&apply(&ends, &greedy(&ends, 0)));
            let t = travel(&apply(&ends, &p));
            assert!(t <= g + 1e-9, "n {n}: plan {t} > greedy {g}");
            if n >= 200 {
                assert!(t < 0.95 * g, "n {n}: plan {t} not clearly below greedy {g}");
            }
            assert_eq!(p, plan(&ends, Span::NONE), "deterministic");
        }
    }

    #[test]
    fn strokes_on_a_line_are_drawn_in_a_row() {
        // Ten unit strokes along x, given shuffled and some reversed: one pass, no travel
        // except the unit gaps between them.
        let mut ends: Vec<[Pt2; 2]> = (0..10)
            .map(|k| {
                let x = 2.0 * f64::from(k);
                [[x, 0.0], [x + 1.0, 0.0]]
            })
            .collect();
        ends.swap(2, 7);
        ends.swap(0, 5);
        ends[3].reverse();
        ends[8].reverse();
        let t = travel(&apply(&ends, &plan(&ends, Span::NONE)));
        assert!((t - 9.0).abs() < 1e-12, "{t}");
    }

    #[test]
    fn a_layer_of_dashes_is_planned_by_chains() {
        // Five parallel dashed lines 5 apart (dash 2, gap 1), the dashes shuffled and some
        // turned: each line's dashes are tied into a chain and drawn in a row, so the travel
        // is the gaps plus four hops between lines, as the untied plan finds it too.
        let mut ends: Vec<[Pt2; 2]> = Vec::new();
        for line in 0..5 {
            let y = 5.0 * f64::from(line);
            for k in 0..20 {
                let x = 3.0 * f64::from(k);
                ends.push([[x, y], [x + 2.0, y]]);
            }
        }
        let mut rng = crate::geom::rng::XorShift::new(3);
        for i in (1..ends.len()).rev() {
            ends.swap(i, rng.below(i + 1));
            if rng.below(2) == 1 {
                ends[i].reverse();
            }
        }
        let tied = plan_tied(&ends, &vec![true; ends.len()], Span::NONE);
        let mut seen: Vec<usize> = tied.iter().map(|o| o.0).collect();
        seen.sort_unstable();
        assert_eq!(seen, (0..100).collect::<Vec<_>>());
        let t = travel(&apply(&ends, &tied));
        assert!((t - (5.0 * 19.0 + 4.0 * 5.0)).abs() < 1e-9, "{t}");
        assert!(t <= travel(&apply(&ends, &plan(&ends, Span::NONE))) + 1e-9);
        // Each line's dashes follow each other.
        let lines: Vec<u64> = tied.iter().map(|o| ends[o.0][0][1] as u64).collect();
        assert_eq!(lines.windows(2).filter(|w| w[0] != w[1]).count(), 4);
    }

    #[test]
    fn a_layer_of_many_dashes_gets_more_kicks_and_no_longer_a_plan() {
        // 2,400 dashes (dash 2, gap 1) of 120 random lines, shuffled: more than
        // MANY_DASHES, so the layer gets DASH_KICKS_PER_STROKE kicks a chain. Its first kicks
        // are the draws one kick a chain makes, and a kick stays only when it shortens the
        // tour, so the plan is never longer than with one kick a chain.
        let mut rng = crate::geom::rng::XorShift::new(11);
        let mut ends: Vec<[Pt2; 2]> = Vec::new();
        for _ in 0..120 {
            let (x, y) = (rng.below(1000) as f64, rng.below(1000) as f64);
            let a = rng.below(628) as f64 / 100.0;
            let at = |t: f64| [x + t * a.cos(), y + t * a.sin()];
            ends.extend((0..20).map(|k| [at(3.0 * k as f64), at(3.0 * k as f64 + 2.0)]));
        }
        for i in (1..ends.len()).rev() {
            ends.swap(i, rng.below(i + 1));
            if rng.below(2) == 1 {
                ends[i].reverse();
            }
        }
        assert!(ends.len() > MANY_DASHES);
        let tieable = vec![true; ends.len()];
        let many = plan_tied(&ends, &tieable, Span::NONE);
        let mut seen: Vec<usize> = many.iter().map(|o| o.0).collect();
        seen.sort_unstable();
        assert_eq!(seen, (0..ends.len()).collect::<Vec<_>>());
        let chains = chains(&ends, &tieable);
        assert!(chains.len() < ends.len(), "dashes along lines are tied");
        let one = chains.expand(&plan_steps(&chains.ends(&ends), DASHES, Span::NONE));
        let (t_many, t_one) = (travel(&apply(&ends, &many)), travel(&apply(&ends, &one)));
        assert!(t_many <= t_one + 1e-9, "{t_many} > {t_one}");
        assert!(
            t_many < t_one,
            "the extra kicks shortened this layer's plan"
        );
        assert_eq!(
            many,
            plan_tied(&ends, &tieable, Span::NONE),
            "deterministic"
        );
    }

    #[test]
    fn reversals_and_moves_keep_positions_consistent() {
        let ends = random_strokes(12, 9);
        let order: Vec<(usize, bool)> = (0..12).map(|i| (i, i % 3 == 0)).collect();
        let near = neighbours(&ends, NEIGHBOURS, Span::NONE);
        let mut t = Tour::new(&ends, &order, &near);
        let before = cycle_cost(&t);
        t.reverse(10, 2); // wraps around the depot at 12
        t.or_opt_move(t.seq[4], 2, 8, true);
        t.or_opt_move(t.seq[9], 3, 1, false);
        for (k, &v) in t.seq.iter().enumerate() {
            assert_eq!(t.pos(v), k);
        }
        let mut all = t.seq.clone();
        all.sort_unstable();
        assert_eq!(all, (0..13).collect::<Vec<_>>());
        assert!(cycle_cost(&t).is_finite() && before.is_finite());
    }

    #[test]
    fn a_counted_plan_fills_its_share_and_plans_the_same() {
        use crate::count::Share;
        use crate::progress::{Phase, Progress, Stage};
        let ends = random_strokes(3000, 6);
        let p = Progress::new();
        p.enter_phase(Stage::Emit, Phase::Order, 3000);
        let share = Share::new(p.count(), 3000);
        // The search and its kicks fill their span by their own counts (2,000 kicks, a
        // whole number of chunks), before any finishing.
        let near = neighbours(&ends, NEIGHBOURS, Span::NONE);
        let mut t = Tour::new(&ends, &greedy(&ends, 0), &near);
        t.improve(FULL, share.span(0.0, 0.5));
        assert_eq!(
            p.counts().0,
            1500,
            "the first search and every kick counted"
        );
        let counted = plan(&ends, share.span(0.5, 1.0));
        assert_eq!(p.counts(), (3000, 3000));
        assert_eq!(counted, plan(&ends, Span::NONE), "counting changes nothing");
    }

    pub(super) fn cycle_cost(t: &Tour) -> f64 {
        (0..t.len() as isize)
            .map(|k| Tour::d(t.end(t.at(k)), t.start(t.at(k + 1))))
            .sum()
    }

    #[test]
    fn or_opt_gain_is_the_cost_change() {
        // Every Or-opt move the search proposes lowers the cycle's cost by its gain.
        let ends = random_strokes(60, 5);
        let near = neighbours(&ends, NEIGHBOURS, Span::NONE);
        let mut t = Tour::new(&ends, &greedy(&ends, 0), &near);
        for v in 0..60 {
            if let Some((g, run, p, r)) = t.best_or_opt(v) {
                let before = cycle_cost(&t);
                t.or_opt_move(v, run, p, r);
                let after = cycle_cost(&t);
                assert!(
                    (before - after - g).abs() < 1e-9,
                    "{before} - {after} != {g}"
                );
            }
            if let Some((g, i, j)) = t.best_two_opt(v) {
                let before = cycle_cost(&t);
                t.two_opt_move(i, j);
                let after = cycle_cost(&t);
                assert!(
                    (before - after - g).abs() < 1e-9,
                    "{before} - {after} != {g}"
                );
            }
        }
    }

    #[test]
    fn candidates_with_one_root_are_ordered_by_slot() {
        // Two different squared distances with the same root: the lower slot comes first,
        // whichever was offered first and whether or not it was turned away or pushed out
        // by squared distance alone.
        let (a, b) = (2.0_f64, f64::from_bits(2.0_f64.to_bits() + 1));
        assert!(a < b && a.sqrt() == b.sqrt());
        let far = 3.0;
        type Case<'c> = (&'c [(f64, u32)], usize, &'c [u32]);
        let cases: [Case; 4] = [
            (&[(a, 5), (b, 1)], 1, &[1]),
            (&[(b, 1), (a, 5)], 1, &[1]),
            (&[(far, 0), (b, 1), (a, 5)], 2, &[1, 5]),
            (&[(b, 7), (a, 5), (far, 0), (b, 1)], 2, &[1, 5]),
        ];
        for (offers, k, want) in cases {
            let mut c = Candidates::new();
            c.start(k);
            offers.iter().for_each(|&(d2, t)| c.offer_squared(d2, t));
            let got = c.nearest();
            let slots: Vec<u32> = got.found[..got.len].iter().map(|f| f.1).collect();
            assert_eq!(slots, want, "{offers:?}");
        }
    }

    #[test]
    fn neighbours_are_the_nearest_other_ends_in_order() {
        // Against a brute force over every pair, by distance then slot: random strokes, a
        // cluster of coincident ends (ties broken by slot), and a layer too small to fill
        // the lists.
        let mut ends = random_strokes(700, 11);
        for k in 0..40 {
            let x = f64::from(k % 3);
            ends.push([[50.0, 50.0], [50.0 + x, 50.0]]);
        }
        // More slots than one parallel task takes: checked at every 37th slot and across
        // the tasks' seam.
        let many = random_strokes(NEAR_TASK, 13);
        // Both widths of list: a layer's and a layer of dashes'.
        let cases = [ends, random_strokes(5, 12), many]
            .into_iter()
            .flat_map(|e| [(e.clone(), NEIGHBOURS), (e, DASH_NEIGHBOURS)]);
        for (ends, k) in cases {
            let near = neighbours(&ends, k, Span::NONE);
            let pts: Vec<Pt2> = ends.iter().flatten().copied().collect();
            let checked: Vec<usize> = if pts.len() > NEAR_TASK {
                (0..pts.len())
                    .step_by(37)
                    .chain(NEAR_TASK - 3..NEAR_TASK + 3)
                    .collect()
            } else {
                (0..pts.len()).collect()
            };
            for s in checked {
                let p = pts[s];
                let mut all: Vec<(f64, usize)> = (0..pts.len())
                    .filter(|t| t / 2 != s / 2)
                    .map(|t| (dist(p, pts[t]), t))
                    .collect();
                all.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
                all.truncate(k);
                let want: Vec<u32> = all.iter().map(|a| a.1 as u32).collect();
                assert_eq!(near.of(s), &want[..], "slot {s}, {k} neighbours");
            }
        }
    }
}
#[cfg(test)]
mod against_full_two_opt {
    use super::*;
    use crate::geom::rng::XorShift;

    /// Travel after a full 2-opt from `order`, written independently the way vpype's
    /// `linesort --two-opt` does it: for each position, flip the best run starting there,
    /// while anything gains.
    fn full_two_opt(ends: &[[Pt2; 2]], order: &[(usize, bool)]) -> f64 {
        let mut e: Vec<[Pt2; 2]> = order
            .iter()
            .map(|&(i, r)| if r { [ends[i][1], ends[i][0]] } else { ends[i] })
            .collect();
        let n = e.len();
        let mut improved = true;
        while improved {
            improved = false;
            for mid in 0..n {
                let mut best = (-1e-10, usize::MAX);
                for j in mid..n {
                    let src = if mid > 0 { Some(e[mid - 1][1]) } else { None };
                    let dst = if j + 1 < n { Some(e[j + 1][0]) } else { None };
                    let d = |a: Option<Pt2>, b: Option<Pt2>| match (a, b) {
                        (Some(a), Some(b)) => dist(a, b),
                        _ => 0.0,
                    };
                    let delta = d(src, Some(e[j][1])) + d(Some(e[mid][0]), dst)
                        - d(src, Some(e[mid][0]))
                        - d(Some(e[j][1]), dst);
                    if delta < best.0 {
                        best = (delta, j);
                    }
                }
                if best.1 != usize::MAX {
                    e[mid..=best.1].reverse();
                    for s in &mut e[mid..=best.1] {
                        s.swap(0, 1);
                    }
                    improved = true;
                }
            }
        }
        e.windows(2).map(|w| dist(w[0][1], w[1][0])).sum()
    }

    #[test]
    fn plan_is_at_least_as_short_as_a_full_two_opt() {
        let mut rng = XorShift::new(77);
        for n in [50, 100, 300] {
            let ends: Vec<[Pt2; 2]> = (0..n)
                .map(|_| {
                    let a = [rng.range(0., 100.), rng.range(0., 100.)];
                    let b = [a[0] + rng.range(-5., 5.), a[1] + rng.range(-5., 5.)];
                    [a, b]
                })
                .collect();
            let g = greedy(&ends, 0);
            let ap = |o: &[(usize, bool)]| -> f64 {
                o.windows(2)
                    .map(|w| {
                        dist(
                            ends[w[0].0][usize::from(!w[0].1)],
                            ends[w[1].0][usize::from(w[1].1)],
                        )
                    })
                    .sum()
            };
            let mine = ap(&plan(&ends, Span::NONE));
            let full = full_two_opt(&ends, &g);
            assert!(mine <= full, "n {n}: plan {mine} > full 2-opt {full}");
        }
    }
}
