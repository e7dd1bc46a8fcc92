// The triangles render draws, built on the CPU. Shapes and tet surfaces are flat-shaded vertex
// arrays: every triangle has its own three vertices carrying the face normal and the face colour
// (linear RGB). A piece with a render surface (core/model.h) is indexed instead: its vertices
// carry the surface's per-vertex normals (smooth on the outer faces, the face normal on fracture
// and cavity faces, which stay crisp) and are shared by the triangles that use them. Per-vertex
// colour lets one draw call show a piece's outer, fracture and cavity faces in their own shades.
// With [render] colours = "input" and a model with materials (core/model.h), each triangle takes
// its material's colour (times the vertex colour) and, on outer faces of a textured material,
// its texture coordinates; render draws the triangles of each texture apart (IndexedVertices::
// texture) and multiplies the colour by the texture there.
//
// Positions are in the body's own frame: a piece's vertices relative to its centre of mass (the
// trajectory's origin for pieces), shapes about their own origin, so that a body's model matrix
// is exactly its trajectory pose [R | p].
#pragma once

#include <array>
#include <vector>

#include "core/geometry.h"
#include "core/model.h"
#include "core/render_settings.h"

namespace shatter {

struct Vertex {
    float position[3];
    float normal[3];
    float colour[3];  // linear RGB
    float uv[2];      // texture coordinates, GL's: t = 1 - v, so (0, 0) is the first row of the decoded image
};
using Colour = std::array<float, 3>;

// How a model material (Model::materials) is drawn.
struct MaterialLook {
    Colour base = {1, 1, 1};  // linear RGB: its base colour factor
    Colour mean = {1, 1, 1};  // base times its texture's mean colour: the colour its inside is lightened from
    int32_t texture = -1;     // the texture its outer faces sample; -1: none (or not decodable)
};

// The face colours of a piece: outer = base, fracture = interior_colour when set, else base
// mixed toward white by `fracture_tint`, cavity = base times `cavity_shade`.
Colour face_colour(const Colour& base, FaceKind kind, const RenderSettings& s);
// The base colour of piece `id`: its piece_colours entry, else the palette (core/palette.h) or
// the material colour.
Colour piece_base_colour(uint32_t id, const RenderSettings& s);

// Vertices and triangle indices (three per triangle); `indices` in triangle order.
struct IndexedVertices {
    std::vector<Vertex> vertices;
    std::vector<uint32_t> indices;
    std::vector<int32_t> texture;     // per triangle, the MaterialLook::texture it samples; empty: none does
    std::vector<uint32_t> material;   // per triangle, its model material; empty: drawn without materials
};

// The piece's tet surface, flat: three vertices per triangle, in the surface's triangle order.
std::vector<Vertex> piece_vertices(const Piece& piece, uint32_t id, const RenderSettings& s);
// What render draws for a piece: its render surface when it has one (a vertex used by faces of
// two kinds gets a copy per kind, for the colours), else its tet surface (piece_vertices,
// indexed 0, 1, 2, ...). Triangles in the surface's order; positions about the centre of mass.
// With colours = "input", `looks` (one per model material) colours a render surface that has
// materials (a vertex gets a copy per kind and material that uses it).
IndexedVertices piece_mesh(const Piece& piece, uint32_t id, const RenderSettings& s,
                           const std::vector<MaterialLook>& looks = {});
// Whether piece_mesh draws `piece` with its model materials.
bool uses_materials(const Piece& piece, uint32_t id, const RenderSettings& s, const std::vector<MaterialLook>& looks);
// The kind of each triangle of piece_mesh().
const std::vector<FaceKind>& piece_mesh_kinds(const Piece& piece);
std::vector<Vertex> box_vertices(const Vec3& size, const Colour& c);       // full extents, centred
std::vector<Vertex> sphere_vertices(double radius, const Colour& c);        // 48 x 24 segments
std::vector<Vertex> quad_vertices(double half_extent, const Colour& c);     // y = 0, facing +y
// Rectangles [x0, x1] x [z0, z1] of the plane y = 0, facing +y (empty ones are skipped).
void add_rect(std::vector<Vertex>& out, double x0, double z0, double x1, double z1, const Colour& c);
std::vector<Vertex> mesh_vertices(const TriangleMesh& mesh, const Colour& c);

}  // namespace shatter
