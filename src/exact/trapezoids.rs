//! One face against the exact answer, by a trapezoidal decomposition of the screen around
//! it: cut by every edge that can bound the answer or the claim, no region of a trapezoid
//! can change owner, so one exact sample point decides it all.
//!
//! For face f the lines are: the edges of f's pieces and of every piece whose box meets
//! theirs, the lines where f's pieces and those pieces are at equal depth (clipped to the
//! pair's box), and the edges of the claimed visible region. The vertical lines through
//! every endpoint and every crossing of two of them cut the x-range of f into slabs; in a
//! slab no two lines cross, so between two consecutive lines lies a trapezoid in which
//! "is f the nearest face" and "does the claim cover it" are constant. Both are decided at
//! the trapezoid's centre, exactly.

use super::project::ExactPiece;
use super::rational::{bounds, box_of, boxes_meet, q, sign, winding, QPt, Q};

/// A line segment of the decomposition, with f64 bounds used only to skip pairs, and its
/// line y = m x + k (exact; None when vertical).
#[derive(Debug, Clone)]
struct Seg {
    a: QPt,
    b: QPt,
    rect: [f64; 4],
    line: Option<(Q, Q)>,
}

impl Seg {
    fn new(a: QPt, b: QPt) -> Seg {
        let rect = box_of([&a, &b]);
        let (a, b) = if a.x <= b.x { (a, b) } else { (b, a) };
        let line = (a.x != b.x).then(|| {
            let m = (&b.y - &a.y) / (&b.x - &a.x);
            let k = &a.y - &m * &a.x;
            (m, k)
        });
        Seg { a, b, rect, line }
    }

    /// dy/dx (f64; the segment is not vertical).
    fn slope(&self) -> f64 {
        self.line.as_ref().map_or(f64::NAN, |(m, _)| to_f64(m))
    }

    /// y at `x` (the segment is not vertical and spans x).
    fn y_at(&self, x: &Q) -> Q {
        match &self.line {
            Some((m, k)) => m * x + k,
            None => self.a.y.clone(),
        }
    }
}

/// Areas of one face: its visible area, the area of the claim, and the area where claim
/// and answer differ (the symmetric difference). Which trapezoid is which is decided
/// exactly; each trapezoid's area is then measured in f64 (relative error ~1e-16).
#[derive(Debug, Clone, Default, PartialEq)]
pub(crate) struct FaceAreas {
    /// Exactly visible area.
    pub visible: f64,
    /// Area of the claimed region (inside the face or not).
    pub claimed: f64,
    /// Area of the symmetric difference of the claim and the exact answer.
    pub mismatch: f64,
    /// The face's projected area.
    pub projected: f64,
}

