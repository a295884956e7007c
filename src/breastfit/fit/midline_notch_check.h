#pragma once
/// \file Checking a placed sternal notch against its own anatomical definition on the scan: the
/// jugular notch on the body's midline.
///
/// The fit follows a notch clicked 20–30 mm off (the neck's and the sternum's skin slide), and so
/// does the prediction from the other landmarks (landmark_prediction.h). The notch has its own
/// definition: it lies on the body's midsagittal plane, where the front of the manubrium meets the
/// neck. The plane comes from the other landmarks (each bilateral pair's midpoint, the xiphoid;
/// normal along the pairs' mean right → left direction), the notch's height from the scan's midline
/// profile in that plane (jugular_notch.h). A notch moved sideways leaves the plane, one moved
/// up or down leaves the profile's break; either way the placed notch is far from the one found.
///
/// The tolerance depends on the direction: the plane is sharp (as given, the notch lies within
/// 6 mm of it), the profile's break less so (on the bench cases as placed within 9 mm of the
/// notch; on the template-made synthetic torsos it sits 4–15 mm below the template's notch), so a
/// given notch is flagged when (sideways / tolerance)² + (vertical / (1.5 tolerance))² > 1.
#include <optional>
#include <string>
#include <vector>

#include "breastfit/core/types.h"
#include "breastfit/fit/landmark_target.h"

namespace breastfit::fit {

/// A plane through `point` with unit `normal`.
struct MidPlane {
  Vec3 point, normal;
};

/// The body's midsagittal plane from `landmarks` without the one named `skip`: through the mean of
/// the midpoints of the bilateral pairs given on both sides (acromia, mid-axillary points, pectoral
/// insertions, nipples, lowest breast points) and of the midline landmarks (sternal notch,
/// xiphoid), normal along the pairs' mean right → left vector. nullopt without any pair.
std::optional<MidPlane> landmark_midplane(const std::vector<LandmarkTarget>& landmarks, const std::string& skip = "");

/// The jugular notch on the scan near `near`, on the midsagittal plane of the landmarks other than
/// the sternal notch: jugular_notch_on_scan in the sagittal strip through `near` moved onto that
/// plane. nullopt without a plane or when the detector is unsure.
/// \param up, front the body's superior and anterior axes (unit, orthogonal)
std::optional<Vec3> midline_notch_on_scan(const Points& scan_vertices, const std::vector<LandmarkTarget>& landmarks,
                                          const Vec3& near, const Vec3& up, const Vec3& front);

/// A given notch against the one found on the scan.
struct NotchCheck {
  Vec3 found = Vec3::Zero();  ///< midline_notch_on_scan
  double distance_mm = 0;     ///< given ↔ found
  /// The tolerance in the given notch's direction from the found one: `tolerance_mm` sideways
  /// (across the midplane), 1.5× that along `up`, the ellipse's radius in between.
  double tolerance_mm = 0;
  bool flagged() const { return distance_mm > tolerance_mm; }
};

/// The given sternal notch `given` checked against midline_notch_on_scan (arguments as there);
/// nullopt when the notch is not found.
std::optional<NotchCheck> check_notch_on_midline(const Points& scan_vertices,
                                                 const std::vector<LandmarkTarget>& landmarks, const Vec3& near,
                                                 const Vec3& up, const Vec3& front, const Vec3& given,
                                                 double tolerance_mm);

}  // namespace breastfit::fit
