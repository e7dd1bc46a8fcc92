// The light half of render surfaces: flat fallbacks and crease-aware corner normals.
#include "prescore/render_surface.h"

#include <cmath>

namespace shatter {

RenderSurface flat_render_surface(const PieceSurface& surface) {
    RenderSurface out;
    out.fell_back = true;
    for (size_t t = 0; t < surface.triangles.size(); ++t) {
        const Tri& tri = surface.triangles[t];
        const Vec3 &a = surface.vertices[tri[0]], &b = surface.vertices[tri[1]], &c = surface.vertices[tri[2]];
        Vec3 n = (b - a).cross(c - a);
        n = n.norm() > 0 ? Vec3(n.normalized()) : Vec3(0, 1, 0);
        const uint32_t base = static_cast<uint32_t>(out.vertices.size());
        for (const Vec3* p : {&a, &b, &c}) {
            out.vertices.push_back(*p);
            out.normals.push_back(n);
        }
        out.triangles.push_back({base, base + 1, base + 2});
        out.kinds.push_back(surface.kinds[t]);
    }
    return out;
}

std::vector<Vec3> corner_normals(const TriangleMesh& mesh, double crease_degrees) {
    const size_t nt = mesh.triangles.size();
    std::vector<Vec3> face(nt);  // area-weighted (length = 2 area)
    std::vector<std::vector<uint32_t>> around(mesh.vertices.size());
    for (size_t t = 0; t < nt; ++t) {
        const Tri& tri = mesh.triangles[t];
        face[t] = (mesh.vertices[tri[1]] - mesh.vertices[tri[0]]).cross(mesh.vertices[tri[2]] - mesh.vertices[tri[0]]);
        for (uint32_t v : tri) around[v].push_back(static_cast<uint32_t>(t));
    }
    const double cos_crease = std::cos(crease_degrees * M_PI / 180);
    std::vector<Vec3> out(3 * nt, Vec3(0, 1, 0));
    for (size_t t = 0; t < nt; ++t) {
        const double len = face[t].norm();
        const Vec3 own = len > 0 ? Vec3(face[t] / len) : Vec3(0, 1, 0);
        for (int k = 0; k < 3; ++k) {
            Vec3 sum = Vec3::Zero();
            for (uint32_t u : around[mesh.triangles[t][k]]) {
                const double lu = face[u].norm();
                if (lu > 0 && face[u].dot(own) >= cos_crease * lu) sum += face[u];
            }
            out[3 * t + k] = sum.norm() > 0 ? Vec3(sum.normalized()) : own;
        }
    }
    return out;
}

}  // namespace shatter