/// The exact areas of face `face` (its pieces `own`) among `pieces`, against the claimed
/// visible region `claim` (rings with exact coordinates; nonzero winding).
pub(crate) fn face_areas(
    own: &[&ExactPiece],
    pieces: &[ExactPiece],
    claim: &[Vec<QPt>],
) -> FaceAreas {
    let mut out = FaceAreas::default();
    if own.is_empty() {
        return out;
    }
    let face = own[0].face;
    let rect = own.iter().fold(own[0].rect, |r, p| union(&r, &p.rect));
    let rect = claim.iter().fold(rect, |r, c| union(&r, &box_of(c)));
    let others: Vec<&ExactPiece> = pieces
        .iter()
        .filter(|p| p.face != face && boxes_meet(&p.rect, &rect))
        .collect();
    let mut segs = Vec::new();
    for p in own.iter().chain(&others) {
        ring_segs(&p.ring, &mut segs);
    }
    for p in own {
        for o in &others {
            if boxes_meet(&p.rect, &o.rect) {
                if let Some(s) = equal_depth(p, o) {
                    segs.push(s);
                }
            }
        }
    }
    for r in claim {
        ring_segs(r, &mut segs);
    }
    // Only lines through the box of the face and its claim can bound a trapezoid there.
    let segs: Vec<Seg> = segs
        .into_iter()
        .filter(|s| boxes_meet(&s.rect, &rect))
        .collect();
    // The claim may reach outside the face: that part is a mismatch too.
    let xlo = own
        .iter()
        .flat_map(|p| &p.ring)
        .chain(claim.iter().flatten())
        .map(|p| &p.x)
        .min()
        .cloned();
    let xhi = own
        .iter()
        .flat_map(|p| &p.ring)
        .chain(claim.iter().flatten())
        .map(|p| &p.x)
        .max()
        .cloned();
    let (Some(xlo), Some(xhi)) = (xlo, xhi) else {
        return out;
    };
    let xs = events(&segs, &xlo, &xhi, &rect);
    for w in xs.windows(2) {
        let (x0, x1) = (&w[0], &w[1]);
        let (b0, b1) = (bounds(x0), bounds(x1));
        // Any x strictly inside the slab orders its lines: a short one keeps the numbers small.
        let xm = between(x0, x1);
        let mut lines: Vec<(Q, &Seg)> = segs
            .iter()
            .filter(|s| s.rect[0] <= b0[1] && s.rect[1] >= b1[0])
            .filter(|s| s.line.is_some() && s.a.x <= *x0 && s.b.x >= *x1)
            .map(|s| (s.y_at(&xm), s))
            .collect();
        lines.sort_by(|a, b| a.0.cmp(&b.0));
        lines.dedup_by(|a, b| a.0 == b.0);
        let width = to_f64(&(x1 - x0));
        let mid = 0.5 * (to_f64(x0) + to_f64(x1));
        let xf = to_f64(&xm);
        for pair in lines.windows(2) {
            let ((ya, sa), (yb, sb)) = (&pair[0], &pair[1]);
            let p = QPt {
                x: xm.clone(),
                y: between(ya, yb),
            };
            let pb = [bounds(&p.x), bounds(&p.y)];
            let near = |r: &[f64; 4]| boxes_meet(r, &[pb[0][0], pb[0][1], pb[1][0], pb[1][1]]);
            let inside = own
                .iter()
                .any(|o| near(&o.rect) && winding(&o.ring, &p) != 0);
            let claimed = claim.iter().map(|r| winding(r, &p)).sum::<i32>() != 0;
            if !inside && !claimed {
                continue;
            }
            // The trapezoid's area: its width times its height at the slab's middle (f64:
            // a measure, not a decision).
            let gap = to_f64(&(yb - ya)) + (sb.slope() - sa.slope()) * (mid - xf);
            let area = width * gap;
            let exact = inside && nearest_is(face, own, &others, &p);
            if inside {
                out.projected += area;
            }
            if exact {
                out.visible += area;
            }
            if claimed {
                out.claimed += area;
            }
            if exact != claimed {
                out.mismatch += area;
            }
        }
    }
    out
}

/// A number strictly between a < b: a short dyadic (an f64) where one fits, else the
/// midpoint.
fn between(a: &Q, b: &Q) -> Q {
    let (ba, bb) = (bounds(a), bounds(b));
    if ba[1] < bb[0] {
        let m = q(0.5 * (ba[1] + bb[0]));
        if *a < m && m < *b {
            return m;
        }
    }
    (a + b) / Q::int(2)
}

fn to_f64(x: &Q) -> f64 {
    x.to_f64().unwrap_or(f64::NAN)
}

/// True when the nearest piece over `p` belongs to `face` (a tie in depth goes to the face
/// earlier in global order).
fn nearest_is(face: u32, own: &[&ExactPiece], others: &[&ExactPiece], p: &QPt) -> bool {
    let mine = own
        .iter()
        .filter(|o| winding(&o.ring, p) != 0)
        .map(|o| o.depth(p))
        .max();
    let Some(mine) = mine else {
        return false;
    };
    !others.iter().any(|o| {
        let [px, py] = [bounds(&p.x), bounds(&p.y)];
        if px[1] < o.rect[0] || px[0] > o.rect[1] || py[1] < o.rect[2] || py[0] > o.rect[3] {
            return false;
        }
        if winding(&o.ring, p) == 0 {
            return false;
        }
        let d = o.depth(p);
        d > mine || (d == mine && o.face < face)
    })
}

/// The ring's edges as segments.
fn ring_segs(r: &[QPt], out: &mut Vec<Seg>) {
    let n = r.len();
    for i in 0..n {
        let (a, b) = (&r[i], &r[(i + 1) % n]);
        if a != b {
            out.push(Seg::new(a.clone(), b.clone()));
        }
    }
}

