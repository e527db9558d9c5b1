//! The bench's outputs: CSV files, SVG charts and the markdown summary (also printed).

use std::fmt::Write as _;
use std::io::Write as _;
use std::path::Path;

use anyhow::{Context, Result};

use super::accuracy::Method;
use super::chart::{self, Chart, Series, Style};
use super::suite::{ViewKind, STAGES};
use super::town::{self, TownRow};
use super::{AccuracyRow, CaseRow};

/// Writes one output file, naming it in the error.
fn put(dir: &Path, name: &str, text: &str) -> Result<()> {
    let p = dir.join(name);
    std::fs::write(&p, text).with_context(|| format!("{}", p.display()))
}

/// Writes every CSV and chart into `dir`, and the summary (also to standard output).
pub fn write_all(
    dir: &Path,
    rows: &[CaseRow],
    acc: &[AccuracyRow],
    town_rows: &[TownRow],
    missing: &[String],
) -> Result<()> {
    put(dir, "times.csv", &times_csv(rows))?;
    put(dir, "size.svg", &chart::to_svg(&size_chart(rows)))?;
    if !acc.is_empty() {
        put(dir, "accuracy.csv", &accuracy_csv(acc))?;
        for subject in subjects(acc) {
            let mine: Vec<&AccuracyRow> = acc.iter().filter(|r| r.subject == subject).collect();
            put(
                dir,
                &format!("accuracy-{subject}.svg"),
                &chart::to_svg(&accuracy_chart(&mine)),
            )?;
        }
    }
    if !town_rows.is_empty() {
        put(dir, "town.csv", &town::csv(town_rows))?;
        put(dir, "town.svg", &chart::to_svg(&town::chart(town_rows)))?;
    }
    let summary = summary(rows, acc, town_rows, missing);
    put(dir, "summary.md", &summary)?;
    // A closed pipe (`| head`) is not an error.
    let _ = writeln!(std::io::stdout().lock(), "{summary}");
    Ok(())
}

/// The accuracy subjects in order of first appearance.
fn subjects(acc: &[AccuracyRow]) -> Vec<String> {
    let mut s: Vec<String> = Vec::new();
    for r in acc {
        if !s.contains(&r.subject) {
            s.push(r.subject.clone());
        }
    }
    s
}

/// The stage timings as CSV: one row per case and view, medians and least total.
pub fn times_csv(rows: &[CaseRow]) -> String {
    let mut s = String::from("case,family,view,faces,runs");
    for st in STAGES {
        let _ = write!(s, ",{st}_ms");
    }
    s.push_str(",total_ms,total_min_ms,peak_kb,start_kb,kb_per_face\n");
    for r in rows {
        let _ = write!(
            s,
            "{},{},{},{},{}",
            r.case.name,
            r.case.family,
            r.view.name(),
            r.faces,
            r.runs.len()
        );
        for m in r.stage_medians() {
            let _ = write!(s, ",{m:.3}");
        }
        let (med, min) = r.total();
        let _ = write!(s, ",{med:.3},{min:.3}");
        match r.memory {
            Some((peak, base)) => {
                let per = (peak.saturating_sub(base)) as f64 / r.faces.max(1) as f64;
                let _ = writeln!(s, ",{peak},{base},{per:.3}");
            }
            None => s.push_str(",,,\n"),
        }
    }
    s
}

/// The accuracy points as CSV.
pub fn accuracy_csv(acc: &[AccuracyRow]) -> String {
    let mut s = String::from(
        "subject,faces,method,param,metric,time_ms,time_min_ms,error,reference,error_rel,item_median_rel,check\n",
    );
    for r in acc {
        let reference = if r.method.metric() == "area" {
            r.reference.0
        } else {
            r.reference.1
        };
        let check = r.check.map(|c| format!("{c:.3e}")).unwrap_or_default();
        let _ = writeln!(
            s,
            "{},{},{},{},{},{:.3},{:.3},{:.6e},{:.6e},{:.6e},{:.6e},{check}",
            r.subject,
            r.faces,
            r.method.name(),
            r.method.param(),
            r.method.metric(),
            r.ms.0,
            r.ms.1,
            r.error.total,
            reference,
            r.error.relative,
            r.error.item_median
        );
    }
    s
}

/// Least-squares slope of log10(y) against log10(x).
pub fn log_slope(pts: &[(f64, f64)]) -> Option<f64> {
    let p: Vec<(f64, f64)> = pts
        .iter()
        .filter(|p| p.0 > 0.0 && p.1 > 0.0)
        .map(|p| (p.0.log10(), p.1.log10()))
        .collect();
    if p.len() < 2 {
        return None;
    }
    let n = p.len() as f64;
    let (mx, my) = (
        p.iter().map(|q| q.0).sum::<f64>() / n,
        p.iter().map(|q| q.1).sum::<f64>() / n,
    );
    let sxx: f64 = p.iter().map(|q| (q.0 - mx).powi(2)).sum();
    let sxy: f64 = p.iter().map(|q| (q.0 - mx) * (q.1 - my)).sum();
    (sxx > 0.0).then(|| sxy / sxx)
}

