// SimulationResult::deepest and its warning (simulate/simulate.h, kDeepContactWarning): a piece
// that moves further in a step than its own size is found inside what it hits as deep as the step
// took it (no deeper: the ground's contact holds the whole base, not one corner a step about which
// it would pivot while the others go on down, 40 mm for the 11.7 mm below; bullet_world_impl.h),
// and the run says which finer step lets it in less deep.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "scenes/box_model.h"
#include "simulate/simulate.h"

namespace shatter {
namespace {

constexpr double kSide = 0.01;  // a 1 cm cube: radius (half its diagonal) 8.66 mm
constexpr double kDrop = 1.0;   // its base this high above the ground (unit: m)

SimulationInput dropped_cube(uint32_t substeps) {
    SimulationInput in;
    in.object.pose.position = Vec3(0, kDrop, 0);
    in.simulate.fps = 30;
    in.simulate.substeps = substeps;
    in.simulate.duration = 0.6;  // it lands at sqrt(2 x 1 / 9.81) = 0.452 s
    return in;
}

// Where the cube's base is after the first step that takes it below the ground: Bullet's (and
// rigid flight's) symplectic Euler, v += g h, then x += v h, from rest (unit: m, negative).
double base_after_first_step_below(double h) {
    double base = kDrop, v = 0;
    while (base >= 0) {
        v -= 9.81 * h;
        base += v * h;
    }
    return base;
}

TEST(DeepContact, APieceFasterThanItsSizeAStepIsFoundAsDeepAsTheStepTookItAndWarned) {
    const Model cube = box_grid(1, 1, 1, kSide, Vec3(-kSide / 2, 0, -kSide / 2), 2400, 2);
    const uint32_t substeps = 4;  // h = 1/120 s: 37 mm a step at the landing's 4.4 m/s
    const double h = 1.0 / (30 * substeps);
    const SimulationResult r = simulate(cube, dropped_cube(substeps), "test");
    ASSERT_TRUE(r.complete) << r.stop_reason;
    const double depth = -base_after_first_step_below(h);
    const double radius = std::sqrt(3.0) * kSide / 2;
    ASSERT_GT(depth, radius);  // 11.7 mm: the step before, its base was 25 mm up
    EXPECT_NEAR(r.deepest.depth, depth, 2e-4);  // Bullet's collision margin rounds the corners
    EXPECT_NEAR(r.deepest.depth_per_radius, r.deepest.depth / radius, 1e-9);
    EXPECT_EQ(r.deepest.piece, 0u);
    EXPECT_NEAR(r.deepest_step, h, 1e-12);
    // The finer step named: 2^k times shorter, k the least that brings depth / radius under 1/2.
    uint32_t factor = 1;
    while (r.deepest.depth_per_radius / factor > 0.5) factor *= 2;
    const std::string named = "[simulate] substeps = " + std::to_string(substeps * factor) + " ";
    bool warned = false;
    for (const std::string& w : r.warnings) warned = warned || w.find(named) != std::string::npos;
    EXPECT_TRUE(warned) << named << " in " << (r.warnings.empty() ? std::string("no warning") : r.warnings[0]);
}

TEST(DeepContact, AStepShorterThanThePiecesSizeAtItsSpeedIsNotWarned) {
    const Model cube = box_grid(1, 1, 1, kSide, Vec3(-kSide / 2, 0, -kSide / 2), 2400, 2);
    const uint32_t substeps = 64;  // h = 1/1920 s: 2.3 mm a step at 4.4 m/s
    const SimulationResult r = simulate(cube, dropped_cube(substeps), "test");
    ASSERT_TRUE(r.complete) << r.stop_reason;
    EXPECT_GT(r.deepest.depth, -base_after_first_step_below(1.0 / (30 * substeps)) - 2e-4);
    EXPECT_LT(r.deepest.depth_per_radius, kDeepContactWarning);
    for (const std::string& w : r.warnings) EXPECT_EQ(w.find("inside what it touches"), std::string::npos) << w;
}

}  // namespace
}  // namespace shatter
