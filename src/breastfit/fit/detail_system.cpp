#include "breastfit/fit/detail_system.h"

#include <cstring>
#include <mutex>
#include <utility>
#include <vector>

#include "breastfit/mesh/adjacency.h"

namespace breastfit::fit {
namespace {

// Kept systems: the template's (one per μ, ε in use) and one more.
constexpr size_t kKept = 2;

struct Pool {
  std::mutex mutex;
  std::vector<std::unique_ptr<DetailSystem>> free;  // released, most recently first
};

// Never destroyed: a lease may end after static destruction began (a fit on a detached thread).
Pool& pool() {
  static Pool* p = new Pool;
  return *p;
}

void release(DetailSystem* s) {
  std::unique_ptr<DetailSystem> owned(s);
  Pool& p = pool();
  std::lock_guard<std::mutex> lock(p.mutex);
  p.free.insert(p.free.begin(), std::move(owned));
  if (p.free.size() > kKept) p.free.pop_back();
}

}  // namespace

DetailSystem::DetailSystem(const Triangles& f, Index num_vertices, double mu, double eps)
    : F(f), n(num_vertices), smoothness(mu), decay(eps) {
  const auto edges = mesh::unique_edges(F, n);
  std::vector<Eigen::Triplet<double>> trip;
  trip.reserve(2 * edges.size() + static_cast<size_t>(n));
  base_diag = Eigen::VectorXd::Constant(n, decay);
  for (const auto& [a, b] : edges) {
    trip.emplace_back(a, b, -smoothness);
    trip.emplace_back(b, a, -smoothness);
    base_diag[a] += smoothness;
    base_diag[b] += smoothness;
  }
  for (Index i = 0; i < n; ++i) trip.emplace_back(i, i, 0.0);  // diagonal entries exist in the pattern
  A.resize(n, n);
  A.setFromTriplets(trip.begin(), trip.end());
  solver.analyzePattern(A);
}

bool DetailSystem::matches(const Triangles& f, Index num_vertices, double mu, double eps) const {
  return n == num_vertices && smoothness == mu && decay == eps && F.rows() == f.rows() &&
         (f.size() == 0 || std::memcmp(F.data(), f.data(), sizeof(Index) * static_cast<size_t>(f.size())) == 0);
}

std::shared_ptr<DetailSystem> lease_detail_system(const Triangles& F, Index n, double smoothness, double decay) {
  std::unique_ptr<DetailSystem> s;
  {
    Pool& p = pool();
    std::lock_guard<std::mutex> lock(p.mutex);
    for (auto it = p.free.begin(); it != p.free.end(); ++it)
      if ((*it)->matches(F, n, smoothness, decay)) {
        s = std::move(*it);
        p.free.erase(it);
        break;
      }
  }
  if (!s) s = std::make_unique<DetailSystem>(F, n, smoothness, decay);  // outside the lock
  return std::shared_ptr<DetailSystem>(s.release(), release);
}

}  // namespace breastfit::fit
