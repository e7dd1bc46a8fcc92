// Top-down median splitting of a piece's tets into convex parts (see collision_parts.h).
#include "prescore/collision_parts.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cassert>
#include <cmath>
#include <string>

#include "core/error.h"
#include "prescore/convex_hull.h"

namespace shatter {

namespace {

struct Group {
    std::vector<uint32_t> tets;
    ConvexPart part;
    double hull_area = 0;
    double excess() const { return part.hull_volume - part.volume; }
};

Vec3 centroid(const TetMesh& mesh, uint32_t t) {
    const Tet& tet = mesh.tets[t];
    return 0.25 * (mesh.vertices[tet[0]] + mesh.vertices[tet[1]] + mesh.vertices[tet[2]] + mesh.vertices[tet[3]]);
}

// `scratch` is a per-vertex flag array (all 0 on entry and on return).
Group make_group(const TetMesh& mesh, std::vector<uint32_t> tets, std::vector<char>& scratch) {
    Group g;
    g.tets = std::move(tets);
    std::vector<uint32_t> vertices;
    for (uint32_t t : g.tets) {
        const Tet& tet = mesh.tets[t];
        g.part.volume += tet_volume(mesh.vertices[tet[0]], mesh.vertices[tet[1]], mesh.vertices[tet[2]],
                                    mesh.vertices[tet[3]]);
        for (uint32_t v : tet) {
            if (scratch[v]) continue;
            scratch[v] = 1;
            vertices.push_back(v);
        }
    }
    std::vector<Vec3> points;
    points.reserve(vertices.size());
    for (uint32_t v : vertices) {
        points.push_back(mesh.vertices[v]);
        scratch[v] = 0;
    }
    g.part.points = convex_hull_points(points, &g.part.hull_volume, &g.hull_area);  // sorts: input order is irrelevant
    g.part.hull_volume = std::max(g.part.hull_volume, g.part.volume);  // rounding: hull >= tets
    return g;
}

bool tight(const Group& g, const CollisionSettings& s) {
    // 1e-9 of the hull: rounding, so that an exactly convex group counts as tight at max_gap 0.
    return g.tets.size() < 2 || g.excess() <= s.max_gap * g.hull_area + 1e-9 * g.part.hull_volume;
}

// The split axes to try: x, y, z and the principal axis of the centroids.
std::vector<Vec3> candidate_axes(const std::vector<Vec3>& centroids) {
    std::vector<Vec3> axes = {Vec3::UnitX(), Vec3::UnitY(), Vec3::UnitZ()};
    Vec3 mean = Vec3::Zero();
    for (const Vec3& c : centroids) mean += c;
    mean /= double(centroids.size());
    Mat3 cov = Mat3::Zero();
    for (const Vec3& c : centroids) cov += (c - mean) * (c - mean).transpose();
    Eigen::SelfAdjointEigenSolver<Mat3> eigen(cov);
    Vec3 principal = eigen.eigenvectors().col(2);  // eigenvalues ascending: largest last
    Eigen::Index largest = 0;
    principal.cwiseAbs().maxCoeff(&largest);
    if (principal[largest] < 0) principal = -principal;  // a sign that does not depend on the solver
    axes.push_back(principal);
    return axes;
}

// Splits g at the median centroid along the best candidate axis.
std::pair<Group, Group> split(const TetMesh& mesh, const Group& g, std::vector<char>& scratch) {
    std::vector<Vec3> centroids;
    for (uint32_t t : g.tets) centroids.push_back(centroid(mesh, t));
    std::pair<Group, Group> best;
    double best_volume = INFINITY;
    for (const Vec3& axis : candidate_axes(centroids)) {
        std::vector<std::pair<double, uint32_t>> order;  // (projection, tet)
        for (size_t k = 0; k < g.tets.size(); ++k) order.emplace_back(axis.dot(centroids[k]), g.tets[k]);
        std::sort(order.begin(), order.end());
        std::vector<uint32_t> low, high;
        for (size_t k = 0; k < order.size(); ++k) (k < order.size() / 2 ? low : high).push_back(order[k].second);
        std::sort(low.begin(), low.end());
        std::sort(high.begin(), high.end());
        Group a = make_group(mesh, std::move(low), scratch);
        Group b = make_group(mesh, std::move(high), scratch);
        const double volume = a.part.hull_volume + b.part.hull_volume;
        if (volume < best_volume) {
            best_volume = volume;
            best = {std::move(a), std::move(b)};
        }
    }
    return best;
}

void validate(const CollisionSettings& s) {
    if (!std::isfinite(s.max_gap) || s.max_gap < 0) {
        throw_input_error("collision.max_gap", "must be a finite length >= 0 m, got " + std::to_string(s.max_gap),
                          "use e.g. 0.002 (hulls at most 2 mm from the real shape on average)");
    }
    if (s.max_parts < 1) {
        throw_input_error("collision.max_parts", "must be >= 1, got 0", "use e.g. 16");
    }
}

}  // namespace

std::vector<ConvexPart> collision_parts(const TetMesh& mesh, const std::vector<uint32_t>& tets,
                                        const CollisionSettings& settings) {
    validate(settings);
    if (tets.empty()) return {};
    std::vector<char> scratch(mesh.vertices.size(), 0);
    std::vector<Group> groups;
    groups.push_back(make_group(mesh, tets, scratch));
    while (groups.size() < settings.max_parts) {
        size_t worst = SIZE_MAX;
        for (size_t i = 0; i < groups.size(); ++i) {
            if (tight(groups[i], settings)) continue;
            if (worst == SIZE_MAX || groups[i].excess() > groups[worst].excess()) worst = i;
        }
        if (worst == SIZE_MAX) break;
        auto [a, b] = split(mesh, groups[worst], scratch);
        groups[worst] = std::move(a);
        groups.insert(groups.begin() + std::ptrdiff_t(worst) + 1, std::move(b));
    }
    std::vector<ConvexPart> parts;
    for (Group& g : groups) parts.push_back(std::move(g.part));
    return parts;
}

}  // namespace shatter
