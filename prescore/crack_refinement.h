// The tets a faired crack can pass through, split 1:8 (crack_fairing.h): each such tet into its
// four corner tets and the four of its middle octahedron (cut along its shortest diagonal), at
// the midpoints of its edges. The other tets stay whole; where one of their boundary faces meets
// a split tet's, its edges' midpoints are corners of the split faces, so a face drawn from them
// takes those midpoints in (`midpoint`) and the surface has no T-junctions.
#pragma once

#include <array>
#include <cstdint>
#include <utility>
#include <vector>

#include "core/geometry.h"
#include "core/model.h"
#include "prescore/tet_topology.h"

namespace shatter {

struct CrackRefinement {
    TetMesh mesh;                 // the original vertices, then one per split edge (its midpoint); the tets in
                                  // order, a split one replaced by its eight (positively oriented)
    std::vector<uint32_t> parent;  // per tet: the original tet it lies in
    std::vector<char> whole;       // per tet: an original tet, not split
    std::vector<std::array<int32_t, 4>> boundary;  // per tet, per face: -1 inside the object, else the
                                                   // FaceKind of the original boundary face it lies on
    std::vector<std::array<uint32_t, 2>> ends;     // per vertex after the originals: its edge's ends (ascending)

    size_t originals() const { return mesh.vertices.size() - ends.size(); }
    // The midpoint vertex of the original edge (a, b), or UINT32_MAX when it is not split.
    uint32_t midpoint(uint32_t a, uint32_t b) const;

    std::vector<std::pair<std::array<uint32_t, 2>, uint32_t>> edges;  // split edges (ascending) -> midpoint
};

// `split[t]`: tet t is split. `face_kind[t][i]`: what face i of tet t is on the boundary.
CrackRefinement refine_tets(const TetMesh& mesh, const TetTopology& topology,
                            const std::vector<std::array<FaceKind, 4>>& face_kind, const std::vector<char>& split);

}  // namespace shatter
