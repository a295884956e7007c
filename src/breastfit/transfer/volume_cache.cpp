#include "breastfit/transfer/volume_cache.h"

#include <algorithm>
#include <cstring>
#include <utility>

#include "breastfit/mesh/boundary.h"

namespace breastfit::transfer {
namespace {

// Entries kept of each kind: the template and, per breast, its patch and refined patch (topology);
// per breast one fill.
constexpr size_t kTopologies = 8;
constexpr size_t kFills = 4;

bool same_triangles(const Triangles& a, const Triangles& b) {
  return a.rows() == b.rows() &&
         (a.size() == 0 || std::memcmp(a.data(), b.data(), sizeof(Index) * static_cast<size_t>(a.size())) == 0);
}

// Same size, same pattern, same values (compressed matrices).
bool same_matrix(const Eigen::SparseMatrix<double>& a, const Eigen::SparseMatrix<double>& b) {
  if (a.rows() != b.rows() || a.cols() != b.cols() || a.nonZeros() != b.nonZeros()) return false;
  if (!a.isCompressed() || !b.isCompressed()) return false;
  const auto n = static_cast<size_t>(a.nonZeros());
  return std::equal(a.outerIndexPtr(), a.outerIndexPtr() + a.outerSize() + 1, b.outerIndexPtr()) &&
         std::equal(a.innerIndexPtr(), a.innerIndexPtr() + n, b.innerIndexPtr()) &&
         std::equal(a.valuePtr(), a.valuePtr() + n, b.valuePtr());
}

// Moves entry i to the front (most recently used).
template <typename T>
T& to_front(std::vector<T>& v, size_t i) {
  std::rotate(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(i), v.begin() + static_cast<std::ptrdiff_t>(i) + 1);
  return v.front();
}

std::shared_ptr<const MeshTopology> computed_topology(const TriangleMesh& mesh) {
  auto t = std::make_shared<MeshTopology>();
  t->neighbours = mesh::vertex_neighbours(mesh);
  t->faces = mesh::vertex_faces(mesh);
  return t;
}

}  // namespace

VolumeCache::TopologyEntry& VolumeCache::entry_for(const TriangleMesh& mesh) {
  for (size_t i = 0; i < topologies_.size(); ++i)
    if (topologies_[i].num_vertices == mesh.num_vertices() && same_triangles(topologies_[i].F, mesh.F))
      return to_front(topologies_, i);
  if (topologies_.size() >= kTopologies) topologies_.pop_back();
  topologies_.insert(topologies_.begin(), TopologyEntry{mesh.num_vertices(), mesh.F, nullptr, nullptr});
  return topologies_.front();
}

int VolumeCache::hits() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return hits_;
}

int VolumeCache::misses() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return misses_;
}

// A lookup: the cached value under the lock; when missing it is computed without the lock (the
// other breast's lookups go on meanwhile) and kept, unless another thread kept one first.
std::shared_ptr<const MeshTopology> VolumeCache::topology(const TriangleMesh& mesh) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (const auto t = entry_for(mesh).topology) {
      ++hits_;
      return t;
    }
    ++misses_;
  }
  auto computed = computed_topology(mesh);
  std::lock_guard<std::mutex> lock(mutex_);
  TopologyEntry& e = entry_for(mesh);
  if (!e.topology) e.topology = std::move(computed);
  return e.topology;
}

std::shared_ptr<const std::vector<std::vector<Index>>> VolumeCache::boundary_loops(const TriangleMesh& mesh) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (const auto b = entry_for(mesh).boundary) {
      ++hits_;
      return b;
    }
    ++misses_;
  }
  auto computed = std::make_shared<const std::vector<std::vector<Index>>>(mesh::boundary_loops(mesh));
  std::lock_guard<std::mutex> lock(mutex_);
  TopologyEntry& e = entry_for(mesh);
  if (!e.boundary) e.boundary = std::move(computed);
  return e.boundary;
}

std::shared_ptr<const FillSolver> VolumeCache::fill_solver(const Eigen::SparseMatrix<double>& m) {
  Eigen::SparseMatrix<double> key = m;
  key.makeCompressed();
  auto find = [&]() -> std::shared_ptr<const FillSolver> {
    for (size_t i = 0; i < fills_.size(); ++i)
      if (same_matrix(fills_[i].matrix, key)) return to_front(fills_, i).solver;
    return nullptr;
  };
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (auto s = find()) {
      ++hits_;
      return s;
    }
    ++misses_;
  }
  auto solver = std::make_shared<const FillSolver>(key);
  std::lock_guard<std::mutex> lock(mutex_);
  if (auto s = find()) return s;
  if (fills_.size() >= kFills) fills_.pop_back();
  fills_.insert(fills_.begin(), FillEntry{std::move(key), solver});
  return solver;
}

std::shared_ptr<const MeshTopology> topology_of(const TriangleMesh& mesh, VolumeCache* cache) {
  return cache ? cache->topology(mesh) : computed_topology(mesh);
}

}  // namespace breastfit::transfer