/// (faces, median total ms) of a family's three-quarter rows, by size.
fn family_points(rows: &[CaseRow], family: &str, view: ViewKind) -> Vec<(f64, f64)> {
    let mut p: Vec<(f64, f64)> = rows
        .iter()
        .filter(|r| r.case.family == family && r.view == view)
        .map(|r| (r.faces as f64, r.total().0))
        .collect();
    p.sort_by(|a, b| a.0.total_cmp(&b.0));
    p
}

/// Time against size: median total time of every case (three-quarter view), log-log, with a
/// dashed line of slope 1 through the generated scenes' geometric mean.
pub fn size_chart(rows: &[CaseRow]) -> Chart {
    let v = ViewKind::ThreeQuarter;
    let mut series = Vec::new();
    let mut notes = vec![
        "median total time (load, prepare, view, visibility, emit JSON+SVG), three-quarter view"
            .to_string(),
    ];
    let mut gen = Vec::new();
    for (family, colour) in [("field", "#1f77b4"), ("terrain", "#2ca02c")] {
        let p = family_points(rows, family, v);
        if let Some(s) = log_slope(
            &p.iter()
                .copied()
                .filter(|q| q.0 >= 1000.0)
                .collect::<Vec<_>>(),
        ) {
            notes.push(format!(
                "{family}: slope {s:.2} above 1k faces (x{:.1} time per 10x faces)",
                10f64.powf(s)
            ));
        }
        gen.extend(p.iter().copied());
        series.push(Series::new(
            &format!("generated {family}"),
            colour,
            Style::LineMarkers,
            p,
        ));
    }
    let models: Vec<&CaseRow> = rows
        .iter()
        .filter(|r| r.case.family == "model" && r.view == v)
        .collect();
    let mut m = Series::new(
        "shared meshes",
        "#d62728",
        Style::Markers,
        models
            .iter()
            .map(|r| (r.faces as f64, r.total().0))
            .collect(),
    );
    m.labels = models.iter().map(|r| r.case.name.clone()).collect();
    series.push(m);
    if let Some(r) = slope_one(&gen) {
        series.push(r);
    }
    Chart {
        title: "Time against scene size".into(),
        notes,
        x_label: "faces".into(),
        y_label: "time, ms".into(),
        log_x: true,
        log_y: true,
        series,
    }
}

/// A dashed reference line y = c·x over the points' x range, through their geometric mean.
fn slope_one(pts: &[(f64, f64)]) -> Option<Series> {
    let p: Vec<&(f64, f64)> = pts.iter().filter(|p| p.0 > 0.0 && p.1 > 0.0).collect();
    if p.is_empty() {
        return None;
    }
    let logc = p.iter().map(|q| q.1.log10() - q.0.log10()).sum::<f64>() / p.len() as f64;
    let c = 10f64.powf(logc);
    let lo = p.iter().map(|q| q.0).fold(f64::INFINITY, f64::min);
    let hi = p.iter().map(|q| q.0).fold(0.0, f64::max);
    Some(Series::new(
        "slope 1 (time ∝ faces)",
        "#888888",
        Style::Dashed,
        vec![(lo, c * lo), (hi, c * hi)],
    ))
}

