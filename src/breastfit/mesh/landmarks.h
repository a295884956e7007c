#pragma once
/// \file Named points and curves as read from / written to landmark and markups files
/// (see io/markups.h and io/landmarks_io.h). Plain positions, not surface points.
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "breastfit/core/types.h"

namespace breastfit {

/// A named position (a landmark such as "nipple_L").
struct NamedPoint {
  std::string name;
  Vec3 position = Vec3::Zero();
};

/// A named polyline (a surgical drawing such as "breast_contour_R").
struct Curve {
  std::string name;
  bool closed = false;  ///< the last point joins the first (Slicer "ClosedCurve")
  Points points;        ///< #P by 3, in order along the curve

  /// Polyline length (including the closing segment when closed), in the units of `points`.
  double length() const {
    double len = 0.0;
    for (Eigen::Index i = 1; i < points.rows(); ++i) len += (points.row(i) - points.row(i - 1)).norm();
    if (closed && points.rows() > 2) len += (points.row(0) - points.row(points.rows() - 1)).norm();
    return len;
  }
};

/// Everything of a markups file that breastfit uses. Positions in LPS, in millimetres (unless a
/// reader documents otherwise).
struct Markups {
  std::vector<NamedPoint> points;  ///< the control points of every point list ("Fiducial")
  std::vector<Curve> curves;       ///< every "Curve" and "ClosedCurve"

  /// The point with this name, or nullptr.
  const NamedPoint* find_point(std::string_view name) const {
    for (const auto& p : points)
      if (p.name == name) return &p;
    return nullptr;
  }
  /// The curve with this name, or nullptr.
  const Curve* find_curve(std::string_view name) const {
    for (const auto& c : curves)
      if (c.name == name) return &c;
    return nullptr;
  }
};

/// Validated anatomical landmarks read by io::read_landmarks: unique names from kLandmarkNames
/// (landmark_names.h), finite positions in LPS. Positions are the file's numbers (a RAS markups
/// file is converted to LPS, but no unit conversion is applied): `declared_units` says what they
/// are ("mm" or "m") when the file declares it (markups files), nullopt when it cannot (plain
/// JSON and CSV; use the scan's units then).
struct LandmarkSet {
  std::vector<NamedPoint> points;            ///< in file order
  std::optional<std::string> declared_units; ///< "mm", "m", or nullopt (undeclared)
  std::vector<std::string> warnings;         ///< what the reader skipped (e.g. unplaced points)

  /// Position of the landmark with this name, or nullptr when absent.
  const Vec3* find(std::string_view name) const {
    for (const auto& p : points)
      if (p.name == name) return &p.position;
    return nullptr;
  }
  /// The names, in order.
  std::vector<std::string> names() const {
    std::vector<std::string> out;
    out.reserve(points.size());
    for (const auto& p : points) out.push_back(p.name);
    return out;
  }
};

}  // namespace breastfit
