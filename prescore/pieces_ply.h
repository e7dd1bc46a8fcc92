// The pieces as one binary PLY (little-endian), with vertex colours, for a quick look in MeshLab
// or Blender. Vertices stay in the model frame (metres). Each piece's render surface when it has
// one (core/model.h), else its tet surface. Colours: one per piece (the palette), or, when the
// model has the input's materials, render's default colours per vertex: on outer faces the
// material's base colour times the vertex colour times the texture's texel at the vertex's UV
// (nearest texel: a vertex colour samples the texture once, so detail finer than the triangles
// is lost), on fracture faces the material's mean colour lightened by the default fracture
// tint, on cavity faces darkened by the default cavity shade.
#pragma once

#include <string>

#include "core/model.h"

namespace shatter {

std::string pieces_ply(const Model& model);

}  // namespace shatter
