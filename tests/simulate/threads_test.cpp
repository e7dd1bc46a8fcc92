// The step's contact tests on several threads (core/workers.h, PieceDispatcher::workers):
// a run's result does not depend on the number of threads.
#include <gtest/gtest.h>
#include <sched.h>

#include <cstdlib>

#include "core/trajectory.h"
#include "scenes/box_model.h"
#include "simulate/simulate.h"
#include "core/workers.h"

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
    ASSERT_TRUE(one.complete) << one.stop_reason;
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

// The default is the cores the process may run on: on one core (a Slurm job given one CPU of a
// large node), one thread.
TEST(Threads, ByDefaultAsManyAsTheCoresTheProcessMayRunOn) {
    if (std::getenv("SHATTER_THREADS")) GTEST_SKIP() << "SHATTER_THREADS is set";
    cpu_set_t all, one;
    ASSERT_EQ(sched_getaffinity(0, sizeof(all), &all), 0);
    EXPECT_EQ(usable_cores(), unsigned(CPU_COUNT(&all)));
    int first = 0;
    while (!CPU_ISSET(first, &all)) ++first;
    CPU_ZERO(&one);
    CPU_SET(first, &one);
    ASSERT_EQ(sched_setaffinity(0, sizeof(one), &one), 0);  // this thread only
    const unsigned cores = usable_cores(), threads = default_threads();
    ASSERT_EQ(sched_setaffinity(0, sizeof(all), &all), 0);
    EXPECT_EQ(cores, 1u);
    EXPECT_EQ(threads, 1u);
}

}  // namespace
}  // namespace shatter
