// The input's appearance on the render surfaces (core/model.h RenderSurface::uv, colour,
// material): the one step that joins what meshio/appearance.h read to what the cut made.
//
// Each triangle of a piece's render surface takes the input triangle nearest to its centre (a
// CGAL AABB tree over the input's triangles, in appearance_transfer_cgal.cpp, its own
// translation unit): its material, and on outer faces the texture coordinates and colours of
// that triangle at each corner (barycentric weights of the corner's projection on its plane,
// extrapolated: the surface prescore cut need not be split where the input's triangles are, so
// a render triangle may span two input triangles of one chart; a corner far outside, a weight
// below -1, takes the input triangle nearest to itself instead). One input triangle per render
// triangle keeps a UV seam a seam: a vertex whose triangles land on two sides of it gets a copy
// per side (vertices are split by (vertex, uv, colour)). Fracture and cavity faces take the
// material of the nearest input triangle, with uv (0, 0) and white. Deterministic: triangle
// order, first-use vertex order.
#pragma once

#include "core/model.h"
#include "meshio/appearance.h"

namespace shatter {

// Paints every piece's render surface of `model` with `look` (in the model's frame: scaled as
// the tets were) and sets model.materials to look.materials. Pieces without a render surface are
// left as they are.
void transfer_appearance(Model& model, const Appearance& look);

}  // namespace shatter
