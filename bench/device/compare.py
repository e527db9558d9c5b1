#!/usr/bin/env python3
"""Two kepler builds on the lent many-core machine: whole processes timed through wait4.

Issue 35's 16-core checks, as one prepared script (the machine is lent for minutes). The
folder this file is copied into (an ignored `.dev/` at the repository's root, carried with
the `run` tool's `carry: [".dev"]`) holds: `k0/kepler` and `k1/kepler` (the base and the
new build, stripped: `strip -o .dev/k0/kepler target/release/kepler`), `kepler-bench`
(for the 10M terrain, made there), optionally `k1x` (a scratch build that prints each
layer's kick time when `KDBG` is set and takes `KLANES`), and `m/` with stanford-bunny,
nefertiti and ogre from ../shared/models (never committed). Run there as
`LIMIT=530 python3 .dev/compare.py` with a `timeout_s` of about 590: labelled jobs in
alternating rounds, CSV files and every run's stderr (`--stats`) written to `$OUT`, the
10M terrain's one-thread run only if time is left. About 330 s on 16 cores.
"""
import os, time, subprocess

D = os.path.dirname(os.path.abspath(__file__))
OUT = os.environ.get("OUT", "/tmp/out")
T = "/tmp/kt"
os.makedirs(T, exist_ok=True)
os.makedirs(OUT, exist_ok=True)
LOG = open(os.path.join(OUT, "stderr.log"), "w")
START = time.time()
LIMIT = float(os.environ.get("LIMIT", "540"))


def left():
    return LIMIT - (time.time() - START)


def run(label, argv, threads, csv, extra_env=None, rnd=0):
    for f in os.listdir(T):
        if f.startswith("o."):
            os.remove(os.path.join(T, f))
    env = dict(os.environ, RAYON_NUM_THREADS=str(threads))
    if extra_env:
        env.update(extra_env)
    LOG.write(f"### {label} round {rnd}\n")
    LOG.flush()
    t0 = time.time()
    p = subprocess.Popen(argv, env=env, stdout=LOG, stderr=LOG)
    _, status, ru = os.wait4(p.pid, 0)
    wall = time.time() - t0
    cpu = ru.ru_utime + ru.ru_stime
    line = f"{label},{threads},{rnd},{wall:.4f},{cpu:.4f},{ru.ru_maxrss},{status}\n"
    csv.write(line)
    csv.flush()
    return wall


def kep(b):
    return [os.path.join(D, b, "kepler")] if b in ("k0", "k1") else [os.path.join(D, b)]


def mesh(m):
    return os.path.join(D, "m", m + ".obj")


def render(b, m, extra):
    return kep(b) + ["render", "-q", m, "--dir", "-1,-2,-3"] + extra


DEF = lambda: ["--json", T + "/o.json", "--svg", T + "/o.svg"]
MESHES = ["stanford-bunny", "nefertiti", "ogre"]

print(subprocess.run(["nproc"], capture_output=True, text=True).stdout, file=LOG)
LOG.write(open("/proc/cpuinfo").read().split("\n\n")[0] + "\n")

# A. meshes, default drawing, 1 and 16 threads, k0 and k1, 5 rounds (1 warm-up uncounted: round -1).
with open(os.path.join(OUT, "mesh.csv"), "w") as csv:
    for rnd in range(-1, 5):
        for m in MESHES:
            for th in (1, 16):
                for b in ("k0", "k1"):
                    run(f"{b}-{m}-{th}", render(b, mesh(m), DEF()), th, csv, rnd=rnd)
print("A done", time.time() - START, file=LOG, flush=True)

# B. stage tables (--stats): nefertiti and ogre, k1 at 1,2,4,8,16 threads, k0 at 16; 2 rounds.
with open(os.path.join(OUT, "stats.csv"), "w") as csv:
    for rnd in range(2):
        for m in ("nefertiti", "ogre"):
            for th in (1, 2, 4, 8, 16):
                run(f"k1-stats-{m}-{th}", render("k1", mesh(m), DEF() + ["--stats"]), th, csv, rnd=rnd)
            run(f"k0-stats-{m}-16", render("k0", mesh(m), DEF() + ["--stats"]), 16, csv, rnd=rnd)
print("B done", time.time() - START, file=LOG, flush=True)

# C. hidden drawing: nefertiti SVG and JSON at 1 and 16, k0/k1, 3 rounds; bunny, ogre SVG at 16.
HID = ["--edges", "all", "--hidden"]
with open(os.path.join(OUT, "hidden.csv"), "w") as csv:
    for rnd in range(3):
        for b in ("k0", "k1"):
            for th in (1, 16):
                run(f"{b}-nef-hsvg-{th}", render(b, mesh("nefertiti"), HID + ["--svg", T + "/o.svg", "--stats"]), th, csv, rnd=rnd)
                run(f"{b}-nef-hjson-{th}", render(b, mesh("nefertiti"), HID + ["--json", T + "/o.json"]), th, csv, rnd=rnd)
            for m in ("stanford-bunny", "ogre"):
                run(f"{b}-{m}-hsvg-16", render(b, mesh(m), HID + ["--svg", T + "/o.svg"]), 16, csv, rnd=rnd)
print("C done", time.time() - START, file=LOG, flush=True)

# D. lanes sweep (k1x prints KDBG lines: each layer's kick phase in ms), 16 threads.
with open(os.path.join(OUT, "lanes.csv"), "w") as csv:
    for rnd in range(3 if os.path.exists(os.path.join(D, "k1x")) else 0):
        for lanes in (1, 2, 4, 8, 16):
            env = {"KDBG": "1", "KLANES": str(lanes)}
            run(f"k1x-nef-def-L{lanes}", render("k1x", mesh("nefertiti"), DEF() + ["--stats"]), 16, csv, env, rnd)
            run(f"k1x-nef-hid-L{lanes}", render("k1x", mesh("nefertiti"), HID + ["--svg", T + "/o.svg", "--stats"]), 16, csv, env, rnd)
print("D done", time.time() - START, file=LOG, flush=True)

# E. 10M terrain: 16 threads k1 x3, k0 x2 alternating; then k1 one thread once if time allows.
t10 = "/tmp/t10m.obj"
subprocess.run([os.path.join(D, "kepler-bench"), "--terrain-obj", "10000000", t10], stdout=LOG, stderr=LOG)
print("terrain made", time.time() - START, file=LOG, flush=True)
TER = lambda b: render(b, t10, ["--up", "0,1,0", "--json", T + "/o.json", "--svg", T + "/o.svg", "--stats"])
with open(os.path.join(OUT, "t16.csv"), "w") as csv:
    for rnd in range(3):
        for b in ("k1", "k0"):
            if rnd == 2 and b == "k0":
                continue
            if left() < 30:
                break
            run(f"{b}-t10m-16", TER(b), 16, csv, rnd=rnd)
print("E16 done", time.time() - START, file=LOG, flush=True)
with open(os.path.join(OUT, "t1.csv"), "w") as csv:
    if left() > 170:
        run("k1-t10m-1", TER("k1"), 1, csv)
    else:
        csv.write(f"skipped,{left():.0f} s left\n")
print("all done", time.time() - START, file=LOG, flush=True)
