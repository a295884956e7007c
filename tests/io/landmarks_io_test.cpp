#include "breastfit/io/landmarks_io.h"

#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "breastfit/core/errors.h"
#include "breastfit/io/markups.h"
#include "breastfit/mesh/landmark_names.h"
#include "support/test_paths.h"

namespace breastfit::io {
namespace {

namespace fs = std::filesystem;

fs::path write_text(const std::string& name, const std::string& text) {
  const fs::path p = test::temp_dir() / name;
  std::ofstream(p, std::ios::binary) << text;
  return p;
}

template <class Fn>
std::string io_error_of(Fn&& fn) {
  try {
    fn();
  } catch (const IoError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no IoError";
  return {};
}

/// The IoError message of reading `text` saved as `name`; checks it is one line naming the file.
std::string read_error(const std::string& name, const std::string& text) {
  const fs::path p = write_text(name, text);
  const std::string msg = io_error_of([&] { read_landmarks(p); });
  EXPECT_NE(msg.find(name), std::string::npos) << msg;
  EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
  return msg;
}

TEST(LandmarksIo, MarkupsFileKeepsDeclaredUnitsAndConvertsRas) {
  Markups m;
  m.points = {{"nipple_L", Vec3(10, 20, 30)}, {"xiphoid", Vec3(-1, -2, -3)}};
  Curve c;
  c.name = "sternum";
  c.points = Points::Zero(2, 3);
  m.curves.push_back(c);  // curves are ignored by read_landmarks
  const fs::path p = test::temp_dir() / "lm.mrk.json";
  write_markups(p, m, {.units = "m", .coordinate_system = "RAS"});
  const LandmarkSet lm = read_landmarks(p);
  ASSERT_EQ(lm.points.size(), 2u);
  EXPECT_EQ(lm.declared_units, "m");
  EXPECT_EQ(lm.names(), (std::vector<std::string>{"nipple_L", "xiphoid"}));
  ASSERT_NE(lm.find("nipple_L"), nullptr);
  EXPECT_LT((*lm.find("nipple_L") - Vec3(0.010, 0.020, 0.030)).norm(), 1e-15);  // LPS, metres
  EXPECT_EQ(lm.find("acromion_R"), nullptr);
  const LandmarkSet mm = landmarks_to_mm(lm, mesh::Units::Millimetres);  // declared m wins
  EXPECT_LT((*mm.find("xiphoid") - Vec3(-1, -2, -3)).norm(), 1e-12);
  EXPECT_EQ(mm.declared_units, "mm");
}

TEST(LandmarksIo, MarkupsWithoutUnitsDeclareMillimetres) {
  const fs::path p = write_text("bare.mrk.json",
                                R"({"markups": [{"type": "Fiducial", "controlPoints": [{"label": "sternal_notch", "position": [1, 2, 3]}]}]})");
  const LandmarkSet lm = read_landmarks(p);
  EXPECT_EQ(lm.declared_units, "mm");
  EXPECT_EQ(*lm.find("sternal_notch"), Vec3(1, 2, 3));
}

TEST(LandmarksIo, UnplacedMarkupsPointIsSkippedWithAWarning) {
  const fs::path p = write_text("unplaced.mrk.json", R"({"markups": [{"type": "Fiducial", "name": "F",
    "controlPoints": [{"label": "nipple_R", "position": "", "positionStatus": "missing"},
                      {"label": "xiphoid", "position": [1, 2, 3]}]}]})");
  const LandmarkSet lm = read_landmarks(p);
  EXPECT_EQ(lm.names(), (std::vector<std::string>{"xiphoid"}));
  ASSERT_EQ(lm.warnings.size(), 1u);
  EXPECT_NE(lm.warnings[0].find("'nipple_R' skipped"), std::string::npos) << lm.warnings[0];
  EXPECT_TRUE(landmarks_to_mm(lm, mesh::Units::Millimetres).warnings == lm.warnings);
}