/// Time against accuracy for one subject: every method's median time and relative error,
/// kepler's exact points drawn at a floor below the smallest measured error.
pub fn accuracy_chart(acc: &[&AccuracyRow]) -> Chart {
    let least = acc
        .iter()
        .map(|r| r.error.relative)
        .filter(|&e| e > 0.0)
        .fold(f64::INFINITY, f64::min);
    let floor = if least.is_finite() {
        10f64.powf(least.log10().floor() - 1.0)
    } else {
        1e-6
    };
    let pick = |f: &dyn Fn(Method) -> bool| -> Vec<&&AccuracyRow> {
        acc.iter().filter(|r| f(r.method)).collect()
    };
    let mut series = Vec::new();
    let mut add = |rows: Vec<&&AccuracyRow>,
                   label: &str,
                   colour: &str,
                   style,
                   text: &dyn Fn(Method) -> String| {
        let mut s = Series::new(
            label,
            colour,
            style,
            rows.iter()
                .map(|r| (r.ms.0, r.error.relative.max(floor)))
                .collect(),
        );
        s.labels = rows.iter().map(|r| text(r.method)).collect();
        series.push(s);
    };
    add(
        pick(&|m| matches!(m, Method::ZBuffer(_))),
        "z-buffer (area error)",
        "#d62728",
        Style::LineMarkers,
        &|m| format!("{} px", m.param()),
    );
    add(
        pick(&|m| matches!(m, Method::Rays(_))),
        "ray sampling (line error)",
        "#ff7f0e",
        Style::LineMarkers,
        &|m| format!("step 1/{}", m.param()),
    );
    add(
        pick(&|m| matches!(m, Method::Lod(_))),
        "kepler --lod (area error by object)",
        "#2ca02c",
        Style::LineMarkers,
        &|m| format!("lod {} px", m.param()),
    );
    add(
        pick(&|m| m == Method::Exact),
        "kepler exact polygons",
        "#1f77b4",
        Style::Markers,
        &|_| "exact".into(),
    );
    add(
        pick(&|m| m == Method::ExactLines),
        "kepler exact lines",
        "#17becf",
        Style::Markers,
        &|_| "exact lines".into(),
    );
    let r0 = acc[0];
    let check = acc.iter().find_map(|r| r.check);
    let mut notes = vec![
        "area error: sum over faces of |P_f sym.diff. V_f| / sum of |V_f| (V_f exact visible region, P_f its pixels)".to_string(),
        "lod error: sum over drawn objects of |exact region sym.diff. substitute's region| / sum of |V_f|".to_string(),
        "line error: sum over edges of |sampled sym.diff. exact visible pieces| / exact visible length".to_string(),
        format!(
            "kepler's own error is 0 (f64-exact); drawn at {}{}",
            chart::number(floor),
            check.map_or(String::new(), |c| format!(
                "; independent check |sum |V_f| - |union P_f|| / |union P_f| = {c:.1e}"
            ))
        ),
    ];
    notes.push(format!(
        "time: view + method from a loaded, prepared scene; median of runs; three-quarter view, {} faces",
        r0.faces
    ));
    Chart {
        title: format!("Time against accuracy: {}", r0.subject),
        notes,
        x_label: "time, ms".into(),
        y_label: "relative error".into(),
        log_x: true,
        log_y: true,
        series,
    }
}

/// The markdown summary: stage table, targets, accuracy table, town table.
pub fn summary(
    rows: &[CaseRow],
    acc: &[AccuracyRow],
    town_rows: &[TownRow],
    missing: &[String],
) -> String {
    let mut s = String::new();
    stage_table(&mut s, rows);
    targets(&mut s, rows);
    if !acc.is_empty() {
        accuracy_table(&mut s, acc);
    }
    if !town_rows.is_empty() {
        town_table(&mut s, town_rows);
    }
    for m in missing {
        let _ = writeln!(s, "\nskipped (not found): {m}");
    }
    s
}

/// Milliseconds with sensible precision.
fn ms(v: f64) -> String {
    if v >= 100.0 {
        format!("{v:.0}")
    } else if v >= 10.0 {
        format!("{v:.1}")
    } else {
        format!("{v:.2}")
    }
}

fn stage_table(s: &mut String, rows: &[CaseRow]) {
    let _ = writeln!(s, "### Stage times (median ms)\n");
    let _ = writeln!(
        s,
        "| case | view | faces | load | prepare | view | visibility | emit | total | min total | peak MB | KB/face |"
    );
    let _ = writeln!(
        s,
        "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"
    );
    for r in rows {
        let m = r.stage_medians();
        let (med, min) = r.total();
        let (peak, per) = match r.memory {
            Some((p, b)) => (
                format!("{:.1}", p as f64 / 1024.0),
                format!("{:.2}", p.saturating_sub(b) as f64 / r.faces.max(1) as f64),
            ),
            None => ("-".into(), "-".into()),
        };
        let _ = writeln!(
            s,
            "| {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {peak} | {per} |",
            r.case.name,
            r.view.name(),
            r.faces,
            ms(m[0]),
            ms(m[1]),
            ms(m[2]),
            ms(m[3]),
            ms(m[4]),
            ms(med),
            ms(min)
        );
    }
}

