#!/usr/bin/python3
"""Scaling of `breastfit register --no-report-html` (docs/PERFORMANCE.md): wall time and peak
memory (GNU time's maximum resident set size) against the scan's size and the template's
resolution, measured on synthetic cases, and a plot of both.

Usage:
  scripts/perf_scaling.py scans --out DIR [--subdivisions 2 3 4 5] [--repeat 3]
  scripts/perf_scaling.py templates --out DIR --templates T1.glb T2.glb ... [--case CASE]
  scripts/perf_scaling.py plot --out DIR --image docs/images/perf_scaling.png

`scans` makes one synthetic case per subdivision level (`breastfit synth --subdivisions K`, the
truth refined up to 5 M triangles) and registers each; `templates` registers one case with each
template (e.g. made by `breastfit template build --edge-mm E`). Both append to DIR/scaling.json;
`plot` draws it. Every number is the median of --repeat runs of the whole process.
"""
import argparse
import json
import os
import re
import statistics
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
BIN = os.environ.get("BREASTFIT_BIN", os.path.join(HERE, "..", "build", "bin", "breastfit"))


def timed_register(case, template=None, threads=None, repeat=3):
    """Median wall seconds, CPU seconds (user + system) and peak RSS (MB) of
    `register --no-report-html`, and the last run's report.json."""
    walls, cpus, rss = [], [], []
    report = None
    for _ in range(repeat):
        with tempfile.TemporaryDirectory() as out:
            cmd = ["/usr/bin/time", "-v", BIN, "register", os.path.join(case, "scan.ply"), "--landmarks",
                   os.path.join(case, "landmarks.mrk.json"), "--out", os.path.join(out, "fit"), "--quiet",
                   "--no-report-html"]
            if template:
                cmd += ["--template", template]
            if threads:
                cmd += ["--threads", str(threads)]
            p = subprocess.run(cmd, capture_output=True, text=True)
            if p.returncode != 0:
                sys.exit("perf_scaling.py: register failed on %s: %s" % (case, p.stderr.strip()[-500:]))
            m = re.search(r"Elapsed \(wall clock\) time \(h:mm:ss or m:ss\): (?:(\d+):)?(\d+):([\d.]+)", p.stderr)
            walls.append(int(m.group(1) or 0) * 3600 + int(m.group(2)) * 60 + float(m.group(3)))
            cpus.append(sum(float(re.search(r"%s time \(seconds\): ([\d.]+)" % k, p.stderr).group(1))
                            for k in ("User", "System")))
            rss.append(int(re.search(r"Maximum resident set size \(kbytes\): (\d+)", p.stderr).group(1)) / 1024.0)
            with open(os.path.join(out, "fit", "report.json")) as f:
                report = json.load(f)
    return statistics.median(walls), statistics.median(cpus), statistics.median(rss), report


def scan_faces(case):
    with open(os.path.join(case, "scan.ply"), "rb") as f:
        head = f.read(4096).decode("latin-1")
    return int(re.search(r"element face (\d+)", head).group(1))


def load(out):
    path = os.path.join(out, "scaling.json")
    if os.path.exists(path):
        with open(path) as f:
            return json.load(f)
    return {"scans": [], "templates": []}


def save(out, data):
    with open(os.path.join(out, "scaling.json"), "w") as f:
        json.dump(data, f, indent=1)


def loadavg():
    return os.getloadavg()[0]


def run_scans(a):
    data = load(a.out)
    for k in a.subdivisions:
        case = os.path.join(a.out, "scan_sub%d" % k)
        if not os.path.exists(os.path.join(case, "scan.ply")):
            subprocess.run([BIN, "synth", "--out", case, "--seed", "7", "--subdivisions", str(k), "--max-faces",
                            "5000000", "--target-edge-mm", "0.05", "--force", "--quiet"], check=True)
        load_before = loadavg()
        wall, cpu, rss, report = timed_register(case, threads=a.threads, repeat=a.repeat)
        row = {"subdivisions": k, "scan_triangles": scan_faces(case), "wall_s": wall, "cpu_s": cpu,
               "peak_rss_mb": rss, "time_s": report["time_s"], "timings_s": report["timings_s"], "load": load_before}
        print(json.dumps(row))
        data["scans"] = [r for r in data["scans"] if r["subdivisions"] != k] + [row]
    data["scans"].sort(key=lambda r: r["scan_triangles"])
    save(a.out, data)


def run_templates(a):
    data = load(a.out)
    for t in a.templates:
        info = subprocess.run([BIN, "template", "info", t], capture_output=True, text=True, check=True).stdout
        vertices = int(re.search(r"(\d+) vertices", info).group(1))
        load_before = loadavg()
        wall, cpu, rss, report = timed_register(a.case, template=t, threads=a.threads, repeat=a.repeat)
        row = {"template": os.path.basename(t), "template_vertices": vertices, "wall_s": wall, "cpu_s": cpu,
               "peak_rss_mb": rss, "time_s": report["time_s"], "load": load_before}
        print(json.dumps(row))
        data["templates"] = [r for r in data["templates"] if r["template"] != row["template"]] + [row]
    data["templates"].sort(key=lambda r: r["template_vertices"])
    save(a.out, data)


def plot(a):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    data = load(a.out)
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.2))

    def panel(ax, rows, x, xlabel, title):
        if not rows:
            return
        ax.loglog(x, [r["wall_s"] for r in rows], "o-", label="register --no-report-html, wall (s)")
        ax.loglog(x, [r["cpu_s"] for r in rows], "d-", label="register, CPU user+system (s)")
        ax.loglog(x, [r["peak_rss_mb"] / 1000 for r in rows], "^-", label="peak memory (GB)")
        for xi, r in zip(x, rows):
            ax.annotate("load %.0f" % r["load"], (xi, r["wall_s"]), fontsize=7, textcoords="offset points",
                        xytext=(4, 4))
        ax.set_xlabel(xlabel)
        ax.set_title(title)
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=8)

    s, t = data["scans"], data["templates"]
    panel(axes[0], s, [r["scan_triangles"] / 1e6 for r in s], "scan triangles (millions)",
          "vs scan size (default template, 2070 vertices)")
    panel(axes[1], t, [r["template_vertices"] for r in t], "template vertices", "vs template resolution (bench p0_standing)")
    fig.tight_layout()
    fig.savefig(a.image, dpi=110)
    print("wrote", a.image)


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = p.add_subparsers(dest="what", required=True)
    s = sub.add_parser("scans")
    s.add_argument("--subdivisions", type=int, nargs="+", default=[2, 3, 4, 5])
    t = sub.add_parser("templates")
    t.add_argument("--templates", nargs="+", required=True)
    t.add_argument("--case", required=True)
    g = sub.add_parser("plot")
    g.add_argument("--image", required=True)
    for q in (s, t, g):
        q.add_argument("--out", required=True)
    for q in (s, t):
        q.add_argument("--repeat", type=int, default=3)
        q.add_argument("--threads", type=int, default=None)
    a = p.parse_args()
    os.makedirs(a.out, exist_ok=True)
    {"scans": run_scans, "templates": run_templates, "plot": plot}[a.what](a)


if __name__ == "__main__":
    main()
