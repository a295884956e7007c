#!/usr/bin/python3
"""Breast volumes on the external benchmark: truth against fits, one rule for both.

Optional check (not part of the test suite; needs ../shared/bench, else prints "skipped" and
exits 0). For every case of the bench and a directory of `breastfit register` results
(RESULTS/<case>/fitted.ply, drawings.mrk.json, report.json, as scripts/bench_check.sh writes
them), it measures with `breastfit volume` (the surface inside a closed contour against a
membrane chest wall, docs/TRANSFER.md):

  truth   CASE/truth/surface.ply inside CASE/truth/curves.json breast_contour_R/L
  fitted  RESULTS/<case>/fitted.ply inside RESULTS/<case>/drawings.mrk.json breast_contour_R/L
  report  report.json breast_measurements.{right,left}.volume_ml (what `register` reported),
          when present

and prints a Markdown table per case and side with the errors against the truth, then the mean
signed and mean absolute errors in %.

Usage: scripts/bench_volumes.py [--cases DIR] [--results DIR] [--only CASE ...]
                                [--fill membrane|thin-plate] [--json OUT.json]
The binary is $BREASTFIT_BIN (default build/bin/breastfit). Nothing is copied into the repo:
the truth curves go to a temporary markups file.
"""
import argparse
import json
import os
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SIDES = (("R", "breast_contour_R"), ("L", "breast_contour_L"))


def markups_from_curves(curves, names, units):
    """Slicer markups (LPS, positions = the file numbers) with the named curves as ClosedCurve."""
    doc = {"@schema": "https://raw.githubusercontent.com/slicer/slicer/master/Modules/Loadable/Markups/"
                      "Resources/Schema/markups-schema-v1.0.3.json#",
           "markups": []}
    for name in names:
        c = curves.get(name)
        if c is None:
            continue
        doc["markups"].append({
            "type": "ClosedCurve", "name": name, "coordinateSystem": "LPS", "coordinateUnits": units,
            "controlPoints": [{"id": str(i + 1), "label": f"{name}-{i + 1}", "position": [float(x) for x in p],
                               "positionStatus": "defined"} for i, p in enumerate(c["points"])]})
    return doc


def run_volume(binary, mesh, curves_file, units, tmp, fill="membrane"):
    """{curve name: volume_ml} from `breastfit volume`, or raises RuntimeError with its message."""
    cmd = [binary, "volume", mesh, "--curves", curves_file, "--json", "--fill", fill]  # JSON on stdout
    for _, name in SIDES:
        cmd += ["--name", name]
    if units:
        cmd += ["--units", units]
    p = subprocess.run(cmd, capture_output=True, text=True)
    if p.returncode != 0:
        msg = (p.stderr or p.stdout).strip().splitlines()
        raise RuntimeError(msg[-1] if msg else f"exit {p.returncode}")
    return {c["name"]: c["volume_ml"] for c in json.loads(p.stdout)["curves"]}


def report_volumes(report_path):
    """{side: volume_ml} of report.json's breast measurements, {} when absent."""
    try:
        with open(report_path) as f:
            rep = json.load(f)
    except (OSError, ValueError):
        return {}
    meas = rep.get("breast_measurements") or rep.get("measurements") or {}
    out = {}
    for side, key in (("R", "right"), ("L", "left")):
        v = (meas.get(key) or {}).get("volume_ml")
        if isinstance(v, (int, float)):
            out[side] = float(v)
    return out


def pct(v, truth):
    return None if v is None or truth is None or truth == 0 else 100.0 * (v - truth) / truth


