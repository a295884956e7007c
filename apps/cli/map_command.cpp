// breastfit map --from FIT_A --to FIT_B INPUT.mrk.json --out OUT.mrk.json: carries points and
// curves drawn on scan A to scan B through the template correspondence of two fits.
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <optional>

#include <nlohmann/json.hpp>

#include "breastfit/core/errors.h"
#include "breastfit/fit/scan_target.h"
#include "breastfit/io/io.h"
#include "breastfit/io/output_set.h"
#include "breastfit/io/markups.h"
#include "breastfit/pipeline/scan_input.h"
#include "breastfit/transfer/fit_directory.h"
#include "breastfit/transfer/surface_map.h"
#include "breastfit/transfer/surface_map_json.h"
#include "command_support.h"
#include "commands.h"
#include "file_warnings.h"

namespace breastfit::cli {
namespace fs = std::filesystem;

void register_map(CLI::App& app, int& exit_code) {
  struct Args {
    std::string from, to, input, out, template_path, template_mesh, to_scan, confidence;
    double max_distance = 10.0;
    bool force = false, quiet = false;
  };
  auto args = std::make_shared<Args>();
  auto* sub = app.add_subcommand(
      "map", "Map points and curves drawn on scan A (e.g. standing) to scan B (e.g. supine) through two fits of "
             "the template (outputs of `breastfit register`)");
  sub->add_option("input", args->input, "points/curves on scan A (.mrk.json, any units, LPS or RAS)")->required();
  sub->add_option("--from", args->from, "output directory of `breastfit register` for scan A")->required();
  sub->add_option("--to", args->to, "output directory of `breastfit register` for scan B")->required();
  sub->add_option("--out,-o", args->out, "mapped markups (.mrk.json, in scan B's frame and units)")->required();
  sub->add_option("--to-scan", args->to_scan,
                  "scan B (.ply .obj .stl .vtk .vtp): project the mapped points onto it (default: onto fitted B)");
  sub->add_option("--template,-t", args->template_path, "the template both fits used; default: the shipped torso");
  sub->add_option("--mesh", args->template_mesh, "the template's skinned mesh to use when its file has several (node or mesh name)");
  sub->add_option("--confidence", args->confidence,
                  "per-point confidence JSON (default: OUT with .mrk.json replaced by .confidence.json)");
  sub->add_option("--max-distance", args->max_distance, "projection onto scan B: farthest scan point used, mm")
      ->check(CLI::PositiveNumber);
  sub->add_flag("--force", args->force, "replace existing output files");
  sub->add_flag("--quiet,-q", args->quiet, "no summary");
  sub->callback([args, &exit_code] {
    std::string conf = args->confidence;
    if (conf.empty()) {
      const std::string o = args->out;
      const std::string ext = ".mrk.json";
      conf = (o.size() > ext.size() && o.compare(o.size() - ext.size(), ext.size(), ext) == 0
                  ? o.substr(0, o.size() - ext.size())
                  : fs::path(o).replace_extension().string()) +
             ".confidence.json";
    }
    for (const std::string& p : {args->out, conf}) check_output_file(p, {args->input}, args->force);

    const model::RiggedModel model = load_template(args->template_path, args->template_mesh);
    const transfer::FitDirectory a = transfer::read_fit_directory(args->from, &model);
    const transfer::FitDirectory b = transfer::read_fit_directory(args->to, &model);
    const Markups input = read_markups_warning(args->input).markups;  // LPS mm
    if (input.points.empty() && input.curves.empty()) throw InvalidInput(args->input + ": no points or curves to map");

    std::optional<fit::ScanTarget> scan_b;
    bool is_point_cloud = false;
    if (!args->to_scan.empty()) {
      const TriangleMesh raw = io::read_mesh(args->to_scan);
      const mesh::Units units = b.units == "m" ? mesh::Units::Metres : mesh::Units::Millimetres;
      pipeline::PreparedScan prepared = pipeline::prepare_scan(raw, args->to_scan, units);
      scan_b.emplace(prepared.mesh_mm, 0);
      is_point_cloud = prepared.was_point_cloud;
    }
    transfer::MapOptions options;
    options.projection.reject_scan_border = !is_point_cloud;  // splats are all border
    options.projection.max_distance_mm = args->max_distance;
    const transfer::MapResult r =
        transfer::map_markups(input, a.fitted_mm, b.fitted_mm, scan_b ? &*scan_b : nullptr, options);

    io::MarkupsWriteOptions wo;
    wo.units = b.units;
    wo.points_name = "mapped";
    nlohmann::json j = transfer::to_json(r);
    j["from"] = args->from;
    j["to"] = args->to;
    j["input"] = args->input;
    j["output"] = args->out;
    j["scan_b"] = args->to_scan.empty() ? nlohmann::json(nullptr) : nlohmann::json(args->to_scan);
    const auto write_confidence = [&](const fs::path& path) {
      std::ofstream f(path);
      if (!f) throw IoError(conf, "cannot open for writing");
      f << j.dump(1) << "\n";
      if (!f) throw IoError(conf, "write failed");
    };
    // Both files as one set (io/output_set.h), the markups last: a failure leaves neither.
    const fs::path out_path = fs::absolute(args->out).lexically_normal(), conf_path = fs::absolute(conf).lexically_normal();
    if (out_path.parent_path() == conf_path.parent_path()) {
      io::OutputSet set = io::loose_file_set({conf_path, out_path});
      write_confidence(set.path(conf_path.filename().string()));
      io::write_markups(set.path(out_path.filename().string()), r.markups, wo);
      set.commit();
    } else {
      io::OutputSet conf_set = io::loose_file_set({conf_path}), out_set = io::loose_file_set({out_path});
      write_confidence(conf_set.path(conf_path.filename().string()));
      io::write_markups(out_set.path(out_path.filename().string()), r.markups, wo);
      conf_set.commit();
      out_set.commit();
    }

    if (!args->quiet) {
      const auto& s = j["summary"];
      std::printf("mapped %d points (%zu point%s, %zu curve%s) from %s to %s%s\n", s["points"].get<int>(),
                  input.points.size(), input.points.size() == 1 ? "" : "s", input.curves.size(),
                  input.curves.size() == 1 ? "" : "s", args->from.c_str(), args->to.c_str(),
                  scan_b ? " (projected onto scan B)" : " (on fitted B)");
      std::printf("confidence: %d high, %d medium, %d low; distance to fitted A mean %.2f mm, max %.2f mm\n",
                  s["high"].get<int>(), s["medium"].get<int>(), s["low"].get<int>(),
                  s["mean_distance_to_fit_a_mm"].get<double>(), s["max_distance_to_fit_a_mm"].get<double>());
      if (scan_b)
        std::printf("supported by scan B: %d of %d\n", s["supported_by_scan_b"].get<int>(), s["points"].get<int>());
      std::printf("wrote %s and %s\n", args->out.c_str(), conf.c_str());
    }
    (void)exit_code;
  });
}

}  // namespace breastfit::cli
