#pragma once
/// \file Basic numeric types shared by every layer.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>

namespace breastfit {

using Scalar = double;
using Index = std::int32_t;
using Vec3 = Eigen::Vector3d;
using Vec2 = Eigen::Vector2d;
using Mat3 = Eigen::Matrix3d;
using Quat = Eigen::Quaterniond;

/// #V by 3 row-major double coordinates (one point per row).
using Points = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;
/// #F by 3 row-major vertex indices (one triangle per row).
using Triangles = Eigen::Matrix<Index, Eigen::Dynamic, 3, Eigen::RowMajor>;
/// #V by 2 row-major texture coordinates.
using TexCoords = Eigen::Matrix<double, Eigen::Dynamic, 2, Eigen::RowMajor>;
/// #V by 3 row-major 8-bit RGB colours.
using Colors = Eigen::Matrix<std::uint8_t, Eigen::Dynamic, 3, Eigen::RowMajor>;

}  // namespace breastfit
