"""breastfit: registers a rigged template torso to breast scans and transfers surgical drawings.

The C++ library through pybind11, numpy arrays in and out (docs/PYTHON.md):

    import breastfit
    fit = breastfit.register(breastfit.read_mesh("scan.ply"), landmarks="landmarks.mrk.json")
    fit.drawings["breast_contour_R"].points     # (n, 3) in the scan's units
    fit.save("out")                             # the output set of `breastfit register`

Bad input raises ValueError, a file problem OSError. `breastfit.cohort` runs a cohort on a Dask
cluster. Automatic landmarks (`landmarks(scan)`) are not part of this module yet.
"""
from ._breastfit import (  # noqa: F401  (the public API)
    Curve,
    Drawing,
    Fit,
    Markups,
    Mesh,
    Template,
    breast_volumes,
    map_curves,
    pose,
    read_markups,
    read_mesh,
    register,
    write_markups,
    write_mesh,
)

__all__ = [
    "Curve", "Drawing", "Fit", "Markups", "Mesh", "Template", "breast_volumes", "map_curves", "pose",
    "read_markups", "read_mesh", "register", "write_markups", "write_mesh",
]
__version__ = "0.1.0"
