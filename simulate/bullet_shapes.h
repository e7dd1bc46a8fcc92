// The rigid-body side of a piece in Bullet: its principal frame and its convex parts.
#pragma once

#include <btBulletDynamicsCommon.h>

#include "core/model.h"

namespace shatter {

// The margin of a piece's convex parts: small against the piece (Bullet's default 4 cm would
// swallow a 5 cm piece), bounded for GJK's sake.
double collision_margin(double volume);

// A convex part in body coordinates, shrunk by the margin so that hull + margin is the part.
btConvexHullShape* make_part(const ConvexPart& part, const Mat3& principal, const Vec3& center, double margin);

// Principal frame of an inertia tensor: a right-handed rotation R (columns = axes) and the
// principal moments, I = R diag(moments) R^T.
void principal_frame(const Mat3& inertia, Mat3* r, Vec3* moments);

}  // namespace shatter
