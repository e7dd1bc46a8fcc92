// The pieces as one binary PLY (little-endian), one colour per piece as vertex colours, for a
// quick look in MeshLab or Blender. Vertices stay in the model frame (metres). Each piece's
// render surface when it has one (core/model.h), else its tet surface.
#pragma once

#include <string>

#include "core/model.h"

namespace shatter {

std::string pieces_ply(const Model& model);

}  // namespace shatter
