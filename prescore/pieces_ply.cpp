#include "prescore/pieces_ply.h"

#include <fmt/format.h>

#include "core/binary_io.h"
#include "core/palette.h"

namespace shatter {

namespace {

// What a piece shows: its render surface when it has one, else its tet surface.
const std::vector<Vec3>& shown_vertices(const Piece& p) { return p.render ? p.render->vertices : p.surface.vertices; }
const std::vector<Tri>& shown_triangles(const Piece& p) { return p.render ? p.render->triangles : p.surface.triangles; }

}  // namespace

std::string pieces_ply(const Model& model) {
    size_t vertices = 0, faces = 0;
    for (const Piece& p : model.pieces) {
        vertices += shown_vertices(p).size();
        faces += shown_triangles(p).size();
    }
    ByteWriter w;
    w.bytes(fmt::format(
        "ply\nformat binary_little_endian 1.0\ncomment shatter pieces: {} pieces, one colour each\n"
        "element vertex {}\nproperty float x\nproperty float y\nproperty float z\n"
        "property uchar red\nproperty uchar green\nproperty uchar blue\n"
        "element face {}\nproperty list uchar uint vertex_indices\nend_header\n",
        model.pieces.size(), vertices, faces));
    for (uint32_t i = 0; i < model.pieces.size(); ++i) {
        const auto c = piece_colour(i);
        for (const Vec3& v : shown_vertices(model.pieces[i])) {
            for (int k = 0; k < 3; ++k) w.f32(static_cast<float>(v[k]));
            for (int k = 0; k < 3; ++k) w.u8(linear_to_srgb8(c[k]));
        }
    }
    uint32_t base = 0;
    for (const Piece& p : model.pieces) {
        for (const Tri& t : shown_triangles(p)) {
            w.u8(3);
            for (uint32_t v : t) w.u32(base + v);
        }
        base += static_cast<uint32_t>(shown_vertices(p).size());
    }
    return std::move(w.data());
}

}  // namespace shatter
