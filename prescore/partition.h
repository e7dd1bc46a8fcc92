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
//
// Graded pieces (a `density` per tet, prescore/graded_seeds.h): small pieces where the density is
// high. Within each component the seeds are drawn without replacement with probability
// proportional to density x tet volume. Then every turn gives each piece one credit, and the
// next tet of its breadth-first frontier costs its density over the lowest density: a piece takes
// it when its credit covers the cost, else waits. So the pieces grow at equal rates of density
// (not of tets), and a piece where the density is k times higher ends about k times smaller.
// Denser seeds alone leave the near pieces only a little smaller (the round-robin gives every
// piece the same growth in tets). Components get their seeds as in the uniform partition.
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
    uint32_t joined_components = 0;    // partition_from_seeds: components without a seed, joined to a piece
};

// Splits `mesh` (with its `topology`) into `pieces` pieces from random seeds drawn with `seed`.
// Input Errors: pieces == 0, pieces > number of tets, pieces < number of face-connected
// components.
// With `density` (one positive value per tet) the pieces are graded as above; without it (empty)
// this is the uniform partition, byte for byte.
Partition partition(const TetMesh& mesh, const TetTopology& topology, uint32_t pieces, uint64_t seed,
                    const std::vector<double>& density = {});

// The uniform round-robin growth from given seed tets (distinct; seeds = "points",
// prescore/seed_points.h): one piece per seed, numbered in ascending order of its seed tet. A
// face-connected component without a seed goes whole to the piece of the seeded tet nearest its
// first tet's centroid (counted in joined_components).
Partition partition_from_seeds(const TetMesh& mesh, const TetTopology& topology, std::vector<uint32_t> seeds);

}  // namespace shatter
