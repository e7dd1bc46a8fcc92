// Point constraints between pieces, as in the paper (Li et al. 2018): one constraint at every
// vertex of every face shared by two tets of different pieces, one per (piece pair, vertex).
//
// Each shared face gives a third of its area to each of its three vertices; a constraint's area
// is the sum of these thirds over the faces of its piece pair that touch the vertex. So the areas
// of one piece pair add up to the area of the faces the two pieces share (the breaking strength
// can then scale with area).
#pragma once

#include <cstdint>
#include <vector>

#include "core/geometry.h"
#include "core/model.h"
#include "prescore/tet_topology.h"

namespace shatter {

// The constraints joining the pieces of `tet_piece` (piece of each tet), sorted by
// (piece_a, piece_b, vertex) with piece_a < piece_b; pivot = the vertex position (m), area in m^2.
std::vector<Constraint> place_constraints(const TetMesh& mesh, const TetTopology& topology,
                                          const std::vector<uint32_t>& tet_piece);

}  // namespace shatter
