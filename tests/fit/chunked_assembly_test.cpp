#include "breastfit/fit/chunked_assembly.h"

#include <gtest/gtest.h>

#include "breastfit/core/rng.h"

namespace breastfit::fit {
namespace {

struct Rows {
  std::vector<std::vector<int>> idx;
  std::vector<std::vector<double>> val;
  std::vector<double> r, w;
};

Rows random_rows(int count, int n) {
  Rng rng(17);
  Rows rows;
  for (int k = 0; k < count; ++k) {
    std::vector<int> idx{k % n, (k * 5 + 1) % n, (k * 11 + 3) % n};
    if (idx[1] == idx[0]) idx[1] = (idx[1] + 1) % n;
    if (idx[2] == idx[0] || idx[2] == idx[1]) idx.pop_back();
    std::vector<double> val;
    for (size_t j = 0; j < idx.size(); ++j) val.push_back(rng.normal());
    rows.idx.push_back(idx);
    rows.val.push_back(val);
    rows.r.push_back(rng.normal());
    rows.w.push_back(rng.uniform(0.1, 2.0));
  }
  return rows;
}

double assemble(const Rows& rows, int threads, NormalEquations* eq) {
  return assemble_in_chunks(static_cast<Index>(rows.r.size()), threads, eq,
                            [&](Index begin, Index end, NormalEquations* part) {
                              double cost = 0;
                              for (Index k = begin; k < end; ++k) {
                                cost += rows.w[k] * rows.r[k] * rows.r[k];
                                if (part)
                                  part->add_row(rows.idx[k].data(), rows.val[k].data(),
                                                static_cast<int>(rows.idx[k].size()), rows.r[k], rows.w[k]);
                              }
                              return cost;
                            });
}

TEST(ChunkedAssembly, MatchesTheSerialNormalEquations) {
  const int n = 12;
  const Rows rows = random_rows(1500, n);  // several chunks
  NormalEquations serial(n), chunked(n);
  double cost = 0;
  for (size_t k = 0; k < rows.r.size(); ++k) {
    cost += rows.w[k] * rows.r[k] * rows.r[k];
    serial.add_row(rows.idx[k].data(), rows.val[k].data(), static_cast<int>(rows.idx[k].size()), rows.r[k],
                   rows.w[k]);
  }
  serial.finalize();
  const double c = assemble(rows, 2, &chunked);
  chunked.finalize();
  EXPECT_NEAR(c, cost, 1e-9 * cost);
  EXPECT_NEAR(chunked.cost(), serial.cost(), 1e-9 * cost);
  EXPECT_LT((chunked.H() - serial.H()).norm(), 1e-10 * serial.H().norm());
  EXPECT_LT((chunked.g() - serial.g()).norm(), 1e-10 * serial.g().norm());
  EXPECT_EQ(chunked.H(), chunked.H().transpose());
}

TEST(ChunkedAssembly, SameBitsWhateverTheThreads) {
  const int n = 20;
  const Rows rows = random_rows(3000, n);
  for (bool gradient_only : {false, true}) {
    NormalEquations one(n);
    one.set_gradient_only(gradient_only);
    const double c1 = assemble(rows, 1, &one);
    one.finalize();
    for (int threads : {2, 3, 8}) {
      NormalEquations many(n);
      many.set_gradient_only(gradient_only);
      const double c = assemble(rows, threads, &many);
      many.finalize();
      EXPECT_EQ(c, c1) << threads;
      EXPECT_EQ(many.cost(), one.cost()) << threads;
      EXPECT_EQ(many.g(), one.g()) << threads;
      if (!gradient_only) EXPECT_EQ(many.H(), one.H()) << threads;
    }
    // The cost alone is the same sum.
    EXPECT_EQ(assemble(rows, 2, nullptr), c1);
  }
}

TEST(ChunkedAssembly, PartialsAreEmptiedAndFollowTheActiveSet) {
  NormalEquations eq(6);
  const std::vector<int> idx{1, 4};
  const std::vector<double> val{1.0, 2.0};
  eq.partial(0).add_row(idx.data(), val.data(), 2, 1.0, 1.0);
  eq.set_active({1, 4});
  NormalEquations& p = eq.partial(0);
  ASSERT_EQ(p.size(), 2);
  p.finalize();
  EXPECT_EQ(p.H().norm(), 0.0);
  EXPECT_EQ(p.cost(), 0.0);
}

}  // namespace
}  // namespace breastfit::fit
