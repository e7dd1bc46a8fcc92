// Pre-scored interfaces and their tie-break fracture for the continuum reference
// (bench/fem_interfaces.h).
#include "bench/fem_interfaces.h"

#include <algorithm>
#include <array>
#include <map>
#include <numeric>
#include <tuple>

namespace shatter::fem {

namespace {

struct UnionFind {
    std::vector<uint32_t> p;
    explicit UnionFind(size_t n) : p(n) { std::iota(p.begin(), p.end(), 0u); }
    uint32_t find(uint32_t x) {
        while (p[x] != x) x = p[x] = p[p[x]];
        return x;
    }
    void join(uint32_t a, uint32_t b) {
        a = find(a);
        b = find(b);
        if (a != b) p[std::max(a, b)] = std::min(a, b);
    }
};

}  // namespace

SplitMesh split_pieces(const TetMesh& mesh, const std::vector<uint32_t>& tet_piece) {
    SplitMesh s;
    for (uint32_t p : tet_piece) s.pieces = std::max(s.pieces, p + 1);
    // One copy per (vertex, piece), numbered in order of first use by ascending tets.
    std::map<std::pair<uint32_t, uint32_t>, uint32_t> copy;
    s.mesh.tets.reserve(mesh.tets.size());
    for (size_t t = 0; t < mesh.tets.size(); ++t) {
        Tet nt;
        for (int a = 0; a < 4; ++a) {
            const auto key = std::make_pair(mesh.tets[t][a], tet_piece[t]);
            auto it = copy.find(key);
            if (it == copy.end()) {
                it = copy.emplace(key, uint32_t(s.mesh.vertices.size())).first;
                s.mesh.vertices.push_back(mesh.vertices[key.first]);
                s.vertex_piece.push_back(key.second);
                s.original.push_back(key.first);
            }
            nt[a] = it->second;
        }
        s.mesh.tets.push_back(nt);
    }
    // Faces shared by tets of two pieces: each gives a third of its area to each of its vertices'
    // ties, with its normal oriented from the lower piece into the higher.
    std::map<std::array<uint32_t, 3>, std::pair<size_t, int>> open;  // sorted face -> (tet, face)
    std::map<std::tuple<uint32_t, uint32_t, uint32_t>, Tie> ties;     // (piece_a, piece_b, vertex)
    for (size_t t = 0; t < mesh.tets.size(); ++t)
        for (int f = 0; f < 4; ++f) {
            std::array<uint32_t, 3> key;
            for (int k = 0; k < 3; ++k) key[k] = mesh.tets[t][kTetFaces[f][k]];
            std::sort(key.begin(), key.end());
            const auto it = open.find(key);
            if (it == open.end()) {
                open.emplace(key, std::make_pair(t, f));
                continue;
            }
            const size_t u = it->second.first;
            const int fu = it->second.second;
            open.erase(it);
            if (tet_piece[u] == tet_piece[t]) continue;
            // The outward normal of tet u's face (kTetFaces is outward), area-weighted.
            const Vec3& p0 = mesh.vertices[mesh.tets[u][kTetFaces[fu][0]]];
            const Vec3& p1 = mesh.vertices[mesh.tets[u][kTetFaces[fu][1]]];
            const Vec3& p2 = mesh.vertices[mesh.tets[u][kTetFaces[fu][2]]];
            Vec3 an = 0.5 * (p1 - p0).cross(p2 - p0);  // out of u's piece
            uint32_t pa = tet_piece[u], pb = tet_piece[t];
            if (pa > pb) {
                std::swap(pa, pb);
                an = -an;
            }
            for (uint32_t v : key) {
                Tie& tie = ties[{pa, pb, v}];
                tie.vertex = v;
                tie.piece_a = pa;
                tie.piece_b = pb;
                tie.copy_a = copy.at({v, pa});
                tie.copy_b = copy.at({v, pb});
                tie.area += an.norm() / 3;
                tie.normal += an / 3;
            }
        }
    for (auto& [key, tie] : ties) {
        tie.normal.normalize();
        s.ties.push_back(tie);
    }
    return s;
}

void Interfaces::apply(FemSolid& solid) const {
    UnionFind uf(s_.mesh.vertices.size());
    for (const Tie& t : s_.ties)
        if (!t.broken) uf.join(t.copy_a, t.copy_b);
    std::vector<uint32_t> group(s_.mesh.vertices.size());
    for (uint32_t v = 0; v < group.size(); ++v) group[v] = uf.find(v);
    solid.set_vertex_groups(group);
}

void Interfaces::traction(const FemSolid& solid, size_t i, double& sigma, double& tau) const {
    const Tie& t = s_.ties[i];
    const Eigen::VectorXd& g = solid.group_forces();
    // (F_b - F_a) / 2: the force into b's copy, and for a vertex shared by two pieces only, minus
    // the force into a's copy. A clamped or driven copy's group force includes what holds it:
    // then the other copy's alone.
    const Vec3 Fa = g.segment<3>(3 * t.copy_a), Fb = g.segment<3>(3 * t.copy_b);
    const Vec3 F = solid.constrained(t.copy_a) ? Fb : solid.constrained(t.copy_b) ? Vec3(-Fa) : Vec3(0.5 * (Fb - Fa));
    const double fn = F.dot(t.normal);
    sigma = -fn / t.area;
    tau = (F - fn * t.normal).norm() / t.area;
}

size_t Interfaces::break_overloaded(FemSolid& solid, const Strength& strength) {
    size_t broke = 0;
    max_sigma = max_tau = 0;
    for (size_t i = 0; i < s_.ties.size(); ++i) {
        if (s_.ties[i].broken) continue;
        double sigma, tau;
        traction(solid, i, sigma, tau);
        max_sigma = std::max(max_sigma, sigma);
        max_tau = std::max(max_tau, tau);
        if (sigma > strength.tensile || tau > strength.shear) {
            s_.ties[i].broken = true;
            s_.ties[i].break_time = solid.time();
            ++broke;
        }
    }
    if (broke) apply(solid);
    return broke;
}

size_t Interfaces::fragments() const {
    UnionFind uf(s_.pieces);
    for (const Tie& t : s_.ties)
        if (!t.broken) uf.join(t.piece_a, t.piece_b);
    size_t n = 0;
    for (uint32_t p = 0; p < s_.pieces; ++p) n += uf.find(p) == p;
    return n;
}

}  // namespace shatter::fem
