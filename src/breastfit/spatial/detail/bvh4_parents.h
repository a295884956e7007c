#pragma once
/// \file Where each face and node of ClosestPointIndex's four-wide tree hangs (private to the
/// spatial layer): the node whose slot holds a face's leaf, and each node's parent. A search
/// warm-started from a face mostly ends near it, reading those nodes and the leaves beside it;
/// knowing them from the face alone lets the caller fetch them into the cache queries ahead
/// (the searches on a large scan are bound by cache misses, docs/PERFORMANCE.md).
#include <cstdint>
#include <vector>

#include "breastfit/core/types.h"
#include "breastfit/spatial/detail/bvh4.h"
#include "breastfit/spatial/detail/leaf_blocks.h"

namespace breastfit::spatial::detail {

struct Bvh4Parents {
  std::vector<std::int32_t> node_parent;  ///< by wide node: its parent node (−1 for the root)
  std::vector<std::int32_t> face_node;    ///< by face: the node whose slot holds its leaf (−1: none)
};

/// The parents of `wide` (a tree of collapse_to_bvh4 whose leaf slots point at their blocks in
/// `blocks`, as ClosestPointIndex builds them) over a mesh of `num_faces` faces.
Bvh4Parents bvh4_parents(const Bvh4Nodes& wide, const LeafBlocks& blocks, Index num_faces);

}  // namespace breastfit::spatial::detail
