#include "render/mesh_builder.h"

#include <cmath>
#include <cstdint>
#include <map>
#include <tuple>

#include "core/palette.h"

namespace shatter {

namespace {

void add_triangle(std::vector<Vertex>& out, const Vec3& a, const Vec3& b, const Vec3& c, const Colour& colour) {
    Vec3 n = (b - a).cross(c - a);
    const double len = n.norm();
    n = len > 0 ? Vec3(n / len) : Vec3(0, 1, 0);
    for (const Vec3* p : {&a, &b, &c}) {
        Vertex v{};
        for (int i = 0; i < 3; ++i) {
            v.position[i] = static_cast<float>((*p)[i]);
            v.normal[i] = static_cast<float>(n[i]);
            v.colour[i] = colour[size_t(i)];
        }
        out.push_back(v);
    }
}

}  // namespace

Colour face_colour(const Colour& base, FaceKind kind, const RenderSettings& s) {
    if (kind == FaceKind::Fracture && s.interior_colour) return *s.interior_colour;
    Colour c = base;
    for (float& v : c) {
        if (kind == FaceKind::Fracture) v += (1.0f - v) * static_cast<float>(s.fracture_tint);
        if (kind == FaceKind::Cavity) v *= static_cast<float>(s.cavity_shade);
    }
    return c;
}

Colour piece_base_colour(uint32_t id, const RenderSettings& s) {
    for (const auto& [piece, colour] : s.piece_colours)
        if (piece == id) return colour;
    return s.colours == Colours::Palette ? piece_colour(id) : s.material_colour;
}

bool uses_materials(const Piece& piece, uint32_t id, const RenderSettings& s, const std::vector<MaterialLook>& looks) {
    if (s.colours != Colours::Input || !piece.render || piece.render->material.empty() || looks.empty()) return false;
    for (const auto& [p, colour] : s.piece_colours)
        if (p == id) return false;
    return true;
}

std::vector<Vertex> piece_vertices(const Piece& piece, uint32_t id, const RenderSettings& s) {
    const PieceSurface& surf = piece.surface;
    const Colour base = piece_base_colour(id, s);
    const Colour by_kind[3] = {face_colour(base, FaceKind::Outer, s), face_colour(base, FaceKind::Fracture, s),
                               face_colour(base, FaceKind::Cavity, s)};
    const Vec3& c = piece.mass.center;
    std::vector<Vertex> out;
    out.reserve(surf.triangles.size() * 3);
    for (size_t t = 0; t < surf.triangles.size(); ++t) {
        const Tri& tri = surf.triangles[t];
        add_triangle(out, surf.vertices[tri[0]] - c, surf.vertices[tri[1]] - c, surf.vertices[tri[2]] - c,
                     by_kind[static_cast<int>(surf.kinds[t]) % 3]);
    }
    return out;
}

namespace {

// A render surface in its materials' colours (piece_mesh with materials).
IndexedVertices material_mesh(const Piece& piece, const RenderSettings& s, const std::vector<MaterialLook>& looks) {
    const RenderSurface& rs = *piece.render;
    const Vec3& c = piece.mass.center;
    IndexedVertices out;
    std::map<std::tuple<uint32_t, int, uint32_t>, uint32_t> copy;  // (vertex, kind, material) -> vertex
    out.indices.reserve(3 * rs.triangles.size());
    out.material = rs.material;
    bool any_texture = false;
    for (size_t t = 0; t < rs.triangles.size(); ++t) {
        const int kind = static_cast<int>(rs.kinds[t]) % 3;
        const uint32_t m = rs.material[t] < looks.size() ? rs.material[t] : 0;
        const MaterialLook& look = looks[m];
        const bool textured = kind == 0 && look.texture >= 0 && !rs.uv.empty();
        out.texture.push_back(textured ? look.texture : -1);
        any_texture = any_texture || textured;
        const Colour colour = kind == 0 ? look.base : face_colour(look.mean, rs.kinds[t], s);
        for (uint32_t v : rs.triangles[t]) {
            auto [it, fresh] = copy.emplace(std::make_tuple(v, kind, m), uint32_t(out.vertices.size()));
            if (fresh) {
                Vertex x{};
                const Vec3 p = rs.vertices[v] - c;
                for (int i = 0; i < 3; ++i) {
                    x.position[i] = static_cast<float>(p[i]);
                    x.normal[i] = static_cast<float>(rs.normals[v][i]);
                    x.colour[i] = colour[size_t(i)] * (kind == 0 && !rs.colour.empty() ? rs.colour[v][size_t(i)] : 1.0f);
                }
                if (textured) x.uv[0] = rs.uv[v][0], x.uv[1] = 1.0f - rs.uv[v][1];
                out.vertices.push_back(x);
            }
            out.indices.push_back(it->second);
        }
    }
    if (!any_texture) out.texture.clear();
    return out;
}

}  // namespace

IndexedVertices piece_mesh(const Piece& piece, uint32_t id, const RenderSettings& s, const std::vector<MaterialLook>& looks) {
    if (uses_materials(piece, id, s, looks)) return material_mesh(piece, s, looks);
    IndexedVertices out;
    if (!piece.render) {
        out.vertices = piece_vertices(piece, id, s);
        out.indices.resize(out.vertices.size());
        for (uint32_t i = 0; i < out.indices.size(); ++i) out.indices[i] = i;
        return out;
    }
    const RenderSurface& rs = *piece.render;
    const Colour base = piece_base_colour(id, s);
    const Colour by_kind[3] = {face_colour(base, FaceKind::Outer, s), face_colour(base, FaceKind::Fracture, s),
                               face_colour(base, FaceKind::Cavity, s)};
    const Vec3& c = piece.mass.center;
    // One copy of a vertex per kind that uses it, made at its first use.
    std::vector<std::array<uint32_t, 3>> copy(rs.vertices.size(), {UINT32_MAX, UINT32_MAX, UINT32_MAX});
    out.vertices.reserve(rs.vertices.size());
    out.indices.reserve(3 * rs.triangles.size());
    for (size_t t = 0; t < rs.triangles.size(); ++t) {
        const int kind = static_cast<int>(rs.kinds[t]) % 3;
        for (uint32_t v : rs.triangles[t]) {
            uint32_t& index = copy[v][size_t(kind)];
            if (index == UINT32_MAX) {
                index = static_cast<uint32_t>(out.vertices.size());
                Vertex x{};
                const Vec3 p = rs.vertices[v] - c;
                for (int i = 0; i < 3; ++i) {
                    x.position[i] = static_cast<float>(p[i]);
                    x.normal[i] = static_cast<float>(rs.normals[v][i]);
                    x.colour[i] = by_kind[kind][size_t(i)];
                }
                out.vertices.push_back(x);
            }
            out.indices.push_back(index);
        }
    }
    return out;
}

const std::vector<FaceKind>& piece_mesh_kinds(const Piece& piece) {
    return piece.render ? piece.render->kinds : piece.surface.kinds;
}

std::vector<Vertex> box_vertices(const Vec3& size, const Colour& c) {
    const Vec3 h = size / 2;
    auto corner = [&](int i) { return Vec3(i & 1 ? h.x() : -h.x(), i & 2 ? h.y() : -h.y(), i & 4 ? h.z() : -h.z()); };
    // Faces as corner indices, counter-clockwise seen from outside.
    static constexpr int kFaces[6][4] = {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4},
                                         {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}};
    std::vector<Vertex> out;
    for (const auto& f : kFaces) {
        add_triangle(out, corner(f[0]), corner(f[1]), corner(f[2]), c);
        add_triangle(out, corner(f[0]), corner(f[2]), corner(f[3]), c);
    }
    return out;
}

