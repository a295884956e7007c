"""Fixtures of the Python module's tests: the built CLI and synthetic cases made with it.

Run by CTest (tests/CMakeLists.txt) with PYTHONPATH=<build>/python and BREASTFIT_CLI set.
"""
import os
import shutil
import subprocess
from pathlib import Path

import pytest


@pytest.fixture(scope="session")
def cli() -> str:
    path = os.environ.get("BREASTFIT_CLI")
    if not path or not os.path.exists(path):
        pytest.fail("BREASTFIT_CLI must name the built breastfit executable (CTest sets it)")
    return path


@pytest.fixture(scope="session")
def source_dir() -> Path:
    return Path(os.environ.get("BREASTFIT_SOURCE_DIR", Path(__file__).resolve().parents[2]))


@pytest.fixture(scope="session")
def synth_cases(cli, tmp_path_factory) -> list[Path]:
    """Three synthetic case directories (scan.ply, landmarks.mrk.json, truth/), seeds 11–13."""
    root = tmp_path_factory.mktemp("synth")
    subprocess.run([cli, "synth", "--out", str(root), "--count", "3", "--seed", "11", "--quiet"], check=True)
    cases = sorted(p for p in root.iterdir() if (p / "scan.ply").exists())
    assert len(cases) == 3
    return cases


@pytest.fixture()
def case_copy(synth_cases, tmp_path) -> Path:
    """A private copy of the first synthetic case's scan and landmarks."""
    d = tmp_path / "case"
    d.mkdir()
    for name in ("scan.ply", "landmarks.mrk.json"):
        shutil.copy(synth_cases[0] / name, d / name)
    return d
