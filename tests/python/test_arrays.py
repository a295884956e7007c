"""numpy round trips, the template, pose, and the errors for bad arrays and files."""
import math

import numpy as np
import pytest

import breastfit


def tetra():
    v = np.array([[0, 0, 0], [10, 0, 0], [0, 10, 0], [0, 0, 10]], dtype=float)
    f = np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]], dtype=np.int32)
    return v, f


@pytest.mark.parametrize("ext", [".ply", ".obj", ".stl"])
def test_mesh_round_trip(tmp_path, ext):
    v, f = tetra()
    v = v + np.array([0.25, -1.5, 3.125])  # exactly representable in float32
    path = tmp_path / f"t{ext}"
    breastfit.write_mesh(path, (v, f))
    m = breastfit.read_mesh(path)
    assert m.faces.dtype == np.int64 and m.vertices.dtype == np.float64
    if ext == ".stl":  # STL stores triangle corners: compare the triangles' coordinates
        np.testing.assert_array_equal(m.vertices[m.faces], v[f])
    else:
        np.testing.assert_array_equal(m.vertices, v)
        np.testing.assert_array_equal(m.faces, f)


def test_mesh_object_and_arrays_are_copies():
    v, f = tetra()
    m = breastfit.Mesh(v, f)
    out = m.vertices
    out[0, 0] = 99.0
    assert m.vertices[0, 0] == 0.0
    m.vertices = v * 2
    np.testing.assert_array_equal(m.vertices, v * 2)
    assert not m.is_point_cloud and breastfit.Mesh(v).is_point_cloud


def test_markups_round_trip(tmp_path):
    pts = {"nipple_R": np.array([1.5, 2.0, 3.0]), "nipple_L": np.array([-1.5, 2.0, 3.0])}
    curve = breastfit.Curve(np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0.5]]), closed=True)
    mk = breastfit.Markups(points=pts, curves={"contour": curve})
    path = tmp_path / "m.mrk.json"
    breastfit.write_markups(path, mk)
    back = breastfit.read_markups(path)
    assert list(back.points) == ["nipple_R", "nipple_L"]
    for k in pts:
        np.testing.assert_array_equal(back.points[k], pts[k])
    assert back.curves["contour"].closed
    np.testing.assert_array_equal(back.curves["contour"].points, curve.points)
    breastfit.write_markups(tmp_path / "m_in_m.mrk.json", mk, units="m")  # converted on write, back to mm on read
    np.testing.assert_allclose(breastfit.read_markups(tmp_path / "m_in_m.mrk.json").points["nipple_R"], pts["nipple_R"])


@pytest.mark.parametrize("vertices, faces, message", [
    (np.zeros((4, 2)), None, "shape"),
    (np.zeros(12), None, "shape"),
    (np.array([[0, 0, math.nan]] * 4), None, "not finite"),
    (np.array([[0, 0, math.inf]] * 4), None, "not finite"),
    (np.array([["a", "b", "c"]]), None, "numbers"),
    (np.zeros((4, 3)), np.array([[0, 1, 4]]), "outside"),
    (np.zeros((4, 3)), np.array([[0, -1, 2]]), "outside"),
    (np.zeros((4, 3)), np.array([[0, 1]]), "shape"),
    (np.zeros((4, 3)), np.array([[0.0, 1.0, 2.0]]), "integer"),
])
def test_bad_arrays_raise_value_error(vertices, faces, message):
    with pytest.raises(ValueError, match=message):
        breastfit.Mesh(vertices, faces)
    with pytest.raises(ValueError, match=message):
        breastfit.register((vertices, faces))


def test_bad_landmarks_raise_value_error(synth_cases):
    scan = breastfit.read_mesh(synth_cases[0] / "scan.ply")
    with pytest.raises(ValueError, match="unknown name"):
        breastfit.register(scan, landmarks={"belly_button": [0, 0, 0]})
    with pytest.raises(ValueError, match="3 coordinates"):
        breastfit.register(scan, landmarks={"nipple_R": [0, 0]})
    with pytest.raises(ValueError, match="not finite"):
        breastfit.register(scan, landmarks={"nipple_R": [0, math.nan, 0]})
    with pytest.raises(ValueError):
        breastfit.register(scan, options={"weights": {"lambda_nonsense": 1}})
    with pytest.raises(ValueError, match="units"):
        breastfit.register(scan, units="inch")


def test_file_problems_raise_os_error(tmp_path):
    with pytest.raises(OSError, match="missing.ply"):
        breastfit.read_mesh(tmp_path / "missing.ply")
    (tmp_path / "bad.ply").write_text("ply\nformat nonsense\n")
    with pytest.raises(OSError, match="bad.ply"):
        breastfit.read_mesh(tmp_path / "bad.ply")
    with pytest.raises(OSError):
        breastfit.read_markups(tmp_path / "missing.mrk.json")
    with pytest.raises(OSError):
        breastfit.register(tmp_path / "missing.ply")
    with pytest.raises(OSError):
        breastfit.Template.load(tmp_path / "missing.glb")
    v, f = tetra()
    with pytest.raises(OSError):
        breastfit.write_mesh(tmp_path / "no_dir" / "t.ply", (v, f))


def test_template_by_name_and_pose():
    t = breastfit.Template.default()
    assert t.vertices.shape[1] == 3 and t.faces.shape[1] == 3
    assert len(t.bones) == 9 and next(iter(t.bones.values()))["parent"] is None
    assert {"nipple_R", "nipple_L", "sternal_notch"} <= set(t.landmarks)
    assert {"breast_contour_R", "breast_contour_L"} <= set(t.drawings)
    assert t.drawings["breast_contour_R"].closed
    shape = next(iter(t.blendshapes))
    assert t.blendshapes[shape]["displacements"].shape == (len(t.blendshapes[shape]["vertices"]), 3)
    np.testing.assert_allclose(breastfit.pose(t), t.vertices, atol=1e-9)
    # a blendshape at weight w moves exactly its vertices by w · displacement
    b = t.blendshapes[shape]
    w = 0.5 * b["hi"]
    moved = breastfit.pose(t, {f"shape.{shape}": w})
    np.testing.assert_allclose(moved[b["vertices"]], t.vertices[b["vertices"]] + w * b["displacements"], atol=1e-9)
    assert f"shape.{shape}" in t.param_names and "global.scale" in t.param_names
    with pytest.raises(ValueError, match="nonsense"):
        breastfit.pose(t, {"nonsense": 1.0})
    with pytest.raises(ValueError):
        breastfit.pose(t, {f"shape.{shape}": b["hi"] + 10})


def test_type_stubs_match_the_module():
    """__init__.pyi declares exactly the public API, and every member it lists exists."""
    import ast
    import pathlib

    stub = ast.parse((pathlib.Path(breastfit.__file__).parent / "__init__.pyi").read_text())
    declared = {n.name: n for n in stub.body if isinstance(n, (ast.ClassDef, ast.FunctionDef))}
    assert set(declared) == set(breastfit.__all__)
    for name, node in declared.items():
        if isinstance(node, ast.ClassDef):
            cls = getattr(breastfit, name)
            for member in node.body:
                member_name = getattr(member, "name", None) or getattr(getattr(member, "target", None), "id", None)
                if member_name and member_name != "__init__":
                    assert hasattr(cls, member_name), f"{name}.{member_name}"
        assert getattr(breastfit, name).__doc__, f"{name} has no docstring"
