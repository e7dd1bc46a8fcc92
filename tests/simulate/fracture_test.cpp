// Breaking and energizing in Bullet, against what the method promises: the kinetic energy a
// break adds, what it does to momentum, the kick directions, step-size independence, rate
// limiting, rollback, determinism, and pieces joined at rest staying at rest.
#include <gtest/gtest.h>

#include <fmt/format.h>

#include "scenes/box_model.h"
#include "core/trajectory.h"
#include "simulate/breaking.h"
#include "simulate/bullet_world.h"
#include "simulate/recording.h"
#include "simulate/simulate.h"

namespace shatter {
namespace {

constexpr double kSide = 0.1;  // 1 kg boxes at 1000 kg/m^3

// anchor (fixed) - upper - lower, hanging; the upper-lower joint carries the lower box's weight.
struct HangingPair {
    BoxModelBuilder b;
    WorldSetup setup;
    HangingPair() {
        const uint32_t anchor = b.box(Vec3(0, 2, 0), Vec3::Constant(kSide));
        const uint32_t upper = b.box(Vec3(0, 2 - kSide, 0), Vec3::Constant(kSide));
        const uint32_t lower = b.box(Vec3(0, 2 - 2 * kSide, 0), Vec3::Constant(kSide));
        b.join(anchor, upper, Vec3(0, 2 - kSide / 2, 0));
        b.join(upper, lower, Vec3(0, 2 - 1.5 * kSide, 0));
        setup.scene.ground = false;
        setup.object.driven.push_back({anchor, true, Vec3::Zero(), {}});
        setup.material.stiffness = 1e6;  // N/m at area 1
        setup.material.damping = 2e3;    // settles in a few steps
        setup.material.strength = 1e30;
        setup.h = 1.0 / 240;
        setup.iterations = 50;
    }
};

void settle(BulletWorld& world, double seconds) {
    for (int i = 0; i < int(seconds / world.h()); ++i) world.step();
}

// Breaks constraint c of a settled world the way the simulate loop does: its load from the last
// step, out of the world, then energized. `gained` is the kinetic energy the break added.
struct Broken {
    std::array<BodyAtPivot, 2> load;
    Vec3 pivot;
    BreakRecord record;
    double gained = 0;
};
Broken break_now(BulletWorld& world, size_t c, const EnergizeSettings& e, uint64_t key) {
    Broken b;
    b.load = world.bodies_at_pivot(c, &b.pivot);
    world.remove_constraint(c);
    const double before = world.kinetic_energy();
    b.record = energize_broken(world, c, b.load, e, key);
    b.gained = world.kinetic_energy() - before;
    return b;
}

TEST(Fracture, BreakingTwoBodiesAtRestAddsAlphaTimesStoredEnergyWithinOnePercent) {
    for (double alpha : {0.5, 1.0, 2.0}) {
        HangingPair s;
        BulletWorld world(s.b.model(), s.setup);
        settle(world, 1.0);
        EnergizeSettings e;
        e.alpha = alpha;
        const Broken b = break_now(world, 1, e, break_key(1, 1));
        const BreakRecord& r = b.record;
        const double gained = b.gained;
        ASSERT_GT(r.kicks.stored_energy, 0);
        EXPECT_NEAR(r.kicks.stored_energy, 0.5 * std::pow(9.81, 2) / 1e6, 1e-3 * r.kicks.stored_energy);
        EXPECT_NEAR(gained / (alpha * r.kicks.stored_energy), 1.0, 0.01) << "alpha " << alpha;
        EXPECT_NEAR(r.injected_energy, gained, 1e-9 * gained);
    }
}

TEST(Fracture, PaperLiteralSplitAddsTwiceAlphaE) {
    HangingPair s;
    BulletWorld world(s.b.model(), s.setup);
    settle(world, 1.0);
    EnergizeSettings e;
    e.split = EnergySplit::PerBody;
    const Broken b = break_now(world, 1, e, break_key(1, 1));
    EXPECT_NEAR(b.gained / (2 * b.record.kicks.stored_energy), 1.0, 0.01);
}

TEST(Fracture, AlphaZeroIsPlainBreakingExactly) {
    HangingPair s;
    BulletWorld world(s.b.model(), s.setup);
    settle(world, 1.0);
    Vec3 pivot;
    const auto load = world.bodies_at_pivot(1, &pivot);
    world.remove_constraint(1);
    const Vec3 v_upper = world.piece_velocity(1), v_lower = world.piece_velocity(2);
    EnergizeSettings e;
    e.alpha = 0;
    const BreakRecord r = energize_broken(world, 1, load, e, break_key(1, 1));
    EXPECT_EQ(r.injected_energy, 0.0);
    EXPECT_EQ(world.piece_velocity(1), v_upper);
    EXPECT_EQ(world.piece_velocity(2), v_lower);
}

// anchor (fixed) - a - b in a row along x, each joint a top and a bottom constraint: gravity
// bends the a-b joint, its top constraint in tension.
struct Cantilever {
    BoxModelBuilder b;
    WorldSetup setup;
    Cantilever() {
        const uint32_t anchor = b.box(Vec3(0, 1, 0), Vec3::Constant(kSide));
        const uint32_t a = b.box(Vec3(kSide, 1, 0), Vec3::Constant(kSide));
        const uint32_t c = b.box(Vec3(2 * kSide, 1, 0), Vec3::Constant(kSide));
        for (double y : {1 + kSide / 2, 1 - kSide / 2}) {
            b.join(anchor, a, Vec3(kSide / 2, y, 0));
            b.join(a, c, Vec3(1.5 * kSide, y, 0));
        }
        setup.scene.ground = false;
        setup.object.driven.push_back({anchor, true, Vec3::Zero(), {}});
        setup.material.stiffness = 1e6;
        setup.material.damping = 2e3;
        setup.material.strength = 1e30;
        setup.h = 1.0 / 240;
        setup.iterations = 100;
    }
    static constexpr size_t kTopOfSecondJoint = 1;  // constraints: (anchor,a) top, (a,b) top, ... sorted by insertion
};

TEST(Fracture, BendingBreakKicksAlongMinusTorqueCrossForceFromBulletsFeedback) {
    Cantilever s;
    BulletWorld world(s.b.model(), s.setup);
    settle(world, 1.0);
    const Broken broken = break_now(world, Cantilever::kTopOfSecondJoint, {}, 7);
    const auto& load = broken.load;
    const BreakRecord& r = broken.record;
    // Bullet's feedback torque is the constraint force's moment about the centre of mass.
    for (const BodyAtPivot& body : load)
        EXPECT_LT((body.torque - body.r.cross(body.force)).norm(), 1e-6 * (body.r.norm() * body.force.norm()));
    EXPECT_GT(load[0].force.x(), 0);  // the top fibre is in tension: b pulls a towards +x
    for (int k = 0; k < 2; ++k) {
        EXPECT_FALSE(r.kicks.kick[k].random_direction);
        const Vec3 expected = -(load[k].torque.cross(load[k].force)).normalized();
        EXPECT_LT((r.kicks.kick[k].direction - expected).norm(), 1e-9);
    }
}

TEST(Fracture, PaperKicksChangeMomentumInABendingBreakTheOpposedVariantDoesNot) {
    for (KickDirections d : {KickDirections::Paper, KickDirections::Opposed}) {
        Cantilever s;
        BulletWorld world(s.b.model(), s.setup);
        settle(world, 1.0);
        Vec3 pivot;
        const auto load = world.bodies_at_pivot(Cantilever::kTopOfSecondJoint, &pivot);
        world.remove_constraint(Cantilever::kTopOfSecondJoint);
        const Vec3 p0 = world.linear_momentum(), l0 = world.angular_momentum();
        EnergizeSettings e;
        e.directions = d;
        const BreakRecord r = energize_broken(world, Cantilever::kTopOfSecondJoint, load, e, 7);
        const double impulse = r.kicks.kick[0].magnitude;
        const double dp = (world.linear_momentum() - p0).norm() / impulse;
        const double dl = (world.angular_momentum() - l0).norm() / (impulse * pivot.norm());
        RecordProperty(d == KickDirections::Paper ? "paper_dp_relative" : "opposed_dp_relative", fmt::format("{:.3g}", dp));
        if (d == KickDirections::Paper) {
            EXPECT_GT(dp, 0.5);  // both pieces kicked the same way
        } else {
            EXPECT_LT(dp, 1e-9);
            EXPECT_LT(dl, 1e-9);
        }
    }
}

TEST(Fracture, PureTensionBreakKicksOrthogonalToTheForce) {
    HangingPair s;
    BulletWorld world(s.b.model(), s.setup);
    settle(world, 1.0);
    const Broken b = break_now(world, 1, {}, 3);
    for (const Kick& k : b.record.kicks.kick) {
        EXPECT_TRUE(k.random_direction);
        EXPECT_LT(std::abs(k.direction.dot(b.load[0].force.normalized())), 1e-9);
    }
}

// A 1 kg box swinging down from horizontal on a pivot 0.5 m from its centre, its constraint
// breaking at twice its weight (about 42 degrees below the horizontal); then it flies free.
SimulationResult pendulum(uint32_t substeps, bool rollback = false) {
    BoxModelBuilder b;
    const uint32_t anchor = b.box(Vec3(0, 2, 0), Vec3::Constant(kSide));
    const uint32_t bob = b.box(Vec3(0.5, 2, 0), Vec3::Constant(kSide));
    b.join(anchor, bob, Vec3(0, 2, 0), 1e-4);
    SimulationInput in;
    in.scene.ground = false;
    in.object.driven.push_back({anchor, true, Vec3::Zero(), {}});
    in.material.stiffness = 1e11;  // 1e7 N/m at 1 cm^2
    in.material.strength = 2 * 9.81 / 1e-4;
    in.simulate.duration = 1.0;
    in.simulate.fps = 60;
    in.simulate.substeps = substeps;
    in.simulate.iterations = 50;
    in.simulate.rollback = rollback;
    return simulate(b.model(), in, "test");
}

double kinetic_energy_at(const std::vector<EnergySample>& e, double t) {
    for (size_t i = 1; i < e.size(); ++i)
        if (e[i].time >= t) {
            const double u = (t - e[i - 1].time) / (e[i].time - e[i - 1].time);
            return e[i - 1].kinetic + u * (e[i].kinetic - e[i - 1].kinetic);
        }
    return e.back().kinetic;
}

TEST(Fracture, BreakTimeAndFragmentEnergyDoNotDependOnTheStepSize) {
    const SimulationResult coarse = pendulum(4), fine = pendulum(16);  // h = 1/240 and 1/960
    ASSERT_EQ(coarse.breaks.size(), 1u);
    ASSERT_EQ(fine.breaks.size(), 1u);
    const double t1 = coarse.breaks[0].time, t2 = fine.breaks[0].time;
    EXPECT_NEAR(t1 / t2, 1.0, 0.05);
    const double e1 = kinetic_energy_at(coarse.energy, t1 + 0.1), e2 = kinetic_energy_at(fine.energy, t2 + 0.1);
    EXPECT_NEAR(e1 / e2, 1.0, 0.05);
    RecordProperty("break_time_ratio", fmt::format("{:.4f}", t1 / t2));
    RecordProperty("fragment_energy_ratio", fmt::format("{:.4f}", e1 / e2));
}

TEST(Fracture, RollbackRerunsTheBreakingStepWithoutTheConstraint) {
    // A box hanging from a constraint weaker than its weight breaks in the first step. Without
    // rollback the constraint has already held it in that step; with rollback the step is re-run
    // and the box is in free fall from the start: v = -g h after the step (alpha = 0: no kick).
    for (bool rollback : {false, true}) {
        HangingPair s;
        s.setup.material.strength = 0.5 * 9.81;
        s.setup.material.damping = 0;
        BulletWorld world(s.b.model(), s.setup);
        world.step();
        ASSERT_GT(world.force_on_a(0).norm(), s.setup.material.strength);
        // The simulate loop's own path, one step: see simulate.cpp (Run::substep).
        SimulationInput in;
        in.scene = s.setup.scene;
        in.object = s.setup.object;
        in.material = s.setup.material;
        in.material.alpha = 0;
        in.simulate.fps = 240;
        in.simulate.substeps = 1;
        in.simulate.duration = 1.0 / 240;
        in.simulate.rollback = rollback;
        in.simulate.iterations = 50;
        const SimulationResult r = simulate(s.b.model(), in, "test");
        ASSERT_EQ(r.breaks.size(), 2u);  // both joints carry more than half a box's weight
        const BodyPose& end = r.trajectory.pose(1, 2);
        const double fall = 2 - 2 * kSide - end.position.y();
        const double free_fall = 0.5 * 9.81 / (240.0 * 240.0) * 2;  // x = v h with v = g h (semi-implicit Euler)
        if (rollback)
            EXPECT_NEAR(fall, free_fall, 1e-6);
        else
            EXPECT_LT(fall, 0.5 * free_fall);
    }
}

TEST(Fracture, RateLimitSpacesBreaksByAtLeastTheLimit) {
    // Five boxes each hanging from a fixed anchor by a constraint weaker than its weight: all are
    // overloaded from the first step. Without a limit all break at once; with 0.3 s, one per 0.3 s.
    for (double limit : {0.0, 0.3}) {
        BoxModelBuilder b;
        const uint32_t anchor = b.box(Vec3(0, 2, 0), Vec3(1, kSide, kSide));
        for (int i = 0; i < 5; ++i) {
            const uint32_t p = b.box(Vec3(-0.4 + 0.2 * i, 2 - kSide, 0), Vec3::Constant(kSide));
            b.join(anchor, p, Vec3(-0.4 + 0.2 * i, 2 - kSide / 2, 0));
        }
        SimulationInput in;
        in.scene.ground = false;
        in.object.driven.push_back({anchor, true, Vec3::Zero(), {}});
        in.material.stiffness = 1e6;
        in.material.strength = 0.5 * 9.81;
        in.simulate.duration = 1.5;
        in.simulate.rate_limit = limit;
        const SimulationResult r = simulate(b.model(), in, "test");
        ASSERT_EQ(r.breaks.size(), 5u);
        if (limit == 0) {
            EXPECT_EQ(r.breaks.front().time, r.breaks.back().time);
        } else {
            for (size_t i = 1; i < r.breaks.size(); ++i)
                EXPECT_GE(r.breaks[i].time - r.breaks[i - 1].time, limit - 1e-9);
            EXPECT_LT(r.breaks[1].time - r.breaks[0].time, limit + 1.0 / 240 + 1e-9);
        }
    }
}

TEST(Fracture, SameInputsGiveIdenticalBytes) {
    const SimulationResult a = pendulum(4), b = pendulum(4);
    EXPECT_EQ(encode_trajectory(a.trajectory), encode_trajectory(b.trajectory));
    EXPECT_EQ(break_log_jsonl(a.breaks), break_log_jsonl(b.breaks));
    EXPECT_EQ(energy_csv(a.energy), energy_csv(b.energy));
}

TEST(Fracture, JoinedPiecesTouchingAtRestStayAtRest) {
    // Two boxes side by side on the ground, touching along a face and joined at its corners:
    // their collision shapes touch, yet they must not push each other apart.
    BoxModelBuilder b;
    const uint32_t l = b.box(Vec3(-kSide / 2, kSide / 2, 0), Vec3::Constant(kSide));
    const uint32_t r = b.box(Vec3(kSide / 2, kSide / 2, 0), Vec3::Constant(kSide));
    for (double y : {0.0, kSide})
        for (double z : {-kSide / 2, kSide / 2}) b.join(l, r, Vec3(0, y, z), 0.0025);
    SimulationInput in;
    in.material.stiffness = 1e12;
    in.material.strength = 1e9;
    in.simulate.duration = 1.0;
    const SimulationResult out = simulate(b.model(), in, "test");
    EXPECT_TRUE(out.breaks.empty());
    EXPECT_LT(out.energy.back().kinetic, 1e-6);
    const uint32_t last = out.trajectory.frames() - 1;
    const float gap = out.trajectory.pose(last, r).position.x() - out.trajectory.pose(last, l).position.x();
    EXPECT_NEAR(gap, kSide, 1e-6);
}

// a overlaps b by `overlap` (joined pieces never collide, so they can); b and c touch along a face,
// held by four stiff joints. Breaking a-b's one joint, then stepping 0.5 s without gravity:
// the kinetic energy at the end.
double kinetic_after_breaking_an_overlapping_pair(double overlap) {
    BoxModelBuilder b;
    const uint32_t a = b.box(Vec3(-kSide + overlap, 0, 0), Vec3::Constant(kSide));
    const uint32_t mid = b.box(Vec3(0, 0, 0), Vec3::Constant(kSide));
    const uint32_t c = b.box(Vec3(kSide, 0, 0), Vec3::Constant(kSide));
    b.join(a, mid, Vec3(-kSide / 2, 0, 0), 0.0025);
    for (double y : {-kSide / 2, kSide / 2})
        for (double z : {-kSide / 2, kSide / 2}) b.join(mid, c, Vec3(kSide / 2, y, z), 0.0025);
    WorldSetup setup;
    setup.scene.ground = false;
    setup.scene.gravity = Vec3::Zero();
    setup.material.stiffness = 1e12;
    setup.material.strength = 1e30;
    setup.h = 1.0 / 240;
    setup.iterations = 20;
    BulletWorld world(b.model(), setup);
    world.remove_constraint(0);
    for (int i = 0; i < 120; ++i) world.step();
    return world.kinetic_energy();
}

TEST(Fracture, APairOverlappingWhenItsLastJointBreaksIgnoresItselfInsteadOfExploding) {
    // Pushing a 3 cm overlap out of b would stretch b's stiff joints to c, step after step, and
    // their ERP turns each stretch into speed (the plate's runaways: 4 J in one step).
    EXPECT_LT(kinetic_after_breaking_an_overlapping_pair(0.03), 1e-6);
    // Touching (no overlap) there is nothing to push: at rest either way.
    EXPECT_LT(kinetic_after_breaking_an_overlapping_pair(0.0), 1e-6);
}

// A 1 kg cube b hangs beside a fixed cube a, joined at the four corners of their shared face
// (x = 0): two stiff strong joints along one edge, two weak ones along the other, which b's
// weight breaks at once. `weak_top`: the weak ones are the top edge's, and b turns about the
// bottom edge, away from a (a crack that opens: the beam's hinge); else about the top edge, its
// bottom corners into a. Simulated for `seconds` at h = 1/960 s with direct joints.
SimulationResult hinged_cube(bool weak_top, double seconds) {
    BoxModelBuilder b;
    const uint32_t fixed = b.box(Vec3(-kSide / 2, 1, 0), Vec3::Constant(kSide));
    const uint32_t hanging = b.box(Vec3(kSide / 2, 1, 0), Vec3::Constant(kSide));
    for (double y : {1 - kSide / 2, 1 + kSide / 2})
        for (double z : {-kSide / 2, kSide / 2})
            b.join(fixed, hanging, Vec3(0, y, z), (y > 1) == weak_top ? 2.5e-5 : 2.5e-3);
    SimulationInput in;
    in.scene.ground = false;
    in.object.driven.push_back({fixed, true, Vec3::Zero(), {}});
    in.material.stiffness = 1e10;  // 2.5e7 N/m strong, 2.5e5 N/m weak
    in.material.strength = 2e4;    // 50 N strong, 0.5 N weak: b's weight loads each about 3.5 N
    in.simulate.joints = JointSolve::Direct;
    in.simulate.fps = 60;
    in.simulate.substeps = 16;
    in.simulate.duration = seconds;
    return simulate(b.take(), in, "test");
}

// Hinged about the top edge, b's bottom corners turn into a (joined pieces do not collide). The
// hinge breaks when the broken joints' pivots have passed into each other by kOverlapBreak of the
// cube's radius (sqrt(3) x 5 cm), at the time the pendulum's equation gives: I theta'' = m g x,
// I = m (s^2 / 6 + s^2 / 2) about the edge, x = (s / 2)(cos theta - sin theta) the centre's lever.
TEST(Fracture, AHingeTurningAPieceIntoItsNeighbourBreaksWhereThePendulumPredicts) {
    const SimulationResult r = hinged_cube(false, 0.2);
    ASSERT_TRUE(r.complete) << r.stop_reason;
    ASSERT_EQ(r.breaks.size(), 4u);
    const double radius = std::sqrt(3.0) * kSide / 2, limit = kOverlapBreak * radius;
    // How far the bottom pivots have passed into each other along the centres' line at theta
    // (about the hinge: b's bottom-left corner (0, -s) turned, a's staying; centres (s/2, -s/2)
    // turned and (-s/2, -s/2)).
    const auto depth = [](double t) {
        const double s = kSide, c = std::cos(t), n = std::sin(t);
        const Vec3 d(-s * n, s - s * c, 0);
        const Vec3 line(s / 2 * (c - n) + s / 2, -s / 2 * (n + c) + s / 2, 0);
        return -d.dot(line) / line.norm();
    };
    double theta = 0, omega = 0, t = 0;
    const double dt = 1e-6, inertia = kSide * kSide * (1.0 / 6 + 0.5);
    while (depth(theta) < limit) {
        omega += dt * 9.81 * kSide / 2 * (std::cos(theta) - std::sin(theta)) / inertia;
        theta += dt * omega;
        t += dt;
    }
    const double start = std::max(r.breaks[0].time, r.breaks[1].time);  // the weak joints
    EXPECT_EQ(r.breaks[0].overlap, 0.0);
    EXPECT_EQ(r.breaks[1].overlap, 0.0);
    EXPECT_LT(start, 0.01);
    for (int i = 2; i < 4; ++i) {
        const BreakRecord& hinge = r.breaks[size_t(i)];
        EXPECT_LT(hinge.force.norm(), hinge.strength);  // not by its load
        EXPECT_GT(hinge.overlap, limit);
        EXPECT_LT(hinge.overlap, limit + 1e-3);  // within a step's turn (b's bottom at 0.4 m/s: 0.4 mm)
        EXPECT_NEAR(hinge.time - start, t, 0.05 * t + 2.0 / 960) << "predicted " << t << " s after the weak joints";
    }
    // Through the usual break and its books: every break gives back alpha E, the first of the
    // two hinge joints' held until the second parts the pair.
    double given = 0, injected = 0;
    for (const BreakRecord& b : r.breaks) given += given_back(b), injected += b.injected_energy;
    EXPECT_GT(given, 0);
    EXPECT_NEAR(injected, given, 0.01 * given);
}

// Hinged about the bottom edge, b turns away from a (the crack opens): the hinge holds.
TEST(Fracture, AHingeThatOpensTheCrackHolds) {
    const SimulationResult r = hinged_cube(true, 0.15);
    ASSERT_TRUE(r.complete) << r.stop_reason;
    ASSERT_EQ(r.breaks.size(), 2u);  // the weak top joints only
    const Trajectory& t = r.trajectory;
    // b has turned (its centre dropped) about the edge that still holds it.
    EXPECT_LT(t.pose(t.frames() - 1, 1).position.y(), 1 - 0.01);
}

// A row of 30 boxes, each joined to the next, the last also to box 6; the joint between boxes 5
// and 6, and one of the two joints between boxes 2 and 3 and between 20 and 21, taken out. What
// a break's kicks act through then follows from the row: two fragments, of 6 and 24 boxes.
TEST(Fracture, ABreaksSidesAreItsPiecesFragmentsAndOnePastTheLimitMovesWhole) {
    BoxModelBuilder b;
    constexpr int kBoxes = 30;
    for (int i = 0; i < kBoxes; ++i) b.box(Vec3(kSide * i, 1, 0), Vec3::Constant(kSide));
    for (uint32_t i = 0; i + 1 < kBoxes; ++i) b.join(i, i + 1, Vec3(kSide * (i + 0.5), 1, 0));  // joint i
    b.join(20, 21, Vec3(kSide * 20.5, 1.01, 0));  // joint 29, beside joint 20
    b.join(2, 3, Vec3(kSide * 2.5, 1.01, 0));     // joint 30, beside joint 2
    b.join(6, 29, Vec3(kSide * 17.5, 1, 0));      // joint 31: a ring (searched from 6: 6, 7, 29, 8, 28, ...)
    WorldSetup setup;
    setup.scene.ground = false;
    BulletWorld world(b.model(), setup);
    for (size_t c : {5, 20, 2}) world.remove_constraint(c);
    BulletWorld::Fragments f;
    world.fragments(&f);
    ASSERT_EQ(f.first.size(), 3u);  // two fragments
    EXPECT_EQ(f.size(f.of[0]), 6u);
    EXPECT_EQ(f.size(f.of[6]), 24u);
    for (uint32_t p = 0; p < kBoxes; ++p) EXPECT_EQ(f.of[p], f.of[p < 6 ? 0 : 6]) << p;

    // Parted: box 5's side as the search reaches it, with its joints (ascending); box 6's, past
    // the limit, every piece ascending and no joints.
    BulletWorld::JoinedPieces parted;
    world.joined_pieces(5, kJoinedPiecesLimit, f, &parted);
    EXPECT_TRUE(parted.parted);
    EXPECT_FALSE(parted.held);
    ASSERT_EQ(parted.side_b, 6u);
    EXPECT_EQ(std::vector<uint32_t>(parted.pieces.begin(), parted.pieces.begin() + 6),
              (std::vector<uint32_t>{5, 4, 3, 2, 1, 0}));
    std::vector<uint32_t> large(24);
    for (uint32_t i = 0; i < 24; ++i) large[i] = 6 + i;
    EXPECT_EQ(std::vector<uint32_t>(parted.pieces.begin() + 6, parted.pieces.end()), large);
    EXPECT_EQ(parted.joints, (std::vector<uint32_t>{0, 1, 3, 4, 30}));

    // Not parted within the limit: the whole fragment, joints included.
    BulletWorld::JoinedPieces small;
    world.joined_pieces(2, kJoinedPiecesLimit, f, &small);
    EXPECT_FALSE(small.parted);
    EXPECT_FALSE(small.held);
    EXPECT_EQ(small.pieces, (std::vector<uint32_t>{2, 1, 3, 0, 4, 5}));
    EXPECT_EQ(small.side_b, 6u);

    // Not parted past the limit: held.
    BulletWorld::JoinedPieces held;
    world.joined_pieces(20, kJoinedPiecesLimit, f, &held);
    EXPECT_TRUE(held.held);
    EXPECT_FALSE(held.parted);
    EXPECT_TRUE(held.pieces.empty());
}

}  // namespace
}  // namespace shatter
