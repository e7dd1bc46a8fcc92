// The surface of one piece: every face of the piece's tets whose neighbour is not in the piece.
//
// Faces keep the outward winding of kTetFaces, so the surface is closed and outward oriented
// (each edge used once in each direction; the signed volume it encloses equals the piece's
// volume). Each triangle says what it borders:
//   Outer    - the mesh boundary (the object's outside),
//   Cavity   - the mesh boundary where hollowing removed tets (cavity_face marks it),
//   Fracture - a tet of another piece.
// Vertices are compacted per piece in first-use order (tets ascending, faces 0..3, corners in
// face order).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "core/geometry.h"
#include "core/model.h"
#include "prescore/tet_topology.h"

namespace shatter {

// The surface of the tets t with tet_piece[t] == piece. `cavity_face` (one entry per tet, or
// null when the mesh was not hollowed) marks boundary faces that are cavity walls.
PieceSurface piece_surface(const TetMesh& mesh, const TetTopology& topology, const std::vector<uint32_t>& tet_piece,
                           uint32_t piece, const std::vector<std::array<bool, 4>>* cavity_face);

}  // namespace shatter
