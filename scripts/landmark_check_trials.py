#!/usr/bin/env python3
"""Moved-landmark trials on cases in the bench layout (scan.ply + landmarks.mrk.json per case).

Each landmark of each case in turn is walked DIST mm along the scan's skin (2 mm steps in a
random tangent direction, or --directions evenly spread ones from a random start, each step projected back onto the plane of the nearest scan points;
in mm whatever the case's units: a case whose markup says "coordinateUnits" m is walked on its scan scaled to mm),
the case is registered with `breastfit register`, and report.json's landmark check says whether
the moved landmark was flagged (and which other landmarks were). With --unmodified, the cases'
landmarks as given are registered too (false flags). Prints one line per trial and a summary.

Usage: scripts/landmark_check_trials.py --cases DIR --out DIR [--distances 20 40] [--seed 1]
       [--directions 1] [--only CASE...] [--landmarks NAME...] [--unmodified] [--jobs 2]
       [-- REGISTER_ARGS...]
"""
import argparse
import concurrent.futures
import json
import math
import os
import random
import shutil
import struct
import subprocess
import sys

import numpy as np
from scipy.spatial import cKDTree

HERE = os.path.dirname(os.path.abspath(__file__))


def read_ply_vertices(path):
    """The vertex positions of a PLY file (ascii or binary little-endian; x y z first)."""
    with open(path, "rb") as f:
        header = []
        while True:
            line = f.readline().decode("ascii", "replace").strip()
            header.append(line)
            if line == "end_header":
                break
        fmt = next(l.split()[1] for l in header if l.startswith("format"))
        n = 0
        props = []
        in_vertex = False
        for l in header:
            w = l.split()
            if w[:2] == ["element", "vertex"]:
                n, in_vertex = int(w[2]), True
            elif w and w[0] == "element":
                in_vertex = False
            elif in_vertex and w[0] == "property":
                props.append(w[1])
        if fmt == "ascii":
            rows = [f.readline().split() for _ in range(n)]
            return np.array([[float(v) for v in r[:3]] for r in rows])
        sizes = {"float": "f", "float32": "f", "double": "d", "float64": "d", "uchar": "B", "uint8": "B",
                 "int": "i", "int32": "i", "uint": "I", "uint32": "I", "short": "h", "ushort": "H"}
        rec = "<" + "".join(sizes[p] for p in props)
        data = f.read(struct.calcsize(rec) * n)
        return np.array([r[:3] for r in struct.iter_unpack(rec, data)], dtype=float)


def millimetres_per_unit(mrk):
    """1000 for landmarks (and so the scan) in metres, else 1: the markup's coordinateUnits."""
    units = mrk["markups"][0].get("coordinateUnits", "mm")
    if isinstance(units, list):
        units = units[0] if units else "mm"
    return 1000.0 if str(units).lower() in ("m", "meter", "metre") else 1.0


class Skin:
    def __init__(self, vertices):
        self.v = vertices
        self.tree = cKDTree(vertices)

    def project(self, p):
        """p onto the plane of its 24 nearest scan vertices; and that plane's normal."""
        _, idx = self.tree.query(p, k=24)
        nb = self.v[idx]
        c = nb.mean(axis=0)
        _, _, vt = np.linalg.svd(nb - c)
        n = vt[2]
        return p - np.dot(p - c, n) * n, n

    def walk(self, p, length, angle):
        q, n = self.project(np.asarray(p, dtype=float))
        a = np.cross(n, [1.0, 0, 0] if abs(n[0]) < 0.9 else [0, 1.0, 0])
        a /= np.linalg.norm(a)
        b = np.cross(n, a)
        d = math.cos(angle) * a + math.sin(angle) * b
        walked = 0.0
        while walked < length:
            d = d - np.dot(d, n) * n
            d /= np.linalg.norm(d)
            q, n = self.project(q + 2.0 * d)
            walked += 2.0
        return q


def register(binary, case, landmarks_file, out, extra):
    cmd = [binary, "register", os.path.join(case, "scan.ply"), "--landmarks", landmarks_file, "--out", out,
           "--force", "--quiet", "--no-report-html"] + extra
    p = subprocess.run(cmd, capture_output=True, text=True)
    report = os.path.join(out, "report.json")
    if not os.path.exists(report):
        return None, p.stderr.strip()
    with open(report) as f:
        return json.load(f), p.stderr.strip()


def checks_of(report):
    return report.get("solver", {}).get("landmark_check", {}) if report else {}


