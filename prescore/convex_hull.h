// Convex hulls of point sets (CGAL::convex_hull_3 on the Epick kernel; the implementation is in
// convex_hull_cgal.cpp, its own translation unit because CGAL is costly to compile).
#pragma once

#include <vector>

#include "core/geometry.h"

namespace shatter {

// The vertices of the convex hull of `points` (m), sorted lexicographically (x, then y, then z)
// so the order never depends on the input order. `hull_volume`, when not null, receives the
// hull's volume (m^3) and `hull_area` its surface area (m^2); both are 0 when the points do not
// span a solid (fewer than 4 points, or all coplanar), and then all distinct input points are
// returned.
std::vector<Vec3> convex_hull_points(const std::vector<Vec3>& points, double* hull_volume,
                                     double* hull_area = nullptr);

}  // namespace shatter
