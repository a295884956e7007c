// End-to-end tests of `breastfit render` through the built executable.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "breastfit/io/io.h"
#include "breastfit/io/markups.h"
#include "breastfit/render/image.h"
#include "support/test_paths.h"
#include "support/toy_model.h"

namespace breastfit {
namespace {

namespace fs = std::filesystem;

/// A closed ellipsoid "torso" in a scanner-like frame (mm): x = left, y = up, z = anterior.
TriangleMesh ellipsoid(int n_lat = 24, int n_lon = 48) {
  const double pi = 3.14159265358979323846;
  TriangleMesh m;
  m.V.resize(2 + (n_lat - 1) * n_lon, 3);
  m.V.row(0) << 0, 250, 0;
  m.V.row(1) << 0, -250, 0;
  for (int i = 1; i < n_lat; ++i)
    for (int j = 0; j < n_lon; ++j) {
      const double th = pi * i / n_lat, ph = 2 * pi * j / n_lon;
      m.V.row(2 + (i - 1) * n_lon + j) << 160 * std::sin(th) * std::cos(ph), 250 * std::cos(th),
          100 * std::sin(th) * std::sin(ph);
    }
  auto idx = [&](int i, int j) { return static_cast<Index>(2 + (i - 1) * n_lon + (j % n_lon)); };
  std::vector<Eigen::Matrix<Index, 1, 3>> tris;
  for (int j = 0; j < n_lon; ++j) {
    tris.push_back({0, idx(1, j + 1), idx(1, j)});
    tris.push_back({1, idx(n_lat - 1, j), idx(n_lat - 1, j + 1)});
  }
  for (int i = 1; i + 1 < n_lat; ++i)
    for (int j = 0; j < n_lon; ++j) {
      tris.push_back({idx(i, j), idx(i + 1, j + 1), idx(i + 1, j)});
      tris.push_back({idx(i, j), idx(i, j + 1), idx(i + 1, j + 1)});
    }
  m.F.resize(static_cast<Eigen::Index>(tris.size()), 3);
  for (size_t k = 0; k < tris.size(); ++k) m.F.row(static_cast<Eigen::Index>(k)) = tris[k];
  return m;
}

void write_text(const fs::path& p, const std::string& s) {
  std::ofstream f(p);
  f << s;
}

/// Mean x of strongly red pixels (the landmark discs).
double mean_red_x(const render::Image& img, int* count) {
  double sx = 0;
  int n = 0;
  for (int y = 0; y < img.height(); ++y)
    for (int x = 0; x < img.width(); ++x) {
      const render::Rgb c = img.at(x, y);
      if (c.r > 170 && c.g < 70 && c.b < 70) {
        sx += x;
        ++n;
      }
    }
  *count = n;
  return n ? sx / n : -1;
}

/// Writes DIR/torso.ply (the ellipsoid) and DIR/lm.json, landmarks on it in its scanner frame
/// (x = patient left, y = up, z = anterior; nipple_R on the patient's right).
void write_torso_with_landmarks(const fs::path& dir) {
  io::write_mesh(dir / "torso.ply", ellipsoid());
  write_text(dir / "lm.json",
             R"({"sternal_notch": [0, 200, 60], "xiphoid": [0, 0, 100],)"
             R"( "acromion_R": [-150, 150, 0], "acromion_L": [150, 150, 0], "nipple_R": [-80, 50, 85]})");
}

TEST(RenderCommand, MeshWithLandmarksAllViews) {
  if (test::cli_path().empty()) GTEST_SKIP() << "CLI not built";
  const fs::path dir = test::temp_dir();
  write_torso_with_landmarks(dir);
  std::string out;
  const int code = test::run_cli("render '" + (dir / "torso.ply").string() + "' --landmarks '" +
                                     (dir / "lm.json").string() + "' --view all --size 256 --title T --out '" +
                                     (dir / "shot").string() + "'",
                                 &out);
  ASSERT_EQ(code, 0) << out;
  EXPECT_NE(out.find("landmarks"), std::string::npos) << out;  // frame from the landmarks
  for (const char* v : {"front", "side", "side-left", "oblique", "oblique-left"}) {
    const fs::path png = dir / (std::string("shot_") + v + ".png");
    ASSERT_TRUE(fs::exists(png)) << png;
    const render::Image img = render::read_png(png);
    EXPECT_EQ(img.width(), 256);
    EXPECT_EQ(img.height(), 256);
  }
  // Front view: the landmarks with x < 0 are on the patient's right → image left; nipple_R and
  // acromion_R dominate the red pixels on the left, the midline ones sit at the centre.
  int n = 0;
  const render::Image front = render::read_png(dir / "shot_front.png");
  const double mx = mean_red_x(front, &n);
  ASSERT_GT(n, 20);
  EXPECT_LT(mx, 128.0);
}

TEST(RenderCommand, SingleViewExactFileAndErrors) {
  if (test::cli_path().empty()) GTEST_SKIP() << "CLI not built";
  const fs::path dir = test::temp_dir();
  io::write_mesh(dir / "torso.ply", ellipsoid());
  std::string out;
  ASSERT_EQ(test::run_cli("render '" + (dir / "torso.ply").string() + "' --view side --size 128 --out '" +
                              (dir / "sub" / "one.png").string() + "'",
                          &out),
            0)
      << out;
  EXPECT_TRUE(fs::exists(dir / "sub" / "one.png"));
  EXPECT_NE(out.find("principal axes"), std::string::npos) << out;  // no landmarks: fallback
  // Bad view → invalid input (3); missing mesh → I/O error (4); no --out → usage (2).
  EXPECT_EQ(test::run_cli("render '" + (dir / "torso.ply").string() + "' --view sideways --out '" +
                              (dir / "x.png").string() + "'",
                          &out),
            3)
      << out;
  EXPECT_NE(out.find("breastfit: error:"), std::string::npos);
  EXPECT_EQ(test::run_cli("render '" + (dir / "missing.ply").string() + "' --out '" + (dir / "x.png").string() + "'",
                          &out),
            4)
      << out;
  EXPECT_EQ(test::run_cli("render '" + (dir / "torso.ply").string() + "'", &out), 2) << out;
}

/// Mean absolute difference of two images of the same size (0–255).
double image_difference(const render::Image& a, const render::Image& b) {
  double sum = 0;
  for (size_t i = 0; i < a.bytes().size(); ++i) sum += std::abs(int(a.bytes()[i]) - int(b.bytes()[i]));
  return sum / static_cast<double>(a.bytes().size());
}

TEST(RenderCommand, WithoutLandmarksTheScanIsOrientedFromItsGeometryOrTheViewIsCaptionedUnknown) {
  if (test::cli_path().empty()) GTEST_SKIP() << "CLI not built";
  const fs::path dir = test::temp_dir();
  std::string out;
  ASSERT_EQ(test::run_cli("synth --quiet --seed 7 --out '" + (dir / "case").string() + "'", &out), 0) << out;
  const std::string scan = "'" + (dir / "case" / "scan.ply").string() + "'";
  const std::string lm = "'" + (dir / "case" / "landmarks.mrk.json").string() + "'";
  // The truth: front and back views oriented by the landmarks.
  for (const char* v : {"front", "back"})
    ASSERT_EQ(test::run_cli("render " + scan + " --landmarks " + lm + " --no-labels --view " + v +
                                " --size 128 --out '" + (dir / (std::string("lm_") + v + ".png")).string() + "'",
                            &out),
              0)
        << out;
  // Without landmarks: the template's orientation search finds the front (not the back).
  ASSERT_EQ(test::run_cli("render " + scan + " --size 128 --out '" + (dir / "geo.png").string() + "'", &out), 0) << out;
  EXPECT_NE(out.find("the scan's geometry"), std::string::npos) << out;
  EXPECT_EQ(out.find("orientation unknown"), std::string::npos) << out;
  const render::Image geo = render::read_png(dir / "geo.png");
  const double to_front = image_difference(geo, render::read_png(dir / "lm_front.png"));
  const double to_back = image_difference(geo, render::read_png(dir / "lm_back.png"));
  EXPECT_LT(to_front, 0.5 * to_back) << to_front << " " << to_back;
  // Principal axes alone cannot tell front from back: said in the output and on the image.
  ASSERT_EQ(test::run_cli("render " + scan + " --frame axes --size 128 --out '" + (dir / "axes.png").string() + "'", &out),
            0)
      << out;
  EXPECT_NE(out.find("orientation unknown"), std::string::npos) << out;
  EXPECT_NE(image_difference(render::read_png(dir / "axes.png"), geo), 0.0);  // the caption at least differs
}

TEST(RenderCommand, PlacedLandmarksAreDrawnBesideTheFittedOnes) {
  if (test::cli_path().empty()) GTEST_SKIP() << "CLI not built";
  const fs::path dir = test::temp_dir();
  write_torso_with_landmarks(dir);  // lm.json: the fitted landmarks
  write_text(dir / "placed.json", R"({"nipple_R": [-40, 20, 95], "xiphoid": [20, -30, 98]})");
  std::string out;
  const std::string base = "render '" + (dir / "torso.ply").string() + "' --landmarks '" + (dir / "lm.json").string() +
                           "' --no-labels --size 256 --out '";
  ASSERT_EQ(test::run_cli(base + (dir / "fitted.png").string() + "'", &out), 0) << out;
  ASSERT_EQ(test::run_cli(base + (dir / "both.png").string() + "' --placed '" + (dir / "placed.json").string() + "'", &out),
            0)
      << out;
  auto dark = [](const render::Image& img) {
    int n = 0;
    for (int y = 0; y < img.height(); ++y)
      for (int x = 0; x < img.width(); ++x) {
        const render::Rgb c = img.at(x, y);
        n += c.r < 50 && c.g < 50 && c.b < 50;
      }
    return n;
  };
  // Dark discs and joining lines (and the legend entry) appear; the fitted landmarks stay red.
  EXPECT_GT(dark(render::read_png(dir / "both.png")), dark(render::read_png(dir / "fitted.png")) + 60);
  int n = 0;
  mean_red_x(render::read_png(dir / "both.png"), &n);
  EXPECT_GT(n, 20);
}

TEST(RenderCommand, DrawingsInMetresAreDrawnOnAMillimetreMesh) {
  if (test::cli_path().empty()) GTEST_SKIP() << "CLI not built";
  const fs::path dir = test::temp_dir();
  io::write_mesh(dir / "torso.ply", ellipsoid());
  // A closed curve on the anterior surface (z ≈ 100 mm), written in metres.
  Markups m;
  Curve c;
  c.name = "breast_contour_R";
  c.closed = true;
  c.points.resize(60, 3);
  for (int i = 0; i < 60; ++i) {
    const double a = 2 * 3.14159265358979323846 * i / 60, x = -70 + 40 * std::cos(a), y = 40 * std::sin(a);
    const double z = 100 * std::sqrt(std::max(0.0, 1 - x * x / (160.0 * 160) - y * y / (250.0 * 250)));
    c.points.row(i) << x, y, z;
  }
  m.curves.push_back(c);
  io::MarkupsWriteOptions wo;
  wo.units = "m";
  io::write_markups(dir / "drawings.mrk.json", m, wo);
  std::string out;
  ASSERT_EQ(test::run_cli("render '" + (dir / "torso.ply").string() + "' --drawings '" +
                              (dir / "drawings.mrk.json").string() + "' --frame identity --view top --size 256 --out '" +
                              (dir / "d.png").string() + "'",
                          &out),
            0)
      << out;
  // With the mesh frame taken as the body frame, "top" looks along −z: at the mesh's anterior
  // side, where the curve lies. Count strong pixels of the first palette colour (curve + legend
  // swatch); a hidden (dimmed) curve or one drawn 1000× too large would not give them.
  const render::Image img = render::read_png(dir / "d.png");
  int blue = 0;
  for (int y = 0; y < img.height(); ++y)
    for (int x = 0; x < img.width(); ++x) {
      const render::Rgb p = img.at(x, y);
      blue += (p.b > 150 && p.r < 80) ? 1 : 0;
    }
  EXPECT_GT(blue, 150) << "curve and legend swatch";
}

TEST(RenderCommand, DefaultTemplate) {
  if (test::cli_path().empty()) GTEST_SKIP() << "CLI not built";
  const fs::path dir = test::temp_dir();
  std::string out;
  ASSERT_EQ(test::run_cli("render --template --view front --size 200 --out '" + (dir / "tpl.png").string() + "'",
                          &out),
            0)
      << out;
  const render::Image img = render::read_png(dir / "tpl.png");
  EXPECT_EQ(img.width(), 200);
  int n = 0;
  mean_red_x(img, &n);
  EXPECT_GT(n, 20);  // the template's landmarks are drawn
}

TEST(RenderCommand, MeshChoosesOneSkinnedMeshOfATemplate) {
  if (test::cli_path().empty()) GTEST_SKIP() << "CLI not built";
  const fs::path dir = test::temp_dir();
  const fs::path two = test::save_two_mesh_toy(dir);
  std::string out;
  const std::string common = "render --template '" + two.string() + "' --size 120 --out '" + (dir / "t.png").string() + "'";
  EXPECT_EQ(test::run_cli(common, &out), 4) << out;
  EXPECT_NE(out.find("choose one with --mesh NAME"), std::string::npos) << out;
  ASSERT_EQ(test::run_cli(common + " --mesh Second", &out), 0) << out;
  EXPECT_TRUE(fs::exists(dir / "t.png"));
  EXPECT_EQ(test::run_cli("render --template '" + two.string() + "' --mesh Third --out '" + (dir / "u.png").string() + "'", &out), 4) << out;
  EXPECT_NE(out.find("no skinned mesh named 'Third'"), std::string::npos) << out;
}

TEST(RenderCommand, RefusesToReplaceAnImageWithoutForce) {
  if (test::cli_path().empty()) GTEST_SKIP() << "CLI not built";
  const fs::path dir = test::temp_dir();
  io::write_mesh(dir / "torso.ply", ellipsoid());
  write_text(dir / "shot.png", "previous");
  std::string out;
  const std::string cmd = "render '" + (dir / "torso.ply").string() + "' --size 64 --out '" + (dir / "shot.png").string() + "'";
  EXPECT_EQ(test::run_cli(cmd, &out), 4) << out;
  EXPECT_NE(out.find("already exists (use --force to replace it)"), std::string::npos) << out;
  EXPECT_EQ(test::file_bytes(dir / "shot.png"), "previous");
  ASSERT_EQ(test::run_cli(cmd + " --force", &out), 0) << out;
  EXPECT_EQ(render::read_png(dir / "shot.png").width(), 64);
}

TEST(RenderCommand, AllViewsAreWrittenAsOneSetOrNotAtAll) {
  if (test::cli_path().empty()) GTEST_SKIP() << "CLI not built";
  const fs::path dir = test::temp_dir();
  io::write_mesh(dir / "torso.ply", ellipsoid());
  write_text(dir / "shot_front.png", "previous front");
  fs::create_directories(dir / "shot_side.png");  // the second view cannot be written: a failure in the middle
  std::string out;
  const std::string cmd = "render '" + (dir / "torso.ply").string() + "' --view all --size 64 --out '" +
                          (dir / "shot").string() + "' --force";
  EXPECT_EQ(test::run_cli(cmd, &out), 4) << out;
  EXPECT_NE(out.find("shot_side.png"), std::string::npos) << out;
  EXPECT_EQ(test::file_bytes(dir / "shot_front.png"), "previous front");  // not a mixed set
  EXPECT_FALSE(fs::exists(dir / "shot_oblique.png"));
  for (const auto& e : fs::directory_iterator(dir))
    EXPECT_EQ(e.path().filename().string().find(".breastfit-tmp-"), std::string::npos) << e.path();
}

}  // namespace
}  // namespace breastfit
