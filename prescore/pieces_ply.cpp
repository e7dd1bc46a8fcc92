#include "prescore/pieces_ply.h"

#include <cmath>
#include <optional>

#include <fmt/format.h>

#include "core/binary_io.h"
#include "core/palette.h"
#include "core/render_settings.h"
#include "meshio/image_decode.h"

namespace shatter {

namespace {

// What a piece shows: its render surface when it has one, else its tet surface.
const std::vector<Vec3>& shown_vertices(const Piece& p) { return p.render ? p.render->vertices : p.surface.vertices; }
const std::vector<Tri>& shown_triangles(const Piece& p) { return p.render ? p.render->triangles : p.surface.triangles; }

using Rgb = std::array<float, 3>;  // linear

// How each material colours a vertex (pieces_ply.h): its base colour, its decoded texture, and
// its inside's colour.
struct MaterialColours {
    Rgb base = {1, 1, 1};
    Rgb mean = {1, 1, 1};  // base times the texture's mean
    std::optional<DecodedImage> texture;
};

std::vector<MaterialColours> material_colours(const Model& model) {
    std::vector<MaterialColours> out;
    for (const Material& m : model.materials) {
        MaterialColours c;
        c.base = c.mean = {m.base_colour[0], m.base_colour[1], m.base_colour[2]};
        if (!m.texture.empty()) c.texture = decode_image(m.texture, nullptr);  // render warns when it does not decode
        if (c.texture) {
            const Rgb mean = mean_linear_colour(*c.texture);
            for (int k = 0; k < 3; ++k) c.mean[size_t(k)] *= mean[size_t(k)];
        }
        out.push_back(std::move(c));
    }
    return out;
}

float srgb8_to_linear(uint8_t v) {
    const float c = float(v) / 255.0f;
    return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}

// The colour of every vertex of a render surface with materials: the first triangle that uses a
// vertex decides (outer, fracture and cavity faces do not share vertices).
std::vector<Rgb> vertex_colours(const RenderSurface& rs, const std::vector<MaterialColours>& materials) {
    const RenderSettings look;
    std::vector<Rgb> out(rs.vertices.size(), Rgb{1, 1, 1});
    std::vector<char> done(rs.vertices.size(), 0);
    for (size_t t = 0; t < rs.triangles.size(); ++t) {
        const MaterialColours& m = materials.at(rs.material[t] < materials.size() ? rs.material[t] : 0);
        for (uint32_t v : rs.triangles[t]) {
            if (done[v]) continue;
            done[v] = 1;
            Rgb c = m.base;
            switch (rs.kinds[t]) {
                case FaceKind::Outer:
                    if (m.texture && !rs.uv.empty()) {
                        const uint8_t* texel = m.texture->at(rs.uv[v][0], rs.uv[v][1]);
                        for (int k = 0; k < 3; ++k) c[size_t(k)] *= srgb8_to_linear(texel[k]);
                    }
                    if (!rs.colour.empty())
                        for (int k = 0; k < 3; ++k) c[size_t(k)] *= rs.colour[v][size_t(k)];
                    break;
                case FaceKind::Fracture:
                    c = m.mean;
                    for (float& x : c) x += (1.0f - x) * float(look.fracture_tint);
                    break;
                case FaceKind::Cavity:
                    c = m.mean;
                    for (float& x : c) x *= float(look.cavity_shade);
                    break;
            }
            out[v] = c;
        }
    }
    return out;
}

}  // namespace

std::string pieces_ply(const Model& model) {
    size_t vertices = 0, faces = 0;
    for (const Piece& p : model.pieces) {
        vertices += shown_vertices(p).size();
        faces += shown_triangles(p).size();
    }
    ByteWriter w;
    w.bytes(fmt::format(
        "ply\nformat binary_little_endian 1.0\ncomment shatter pieces: {} pieces, {}\n"
        "element vertex {}\nproperty float x\nproperty float y\nproperty float z\n"
        "property uchar red\nproperty uchar green\nproperty uchar blue\n"
        "element face {}\nproperty list uchar uint vertex_indices\nend_header\n",
        model.pieces.size(), model.materials.empty() ? "one colour each" : "in the input's colours", vertices, faces));
    const std::vector<MaterialColours> materials = material_colours(model);
    for (uint32_t i = 0; i < model.pieces.size(); ++i) {
        const Piece& p = model.pieces[i];
        const bool painted = !materials.empty() && p.render && !p.render->material.empty();
        const std::vector<Rgb> colours = painted ? vertex_colours(*p.render, materials) : std::vector<Rgb>();
        const auto own = piece_colour(i);
        const std::vector<Vec3>& shown = shown_vertices(p);
        for (size_t v = 0; v < shown.size(); ++v) {
            for (int k = 0; k < 3; ++k) w.f32(static_cast<float>(shown[v][k]));
            const Rgb& c = painted ? colours[v] : own;
            for (int k = 0; k < 3; ++k) w.u8(linear_to_srgb8(c[size_t(k)]));
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
