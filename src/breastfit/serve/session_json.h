#pragma once
/// \file What the workstation's page receives about a scan and its fits (JSON), and the landmarks
/// it sends back.
#include <string>

#include <nlohmann/json.hpp>

#include "breastfit/mesh/body_frame.h"
#include "breastfit/mesh/landmarks.h"
#include "breastfit/serve/scan_session.h"
#include "breastfit/transfer/surface_map.h"

namespace breastfit::serve {

/// The scan's triangles for the page, in mm (scan frame), little-endian binary: uint32 #V,
/// uint32 #F, float32 x y z per vertex, uint32 a b c per face.
std::string scan_mesh_binary(const pipeline::PreparedScan& scan);

/// The scan's texture coordinates per face corner, for a textured display (the page gives each
/// corner its own vertex: one vertex may have several coordinates): little-endian float32 u v of
/// corner k of face f at index 2 * (3 f + k). Empty when the scan has none.
std::string scan_uv_binary(const pipeline::PreparedScan& scan);

/// The job status: job ("fit" or "suggest"), state, stage, iterations, message, and (when a fit
/// or a suggestion has finished) the outcome as "result" and "suggestion". `with_outcomes` false:
/// without those two (the event stream's progress events).
nlohmann::json to_json(const FitStatus& status, const model::RiggedModel& model, bool with_outcomes = true);

/// Suggested landmarks: [{"name", "position", "confidence", "method"}], warnings and server time.
nlohmann::json to_json(const SuggestOutcome& outcome);

/// A finished fit: fitted surface and per-vertex distance to the scan, drawings with their
/// report.html colours, placed and fitted landmarks, landmark checks, warnings, verdict, breast
/// measurements, surface errors and the server time.
nlohmann::json to_json(const FitOutcome& outcome, const model::RiggedModel& model);

/// A body frame for the page's views: {"origin", "left", "posterior", "superior", "source"}.
nlohmann::json to_json(const mesh::BodyFrame& frame);

/// Drawings mapped from another fit (transfer::map_markups): the curves with their report.html
/// colours and, per curve, how many control points are of "high", "medium" and "low" confidence.
nlohmann::json mapped_drawings_json(const transfer::MapResult& mapped);

/// Landmarks sent by the page: [{"name": ..., "position": [x, y, z]}] in mm.
/// \throws InvalidInput naming the problem (not an array, a bad entry, a non-finite position)
LandmarkSet landmarks_from_json(const nlohmann::json& j);

/// Landmarks for the page: [{"name": ..., "position": [x, y, z]}].
nlohmann::json landmarks_to_json(const std::vector<NamedPoint>& points);

}  // namespace breastfit::serve
