#include "breastfit/io/detail/vtk_values.h"

#include <bit>
#include <cstring>
#include <limits>

namespace breastfit::io::detail {
namespace {

/// The raw bits of the value at `p` (type.bytes bytes), in host order.
std::uint64_t load_bits(const char* p, std::size_t bytes, bool big_endian) {
  std::uint64_t v = 0;
  for (std::size_t k = 0; k < bytes; ++k) {
    const auto byte = static_cast<std::uint64_t>(static_cast<unsigned char>(p[k]));
    const std::size_t shift = big_endian ? 8 * (bytes - 1 - k) : 8 * k;
    v |= byte << shift;
  }
  return v;
}

std::int64_t sign_extend(std::uint64_t bits, std::size_t bytes) {
  if (bytes == 8) return std::bit_cast<std::int64_t>(bits);
  const std::uint64_t sign = std::uint64_t{1} << (8 * bytes - 1);
  return static_cast<std::int64_t>(bits ^ sign) - static_cast<std::int64_t>(sign);
}

double to_double(std::uint64_t bits, VtkScalar type) {
  switch (type.kind) {
    case VtkScalar::Kind::Float:
      if (type.bytes == 4) return std::bit_cast<float>(static_cast<std::uint32_t>(bits));
      return std::bit_cast<double>(bits);
    case VtkScalar::Kind::Signed:
      return static_cast<double>(sign_extend(bits, type.bytes));
    case VtkScalar::Kind::Unsigned:
      break;
  }
  return static_cast<double>(bits);
}

}  // namespace

std::optional<VtkScalar> legacy_vtk_scalar(std::string_view n) {
  using K = VtkScalar::Kind;
  if (n == "unsigned_char") return VtkScalar{K::Unsigned, 1};
  if (n == "char" || n == "signed_char") return VtkScalar{K::Signed, 1};
  if (n == "unsigned_short") return VtkScalar{K::Unsigned, 2};
  if (n == "short") return VtkScalar{K::Signed, 2};
  if (n == "unsigned_int") return VtkScalar{K::Unsigned, 4};
  if (n == "int" || n == "vtkIdType") return VtkScalar{K::Signed, 4};  // ids are written as int
  if (n == "unsigned_long" || n == "vtktypeuint64") return VtkScalar{K::Unsigned, 8};
  if (n == "long" || n == "vtktypeint64") return VtkScalar{K::Signed, 8};
  if (n == "float") return VtkScalar{K::Float, 4};
  if (n == "double") return VtkScalar{K::Float, 8};
  return std::nullopt;
}

std::optional<VtkScalar> xml_vtk_scalar(std::string_view n) {
  using K = VtkScalar::Kind;
  if (n == "Int8" || n == "Char") return VtkScalar{K::Signed, 1};
  if (n == "UInt8") return VtkScalar{K::Unsigned, 1};
  if (n == "Int16") return VtkScalar{K::Signed, 2};
  if (n == "UInt16") return VtkScalar{K::Unsigned, 2};
  if (n == "Int32") return VtkScalar{K::Signed, 4};
  if (n == "UInt32") return VtkScalar{K::Unsigned, 4};
  if (n == "Int64") return VtkScalar{K::Signed, 8};
  if (n == "UInt64") return VtkScalar{K::Unsigned, 8};
  if (n == "Float32") return VtkScalar{K::Float, 4};
  if (n == "Float64") return VtkScalar{K::Float, 8};
  return std::nullopt;
}

void decode_vtk_doubles(const char* data, std::size_t count, VtkScalar type, bool big_endian,
                        std::vector<double>& out) {
  out.reserve(out.size() + count);
  for (std::size_t i = 0; i < count; ++i) {
    out.push_back(to_double(load_bits(data + i * type.bytes, type.bytes, big_endian), type));
  }
}

void decode_vtk_integers(const char* data, std::size_t count, VtkScalar type, bool big_endian,
                         std::vector<std::int64_t>& out) {
  out.reserve(out.size() + count);
  for (std::size_t i = 0; i < count; ++i) {
    const std::uint64_t bits = load_bits(data + i * type.bytes, type.bytes, big_endian);
    if (type.kind == VtkScalar::Kind::Signed) {
      out.push_back(sign_extend(bits, type.bytes));
    } else {
      out.push_back(bits > static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max())
                        ? std::numeric_limits<std::int64_t>::max()
                        : static_cast<std::int64_t>(bits));
    }
  }
}

}  // namespace breastfit::io::detail
