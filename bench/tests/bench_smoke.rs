//! Smoke test of `kepler bench --quick` on generated scenes only (no shared meshes), with a
//! tiny configuration: every output file is written and well formed. Nothing is timed here.

use std::process::Command;

#[test]
fn quick_bench_writes_csv_charts_and_table() {
    let out = std::env::temp_dir().join(format!("kepler-bench-smoke-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&out);
    let run = Command::new(env!("CARGO_BIN_EXE_kepler-bench"))
        .args([
            "--quick",
            "--runs",
            "1",
            "--max-faces",
            "1000",
            "--town",
            "1,2",
        ])
        .arg("--models")
        .arg(out.join("no-models-here"))
        .arg("--out")
        .arg(&out)
        .output()
        .expect("kepler runs");
    let stdout = String::from_utf8_lossy(&run.stdout);
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    assert!(stdout.contains("| field-1k | three-quarter |"), "{stdout}");
    assert!(
        stdout.contains("| field-1k | zbuffer | 256 px |"),
        "{stdout}"
    );
    assert!(String::from_utf8_lossy(&run.stderr).contains("not found, skipped"));
    let read =
        |n: &str| std::fs::read_to_string(out.join(n)).unwrap_or_else(|e| panic!("{n}: {e}"));
    let times = read("times.csv");
    assert!(times.starts_with("case,family,view,faces,runs,load_ms,"));
    // Header, two sizes of two families.
    assert_eq!(times.lines().count(), 5, "{times}");
    let acc = read("accuracy.csv");
    assert!(acc.contains("field-1k,") && acc.contains(",kepler-exact,0,area,"));
    // Header, two Ns of three series (districts/flat with inboxes, without inboxes).
    assert_eq!(read("town.csv").lines().count(), 7);
    for svg in ["size.svg", "town.svg", "accuracy-field-1k.svg"] {
        let s = read(svg);
        assert!(
            s.starts_with("<svg") && s.trim_end().ends_with("</svg>"),
            "{svg}"
        );
    }
    assert!(read("summary.md").contains("### Stage times"));
    let _ = std::fs::remove_dir_all(&out);
}
