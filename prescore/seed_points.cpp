// Seed tets from points (see seed_points.h): a brute-force search over the tets per point.
#include "prescore/seed_points.h"

#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "core/error.h"

namespace shatter {

namespace {

// Whether p lies in the tet (a, b, c, d), its boundary included up to round-off.
bool inside(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
    const double v = tet_volume(a, b, c, d), tol = -1e-12 * v * v;
    return tet_volume(p, b, c, d) * v >= tol && tet_volume(a, p, c, d) * v >= tol &&
           tet_volume(a, b, p, d) * v >= tol && tet_volume(a, b, c, p) * v >= tol;
}

std::string text(const std::array<double, 3>& p) { return fmt::format("[{:g}, {:g}, {:g}]", p[0], p[1], p[2]); }

}  // namespace

std::vector<uint32_t> seed_tets_of_points(const TetMesh& mesh, const std::vector<std::array<double, 3>>& points,
                                          double reach, const std::string& where) {
    Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
    for (const Vec3& v : mesh.vertices) lo = lo.cwiseMin(v), hi = hi.cwiseMax(v);
    std::vector<uint32_t> seeds;
    for (size_t i = 0; i < points.size(); ++i) {
        const Vec3 p(points[i][0], points[i][1], points[i][2]);
        uint32_t found = UINT32_MAX, nearest = 0;
        double best = std::numeric_limits<double>::infinity();
        for (uint32_t t = 0; t < mesh.tets.size() && found == UINT32_MAX; ++t) {
            const Tet& k = mesh.tets[t];
            const Vec3 &a = mesh.vertices[k[0]], &b = mesh.vertices[k[1]], &c = mesh.vertices[k[2]],
                       &d = mesh.vertices[k[3]];
            if (inside(p, a, b, c, d)) found = t;
            const double d2 = (tet_centroid(mesh, t) - p).squaredNorm();
            if (d2 < best) best = d2, nearest = t;
        }
        if (found == UINT32_MAX && std::sqrt(best) > reach)
            throw_input_error(where,
                              fmt::format("prescore.seed_points[{}] = {} m is outside the object: {:.3g} m from its "
                                          "nearest tet (the object spans [{:.3g}, {:.3g}, {:.3g}] to [{:.3g}, {:.3g}, "
                                          "{:.3g}] m in the model's frame)",
                                          i, text(points[i]), std::sqrt(best), lo.x(), lo.y(), lo.z(), hi.x(), hi.y(),
                                          hi.z()),
                              "give points inside the object, in metres in the model's frame (the mesh's own "
                              "coordinates at its scale, before [object] places it)");
        const uint32_t tet = found != UINT32_MAX ? found : nearest;
        for (size_t j = 0; j < seeds.size(); ++j)
            if (seeds[j] == tet)
                throw_input_error(where,
                                  fmt::format("prescore.seed_points[{}] = {} and [{}] = {} fall in the same tet", j,
                                              text(points[j]), i, text(points[i])),
                                  fmt::format("give points at least a tet apart (about {:.3g} m here), or fewer",
                                              reach));
        seeds.push_back(tet);
    }
    return seeds;
}

}  // namespace shatter
