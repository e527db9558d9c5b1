#!/usr/bin/env python3
"""kepler against itself on two threads: each stage's time alone on one thread.

    python3 bench/peers/stages.py RUNS MESH [RENDER FLAGS] -- KEPLER [KEPLER ...]

Runs `KEPLER render -q MESH FLAGS --json J --svg S --stats` RUNS times for each binary in
turn (A B A B ...) with RAYON_NUM_THREADS=2 (or $THREADS) and prints, per binary, the
medians of each stage's serial milliseconds (its wall time times the serial share `--stats`
prints for it), of the run's serial share and of the stages' wall time summed; then each
stage's wall and CPU milliseconds (medians). Outputs go to a temporary folder that is
removed at the end.
"""
import os
import re
import statistics
import subprocess
import sys
import tempfile

STAGE = re.compile(r"time (\w+)\s+([\d.]+) ms\s+cpu\s+([\d.]+) ms\s+serial\s+([\d.]+)%")
SHARE = re.compile(r"serial share of the stages' wall time: ([\d.]+)%")


def main():
    if "--" not in sys.argv or len(sys.argv) < 5:
        sys.exit(__doc__)
    cut = sys.argv.index("--")
    runs, mesh, flags = int(sys.argv[1]), sys.argv[2], sys.argv[3:cut]
    bins = sys.argv[cut + 1:]
    # Per binary, by stage: serial ms (and the run's totals); (wall ms, CPU ms).
    got = {b: {} for b in bins}
    wall_cpu = {b: {} for b in bins}
    threads = os.environ.get("THREADS", "2")
    env = dict(os.environ, RAYON_NUM_THREADS=threads)
    with tempfile.TemporaryDirectory() as tmp:
        out = [os.path.join(tmp, "o.json"), os.path.join(tmp, "o.svg")]
        for _ in range(runs):
            for b in bins:
                argv = [b, "render", "-q", mesh, *flags, "--json", out[0], "--svg", out[1],
                        "--stats"]
                err = subprocess.run(argv, capture_output=True, text=True, env=env,
                                     check=True).stderr
                wall = 0.0
                for m in STAGE.finditer(err):
                    got[b].setdefault(m[1], []).append(float(m[2]) * float(m[4]) / 100)
                    wall_cpu[b].setdefault(m[1], []).append((float(m[2]), float(m[3])))
                    wall += float(m[2])
                got[b].setdefault("run's serial share %", []).append(float(SHARE.search(err)[1]))
                got[b].setdefault("stages' wall ms", []).append(wall)
    print("| serial ms, medians of %d, %s threads | %s |" % (runs, threads, " | ".join(bins)))
    print("|---|" + "--:|" * len(bins))
    for k in got[bins[0]]:
        cells = " | ".join("%.1f" % statistics.median(got[b][k]) for b in bins)
        print(f"| {k} | {cells} |")
    print()
    print("| stage: wall ms / CPU ms, medians | %s |" % " | ".join(bins))
    print("|---|" + "--:|" * len(bins))
    for k in wall_cpu[bins[0]]:
        med = lambda b, i: statistics.median(x[i] for x in wall_cpu[b][k])
        cells = " | ".join("%.1f / %.1f" % (med(b, 0), med(b, 1)) for b in bins)
        print(f"| {k} | {cells} |")


if __name__ == "__main__":
    main()
