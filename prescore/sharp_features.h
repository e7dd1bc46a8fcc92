// Sharp creases of a closed triangle mesh, as polylines for Mesh_3 to protect.
//
// An edge is sharp when the normals of its two triangles differ by more than `angle` degrees
// (a box's edges: 90). Sharp edges are chained into polylines that end where the chain branches
// or stops (a box corner ends three). Only polylines at least `min_length` long are kept.
// tetrahedralize asks for creases at least as long as a tet (a shorter one cannot be represented
// at that resolution) and at least 10% of the diagonal: scanned meshes are full of short creases
// (the bunny's longest is 8% of its diagonal) that would make Mesh_3 refine to hundreds of
// thousands of tets around them, while the edges of boxes, beams and plates are far longer.
#pragma once

#include <vector>

#include "core/geometry.h"

namespace shatter {

using Polyline = std::vector<Vec3>;

std::vector<Polyline> sharp_polylines(const TriangleMesh& mesh, double angle_degrees, double min_length);

}  // namespace shatter
