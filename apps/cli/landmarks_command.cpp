// breastfit landmarks SCAN --out L.mrk.json: the 12 landmarks found on a scan without any given
// (a landmark-free registration, the nipples at the breast tips), each with a confidence, as a
// Slicer markups file a person can open, correct and pass to `register --landmarks`.
#include <cstdio>
#include <iostream>
#include <memory>
#include <string>

#include <nlohmann/json.hpp>

#include "breastfit/io/io.h"
#include "breastfit/io/markups.h"
#include "breastfit/mesh/units.h"
#include "breastfit/pipeline/detect_landmarks.h"
#include "command_support.h"
#include "commands.h"

namespace breastfit::cli {

void register_landmarks(CLI::App& app, int& /*exit_code*/) {
  struct Args {
    std::string scan, out, template_path, units = "auto";
    bool json = false, force = false;
  };
  auto args = std::make_shared<Args>();
  auto* sub = app.add_subcommand("landmarks", "Find the 12 landmarks on a scan without any given (landmark-free "
                                              "registration, nipples at the breast tips), each with a confidence");
  sub->add_option("scan", args->scan, "scan mesh (.ply .obj .stl; a vertex-only PLY is a point cloud)")->required();
  sub->add_option("--out,-o", args->out, "landmarks file to write (.mrk.json, the scan's frame and units)")->required();
  sub->add_option("--template,-t", args->template_path, "rigged template (.glb/.gltf); default: the shipped torso");
  sub->add_option("--units", args->units, "scan units: auto (from the extent), mm or m")
      ->check(CLI::IsMember({"auto", "mm", "m"}));
  sub->add_flag("--json", args->json, "print the landmarks, confidences and the orientation found as JSON");
  sub->add_flag("--force", args->force, "replace an existing --out file");
  sub->callback([args] {
    check_output_file(args->out, {args->scan, args->template_path}, args->force);
    pipeline::RegisterRequest req;
    req.scan = io::read_mesh(args->scan);
    req.scan_name = args->scan;
    req.units = parse_units_flag(args->units);
    req.model = std::make_shared<const model::RiggedModel>(load_template(args->template_path));
    const pipeline::DetectedLandmarks d = pipeline::detect_landmarks(req);
    const auto& r = d.registration;
    io::MarkupsWriteOptions mo;
    mo.units = r.scan.units == mesh::Units::Metres ? "m" : "mm";
    io::write_markups(args->out, pipeline::to_markups(d.landmarks), mo);
    const auto& o = r.fit.summary.orientation;
    if (args->json) {
      nlohmann::json lm = nlohmann::json::array();
      const double from_mm = 1.0 / r.scan.to_mm;
      for (const auto& p : d.landmarks) {
        const Vec3 x = p.position_mm * from_mm;
        lm.push_back({{"name", p.name}, {"position", {x.x(), x.y(), x.z()}}, {"confidence", p.confidence},
                      {"method", p.method}});
      }
      nlohmann::json j = {{"scan", args->scan},
                          {"out", args->out},
                          {"units", std::string(mesh::units_name(r.scan.units))},
                          {"coordinate_system", "LPS"},
                          {"initialization", r.fit.summary.initialization_detail},
                          {"orientation_margin", std::isfinite(o.margin) ? nlohmann::json(o.margin) : nlohmann::json()},
                          {"arm_pose", o.arm_pose},
                          {"time_s", r.time_s},
                          {"landmarks", lm},
                          {"warnings", r.warnings}};
      std::cout << j.dump(1) << "\n";
      return;
    }
    std::cout << "landmarks found in " << r.time_s << " s (" << r.fit.summary.initialization_detail << ")\n";
    char buf[160];
    for (const auto& p : d.landmarks) {
      std::snprintf(buf, sizeof buf, "  %-22s confidence %.2f  %s\n", p.name.c_str(), p.confidence, p.method.c_str());
      std::cout << buf;
    }
    for (const auto& w : r.warnings) std::cerr << "breastfit: warning: " << w << "\n";
    std::cout << "  written: " << args->out << " (check and correct them, e.g. in 3D Slicer, before register --landmarks)\n";
  });
}

}  // namespace breastfit::cli
