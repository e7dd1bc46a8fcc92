// Convex hull with CGAL::convex_hull_3 into a Surface_mesh; the volume is the sum of the signed
// volumes of the tets (first hull vertex, face) over the hull's triangles, in a canonical order.
#include "prescore/convex_hull.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/convex_hull_3.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

namespace shatter {

namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = K::Point_3;
using Mesh = CGAL::Surface_mesh<Point>;

Vec3 vec(const Point& p) { return {p.x(), p.y(), p.z()}; }

bool lex_less(const Vec3& a, const Vec3& b) {
    return std::lexicographical_compare(a.data(), a.data() + 3, b.data(), b.data() + 3);
}

std::vector<Vec3> sorted_unique(std::vector<Vec3> points) {
    std::sort(points.begin(), points.end(), lex_less);
    points.erase(std::unique(points.begin(), points.end()), points.end());
    return points;
}

// True when the (distinct) points are not all coplanar.
bool spans_solid(const std::vector<Point>& p) {
    size_t i2 = 2;
    while (i2 < p.size() && CGAL::collinear(p[0], p[1], p[i2])) ++i2;
    for (size_t i3 = i2 + 1; i3 < p.size(); ++i3) {
        if (!CGAL::coplanar(p[0], p[1], p[i2], p[i3])) return true;
    }
    return false;
}

}  // namespace

std::vector<Vec3> convex_hull_points(const std::vector<Vec3>& points, double* hull_volume, double* hull_area) {
    if (hull_volume) *hull_volume = 0;
    if (hull_area) *hull_area = 0;
    std::vector<Vec3> unique = sorted_unique(points);
    if (unique.size() < 4) return unique;
    std::vector<Point> input;
    input.reserve(unique.size());
    for (const Vec3& p : unique) input.emplace_back(p.x(), p.y(), p.z());
    if (!spans_solid(input)) return unique;

    Mesh hull;
    CGAL::convex_hull_3(input.begin(), input.end(), hull);
    if (hull.number_of_faces() < 4) return unique;

    // CGAL's output order of vertices and faces can change from call to call (it copies through
    // containers ordered by address), so sort both before summing, for bit-identical volumes.
    std::vector<Vec3> result;
    for (auto v : hull.vertices()) result.push_back(vec(hull.point(v)));
    std::sort(result.begin(), result.end(), lex_less);
    auto index_of = [&](const Point& p) {
        return uint32_t(std::lower_bound(result.begin(), result.end(), vec(p), lex_less) - result.begin());
    };
    std::vector<std::array<uint32_t, 3>> triangles;
    for (auto f : hull.faces()) {
        std::array<uint32_t, 3> t{};
        int k = 0;
        for (auto v : CGAL::vertices_around_face(hull.halfedge(f), hull)) {
            if (k < 3) t[k] = index_of(hull.point(v));
            ++k;
        }
        std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());  // keeps orientation
        triangles.push_back(t);
    }
    std::sort(triangles.begin(), triangles.end());
    double volume = 0, area = 0;
    for (const auto& t : triangles) {
        volume += tet_volume(result[0], result[t[0]], result[t[1]], result[t[2]]);
        area += 0.5 * (result[t[1]] - result[t[0]]).cross(result[t[2]] - result[t[0]]).norm();
    }
    if (hull_volume) *hull_volume = std::abs(volume);
    if (hull_area) *hull_area = area;
    return result;
}

}  // namespace shatter
