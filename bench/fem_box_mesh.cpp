// Box tet meshes from hexahedra split into 6 Kuhn tets (bench/fem_box_mesh.h).
#include "bench/fem_box_mesh.h"

#include <algorithm>
#include <array>

namespace shatter::fem {

TetMesh box_tet_mesh(const Vec3& size, uint32_t n_x, uint32_t n_y, uint32_t n_z) {
    TetMesh m;
    const auto id = [&](uint32_t i, uint32_t j, uint32_t k) { return i + (n_x + 1) * (j + (n_y + 1) * k); };
    m.vertices.reserve(size_t(n_x + 1) * (n_y + 1) * (n_z + 1));
    for (uint32_t k = 0; k <= n_z; ++k)
        for (uint32_t j = 0; j <= n_y; ++j)
            for (uint32_t i = 0; i <= n_x; ++i)
                m.vertices.emplace_back(size.x() * i / n_x, size.y() * j / n_y, size.z() * k / n_z);
    // Corner c of a cell (bits: x, y, z); each Kuhn tet walks from corner 0 to corner 7 along
    // the axes in one of the 6 orders.
    const std::array<std::array<int, 3>, 6> orders = {{{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}}};
    m.tets.reserve(size_t(6) * n_x * n_y * n_z);
    for (uint32_t k = 0; k < n_z; ++k)
        for (uint32_t j = 0; j < n_y; ++j)
            for (uint32_t i = 0; i < n_x; ++i) {
                const auto corner = [&](int c) { return id(i + (c & 1), j + ((c >> 1) & 1), k + ((c >> 2) & 1)); };
                for (const auto& o : orders) {
                    const int c1 = 1 << o[0], c2 = c1 | (1 << o[1]);
                    Tet t = {corner(0), corner(c1), corner(c2), corner(7)};
                    if (tet_volume(m.vertices[t[0]], m.vertices[t[1]], m.vertices[t[2]], m.vertices[t[3]]) < 0)
                        std::swap(t[2], t[3]);
                    m.tets.push_back(t);
                }
            }
    return m;
}

std::vector<uint32_t> select_vertices(const TetMesh& mesh, const std::function<bool(const Vec3&)>& on) {
    std::vector<uint32_t> out;
    for (uint32_t v = 0; v < mesh.vertices.size(); ++v)
        if (on(mesh.vertices[v])) out.push_back(v);
    return out;
}

}  // namespace shatter::fem