/// The line where pieces p and o are at equal depth, within the box of both rings (exact
/// box from their vertices); None when their planes do not cross there.
fn equal_depth(p: &ExactPiece, o: &ExactPiece) -> Option<Seg> {
    // (a_p - a_o) x + (b_p - b_o) y + (c_p - c_o) = 0.
    let a = &p.plane[0] - &o.plane[0];
    let b = &p.plane[1] - &o.plane[1];
    let c = &p.plane[2] - &o.plane[2];
    if a.is_zero() && b.is_zero() {
        return None;
    }
    let xs = p.ring.iter().chain(&o.ring).map(|q| &q.x);
    let ys = p.ring.iter().chain(&o.ring).map(|q| &q.y);
    let (x0, x1) = (xs.clone().min()?.clone(), xs.max()?.clone());
    let (y0, y1) = (ys.clone().min()?.clone(), ys.max()?.clone());
    // Points of the line on the box's sides, kept when inside the box.
    let mut pts: Vec<QPt> = Vec::new();
    if !b.is_zero() {
        for x in [&x0, &x1] {
            let y = -(&a * x + &c) / &b;
            if y >= y0 && y <= y1 {
                pts.push(QPt { x: x.clone(), y });
            }
        }
    }
    if !a.is_zero() {
        for y in [&y0, &y1] {
            let x = -(&b * y + &c) / &a;
            if x >= x0 && x <= x1 {
                pts.push(QPt { x, y: y.clone() });
            }
        }
    }
    pts.sort();
    pts.dedup();
    (pts.len() >= 2).then(|| Seg::new(pts[0].clone(), pts[pts.len() - 1].clone()))
}

/// The x of every endpoint and every crossing of two segments within [xlo, xhi] (crossings
/// only where the segments' boxes meet inside `rect`), sorted, distinct, with xlo and xhi.
fn events(segs: &[Seg], xlo: &Q, xhi: &Q, rect: &[f64; 4]) -> Vec<Q> {
    let mut xs: Vec<Q> = vec![xlo.clone(), xhi.clone()];
    for s in segs {
        for x in [&s.a.x, &s.b.x] {
            if x > xlo && x < xhi {
                xs.push(x.clone());
            }
        }
    }
    let mut order: Vec<usize> = (0..segs.len()).collect();
    order.sort_by(|&i, &j| segs[i].rect[0].total_cmp(&segs[j].rect[0]));
    for (k, &i) in order.iter().enumerate() {
        for &j in &order[k + 1..] {
            if segs[j].rect[0] > segs[i].rect[1] {
                break;
            }
            let (a, b) = (&segs[i].rect, &segs[j].rect);
            let both = [
                a[0].max(b[0]),
                a[1].min(b[1]),
                a[2].max(b[2]),
                a[3].min(b[3]),
            ];
            if !(both[0] <= both[1] && both[2] <= both[3] && boxes_meet(&both, rect)) {
                continue;
            }
            if let Some(x) = crossing_x(&segs[i], &segs[j]) {
                if &x > xlo && &x < xhi {
                    xs.push(x);
                }
            }
        }
    }
    xs.sort();
    xs.dedup();
    xs
}

/// The x where two segments cross at a single point (None when apart or collinear: their
/// endpoints are events already).
fn crossing_x(s: &Seg, t: &Seg) -> Option<Q> {
    let d = |p: &QPt, q: &QPt| (&q.x - &p.x, &q.y - &p.y);
    let (rx, ry) = d(&s.a, &s.b);
    let (sx, sy) = d(&t.a, &t.b);
    let den = &rx * &sy - &ry * &sx;
    if den.is_zero() {
        return None;
    }
    let (qx, qy) = d(&s.a, &t.a);
    let u = (&qx * &sy - &qy * &sx) / &den;
    let v = (&qx * &ry - &qy * &rx) / &den;
    let one = Q::int(1);
    let inside = |x: &Q| sign(x) >= 0 && *x <= one;
    (inside(&u) && inside(&v)).then(|| &s.a.x + u * rx)
}

fn union(a: &[f64; 4], b: &[f64; 4]) -> [f64; 4] {
    [
        a[0].min(b[0]),
        a[1].max(b[1]),
        a[2].min(b[2]),
        a[3].max(b[3]),
    ]
}
