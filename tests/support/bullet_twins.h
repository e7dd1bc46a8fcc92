// Two Bullet worlds stepped side by side, one with a part of shatter's (PieceSolver,
// PieceConvexAlgorithm) and one with Bullet's own, must agree bit for bit: the pieces the
// twin-world tests share.
#pragma once

#include <gtest/gtest.h>

#include <btBulletDynamicsCommon.h>

#include <cstring>
#include <memory>
#include <vector>

namespace shatter::testing_support {

// x, y and z bit for bit (a btVector3's fourth lane is padding).
inline bool same_bytes(const btVector3& a, const btVector3& b) {
    return std::memcmp(a.m_floats, b.m_floats, 3 * sizeof(btScalar)) == 0;
}
inline bool same_bytes(const btTransform& a, const btTransform& b) {
    for (int r = 0; r < 3; ++r)
        if (!same_bytes(a.getBasis()[r], b.getBasis()[r])) return false;
    return same_bytes(a.getOrigin(), b.getOrigin());
}

using Bodies = std::vector<std::unique_ptr<btRigidBody>>;

// A rigid body of `mass` (0: static) with friction 0.5 at `t`, added to `world` and kept in `bodies`.
inline btRigidBody* add_body(btDynamicsWorld& world, Bodies& bodies, double mass, btCollisionShape* shape,
                             const btTransform& t) {
    btVector3 inertia(0, 0, 0);
    if (mass > 0) shape->calculateLocalInertia(mass, inertia);
    btRigidBody::btRigidBodyConstructionInfo info(mass, nullptr, shape, inertia);
    info.m_startWorldTransform = t;
    info.m_friction = 0.5;
    bodies.push_back(std::make_unique<btRigidBody>(info));
    world.addRigidBody(bodies.back().get());
    return bodies.back().get();
}

// Every body's transform and velocities the same bytes in both worlds; else the first body that
// differs, and in what.
inline ::testing::AssertionResult same_bodies(const Bodies& a, const Bodies& b) {
    for (size_t i = 0; i < a.size(); ++i) {
        if (!same_bytes(a[i]->getWorldTransform(), b[i]->getWorldTransform()))
            return ::testing::AssertionFailure() << "body " << i << ": transform";
        if (!same_bytes(a[i]->getLinearVelocity(), b[i]->getLinearVelocity()))
            return ::testing::AssertionFailure() << "body " << i << ": linear velocity";
        if (!same_bytes(a[i]->getAngularVelocity(), b[i]->getAngularVelocity()))
            return ::testing::AssertionFailure() << "body " << i << ": angular velocity";
    }
    return ::testing::AssertionSuccess();
}

}  // namespace shatter::testing_support
