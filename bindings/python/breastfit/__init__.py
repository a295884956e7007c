"""breastfit: registers a rigged template torso to breast scans and transfers surgical drawings.

The C++ library through pybind11, numpy arrays in and out (docs/PYTHON.md):

    import breastfit
    fit = breastfit.register(breastfit.read_mesh("scan.ply"), landmarks="landmarks.mrk.json")
    fit.drawings["breast_contour_R"].points     # (n, 3) in the scan's units
    fit.save("out")                             # the output set of `breastfit register`

Bad input raises ValueError, a file problem OSError. `breastfit.cohort` runs a cohort on a Dask
cluster. `landmarks(scan)` finds the 12 landmarks automatically (to check before register()).
"""
import os as _os

from . import _breastfit

# Installed (cmake --install): <prefix>/lib/pythonX.Y/site-packages/breastfit → <prefix>/share/breastfit.
_installed_template = _os.path.normpath(_os.path.join(_os.path.dirname(__file__), "..", "..", "..", "..", "share",
                                                      "breastfit", "default_torso.glb"))
if _os.path.isfile(_installed_template):
    _breastfit._set_installed_template(_installed_template)

from ._breastfit import (  # noqa: E402,F401  (the public API)
    Curve,
    Drawing,
    Fit,
    Markups,
    Mesh,
    Template,
    breast_volumes,
    landmarks,
    map_curves,
    pose,
    read_markups,
    read_mesh,
    register,
    write_markups,
    write_mesh,
)

__all__ = [
    "Curve", "Drawing", "Fit", "Markups", "Mesh", "Template", "breast_volumes", "landmarks", "map_curves", "pose",
    "read_markups", "read_mesh", "register", "write_markups", "write_mesh",
]
__version__ = "0.1.0"
