#pragma once
/// \file The simulated scanner's viewpoints and the visibility of surface points from them.
///
/// Cameras sit on rings of `n_azimuth` viewpoints spread over an arc around the body's vertical
/// axis (standing: centred on the front; supine: over the patient around the head-foot axis, so
/// the back on the table is never seen), one ring per elevation (tilt towards the head), at
/// `distance_mm` from the torso centre, all looking at it. A point is seen by a camera when it
/// lies in the field of view, its normal faces the camera with an incidence below
/// `max_incidence_deg`, and the segment to the camera is not blocked by the surface.
#include <vector>

#include "breastfit/core/types.h"
#include "breastfit/mesh/triangle_mesh.h"
#include "breastfit/synth/synth_options.h"

namespace breastfit::synth {

/// A pinhole viewpoint (body frame, mm): position and orthonormal viewing axes.
struct Camera {
  Vec3 position = Vec3::Zero();
  Vec3 forward = Vec3::UnitY();  ///< viewing direction
  Vec3 right = Vec3::UnitX();    ///< image x axis
  Vec3 up = Vec3::UnitZ();       ///< image y axis
};

/// The viewpoints of `options` looking at `centre` (body frame LPS: +z superior, −y anterior).
/// Ordered ring by ring (elevations in the given order), azimuths from patient right to left.
std::vector<Camera> camera_rig(const ScannerOptions& options, PoseType pose, const Vec3& centre);

/// Number of cameras that see each vertex of `surface` (counting stops at `stop_at`, so a value
/// equal to stop_at means "at least stop_at").
/// \param[in] surface  the occluding surface (triangles) whose vertices are tested
/// \param[in] normals  #V by 3 unit vertex normals of `surface` (outward)
/// \param[in] cameras  viewpoints
/// \param[in] options  field of view and maximum incidence
/// \param[in] stop_at  >= 1
/// \return #V counts in [0, stop_at]
std::vector<int> count_views(const TriangleMesh& surface, const Points& normals, const std::vector<Camera>& cameras,
                             const ScannerOptions& options, int stop_at);

}  // namespace breastfit::synth
