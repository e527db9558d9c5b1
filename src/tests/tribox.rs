//! Triboxes against independent computations: the boundary from corner classification
//! (section 3) equals the intersection of the 18 half-spaces found by brute force (every
//! triple of planes solved, points kept when they satisfy all 18 inequalities), on random and
//! degenerate bound sets; inputs lie inside; at most 18 faces; volumes below the CBOX's.

use crate::geom::{Box3, M4, P3, V3};
use crate::tribox::boundary::Case;
use crate::tribox::bounds::face_normal;
use crate::tribox::Tribox;
use kepler_testkit::Rng;

/// A whole number in 0..n, as a float.
fn int(rng: &mut Rng, n: u32) -> f64 {
    (rng.unit() * f64::from(n)).floor()
}

/// The polytope of 18 half-spaces, computed by brute force.
struct Brute {
    vertices: Vec<P3>,
    /// Area of each face (0 for a face touching in an edge or a vertex).
    areas: [f64; 18],
    volume: f64,
}

fn brute(offsets: &[f64; 18], tol: f64) -> Brute {
    let n: Vec<V3> = (0..18).map(face_normal).collect();
    let inside = |p: &P3| (0..18).all(|g| n[g].dot(&p.coords) <= offsets[g] + tol);
    let mut vertices: Vec<P3> = Vec::new();
    for i in 0..18 {
        for j in i + 1..18 {
            for k in j + 1..18 {
                let m = nalgebra::Matrix3::from_rows(&[
                    n[i].transpose(),
                    n[j].transpose(),
                    n[k].transpose(),
                ]);
                if m.determinant().abs() < 0.5 {
                    continue;
                }
                let Some(x) = m.lu().solve(&V3::new(offsets[i], offsets[j], offsets[k])) else {
                    continue;
                };
                let p = P3::from(x);
                if inside(&p) && !vertices.iter().any(|q| (q - p).norm() <= tol) {
                    vertices.push(p);
                }
            }
        }
    }
    let centre = if vertices.is_empty() {
        P3::origin()
    } else {
        P3::from(vertices.iter().map(|p| p.coords).sum::<V3>() / vertices.len() as f64)
    };
    let mut areas = [0.0; 18];
    let mut volume = 0.0;
    for f in 0..18 {
        let nf = n[f] / n[f].norm();
        let on: Vec<P3> = vertices
            .iter()
            .filter(|p| (n[f].dot(&p.coords) - offsets[f]).abs() <= tol * n[f].norm())
            .copied()
            .collect();
        if on.len() < 3 {
            continue;
        }
        let c = P3::from(on.iter().map(|p| p.coords).sum::<V3>() / on.len() as f64);
        let u =
            (on.iter()
                .map(|p| p - c)
                .fold(V3::zeros(), |a, d| if d.norm() > a.norm() { d } else { a }))
            .normalize();
        let w = nf.cross(&u);
        let mut sorted = on.clone();
        sorted.sort_by(|a, b| {
            let ang = |p: &P3| w.dot(&(p - c)).atan2(u.dot(&(p - c)));
            ang(a).total_cmp(&ang(b))
        });
        let mut a = V3::zeros();
        for i in 0..sorted.len() {
            a += (sorted[i] - c).cross(&(sorted[(i + 1) % sorted.len()] - c));
        }
        areas[f] = a.dot(&nf).abs() * 0.5;
        volume += areas[f] * (offsets[f] - n[f].dot(&centre.coords)) / n[f].norm() / 3.0;
    }
    Brute {
        vertices,
        areas,
        volume,
    }
}

fn newell(v: &[P3], f: &[u32]) -> V3 {
    let mut n = V3::zeros();
    for i in 0..f.len() {
        let (a, b) = (v[f[i] as usize], v[f[(i + 1) % f.len()] as usize]);
        n += a.coords.cross(&b.coords);
    }
    n
}

