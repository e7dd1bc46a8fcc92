// Hollowing: remove the interior of a tet mesh and keep a shell (the paper's hollow bunny,
// Li et al. 2018: "interior removed").
//
// Rule: keep a tet when its centroid lies within `thickness` of the tet mesh's boundary surface
// (the faces with no neighbour). Two additions make the result a usable solid:
// - Tets with a face on the boundary are always kept, so the outside surface is never opened
//   even when `thickness` is below the size of a tet.
// - The shell stays connected: the kept tets have as many face-connected components as the
//   input. Where removal splits a component (e.g. a solid with an internal void keeps an outer
//   shell and a shell around the void), removed tets are restored along shortest face paths:
//   a multi-source BFS from the kept pieces through removed tets, then a minimum spanning tree
//   (Kruskal, ties by tet index) over the shortest bridges between the kept pieces.
// Cost: shortest paths through centroids give upper bounds that settle most kept tets; an
// AABB-tree ball test (surface_distance.h) settles the rest. 105k tets: ~0.02-0.07 s.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/geometry.h"
#include "prescore/tet_topology.h"

namespace shatter {

struct HollowResult {
    TetMesh mesh;                               // the kept tets; vertices compacted, ascending by old index
    std::vector<uint32_t> source_tet;           // index of each kept tet in the input mesh
    std::vector<std::array<bool, 4>> cavity_face;  // per kept tet: face i borders a removed tet
    size_t removed = 0;                         // tets removed (after restoring)
    size_t restored = 0;                        // removed tets put back to keep the shell connected
};

// Hollows `mesh` (with its `topology`) to a shell of `thickness` (m; finite and > 0, otherwise
// an input Error).
HollowResult hollow(const TetMesh& mesh, const TetTopology& topology, double thickness);

}  // namespace shatter
