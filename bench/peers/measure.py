#!/usr/bin/env python3
"""One-thread comparison of kepler with ln, Open CASCADE's polygonal HLR and
Blender's Line Art (see bench/peers/README.md for building the peers), with
kepler's own runs on two threads and its hidden drawing's JSON beside them.

Every run is a whole process, timed with os.wait4: wall seconds, user+sys
CPU seconds, peak RSS (ru_maxrss). Output files go to a scratch directory
that is emptied before each run. --warmup rounds (one by default, not
counted), then --rounds rounds; in each round every mesh runs every job in turn, so the
jobs alternate. Open CASCADE runs once per mesh (after the rounds), with a
timeout. Ratios are peer CPU / kepler CPU of the same round (above 1: kepler
is faster), and the table gives the median over the rounds.

    python3 bench/peers/measure.py --kepler /tmp/k/k0/kepler \
        --bin /work/peers/bin --models /work/shared/models --out /work/peers

writes OUT/table.csv (every run) and OUT/table.md (medians and ratios).
"""
import argparse
import csv
import os
import re
import shutil
import signal
import statistics
import subprocess
import sys
import tempfile
import time

MESHES = ["cube", "twocubes", "suzanne", "ico3", "beetle", "cow", "spot", "teapot",
          "fandisk", "grid100", "rocker-arm", "ico5", "stanford-bunny", "nefertiti", "ogre"]
DIR = "-1,-2,-3"
HERE = os.path.dirname(os.path.abspath(__file__))


def jobs(a, mesh, tmp):
    """name -> (argv, extra env); the jobs measured in every round."""
    k = a.kepler
    ln = os.path.join(a.bin, "ln-render")
    la = ["blender", "-b", "--factory-startup", "-t", "1", "--python",
          os.path.join(HERE, "lineart.py"), "--", mesh, os.path.join(tmp, "la.svg")]
    one, two = {"RAYON_NUM_THREADS": "1"}, {"RAYON_NUM_THREADS": "2"}
    render = [k, "render", "-q", mesh, "--dir", DIR, "--up", "0,1,0"]
    default = render + ["--json", os.path.join(tmp, "F.json"), "--svg", os.path.join(tmp, "G.svg")]
    hidden = render + ["--edges", "all", "--hidden"]
    hidden_svg = hidden + ["--svg", os.path.join(tmp, "G.svg")]
    return {
        "kepler": (default, one),
        "kepler_hidden": (hidden_svg, one),
        # The same render's JSON (the SVG/JSON goal), and both drawings on two threads.
        "kepler_hidden_json": (hidden + ["--json", os.path.join(tmp, "F.json")], one),
        "kepler_2t": (default, two),
        "kepler_hidden_2t": (hidden_svg, two),
        "ln_feature": ([ln, "-obj", mesh, "-dir", DIR, "-mode", "feature", "-crease", "30",
                        "-out", os.path.join(tmp, "F.svg"), "-size", "1024", "-step", "1"],
                       {"GOMAXPROCS": "1"}),
        "ln_hidden": ([ln, "-obj", mesh, "-dir", DIR, "-mode", "all", "-crease", "30", "-hidden",
                       "-out", os.path.join(tmp, "F.svg"), "-size", "1024", "-step", "1"],
                      {"GOMAXPROCS": "1"}),
        "lineart": (la, {}),
        "lineart_hidden": (la + ["--hidden"], {}),
        "lineart_hidden_all": (la + ["--hidden", "--all-edges"], {}),
    }


def occt_job(a, mesh, tmp):
    return ([os.path.join(a.bin, "hlr-occt"), mesh, DIR, os.path.join(tmp, "out.svg"),
             "poly", "1e-9", "--build", "shared"], {})


def run(argv, env_extra, tmp, timeout=None):
    shutil.rmtree(tmp, ignore_errors=True)
    os.makedirs(tmp)
    env = dict(os.environ, **env_extra)
    out = open(os.path.join(tmp, ".out"), "w+b")
    t0 = time.perf_counter()
    p = subprocess.Popen(argv, env=env, stdout=out, stderr=subprocess.STDOUT,
                         start_new_session=True)
    timed_out = False
    while True:
        pid, status, ru = os.wait4(p.pid, os.WNOHANG)
        if pid:
            break
        if timeout is not None and time.perf_counter() - t0 > timeout:
            os.killpg(p.pid, signal.SIGKILL)
            pid, status, ru = os.wait4(p.pid, 0)
            timed_out = True
            break
        time.sleep(0.002)
    wall = time.perf_counter() - t0
    p.returncode = os.waitstatus_to_exitcode(status)
    out.seek(0)
    text = out.read().decode(errors="replace")
    out.close()
    return {
        "wall_s": wall, "cpu_s": ru.ru_utime + ru.ru_stime, "user_s": ru.ru_utime,
        "sys_s": ru.ru_stime, "maxrss_kb": ru.ru_maxrss, "rc": p.returncode,
        "timed_out": timed_out, "text": text,
    }


