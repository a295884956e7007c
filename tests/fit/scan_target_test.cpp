// The scan as a registration target: its skin labels (fit/skin_around.h skin_vertices of its
// scan), computed once per target and kept — the same labels whoever asks first, from any thread.
#include "breastfit/fit/scan_target.h"

#include <gtest/gtest.h>

#include <thread>
#include <utility>
#include <vector>

#include "breastfit/fit/skin_around.h"
#include "support/test_shapes.h"

namespace breastfit::fit {
namespace {

TEST(ScanTarget, SkinIsTheScansSkinVerticesKeptOnce) {
  const TriangleMesh scan = test::breast_with_fragment();
  const std::vector<char> expected = skin_vertices(scan);
  ScanTarget target(scan, 100);
  const std::vector<char>& skin = target.skin();
  EXPECT_EQ(skin, expected);
  EXPECT_EQ(&target.skin(), &skin);  // kept, not labelled again
  // The fragment's vertices are not skin, the breast's are.
  const Index breast_vertices = test::sphere_mesh(60.0, Vec3::Zero(), 64, 128).V.rows();
  for (Index i = 0; i < scan.num_vertices(); ++i) EXPECT_EQ(skin[static_cast<size_t>(i)], i < breast_vertices ? 1 : 0);
  // A moved target keeps its labels.
  ScanTarget moved(std::move(target));
  EXPECT_EQ(moved.skin(), expected);
}

TEST(ScanTarget, SkinIsLabelledOnceWhenTwoThreadsAskFirst) {
  const TriangleMesh scan = test::breast_with_fragment();
  const std::vector<char> expected = skin_vertices(scan);
  for (int round = 0; round < 5; ++round) {
    const ScanTarget target(scan, 100);
    const std::vector<char>* seen[2] = {nullptr, nullptr};
    std::thread a([&] { seen[0] = &target.skin(); });
    std::thread b([&] { seen[1] = &target.skin(); });
    a.join();
    b.join();
    EXPECT_EQ(seen[0], seen[1]);
    EXPECT_EQ(*seen[0], expected);
  }
}

}  // namespace
}  // namespace breastfit::fit
