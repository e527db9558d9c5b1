//! The town benchmark: a wall in front of N detailed buildings (instances of a few
//! prototypes), timed stage by stage with inboxes on and off, with the buildings in districts
//! and blocks and flat under the root. Writes out/town-bench.csv and
//! out/town-bench.svg. Run with `cargo bench -p kepler-hsr-bench --bench town` (optionally
//! `-- 10,30` for the Ns). The same measurement is part of `kepler-bench`; both use the one
//! copy of its code in the harness library.

use kepler_bench::{chart, town};

fn main() {
    let ns: Vec<usize> = std::env::args()
        .skip(1)
        .find(|a| !a.starts_with('-'))
        .map(|a| a.split(',').filter_map(|x| x.parse().ok()).collect())
        .unwrap_or_else(|| town::TOWN_NS.to_vec());
    let mut rows = Vec::new();
    for &n in &ns {
        for (layout, use_inbox, _, _) in town::SERIES {
            let runs = if n >= 300 { 5 } else { 9 };
            let r = town::measure(n, layout, use_inbox, runs);
            eprintln!(
                "N={n:5} faces={:7} {layout:?} inbox={use_inbox:5} load {:7.3} prepare {:7.3} cull {:7.3} view {:8.3} pass {:8.3} visibility {:8.3} ms  visible faces {}",
                r.faces, r.ms[0], r.ms[1], r.ms[2], r.ms[3], r.ms[4], r.visibility(), r.visible_faces
            );
            rows.push(r);
        }
    }
    for (layout, inbox, label, _) in town::SERIES {
        if let Some(g) = town::growth(&rows, layout, inbox) {
            eprintln!("visibility, {label}: largest N / smallest N: {g:.2}x");
        }
    }
    let out = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../out");
    let _ = std::fs::create_dir_all(&out);
    let _ = std::fs::write(out.join("town-bench.csv"), town::csv(&rows));
    let _ = std::fs::write(
        out.join("town-bench.svg"),
        chart::to_svg(&town::chart(&rows)),
    );
}
