#include "breastfit/serve/session_json.h"

#include <cstdio>
#include <cstring>

#include "breastfit/core/errors.h"
#include "breastfit/fit/fit_summary_json.h"
#include "breastfit/metrics/distance_stats_json.h"
#include "breastfit/pipeline/report_figures.h"
#include "breastfit/transfer/breast_measurements_json.h"

namespace breastfit::serve {
namespace {

using nlohmann::json;

json flat(const Points& P) {
  json a = json::array();
  for (Eigen::Index i = 0; i < P.rows(); ++i)
    for (int k = 0; k < 3; ++k) a.push_back(static_cast<float>(P(i, k)));
  return a;
}

json vec(const Vec3& v) { return json::array({v.x(), v.y(), v.z()}); }

std::string hex(const render::Rgb& c) {
  char buf[8];
  std::snprintf(buf, sizeof buf, "#%02x%02x%02x", c.r, c.g, c.b);
  return buf;
}

template <typename T>
void append(std::string& out, const T& v) {
  char buf[sizeof(T)];
  std::memcpy(buf, &v, sizeof(T));
  out.append(buf, sizeof(T));
}

}  // namespace

std::string scan_mesh_binary(const pipeline::PreparedScan& scan) {
  // Little-endian: uint32 #V, uint32 #F, float32 xyz per vertex, uint32 abc per face.
  const TriangleMesh& m = scan.mesh_mm;
  std::string out;
  out.reserve(8 + 12 * (m.V.rows() + m.F.rows()));
  append(out, static_cast<uint32_t>(m.V.rows()));
  append(out, static_cast<uint32_t>(m.F.rows()));
  for (Eigen::Index i = 0; i < m.V.rows(); ++i)
    for (int k = 0; k < 3; ++k) append(out, static_cast<float>(m.V(i, k)));
  for (Eigen::Index i = 0; i < m.F.rows(); ++i)
    for (int k = 0; k < 3; ++k) append(out, static_cast<uint32_t>(m.F(i, k)));
  return out;
}

std::string scan_uv_binary(const pipeline::PreparedScan& scan) {
  const TriangleMesh& m = scan.mesh_mm;
  std::string out;
  if (!m.has_texcoords()) return out;
  out.reserve(24 * m.FUV.rows());
  for (Eigen::Index f = 0; f < m.FUV.rows(); ++f)
    for (int k = 0; k < 3; ++k)
      for (int c = 0; c < 2; ++c) append(out, static_cast<float>(m.UV(m.FUV(f, k), c)));
  return out;
}

json landmarks_to_json(const std::vector<NamedPoint>& points) {
  json a = json::array();
  for (const auto& p : points) a.push_back({{"name", p.name}, {"position", vec(p.position)}});
  return a;
}

LandmarkSet landmarks_from_json(const json& j) {
  if (!j.is_array()) throw InvalidInput("landmarks: expected an array of {name, position}");
  LandmarkSet out;
  out.declared_units = "mm";
  for (const auto& e : j) {
    if (!e.is_object() || !e.contains("name") || !e["name"].is_string() || !e.contains("position") ||
        !e["position"].is_array() || e["position"].size() != 3)
      throw InvalidInput("landmarks: every entry needs a name and a position [x, y, z]");
    NamedPoint p;
    p.name = e["name"].get<std::string>();
    for (int k = 0; k < 3; ++k) {
      if (!e["position"][k].is_number()) throw InvalidInput("landmark '" + p.name + "': the position is not 3 numbers");
      p.position[k] = e["position"][k].get<double>();
    }
    if (!p.position.allFinite()) throw InvalidInput("landmark '" + p.name + "' has a non-finite position");
    out.points.push_back(p);
  }
  return out;
}

json to_json(const mesh::BodyFrame& frame) {
  const Eigen::Matrix4d& T = frame.body_to_world;
  return {{"origin", vec(T.block<3, 1>(0, 3))},
          {"left", vec(T.block<3, 1>(0, 0))},
          {"posterior", vec(T.block<3, 1>(0, 1))},
          {"superior", vec(T.block<3, 1>(0, 2))},
          {"source", frame.source == mesh::BodyFrameSource::Landmarks ? "landmarks" : "shape"}};
}

json to_json(const FitOutcome& o, const model::RiggedModel& model) {
  const pipeline::RegisterResult& r = o.result;
  json j;
  j["generation"] = o.generation;
  j["warm"] = o.warm;
  j["server_ms"] = o.server_ms;
  j["server_cpu_ms"] = o.server_cpu_ms;
  j["surface_ms"] = o.surface_ms;
  j["complete"] = o.complete;
  j["usable"] = r.usable();
  j["status"] = r.status();  // "ok", "implausible" or "not_usable" (report.json's)
  j["verdict"] = r.fit.summary.verdict.reason;
  j["message"] = r.fit.summary.message;
  j["warnings"] = r.warnings;
  j["fitted"] = {{"vertices", flat(r.fit.vertices)}, {"faces", json::array()}, {"distances_mm", o.distances_mm},
                  {"distance_scale_mm", pipeline::distance_scale_mm(Eigen::Map<const Eigen::VectorXd>(
                                            o.distances_mm.data(), static_cast<Eigen::Index>(o.distances_mm.size())))}};
  json& faces = j["fitted"]["faces"];
  for (Eigen::Index i = 0; i < model.rest.F.rows(); ++i)
    for (int k = 0; k < 3; ++k) faces.push_back(model.rest.F(i, k));
  json drawings = json::array();
  for (size_t k = 0; k < r.drawings_on_scan.size(); ++k) {
    const auto& c = r.drawings_on_scan[k];
    drawings.push_back({{"name", c.name},
                        {"closed", c.closed},
                        {"colour", hex(pipeline::report_curve_colour(c.name, k))},
                        {"points", flat(c.points)},
                        {"length_mm", c.length_mm},
                        {"supported_fraction", c.supported_fraction}});
  }
  j["drawings"] = drawings;
  j["model_landmarks"] = landmarks_to_json(r.model_landmarks_mm.points);
  mesh::NamedPositions fitted;
  for (const auto& p : r.model_landmarks_mm.points) fitted[p.name] = p.position;
  if (const auto frame = mesh::body_frame_from_landmarks(fitted)) j["body_frame"] = to_json(*frame);
  std::vector<NamedPoint> used;
  for (const auto& t : r.fit.landmarks) used.push_back({t.name, t.position});
  j["placed_landmarks"] = landmarks_to_json(used);
  j["landmark_checks"] = fit::landmark_checks_json(r.fit.summary.landmark_checks);
  j["breasts"] = transfer::to_json(r.breasts);
  j["surface"] = metrics::to_json(r.surface);
  j["timings"] = fit::timings_json(r.timings);
  return j;
}

json mapped_drawings_json(const transfer::MapResult& mapped) {
  json curves = json::array();
  size_t first = mapped.markups.points.size();  // MapResult::points: the points, then each curve's
  for (size_t k = 0; k < mapped.markups.curves.size(); ++k) {
    const Curve& c = mapped.markups.curves[k];
    json counts = {{"high", 0}, {"medium", 0}, {"low", 0}};
    for (Eigen::Index i = 0; i < c.points.rows(); ++i) {
      const auto& conf = mapped.points[first + static_cast<size_t>(i)].confidence;
      if (counts.contains(conf)) counts[conf] = counts[conf].get<int>() + 1;
    }
    first += static_cast<size_t>(c.points.rows());
    curves.push_back({{"name", c.name},
                      {"closed", c.closed},
                      {"colour", hex(pipeline::report_curve_colour(c.name, k))},
                      {"points", flat(c.points)},
                      {"confidence", counts}});
  }
  return {{"curves", curves}};
}

json to_json(const SuggestOutcome& o) {
  json landmarks = json::array();
  for (const auto& d : o.landmarks)
    landmarks.push_back(
        {{"name", d.name}, {"position", vec(d.position_mm)}, {"confidence", d.confidence}, {"method", d.method}});
  return {{"landmarks", landmarks}, {"warnings", o.warnings}, {"server_ms", o.server_ms}, {"server_cpu_ms", o.server_cpu_ms}};
}

json to_json(const FitStatus& s, const model::RiggedModel& model, bool with_outcomes) {
  json j;
  j["job"] = s.job;
  j["state"] = to_string(s.state);
  j["stage"] = s.stage;
  j["iterations"] = s.iterations;
  j["message"] = s.message;
  if (with_outcomes) {
    j["result"] = s.outcome ? to_json(*s.outcome, model) : json(nullptr);
    j["suggestion"] = s.suggestion ? to_json(*s.suggestion) : json(nullptr);
  }
  return j;
}

}  // namespace breastfit::serve
