// breastfit volume MESH --curves CURVES.mrk.json: the volume inside each closed curve drawn on a
// surface (skin inside the curve against a chest-wall membrane spanning it), e.g. the breast
// contour a surgeon drew on a scan, the contours `register` transferred onto its fit, or a
// ground-truth surface with its contours (docs/TRANSFER.md "Breast measurements"). The surface
// must be closed inside each curve: a hole there is refused (transfer::curve_volume).
#include <cstdio>
#include <iostream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "breastfit/core/errors.h"
#include "breastfit/io/io.h"
#include "breastfit/io/markups.h"
#include "breastfit/mesh/units.h"
#include "breastfit/transfer/curve_region.h"
#include "command_support.h"
#include "commands.h"
#include "file_warnings.h"

namespace breastfit::cli {

void register_volume(CLI::App& app, int& exit_code) {
  struct Args {
    std::string mesh, curves, fill = "membrane", units = "auto";
    std::vector<std::string> names;
    double target_edge_mm = 2.0, max_distance_mm = 10.0;
    bool json = false, regions = false, quiet = false;
  };
  auto args = std::make_shared<Args>();
  auto* sub = app.add_subcommand(
      "volume", "Volume inside closed curves drawn on a surface (e.g. breast contours): the surface inside each "
                "curve against a chest-wall fill spanning it");
  sub->add_option("mesh", args->mesh,
                  "surface (.ply .obj .stl .vtk .vtp triangle mesh) to measure on: closed inside each curve. "
                  "fitted.ply of `breastfit register` gives report.json's volumes; a scan with a hole or open "
                  "border inside a curve is refused (holes are not filled)")
      ->required();
  sub->add_option("--curves,-c", args->curves, "closed curves on the surface (.mrk.json ClosedCurve, any units)")
      ->required();
  sub->add_option("--name", args->names, "measure only these curves (default: every closed curve)");
  sub->add_option("--fill", args->fill, "chest wall under the curve: membrane (harmonic) or thin-plate")
      ->check(CLI::IsMember({"membrane", "thin-plate"}));
  sub->add_option("--units", args->units, "mesh units: auto (from the extent), mm or m")
      ->check(CLI::IsMember({"auto", "mm", "m"}));
  sub->add_option("--target-edge", args->target_edge_mm,
                  "refine the surface around each curve to about this edge length before measuring, mm (0: the mesh as given)")
      ->check(CLI::NonNegativeNumber);
  sub->add_option("--max-distance", args->max_distance_mm,
                  "reject a curve farther than this from the surface on average, mm")
      ->check(CLI::PositiveNumber);
  sub->add_flag("--json", args->json, "print the results as JSON instead of the table (as every --json: redirect it to keep it)");
  sub->add_flag("--regions", args->regions, "with --json: include each curve's region (mesh vertex indices)");
  sub->add_flag("--quiet,-q", args->quiet, "no table on stdout (the JSON of --json is printed all the same)");
  sub->callback([args, &exit_code] {
    TriangleMesh mesh = io::read_mesh(args->mesh);
    if (mesh.is_point_cloud()) throw InvalidInput(args->mesh + ": a point cloud; volume needs a triangle mesh");
    mesh::Units units;
    try {
      units = mesh::resolve_units(parse_units_flag(args->units), mesh.V);
    } catch (const InvalidInput& e) {
      throw InvalidInput(args->mesh + ": " + e.what());
    }
    mesh.V *= mesh::to_mm_factor(units);
    const Markups markups = read_markups_warning(args->curves).markups;  // mm

    std::vector<const Curve*> chosen;
    if (args->names.empty()) {
      for (const Curve& c : markups.curves)
        if (c.closed) chosen.push_back(&c);
      if (chosen.empty()) throw InvalidInput(args->curves + ": no closed curve (ClosedCurve markup) to measure");
    } else {
      for (const std::string& name : args->names) {
        const Curve* c = markups.find_curve(name);
        if (!c) {
          std::string have;
          for (const Curve& k : markups.curves) have += (have.empty() ? "" : ", ") + k.name;
          throw InvalidInput(args->curves + ": no curve named '" + name + "' (has: " + (have.empty() ? "none" : have) + ")");
        }
        if (!c->closed)
          throw InvalidInput(args->curves + ": curve '" + name + "' is open; a volume needs a closed curve (ClosedCurve)");
        chosen.push_back(c);
      }
    }

    transfer::CurveVolumeOptions options;
    options.volume.fill = args->fill == "thin-plate" ? transfer::ChestWallFill::ThinPlate : transfer::ChestWallFill::Membrane;
    options.target_edge_mm = args->target_edge_mm;
    options.region.max_curve_distance_mm = args->max_distance_mm;

    nlohmann::json results = nlohmann::json::array();
    for (const Curve* c : chosen) {
      transfer::CurveVolume v;
      try {
        v = transfer::curve_volume(mesh, c->points, options);
      } catch (const InvalidInput& e) {
        throw InvalidInput(args->mesh + ": curve '" + c->name + "' of " + args->curves + ": " + e.what());
      }
      nlohmann::json j = {{"name", c->name},
                          {"volume_ml", v.volume_ml},
                          {"region_vertices", v.region.size()},
                          {"measured_vertices", v.measured_vertices},
                          {"refinement_levels", v.refinement_levels},
                          {"mean_curve_distance_mm", v.mean_curve_distance_mm}};
      if (args->regions) j["region"] = v.region;
      results.push_back(std::move(j));
    }
    if (!args->quiet && !args->json) {  // after every curve was measured: an error leaves no partial table
      std::printf("%-24s %10s %16s\n", "curve", "volume_ml", "region_vertices");
      for (const auto& j : results)
        std::printf("%-24s %10.1f %16zu\n", j["name"].get<std::string>().c_str(), j["volume_ml"].get<double>(),
                    j["region_vertices"].get<size_t>());
    }
    if (args->json) {
      const nlohmann::json doc = {
          {"mesh", args->mesh},
          {"curves_file", args->curves},
          {"mesh_units", std::string(mesh::units_name(units))},
          {"chest_wall", args->fill == "thin-plate" ? "thin_plate" : "membrane"},
          {"target_edge_mm", args->target_edge_mm},
          {"method",
           "surface inside each closed curve (topological cut along the curve snapped to the mesh) against a "
           "chest-wall fill of that region; the surface around the curve refined to target_edge_mm first"},
          {"curves", results}};
      std::cout << doc.dump(1) << "\n";
    }
    (void)exit_code;
  });
}

}  // namespace breastfit::cli
