// The engine-free energized-fracture math against what mechanics predicts: the energy the
// impulses give two bodies at rest, the momentum they change, and the paper's directions.
#include <gtest/gtest.h>

#include <Eigen/Dense>

#include "simulate/energized_fracture.h"

namespace shatter {
namespace {

struct Body {
    double mass;
    Mat3 inertia;  // world frame
    Vec3 com;
};

BodyAtPivot at_pivot(const Body& b, const Vec3& pivot, const Vec3& force) {
    BodyAtPivot p;
    p.inv_mass = 1.0 / b.mass;
    p.inv_inertia = b.inertia.inverse();
    p.r = pivot - b.com;
    p.force = force;
    p.torque = p.r.cross(force);
    return p;
}

// Kinetic energy a body at rest gains from `impulse` applied at r from its centre.
double kinetic_energy_gain(const Body& b, const Vec3& r, const Vec3& impulse) {
    const Vec3 v = impulse / b.mass;
    const Vec3 w = b.inertia.inverse() * r.cross(impulse);
    return 0.5 * b.mass * v.squaredNorm() + 0.5 * w.dot(b.inertia * w);
}

Mat3 box_inertia(double m, double x, double y, double z) {
    return (Vec3(y * y + z * z, x * x + z * z, x * x + y * y) * m / 12.0).asDiagonal();
}

// A bending break: two unequal boxes side by side along x, the pivot on their top edge, the
// constraint pulling them together along x (the top fibre in tension).
struct Bending {
    Body a{2.0, box_inertia(2.0, 1, 0.5, 0.5), Vec3(-0.5, 0, 0)};
    Body b{0.5, box_inertia(0.5, 0.25, 0.5, 0.5), Vec3(0.125, 0, 0)};
    Vec3 pivot{0, 0.25, 0};
    Vec3 force_on_a{30, 0, 0};
};

TEST(EnergizedFracture, StoredEnergyIsHalfForceSquaredOverStiffness) {
    EXPECT_DOUBLE_EQ(stored_energy(Vec3(3, 4, 0), 10.0), 0.5 * 25 / 10.0);
}

TEST(EnergizedFracture, TotalSplitGivesTwoBodiesAtRestExactlyAlphaE) {
    Bending s;
    for (double alpha : {0.5, 1.0, 2.0}) {
        EnergizeSettings cfg;
        cfg.alpha = alpha;
        BreakKicks k = energize(at_pivot(s.a, s.pivot, s.force_on_a), at_pivot(s.b, s.pivot, -s.force_on_a), 1e4, cfg, 7);
        const double gained = kinetic_energy_gain(s.a, s.pivot - s.a.com, k.kick[0].impulse) +
                              kinetic_energy_gain(s.b, s.pivot - s.b.com, k.kick[1].impulse);
        EXPECT_NEAR(gained, alpha * k.stored_energy, 1e-12 * k.stored_energy) << alpha;
        EXPECT_NEAR(k.kick[0].energy + k.kick[1].energy, alpha * k.stored_energy, 1e-12);
        EXPECT_DOUBLE_EQ(k.kick[0].magnitude, k.kick[1].magnitude);  // an internal force pair
        EXPECT_GT(k.kick[1].energy, k.kick[0].energy);               // the lighter body moves more
    }
}

TEST(EnergizedFracture, PerBodySplitGivesEachBodyAlphaE) {
    Bending s;
    EnergizeSettings cfg;
    cfg.split = EnergySplit::PerBody;
    BreakKicks k = energize(at_pivot(s.a, s.pivot, s.force_on_a), at_pivot(s.b, s.pivot, -s.force_on_a), 1e4, cfg, 7);
    EXPECT_NEAR(kinetic_energy_gain(s.a, s.pivot - s.a.com, k.kick[0].impulse), k.stored_energy, 1e-12);
    EXPECT_NEAR(kinetic_energy_gain(s.b, s.pivot - s.b.com, k.kick[1].impulse), k.stored_energy, 1e-12);
}

TEST(EnergizedFracture, BodyJoinedToStaticTakesTheWholeShare) {
    Bending s;
    BodyAtPivot ground;
    ground.dynamic = false;
    for (EnergySplit split : {EnergySplit::Total, EnergySplit::PerBody}) {
        EnergizeSettings cfg;
        cfg.split = split;
        BreakKicks k = energize(at_pivot(s.a, s.pivot, s.force_on_a), ground, 1e4, cfg, 7);
        EXPECT_EQ(k.kick[1].magnitude, 0.0);
        EXPECT_NEAR(kinetic_energy_gain(s.a, s.pivot - s.a.com, k.kick[0].impulse), k.stored_energy, 1e-12);
    }
}

TEST(EnergizedFracture, AlphaZeroGivesNoImpulse) {
    Bending s;
    EnergizeSettings cfg;
    cfg.alpha = 0;
    BreakKicks k = energize(at_pivot(s.a, s.pivot, s.force_on_a), at_pivot(s.b, s.pivot, -s.force_on_a), 1e4, cfg, 7);
    EXPECT_EQ(k.kick[0].impulse.norm(), 0.0);
    EXPECT_EQ(k.kick[1].impulse.norm(), 0.0);
}

TEST(EnergizedFracture, BendingBreakKicksAlongMinusTorqueCrossForce) {
    Bending s;
    BodyAtPivot a = at_pivot(s.a, s.pivot, s.force_on_a);
    BreakKicks k = energize(a, at_pivot(s.b, s.pivot, -s.force_on_a), 1e4, {}, 7);
    const Vec3 expected = -(a.torque.cross(a.force)).normalized();
    EXPECT_LT((k.kick[0].direction - expected).norm(), 1e-12);
    EXPECT_FALSE(k.kick[0].random_direction);
    // -(t x f) = |f|^2 r_perp: the lever arm's part across the force, here +y for both bodies.
    EXPECT_LT((k.kick[0].direction - Vec3::UnitY()).norm(), 1e-12);
    EXPECT_LT((k.kick[1].direction - Vec3::UnitY()).norm(), 1e-12);
}

TEST(EnergizedFracture, PaperDirectionsChangeMomentumInABendingBreakOpposedDoNot) {
    Bending s;
    auto momentum_change = [&](KickDirections d, Vec3* angular) {
        EnergizeSettings cfg;
        cfg.directions = d;
        BreakKicks k = energize(at_pivot(s.a, s.pivot, s.force_on_a), at_pivot(s.b, s.pivot, -s.force_on_a), 1e4, cfg, 7);
        *angular = s.pivot.cross(k.kick[0].impulse) + s.pivot.cross(k.kick[1].impulse);
        return Vec3(k.kick[0].impulse + k.kick[1].impulse);
    };
    Vec3 angular;
    const Vec3 paper = momentum_change(KickDirections::Paper, &angular);
    EXPECT_GT(paper.norm(), 0.1);  // both pieces kicked the same way (+y)
    const Vec3 opposed = momentum_change(KickDirections::Opposed, &angular);
    EXPECT_LT(opposed.norm(), 1e-12);
    EXPECT_LT(angular.norm(), 1e-12);
}

TEST(EnergizedFracture, OpposedKicksStillReleaseAlphaE) {
    Bending s;
    EnergizeSettings cfg;
    cfg.directions = KickDirections::Opposed;
    BreakKicks k = energize(at_pivot(s.a, s.pivot, s.force_on_a), at_pivot(s.b, s.pivot, -s.force_on_a), 1e4, cfg, 7);
    const double gained = kinetic_energy_gain(s.a, s.pivot - s.a.com, k.kick[0].impulse) +
                          kinetic_energy_gain(s.b, s.pivot - s.b.com, k.kick[1].impulse);
    EXPECT_NEAR(gained, k.stored_energy, 1e-12);
}

TEST(EnergizedFracture, ForceKicksPushThePiecesApartAlongTheLoadInTensionAndCompression) {
    Bending s;  // a lies on -x of b
    for (double sign : {1.0, -1.0}) {  // +1: a pulled towards b (tension); -1: pushed away (compression)
        const Vec3 f = sign * s.force_on_a;
        EnergizeSettings cfg;
        cfg.directions = KickDirections::Force;
        BreakKicks k = energize(at_pivot(s.a, s.pivot, f), at_pivot(s.b, s.pivot, -f), 1e4, cfg, 7);
        EXPECT_LT((k.kick[0].direction + Vec3::UnitX()).norm(), 1e-12) << sign;  // a away from b
        EXPECT_LT((k.kick[1].direction - Vec3::UnitX()).norm(), 1e-12) << sign;  // b away from a
        EXPECT_FALSE(k.kick[0].random_direction);
        // Equal and opposite at one point: no change of linear or angular momentum.
        EXPECT_LT((k.kick[0].impulse + k.kick[1].impulse).norm(), 1e-15);
        const double gained = kinetic_energy_gain(s.a, s.pivot - s.a.com, k.kick[0].impulse) +
                              kinetic_energy_gain(s.b, s.pivot - s.b.com, k.kick[1].impulse);
        EXPECT_NEAR(gained, k.stored_energy, 1e-12 * k.stored_energy) << sign;
    }
}

TEST(EnergizedFracture, ForceKicksReleaseAShearLoadAcrossTheInterface) {
    // An impact's load: the force across the line of centres. The joint held a up (+y) and b down;
    // released, a goes on up and b down, along the interface rather than into each other.
    Bending s;
    const Vec3 f(0, 30, 0);
    EnergizeSettings cfg;
    cfg.directions = KickDirections::Force;
    BreakKicks k = energize(at_pivot(s.a, s.pivot, f), at_pivot(s.b, s.pivot, -f), 1e4, cfg, 7);
    EXPECT_LT((k.kick[0].direction - Vec3::UnitY()).norm(), 1e-12);
    EXPECT_LT((k.kick[1].direction + Vec3::UnitY()).norm(), 1e-12);
    // The paper's direction for the same break points into the partner (r_perp: along +x for a).
    BreakKicks paper = energize(at_pivot(s.a, s.pivot, f), at_pivot(s.b, s.pivot, -f), 1e4, {}, 7);
    EXPECT_GT(paper.kick[0].direction.dot(s.b.com - s.a.com), 0.5 * (s.b.com - s.a.com).norm());
}

TEST(EnergizedFracture, PureTensionKicksOrthogonalToTheForceReproducibly) {
    // A chain link pulled along the line through its centre: t x f = 0.
    Body link{0.1, box_inertia(0.1, 0.1, 0.02, 0.02), Vec3(0, 0, 0)};
    const Vec3 pivot(0.05, 0, 0), f(40, 0, 0);
    BodyAtPivot a = at_pivot(link, pivot, f);
    BodyAtPivot fixed;
    fixed.dynamic = false;
    BreakKicks k1 = energize(a, fixed, 1e5, {}, 11);
    BreakKicks k2 = energize(a, fixed, 1e5, {}, 11);
    BreakKicks k3 = energize(a, fixed, 1e5, {}, 12);
    EXPECT_TRUE(k1.kick[0].random_direction);
    EXPECT_NEAR(k1.kick[0].direction.norm(), 1.0, 1e-12);
    EXPECT_NEAR(k1.kick[0].direction.dot(f), 0.0, 1e-9);
    EXPECT_EQ(k1.kick[0].direction, k2.kick[0].direction);
    EXPECT_GT((k1.kick[0].direction - k3.kick[0].direction).norm(), 1e-6);
}

TEST(EnergizedFracture, EffectiveMassAtTheCentreIsTheMass) {
    EXPECT_DOUBLE_EQ(effective_mass(0.5, Mat3::Identity(), Vec3::Zero(), Vec3::UnitX()), 2.0);
    // A rod's tip struck sideways: 1/m_G = 1/m + r^2/I = 1/m + (L/2)^2 / (m L^2/12) = 4/m.
    const double m = 3, L = 2;
    Mat3 inv_i = Mat3::Identity() / (m * L * L / 12);
    EXPECT_NEAR(effective_mass(1 / m, inv_i, Vec3(L / 2, 0, 0), Vec3::UnitY()), m / 4, 1e-12);
}

}  // namespace
}  // namespace shatter

