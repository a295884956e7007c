"""`breastfit batch`: outputs per case, cohort.csv/.html, a bad case recorded as failed, resumability."""
import csv
import shutil
import subprocess

import pytest


def read_csv(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


@pytest.fixture()
def cohort_inputs(synth_cases, tmp_path):
    """Two case directories, one scan file with a sibling landmark file, and one bad scan."""
    inputs = tmp_path / "in"
    inputs.mkdir()
    for c in synth_cases[:2]:
        shutil.copytree(c, inputs / "cases" / c.name)
    shutil.copy(synth_cases[2] / "scan.ply", inputs / "p3.ply")
    shutil.copy(synth_cases[2] / "landmarks.mrk.json", inputs / "p3.mrk.json")
    (inputs / "broken.ply").write_text("ply\nformat ascii 1.0\nelement vertex 3\nend_header\n1 2\n")
    return [str(inputs / "cases"), str(inputs / "p3.ply"), str(inputs / "broken.ply")]


def run_batch(cli, args, out):
    return subprocess.run([cli, "batch", *args, "--out", str(out), "--jobs", "2", "--no-report-html"],
                          capture_output=True, text=True)


def test_batch_runs_resumes_and_forces(cli, synth_cases, cohort_inputs, tmp_path):
    out = tmp_path / "out"
    r = run_batch(cli, cohort_inputs, out)
    assert r.returncode == 6, r.stderr  # one case failed, the others were done
    rows = read_csv(out / "cohort.csv")
    names = [synth_cases[0].name, synth_cases[1].name, "p3", "broken"]
    assert [row["case"] for row in rows] == names
    status = {row["case"]: row for row in rows}
    assert status["broken"]["status"] == "failed" and "broken.ply" in status["broken"]["message"]
    for n in names[:3]:
        assert status[n]["status"] == "ok" and status[n]["resumed"] == "no"
        assert float(status[n]["surface_mae_mm"]) < 2.0 and float(status[n]["landmark_mae_mm"]) < 15
        assert float(status[n]["volume_right_ml"]) > 50 and status[n]["notch_to_nipple_left_mm"]
        assert (out / n / "report.json").exists() and (out / n / "fitted.ply").exists()
    assert not (out / "broken" / "report.json").exists()
    assert "broken" in (out / "cohort.html").read_text()
    # not a terminal: one progress line per case, no bar
    assert r.stderr.count("breastfit batch: [") == 4 and "\r" not in r.stderr

    # The batch's outputs are those of `breastfit register`.
    single = tmp_path / "single"
    p3 = cohort_inputs[1]
    subprocess.run([cli, "register", p3, "--landmarks", p3.replace(".ply", ".mrk.json"), "--out", str(single),
                    "--quiet", "--no-report-html"], check=True)
    assert (single / "params.json").read_bytes() == (out / "p3" / "params.json").read_bytes()

    # Resumed: finished cases are not touched, the failed one is tried again.
    stamp = {n: (out / n / "fitted.ply").stat().st_mtime_ns for n in names[:3]}
    (out / names[0] / "report.json").unlink()  # as if killed before its commit: done again
    r = run_batch(cli, cohort_inputs, out)
    assert r.returncode == 6
    rows = {row["case"]: row for row in read_csv(out / "cohort.csv")}
    assert rows[names[0]]["resumed"] == "no" and rows[names[1]]["resumed"] == "yes" and rows["p3"]["resumed"] == "yes"
    assert rows["broken"]["status"] == "failed"
    assert (out / names[1] / "fitted.ply").stat().st_mtime_ns == stamp[names[1]]
    assert (out / names[0] / "fitted.ply").stat().st_mtime_ns != stamp[names[0]]
    for n in names[1:3]:  # a resumed row holds the numbers of the run that fitted it
        assert rows[n]["surface_mae_mm"] == status[n]["surface_mae_mm"]

    r = run_batch(cli, [*cohort_inputs[:2], "--force"], out)
    assert r.returncode == 0, r.stderr
    rows = read_csv(out / "cohort.csv")
    assert len(rows) == 3 and all(row["resumed"] == "no" and row["status"] == "ok" for row in rows)


def test_batch_bad_arguments(cli, synth_cases, tmp_path):
    r = subprocess.run([cli, "batch", str(tmp_path / "nothing"), "--out", str(tmp_path / "o")],
                       capture_output=True, text=True)
    assert r.returncode == 4 and "nothing" in r.stderr
    r = subprocess.run([cli, "batch", str(synth_cases[0]), str(synth_cases[0]), "--out", str(tmp_path / "o")],
                       capture_output=True, text=True)
    assert r.returncode == 3 and "two cases named" in r.stderr