TEST(LandmarksIo, SlicerFcsvInRasLpsAndCodedSystems) {
  const std::string rows =
      "vtkMRMLMarkupsFiducialNode_0,12.3,-4.5,6.7,0,0,0,1,1,1,0,nipple_R,,\n"
      "vtkMRMLMarkupsFiducialNode_1,-1,2,3,0,0,0,1,1,1,0,xiphoid,a note,vtkMRMLModelNode4\n";
  const std::string header =
      "# Markups fiducial file version = 4.11\n"
      "# columns = id,x,y,z,ow,ox,oy,oz,vis,sel,lock,label,desc,associatedNodeID\n";
  for (const std::string cs : {"RAS", "0", ""}) {
    SCOPED_TRACE("CoordinateSystem '" + cs + "'");
    const std::string system = cs.empty() ? "" : "# CoordinateSystem = " + cs + "\n";
    const LandmarkSet lm = read_landmarks(write_text("ras.fcsv", header + system + rows));
    EXPECT_EQ(lm.names(), (std::vector<std::string>{"nipple_R", "xiphoid"}));
    EXPECT_EQ(lm.declared_units, "mm");
    EXPECT_EQ(*lm.find("nipple_R"), Vec3(-12.3, 4.5, 6.7));  // RAS -> LPS as for markups
  }
  for (const std::string cs : {"LPS", "1"}) {
    const LandmarkSet lm = read_landmarks(write_text("lps.FCSV", header + "# CoordinateSystem = " + cs + "\n" + rows));
    EXPECT_EQ(*lm.find("xiphoid"), Vec3(-1, 2, 3));
  }
  // Columns in another order are followed.
  const LandmarkSet moved = read_landmarks(
      write_text("cols.fcsv", "# CoordinateSystem = LPS\n# columns = label,z,y,x\nsternal_notch, 3, 2, 1\n"));
  EXPECT_EQ(*moved.find("sternal_notch"), Vec3(1, 2, 3));
  // Slicer quotes fields holding commas ("" is a quote inside): a description before the label
  // must not shift it.
  const LandmarkSet quoted = read_landmarks(write_text(
      "quoted.fcsv", "# CoordinateSystem = LPS\n# columns = id,x,y,z,desc,label\n"
                     "1,1,2,3,\"the \"\"tip\"\", seen, twice\",\"nipple_R\"\n"
                     "2,4,5,6,,xiphoid\n"));
  ASSERT_EQ(quoted.points.size(), 2u);
  EXPECT_EQ(quoted.points[0].name, "nipple_R");
  EXPECT_EQ(quoted.points[0].position, Vec3(1, 2, 3));
  EXPECT_EQ(*quoted.find("xiphoid"), Vec3(4, 5, 6));
}

TEST(LandmarksIo, PlainJsonInFileOrder) {
  const fs::path p = write_text("lm.json", R"({"xiphoid": [1.5, 2, 3e2], "acromion_R": [-4, 5, -6]})");
  const LandmarkSet lm = read_landmarks(p);
  EXPECT_FALSE(lm.declared_units.has_value());
  EXPECT_EQ(lm.names(), (std::vector<std::string>{"xiphoid", "acromion_R"}));
  EXPECT_EQ(*lm.find("xiphoid"), Vec3(1.5, 2, 300));
  const LandmarkSet mm = landmarks_to_mm(lm, mesh::Units::Metres);  // undeclared: fallback units
  EXPECT_EQ(*mm.find("acromion_R"), Vec3(-4000, 5000, -6000));
  // A .json holding markups is read as markups.
  const fs::path q = write_text("slicer.json",
                                R"({"markups": [{"type": "Fiducial", "coordinateUnits": "m", "controlPoints": [{"label": "nipple_R", "position": [1, 2, 3]}]}]})");
  EXPECT_EQ(read_landmarks(q).declared_units, "m");
}

TEST(LandmarksIo, CsvWithHeaderSpacesCommentsAndBlanks) {
  const fs::path p = write_text("lm.csv",
                                "\xEF\xBB\xBFname, x, y, z\r\n"
                                "# a comment\n"
                                "\n"
                                "  nipple_R ,  1.25, -2 ,3  \r\n"
                                "\"nipple_L\",4,5,6,\n"
                                "lowest_breast_L\t7\t8\t9\n");
  const LandmarkSet lm = read_landmarks(p);
  EXPECT_FALSE(lm.declared_units.has_value());
  EXPECT_EQ(lm.names(), (std::vector<std::string>{"nipple_R", "nipple_L", "lowest_breast_L"}));
  EXPECT_EQ(*lm.find("nipple_R"), Vec3(1.25, -2, 3));
  EXPECT_EQ(*lm.find("nipple_L"), Vec3(4, 5, 6));
  EXPECT_EQ(*lm.find("lowest_breast_L"), Vec3(7, 8, 9));
  // No header.
  const LandmarkSet lm2 = read_landmarks(write_text("nohead.CSV", "xiphoid,1,2,3\n"));
  EXPECT_EQ(*lm2.find("xiphoid"), Vec3(1, 2, 3));
}

TEST(LandmarksIo, AllTwelveNamesAccepted) {
  std::string csv;
  for (size_t i = 0; i < kLandmarkNames.size(); ++i)
    csv += std::string(kLandmarkNames[i]) + "," + std::to_string(i) + ",0,0\n";
  const LandmarkSet lm = read_landmarks(write_text("all.csv", csv));
  EXPECT_EQ(lm.points.size(), 12u);
  EXPECT_EQ(lm.find("lowest_breast_L")->x(), 11.0);
}

TEST(LandmarksIo, UnknownNameListsExpected) {
  const std::string msg = read_error("u.json", R"({"nipple_left": [1, 2, 3]})");
  EXPECT_NE(msg.find("unknown landmark 'nipple_left'"), std::string::npos) << msg;
  EXPECT_NE(msg.find(landmark_name_list()), std::string::npos) << msg;
  const fs::path p = write_text("any.json", R"({"custom": [1, 2, 3]})");
  EXPECT_EQ(read_landmarks(p, {.require_known_names = false}).points.size(), 1u);
}

