// The impulse response of joined bodies (simulate/joined_response.h) against what rigid-body
// mechanics predicts for a welded pair, a pinned rod, a free body and a chain.
#include "simulate/joined_response.h"

#include <gtest/gtest.h>

namespace shatter {
namespace {

// A box of mass m and sides (x, y, z) centred at `centre`, axes along the world's.
JoinedBody box(double m, const Vec3& sides, const Vec3& centre) {
    const Vec3 s2 = sides.cwiseProduct(sides);
    const Vec3 inertia = m / 12 * Vec3(s2.y() + s2.z(), s2.x() + s2.z(), s2.x() + s2.y());
    JoinedBody b;
    b.inv_mass = 1 / m;
    b.inv_inertia = inertia.cwiseInverse().asDiagonal();
    b.centre = centre;
    return b;
}

Vec3 point_velocity(const VelocityChange& v, const JoinedBody& b, const Vec3& p) {
    return v.linear + v.angular.cross(p - b.centre);
}

TEST(JoinedResponse, AFreeBodyRespondsAsNewtonSays) {
    const std::vector<JoinedBody> bodies = {box(2, {1, 0.2, 0.2}, {0, 0, 0})};
    const Vec3 j(0, 3, 0), p(0.5, 0, 0);
    const auto u = joined_response(bodies, {}, {{0, p, j}});
    EXPECT_TRUE(u[0].linear.isApprox(j / 2));
    EXPECT_TRUE(u[0].angular.isApprox(bodies[0].inv_inertia * p.cross(j)));
}

TEST(JoinedResponse, TwoBodiesWeldedAtFourPointsMoveAsOneRigidBody) {
    // Two 1 x 1 x 1 m cubes side by side along x, welded at four points of their shared face
    // (twelve rows for six degrees of freedom: singular without the regularization).
    const std::vector<JoinedBody> bodies = {box(1, {1, 1, 1}, {-0.5, 0, 0}), box(3, {1, 1, 1}, {0.5, 0, 0})};
    std::vector<JoinedJoint> joints;
    for (const Vec3& p : {Vec3(0, 0.4, 0.4), Vec3(0, -0.4, 0.4), Vec3(0, 0, -0.4), Vec3(0, 0.4, -0.4)})
        joints.push_back({0, 1, p});
    const Vec3 j(0.2, 1.0, -0.5), p(-1, 0.5, 0.5);  // on the light cube's far corner
    const auto u = joined_response(bodies, joints, {{0, p, j}});
    // The pair as one body: mass 4, centre at x = 0.25, inertia of the two cubes about it.
    const double m = 4;
    const Vec3 centre(0.25, 0, 0);
    Mat3 inertia = Mat3::Zero();
    for (const JoinedBody& b : bodies) {
        const Vec3 d = b.centre - centre;
        inertia += b.inv_inertia.inverse() + (1 / b.inv_mass) * (d.squaredNorm() * Mat3::Identity() - d * d.transpose());
    }
    const Vec3 v = j / m, w = inertia.inverse() * (p - centre).cross(j);
    for (int i = 0; i < 2; ++i) {
        EXPECT_NEAR((u[i].angular - w).norm(), 0, 1e-6 * w.norm()) << "body " << i;
        EXPECT_NEAR((u[i].linear - (v + w.cross(bodies[i].centre - centre))).norm(), 0, 1e-6 * v.norm()) << "body " << i;
    }
    // rigid_response() gives the same without the joints.
    const auto rigid = rigid_response(bodies, {{0, p, j}});
    for (int i = 0; i < 2; ++i) {
        EXPECT_NEAR((rigid[i].angular - w).norm(), 0, 1e-12 * w.norm());
        EXPECT_NEAR((rigid[i].linear - (v + w.cross(bodies[i].centre - centre))).norm(), 0, 1e-12 * v.norm());
    }
    // Equal and opposite impulses at one point of a rigid body move nothing.
    const auto none = joined_response(bodies, joints, {{0, Vec3(0, 0, 0), j}, {1, Vec3(0, 0, 0), -j}});
    for (const VelocityChange& c : none) EXPECT_LT(c.linear.norm() + c.angular.norm(), 1e-6 * j.norm());
}

TEST(JoinedResponse, ARodPinnedAtOneEndSwingsAboutThePin) {
    // A thin rod of mass m and length L along x, pinned to a static body at x = 0 and struck
    // across at its free end: it turns about the pin, I = m L^2 / 3, so the end moves at 3 j / m.
    const double m = 0.5, l = 2;
    JoinedBody ground;
    ground.dynamic = false;
    const std::vector<JoinedBody> bodies = {ground, box(m, {l, 0.01, 0.01}, {l / 2, 0, 0})};
    const std::vector<JoinedJoint> joints = {{0, 1, Vec3(0, 0, 0)}};
    const Vec3 j(0, 0, 0.1), end(l, 0, 0);
    const auto u = joined_response(bodies, joints, {{1, end, j}});
    EXPECT_NEAR(point_velocity(u[1], bodies[1], end).z(), 3 * j.z() / m, 1e-4 * j.z() / m);
    EXPECT_LT(point_velocity(u[1], bodies[1], Vec3::Zero()).norm(), 1e-7);
    EXPECT_EQ(u[0].linear, Vec3::Zero());
    // The impulse's work on the velocity it causes is twice the kinetic energy gained.
    const Vec3 wu = u[1].angular, vu = u[1].linear;
    const double kinetic = 0.5 * (m * vu.squaredNorm() + wu.dot(bodies[1].inv_inertia.inverse() * wu));
    EXPECT_NEAR(2 * kinetic, j.dot(point_velocity(u[1], bodies[1], end)), 1e-9);
}

TEST(JoinedResponse, AChainStruckAtOneEndKeepsEveryJointTogether) {
    // Five links joined end to end by ball joints, struck at an angle at the last link's end:
    // every joint's two pivots move alike afterwards, and momentum is the impulse.
    std::vector<JoinedBody> bodies;
    std::vector<JoinedJoint> joints;
    for (int i = 0; i < 5; ++i) {
        bodies.push_back(box(0.1 * (i + 1), {0.3, 0.1, 0.1}, {0.3 * i, 0.02 * i, 0}));
        if (i > 0) joints.push_back({uint32_t(i - 1), uint32_t(i), Vec3(0.3 * i - 0.15, 0.02 * i - 0.01, 0)});
    }
    const Vec3 j(1, 2, -3), p(1.35, 0.08, 0.05);
    const auto u = joined_response(bodies, joints, {{4, p, j}});
    Vec3 momentum = Vec3::Zero();
    for (size_t i = 0; i < bodies.size(); ++i) momentum += u[i].linear / bodies[i].inv_mass;
    EXPECT_NEAR((momentum - j).norm(), 0, 1e-12 * j.norm());
    for (const JoinedJoint& k : joints) {
        const Vec3 gap = point_velocity(u[k.b], bodies[k.b], k.pivot) - point_velocity(u[k.a], bodies[k.a], k.pivot);
        EXPECT_LT(gap.norm(), 1e-6 * point_velocity(u[4], bodies[4], p).norm());
    }
}

}  // namespace
}  // namespace shatter
