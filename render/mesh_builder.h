// The triangles render draws, built on the CPU as flat-shaded vertex arrays: every triangle has
// its own three vertices carrying the face normal and the face colour (linear RGB). Flat
// shading keeps the tet facets and the fracture faces crisp, and per-vertex colour lets one
// draw call show a piece's outer, fracture and cavity faces in their own shades.
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
};
using Colour = std::array<float, 3>;

// The face colours of a piece: outer = base, fracture = base mixed toward white by
// `fracture_tint`, cavity = base times `cavity_shade`.
Colour face_colour(const Colour& base, FaceKind kind, const RenderSettings& s);
// The base colour of piece `id`: its piece_colours entry, else the palette (core/palette.h) or
// the material colour.
Colour piece_base_colour(uint32_t id, const RenderSettings& s);

std::vector<Vertex> piece_vertices(const Piece& piece, uint32_t id, const RenderSettings& s);
std::vector<Vertex> box_vertices(const Vec3& size, const Colour& c);       // full extents, centred
std::vector<Vertex> sphere_vertices(double radius, const Colour& c);        // 48 x 24 segments
std::vector<Vertex> quad_vertices(double half_extent, const Colour& c);     // y = 0, facing +y
// Rectangles [x0, x1] x [z0, z1] of the plane y = 0, facing +y (empty ones are skipped).
void add_rect(std::vector<Vertex>& out, double x0, double z0, double x1, double z1, const Colour& c);
std::vector<Vertex> mesh_vertices(const TriangleMesh& mesh, const Colour& c);

}  // namespace shatter
