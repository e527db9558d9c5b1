//! The town benchmark: a wall in front of N detailed buildings (instances of a few
//! prototypes), timed stage by stage with inboxes on and off. Writes out/town-bench.csv and
//! out/town-bench.svg. Run with `cargo bench --bench town` (optionally `-- 10,30` for the Ns).
//! The same measurement is part of `kepler bench`; both use the one copy of its code.

#[allow(dead_code)]
#[path = "../src/cmd/bench/chart.rs"]
mod chart;
#[allow(dead_code)]
#[path = "../src/cmd/bench/town.rs"]
mod town;

fn main() {
    let ns: Vec<usize> = std::env::args()
        .skip(1)
        .find(|a| !a.starts_with('-'))
        .map(|a| a.split(',').filter_map(|x| x.parse().ok()).collect())
        .unwrap_or_else(|| town::TOWN_NS.to_vec());
    let mut rows = Vec::new();
    for &n in &ns {
        for use_inbox in [true, false] {
            let runs = if n >= 300 { 3 } else { 5 };
            let r = town::measure(n, use_inbox, runs);
            eprintln!(
                "N={n:5} faces={:8} inbox={use_inbox:5} load {:9.3} prepare {:9.3} view {:9.3} visibility {:10.3} ms  visible faces {}",
                r.faces, r.ms[0], r.ms[1], r.ms[2], r.ms[3], r.visible_faces
            );
            rows.push(r);
        }
    }
    if let Some(g) = town::growth(&rows, true) {
        eprintln!("visibility with inboxes, largest N / smallest N: {g:.2}x");
    }
    let _ = std::fs::create_dir_all("out");
    let _ = std::fs::write("out/town-bench.csv", town::csv(&rows));
    let _ = std::fs::write("out/town-bench.svg", chart::to_svg(&town::chart(&rows)));
}
