"""A cohort of scans on a Dask cluster: the same outputs as `breastfit batch`.

    python3 -m breastfit.cohort CASES... --out DIR [--workers N] [--scheduler tcp://HOST:PORT]

Every case is registered by a Dask task in a worker process (breastfit's own code, through
`run_case`: the case's sub-directory DIR/<case>/ with the register output set, finished cases skipped
unless --force, a bad case recorded as failed); the client then writes DIR/cohort.csv and
DIR/cohort.html. Without --scheduler a LocalCluster of N single-threaded worker processes is started
on 127.0.0.1. With --scheduler the workers must have breastfit importable and see the case files and
DIR at the same paths (a shared file system). See docs/COHORTS.md.
"""
from __future__ import annotations

import argparse
import os
import sys
import time
from typing import Any, Iterable, Optional, Sequence

from . import _breastfit

__all__ = ["run_cohort", "main"]

_templates: dict[Optional[str], Any] = {}


def _template(path: Optional[str]):
    """The template of this worker process, loaded once (None: the shipped default)."""
    if path not in _templates:
        _templates[path] = _breastfit.Template.load(path) if path else _breastfit.Template.default()
    return _templates[path]


def _run_one(case: tuple, out: str, settings: dict) -> dict:
    """One case in a worker: its record (a dict with the columns of cohort.csv)."""
    name, scan, landmarks = case
    return _breastfit.run_case(name, scan, landmarks, out, template=_template(settings["template"]),
                               options=settings["options"], units=settings["units"], force=settings["force"],
                               report_html=settings["report_html"], ignore_landmarks=settings["ignore_landmarks"])


def run_cohort(cases: Sequence[str | os.PathLike], out: str | os.PathLike, *, client=None, workers: int = 2,
               template: Optional[str] = None, options: Optional[dict] = None, units: str = "auto",
               force: bool = False, report_html: bool = True, ignore_landmarks: bool = False,
               progress=None) -> list[dict]:
    """Registers every case on a Dask cluster and writes out/cohort.csv and out/cohort.html.

    cases    CASE arguments as for `breastfit batch` (scan files, case directories, directories of cases)
    client   a dask.distributed Client; None starts a LocalCluster of `workers` processes on 127.0.0.1
    template a template file (.glb) every worker loads once; None: the shipped default
    options  fit options (the JSON of `breastfit register --config`)
    progress called as progress(done, total, record) on the client as records arrive
    Returns the records in case order (dicts with the columns of cohort.csv).
    """
    from dask.distributed import Client, LocalCluster, as_completed

    resolved = _breastfit.resolve_cases([os.fspath(c) for c in cases])
    out = os.path.abspath(os.fspath(out))
    os.makedirs(out, exist_ok=True)
    # One fit per worker thread: each fit on one thread unless the options say otherwise (threads
    # change only the speed, never the result).
    options = {"threads": 1, **(options or {})}
    settings = {"template": os.path.abspath(template) if template else None, "options": options, "units": units,
                "force": force, "report_html": report_html, "ignore_landmarks": ignore_landmarks}
    cases_abs = [(n, os.path.abspath(s), os.path.abspath(l) if l else None) for n, s, l in resolved]

    own = client is None
    cluster = None
    if own:
        cluster = LocalCluster(n_workers=workers, threads_per_worker=1, processes=True, host="127.0.0.1",
                               dashboard_address=None)
        client = Client(cluster)
    try:
        futures = [client.submit(_run_one, c, out, settings, key=f"breastfit-case-{i}-{c[0]}", pure=False)
                   for i, c in enumerate(cases_abs)]
        index = {f.key: i for i, f in enumerate(futures)}
        records: list[Optional[dict]] = [None] * len(futures)
        done = 0
        for future in as_completed(futures):
            i = index[future.key]
            try:
                records[i] = future.result()
            except Exception as e:  # a worker died (e.g. out of memory): this case only
                name, scan, _ = cases_abs[i]
                records[i] = {"name": name, "scan": scan, "status": "failed", "resumed": False,
                              "message": f"worker: {type(e).__name__}: {e}", "warnings": 0}
            done += 1
            if progress:
                progress(done, len(futures), records[i])
    finally:
        if own:
            client.close()
            cluster.close()
    _breastfit.write_cohort_summary(out, records)
    return records  # type: ignore[return-value]


def _parse(argv: Optional[Iterable[str]]):
    p = argparse.ArgumentParser(prog="python3 -m breastfit.cohort",
                                description="Register a cohort of scans on a Dask cluster (same outputs as "
                                            "`breastfit batch`: DIR/<case>/, DIR/cohort.csv, DIR/cohort.html).")
    p.add_argument("cases", nargs="+", help="scan files, case directories or directories of cases")
    p.add_argument("--out", "-o", required=True, help="output directory (created)")
    p.add_argument("--scheduler", help="address of a running Dask scheduler, tcp://HOST:PORT "
                                       "(default: a LocalCluster of --workers processes on 127.0.0.1)")
    p.add_argument("--workers", type=int, default=os.cpu_count() or 1, help="LocalCluster worker processes")
    p.add_argument("--template", help="rigged template (.glb); default: the shipped torso")
    p.add_argument("--config", help="JSON file with fit options (as `breastfit register --config`)")
    p.add_argument("--units", default="auto", choices=["auto", "mm", "m"])
    p.add_argument("--no-landmarks", action="store_true", help="ignore the landmark files")
    p.add_argument("--no-report-html", action="store_true", help="do not write each case's report.html")
    p.add_argument("--force", action="store_true", help="register every case again")
    p.add_argument("--quiet", "-q", action="store_true")
    return p.parse_args(argv)


def main(argv: Optional[Iterable[str]] = None) -> int:
    """The command line; exit code 0 when every case is ok, 6 when one failed or was not usable (as batch)."""
    import json

    a = _parse(argv)
    if a.workers < 1:
        print("breastfit.cohort: error: --workers must be at least 1", file=sys.stderr)
        return 2
    options = None
    try:
        if a.config:
            with open(a.config) as f:
                options = json.load(f)
        client = None
        if a.scheduler:
            from dask.distributed import Client
            client = Client(a.scheduler)
        start = time.monotonic()

        def progress(done, total, record):
            if not a.quiet:
                print(f"breastfit.cohort: [{done}/{total}] {record['name']} {record['status']}"
                      + (f": {record['message']}" if record.get("message") else ""), file=sys.stderr)

        try:
            records = run_cohort(a.cases, a.out, client=client, workers=a.workers, template=a.template,
                                 options=options, units=a.units, force=a.force, report_html=not a.no_report_html,
                                 ignore_landmarks=a.no_landmarks, progress=progress)
        finally:
            if client is not None:
                client.close()
    except (OSError, ValueError) as e:
        print(f"breastfit.cohort: error: {e}", file=sys.stderr)
        return 4 if isinstance(e, OSError) else 3
    ok = sum(r["status"] == "ok" for r in records)
    if not a.quiet:
        print(f"{len(records)} cases: {ok} ok, {len(records) - ok} not ok in {time.monotonic() - start:.1f} s; "
              f"wrote {os.path.join(a.out, 'cohort.csv')} and cohort.html")
    return 0 if ok == len(records) else 6


if __name__ == "__main__":
    sys.exit(main())
