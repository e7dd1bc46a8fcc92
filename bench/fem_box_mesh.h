// A box as a tet mesh for the continuum reference's checks (bench/fem_solid.h): n_x x n_y x n_z
// hexahedra, each split into the 6 tets of its Kuhn (Freudenthal) triangulation, which all share
// the cube's main diagonal. Every hexahedron is split the same way, so neighbouring tets meet face
// to face and refining the grid refines the mesh uniformly (the linear-tet error falls as the
// square of the cell size; Zienkiewicz & Taylor, "The Finite Element Method", vol. 1, ch. 9).
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include "core/geometry.h"

namespace shatter::fem {

// The box [0, size.x] x [0, size.y] x [0, size.z] (unit: m) cut into cells^3 hexahedra of 6 tets.
// Vertex (i, j, k) is vertices[i + (n_x + 1) (j + (n_y + 1) k)].
TetMesh box_tet_mesh(const Vec3& size, uint32_t n_x, uint32_t n_y, uint32_t n_z);

// The vertices for which `on` holds (e.g. those on the face x = 0), ascending.
std::vector<uint32_t> select_vertices(const TetMesh& mesh, const std::function<bool(const Vec3&)>& on);

}  // namespace shatter::fem
