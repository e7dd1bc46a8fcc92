// Face adjacency of a tet mesh and its face-connected components.
//
// Two tets are neighbours when they share a face (three vertex indices, any order). A face is on
// the boundary when no other tet shares it. Built by sorting the 4n faces by their sorted vertex
// triple: O(n log n), no hashing, so the result never depends on hash-table order.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "core/geometry.h"

namespace shatter {

struct TetTopology {
    // neighbour[t][i]: the tet across face i of tet t (face i is opposite vertex i, see
    // kTetFaces), or -1 when that face is on the boundary.
    std::vector<std::array<int32_t, 4>> neighbour;
};

// Face adjacency of `mesh`. A face shared by more than two tets means the mesh is not a
// manifold tet mesh, which our tetrahedralization never produces: that is a bug, reported as an
// Error with ExitCode::Internal.
TetTopology build_topology(const TetMesh& mesh);

// Face-connected components of the tets with mask[t] != 0 (all tets when mask is empty), moving
// only between masked tets. Returns the component of each tet (-1 for tets outside the mask);
// components are numbered 0, 1, ... in the order of their lowest tet index. `count`, when not
// null, receives the number of components.
std::vector<int32_t> tet_components(const TetTopology& topology, const std::vector<char>& mask,
                                    int32_t* count);

}  // namespace shatter
