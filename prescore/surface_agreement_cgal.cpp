// Closest points on every piece's render triangles with one CGAL AABB tree
// (prescore/triangle_tree_cgal.h: distances, no predicates that need exactness).
#include "prescore/surface_agreement.h"

#include <algorithm>
#include <cmath>

#include "prescore/triangle_tree_cgal.h"

namespace shatter {

SurfaceAgreement surface_agreement(const TriangleMesh& input, const std::vector<RenderSurface>& surfaces,
                                   double crease_degrees, double normal_degrees) {
    SurfaceAgreement a;
    std::vector<TreeTriangle> triangles;
    std::vector<std::pair<uint32_t, uint32_t>> owner;  // (surface, triangle)
    for (uint32_t s = 0; s < surfaces.size(); ++s)
        for (uint32_t t = 0; t < surfaces[s].triangles.size(); ++t) {
            const Tri& tri = surfaces[s].triangles[t];
            const auto& v = surfaces[s].vertices;
            triangles.emplace_back(tree_point(v[tri[0]]), tree_point(v[tri[1]]), tree_point(v[tri[2]]));
            owner.emplace_back(s, t);
        }
    if (triangles.empty() || input.vertices.empty()) return a;
    TriangleTree tree(triangles.cbegin(), triangles.cend());
    tree.accelerate_distance_queries();

    std::vector<Vec3> sum(input.vertices.size(), Vec3::Zero());
    std::vector<std::vector<Vec3>> faces(input.vertices.size());
    for (const Tri& t : input.triangles) {
        const Vec3 n = (input.vertices[t[1]] - input.vertices[t[0]]).cross(input.vertices[t[2]] - input.vertices[t[0]]);
        for (uint32_t v : t) sum[v] += n, faces[v].push_back(n);
    }
    const double cos_crease = std::cos(crease_degrees * M_PI / 180), cos_ok = std::cos(normal_degrees * M_PI / 180);
    std::vector<double> distance;
    size_t within = 0;
    for (size_t i = 0; i < input.vertices.size(); ++i) {
        if (faces[i].empty()) continue;
        const Vec3& p = input.vertices[i];
        const auto hit = tree.closest_point_and_primitive(tree_point(p));
        const Vec3 q(hit.first.x(), hit.first.y(), hit.first.z());
        distance.push_back((q - p).norm());
        const Vec3 n = sum[i].normalized();
        bool smooth = sum[i].norm() > 0;
        for (const Vec3& f : faces[i]) smooth = smooth && f.dot(n) >= cos_crease * f.norm();
        if (!smooth) continue;
        ++a.smooth_samples;
        const auto [s, t] = owner[size_t(hit.second - triangles.cbegin())];
        const RenderSurface& rs = surfaces[s];
        const Tri& tri = rs.triangles[t];
        const Vec3 &x = rs.vertices[tri[0]], &y = rs.vertices[tri[1]], &z = rs.vertices[tri[2]];
        const Vec3 fn = (y - x).cross(z - x);
        const double nn = fn.squaredNorm();
        Vec3 w(1.0 / 3, 1.0 / 3, 1.0 / 3);
        if (nn > 0) {
            w = Vec3((z - y).cross(q - y).dot(fn) / nn, (x - z).cross(q - z).dot(fn) / nn, 0);
            w.z() = 1 - w.x() - w.y();
        }
        const Vec3 rn = w.x() * rs.normals[tri[0]] + w.y() * rs.normals[tri[1]] + w.z() * rs.normals[tri[2]];
        if (rn.norm() > 0 && rn.normalized().dot(n) >= cos_ok) ++within;
    }
    a.samples = distance.size();
    std::sort(distance.begin(), distance.end());
    a.distance_max = distance.back();
    a.distance_p99 = distance[std::min(distance.size() - 1, size_t(std::ceil(0.99 * distance.size())) - 1)];
    a.normals_within = a.smooth_samples ? double(within) / a.smooth_samples : 0;
    return a;
}

}  // namespace shatter