TEST(LandmarksIo, DuplicateNames) {
  EXPECT_NE(read_error("d.json", R"({"xiphoid": [1, 2, 3], "xiphoid": [4, 5, 6]})").find("'xiphoid' appears more than once"),
            std::string::npos);
  EXPECT_NE(read_error("d.csv", "xiphoid,1,2,3\nxiphoid,1,2,3\n").find("'xiphoid' appears more than once"),
            std::string::npos);
  EXPECT_NE(read_error("d.mrk.json",
                       R"({"markups": [{"type": "Fiducial", "controlPoints": [{"label": "nipple_L", "position": [1, 2, 3]}, {"label": "nipple_L", "position": [1, 2, 3]}]}]})")
                .find("'nipple_L' appears more than once"),
            std::string::npos);
}

TEST(LandmarksIo, NonFiniteNamesTheLandmark) {
  EXPECT_NE(read_error("n.json", R"({"xiphoid": [1, 2, 3], "nipple_R": [NaN, 2, 3]})").find("'nipple_R' has a non-finite"),
            std::string::npos);
  EXPECT_NE(read_error("i.json", R"({"nipple_R": [1, -Infinity, 3]})").find("'nipple_R' has a non-finite"),
            std::string::npos);
  EXPECT_NE(read_error("n.csv", "nipple_L,1,nan,3\n").find("'nipple_L' has a non-finite"), std::string::npos);
  EXPECT_NE(read_error("n.mrk.json",
                       R"({"markups": [{"type": "Fiducial", "controlPoints": [{"label": "xiphoid", "position": [1, Infinity, 3]}]}]})")
                .find("'xiphoid' has a non-finite"),
            std::string::npos);
}

TEST(LandmarksIo, MalformedInputsGiveOneLineErrors) {
  EXPECT_NE(read_error("e.json", "").find("empty file"), std::string::npos);
  EXPECT_NE(read_error("e.csv", "  \n\n").find("empty file"), std::string::npos);
  EXPECT_NE(read_error("m.json", "{\"xiphoid\": [1, 2,").find("malformed JSON"), std::string::npos);
  EXPECT_NE(read_error("a.json", "[[1, 2, 3]]").find("expected a JSON object"), std::string::npos);
  EXPECT_NE(read_error("s.json", R"({"xiphoid": [1, 2]})").find("landmark 'xiphoid': expected [x, y, z]"),
            std::string::npos);
  EXPECT_NE(read_error("t.json", R"({"xiphoid": {"x": 1}})").find("expected [x, y, z]"), std::string::npos);
  EXPECT_NE(read_error("o.json", "{}").find("contains no landmarks"), std::string::npos);
  EXPECT_NE(read_error("f.csv", "xiphoid,1,2\n").find("line 1: expected 'name,x,y,z', got 3 fields"),
            std::string::npos);
  EXPECT_NE(read_error("g.csv", "name,x,y,z\nxiphoid,1,abc,3\n").find("line 2: 'abc' is not a number"),
            std::string::npos);
  EXPECT_NE(read_error("h.csv", "xiphoid,1,2,3\nnipple_L,x,2,3\n").find("line 2"), std::string::npos);
  EXPECT_NE(read_error("x.txt", "xiphoid 1 2 3")
                .find("unsupported landmark file extension '.txt' (supported landmark files: .mrk.json, .json, "
                      ".csv, .fcsv)"),
            std::string::npos);
  EXPECT_NE(read_error("c.fcsv", "# CoordinateSystem = XYZ\n").find("line 1: unsupported CoordinateSystem 'XYZ'"),
            std::string::npos);
  EXPECT_NE(read_error("n.fcsv", "vtkMRMLMarkupsFiducialNode_0,1,abc,3,0,0,0,1,1,1,0,xiphoid,,\n")
                .find("line 1: expected a number in column 'y'"),
            std::string::npos);
  EXPECT_NE(read_error("l.fcsv", "# columns = id,x,y,z\nid0,1,2,3\n").find("line 2: the point has no label"),
            std::string::npos);
  EXPECT_NE(io_error_of([] { read_landmarks(test::temp_dir() / "nope.csv"); }).find("does not exist"),
            std::string::npos);
}

TEST(LandmarksIo, RoundTripThroughMarkups) {
  Markups m;
  for (size_t i = 0; i < kLandmarkNames.size(); ++i)
    m.points.push_back({std::string(kLandmarkNames[i]), Vec3(0.1 * i, -1.0 / (i + 1), 1e3 + i)});
  const fs::path p = test::temp_dir() / "rt.mrk.json";
  write_markups(p, m);
  const LandmarkSet lm = read_landmarks(p);
  ASSERT_EQ(lm.points.size(), m.points.size());
  for (size_t i = 0; i < m.points.size(); ++i) {
    EXPECT_EQ(lm.points[i].name, m.points[i].name);
    EXPECT_EQ(lm.points[i].position, m.points[i].position);
  }
}

}  // namespace
}  // namespace breastfit::io
