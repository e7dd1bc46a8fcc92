// How rigid bodies joined by point constraints move when struck: the change of every body's
// velocity under given impulses, in the motion their joints allow (each joint's two pivots keep
// the same velocity). Free of any physics engine (Eigen only).
//
// A break's kicks (energized_fracture.h) act on two pieces that are usually still joined to
// others, often stiffly. A kick applied to the two pieces alone moves them as free bodies; the
// joints around them then take the part of that motion they forbid, and an implicit step with
// omega h >> 1 damps it within a step or two. The response here is that kick already passed
// through the joints: the impulse response of the joined bodies with rigid joints,
//
//   M du = j + G^T l,   G du = 0
//
// (M: the bodies' masses and inertias; G: each joint's relative pivot velocity; j: the impulses
// as forces and torques on the bodies' centres), solved as the limit of stiff penalties,
// (M + sum_j kappa_j G_j^T G_j) du = j with kappa_j = 1e8 times the heavier body's mass: six
// unknowns per body, and joints that hold a pair at more points than it needs (three or four per
// shared face) cost nothing, where G M^-1 G^T would be singular. The joints' relative pivot
// velocities come out ~1e-8 of the free ones. A body that is not dynamic (static or driven) does
// not move.
//
// The kinetic energy the response adds to bodies moving with velocities v is
// mu (v^T M du) + mu^2 (du^T M du) / 2 for impulses scaled by mu, where du^T M du = j . du: the
// impulses' work on the velocities they cause.
#pragma once

#include <cstdint>
#include <vector>

#include "core/geometry.h"

namespace shatter {

struct JoinedBody {
    bool dynamic = true;
    double inv_mass = 0;              // (unit: 1/kg)
    Mat3 inv_inertia = Mat3::Zero();  // world frame (unit: 1/(kg m^2))
    Vec3 centre = Vec3::Zero();       // centre of mass, world (unit: m)
};

struct JoinedJoint {
    uint32_t a = 0, b = 0;        // bodies (indices)
    Vec3 pivot = Vec3::Zero();    // world (unit: m)
};

struct BodyImpulse {
    uint32_t body = 0;
    Vec3 point = Vec3::Zero();    // world (unit: m)
    Vec3 impulse = Vec3::Zero();  // (unit: N s)
};

struct VelocityChange {
    Vec3 linear = Vec3::Zero();   // (unit: m/s)
    Vec3 angular = Vec3::Zero();  // (unit: rad/s)
};

// One entry per body, in the bodies' order.
std::vector<VelocityChange> joined_response(const std::vector<JoinedBody>& bodies,
                                            const std::vector<JoinedJoint>& joints,
                                            const std::vector<BodyImpulse>& impulses);

// The same for bodies welded into one rigid body (the limit of joined_response when the joints
// hold every pair rigidly; O(bodies)): nothing moves if any of them is not dynamic.
std::vector<VelocityChange> rigid_response(const std::vector<JoinedBody>& bodies, const std::vector<BodyImpulse>& impulses);

}  // namespace shatter
