#pragma once
/// \file Estimating a torso's body frame (LPS: x = patient's left, y = posterior, z = superior)
/// in an arbitrary scanner frame: the standard views (render/view.h) and the body axes of the
/// drawing transfer's fold slide (transfer/drawing_transfer.h) are expressed in it.
#include <map>
#include <optional>
#include <string>

#include <Eigen/Core>

#include "breastfit/core/types.h"
#include "breastfit/mesh/triangle_mesh.h"

namespace breastfit::mesh {

/// Landmark positions by name (names as in breastfit/mesh/landmark_names.h), world coordinates.
using NamedPositions = std::map<std::string, Vec3, std::less<>>;

enum class BodyFrameSource {
  Landmarks,      ///< from anatomical landmarks
  PrincipalAxes,  ///< from the shape (heuristic; may be wrong for unusual crops)
};

/// A rigid body→world transform and how it was found.
struct BodyFrame {
  Eigen::Matrix4d body_to_world = Eigen::Matrix4d::Identity();  ///< rotation + translation
  BodyFrameSource source = BodyFrameSource::Landmarks;
  std::string description;  ///< e.g. "landmarks: sternal_notch->xiphoid, acromion_R->acromion_L"
};

/// Mean inclination of the sternum (xiphoid → sternal notch) from the body's long axis, top
/// leaning posteriorly, degrees. Anatomically 15–20°; 16–19° in the benchmark's subjects.
inline constexpr double kSternumInclinationDeg = 17.0;

/// Body frame from landmarks:
/// - superior (+z) = xiphoid → sternal_notch turned about the left axis by
///   `sternum_inclination_deg` (top towards anterior) so that z follows the body's long axis
///   rather than the sloping sternum; if either is missing, the mid-point of the lowest breast
///   points (or nipples) → the mid-point of the acromions (no correction);
/// - patient's left (+x) = the first available R → L pair among acromion, midaxillary,
///   pectoral_insertion, nipple, lowest_breast, made orthogonal to z;
/// - posterior (+y) = z × x, so anterior = x × z (right-handed).
/// Origin: the sternal notch if given, else the mean of the landmarks used.
/// \returns nullopt when the landmarks cannot define both axes (missing or degenerate).
std::optional<BodyFrame> body_frame_from_landmarks(const NamedPositions& landmarks,
                                                   double sternum_inclination_deg = kSternumInclinationDeg);

/// Body frame from the shape alone (heuristic fallback), for a torso crop:
/// - antero-posterior axis = the direction of least spread (principal axes, area-weighted);
/// - lateral axis = the direction orthogonal to it across which the shape is most mirror
///   symmetric (mean closest-sample distance of the mirrored shape; searched every 6°, then 1°);
///   superior axis = antero-posterior × lateral;
/// - anterior sign: the area-weighted mean normal (a front-only scan faces the scanner) or, when
///   that is inconclusive, the side with the larger extreme spread (breasts protrude);
/// - superior sign: the end third whose lateral extent (area-weighted 95th percentile) is larger
///   (shoulders and arms).
/// Origin: the area-weighted centroid. Deterministic. On the 14 visible benchmark scans it is
/// within 14° of the true body frame (docs/RENDER.md); prefer landmarks when available.
/// \throws InvalidInput if the mesh has fewer than 4 vertices or is degenerate (flat or a line).
BodyFrame body_frame_from_principal_axes(const TriangleMesh& mesh);

/// Landmarks when they suffice, else principal axes.
BodyFrame estimate_body_frame(const TriangleMesh& mesh, const NamedPositions& landmarks,
                              double sternum_inclination_deg = kSternumInclinationDeg);

}  // namespace breastfit::mesh
