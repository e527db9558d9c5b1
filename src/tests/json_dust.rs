//! No rounding dust in the canonical JSON: in every golden (tests/golden/*.json) and in the
//! JSON of every shared mesh present, read back as a user reads it, no two consecutive ring
//! points within one ulp of each other (nor within the merge distance δ of the rule in
//! docs/numerics.md), no polygon or hole of area within the rounding of zero (at most δ times
//! its perimeter), every ring valid, and every face's `area` that of its rings.

use std::path::Path;

use serde_json::Value;

use super::common::{load, models, prepare, SHARED_MESHES};
use crate::emit::write::dust::DUST_ULPS;
use crate::geom::poly2::{multipolygon_area, MultiPolygon, Pt2};
use crate::geom::ring_check::ring_defect;
use crate::{render, Camera, Outputs, RenderOptions};

/// The distance between two f64 in units in the last place (adjacent values: 1).
fn ulps(a: f64, b: f64) -> u64 {
    let key = |x: f64| {
        let i = x.to_bits() as i64;
        if i < 0 {
            i64::MIN - i
        } else {
            i
        }
    };
    key(a).abs_diff(key(b))
}

fn perimeter(r: &[Pt2]) -> f64 {
    (0..r.len())
        .map(|i| {
            let (a, b) = (r[i], r[(i + 1) % r.len()]);
            ((b[0] - a[0]).powi(2) + (b[1] - a[1]).powi(2)).sqrt()
        })
        .sum()
}

fn region(v: &Value) -> MultiPolygon {
    let pt = |p: &Value| [p[0].as_f64().unwrap(), p[1].as_f64().unwrap()];
    let arr = |v: &Value| v.as_array().unwrap().clone();
    arr(v)
        .iter()
        .map(|poly| {
            arr(poly)
                .iter()
                .map(|r| arr(r).iter().map(pt).collect())
                .collect()
        })
        .collect()
}

/// Every breach of the dust rule in a `kepler-visible/1` text, as lines.
fn dust(text: &str) -> Vec<String> {
    let v: Value = serde_json::from_str(text).unwrap();
    let faces: Vec<(u64, f64, MultiPolygon)> = v["faces"]
        .as_array()
        .unwrap()
        .iter()
        .map(|f| {
            let id = f["id"].as_u64().unwrap();
            (id, f["area"].as_f64().unwrap(), region(&f["visible"]))
        })
        .collect();
    let extent = faces
        .iter()
        .flat_map(|f| f.2.iter().flatten().flatten())
        .fold(0.0f64, |m, p| m.max(p[0].abs()).max(p[1].abs()));
    let delta = DUST_ULPS * f64::EPSILON * extent;
    let mut bad = Vec::new();
    for (id, area, m) in &faces {
        if *area != multipolygon_area(m) || m.is_empty() {
            bad.push(format!("face {id}: area {area} is not its rings'"));
        }
        for poly in m {
            let whole: f64 = poly.iter().map(|r| crate::geom::poly2::ring_area(r)).sum();
            let around: f64 = poly.iter().map(|r| perimeter(r)).sum();
            if whole.abs() <= delta * around {
                bad.push(format!(
                    "face {id}: polygon of area {whole:e} within rounding"
                ));
            }
            for (k, r) in poly.iter().enumerate() {
                if let Some(d) = ring_defect(r, k == 0) {
                    bad.push(format!("face {id}: ring {k} {d:?}"));
                }
                let hole = crate::geom::poly2::ring_area(r).abs();
                if k > 0 && hole <= delta * perimeter(r) {
                    bad.push(format!("face {id}: hole of area {hole:e} within rounding"));
                }
                for i in 0..r.len() {
                    let (a, b) = (r[i], r[(i + 1) % r.len()]);
                    if ulps(a[0], b[0]) <= 1 && ulps(a[1], b[1]) <= 1 {
                        bad.push(format!("face {id}: {a:?} {b:?} one ulp apart"));
                    } else if (a[0] - b[0]).abs() <= delta && (a[1] - b[1]).abs() <= delta {
                        bad.push(format!("face {id}: {a:?} {b:?} within {delta:e}"));
                    }
                }
            }
        }
    }
    bad
}

#[test]
fn the_rule_sees_dust() {
    let text = |visible: &str, area: &str| {
        format!(
            r#"{{"format":"kepler-visible/1","faces":[{{"id":0,"area":{area},"visible":{visible}}}]}}"#
        )
    };
    assert!(dust(&text("[[[[0,0],[1,0],[0,1]]]]", "0.5")).is_empty());
    assert_eq!(dust(&text("[[[[0,0],[1,0],[0,1]]]]", "0.4")).len(), 1);
    let one_ulp = text("[[[[0,0],[1,0],[1,1],[1,1.0000000000000002],[0,1]]]]", "1");
    let bad = dust(&one_ulp);
    assert!(bad.iter().any(|b| b.contains("one ulp")), "{bad:?}");
    let sliver = text("[[[[0,0],[1,0],[0,1e-300]]]]", "5e-301");
    assert!(dust(&sliver).iter().any(|b| b.contains("within rounding")));
    assert_eq!(ulps(-0.0, f64::from_bits(1)), 1);
    assert_eq!(ulps(1.0, 1.0 + f64::EPSILON), 1);
}

/// Defects this test knows of and tolerates: none. (Town's face 871, a vertex rounded an ulp
/// past a non-adjacent edge, was listed until the ring repair's nudge mended it, issue 31.)
const KNOWN: [&str; 0] = [];

#[test]
fn goldens_hold_no_rounding_dust() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/golden");
    let (mut checked, mut bad) = (0, Vec::new());
    for entry in std::fs::read_dir(&dir).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().and_then(|e| e.to_str()) != Some("json") {
            continue;
        }
        let name = path.file_name().unwrap().to_string_lossy().into_owned();
        let text = std::fs::read_to_string(&path).unwrap();
        bad.extend(dust(&text).into_iter().map(|b| format!("{name}: {b}")));
        checked += 1;
    }
    bad.sort();
    assert_eq!(bad, KNOWN, "over {checked} goldens");
    assert!(checked >= 15, "only {checked} goldens");
}

#[test]
fn shared_meshes_json_holds_no_rounding_dust() {
    let Some(dir) = models() else { return };
    for name in SHARED_MESHES {
        let path = dir.join(name);
        if !path.is_file() {
            kepler_testkit::skip(kepler_testkit::REQUIRE_MODELS_ENV, name, "absent");
            continue;
        }
        let mut scene = load(&path);
        prepare(&mut scene);
        let opts = RenderOptions {
            outputs: Outputs::default(),
            ..RenderOptions::default()
        };
        let r = render(&scene, &Camera::three_quarter(), &opts, &Default::default()).unwrap();
        let bad = dust(&r.to_json(false));
        assert!(bad.is_empty(), "{name}: {:#?}", &bad[..bad.len().min(10)]);
    }
}
