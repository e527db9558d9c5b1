"""Render time through Python against the command, paired: for each run, the command as a
whole process and then load + render + JSON in this process, alternating; medians and the
median of the paired ratios.

    python python/bench/vs_cli.py MESH [--runs N] [--kepler target/release/kepler]
"""

import argparse
import statistics
import subprocess
import tempfile
import time
from pathlib import Path

import kepler


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("scene")
    ap.add_argument("--runs", type=int, default=11)
    ap.add_argument("--kepler", default="target/release/kepler")
    a = ap.parse_args()
    out = Path(tempfile.mkdtemp()) / "r.json"
    cli, py = [], []
    for _ in range(a.runs):
        t = time.perf_counter()
        subprocess.run([a.kepler, "render", a.scene, "--json", str(out), "-q"], check=True)
        cli.append(time.perf_counter() - t)
        t = time.perf_counter()
        out.write_text(kepler.load(a.scene).render().to_json())
        py.append(time.perf_counter() - t)
    ratios = [p / c for p, c in zip(py, cli)]
    print(f"{a.scene}: {a.runs} paired runs")
    print(f"  command (whole process) median {statistics.median(cli):.4f} s")
    print(f"  Python (in process)     median {statistics.median(py):.4f} s")
    print(f"  Python / command: median of paired ratios {statistics.median(ratios):.3f}")


if __name__ == "__main__":
    main()
