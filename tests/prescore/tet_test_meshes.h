// Tet meshes built in code for the prescore tests: structured grids of cubes (each split into
// the 6 tets of the Kuhn subdivision, which conform across cells) and spherical shells (a
// subdivided icosahedron extruded into radial layers, each prism split into 3 tets so that
// neighbouring prisms agree on their shared quads).
#pragma once

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <sstream>
#include <string>
#include <utility>

#include "core/geometry.h"

namespace shatter::test {

// Puts tet t in positive orientation by swapping two vertices if needed.
inline void orient(const TetMesh& mesh, Tet& t) {
    if (tet_volume(mesh.vertices[t[0]], mesh.vertices[t[1]], mesh.vertices[t[2]], mesh.vertices[t[3]]) < 0) {
        std::swap(t[2], t[3]);
    }
}

// Removes vertices no tet uses, keeping the order of the rest.
inline void compact(TetMesh& mesh) {
    std::vector<uint32_t> remap(mesh.vertices.size(), UINT32_MAX);
    for (const Tet& t : mesh.tets)
        for (uint32_t v : t) remap[v] = 0;
    std::vector<Vec3> kept;
    for (size_t v = 0; v < mesh.vertices.size(); ++v) {
        if (remap[v] == UINT32_MAX) continue;
        remap[v] = uint32_t(kept.size());
        kept.push_back(mesh.vertices[v]);
    }
    for (Tet& t : mesh.tets)
        for (uint32_t& v : t) v = remap[v];
    mesh.vertices = std::move(kept);
}

// Grid of nx*ny*nz cubes of side h from `origin`; only cells where keep(i, j, k) is true.
inline TetMesh cube_grid(int nx, int ny, int nz, double h, const Vec3& origin = Vec3::Zero(),
                         const std::function<bool(int, int, int)>& keep = nullptr) {
    TetMesh mesh;
    auto index = [&](int i, int j, int k) { return uint32_t((k * (ny + 1) + j) * (nx + 1) + i); };
    for (int k = 0; k <= nz; ++k)
        for (int j = 0; j <= ny; ++j)
            for (int i = 0; i <= nx; ++i) mesh.vertices.push_back(origin + h * Vec3(i, j, k));
    static const int perms[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
    for (int k = 0; k < nz; ++k)
        for (int j = 0; j < ny; ++j)
            for (int i = 0; i < nx; ++i) {
                if (keep && !keep(i, j, k)) continue;
                for (const auto& p : perms) {  // path from corner (0,0,0) to (1,1,1), one axis at a time
                    int c[3] = {i, j, k};
                    Tet t;
                    t[0] = index(c[0], c[1], c[2]);
                    for (int s = 0; s < 3; ++s) {
                        ++c[p[s]];
                        t[s + 1] = index(c[0], c[1], c[2]);
                    }
                    orient(mesh, t);
                    mesh.tets.push_back(t);
                }
            }
    compact(mesh);
    return mesh;
}

// Appends b to a (no shared vertices).
inline void append(TetMesh& a, const TetMesh& b) {
    const auto offset = uint32_t(a.vertices.size());
    a.vertices.insert(a.vertices.end(), b.vertices.begin(), b.vertices.end());
    for (Tet t : b.tets) {
        for (uint32_t& v : t) v += offset;
        a.tets.push_back(t);
    }
}

// Icosahedron subdivided `levels` times, projected on the unit sphere.
inline TriangleMesh icosphere(int levels) {
    const double g = (1 + std::sqrt(5.0)) / 2;
    TriangleMesh m;
    m.vertices = {{-1, g, 0}, {1, g, 0}, {-1, -g, 0}, {1, -g, 0}, {0, -1, g}, {0, 1, g},
                  {0, -1, -g}, {0, 1, -g}, {g, 0, -1}, {g, 0, 1}, {-g, 0, -1}, {-g, 0, 1}};
    for (Vec3& v : m.vertices) v.normalize();
    m.triangles = {{0, 11, 5}, {0, 5, 1}, {0, 1, 7},   {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
                   {11, 10, 2}, {10, 7, 6}, {7, 1, 8}, {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
                   {3, 8, 9},  {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
    for (int l = 0; l < levels; ++l) {
        std::map<std::pair<uint32_t, uint32_t>, uint32_t> mid;
        auto midpoint = [&](uint32_t a, uint32_t b) {
            auto key = std::minmax(a, b);
            auto it = mid.find(key);
            if (it != mid.end()) return it->second;
            m.vertices.push_back((m.vertices[a] + m.vertices[b]).normalized());
            return mid[key] = uint32_t(m.vertices.size() - 1);
        };
        std::vector<Tri> next;
        for (const Tri& t : m.triangles) {
            const uint32_t ab = midpoint(t[0], t[1]), bc = midpoint(t[1], t[2]), ca = midpoint(t[2], t[0]);
            next.push_back({t[0], ab, ca});
            next.push_back({t[1], bc, ab});
            next.push_back({t[2], ca, bc});
            next.push_back({ab, bc, ca});
        }
        m.triangles = std::move(next);
    }
    return m;
}

// The mesh as OBJ text (17 digits: the file reads back the same doubles).
inline std::string obj_text(const TriangleMesh& m) {
    std::ostringstream out;
    out.precision(17);
    for (const Vec3& v : m.vertices) out << "v " << v.x() << ' ' << v.y() << ' ' << v.z() << '\n';
    for (const Tri& t : m.triangles) out << "f " << t[0] + 1 << ' ' << t[1] + 1 << ' ' << t[2] + 1 << '\n';
    return out.str();
}

// Spherical shell between radii r_in and r_out (centred at `centre`), `layers` radial layers.
inline TetMesh spherical_shell(double r_out, double r_in, int levels, int layers, const Vec3& centre = Vec3::Zero()) {
    const TriangleMesh sphere = icosphere(levels);
    const auto nv = uint32_t(sphere.vertices.size());
    TetMesh mesh;
    for (int l = 0; l <= layers; ++l) {
        const double r = r_in + (r_out - r_in) * l / layers;
        for (const Vec3& v : sphere.vertices) mesh.vertices.push_back(centre + r * v);
    }
    for (int l = 0; l < layers; ++l) {
        for (Tri t : sphere.triangles) {
            std::sort(t.begin(), t.end());  // quads split from the lower to the higher index
            const uint32_t a = l * nv + t[0], b = l * nv + t[1], c = l * nv + t[2];
            const uint32_t A = a + nv, B = b + nv, C = c + nv;
            for (Tet tet : {Tet{a, b, c, C}, Tet{a, b, B, C}, Tet{a, A, B, C}}) {
                orient(mesh, tet);
                mesh.tets.push_back(tet);
            }
        }
    }
    return mesh;
}

// Total volume of a tet mesh (m^3).
inline double total_volume(const TetMesh& mesh) {
    double v = 0;
    for (const Tet& t : mesh.tets)
        v += tet_volume(mesh.vertices[t[0]], mesh.vertices[t[1]], mesh.vertices[t[2]], mesh.vertices[t[3]]);
    return v;
}

// All tet indices 0..n-1.
inline std::vector<uint32_t> all_tets(const TetMesh& mesh) {
    std::vector<uint32_t> t(mesh.tets.size());
    for (size_t i = 0; i < t.size(); ++i) t[i] = uint32_t(i);
    return t;
}

}  // namespace shatter::test
