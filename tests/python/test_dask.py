"""The cohort on Dask (breastfit.cohort): a LocalCluster of processes on loopback gives the same
outputs as `breastfit batch`; the command line with --scheduler."""
import csv
import subprocess
import sys

import pytest

from breastfit import cohort

TIMES = {"time_s", "wall_s", "resumed"}


def rows(path):
    with open(path, newline="") as f:
        return [{k: v for k, v in r.items() if k not in TIMES} for r in csv.DictReader(f)]


@pytest.fixture(scope="module")
def cluster():
    from dask.distributed import LocalCluster
    c = LocalCluster(n_workers=2, threads_per_worker=1, processes=True, host="127.0.0.1", dashboard_address=None)
    yield c
    c.close()


def test_dask_matches_batch(cli, synth_cases, tmp_path, cluster):
    from dask.distributed import Client
    cases = [str(c) for c in synth_cases] + [str(tmp_path / "bad.ply")]
    (tmp_path / "bad.ply").write_bytes(b"not a ply")
    batch_out = tmp_path / "batch"
    subprocess.run([cli, "batch", *cases, "--out", str(batch_out), "--jobs", "2", "--no-report-html", "--quiet"])
    seen = []
    with Client(cluster) as client:
        records = cohort.run_cohort(cases, tmp_path / "dask", client=client, report_html=False,
                                    progress=lambda done, total, r: seen.append((done, total)))
    assert [r["status"] for r in records] == ["ok", "ok", "ok", "failed"]
    assert sorted(seen) == [(i, 4) for i in range(1, 5)]
    assert rows(tmp_path / "dask" / "cohort.csv") == rows(batch_out / "cohort.csv")
    for c in synth_cases:
        assert (tmp_path / "dask" / c.name / "params.json").read_bytes() == \
            (batch_out / c.name / "params.json").read_bytes()
    assert (tmp_path / "dask" / "cohort.html").exists()


def test_command_line_with_scheduler_resumes(synth_cases, tmp_path, cluster):
    out = tmp_path / "out"
    args = [sys.executable, "-m", "breastfit.cohort", *map(str, synth_cases[:2]), "--out", str(out),
            "--scheduler", cluster.scheduler_address, "--no-report-html"]
    r = subprocess.run(args, capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    assert [row["status"] for row in rows(out / "cohort.csv")] == ["ok", "ok"]
    r = subprocess.run(args, capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    with open(out / "cohort.csv", newline="") as f:
        assert [row["resumed"] for row in csv.DictReader(f)] == ["yes", "yes"]


def test_local_cluster_by_default(synth_cases, tmp_path):
    r = subprocess.run([sys.executable, "-m", "breastfit.cohort", str(synth_cases[0]), "--out", str(tmp_path / "o"),
                        "--workers", "1", "--no-report-html", "--quiet"], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    assert rows(tmp_path / "o" / "cohort.csv")[0]["status"] == "ok"
    r = subprocess.run([sys.executable, "-m", "breastfit.cohort", str(tmp_path / "missing"), "--out",
                        str(tmp_path / "o2")], capture_output=True, text=True)
    assert r.returncode == 4 and "missing" in r.stderr