def run_trial(job):
    binary, case, name, dist, mrk, moved_name, moved_pos, out, extra = job
    os.makedirs(out, exist_ok=True)
    doc = json.loads(json.dumps(mrk))
    for cp in doc["markups"][0]["controlPoints"]:
        if cp["label"] == moved_name:
            cp["position"] = [float(x) for x in moved_pos]
    lm = os.path.join(out, "landmarks.mrk.json")
    with open(lm, "w") as f:
        json.dump(doc, f)
    report, err = register(binary, case, lm, os.path.join(out, "result"), extra)
    checks = checks_of(report)
    flagged = sorted(n for n, c in checks.items() if c.get("flagged"))
    moved = checks.get(moved_name, {}) if moved_name else {}
    shutil.rmtree(os.path.join(out, "result"), ignore_errors=True)
    return {"case": name, "landmark": moved_name, "distance": dist, "flagged": flagged,
            "predicted_mm": moved.get("predicted_distance_mm"), "fit_mm": moved.get("distance_mm"),
            "anatomy_mm": moved.get("anatomy_distance_mm"),
            "error": None if report else err, "checks": checks}


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--cases", required=True)
    ap.add_argument("--out", required=True)
    ap.add_argument("--bin", default=os.environ.get("BREASTFIT_BIN", os.path.join(HERE, "..", "build", "bin", "breastfit")))
    ap.add_argument("--distances", type=float, nargs="+", default=[20.0, 40.0])
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--directions", type=int, default=1,
                    help="moves per landmark and distance, in directions spread around the landmark")
    ap.add_argument("--only", nargs="+")
    ap.add_argument("--landmarks", nargs="+")
    ap.add_argument("--unmodified", action="store_true", help="also register the landmarks as given")
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("extra", nargs="*", help="after --: arguments for breastfit register")
    a = ap.parse_args()
    rng = random.Random(a.seed)
    jobs = []
    for name in sorted(os.listdir(a.cases)):
        case = os.path.join(a.cases, name)
        if a.only and name not in a.only or not os.path.exists(os.path.join(case, "landmarks.mrk.json")):
            continue
        with open(os.path.join(case, "landmarks.mrk.json")) as f:
            mrk = json.load(f)
        mm = millimetres_per_unit(mrk)  # walk in mm whatever the case's units
        skin = Skin(read_ply_vertices(os.path.join(case, "scan.ply")) * mm)
        if a.unmodified:
            jobs.append((a.bin, case, name, 0.0, mrk, None, None, os.path.join(a.out, name, "as_given"), a.extra))
        for cp in mrk["markups"][0]["controlPoints"]:
            label = cp["label"]
            for dist in a.distances:
                start = rng.uniform(0, 2 * math.pi)  # drawn for every landmark: --landmarks repeats a full run's moves
                if a.landmarks and label not in a.landmarks:
                    continue
                for k in range(a.directions):
                    moved = skin.walk(np.asarray(cp["position"], dtype=float) * mm, dist,
                                      start + 2 * math.pi * k / a.directions) / mm
                    jobs.append((a.bin, case, name, dist, mrk, label, moved,
                                 os.path.join(a.out, name, "%s_%g_%d" % (label, dist, k)), a.extra))
    results = []
    with concurrent.futures.ThreadPoolExecutor(max_workers=a.jobs) as pool:
        for r in pool.map(run_trial, jobs):
            results.append(r)
            if r["landmark"] is None:
                print("%-14s as given: flagged %s" % (r["case"], ", ".join(r["flagged"]) or "none"), flush=True)
            else:
                print("%-14s %-22s %2.0f mm: %s (predicted %s, fitted %s, anatomy %s)%s" % (
                    r["case"], r["landmark"], r["distance"], "FLAGGED" if r["landmark"] in r["flagged"] else "missed",
                    "-" if r["predicted_mm"] is None else "%.1f" % r["predicted_mm"],
                    "-" if r["fit_mm"] is None else "%.1f" % r["fit_mm"],
                    "-" if r["anatomy_mm"] is None else "%.1f" % r["anatomy_mm"],
                    "" if not r["error"] else " error: " + r["error"]), flush=True)
    with open(os.path.join(a.out, "trials.json"), "w") as f:
        json.dump(results, f, indent=1)
    moved = [r for r in results if r["landmark"]]
    if moved:
        print("\nflagged (moved landmark): %d / %d" % (sum(r["landmark"] in r["flagged"] for r in moved), len(moved)))
        for dist in a.distances:
            sub = [r for r in moved if r["distance"] == dist]
            print("  %g mm: %d / %d" % (dist, sum(r["landmark"] in r["flagged"] for r in sub), len(sub)))
        per = {}
        for r in moved:
            per.setdefault(r["landmark"], []).append(r["landmark"] in r["flagged"])
        for k, v in per.items():
            print("  %-22s %d / %d" % (k, sum(v), len(v)))
        print("other landmarks flagged with it: %d trials" % sum(any(f != r["landmark"] for f in r["flagged"]) for r in moved))
    given = [r for r in results if r["landmark"] is None]
    if given:
        print("cases with a false flag (as given): %d / %d" % (sum(bool(r["flagged"]) for r in given), len(given)))
        for key in ("predicted_distance_mm", "anatomy_distance_mm"):
            spread = {}
            for r in given:
                for n, c in r["checks"].items():
                    if key in c:
                        spread.setdefault(n, []).append(c[key])
            for n, v in spread.items():
                print("  %-22s %s as given: mean %.1f, max %.1f mm (%d cases)" % (n, key, np.mean(v), np.max(v), len(v)))
    return 0


if __name__ == "__main__":
    sys.exit(main())
