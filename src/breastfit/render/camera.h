#pragma once
/// \file A look-at camera (orthographic or perspective) mapping world points to pixels.
#include <Eigen/Geometry>

#include <vector>

#include "breastfit/core/types.h"

namespace breastfit::render {

enum class Projection { Orthographic, Perspective };

/// A world point seen by the camera: pixel coordinates (x to the right, y down, pixel centres at
/// integer + 0.5) and the depth along the viewing direction (world units; larger = farther).
struct Projected {
  double x = 0;
  double y = 0;
  double depth = 0;
};

/// Camera at `eye` looking at `target`, `up` giving the image's vertical.
/// Orthographic: the image shows `view_height` world units vertically (width from the aspect).
/// Perspective: `fov_y_deg` vertical field of view; points with depth <= `near` are not visible.
struct Camera {
  Vec3 eye = Vec3(0, 0, 1);
  Vec3 target = Vec3::Zero();
  Vec3 up = Vec3(0, 1, 0);
  Projection projection = Projection::Orthographic;
  double view_height = 2.0;   ///< orthographic: world units spanned by the image height
  double fov_y_deg = 30.0;    ///< perspective: vertical field of view, degrees
  double near = 1e-3;         ///< perspective: nearest visible depth, world units

  /// Unit viewing direction (eye → target).
  Vec3 forward() const;
  /// Unit image-right direction in world coordinates (forward × up, normalised).
  Vec3 right() const;
  /// Unit image-up direction in world coordinates (orthogonalised `up`).
  Vec3 true_up() const;

  /// Projects a world point into a `width` by `height` image.
  Projected project(const Vec3& p, int width, int height) const;
  /// project() of every row of `points` (the camera's axes computed once; the same values).
  std::vector<Projected> project_all(const Points& points, int width, int height) const;
  /// World units per pixel at a given depth (constant for orthographic).
  double world_per_pixel(double depth, int height) const;

  /// \throws InvalidInput if eye == target, up is parallel to the viewing direction, or a
  /// size/angle is not positive and finite.
  void validate() const;
};

/// A camera looking along `view_dir` with image-up `up` that frames `points` (N by 3) in an image
/// of the given aspect ratio (width / height), leaving `margin` (fraction of the image size) free
/// on every side. For perspective the camera backs off until the framed points fit.
/// \throws InvalidInput if points is empty or the directions are degenerate.
Camera frame_points(const Points& points, const Vec3& view_dir, const Vec3& up, double aspect,
                    double margin = 0.06, Projection projection = Projection::Orthographic,
                    double fov_y_deg = 30.0);

/// frame_points on the 8 corners of an axis-aligned box.
Camera frame_box(const Eigen::AlignedBox3d& box, const Vec3& view_dir, const Vec3& up, double aspect,
                 double margin = 0.06, Projection projection = Projection::Orthographic,
                 double fov_y_deg = 30.0);

}  // namespace breastfit::render