def step_of(text):
    """The step time a peer printed, if any: (seconds, cpu seconds)."""
    m = re.search(r"lineart_step_s=([0-9.]+) lineart_step_cpu_s=([0-9.]+)", text)
    if m:
        return float(m.group(1)), float(m.group(2))
    m = re.search(r"hlr_s=([0-9.]+)", text)
    if m:
        return float(m.group(1)), ""
    return "", ""


def faces(path):
    n = 0
    with open(path) as f:
        for line in f:
            if line.startswith("f "):
                n += 1  # OBJ faces (polygons), as kepler counts them
    return n


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--kepler", default="/tmp/k/k0/kepler")
    ap.add_argument("--bin", default="/work/peers/bin")
    ap.add_argument("--models", default="/work/shared/models")
    ap.add_argument("--out", default="/work/peers")
    ap.add_argument("--rounds", type=int, default=3)
    ap.add_argument("--occt-timeout", type=float, default=60)
    ap.add_argument("--timeout", type=float, default=None,
                    help="seconds after which any run is stopped and counted as not finished")
    ap.add_argument("--warmup", type=int, default=1, help="rounds run first and not counted")
    ap.add_argument("--meshes", default=",".join(MESHES))
    ap.add_argument("--skip", default="", help="comma-separated jobs to leave out")
    a = ap.parse_args()
    meshes = a.meshes.split(",")
    skip = set(filter(None, a.skip.split(",")))
    tmp = tempfile.mkdtemp(prefix="peers-measure-")
    os.makedirs(a.out, exist_ok=True)
    csv_path = os.path.join(a.out, "table.csv")
    fields = ["round", "mesh", "faces", "job", "wall_s", "cpu_s", "user_s", "sys_s", "maxrss_kb",
              "rc", "timed_out", "step_s", "step_cpu_s", "loadavg"]
    rows = []
    log = open(os.path.join(a.out, "measure.log"), "w")

    def record(rnd, mesh, job, r):
        step, step_cpu = step_of(r["text"])
        row = {"round": rnd, "mesh": mesh, "faces": nf[mesh], "job": job,
               "wall_s": "%.4f" % r["wall_s"], "cpu_s": "%.4f" % r["cpu_s"],
               "user_s": "%.4f" % r["user_s"], "sys_s": "%.4f" % r["sys_s"],
               "maxrss_kb": r["maxrss_kb"], "rc": r["rc"], "timed_out": r["timed_out"],
               "step_s": step, "step_cpu_s": step_cpu,
               "loadavg": open("/proc/loadavg").read().split()[0]}
        rows.append(row)
        log.write("%s %s %s: %s\n%s\n" % (rnd, mesh, job, row, r["text"][-2000:]))
        log.flush()
        if r["rc"] != 0:
            print("  %s %s rc=%s timed_out=%s" % (mesh, job, r["rc"], r["timed_out"]), flush=True)

    nf = {m: faces(os.path.join(a.models, m + ".obj")) for m in meshes}
    def others():
        """The busiest processes now (is the machine shared?)."""
        ps = subprocess.run(["ps", "-eo", "pid,pcpu,etime,comm", "--sort=-pcpu"],
                            capture_output=True, text=True).stdout.splitlines()[:5]
        log.write("processes: " + " | ".join(" ".join(x.split()) for x in ps) + "\n")
        log.flush()

    for rnd in range(1 - a.warmup, a.rounds + 1):
        others()
        print("round %d%s  load %s" % (rnd, " (warm-up)" if rnd <= 0 else "",
                                       open("/proc/loadavg").read().strip()), flush=True)
        for m in meshes:
            path = os.path.join(a.models, m + ".obj")
            for job, (argv, env) in jobs(a, path, tmp).items():
                if job in skip:
                    continue
                r = run(argv, env, tmp, timeout=a.timeout)
                if rnd > 0:
                    record(rnd, m, job, r)
    if "occt" not in skip:
        others()
        print("occt, once per mesh  load %s" % open("/proc/loadavg").read().strip(), flush=True)
        for m in meshes:
            argv, env = occt_job(a, os.path.join(a.models, m + ".obj"), tmp)
            r = run(argv, env, tmp, timeout=a.occt_timeout)
            record(1, m, "occt", r)
    shutil.rmtree(tmp, ignore_errors=True)

    with open(csv_path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=fields)
        w.writeheader()
        w.writerows(rows)
    write_md(a, meshes, nf, rows)


