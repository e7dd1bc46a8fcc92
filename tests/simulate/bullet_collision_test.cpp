// PieceConvexAlgorithm (simulate/bullet_collision.h) skips GJK for pairs of hulls it can prove
// apart, and the near callback skips such pairs and linked ones before touching the bodies; they
// must find the same contacts as Bullet's btConvexConvexAlgorithm and needsCollision: two worlds
// stepped side by side, one with the skips and one without, with a heap of irregular spinning
// hulls thrown together so that pairs come near, touch, rest and part again, some of them linked
// by constraints that break.
#include <gtest/gtest.h>

#include <btBulletDynamicsCommon.h>

#include <cstdint>
#include <memory>
#include <vector>

#include "simulate/bullet_collision.h"
#include "support/bullet_twins.h"

namespace shatter {
namespace {

// A 3 x 3 x 3 heap of 2 cm hulls of 12 random points each, 3 mm apart, each with its own spin
// and a velocity towards the heap's centre, above the ground.
struct Rig {
    btDefaultCollisionConfiguration config;
    std::unique_ptr<PieceDispatcher> dispatcher;
    btDbvtBroadphase broadphase;
    btSequentialImpulseConstraintSolver solver;
    std::unique_ptr<PieceWorld> world;
    btStaticPlaneShape ground_shape{btVector3(0, 1, 0), 0};
    std::vector<std::unique_ptr<btConvexHullShape>> shapes;
    testing_support::Bodies bodies;
    std::vector<std::unique_ptr<btPoint2PointConstraint>> joints;

    explicit Rig(bool skip) {
        dispatcher = std::make_unique<PieceDispatcher>(&config, skip);
        dispatcher->setNearCallback(exact_aabb_near_callback);
        world = std::make_unique<PieceWorld>(dispatcher.get(), &broadphase, &solver, &config);
        world->setGravity(btVector3(0, -9.81, 0));
        add(0, &ground_shape, btTransform::getIdentity());
        uint64_t seed = 12345;
        auto next = [&seed] {  // in [-1, 1)
            seed = seed * 6364136223846793005ull + 1442695040888963407ull;
            return double(seed >> 11) / double(1ull << 52) - 1.0;
        };
        for (int i = 0; i < 27; ++i) {
            shapes.push_back(std::make_unique<btConvexHullShape>());
            for (int p = 0; p < 12; ++p) shapes.back()->addPoint(btVector3(0.01 * next(), 0.01 * next(), 0.01 * next()));
            shapes.back()->setMargin(0.0005);
            const btVector3 at(0.023 * (i % 3 - 1), 0.05 + 0.023 * (i / 3 % 3), 0.023 * (i / 9 - 1));
            btRigidBody* b = add(0.01, shapes.back().get(), btTransform(btQuaternion(next(), next(), next()), at));
            b->setLinearVelocity(btVector3(0, 0.05, 0) - at * 2 + btVector3(next(), next(), next()) * 0.05);
            b->setAngularVelocity(btVector3(next(), next(), next()) * 60);
            b->setActivationState(DISABLE_DEACTIVATION);
        }
        for (int i = 0; i + 1 < 27; i += 3) {  // pairs of neighbours in a row, linked at their midpoint
            btRigidBody& a = *bodies[size_t(i) + 1];
            btRigidBody& b = *bodies[size_t(i) + 2];
            const btVector3 mid = 0.5 * (a.getWorldTransform().getOrigin() + b.getWorldTransform().getOrigin());
            joints.push_back(std::make_unique<btPoint2PointConstraint>(a, b, a.getWorldTransform().inverse() * mid,
                                                                       b.getWorldTransform().inverse() * mid));
            world->addConstraint(joints.back().get(), true);
        }
    }
    btRigidBody* add(double mass, btCollisionShape* shape, const btTransform& t) {
        return testing_support::add_body(*world, bodies, mass, shape, t);
    }
    ~Rig() {
        for (auto& j : joints)
            if (j) world->removeConstraint(j.get());
        for (auto& b : bodies) world->removeRigidBody(b.get());
    }
};


TEST(PieceConvexAlgorithm, FindsTheSameContactsAsBulletsOwn) {
    Rig bullet(false), ours(true);
    int apart = 0, touching = 0;  // pairs (summed over steps) with an empty manifold, with points
    for (int step = 0; step < 480; ++step) {
        if (step % 40 == 20 && !bullet.joints.empty()) {  // a link breaks: its pair collides again
            for (Rig* r : {&bullet, &ours}) {
                r->world->removeConstraint(r->joints.back().get());
                r->joints.pop_back();
            }
        }
        bullet.world->stepSimulation(1.0 / 480, 0, 1.0 / 480);
        ours.world->stepSimulation(1.0 / 480, 0, 1.0 / 480);
        ASSERT_EQ(bullet.dispatcher->getNumManifolds(), ours.dispatcher->getNumManifolds()) << "step " << step;
        for (int m = 0; m < bullet.dispatcher->getNumManifolds(); ++m) {
            const btPersistentManifold* a = bullet.dispatcher->getManifoldByIndexInternal(m);
            const btPersistentManifold* b = ours.dispatcher->getManifoldByIndexInternal(m);
            ASSERT_EQ(a->getNumContacts(), b->getNumContacts()) << "manifold " << m << " step " << step;
            const bool pieces = a->getBody0()->getCollisionShape()->getShapeType() == CONVEX_HULL_SHAPE_PROXYTYPE &&
                                a->getBody1()->getCollisionShape()->getShapeType() == CONVEX_HULL_SHAPE_PROXYTYPE;
            if (pieces) ++(a->getNumContacts() ? touching : apart);
        }
        ASSERT_TRUE(testing_support::same_bodies(bullet.bodies, ours.bodies)) << "step " << step;
    }
    // The heap did what it is for: hulls near one another without touching (the pairs whose GJK
    // the algorithm may skip) and hulls in contact.
    EXPECT_GT(apart, 500);
    EXPECT_GT(touching, 500);
}

}  // namespace
}  // namespace shatter
