// Every shared face between two pieces emits three (pair, vertex, area/3) records in tet order;
// a stable sort by (pair, vertex) then merges equal keys, summing areas in emission order so the
// sums are bit-identical run to run.
#include "prescore/constraints.h"

#include <algorithm>
#include <cassert>
#include <tuple>

namespace shatter {

namespace {

struct Share {
    uint32_t piece_a;
    uint32_t piece_b;
    uint32_t vertex;
    double area;  // (unit: m^2)

    auto key() const { return std::tie(piece_a, piece_b, vertex); }
};

std::vector<Share> shared_face_shares(const TetMesh& mesh, const TetTopology& topology,
                                      const std::vector<uint32_t>& tet_piece) {
    std::vector<Share> shares;
    for (size_t t = 0; t < mesh.tets.size(); ++t) {
        for (int i = 0; i < 4; ++i) {
            const int32_t u = topology.neighbour[t][i];
            if (u <= int32_t(t) || tet_piece[u] == tet_piece[t]) continue;  // each face once
            const uint32_t a = std::min(tet_piece[t], tet_piece[u]);
            const uint32_t b = std::max(tet_piece[t], tet_piece[u]);
            const Tet& tet = mesh.tets[t];
            const std::array<uint32_t, 3> f = {tet[kTetFaces[i][0]], tet[kTetFaces[i][1]], tet[kTetFaces[i][2]]};
            const Vec3& p0 = mesh.vertices[f[0]];
            const double area = 0.5 * (mesh.vertices[f[1]] - p0).cross(mesh.vertices[f[2]] - p0).norm();
            for (uint32_t v : f) shares.push_back({a, b, v, area / 3.0});
        }
    }
    return shares;
}

}  // namespace

std::vector<Constraint> place_constraints(const TetMesh& mesh, const TetTopology& topology,
                                          const std::vector<uint32_t>& tet_piece) {
    assert(topology.neighbour.size() == mesh.tets.size() && tet_piece.size() == mesh.tets.size());
    std::vector<Share> shares = shared_face_shares(mesh, topology, tet_piece);
    std::stable_sort(shares.begin(), shares.end(), [](const Share& x, const Share& y) { return x.key() < y.key(); });
    std::vector<Constraint> constraints;
    for (size_t i = 0; i < shares.size();) {
        Constraint c;
        c.piece_a = shares[i].piece_a;
        c.piece_b = shares[i].piece_b;
        c.vertex = shares[i].vertex;
        c.pivot = mesh.vertices[c.vertex];
        for (; i < shares.size() && shares[i].key() == std::tie(c.piece_a, c.piece_b, c.vertex); ++i) {
            c.area += shares[i].area;
        }
        constraints.push_back(c);
    }
    return constraints;
}

}  // namespace shatter
