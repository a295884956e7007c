#pragma once
/// \file Refitting ClosestPointIndex's tree to moved vertices (private to the spatial layer): the
/// same triangles in the same leaves, the leaves' corners and every box recomputed. A model posed
/// again and again (the fit's reverse term searches the posed template at every new pose) needs
/// no new tree: the search is exact whatever the tree, as long as each box holds what lies below
/// it, so the answers are those of a tree built for the new positions; only the queries slow
/// down as the boxes grow looser, the farther the vertices move from where the tree was built.
#include <cstdint>
#include <vector>

#include "breastfit/mesh/triangle_mesh.h"
#include "breastfit/spatial/detail/bvh4.h"
#include "breastfit/spatial/detail/leaf_blocks.h"

namespace breastfit::spatial::detail {

/// Rewrites each leaf block of `wide` with the corners of `mesh` (its new vertex positions; the
/// faces those the blocks were built from) and the degenerate bit of `face_flags` (kFlag*, by
/// face, already marked for the new positions), then every child box: a leaf's the bounds of its
/// corners rounded outward to float (as build_leaf_blocks), an inner child's the union of its
/// own children's (as the binary tree's, which the four-wide tree was collapsed from). A block
/// stored in doubles stays in doubles (exact either way). Returns false, with the blocks and
/// boxes partly rewritten, when a block stored in floats would have to hold a corner that is not
/// exactly a float: the caller builds the index anew.
bool refit_bvh4(const TriangleMesh& mesh, const std::vector<std::uint8_t>& face_flags, LeafBlocks& blocks,
                Bvh4Nodes& wide);

}  // namespace breastfit::spatial::detail
