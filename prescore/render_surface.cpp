// The light half of render surfaces: flat fallbacks and crease-aware corner normals.
#include "prescore/render_surface.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include <meshoptimizer.h>

namespace shatter {

TriangleMesh reduce_surface(const TriangleMesh& surface, size_t max_triangles) {
    if (surface.triangles.size() <= max_triangles) return surface;
    std::vector<float> positions;
    positions.reserve(3 * surface.vertices.size());
    for (const Vec3& v : surface.vertices)
        for (int k = 0; k < 3; ++k) positions.push_back(float(v[k]));
    std::vector<uint32_t> indices;
    indices.reserve(3 * surface.triangles.size());
    for (const Tri& t : surface.triangles) indices.insert(indices.end(), t.begin(), t.end());
    std::vector<uint32_t> kept(indices.size());
    // No error bound (1 = the whole extent): the count decides.
    kept.resize(meshopt_simplify(kept.data(), indices.data(), indices.size(), positions.data(),
                                 surface.vertices.size(), 3 * sizeof(float), 3 * max_triangles, 1.0f));
    // A collapse can fold two triangles onto each other (the same three vertices, opposite
    // sides): such a fin encloses nothing, and both go. Of triangles on the same three vertices
    // one is kept when more face one way than the other.
    std::vector<std::array<uint32_t, 4>> sorted;  // the three vertices ascending, then the triangle
    for (size_t i = 0; i + 2 < kept.size(); i += 3) {
        std::array<uint32_t, 4> key = {kept[i], kept[i + 1], kept[i + 2], uint32_t(i / 3)};
        std::sort(key.begin(), key.begin() + 3);
        sorted.push_back(key);
    }
    std::sort(sorted.begin(), sorted.end());
    // A triangle's vertices in an even permutation of ascending order face one way, odd the other.
    const auto even = [&](uint32_t t) {
        const uint32_t a = kept[3 * size_t(t)], b = kept[3 * size_t(t) + 1], c = kept[3 * size_t(t) + 2];
        return (a < b) + (b < c) + (c < a) == 2;
    };
    std::vector<char> folded(kept.size() / 3, 0);
    for (size_t i = 0; i < sorted.size();) {
        size_t j = i + 1;
        while (j < sorted.size() && std::equal(sorted[i].begin(), sorted[i].begin() + 3, sorted[j].begin())) ++j;
        if (j - i > 1) {
            int balance = 0;  // even minus odd
            for (size_t k = i; k < j; ++k) {
                folded[sorted[k][3]] = 1;
                balance += even(sorted[k][3]) ? 1 : -1;
            }
            for (size_t k = i; k < j && balance != 0; ++k)
                if (even(sorted[k][3]) == (balance > 0)) {
                    folded[sorted[k][3]] = 0;  // the first of the way more face
                    break;
                }
        }
        i = j;
    }
    TriangleMesh out;
    std::vector<uint32_t> index(surface.vertices.size(), UINT32_MAX);
    for (size_t i = 0; i + 2 < kept.size(); i += 3) {
        if (folded[i / 3]) continue;
        Tri t;
        for (int k = 0; k < 3; ++k) {
            uint32_t& at = index[kept[i + size_t(k)]];
            if (at == UINT32_MAX) {
                at = uint32_t(out.vertices.size());
                out.vertices.push_back(surface.vertices[kept[i + size_t(k)]]);
            }
            t[size_t(k)] = at;
        }
        out.triangles.push_back(t);
    }
    return out;
}

std::optional<TriangleMesh> first_reduction(const TriangleMesh& surface) {
    if (surface.triangles.size() <= kRenderSurfaceSimplifyLimit) return std::nullopt;
    return reduce_surface(surface, kRenderSurfaceReduced);
}

size_t render_surface_triangles(size_t pieces, size_t surface_triangles) {
    const size_t most = std::min(surface_triangles, kRenderSurfaceTriangles);
    const double fits = pieces > 0 ? kRenderSurfaceWork / double(pieces) : double(most);
    if (fits >= double(most)) return most;
    return std::max(size_t(fits), std::min(most, kRenderSurfaceFewest));
}

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
