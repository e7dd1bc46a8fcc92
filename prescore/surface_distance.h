// Which points lie within a distance of a triangle surface (a CGAL AABB tree; the
// implementation is in surface_distance_cgal.cpp, its own translation unit because CGAL is
// costly to compile).
#pragma once

#include <vector>

#include "core/geometry.h"

namespace shatter {

// For each of `points`: 1 when some triangle of `surface` comes within `radius` (m) of it,
// else 0. Asks "is any triangle inside the ball", which stops at the first hit and skips far
// points near the tree's root, several times faster than computing distances.
std::vector<char> within_distance(const TriangleMesh& surface, const std::vector<Vec3>& points, double radius);

}  // namespace shatter
