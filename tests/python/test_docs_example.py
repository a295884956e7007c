"""docs/PYTHON.md's complete example, executed as written in a directory holding a synthetic case."""
import os
import re
import shutil

import matplotlib.image


def test_python_md_example(source_dir, synth_cases, tmp_path, monkeypatch):
    text = (source_dir / "docs" / "PYTHON.md").read_text()
    m = re.search(r"<!-- example: executed by tests/python/test_docs_example.py -->\n```python\n(.*?)```", text, re.S)
    assert m, "docs/PYTHON.md: the tested example block is missing"
    for name in ("scan.ply", "landmarks.mrk.json"):
        shutil.copy(synth_cases[2] / name, tmp_path / name)
    monkeypatch.chdir(tmp_path)
    exec(compile(m.group(1), "docs/PYTHON.md", "exec"), {"__name__": "__main__"})
    image = matplotlib.image.imread(tmp_path / "drawings.png")
    assert image.shape[0] > 300 and image.std() > 0.05  # something was drawn
    for name in ("fitted.ply", "params.json", "drawings.mrk.json", "report.json", "report.html"):
        assert os.path.exists(tmp_path / "fit" / name), name
