#include "breastfit/mesh/units.h"

#include <gtest/gtest.h>

#include <limits>
#include <string>

#include "breastfit/core/errors.h"

namespace breastfit::mesh {
namespace {

Points box(double x, double y, double z) {
  Points P(2, 3);
  P << 0, 0, 0, x, y, z;
  return P;
}

TEST(Units, DetectTorsoInMillimetresAndMetres) {
  EXPECT_EQ(detect_units(box(450, 300, 250)), Units::Millimetres);
  EXPECT_EQ(detect_units(box(0.45, 0.3, 0.25)), Units::Metres);
  EXPECT_EQ(detect_units(box(4.9, 0, 0)), Units::Metres);
  EXPECT_EQ(detect_units(box(50, 0, 0)), Units::Millimetres);
  EXPECT_EQ(detect_units(box(5000, 0, 0)), Units::Millimetres);
  EXPECT_DOUBLE_EQ(max_extent(box(1, -7, 3)), 7.0);
}

TEST(Units, AmbiguousExtentThrowsWithAdvice) {
  for (double e : {5.0, 20.0, 49.9, 5001.0, 1e6}) {
    try {
      detect_units(box(e, 1, 1));
      FAIL() << "no throw for extent " << e;
    } catch (const InvalidInput& err) {
      const std::string msg = err.what();
      EXPECT_NE(msg.find("neither a torso in mm nor in m; pass --units"), std::string::npos) << msg;
      EXPECT_NE(msg.find("extent "), std::string::npos);
    }
  }
  EXPECT_THROW(detect_units(Points(0, 3)), InvalidInput);
  EXPECT_THROW(detect_units(box(0, 0, 0)), InvalidInput);
  Points nan = box(1, 1, 1);
  nan(1, 1) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(detect_units(nan), InvalidInput);
}

TEST(Units, FactorsNamesParsing) {
  EXPECT_EQ(to_mm_factor(Units::Millimetres), 1.0);
  EXPECT_EQ(to_mm_factor(Units::Metres), 1000.0);
  EXPECT_EQ(units_name(Units::Metres), "m");
  EXPECT_EQ(units_name(Units::Millimetres), "mm");
  EXPECT_EQ(parse_units("mm"), Units::Millimetres);
  EXPECT_EQ(parse_units("m"), Units::Metres);
  EXPECT_FALSE(parse_units("auto").has_value());
  EXPECT_THROW(parse_units("cm"), InvalidInput);
  EXPECT_THROW(parse_units(""), InvalidInput);
  EXPECT_EQ(resolve_units(Units::Metres, box(400, 0, 0)), Units::Metres);
  EXPECT_EQ(resolve_units(std::nullopt, box(400, 0, 0)), Units::Millimetres);
}

}  // namespace
}  // namespace breastfit::mesh
