// PieceSolver (simulate/bullet_solver.h) skips work in Bullet's solver that point constraints do
// not need; it must give the same bytes as Bullet's own solver: two worlds stepped side by side,
// one per solver, with joints that bend, carry contacts and break by Bullet's impulse threshold.
#include <gtest/gtest.h>

#include <btBulletDynamicsCommon.h>

#include <memory>
#include <vector>

#include "simulate/bullet_solver.h"
#include "simulate/compliant_constraint.h"
#include "support/bullet_twins.h"

namespace shatter {
namespace {

// Six 4 cm boxes in a row, joined by four compliant point constraints per shared face, dropped
// tilted onto the ground so that one end lands first: contacts, bending, and (at the weakest
// threshold) breaks.
struct Rig {
    btDefaultCollisionConfiguration config;
    btCollisionDispatcher dispatcher{&config};
    btDbvtBroadphase broadphase;
    std::unique_ptr<btSequentialImpulseConstraintSolver> solver;
    std::unique_ptr<btDiscreteDynamicsWorld> world;
    btStaticPlaneShape ground_shape{btVector3(0, 1, 0), 0};
    btBoxShape box_shape{btVector3(0.02, 0.02, 0.02)};
    testing_support::Bodies bodies;
    std::vector<std::unique_ptr<CompliantPointConstraint>> joints;

    explicit Rig(std::unique_ptr<btSequentialImpulseConstraintSolver> s) : solver(std::move(s)) {
        world = std::make_unique<btDiscreteDynamicsWorld>(&dispatcher, &broadphase, solver.get(), &config);
        world->setGravity(btVector3(0, -9.81, 0));
        world->getSolverInfo().m_numIterations = 30;
        add(0, &ground_shape, btTransform::getIdentity());
        const btQuaternion tilt(btVector3(0, 0, 1), 0.3);
        for (int i = 0; i < 6; ++i) {
            const btVector3 centre = btVector3(0, 0.2, 0) + quatRotate(tilt, btVector3(0.04 * i, 0, 0));
            btRigidBody* b = add(0.064, &box_shape, btTransform(tilt, centre));
            b->setActivationState(DISABLE_DEACTIVATION);
            if (i == 0) continue;
            btRigidBody* a = bodies[bodies.size() - 2].get();
            for (double y : {-0.01, 0.01})
                for (double z : {-0.01, 0.01}) {
                    joints.push_back(std::make_unique<CompliantPointConstraint>(
                        *a, *b, btVector3(0.02, y, z), btVector3(-0.02, y, z), 2e5, 5, 1.0 / 480));
                    joints.back()->setBreakingImpulseThreshold(i == 3 ? 0.004 : 1e30);
                    world->addConstraint(joints.back().get(), true);
                }
        }
    }
    btRigidBody* add(double mass, btCollisionShape* shape, const btTransform& t) {
        return testing_support::add_body(*world, bodies, mass, shape, t);
    }
    ~Rig() {
        for (auto& j : joints) world->removeConstraint(j.get());
        for (auto& b : bodies) world->removeRigidBody(b.get());
    }
};

using testing_support::same_bytes;

bool same_bytes(const btJointFeedback& a, const btJointFeedback& b) {
    return same_bytes(a.m_appliedForceBodyA, b.m_appliedForceBodyA) &&
           same_bytes(a.m_appliedTorqueBodyA, b.m_appliedTorqueBodyA) &&
           same_bytes(a.m_appliedForceBodyB, b.m_appliedForceBodyB) &&
           same_bytes(a.m_appliedTorqueBodyB, b.m_appliedTorqueBodyB);
}

TEST(PieceSolver, StepsToTheSameBytesAsBulletsOwnSolver) {
    Rig bullet(std::make_unique<btSequentialImpulseConstraintSolver>());
    Rig ours(std::make_unique<PieceSolver>());
    int contacts = 0, broken = 0;
    for (int step = 0; step < 240; ++step) {
        bullet.world->stepSimulation(1.0 / 480, 0, 1.0 / 480);
        ours.world->stepSimulation(1.0 / 480, 0, 1.0 / 480);
        contacts += bullet.dispatcher.getNumManifolds() > 0;
        ASSERT_TRUE(testing_support::same_bodies(bullet.bodies, ours.bodies)) << "step " << step;
        for (size_t j = 0; j < bullet.joints.size(); ++j) {
            const btJointFeedback& a = bullet.joints[j]->feedback();
            const btJointFeedback& b = ours.joints[j]->feedback();
            ASSERT_TRUE(same_bytes(a, b)) << "joint " << j << " step " << step;
            ASSERT_EQ(bullet.joints[j]->isEnabled(), ours.joints[j]->isEnabled()) << "joint " << j << " step " << step;
            ASSERT_EQ(bullet.joints[j]->getAppliedImpulse(), ours.joints[j]->getAppliedImpulse());
        }
    }
    for (const auto& j : bullet.joints) broken += !j->isEnabled();
    // The rig did what it is for: it touched the ground, and the weak face's joints broke.
    EXPECT_GT(contacts, 10);
    EXPECT_EQ(broken, 4);
}

}  // namespace
}  // namespace shatter
