// `breastfit synth`: synthetic scan cases with full ground truth, in the bench case layout.
// See docs/SYNTH.md.
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <string>

#include "breastfit/core/errors.h"
#include "breastfit/core/timer.h"
#include "breastfit/model/gltf_io.h"
#include "breastfit/model/template_library.h"
#include "breastfit/synth/case_writer.h"
#include "breastfit/synth/synth_case.h"
#include "breastfit/template/default_template.h"
#include "command_support.h"
#include "commands.h"

namespace breastfit::cli {
namespace {

namespace fs = std::filesystem;

struct SynthArgs {
  std::string out;
  std::uint64_t seed = 1;
  std::string pose = "standing";
  std::string units = "mm";
  std::string template_file, template_mesh;
  int count = 1;
  bool force = false;
  bool quiet = false;
  std::optional<double> noise_mm, lowfreq_noise_mm, rotation_deg, translation_m, landmark_noise_mm, shape_amplitude;
  std::optional<int> holes, fragments, azimuths, bumps, subdivisions, max_faces;
  std::optional<double> target_edge_mm;
  bool no_table = false;
};

/// The shipped template when it exists, else the template built in memory (about a second).
model::RiggedModel load_model(const std::string& path, const std::string& mesh) {
  if (!path.empty() || !mesh.empty()) return load_template(path, mesh);
  try {
    return model::load_default_template();
  } catch (const IoError&) {
    return templ::build_default_template();
  }
}

synth::SynthOptions make_options(const SynthArgs& a, std::uint64_t seed, synth::PoseType pose) {
  synth::SynthOptions o;
  o.seed = seed;
  o.pose = pose;
  o.units = a.units;
  if (a.noise_mm) o.artifacts.white_noise_mm = *a.noise_mm;
  if (a.lowfreq_noise_mm) o.artifacts.lowfreq_noise_mm = *a.lowfreq_noise_mm;
  if (a.rotation_deg) o.misalign_rotation_deg = *a.rotation_deg;
  if (a.translation_m) o.misalign_translation_m = *a.translation_m;
  if (a.landmark_noise_mm) o.landmark_noise_mm = *a.landmark_noise_mm;
  if (a.shape_amplitude) o.subject.shape_amplitude = *a.shape_amplitude;
  if (a.holes) o.artifacts.n_holes = *a.holes;
  if (a.fragments) o.artifacts.n_fragments = *a.fragments;
  if (a.azimuths) o.scanner.n_azimuth = *a.azimuths;
  if (a.bumps) o.deformation.n_bumps = *a.bumps;
  if (a.subdivisions) o.refinement.max_steps = *a.subdivisions;
  if (a.max_faces) o.refinement.max_faces = *a.max_faces;
  if (a.target_edge_mm) o.refinement.target_edge_mm = *a.target_edge_mm;
  if (a.no_table) o.artifacts.table_strip = false;
  o.validate();
  return o;
}

void run(const SynthArgs& a) {
  if (a.out.empty()) throw InvalidInput("--out is required");
  if (a.count < 1 || a.count > 1000) throw InvalidInput("--count must be in [1, 1000]");
  const synth::PoseType first_pose = synth::parse_pose_type(a.pose);
  // Validate every option before the (slow) template load.
  (void)make_options(a, a.seed, first_pose);
  const fs::path out(a.out);
  for (int i = 0; i < a.count; ++i) {  // refuse before writing anything
    const std::uint64_t seed = a.seed + static_cast<std::uint64_t>(i);
    const synth::PoseType pose = (i % 2 == 0) == (first_pose == synth::PoseType::Standing)
                                     ? synth::PoseType::Standing
                                     : synth::PoseType::Supine;
    const fs::path dir = a.count == 1 ? out : out / synth::default_case_id(make_options(a, seed, pose));
    if (!a.force && (fs::exists(dir / "scan.ply") || fs::exists(dir / "truth")))
      throw IoError(dir.string(), "a case already exists here (use --force to overwrite it)");
  }
  const model::RiggedModel model = load_model(a.template_file, a.template_mesh);
  for (int i = 0; i < a.count; ++i) {
    const std::uint64_t seed = a.seed + static_cast<std::uint64_t>(i);
    const synth::PoseType pose = (i % 2 == 0) == (first_pose == synth::PoseType::Standing)
                                     ? synth::PoseType::Standing
                                     : synth::PoseType::Supine;
    synth::SynthOptions o = make_options(a, seed, pose);
    const fs::path dir = a.count == 1 ? out : out / synth::default_case_id(o);
    if (a.count == 1) o.case_id = dir.filename().empty() ? dir.parent_path().filename().string() : dir.filename().string();
    Timer timer;
    const synth::SynthCase c = synth::make_case(model, o);
    synth::write_case(dir, c, a.force);
    if (!a.quiet) {
      std::printf("%s: %s, seed %llu, units %s, scan %d vertices / %d triangles, truth %d triangles, %zu landmarks, "
                  "%zu curves (%.2f s)\n",
                  dir.string().c_str(), std::string(synth::pose_type_name(pose)).c_str(),
                  static_cast<unsigned long long>(seed), c.units.c_str(), c.scan.num_vertices(), c.scan.num_faces(),
                  c.truth_surface.num_faces(), c.truth_landmarks.size(), c.truth_curves.size(), timer.seconds());
    }
  }
}

}  // namespace

void register_synth(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<SynthArgs>();
  auto* sub = app.add_subcommand(
      "synth", "Generate synthetic scan cases with full ground truth (bench layout: scan.ply, landmarks.mrk.json, truth/)");
  sub->add_option("--out,-o", args->out, "case directory (one case) or parent directory (--count > 1)")->required();
  sub->add_option("--seed", args->seed, "random seed (case i of --count uses seed + i)")->capture_default_str();
  sub->add_option("--pose", args->pose, "standing or supine (with --count, poses alternate from this one)")
      ->capture_default_str();
  sub->add_option("--units", args->units, "units of the written files: mm or m")->capture_default_str();
  sub->add_option("--template,-t", args->template_file, "rigged template (.glb/.gltf); default: the shipped template");
  sub->add_option("--mesh", args->template_mesh, "the template's skinned mesh to use when its file has several (node or mesh name)");
  sub->add_option("--count", args->count, "number of cases (DIR/synth_<seed>_<pose>)")->capture_default_str();
  sub->add_flag("--force", args->force, "overwrite existing cases");
  sub->add_flag("--quiet,-q", args->quiet, "print nothing on success");
  sub->add_option("--noise-mm", args->noise_mm, "white noise along the normal, sd in mm (default 0.5)");
  sub->add_option("--lowfreq-noise-mm", args->lowfreq_noise_mm, "smooth normal noise amplitude, mm (default 0.5)");
  sub->add_option("--rotation-deg", args->rotation_deg, "max random rotation of the scan, degrees (default 20)");
  sub->add_option("--translation-m", args->translation_m, "max random translation of the scan, metres (default 0.3)");
  sub->add_option("--landmark-noise-mm", args->landmark_noise_mm, "annotation noise sd, mm (default 2.5)");
  sub->add_option("--shape-amplitude", args->shape_amplitude, "blendshape randomness in [0, 1] (default 0.5)");
  sub->add_option("--holes", args->holes, "number of holes (default 3)");
  sub->add_option("--fragments", args->fragments, "number of floating fragments (default 3)");
  sub->add_option("--azimuths", args->azimuths, "cameras per ring (default 12)");
  sub->add_option("--bumps", args->bumps, "smooth deformation bumps outside the model (default 4)");
  sub->add_option("--subdivisions", args->subdivisions, "max subdivision steps of the truth (default 3)");
  sub->add_option("--max-faces", args->max_faces,
                  "never subdivide the truth beyond this many triangles (default 400000; dense scans for scaling)");
  sub->add_option("--target-edge-mm", args->target_edge_mm,
                  "subdivide the truth until its median edge is at most this, mm (default 2.5)");
  sub->add_flag("--no-table", args->no_table, "supine: no table strips");
  sub->callback([args, &exit_code] {
    run(*args);
    exit_code = 0;
  });
}

}  // namespace breastfit::cli
