// The step's contact tests on several threads (simulate/workers.h, PieceDispatcher::workers):
// a run's result does not depend on the number of threads.
#include <gtest/gtest.h>

#include "core/trajectory.h"
#include "scenes/box_model.h"
#include "simulate/simulate.h"

namespace shatter {
namespace {

// A 6 x 2 x 6 slab of 2 cm cubes (72 pieces), its joints weak, dropped 30 cm onto the ground: it
// shatters, and the fragments tumble against each other and the ground.
SimulationResult shattered_slab(unsigned threads) {
    SimulationInput in;
    in.object.pose.position = Vec3(0, 0.3, 0);
    in.object.pose.rotation_deg = Vec3(15, 30, 10);
    in.material.stiffness = 1e10;
    in.material.strength = 2e4;
    in.simulate.duration = 0.5;
    in.simulate.fps = 60;
    in.simulate.substeps = 8;
    in.threads = threads;
    return simulate(box_grid(6, 2, 6, 0.02, Vec3(-0.06, 0, -0.06), 2400, 2), in, "test");
}

TEST(Threads, AnyNumberOfThreadsGivesTheSameRun) {
    const SimulationResult one = shattered_slab(1);
    ASSERT_TRUE(one.complete);
    EXPECT_EQ(one.parallel_contact_tests, 0u);
    // It did shatter: most joints broke, into many fragments that touch.
    ASSERT_GT(one.breaks.size(), 200u);
    const std::string bytes = encode_trajectory(one.trajectory);
    for (unsigned threads : {2u, 3u}) {
        const SimulationResult many = shattered_slab(threads);
        // The contact tests ran on the workers (pairs in contact or near it, every step).
        EXPECT_GT(many.parallel_contact_tests, 20000u) << threads << " threads";
        ASSERT_EQ(many.breaks.size(), one.breaks.size()) << threads << " threads";
        EXPECT_TRUE(encode_trajectory(many.trajectory) == bytes) << threads << " threads";
    }
}

}  // namespace
}  // namespace shatter
