#include "breastfit/fit/detail_system.h"

#include <cmath>
#include <cstring>
#include <thread>

#include <gtest/gtest.h>

#include "breastfit/fit/surface_detail.h"
#include "support/grid_mesh.h"

namespace breastfit::fit {
namespace {

bool same_bits(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), sizeof(double) * static_cast<size_t>(a.size())) == 0;
}

// One numeric use of a system: its diagonal set to base + `weight` per vertex, factorised, solved.
Eigen::VectorXd solve_with(DetailSystem& s, double weight) {
  Eigen::VectorXd rhs(s.n);
  for (Index i = 0; i < s.n; ++i) {
    s.A.coeffRef(i, i) = s.base_diag[i] + weight * static_cast<double>(i % 3);
    rhs[i] = std::sin(0.1 * static_cast<double>(i));
  }
  s.solver.factorize(s.A);
  EXPECT_EQ(s.solver.info(), Eigen::Success);
  return s.solver.solve(rhs);
}

TEST(DetailSystem, AReleasedSystemIsLeasedAgainForTheSameKeyOnly) {
  const Triangles F = test::grid_triangles(7);
  DetailSystem* first = nullptr;
  {
    const auto s = lease_detail_system(F, 49, 4.0, 0.01);
    first = s.get();
  }
  {
    const auto again = lease_detail_system(F, 49, 4.0, 0.01);
    EXPECT_EQ(again.get(), first);
    const auto at_once = lease_detail_system(F, 49, 4.0, 0.01);  // the kept one is out: a new one
    EXPECT_NE(at_once.get(), first);
  }
  const auto other_mu = lease_detail_system(F, 49, 2.0, 0.01);
  EXPECT_FALSE(other_mu->matches(F, 49, 4.0, 0.01));
  EXPECT_TRUE(other_mu->matches(F, 49, 2.0, 0.01));
  EXPECT_FALSE(other_mu->matches(test::grid_triangles(6), 36, 2.0, 0.01));
}

TEST(DetailSystem, AKeptSystemSolvesToTheSameBitsAsANewOne) {
  const Triangles F = test::grid_triangles(9);
  DetailSystem fresh(F, 81, 4.0, 0.01);
  const Eigen::VectorXd expected = solve_with(fresh, 2.0);
  {
    const auto used = lease_detail_system(F, 81, 4.0, 0.01);
    solve_with(*used, 7.0);  // other values first: the kept system's numeric state differs
  }
  const auto kept = lease_detail_system(F, 81, 4.0, 0.01);
  EXPECT_TRUE(same_bits(solve_with(*kept, 2.0), expected));
}

TEST(DetailSystem, SurfaceDetailIsTheSameBitsWithAKeptSystemAndOnTwoThreadsAtOnce) {
  const TriangleMesh model = test::grid_mesh(10, 10.0);
  const ScanTarget scan(test::grid_mesh(44, 2.5, [](double x, double y) { return 3.0 * std::cos(0.02 * x) * std::cos(0.03 * y); }));
  auto fit = [&] { return fit_surface_detail(model.V, model.F, scan, CorrespondenceOptions{}, SurfaceDetailOptions{}, 1).offsets; };
  const Eigen::VectorXd first = fit();   // a new system (or one kept by another test)
  const Eigen::VectorXd second = fit();  // the kept one
  EXPECT_TRUE(same_bits(first, second));
  Eigen::VectorXd a, b;
  std::thread ta([&] { a = fit(); });
  std::thread tb([&] { b = fit(); });
  ta.join();
  tb.join();
  EXPECT_TRUE(same_bits(a, first));
  EXPECT_TRUE(same_bits(b, first));
}

}  // namespace
}  // namespace breastfit::fit