/// Everything the tribox of these bounds must satisfy; returns the corner cases seen.
fn check(t: &Tribox, points: &[P3], what: &str) -> Vec<Case> {
    let t = t.tightened();
    let scale = t.offsets().iter().fold(1.0f64, |m, o| m.max(o.abs()));
    let tol = 1e-10 * scale;
    let b = t.boundary();
    let br = brute(&t.offsets(), tol);
    // Same vertex set.
    for v in &b.vertices {
        assert!(
            br.vertices.iter().any(|q| (q - v).norm() <= 10.0 * tol),
            "{what}: boundary vertex {v:?} is no vertex of the half-space intersection"
        );
    }
    for q in &br.vertices {
        assert!(
            b.vertices.iter().any(|v| (q - v).norm() <= 10.0 * tol),
            "{what}: vertex {q:?} of the half-space intersection is missing"
        );
    }
    // Face by face: on its plane, facing out, same area.
    assert_eq!(b.faces.len(), 18);
    for (f, face) in b.faces.iter().enumerate() {
        let n = face_normal(f);
        for &v in face {
            let d = n.dot(&b.vertices[v as usize].coords) - t.offset(f);
            assert!(
                d.abs() <= tol * n.norm(),
                "{what}: face {f} vertex off its plane by {d}"
            );
        }
        let nn = newell(&b.vertices, face);
        assert!(nn.dot(&n) >= -tol * scale, "{what}: face {f} faces inward");
        let area = nn.norm() * 0.5;
        assert!(
            (area - br.areas[f]).abs() <= 1e-8 * scale * scale,
            "{what}: face {f} area {area} vs {}",
            br.areas[f]
        );
    }
    let vol = b.volume();
    assert!(
        (vol - br.volume).abs() <= 1e-8 * scale.powi(3),
        "{what}: volume {vol} vs {}",
        br.volume
    );
    assert!(
        vol <= t.cbox().volume() * (1.0 + 1e-12) + tol,
        "{what}: larger than its CBOX"
    );
    // Inputs inside; the paper's operation counts.
    for p in points {
        assert!(t.contains(p), "{what}: {p:?} outside");
    }
    assert!(b.ops.additions <= 112 && b.ops.shifts == 24 && b.ops.tests <= 24);
    // The cleaned mesh: at most 18 faces, closed (every edge used once each way) when solid.
    let m = b.mesh();
    assert!(m.faces.len() <= 18, "{what}: {} faces", m.faces.len());
    if vol > 1e-6 * scale.powi(3) {
        let mut edges = std::collections::HashMap::new();
        for f in &m.faces {
            for i in 0..f.len() {
                *edges.entry((f[i], f[(i + 1) % f.len()])).or_insert(0) += 1;
            }
        }
        for (&(a, c), &k) in &edges {
            assert_eq!(k, 1, "{what}: edge used twice the same way");
            assert_eq!(
                edges.get(&(c, a)),
                Some(&1),
                "{what}: edge {a}-{c} unpaired"
            );
        }
        let euler = m.vertices.len() as i64 - edges.len() as i64 / 2 + m.faces.len() as i64;
        assert_eq!(euler, 2, "{what}: not a sphere");
    }
    b.cases.to_vec()
}

fn pts(rng: &mut Rng, n: usize, f: impl Fn(&mut Rng) -> P3) -> Vec<P3> {
    (0..n).map(|_| f(rng)).collect()
}

#[test]
fn boundary_equals_half_space_intersection() {
    let mut rng = Rng::new(0x9E3779B97F4A7C15);
    let mut seen = std::collections::BTreeMap::<Case, usize>::new();
    let mut count = |cases: Vec<Case>| {
        for c in cases {
            *seen.entry(c).or_default() += 1;
        }
    };
    for i in 0..300 {
        // Random points, anisotropic and offset.
        let n = 1 + (i % 12);
        let s = V3::new(
            0.2 + rng.unit() * 3.0,
            0.2 + rng.unit() * 3.0,
            0.2 + rng.unit() * 3.0,
        );
        let o = V3::new(rng.unit() - 0.5, rng.unit() - 0.5, rng.unit() - 0.5) * 100.0;
        let p = pts(&mut rng, n, |r| {
            P3::new(r.unit() * s.x, r.unit() * s.y, r.unit() * s.z) + o
        });
        count(check(
            &Tribox::from_points(p.iter()),
            &p,
            &format!("random points {i}"),
        ));
        // Small integer grids: coincident planes, chamfers meeting exactly on principal planes.
        let p = pts(&mut rng, 2 + i % 6, |r| {
            P3::new(int(r, 3), int(r, 3), int(r, 3))
        });
        count(check(
            &Tribox::from_points(p.iter()),
            &p,
            &format!("grid points {i}"),
        ));
        // 18 random bounds, tightened (not from points).
        let mut t = Tribox::empty();
        for k in 0..9 {
            let c = rng.unit() * 4.0 - 2.0;
            t.lo[k] = c - rng.unit() * 3.0;
            t.hi[k] = c + rng.unit() * 3.0;
        }
        if !t.tightened().is_empty() {
            count(check(&t, &[], &format!("random bounds {i}")));
        }
    }
    // Degenerate sets.
    let single = [P3::new(1.5, -2.0, 7.0)];
    check(&Tribox::from_points(single.iter()), &single, "single point");
    let flat = pts(&mut rng, 9, |r| P3::new(r.unit(), r.unit(), 0.25));
    check(&Tribox::from_points(flat.iter()), &flat, "flat set");
    let diagonal_plane = pts(&mut rng, 9, |r| {
        let x = r.unit();
        P3::new(x, 1.0 - x, r.unit())
    });
    check(
        &Tribox::from_points(diagonal_plane.iter()),
        &diagonal_plane,
        "set in x+y=1",
    );
    let line = pts(&mut rng, 5, |r| {
        let u = r.unit();
        P3::new(u, 2.0 * u, -u)
    });
    check(&Tribox::from_points(line.iter()), &line, "collinear set");
    let cube = Box3::new(P3::new(-1., -1., -1.), P3::new(1., 1., 1.)).corners();
    check(&Tribox::from_points(cube.iter()), &cube, "cube");
    for case in [Case::One, Case::Two, Case::Three, Case::Four] {
        assert!(
            seen.get(&case).copied().unwrap_or(0) >= 10,
            "corner case {case:?} seen too rarely: {seen:?}"
        );
    }
}

