// seeds = "points": the seed tets the shot names by points ([prescore] seed_points).
//
// Each point (the model's frame, unit: m) picks the tet that holds it; a point in no tet (on the
// surface, in a hollow's cavity, a little outside) picks the tet whose centroid is nearest, if
// that is within `reach` (a tet's size) of the point, and is refused otherwise. The pieces then grow
// from those tets by the round-robin flood fill (prescore/partition.h): one piece per point.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "core/geometry.h"

namespace shatter {

// The seed tet of each point, in the points' order. Throws Error(BadInput) naming `where`
// ("FILE:LINE" of seed_points, or the flag), the point's index and value, for a point farther
// than `reach` (unit: m) from every tet, or two points in one tet.
std::vector<uint32_t> seed_tets_of_points(const TetMesh& mesh, const std::vector<std::array<double, 3>>& points,
                                          double reach, const std::string& where);

}  // namespace shatter
