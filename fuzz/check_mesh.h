#pragma once
// Shared by the fuzz harnesses: run one reader on the input and trap on anything but a
// consistent mesh or an IoError with a one-line message.
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "breastfit/core/errors.h"
#include "breastfit/mesh/triangle_mesh.h"

namespace breastfit::fuzz {

#define BREASTFIT_FUZZ_CHECK(cond) \
  do {                             \
    if (!(cond)) __builtin_trap(); \
  } while (0)

/// Invariants every successfully read mesh must satisfy.
inline void check_mesh(const TriangleMesh& m) {
  BREASTFIT_FUZZ_CHECK(m.V.rows() > 0);
  BREASTFIT_FUZZ_CHECK(m.V.allFinite());
  for (Eigen::Index f = 0; f < m.F.rows(); ++f) {
    for (int k = 0; k < 3; ++k) {
      BREASTFIT_FUZZ_CHECK(m.F(f, k) >= 0 && m.F(f, k) < m.V.rows());
    }
    BREASTFIT_FUZZ_CHECK(m.F(f, 0) != m.F(f, 1) && m.F(f, 1) != m.F(f, 2) &&
                         m.F(f, 0) != m.F(f, 2));
  }
  BREASTFIT_FUZZ_CHECK(m.N.rows() == 0 || m.N.rows() == m.V.rows());
  BREASTFIT_FUZZ_CHECK(m.C.rows() == 0 || m.C.rows() == m.V.rows());
  BREASTFIT_FUZZ_CHECK(m.FUV.rows() == 0 || m.FUV.rows() == m.F.rows());
  for (Eigen::Index i = 0; i < m.FUV.size(); ++i) {
    BREASTFIT_FUZZ_CHECK(m.FUV.data()[i] >= 0 && m.FUV.data()[i] < m.UV.rows());
  }
}

template <typename Reader>
int run_reader(Reader reader, const std::uint8_t* data, std::size_t size, const char* name) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  try {
    check_mesh(reader(bytes, std::string(name)));
  } catch (const IoError& e) {
    const std::string what = e.what();
    BREASTFIT_FUZZ_CHECK(what.find('\n') == std::string::npos);
    BREASTFIT_FUZZ_CHECK(what.rfind(std::string(name) + ": ", 0) == 0);
  }
  // Any other exception (bad_alloc, length_error, InvalidInput, ...) escapes and libFuzzer
  // reports it as a crash through std::terminate.
  return 0;
}

}  // namespace breastfit::fuzz
