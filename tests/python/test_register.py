"""register() against the CLI (bit for bit), the Fit's contents, save(), map_curves, breast_volumes."""
import json
import subprocess

import numpy as np
import pytest

import breastfit

# Outputs that hold no wall times: byte-identical between two runs of the same registration.
DETERMINISTIC = ["fitted.ply", "params.json", "landmarks.mrk.json", "drawings.mrk.json", "drawings.ply",
                 "drawings.obj", "scan_painted.ply"]


def strip_times(value):
    """The report without its wall times (time_s, timings_s, every "seconds"), which differ between runs."""
    if isinstance(value, dict):
        return {k: strip_times(v) for k, v in value.items() if k not in ("time_s", "timings_s", "seconds")}
    if isinstance(value, list):
        return [strip_times(v) for v in value]
    return value


@pytest.fixture(scope="module")
def cli_fit(cli, synth_cases, tmp_path_factory):
    out = tmp_path_factory.mktemp("cli") / "fit"
    case = synth_cases[0]
    subprocess.run([cli, "register", str(case / "scan.ply"), "--landmarks", str(case / "landmarks.mrk.json"),
                    "--out", str(out), "--quiet", "--no-report-html"], check=True)
    return out


@pytest.fixture(scope="module")
def fit(synth_cases):
    case = synth_cases[0]
    return breastfit.register(breastfit.read_mesh(case / "scan.ply"), landmarks=str(case / "landmarks.mrk.json"))


def test_register_matches_cli_bit_for_bit(fit, cli_fit, tmp_path):
    fit.save(tmp_path / "py", report_html=False)
    for name in DETERMINISTIC:
        assert (tmp_path / "py" / name).read_bytes() == (cli_fit / name).read_bytes(), name
    py_report = json.loads((tmp_path / "py" / "report.json").read_text())
    cli_report = json.loads((cli_fit / "report.json").read_text())
    # The run blocks differ by design (start time, command line); the scan was given to Python as
    # an in-memory mesh, so only the CLI's provenance lists a scan file.
    assert py_report["run"]["command_line"].startswith("python3") and "started_utc" in py_report["run"]
    cli_inputs = cli_report["provenance"].pop("inputs")
    fit_report = fit.report  # a new dict at every access
    for report in (py_report, fit_report):
        report.pop("run")
        assert report["provenance"].pop("inputs") == {k: v for k, v in cli_inputs.items() if k != "scan"}
    cli_report.pop("run")
    assert strip_times(py_report) == strip_times(cli_report)
    assert strip_times(fit_report) == strip_times(cli_report)
    cli_params = json.loads((cli_fit / "params.json").read_text())["params"]
    assert fit.params == cli_params  # exact doubles


def test_fit_contents(fit, synth_cases):
    assert fit.usable and fit.status == "ok" and fit.units == "mm"
    t = breastfit.Template.default()
    assert fit.vertices.shape == t.vertices.shape and np.array_equal(fit.faces, t.faces)
    assert set(fit.landmarks) == set(t.landmarks)
    contour = fit.drawings["breast_contour_R"]
    assert contour.closed and contour.points.shape[1] == 3
    assert contour.supported.shape == (contour.points.shape[0],) and contour.supported.dtype == bool
    assert 0.5 < contour.supported_fraction <= 1.0
    assert fit.report["table1"]["surface_mm"]["mae"] < 2.0
    # the parameters pose the template: without surface detail, close to the fitted vertices
    posed = breastfit.pose(fit.template, fit.params)
    assert np.median(np.linalg.norm(posed - fit.vertices, axis=1)) < 2.0
    vols = breastfit.breast_volumes(fit)
    assert vols["right"] > 50 and vols["left"] > 50


def test_arrays_and_dict_landmarks_give_the_same_fit(fit, synth_cases):
    case = synth_cases[0]
    scan = breastfit.read_mesh(case / "scan.ply")
    lm = breastfit.read_markups(case / "landmarks.mrk.json").points  # mm, as is the scan
    again = breastfit.register((scan.vertices, scan.faces), landmarks=lm)
    np.testing.assert_array_equal(again.vertices, fit.vertices)
    assert again.params == fit.params


def test_save_refuses_existing_outputs_without_force(fit, tmp_path):
    fit.save(tmp_path / "o", report_html=False)
    with pytest.raises(OSError, match="exists"):
        fit.save(tmp_path / "o", report_html=False)
    fit.save(tmp_path / "o", force=True, report_html=False)


def test_landmark_free_and_options(synth_cases):
    scan = breastfit.read_mesh(synth_cases[1] / "scan.ply")
    f = breastfit.register(scan, options={"use_landmarks": False})
    assert f.usable
    assert f.report["table1"]["landmarks_mm"]["n"] == 0


def test_map_curves_between_two_fits(fit, synth_cases):
    other = breastfit.register(synth_cases[1] / "scan.ply", landmarks=synth_cases[1] / "landmarks.mrk.json")
    contour = fit.drawings["breast_contour_R"]
    mapped, confidence = breastfit.map_curves(fit, other, {"c": breastfit.Curve(contour.points, closed=True)})
    assert mapped.curves["c"].points.shape == contour.points.shape
    assert confidence["summary"]["points"] == contour.points.shape[0]
    # it lands near where the second fit put its own contour
    own = other.drawings["breast_contour_R"].points
    d = np.linalg.norm(mapped.curves["c"].points[:, None, :] - own[None, :, :], axis=2).min(axis=1)
    assert np.median(d) < 5.0
    # the volume inside the fit's contour on its own fitted surface
    vols = breastfit.breast_volumes((fit.vertices, fit.faces), {"R": contour.points})
    assert 50 < vols["R"] < 3000
    with pytest.raises(ValueError):
        breastfit.breast_volumes((fit.vertices, fit.faces), {"R": contour.points + 500})
