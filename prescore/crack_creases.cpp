#include "prescore/crack_creases.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <utility>

namespace shatter {

CrackCreases crack_creases(const std::vector<RenderSurface>& surfaces, double diagonal, double degrees) {
    CrackCreases out;
    const double cos_limit = std::cos(degrees * M_PI / 180);
    for (const RenderSurface& s : surfaces) {
        std::map<std::array<double, 3>, uint32_t> weld;
        std::vector<Vec3> at;
        std::vector<Vec3> normal;  // per crack triangle; zero when degenerate
        std::map<std::pair<uint32_t, uint32_t>, std::vector<size_t>> edges;
        for (size_t t = 0; t < s.triangles.size(); ++t) {
            if (s.kinds[t] != FaceKind::Fracture) continue;
            std::array<uint32_t, 3> v;
            for (int k = 0; k < 3; ++k) {
                const Vec3& p = s.vertices[s.triangles[t][k]];
                auto [it, fresh] = weld.emplace(std::array<double, 3>{p.x(), p.y(), p.z()}, uint32_t(at.size()));
                if (fresh) at.push_back(p);
                v[k] = it->second;
            }
            const Vec3 n = (at[v[1]] - at[v[0]]).cross(at[v[2]] - at[v[0]]);
            out.area += n.norm() / 2;
            const size_t f = normal.size();
            normal.push_back(n.norm() > 2e-12 * diagonal * diagonal ? Vec3(n.normalized()) : Vec3::Zero());
            for (int k = 0; k < 3; ++k) edges[std::minmax(v[k], v[(k + 1) % 3])].push_back(f);
        }
        for (const auto& [e, faces] : edges) {
            if (faces.size() != 2 || normal[faces[0]].isZero() || normal[faces[1]].isZero()) continue;
            ++out.inner_edges;
            if (normal[faces[0]].dot(normal[faces[1]]) < cos_limit) {
                ++out.creases;
                out.crease_length += (at[e.first] - at[e.second]).norm();
            }
        }
    }
    out.density = out.area > 0 ? out.crease_length / out.area * diagonal : 0;
    out.share = out.inner_edges ? double(out.creases) / double(out.inner_edges) : 0;
    return out;
}

}  // namespace shatter
