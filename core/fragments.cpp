#include <algorithm>
#include <cmath>
#include <numeric>

#include "core/fragments.h"
#include "core/model.h"

namespace shatter {

double piece_radius(const Piece& piece) {
    double r2 = 0;
    for (const Vec3& v : piece.surface.vertices) r2 = std::max(r2, (v - piece.mass.center).squaredNorm());
    return std::sqrt(r2);
}

std::vector<uint32_t> fragment_of(const Model& model, const std::vector<bool>& broken) {
    std::vector<uint32_t> parent(model.pieces.size());
    std::iota(parent.begin(), parent.end(), 0u);
    auto find = [&](uint32_t x) {
        while (parent[x] != x) x = parent[x] = parent[parent[x]];
        return x;
    };
    for (size_t c = 0; c < model.constraints.size(); ++c)
        if (c >= broken.size() || !broken[c]) parent[find(model.constraints[c].piece_a)] = find(model.constraints[c].piece_b);
    for (uint32_t p = 0; p < parent.size(); ++p) parent[p] = find(p);
    return parent;
}

size_t count_fragments(const Model& model, const std::vector<bool>& broken) {
    const std::vector<uint32_t> group = fragment_of(model, broken);
    size_t groups = 0;
    for (uint32_t p = 0; p < group.size(); ++p) groups += group[p] == p;
    return groups;
}

double spread_energy(const Model& model, const Trajectory& t, uint32_t f) {
    if (t.frames() < 3) return 0;
    f = std::clamp<uint32_t>(f, 1, t.frames() - 2);
    double mass = 0;
    Eigen::Vector3d momentum = Eigen::Vector3d::Zero();
    std::vector<Eigen::Vector3d> v(t.pieces);
    for (uint32_t b = 0; b < t.pieces; ++b) {
        v[b] = (t.pose(f + 1, b).position - t.pose(f - 1, b).position).cast<double>() * (t.fps / 2);
        mass += model.pieces[b].mass.mass;
        momentum += model.pieces[b].mass.mass * v[b];
    }
    const Eigen::Vector3d v_cm = mass > 0 ? Eigen::Vector3d(momentum / mass) : Eigen::Vector3d::Zero();
    double e = 0;
    for (uint32_t b = 0; b < t.pieces; ++b) e += 0.5 * model.pieces[b].mass.mass * (v[b] - v_cm).squaredNorm();
    return e;
}

}  // namespace shatter