def write_md(a, meshes, nf, rows):
    by = {}
    for r in rows:
        by.setdefault((r["mesh"], r["job"]), {})[int(r["round"])] = r

    def med(mesh, job, key="cpu_s"):
        d = by.get((mesh, job), {})
        v = [float(r[key]) for r in d.values() if r[key] != "" and r["rc"] == 0]
        return statistics.median(v) if v else None

    def ratio(mesh, job, base, key="cpu_s", base_key="cpu_s"):
        """Median over rounds of job[key] / base[base_key] of the same round."""
        d, b = by.get((mesh, job), {}), by.get((mesh, base), {})
        v = [float(d[i][key]) / float(b[i][base_key]) for i in d
             if i in b and d[i][key] != "" and d[i]["rc"] == 0 and b[i]["rc"] == 0]
        return statistics.median(v) if v else None

    def f(x, fmt="%.3f"):
        return "-" if x is None else fmt % x

    def fr(x):
        return "-" if x is None else ("%.2f" % x if x < 10 else "%.1f" % x)

    def mib(mesh, job):
        """The median peak in MiB, written out."""
        kb = med(mesh, job, "maxrss_kb")
        return f(kb and kb / 1024, "%.0f")

    def stopped(mesh, job):
        """The CPU seconds of a run stopped at the timeout, if every run of it was."""
        d = by.get((mesh, job), {})
        if d and all(r["timed_out"] in (True, "True") for r in d.values()):
            return min(float(r["cpu_s"]) for r in d.values())
        return None

    def fp(mesh, job, base, key="cpu_s"):
        """[`ratio`] written out, or "> x" where the peer never finished."""
        t = stopped(mesh, job)
        if t is not None and med(mesh, base):
            return "> %s (dnf)" % fr(t / med(mesh, base))
        return fr(ratio(mesh, job, base, key))

    def fm(mesh, job, key="cpu_s", fmt="%.3f"):
        """[`med`] written out, or "dnf" where the run never finished."""
        if stopped(mesh, job) is not None:
            return "dnf %gs" % a.timeout
        return f(med(mesh, job, key), fmt)

    def occt(mesh, key):
        r = by.get((mesh, "occt"), {}).get(1)
        if r is None:
            return "-"
        if r["timed_out"] in (True, "True"):
            return "dnf %gs" % a.occt_timeout
        if r["rc"] != 0:
            return "rc %s" % r["rc"]
        return "%.3f" % float(r[key])

    def occt_ratio(mesh):
        r = by.get((mesh, "occt"), {}).get(1)
        k = med(mesh, "kepler_hidden")
        if r is None or k is None:
            return "-"
        if r["timed_out"] in (True, "True"):
            return "> %.0f" % (float(r["cpu_s"]) / k)
        if r["rc"] != 0:
            return "-"
        return fr(float(r["cpu_s"]) / k)

    L = []
    L.append("# kepler against ln, OCCT polygonal HLR and Blender Line Art, one thread\n")
    if a.timeout:
        L.append("Runs stopped after %g s are marked dnf; a ratio against one is a lower "
                 "bound (\"> x\").\n" % a.timeout)
    L.append("CPU = user+sys seconds of the whole process (os.wait4), median of %d rounds "
             "after %d warm-up round(s); OCCT once per mesh (timeout %g s). Ratio = peer / kepler "
             "of the same round, median (above 1: kepler faster). Line Art step = its own "
             "depsgraph evaluation of the Line Art modifier (printed by lineart.py); "
             "OCCT step = HLRBRep_PolyAlgo + PolyHLRToShape (printed by hlr-occt).\n"
             % (a.rounds, a.warmup, a.occt_timeout))
    L.append("## CPU seconds\n")
    L.append("| mesh | faces | kepler | kepler hidden | ln feature | ln hidden | OCCT whole | "
             "OCCT step | Line Art whole | Line Art step | LA hidden whole | LA hidden step | "
             "LA hidden all-edges whole | LA hidden all-edges step |")
    L.append("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    for m in meshes:
        L.append("| %s | %d | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s |" % (
            m, nf[m], f(med(m, "kepler")), f(med(m, "kepler_hidden")),
            fm(m, "ln_feature"), fm(m, "ln_hidden"),
            occt(m, "cpu_s"), occt(m, "step_s"),
            fm(m, "lineart"), f(med(m, "lineart", "step_cpu_s")),
            f(med(m, "lineart_hidden")), f(med(m, "lineart_hidden", "step_cpu_s")),
            f(med(m, "lineart_hidden_all")), f(med(m, "lineart_hidden_all", "step_cpu_s"))))
    L.append("\n## Ratios (peer CPU / kepler CPU; above 1: kepler faster)\n")
    L.append("Goals (issue 35): ln feature / kepler >= 3 and ln hidden / kepler hidden >= 5 on "
             "meshes of 1,000 faces or more; OCCT / kepler hidden > 1 everywhere; Line Art step "
             "/ kepler > 1 on stanford-bunny, nefertiti and ogre.\n")
    L.append("| mesh | faces | ln feature / kepler | ln hidden / kepler hidden | "
             "OCCT whole / kepler hidden | Line Art step / kepler | Line Art whole / kepler | "
             "LA hidden step / kepler hidden | LA hidden whole / kepler hidden | "
             "LA hidden all-edges step / kepler hidden |")
    L.append("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    for m in meshes:
        L.append("| %s | %d | %s | %s | %s | %s | %s | %s | %s | %s |" % (
            m, nf[m], fp(m, "ln_feature", "kepler"),
            fp(m, "ln_hidden", "kepler_hidden"), occt_ratio(m),
            fr(ratio(m, "lineart", "kepler", "step_cpu_s")), fp(m, "lineart", "kepler"),
            fr(ratio(m, "lineart_hidden", "kepler_hidden", "step_cpu_s")),
            fr(ratio(m, "lineart_hidden", "kepler_hidden")),
            fr(ratio(m, "lineart_hidden_all", "kepler_hidden", "step_cpu_s"))))
    L.append("\n## kepler on one and two threads, and its hidden SVG against its JSON\n")
    L.append("Default drawing = `--json F --svg G`; hidden = `--edges all --hidden --svg G`; "
             "hidden JSON = `--edges all --hidden --json F`. Speed-up = 1-thread wall / "
             "2-thread wall of the same round, median. SVG/JSON = hidden SVG CPU / hidden "
             "JSON CPU of the same round, one thread, median (goal: at most 1.5).\n")
    L.append("| mesh | faces | 1t wall | 1t CPU | 1t MiB | 2t wall | 2t CPU | 2t MiB | speed-up | "
             "hidden 1t wall | hidden 1t CPU | hidden 1t MiB | hidden 2t wall | hidden 2t CPU | "
             "hidden speed-up | hidden JSON 1t CPU | SVG/JSON |")
    L.append("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    for m in meshes:
        L.append("| %s | %d | %s |" % (m, nf[m], " | ".join([
            f(med(m, "kepler", "wall_s")), f(med(m, "kepler")), mib(m, "kepler"),
            f(med(m, "kepler_2t", "wall_s")), f(med(m, "kepler_2t")), mib(m, "kepler_2t"),
            fr(ratio(m, "kepler", "kepler_2t", "wall_s", "wall_s")),
            f(med(m, "kepler_hidden", "wall_s")), f(med(m, "kepler_hidden")),
            mib(m, "kepler_hidden"),
            f(med(m, "kepler_hidden_2t", "wall_s")), f(med(m, "kepler_hidden_2t")),
            fr(ratio(m, "kepler_hidden", "kepler_hidden_2t", "wall_s", "wall_s")),
            f(med(m, "kepler_hidden_json")),
            fr(ratio(m, "kepler_hidden", "kepler_hidden_json"))])))
    L.append("\n## Wall seconds and peak RSS (MiB), medians\n")
    L.append("| mesh | kepler wall | kepler MiB | kepler hidden wall | kepler hidden MiB | "
             "ln feature wall | ln feature MiB | ln hidden wall | ln hidden MiB | OCCT wall | "
             "OCCT MiB | Line Art wall | Line Art MiB | LA hidden wall | LA hidden MiB |")
    L.append("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    for m in meshes:
        cells = []
        for j in ["kepler", "kepler_hidden", "ln_feature", "ln_hidden"]:
            cells += [f(med(m, j, "wall_s")), mib(m, j)]
        o = by.get((m, "occt"), {}).get(1)
        cells += [("%.2f" % float(o["wall_s"])) if o else "-",
                  ("%.0f" % (float(o["maxrss_kb"]) / 1024)) if o else "-"]
        for j in ["lineart", "lineart_hidden"]:
            cells += [f(med(m, j, "wall_s")), mib(m, j)]
        L.append("| %s | %s |" % (m, " | ".join(cells)))
    with open(os.path.join(a.out, "table.md"), "w") as fh:
        fh.write("\n".join(L) + "\n")
    print("\n".join(L))


if __name__ == "__main__":
    main()
