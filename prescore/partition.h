// Splitting a tet mesh into pieces: the paper's round-robin flood fill.
//
// Li, Andrews, Jones, Bargteil, "Energized Rigid Body Fracture" (2018), hollow bunny scene:
// choose N seed tets at random, then grow the pieces in turn, each claiming one unclaimed
// face-neighbour of its region per turn in breadth-first order, until every tet is claimed.
// Every tet ends in exactly one piece and every piece is one face-connected component.
//
// Decisions the paper leaves open:
// - A piece whose frontier empties (enclosed by other pieces) stops; the others go on.
// - A mesh of several face-connected components gets at least one seed per component (otherwise
//   a component could never be claimed). The other seeds go to components in proportion to
//   their tet counts (Jefferson/D'Hondt highest averages, ties to the lower component), never
//   more seeds than a component has tets.
// - Seeds are drawn with prescore's own Rng (rng.h), so the same seed gives the same pieces on
//   every platform. Pieces are numbered in ascending order of their seed tet.
#pragma once

#include <cstdint>
#include <vector>

#include "core/geometry.h"
#include "prescore/tet_topology.h"

namespace shatter {

struct Partition {
    std::vector<uint32_t> tet_piece;   // piece of each tet
    std::vector<uint32_t> seeds;       // seed tet of each piece, ascending
    std::vector<uint32_t> piece_tets;  // number of tets in each piece
};

// Splits `mesh` (with its `topology`) into `pieces` pieces from random seeds drawn with `seed`.
// Input Errors: pieces == 0, pieces > number of tets, pieces < number of face-connected
// components.
Partition partition(const TetMesh& mesh, const TetTopology& topology, uint32_t pieces, uint64_t seed);

}  // namespace shatter
