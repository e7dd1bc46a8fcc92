// One pass over the piece's tets; a vertex map (mesh vertex -> surface vertex) compacts the
// vertices in first-use order.
#include "prescore/piece_surface.h"

#include <cassert>

namespace shatter {

PieceSurface piece_surface(const TetMesh& mesh, const TetTopology& topology, const std::vector<uint32_t>& tet_piece,
                           uint32_t piece, const std::vector<std::array<bool, 4>>* cavity_face) {
    assert(topology.neighbour.size() == mesh.tets.size() && tet_piece.size() == mesh.tets.size());
    assert(!cavity_face || cavity_face->size() == mesh.tets.size());
    constexpr uint32_t kUnused = UINT32_MAX;
    std::vector<uint32_t> remap(mesh.vertices.size(), kUnused);
    PieceSurface surface;
    auto surface_vertex = [&](uint32_t v) {
        if (remap[v] == kUnused) {
            remap[v] = uint32_t(surface.vertices.size());
            surface.vertices.push_back(mesh.vertices[v]);
        }
        return remap[v];
    };
    for (size_t t = 0; t < mesh.tets.size(); ++t) {
        if (tet_piece[t] != piece) continue;
        for (int i = 0; i < 4; ++i) {
            const int32_t u = topology.neighbour[t][i];
            FaceKind kind;
            if (u >= 0) {
                if (tet_piece[u] == piece) continue;
                kind = FaceKind::Fracture;
            } else {
                kind = (cavity_face && (*cavity_face)[t][i]) ? FaceKind::Cavity : FaceKind::Outer;
            }
            const Tet& tet = mesh.tets[t];
            Tri tri;
            for (int k = 0; k < 3; ++k) tri[k] = surface_vertex(tet[kTetFaces[i][k]]);
            surface.triangles.push_back(tri);
            surface.kinds.push_back(kind);
        }
    }
    return surface;
}

}  // namespace shatter
