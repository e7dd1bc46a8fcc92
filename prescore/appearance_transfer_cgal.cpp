// The input's appearance on the render surfaces: nearest input triangles by a CGAL AABB tree
// (Simple_cartesian<double>). Design notes: appearance_transfer.h.
#include "prescore/appearance_transfer.h"

#include <map>
#include <tuple>

#include "prescore/triangle_tree_cgal.h"

namespace shatter {

namespace {

// How far outside its triangle a corner may lie and still take that triangle's attributes
// extrapolated (a weight down to -kReach): a render triangle is cut from the surface prescore
// tetrahedralized, which need not be split where the input's triangles are, so one render
// triangle may span two input triangles of one chart, where extrapolating across their shared
// edge is exact on a flat face and close on a curved one. Beyond, the corner takes the input
// triangle nearest to itself.
constexpr double kReach = 1.0;

void paint(RenderSurface& rs, const Appearance& look, const std::vector<TreeTriangle>& triangles,
           const TriangleTree& tree) {
    const bool has_uv = !look.uv.empty(), has_colour = !look.colour.empty();
    using Key = std::tuple<uint32_t, float, float, float, float, float, float>;
    std::map<Key, uint32_t> index;
    RenderSurface out;
    out.kinds = rs.kinds;
    out.fell_back = rs.fell_back;
    out.triangles.resize(rs.triangles.size());
    out.material.resize(rs.triangles.size());
    for (size_t t = 0; t < rs.triangles.size(); ++t) {
        const Tri& tri = rs.triangles[t];
        const Vec3 centre = (rs.vertices[tri[0]] + rs.vertices[tri[1]] + rs.vertices[tri[2]]) / 3;
        const size_t j = size_t(tree.closest_point_and_primitive(tree_point(centre)).second - triangles.cbegin());
        const Tri& src = look.mesh.triangles[j];
        out.material[t] = look.material[j];
        const bool outer = rs.kinds[t] == FaceKind::Outer;
        for (int k = 0; k < 3; ++k) {
            const uint32_t v = tri[size_t(k)];
            std::array<float, 2> uv = {0, 0};
            std::array<float, 4> colour = {1, 1, 1, 1};
            if (outer && (has_uv || has_colour)) {
                const auto& x = look.mesh.vertices;
                const Tri* from = &src;
                Vec3 w = barycentric(rs.vertices[v], x[src[0]], x[src[1]], x[src[2]]);
                if (w.minCoeff() < -kReach) {
                    from = &look.mesh.triangles[size_t(tree.closest_point_and_primitive(tree_point(rs.vertices[v])).second -
                                                       triangles.cbegin())];
                    w = clamped(barycentric(rs.vertices[v], x[(*from)[0]], x[(*from)[1]], x[(*from)[2]]));
                }
                const Tri& src = *from;
                if (has_uv)
                    for (int i = 0; i < 2; ++i)
                        uv[size_t(i)] = float(w[0] * look.uv[src[0]][size_t(i)] + w[1] * look.uv[src[1]][size_t(i)] +
                                              w[2] * look.uv[src[2]][size_t(i)]);
                if (has_colour)
                    for (int i = 0; i < 4; ++i)
                        colour[size_t(i)] = float(w[0] * look.colour[src[0]][size_t(i)] +
                                                  w[1] * look.colour[src[1]][size_t(i)] +
                                                  w[2] * look.colour[src[2]][size_t(i)]);
            }
            const Key key{v, uv[0], uv[1], colour[0], colour[1], colour[2], colour[3]};
            auto [it, fresh] = index.emplace(key, uint32_t(out.vertices.size()));
            if (fresh) {
                out.vertices.push_back(rs.vertices[v]);
                out.normals.push_back(rs.normals[v]);
                if (has_uv) out.uv.push_back(uv);
                if (has_colour) out.colour.push_back(colour);
            }
            out.triangles[t][size_t(k)] = it->second;
        }
    }
    rs = std::move(out);
}

}  // namespace

void transfer_appearance(Model& model, const Appearance& look) {
    model.materials = look.materials;
    if (look.mesh.triangles.empty()) return;
    std::vector<TreeTriangle> triangles;
    triangles.reserve(look.mesh.triangles.size());
    for (const Tri& t : look.mesh.triangles)
        triangles.emplace_back(tree_point(look.mesh.vertices[t[0]]), tree_point(look.mesh.vertices[t[1]]),
                               tree_point(look.mesh.vertices[t[2]]));
    TriangleTree tree(triangles.cbegin(), triangles.cend());
    tree.accelerate_distance_queries();
    for (Piece& piece : model.pieces)
        if (piece.render) paint(*piece.render, look, triangles, tree);
}

}  // namespace shatter
