// map_curves (standing ↔ supine through two fits) and breast_volumes (transfer layer).
#include "bindings.h"
#include "breastfit/core/errors.h"
#include "breastfit/io/markups.h"
#include "breastfit/transfer/curve_region.h"
#include "breastfit/transfer/surface_map.h"
#include "breastfit/transfer/surface_map_json.h"
#include "fit_object.h"

namespace breastfit::python {
namespace {

/// Curves and points in millimetres from Markups / a dict name → (n, 3) (both in `to_mm` units)
/// or a markups file (its declared units).
Markups markups_mm_from_python(const py::handle& value, double to_mm, const std::string& what) {
  if (const auto path = path_from_python(value)) {
    py::gil_scoped_release release;
    return io::read_markups(*path);
  }
  Markups mk;
  if (py::isinstance<Markups>(value)) {
    mk = value.cast<Markups>();
  } else if (py::isinstance<py::dict>(value)) {
    mk.curves = curves_from_dict(value, what);
  } else {
    throw InvalidInput(what + ": expected Markups, a dict name → (n, 3) array or Curve, or a markups file path");
  }
  for (auto& p : mk.points) p.position *= to_mm;
  for (auto& c : mk.curves) c.points *= to_mm;
  return mk;
}

}  // namespace

void bind_transfer(py::module_& m) {
  m.def(
      "map_curves",
      [](const Fit& from, const Fit& to, const py::handle& curves) {
        if (from.model->rest.F.rows() != to.model->rest.F.rows() || from.model->num_vertices() != to.model->num_vertices())
          throw InvalidInput("map_curves: the two fits use different templates");
        const Markups input = markups_mm_from_python(curves, from.result.scan.to_mm, "curves");
        if (input.points.empty() && input.curves.empty()) throw InvalidInput("curves: no points or curves to map");
        transfer::MapResult r;
        {
          py::gil_scoped_release release;
          r = transfer::map_markups(input, from.result.fitted_mm, to.result.fitted_mm, nullptr);
        }
        const double scale = 1.0 / to.result.scan.to_mm;
        for (auto& p : r.markups.points) p.position *= scale;
        for (auto& c : r.markups.curves) c.points *= scale;
        return py::make_tuple(r.markups, python_from_json(transfer::to_json(r)));
      },
      py::arg("fit_from"), py::arg("fit_to"), py::arg("curves"),
      R"(Carries points and curves drawn on scan A to scan B through two fits of the same template
(closest point on fitted A → the same template surface point on fitted B; docs/TRANSFER.md), as
`breastfit map` does without --to-scan.

curves  Markups or a dict name → (n, 3) array / Curve, in fit_from's units; or a .mrk.json path
Returns (Markups in fit_to's units, dict with one confidence entry per control point and a summary,
as map's .confidence.json). Raises ValueError for fits of different templates or bad arrays.)");

  m.def(
      "breast_volumes",
      [](const py::handle& surface, const py::handle& curves, const std::string& fill, const py::handle& units) {
        if (py::isinstance<Fit>(surface)) {
          if (!curves.is_none())
            throw InvalidInput("breast_volumes: with a Fit, the volumes are the fit's own (curves must be None)");
          const auto& b = surface.cast<const Fit&>().result.breasts;
          py::dict d;
          d["right"] = b.right.volume_ml ? py::object(py::float_(*b.right.volume_ml)) : py::none();
          d["left"] = b.left.volume_ml ? py::object(py::float_(*b.left.volume_ml)) : py::none();
          return d;
        }
        if (curves.is_none()) throw InvalidInput("breast_volumes: curves are needed for a mesh");
        TriangleMesh mesh = mesh_from_python(surface, "surface");
        if (mesh.is_point_cloud()) throw InvalidInput("surface: a point cloud; a volume needs a triangle mesh");
        const mesh::Units u = mesh::resolve_units(units_from_python(units), mesh.V);
        const double to_mm = mesh::to_mm_factor(u);
        mesh.V *= to_mm;
        Markups mk = markups_mm_from_python(curves, to_mm, "curves");
        if (py::isinstance<py::dict>(curves))
          for (Curve& c : mk.curves) c.closed = true;  // a dict of arrays names regions
        transfer::CurveVolumeOptions o;
        if (fill == "thin-plate") o.volume.fill = transfer::ChestWallFill::ThinPlate;
        else if (fill != "membrane") throw InvalidInput("fill: expected \"membrane\" or \"thin-plate\", got \"" + fill + "\"");
        py::dict d;
        for (const Curve& c : mk.curves) {
          if (!c.closed) continue;  // an open curve encloses no region
          double ml = 0;
          {
            py::gil_scoped_release release;
            try {
              ml = transfer::curve_volume(mesh, c.points, o).volume_ml;
            } catch (const InvalidInput& e) {
              throw InvalidInput("curve '" + c.name + "': " + e.what());
            }
          }
          d[py::str(c.name)] = ml;
        }
        if (d.empty()) throw InvalidInput("curves: no closed curve to measure");
        return d;
      },
      py::arg("surface"), py::arg("curves") = py::none(), py::arg("fill") = "membrane", py::arg("units") = "auto",
      R"(Breast volumes in millilitres.

breast_volumes(fit): {"right", "left"} of the fit's measurements (inside breast_contour_R/L on the
fitted model; None when a contour is missing).
breast_volumes(surface, curves): the volume inside each closed curve drawn on a surface (a Mesh,
(vertices, faces) or a mesh path), against a chest-wall fill spanning it ("membrane" or
"thin-plate"), as `breastfit volume`; curves are Markups (its closed curves), a dict name → (n, 3)
array (each taken as closed) or a .mrk.json path (its closed curves), in the surface's units.)");
}

}  // namespace breastfit::python
