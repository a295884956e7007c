#pragma once
/// \file What repeated volume measurements reuse: a mesh's topology (the neighbours and the
/// triangles around every vertex, its boundary loops) and the chest-wall fills' factorisations.
///
/// One curve_volume needs the neighbours of its mesh and of its refined patch twice each, and the
/// workstation measures both breasts of the same template after every re-fit: the template's
/// triangles never change, the refined patch and the membrane fill's matrix (a graph Laplacian:
/// topology only) mostly do not. An entry is used only when its key equals the new input (the
/// triangles and vertex count; the whole fill matrix), so the results are the same bits with or
/// without a cache. Thread-safe (the two breasts may be measured at the same time; a lookup holds
/// the cache while it computes what is missing).
#include <cstddef>
#include <memory>
#include <mutex>
#include <vector>

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>

#include "breastfit/core/types.h"
#include "breastfit/mesh/adjacency.h"
#include "breastfit/mesh/triangle_mesh.h"

namespace breastfit::transfer {

/// The topology of one mesh (its triangles and vertex count).
struct MeshTopology {
  mesh::AdjacencyLists neighbours;  ///< mesh::vertex_neighbours
  mesh::AdjacencyLists faces;       ///< mesh::vertex_faces
};

/// The factorisation of a chest-wall fill's matrix (free vertices by free vertices).
using FillSolver = Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>>;

/// Topologies and fill factorisations kept across measurements (see the file comment). Holds
/// the most recently used few of each; what it returns stays valid after later calls.
class VolumeCache {
 public:
  /// The topology of `mesh`: the cached one when an entry has the same triangles and vertex
  /// count, else computed (and kept).
  std::shared_ptr<const MeshTopology> topology(const TriangleMesh& mesh);
  /// mesh::boundary_loops of `mesh`, cached as topology().
  std::shared_ptr<const std::vector<std::vector<Index>>> boundary_loops(const TriangleMesh& mesh);
  /// The factorisation of the fill matrix `m` (square, symmetric positive definite): the cached
  /// one when an entry's matrix equals `m` entry for entry, else factorised (and kept, also
  /// when it failed: check solver->info()).
  std::shared_ptr<const FillSolver> fill_solver(const Eigen::SparseMatrix<double>& m);

  int hits() const;    ///< lookups answered from the cache (all kinds)
  int misses() const;  ///< lookups computed

 private:
  struct TopologyEntry {
    Index num_vertices = 0;
    Triangles F;
    std::shared_ptr<const MeshTopology> topology;
    std::shared_ptr<const std::vector<std::vector<Index>>> boundary;
  };
  struct FillEntry {
    Eigen::SparseMatrix<double> matrix;
    std::shared_ptr<const FillSolver> solver;
  };
  TopologyEntry& entry_for(const TriangleMesh& mesh);  // with mutex_ held
  mutable std::mutex mutex_;
  int hits_ = 0, misses_ = 0;
  std::vector<TopologyEntry> topologies_;  ///< most recently used first
  std::vector<FillEntry> fills_;           ///< most recently used first
};

/// cache->topology(mesh), or the topology computed afresh without a cache.
std::shared_ptr<const MeshTopology> topology_of(const TriangleMesh& mesh, VolumeCache* cache);

}  // namespace breastfit::transfer