std::vector<Vertex> sphere_vertices(double radius, const Colour& c) {
    constexpr int kSlices = 48, kStacks = 24;
    auto point = [&](int i, int j) {
        const double theta = M_PI * j / kStacks, phi = 2 * M_PI * i / kSlices;
        return Vec3(radius * std::sin(theta) * std::cos(phi), radius * std::cos(theta),
                    -radius * std::sin(theta) * std::sin(phi));
    };
    std::vector<Vertex> out;
    for (int j = 0; j < kStacks; ++j)
        for (int i = 0; i < kSlices; ++i) {
            const Vec3 a = point(i, j), b = point(i, j + 1), d = point(i + 1, j), e = point(i + 1, j + 1);
            if (j > 0) add_triangle(out, a, b, d, c);
            if (j < kStacks - 1) add_triangle(out, d, b, e, c);
        }
    // Flat facets show the tessellation; smooth them by using the radial direction as normal.
    for (Vertex& v : out) {
        const double len = std::sqrt(double(v.position[0]) * v.position[0] + double(v.position[1]) * v.position[1] +
                                     double(v.position[2]) * v.position[2]);
        for (int i = 0; i < 3; ++i) v.normal[i] = static_cast<float>(v.position[i] / len);
    }
    return out;
}

void add_rect(std::vector<Vertex>& out, double x0, double z0, double x1, double z1, const Colour& c) {
    if (!(x1 > x0) || !(z1 > z0)) return;
    add_triangle(out, Vec3(x0, 0, z0), Vec3(x0, 0, z1), Vec3(x1, 0, z1), c);
    add_triangle(out, Vec3(x0, 0, z0), Vec3(x1, 0, z1), Vec3(x1, 0, z0), c);
}

std::vector<Vertex> quad_vertices(double e, const Colour& c) {
    std::vector<Vertex> out;
    add_triangle(out, Vec3(-e, 0, -e), Vec3(-e, 0, e), Vec3(e, 0, e), c);
    add_triangle(out, Vec3(-e, 0, -e), Vec3(e, 0, e), Vec3(e, 0, -e), c);
    return out;
}

std::vector<Vertex> mesh_vertices(const TriangleMesh& mesh, const Colour& c) {
    std::vector<Vertex> out;
    out.reserve(mesh.triangles.size() * 3);
    for (const Tri& t : mesh.triangles)
        add_triangle(out, mesh.vertices[t[0]], mesh.vertices[t[1]], mesh.vertices[t[2]], c);
    return out;
}

}  // namespace shatter