fn targets(s: &mut String, rows: &[CaseRow]) {
    let _ = writeln!(s, "\n### Targets\n");
    for (name, limit) in [("stanford-bunny", 500.0), ("nefertiti", 700.0)] {
        for r in rows.iter().filter(|r| r.case.name == name) {
            let (med, min) = r.total();
            let _ = writeln!(
                s,
                "- {name} ({} faces), {}: median {} ms, min {} ms (target < {limit} ms: {})",
                r.faces,
                r.view.name(),
                ms(med),
                ms(min),
                if med < limit { "met" } else { "MISSED" }
            );
        }
    }
    for family in ["field", "terrain"] {
        for &v in &ViewKind::ALL {
            let p = family_points(rows, family, v);
            let big: Vec<(f64, f64)> = p.iter().copied().filter(|q| q.0 >= 1000.0).collect();
            let Some(slope) = log_slope(&big) else {
                continue;
            };
            let decade = worst_decade(&p);
            let _ = writeln!(
                s,
                "- growth, {family} {}: x{:.1} time per 10x faces (least squares above 1k faces){} (target <= 12)",
                v.name(),
                10f64.powf(slope),
                decade.map_or(String::new(), |d| format!("; worst single step x{d:.1} per 10x")),
            );
        }
    }
    let mut worst: Option<(&CaseRow, f64)> = None;
    for r in rows {
        if let Some((p, b)) = r.memory {
            let per = p.saturating_sub(b) as f64 / r.faces.max(1) as f64;
            if r.faces >= 10000 && worst.is_none_or(|w| per > w.1) {
                worst = Some((r, per));
            }
        }
    }
    if let Some((r, per)) = worst {
        let _ = writeln!(
            s,
            "- peak memory: at most {per:.2} KB per face above the process's start over scenes of 10k+ faces ({} {}; target < 1 KB)",
            r.case.name,
            r.view.name()
        );
    }
}

/// The largest time ratio between consecutive sizes, scaled to a 10× step in faces.
fn worst_decade(p: &[(f64, f64)]) -> Option<f64> {
    p.windows(2)
        .filter(|w| w[0].0 >= 1000.0 && w[1].0 > w[0].0)
        .map(|w| (w[1].1 / w[0].1).powf(1.0 / (w[1].0 / w[0].0).log10()))
        .fold(None, |a: Option<f64>, x| Some(a.map_or(x, |a| a.max(x))))
}

fn accuracy_table(s: &mut String, acc: &[AccuracyRow]) {
    let _ = writeln!(s, "\n### Time against accuracy (three-quarter view)\n");
    let _ = writeln!(
        s,
        "| subject | method | parameter | median ms | min ms | relative error | median per face/edge |"
    );
    let _ = writeln!(s, "|---|---|---:|---:|---:|---:|---:|");
    for r in acc {
        let param = match r.method {
            Method::ZBuffer(px) => format!("{px} px"),
            Method::Rays(k) => format!("step 1/{k}"),
            Method::Lod(px) => format!("{px} px of {}", super::accuracy::LOD_SIZE),
            _ => String::new(),
        };
        let err = match r.check {
            Some(c) => format!("0 (check {c:.1e})"),
            None if r.error.total == 0.0 => "0".into(),
            None => format!("{:.2e}", r.error.relative),
        };
        let _ = writeln!(
            s,
            "| {} | {} | {param} | {} | {} | {err} | {:.2e} |",
            r.subject,
            r.method.name(),
            ms(r.ms.0),
            ms(r.ms.1),
            r.error.item_median
        );
    }
}

fn town_table(s: &mut String, rows: &[TownRow]) {
    let _ = writeln!(s, "\n### Town (median ms)\n");
    let _ = writeln!(
        s,
        "| N | faces | layout | inboxes | build | prepare | cull | view | pass | visibility | visible faces |"
    );
    let _ = writeln!(s, "|---:|---:|---|---|---:|---:|---:|---:|---:|---:|---:|");
    for r in rows {
        let _ = writeln!(
            s,
            "| {} | {} | {:?} | {} | {} | {} | {} | {} | {} | {} | {} |",
            r.n,
            r.faces,
            r.layout,
            if r.inbox { "on" } else { "off" },
            ms(r.ms[0]),
            ms(r.ms[1]),
            ms(r.ms[2]),
            ms(r.ms[3]),
            ms(r.ms[4]),
            ms(r.visibility()),
            r.visible_faces
        );
    }
    for (layout, inbox, label, _) in town::SERIES {
        if let Some(g) = town::growth(rows, layout, inbox) {
            let _ = writeln!(s, "\nvisibility, largest N / smallest N, {label}: x{g:.2}");
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn slopes_and_steps() {
        let p = [(1000.0, 10.0), (10000.0, 100.0), (100000.0, 1000.0)];
        assert!((log_slope(&p).unwrap() - 1.0).abs() < 1e-12);
        assert!((worst_decade(&p).unwrap() - 10.0).abs() < 1e-9);
        let q = [(1000.0, 10.0), (3000.0, 90.0)];
        // Nine times the time for three times the faces: 2 decades of time per decade of faces.
        assert!((worst_decade(&q).unwrap() - 100.0).abs() < 1e-6);
        assert!(log_slope(&[(1.0, 1.0)]).is_none());
    }
}