#[test]
fn flat_and_point_sets_clean_up_to_polygons_and_nothing() {
    let single = [P3::new(1.5, -2.0, 7.0)];
    assert!(Tribox::from_points(single.iter())
        .boundary()
        .mesh()
        .faces
        .is_empty());
    let square = [
        P3::new(0., 0., 1.),
        P3::new(1., 0., 1.),
        P3::new(1., 1., 1.),
        P3::new(0., 1., 1.),
    ];
    let m = Tribox::from_points(square.iter()).boundary().mesh();
    assert_eq!(m.faces.len(), 2, "the square, once per side");
    assert_eq!(m.vertices.len(), 4);
}

#[test]
fn simplification_contains_the_original_and_drops_small_faces() {
    let mut rng = Rng::new(77);
    for i in 0..100 {
        let p = pts(&mut rng, 30, |r| {
            let v = V3::new(r.unit() - 0.5, r.unit() - 0.5, r.unit() - 0.5);
            P3::from(v.normalize())
        });
        let t = Tribox::from_points(p.iter());
        let tol = 0.02 + 0.002 * i as f64;
        let s = t.simplified(tol);
        let (to, so) = (t.tightened().offsets(), s.offsets());
        for f in 0..18 {
            assert!(so[f] >= to[f] - 1e-12, "moved inward");
            assert!(
                (so[f] - to[f]) / face_normal(f).norm() <= tol + 1e-12,
                "moved too far"
            );
        }
        for q in &p {
            assert!(s.contains(q));
        }
        let (nt, ns) = (
            t.boundary().mesh().faces.len(),
            s.boundary().mesh().faces.len(),
        );
        assert!(ns <= nt, "{ns} faces after simplifying, {nt} before");
        check(&s, &p, &format!("simplified {i}"));
    }
}

#[test]
fn transformed_tribox_holds_the_transformed_points() {
    let mut rng = Rng::new(5);
    for _ in 0..50 {
        let p = pts(&mut rng, 20, |r| {
            P3::new(r.unit(), r.unit() * 2.0, r.unit() * 0.5)
        });
        let axis = nalgebra::Unit::new_normalize(V3::new(rng.unit(), rng.unit(), rng.unit() + 0.1));
        let m: M4 = nalgebra::Translation3::new(3.0, -1.0, 2.0).to_homogeneous()
            * nalgebra::Rotation3::from_axis_angle(&axis, rng.unit() * 6.0).to_homogeneous()
            * M4::new_scaling(0.5 + rng.unit());
        let t = Tribox::from_points(p.iter());
        let tt = t.transformed(&m);
        let exact = Tribox::from_points(
            p.iter()
                .map(|q| m.transform_point(q))
                .collect::<Vec<_>>()
                .iter(),
        );
        for k in 0..9 {
            assert!(tt.lo[k] <= exact.lo[k] + 1e-12 && exact.hi[k] <= tt.hi[k] + 1e-12);
        }
    }
}

#[test]
fn interference_never_misses_a_meeting() {
    let mut rng = Rng::new(99);
    let (mut meet, mut apart_boxes_meet) = (0, 0);
    for _ in 0..400 {
        let c = V3::new(rng.unit(), rng.unit(), rng.unit()) * 1.3;
        let a = pts(&mut rng, 6, |r| P3::new(r.unit(), r.unit(), r.unit()));
        let b = pts(&mut rng, 6, |r| P3::new(r.unit(), r.unit(), r.unit()) + c);
        let (ta, tb) = (Tribox::from_points(a.iter()), Tribox::from_points(b.iter()));
        let both = Tribox {
            lo: std::array::from_fn(|k| ta.lo[k].max(tb.lo[k])),
            hi: std::array::from_fn(|k| ta.hi[k].min(tb.hi[k])),
        };
        let scale = 4.0;
        let nonempty = !brute(&both.offsets(), 1e-12 * scale).vertices.is_empty();
        if nonempty {
            meet += 1;
            assert!(ta.interferes(&tb), "triboxes meet but the test says apart");
        }
        let boxes = ta.cbox().union(&tb.cbox());
        let boxes_meet = (0..3).all(|i| ta.lo[i] <= tb.hi[i] && tb.lo[i] <= ta.hi[i]);
        if boxes_meet && !ta.interferes(&tb) {
            apart_boxes_meet += 1;
        }
        let _ = boxes;
    }
    assert!(meet > 20, "too few meeting pairs to test: {meet}");
    assert!(
        apart_boxes_meet > 0,
        "triboxes never pruned better than boxes"
    );
}
