#pragma once
/// \file Scalar types of VTK files (legacy .vtk names such as `float`, `vtktypeint64`; XML .vtp
/// names such as `Float32`, `UInt64`) and decoding their binary values (private to the io
/// layer).
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string_view>
#include <vector>

namespace breastfit::io::detail {

/// A VTK scalar type: its size in bytes and how its bits read.
struct VtkScalar {
  enum class Kind { Signed, Unsigned, Float };
  Kind kind = Kind::Float;
  std::size_t bytes = 4;
};

/// The type of a legacy .vtk array (`bit` excluded: it has no byte size), or nothing.
std::optional<VtkScalar> legacy_vtk_scalar(std::string_view name);

/// The type of a .vtp DataArray (`Int8` ... `UInt64`, `Float32`, `Float64`), or nothing.
std::optional<VtkScalar> xml_vtk_scalar(std::string_view name);

/// Decodes `count` values of `type` starting at `data` (which holds count * type.bytes bytes)
/// into doubles, appended to `out`.
void decode_vtk_doubles(const char* data, std::size_t count, VtkScalar type, bool big_endian,
                        std::vector<double>& out);

/// Decodes `count` integer values of `type` (Signed or Unsigned) into int64 appended to `out`;
/// unsigned values above the int64 range become INT64_MAX (out of any index range).
void decode_vtk_integers(const char* data, std::size_t count, VtkScalar type, bool big_endian,
                         std::vector<std::int64_t>& out);

}  // namespace breastfit::io::detail
