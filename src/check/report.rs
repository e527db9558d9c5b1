//! A comparison's report as text lines and as `kepler-diff/1` JSON (what `kepler check` and
//! `kepler diff` print, `--report json` for the latter).

use std::fmt::Write as _;

use super::compare::{Change, ChangeKind, Comparison};
use crate::scene::flatten::write_num;

/// "1 face" or "N faces".
pub(crate) fn faces(n: usize) -> String {
    if n == 1 {
        "1 face".into()
    } else {
        format!("{n} faces")
    }
}

impl Comparison {
    /// True when no face changed by more than the tolerance.
    pub fn is_same(&self) -> bool {
        self.changes.is_empty()
    }

    /// The report as text: a note when the cameras differ, one line per changed face
    /// (`face ID (OBJECT): ...` with both areas, their delta, the symmetric difference and
    /// the relative change), then a summary line (`ok: ...` or `N faces changed ...`).
    pub fn to_text(&self) -> String {
        let mut s = String::new();
        if self.camera_differs {
            s.push_str("note: the camera differs from the golden's\n");
        }
        for c in &self.changes {
            s.push_str(&change_line(c));
            s.push('\n');
        }
        let tol = self.tol;
        let compared = faces(self.compared);
        if self.is_same() {
            let _ = writeln!(
                s,
                "ok: {compared} compared, none changed by more than {tol:e}"
            );
        } else {
            let changed = faces(self.changes.len());
            let _ = writeln!(
                s,
                "{changed} changed (of {compared} compared, tolerance {tol:e})"
            );
        }
        s
    }

    /// The report as `kepler-diff/1` JSON: the tolerance, the floor, the counts, whether the
    /// cameras differ, and each changed face with `id`, `object`, `kind` (changed, added,
    /// removed), `golden_area`, `current_area`, `area_delta`, `xor_area` and `relative`.
    /// One changed face per line; numbers in the shortest form that reads back the same.
    pub fn to_json(&self) -> String {
        let mut s = String::from("{\"format\":\"kepler-diff/1\",\"tol\":");
        number(&mut s, self.tol);
        s.push_str(",\"floor\":");
        number(&mut s, self.floor);
        let _ = write!(
            s,
            ",\"compared\":{},\"changed\":{},\"camera_differs\":{},\n\"changes\":[",
            self.compared,
            self.changes.len(),
            self.camera_differs
        );
        for (i, c) in self.changes.iter().enumerate() {
            s.push_str(if i == 0 { "\n" } else { ",\n" });
            let object = serde_json::to_string(&c.object).unwrap_or_else(|_| "\"\"".into());
            let _ = write!(
                s,
                "{{\"id\":{},\"object\":{object},\"kind\":\"{}\"",
                c.id,
                c.kind.name()
            );
            for (key, x) in [
                ("golden_area", c.golden_area),
                ("current_area", c.current_area),
                ("area_delta", c.area_delta()),
                ("xor_area", c.xor_area),
                ("relative", c.relative),
            ] {
                let _ = write!(s, ",\"{key}\":");
                number(&mut s, x);
            }
            s.push('}');
        }
        s.push_str("\n]}\n");
        s
    }
}

/// One changed face as a line of text.
fn change_line(c: &Change) -> String {
    let what = match c.kind {
        ChangeKind::Changed => "changed",
        ChangeKind::Added => "newly visible",
        ChangeKind::Removed => "no longer visible",
    };
    format!(
        "face {} ({}): {what} by {:.3e} of its size: area {:.6e} -> {:.6e} ({:+.3e}), symmetric difference {:.3e}",
        c.id,
        c.object,
        c.relative,
        c.golden_area,
        c.current_area,
        c.area_delta(),
        c.xor_area
    )
}

/// A JSON number (null when not finite).
fn number(s: &mut String, x: f64) {
    if x.is_finite() {
        write_num(s, x);
    } else {
        s.push_str("null");
    }
}

#[cfg(test)]
mod tests {
    use crate::check::{diff, SetFace, VisibleSet};

    fn square(x: f64, s: f64) -> SetFace {
        SetFace {
            object: "a \"b\"".into(),
            visible: vec![vec![vec![[x, 0.], [x + s, 0.], [x + s, s], [x, s]]]],
            section: false,
        }
    }

    #[test]
    fn text_and_json_name_every_change() {
        let mut g = VisibleSet::default();
        g.faces.insert(1, square(0., 1.));
        g.faces.insert(2, square(5., 1.));
        let mut c = g.clone();
        c.faces.insert(1, square(0., 2.));
        c.faces.remove(&2);
        c.faces.insert(3, square(9., 1.));
        c.matrix = Some(vec![1.0; 16]);
        let r = diff(&g, &c, 1e-9);
        let text = r.to_text();
        assert!(text.starts_with("note: the camera differs"), "{text}");
        assert!(text.contains("face 1 (a \"b\"): changed by 7.500e-1 of its size"));
        assert!(text.contains("face 2 (a \"b\"): no longer visible by 1.000e0"));
        assert!(text.contains("face 3 (a \"b\"): newly visible"));
        assert!(text.ends_with("3 faces changed (of 3 faces compared, tolerance 1e-9)\n"));
        let v: serde_json::Value = serde_json::from_str(&r.to_json()).unwrap();
        assert_eq!(v["format"], "kepler-diff/1");
        assert_eq!(
            (v["changed"].as_u64(), v["compared"].as_u64()),
            (Some(3), Some(3))
        );
        assert_eq!(v["camera_differs"], true);
        let first = &v["changes"][0];
        assert_eq!(first["object"], "a \"b\"");
        assert_eq!(first["kind"], "changed");
        let num = |k: &str| first[k].as_f64().unwrap();
        assert_eq!((num("golden_area"), num("current_area")), (1.0, 4.0));
        assert_eq!((num("area_delta"), num("relative")), (3.0, 0.75));
        assert!((num("xor_area") - 3.0).abs() < 1e-12);
        let kinds: Vec<_> = (0..3).map(|i| v["changes"][i]["kind"].clone()).collect();
        assert_eq!(kinds, ["changed", "removed", "added"]);
        // One of one: singular.
        let one = diff(&g, &g, 1e-9);
        assert_eq!(
            one.to_text(),
            "ok: 2 faces compared, none changed by more than 1e-9\n"
        );
        g.faces.remove(&2);
        let mut h = g.clone();
        h.faces.insert(1, square(0., 2.));
        assert!(diff(&g, &h, 0.1)
            .to_text()
            .ends_with("1 face changed (of 1 face compared, tolerance 1e-1)\n"));
        let empty = diff(&h, &h, 0.0).to_json();
        assert!(empty.ends_with("\"changes\":[\n]}\n"), "{empty}");
        assert!(serde_json::from_str::<serde_json::Value>(&empty).is_ok());
    }
}
