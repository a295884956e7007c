// Mesh, Curve and Markups, and reading/writing them (io layer).
#include "bindings.h"
#include "breastfit/core/errors.h"
#include "breastfit/io/io.h"
#include "breastfit/io/markups.h"

namespace breastfit::python {

void bind_mesh_io(py::module_& m) {
  py::class_<TriangleMesh>(m, "Mesh", "A triangle mesh (or a point cloud when it has no faces).")
      .def(py::init([](const py::handle& vertices, const py::handle& faces) {
             TriangleMesh mesh;
             mesh.V = points_from_array(vertices, "vertices");
             if (!faces.is_none()) mesh.F = triangles_from_array(faces, mesh.num_vertices(), "faces");
             return mesh;
           }),
           py::arg("vertices"), py::arg("faces") = py::none(),
           "Mesh(vertices, faces=None): vertices an (n, 3) float array, faces an (m, 3) integer array of "
           "vertex indices (counter-clockwise = outward), None for a point cloud. Raises ValueError for another "
           "shape, a NaN or an index out of range.")
      .def_property(
          "vertices", [](const TriangleMesh& mesh) { return to_array(mesh.V); },
          [](TriangleMesh& mesh, const py::handle& v) {
            Points p = points_from_array(v, "vertices");
            if (mesh.F.rows() > 0 && mesh.F.maxCoeff() >= p.rows())
              throw InvalidInput("vertices: the faces index " + std::to_string(mesh.F.maxCoeff() + 1) +
                                 " vertices, got " + std::to_string(p.rows()));
            mesh.V = std::move(p);
            mesh.N.resize(0, 3);
            mesh.C.resize(0, 3);
          },
          "(n, 3) float64 array: the vertex positions (a copy; assign to change them)")
      .def_property(
          "faces", [](const TriangleMesh& mesh) { return to_array(mesh.F); },
          [](TriangleMesh& mesh, const py::handle& f) {
            mesh.F = f.is_none() ? Triangles(0, 3) : triangles_from_array(f, mesh.num_vertices(), "faces");
            mesh.UV.resize(0, 2);
            mesh.FUV.resize(0, 3);
          },
          "(m, 3) int64 array: the triangles (a copy; assign to change them)")
      .def_property_readonly("is_point_cloud", &TriangleMesh::is_point_cloud, "True when the mesh has no faces")
      .def("__repr__", [](const TriangleMesh& mesh) {
        return "<breastfit.Mesh " + std::to_string(mesh.num_vertices()) + " vertices, " +
               std::to_string(mesh.num_faces()) + " faces>";
      });

  py::class_<Curve>(m, "Curve", "A named polyline (a surgical drawing): points (n, 3) and closed.")
      .def(py::init([](const py::handle& points, bool closed, const std::string& name) {
             return Curve{name, closed, points_from_array(points, "curve '" + name + "'")};
           }),
           py::arg("points"), py::arg("closed") = false, py::arg("name") = "",
           "Curve(points, closed=False, name=''): points an (n, 3) float array in order along the curve.")
      .def_readwrite("name", &Curve::name)
      .def_readwrite("closed", &Curve::closed, "the last point joins the first")
      .def_property(
          "points", [](const Curve& c) { return to_array(c.points); },
          [](Curve& c, const py::handle& p) { c.points = points_from_array(p, "curve '" + c.name + "'"); },
          "(n, 3) float64 array (a copy)")
      .def_property_readonly("length", &Curve::length, "polyline length, closing segment included")
      .def("__repr__", [](const Curve& c) {
        return "<breastfit.Curve '" + c.name + "' " + std::to_string(c.points.rows()) + " points" +
               (c.closed ? ", closed>" : ">");
      });

  py::class_<Markups>(m, "Markups", "Named points and curves (a 3D Slicer markups file), LPS.")
      .def(py::init([](const py::handle& points, const py::handle& curves) {
             Markups mk;
             if (!points.is_none())
               for (const auto& [k, v] : points.cast<py::dict>()) {
                 const std::string name = py::str(k);
                 mk.points.push_back({name, vec3_from_array(v, "point '" + name + "'")});
               }
             if (!curves.is_none()) mk.curves = curves_from_dict(curves, "curve");
             return mk;
           }),
           py::arg("points") = py::none(), py::arg("curves") = py::none(),
           "Markups(points=None, curves=None): points a dict name → (3,) array, curves a dict name → Curve or "
           "(n, 3) array (an open curve).")
      .def_property_readonly(
          "points",
          [](const Markups& mk) {
            py::dict d;
            for (const auto& p : mk.points) d[py::str(p.name)] = to_array(p.position);
            return d;
          },
          "dict name → (3,) array, in file order")
      .def_property_readonly(
          "curves",
          [](const Markups& mk) {
            py::dict d;
            for (const auto& c : mk.curves) d[py::str(c.name)] = c;
            return d;
          },
          "dict name → Curve, in file order")
      .def("__repr__", [](const Markups& mk) {
        return "<breastfit.Markups " + std::to_string(mk.points.size()) + " points, " +
               std::to_string(mk.curves.size()) + " curves>";
      });

  m.def(
      "read_mesh",
      [](const std::filesystem::path& path) {
        py::gil_scoped_release release;
        return io::read_mesh(path);
      },
      py::arg("path"),
      "Reads a mesh or point cloud (.ply .obj .stl) in the file's units. Raises OSError naming the file for a "
      "missing, unreadable or malformed file.");
  m.def(
      "write_mesh",
      [](const std::filesystem::path& path, const py::handle& mesh, bool binary) {
        const TriangleMesh mk = mesh_from_python(mesh, "mesh");
        io::MeshWriteOptions o;
        o.binary = binary;
        py::gil_scoped_release release;
        io::write_mesh(path, mk, o);
      },
      py::arg("path"), py::arg("mesh"), py::arg("binary") = true,
      "Writes a Mesh or (vertices, faces) pair (.ply .obj .stl by extension; float coordinates in PLY). "
      "Raises ValueError for bad arrays, OSError when the file cannot be written.");
  m.def(
      "read_markups",
      [](const std::filesystem::path& path) {
        py::gil_scoped_release release;
        return io::read_markups(path);
      },
      py::arg("path"),
      "Reads a 3D Slicer markups file (.mrk.json): points and curves in LPS millimetres (RAS and metres are "
      "converted). Raises OSError naming the file for any problem.");
  m.def(
      "write_markups",
      [](const std::filesystem::path& path, const Markups& markups, const std::string& units) {
        io::MarkupsWriteOptions o;
        o.units = units;
        o.validate();
        py::gil_scoped_release release;
        io::write_markups(path, markups, o);
      },
      py::arg("path"), py::arg("markups"), py::arg("units") = "mm",
      "Writes markups (positions in millimetres) as a .mrk.json file declaring `units` (\"mm\" or \"m\"; "
      "positions converted). Raises OSError when the file cannot be written.");
}

}  // namespace breastfit::python
