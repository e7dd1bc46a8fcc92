// Sleeping (simulate/bullet_world.h, WorldSetup::sleep_speed; [simulate] sleep): an island of
// pieces at rest stops being solved and moved, keeps its joints' forces, and wakes when something
// touches it.
#include <gtest/gtest.h>

#include <cmath>

#include "core/material_presets.h"
#include "scenes/box_model.h"
#include "simulate/bullet_world.h"
#include "simulate/simulate.h"

namespace shatter {
namespace {

// 3 x 3 joined cubes of 2 cm (a plate 6 cm wide, 0.2 kg), dropped 1 mm onto the ground.
Model plate() { return box_grid(3, 1, 3, 0.02, Vec3(-0.03, 0, -0.03), 2400, 2); }

WorldSetup resting(bool sleep) {
    WorldSetup setup;
    setup.object.pose.position = Vec3(0, 0.001, 0);
    setup.material.stiffness = 1e10;
    setup.material.strength = 1e9;  // never breaks
    setup.h = 1.0 / 240;
    setup.sleep_speed = sleep ? kSleepSpeed : 0;
    return setup;
}

// The books' sum that stays constant (docs/physics.md, "The books"), without breaks.
double books(const BulletWorld& w) {
    const BulletWorld::StepWork s = w.step_work();
    return w.kinetic_energy() + w.potential_energy() + w.elastic_energy() + s.joints + s.contacts + s.integration -
           s.driven;
}

// The plate lands, settles, and falls asleep kSleepTime after its pieces get slower than the sleep
// speed: from then on nothing moves (the same bytes step after step), its joints keep the forces
// of their last solve and leave the reported loads, and the books still close. It rests where the
// same plate never put to sleep rests, within how far that one still wanders (micrometres, at
// well under the sleep speed).
TEST(Sleep, APlateAtRestSleepsWhereItRestsAndKeepsItsBooks) {
    const Model model = plate();
    BulletWorld sleeping(model, resting(true)), awake(model, resting(false));
    const double start = books(sleeping);
    double asleep_at = -1, wander = 0;
    std::vector<Vec3> at_sleep(model.pieces.size());
    while (sleeping.time() < 1.0) {
        sleeping.step();
        awake.step();
        if (asleep_at < 0 && sleeping.sleeping_pieces() == model.pieces.size()) {
            asleep_at = sleeping.time();
            for (uint32_t i = 0; i < model.pieces.size(); ++i) at_sleep[i] = awake.piece_position(i);
        }
        if (asleep_at >= 0)
            for (uint32_t i = 0; i < model.pieces.size(); ++i)
                wander = std::max(wander, (awake.piece_position(i) - at_sleep[i]).norm());
    }
    ASSERT_GT(asleep_at, kSleepTime);  // it lands first, then stays slow for kSleepTime
    ASSERT_LT(asleep_at, 0.5);
    EXPECT_LT(wander, 1e-4);
    EXPECT_EQ(awake.sleeping_pieces(), 0u);
    EXPECT_NEAR(books(sleeping), start, 1e-9);
    EXPECT_NEAR(books(awake), start, 1e-9);
    EXPECT_EQ(sleeping.kinetic_energy(), 0.0);
    EXPECT_EQ(sleeping.max_load(), 0.0);
    for (size_t c = 0; c < sleeping.constraint_count(); ++c) EXPECT_FALSE(sleeping.awake(c));
    for (uint32_t i = 0; i < model.pieces.size(); ++i)
        EXPECT_LE((sleeping.piece_position(i) - awake.piece_position(i)).norm(), wander + 1e-6) << "piece " << i;
    std::vector<Vec3> position, force;
    for (uint32_t i = 0; i < model.pieces.size(); ++i) position.push_back(sleeping.piece_position(i));
    for (size_t c = 0; c < sleeping.constraint_count(); ++c) force.push_back(sleeping.force_on_a(c));
    for (int s = 0; s < 24; ++s) sleeping.step();
    for (uint32_t i = 0; i < model.pieces.size(); ++i) EXPECT_EQ(sleeping.piece_position(i), position[i]);
    for (size_t c = 0; c < sleeping.constraint_count(); ++c) EXPECT_EQ(sleeping.force_on_a(c), force[c]);
    EXPECT_NEAR(books(sleeping), start, 1e-9);
}

// A steel cube (2 cm, 62 g) dropped from 0.6 m above the plate lands on it after
// sqrt(2 x 0.6 / 9.81) = 0.35 s, after the plate fell asleep: the contact wakes the plate, and
// the cube comes to rest on top of it (its centre 2 cm up, plus its half size) instead of falling
// through, as on a plate that never slept; then the plate, ball and all, falls asleep again.
TEST(Sleep, ABallLandingOnASleepingPlateWakesItAndRestsOnIt) {
    const Model model = plate();
    WorldSetup setup = resting(true);
    setup.h = 1.0 / 1000;
    ProjectileSettings ball;
    ball.shape.size = Vec3::Constant(0.02);
    ball.pose.position = Vec3(0, 0.02 + 0.01 + 0.6, 0);
    ball.surface.restitution = 0;
    setup.scene.projectiles.push_back(ball);
    WorldSetup never = setup;
    never.sleep_speed = 0;
    BulletWorld world(model, setup), control(model, never);
    const double landing = std::sqrt(2 * 0.6 / 9.81);
    bool slept = false, woke = false;
    while (world.time() < landing - 0.005) {
        world.step();
        control.step();
        slept = slept || world.sleeping_pieces() == model.pieces.size();
    }
    ASSERT_TRUE(slept);
    ASSERT_EQ(world.sleeping_pieces(), model.pieces.size());
    while (world.time() < landing + 0.02) {
        world.step();
        control.step();
        woke = woke || world.sleeping_pieces() == 0;
    }
    EXPECT_TRUE(woke);
    while (world.time() < landing + 1.0) {
        world.step();
        control.step();
    }
    // The cube is the first prop; its centre rests half its size above the plate's top.
    EXPECT_NEAR(world.prop_pose(0).position.y(), 0.02 + 0.01, 1e-3);
    EXPECT_NEAR(control.prop_pose(0).position.y(), 0.02 + 0.01, 1e-3);
    EXPECT_EQ(world.sleeping_pieces(), model.pieces.size());
}

// A piece joined to a driven piece is loaded by a script: it never sleeps, nor does anything
// joined to it.
TEST(Sleep, PiecesJoinedToADrivenPieceStayAwake) {
    const Model model = plate();
    WorldSetup setup = resting(true);
    PieceDriveSettings fixed;
    fixed.piece = 4;  // the middle cube, held in place
    fixed.fixed = true;
    setup.object.driven.push_back(fixed);
    BulletWorld world(model, setup);
    while (world.time() < 1.0) world.step();
    EXPECT_EQ(world.sleeping_pieces(), 0u);
    for (size_t c = 0; c < world.constraint_count(); ++c) {
        if (world.active(c)) {
            EXPECT_TRUE(world.awake(c));
        }
    }
}

// The automatic step (substeps = "auto"): a porcelain bar of five 2 cm cubes lying across two
// supports 8 cm apart, its joints bent by its weight and solved one row at a time (direct joints
// hold its stretch to their forces at any step: awake, it then runs the longest step too). Awake,
// a longer step shows more stretch than the joints' forces hold (the pivots parted within a step
// grow as its square): at 4 steps a block it passes half the strength, so it lies there in 8 steps
// a block (1/3,840 s). Asleep, nothing moves and no joint is counted: every step is the longest
// calm step, kAutoMaxSpan blocks.
TEST(Sleep, ASleepingObjectRunsTheAutomaticStepAtItsLongestStep) {
    const Model model = box_grid(5, 1, 1, 0.02, Vec3(-0.05, 0, -0.01), 2400, 2);
    SimulationInput in;
    in.scene.ground = false;
    for (double x : {-0.04, 0.04}) {
        ColliderSettings support;
        support.shape.size = Vec3(0.02, 0.1, 0.04);
        support.pose.position = Vec3(x, -0.05, 0);
        in.scene.colliders.push_back(support);
    }
    in.object.pose.position = Vec3(0, 0.0005, 0);
    apply_material_preset(*find_material_preset("porcelain"), in.material);
    in.material.strength = 1e6;  // nothing breaks
    in.simulate.auto_substeps = true;
    in.simulate.joints = JointSolve::Iterative;
    in.simulate.fps = 30;
    const auto run = [&](double duration, bool sleep) {
        in.simulate.duration = duration;
        in.simulate.sleep = sleep;
        const SimulationResult r = simulate(model, in, "test");
        EXPECT_TRUE(r.complete);
        EXPECT_TRUE(r.breaks.empty());
        return r.steps;
    };
    // It sleeps by 0.3 s (measured: 0.27 s): from then on one step per kAutoMaxSpan blocks, 144 in
    // 0.6 s.
    const uint64_t slept = run(0.4, true);
    EXPECT_EQ(run(1.0, true) - slept, uint64_t(std::llround(0.6 / (kAutoMaxSpan * kAutoBlock))));
    // Awake, the same 0.6 s take 8 steps in each of its 288 blocks (more than 4 asserted).
    EXPECT_GT(run(1.0, false) - run(0.4, false), uint64_t(4 * std::llround(0.6 / kAutoBlock)));
}

}  // namespace
}  // namespace shatter