namespace shatter {
namespace {

// Two boxes (1 kg) break in bending while moving with the given velocities (no spin, so the pivot
// moves with the centre). Returns the kinetic energy the kicks add, counted in a frame moving at
// `frame`.
struct MovingPair {
    Mat3 inertia = Vec3(0.1, 0.2, 0.2).asDiagonal();
    BodyAtPivot a, b;
    MovingPair(const Vec3& va, const Vec3& vb) {
        const Vec3 v[2] = {va, vb};
        BodyAtPivot* body[2] = {&a, &b};
        for (int s = 0; s < 2; ++s) {
            body[s]->inv_mass = 1.0;
            body[s]->inv_inertia = inertia.inverse();
            body[s]->velocity = body[s]->centre_velocity = v[s];
        }
        a.r = Vec3(0.1, 0.05, 0);
        b.r = Vec3(-0.1, 0.05, 0);
        a.force = Vec3(20, 0, 0);
        b.force = -a.force;
        a.torque = a.r.cross(a.force);
        b.torque = b.r.cross(b.force);
    }
    double gained(const BreakKicks& k, const Vec3& frame) const {
        double e = 0;
        const BodyAtPivot* body[2] = {&a, &b};
        for (int s = 0; s < 2; ++s) {
            const Vec3 v0 = body[s]->velocity - frame;
            const Vec3 v = v0 + k.kick[s].impulse * body[s]->inv_mass;
            const Vec3 w = body[s]->inv_inertia * body[s]->r.cross(k.kick[s].impulse);
            e += 0.5 * (v.squaredNorm() - v0.squaredNorm()) / body[s]->inv_mass + 0.5 * w.dot(inertia * w);
        }
        return e;
    }
};

TEST(EnergizedFractureMoving, ExactEnergyCountsInThePairsFrameSoACommonMotionChangesNothing) {
    // Falling together at 4 m/s: in the pair's frame they are at rest, so the exact magnitudes are
    // the paper's and the pair's frame gains alpha E. In the world's frame the paper's directions
    // (both kicked the same way in bending) add dP . V on top.
    const MovingPair fall(Vec3(0, -4, 0), Vec3(0, -4, 0)), rest(Vec3::Zero(), Vec3::Zero());
    EnergizeSettings paper, exact;
    exact.exact_energy = true;
    const BreakKicks kf = energize(fall.a, fall.b, 1e4, exact, 1), kr = energize(rest.a, rest.b, 1e4, paper, 1);
    EXPECT_EQ(pair_frame_velocity(fall.a, fall.b), Vec3(0, -4, 0));
    for (int s = 0; s < 2; ++s) EXPECT_EQ(kf.kick[s].impulse, kr.kick[s].impulse);
    const Vec3 frame(0, -4, 0);
    EXPECT_NEAR(fall.gained(kf, frame), kf.stored_energy, 1e-9 * kf.stored_energy);
    const Vec3 dp = kf.kick[0].impulse + kf.kick[1].impulse;
    EXPECT_GT(dp.norm(), 0.1 * kf.kick[0].magnitude);  // the paper's kicks do not conserve momentum here
    EXPECT_NEAR(fall.gained(kf, Vec3::Zero()), kf.stored_energy + dp.dot(frame), 1e-9 * kf.stored_energy);
}

TEST(EnergizedFractureMoving, PaperMagnitudesMissAlphaEForPiecesInRelativeMotionExactEnergyHitsIt) {
    // Already parting (a falls faster than b, and b drifts sideways), and b four times as heavy:
    // the cross term mu (i . v_p) in the pair's frame no longer vanishes.
    MovingPair pair(Vec3(0, -4, 0), Vec3(0.5, -2, 0.3));
    pair.b.inv_mass = 0.25;
    EnergizeSettings paper, exact;
    exact.exact_energy = true;
    const BreakKicks kp = energize(pair.a, pair.b, 1e4, paper, 1), ke = energize(pair.a, pair.b, 1e4, exact, 1);
    const Vec3 frame = pair_frame_velocity(pair.a, pair.b);
    EXPECT_TRUE(frame.isApprox(Vec3(0.4, -2.4, 0.24), 1e-15)) << frame.transpose();
    EXPECT_GT(std::abs(pair.gained(kp, frame) / kp.stored_energy - 1), 0.5);  // the cross term dominates
    EXPECT_NEAR(pair.gained(ke, frame), ke.stored_energy, 1e-9 * ke.stored_energy);
    EXPECT_EQ(ke.kick[0].direction, kp.kick[0].direction);
}

TEST(EnergizedFractureMoving, APieceJoinedToAStaticBodyCountsInTheWorldsFrame) {
    MovingPair pair(Vec3(0, -4, 0), Vec3::Zero());
    pair.b.dynamic = false;
    EXPECT_EQ(pair_frame_velocity(pair.a, pair.b), Vec3::Zero());
}

}  // namespace
}  // namespace shatter
