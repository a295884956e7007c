#include "breastfit/spatial/detail/bvh4_parents.h"

#include <cstddef>

namespace breastfit::spatial::detail {

Bvh4Parents bvh4_parents(const Bvh4Nodes& wide, const LeafBlocks& blocks, Index num_faces) {
  Bvh4Parents p;
  p.node_parent.assign(wide.size(), -1);
  p.face_node.assign(static_cast<std::size_t>(num_faces), -1);
  for (std::size_t n = 0; n < wide.size(); ++n) {
    const Bvh4Node& node = wide[n];
    for (int s = 0; s < 4 && node.ref[s] != kBvh4Empty; ++s) {
      if (node.ref[s] >= 0) {
        p.node_parent[static_cast<std::size_t>(node.ref[s])] = static_cast<std::int32_t>(n);
        continue;
      }
      const auto* h = reinterpret_cast<const LeafHeader*>(blocks[static_cast<std::size_t>(~node.ref[s])].bytes);
      for (int t = 0; t < h->count; ++t) p.face_node[static_cast<std::size_t>(h->face[t])] = static_cast<std::int32_t>(n);
    }
  }
  return p;
}

}  // namespace breastfit::spatial::detail
