"""landmarks(scan): the automatic landmarks against the synthetic truth, in the scan's units."""
import json

import numpy as np
import pytest

import breastfit


def truth_landmarks(case):
    data = json.loads((case / "truth" / "landmarks.json").read_text())
    items = data["landmarks"] if isinstance(data, dict) and "landmarks" in data else data
    if isinstance(items, dict):
        return {k: np.asarray(v, dtype=float) for k, v in items.items()}
    return {d["name"]: np.asarray(d["position"], dtype=float) for d in items}


def test_landmarks_found_near_the_truth(synth_cases):
    case = synth_cases[0]
    found = breastfit.landmarks(breastfit.read_mesh(case / "scan.ply"))
    assert set(found) == set(breastfit.Template.default().landmarks)
    truth = truth_landmarks(case)
    errors = []
    for name, entry in found.items():
        assert entry["position"].shape == (3,) and 0.0 <= entry["confidence"] <= 1.0 and entry["method"]
        if name in truth:
            errors.append(np.linalg.norm(entry["position"] - truth[name]))
    assert len(errors) >= 6
    assert np.mean(errors) < 30.0  # mm: a landmark-free fit, a starting point to correct
    assert found["nipple_R"]["method"] != found["sternal_notch"]["method"]  # nipples from the breast tips


def test_landmarks_bad_input():
    with pytest.raises(ValueError):
        breastfit.landmarks((np.zeros((2, 3)), np.zeros((0, 3), dtype=np.int64)))
    with pytest.raises(OSError):
        breastfit.landmarks("/nonexistent/scan.ply")
