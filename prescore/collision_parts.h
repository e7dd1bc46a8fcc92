// A piece's collision shape: a compound of a few convex parts that follows its real shape.
//
// A piece collides as the union of convex hulls of groups of its tets. One hull of all tets is
// wrong for non-convex pieces (a hollow shell piece would collide as if filled), so the tets are
// split top-down, like a BVH build:
//   start with one part = all tets;
//   while some part's mean gap (hull_volume - volume) / hull_area, the average depth of the empty
//   space between the hull and the real shape, exceeds max_gap, and there are fewer than
//   max_parts parts: take the part with the largest excess volume (hull_volume - volume), split
//   its tets at the median centroid along an axis, keep both halves.
// A length, not a volume ratio: a thin curved shell is fine when its hull strays little from it,
// although the hull's volume may be twice the shell's; and contact points are then off the real
// surface by about max_gap at most on average.
// The axis is the one of {x, y, z, principal axis of the centroids} whose split gives the smallest
// total hull volume. Ties go to the earlier candidate and tet order breaks median ties, so the
// result is deterministic. We stop as soon as every part is tight: as few parts as keep the shape.
#pragma once

#include <cstdint>
#include <vector>

#include "core/geometry.h"
#include "core/model.h"

namespace shatter {

struct CollisionSettings {
    double max_gap = 0.0;      // most mean gap between a part's hull and its tets (unit: m, >= 0)
    uint32_t max_parts = 16;   // most convex parts per piece (unit: count, >= 1)
};

// The convex parts of the tets `tets` of `mesh`. Input Error when a setting is out of range
// (max_gap finite and >= 0, max_parts >= 1).
std::vector<ConvexPart> collision_parts(const TetMesh& mesh, const std::vector<uint32_t>& tets,
                                        const CollisionSettings& settings);

}  // namespace shatter