def fmt(x, spec):
    return "—" if x is None else format(x, spec)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    bench = os.environ.get("BENCH_DIR", os.path.join(HERE, "..", "shared", "bench"))
    ap.add_argument("--cases", default=os.path.join(bench, "cases"), help="bench cases directory")
    ap.add_argument("--results", default=os.path.join(HERE, "out", "bench", "results"),
                    help="RESULTS/<case>/ from breastfit register (default out/bench/results)")
    ap.add_argument("--only", nargs="+", default=None, help="only these cases")
    ap.add_argument("--fill", default="membrane", choices=["membrane", "thin-plate"])
    ap.add_argument("--json", default=None, help="write every number here")
    args = ap.parse_args()

    if not os.path.isdir(args.cases):
        print(f"bench_volumes.py: no benchmark cases at {args.cases}; skipped")
        return 0
    binary = os.environ.get("BREASTFIT_BIN", os.path.join(HERE, "build", "bin", "breastfit"))
    if not os.access(binary, os.X_OK):
        print(f"bench_volumes.py: {binary} not built (set BREASTFIT_BIN)", file=sys.stderr)
        return 1
    cases = sorted(d for d in os.listdir(args.cases) if os.path.isdir(os.path.join(args.cases, d, "truth")))
    if args.only:
        cases = [c for c in cases if c in args.only]
    rows = []
    with tempfile.TemporaryDirectory(prefix="bench_volumes_") as tmp:
        for case in cases:
            cdir = os.path.join(args.cases, case)
            with open(os.path.join(cdir, "truth", "meta.json")) as f:
                units = json.load(f).get("units", "mm")
            with open(os.path.join(cdir, "truth", "curves.json")) as f:
                curves = json.load(f)
            truth_mrk = os.path.join(tmp, "truth.mrk.json")
            with open(truth_mrk, "w") as f:
                json.dump(markups_from_curves(curves, [n for _, n in SIDES], units), f)
            errors = []
            try:
                truth = run_volume(binary, os.path.join(cdir, "truth", "surface.ply"), truth_mrk, units, tmp, args.fill)
            except RuntimeError as e:
                truth, errors = {}, errors + [f"truth: {e}"]
            rdir = os.path.join(args.results, case)
            fitted = {}
            if os.path.isfile(os.path.join(rdir, "fitted.ply")):
                try:
                    fitted = run_volume(binary, os.path.join(rdir, "fitted.ply"),
                                        os.path.join(rdir, "drawings.mrk.json"), units, tmp, args.fill)
                except RuntimeError as e:
                    errors.append(f"fitted: {e}")
            else:
                errors.append(f"fitted: no {os.path.join(rdir, 'fitted.ply')}")
            reported = report_volumes(os.path.join(rdir, "report.json"))
            for side, name in SIDES:
                t, v, r = truth.get(name), fitted.get(name), reported.get(side)
                rows.append({"case": case, "side": side, "truth_ml": t, "fitted_ml": v, "fitted_error_pct": pct(v, t),
                             "report_ml": r, "report_error_pct": pct(r, t), "errors": errors})

    print(f"Breast volumes (`breastfit volume`, {args.fill} chest wall): truth surface inside the truth contour vs "
          f"fitted surface inside the transferred contour; `report` = register's report.json\n")
    print("| case | side | truth ml | fitted ml | fitted err % | report ml | report err % |")
    print("|---|---|---:|---:|---:|---:|---:|")
    for r in rows:
        print(f"| {r['case']} | {r['side']} | {fmt(r['truth_ml'], '.0f')} | {fmt(r['fitted_ml'], '.0f')} | "
              f"{fmt(r['fitted_error_pct'], '+.1f')} | {fmt(r['report_ml'], '.0f')} | {fmt(r['report_error_pct'], '+.1f')} |")
    summary = {}
    for key in ("fitted", "report"):
        errs = [r[f"{key}_error_pct"] for r in rows if r[f"{key}_error_pct"] is not None]
        if errs:
            summary[key] = {"n": len(errs), "mean_signed_pct": sum(errs) / len(errs),
                            "mean_abs_pct": sum(abs(e) for e in errs) / len(errs),
                            "min_pct": min(errs), "max_pct": max(errs)}
    print()
    for key, s in summary.items():
        print(f"{key}: n = {s['n']}, mean signed {s['mean_signed_pct']:+.1f} %, mean |error| {s['mean_abs_pct']:.1f} %, "
              f"range {s['min_pct']:+.1f} … {s['max_pct']:+.1f} %")
    problems = sorted({e for r in rows for e in r["errors"]})
    for e in problems:
        print(f"error: {e}")
    if args.json:
        with open(args.json, "w") as f:
            json.dump({"fill": args.fill, "cases_dir": args.cases, "results_dir": args.results, "rows": rows,
                       "summary": summary}, f, indent=1)
    return 0


if __name__ == "__main__":
    sys.exit(main())
