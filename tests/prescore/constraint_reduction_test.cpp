#include <gtest/gtest.h>

#include "prescore/constraint_reduction.h"

namespace shatter {
namespace {

// A 5 x 5 grid of constraints of area 0.04 (1 m^2 in all) on the plane x = 0 between pieces 0
// and 1, and one constraint between pieces 1 and 2.
std::vector<Constraint> grid_pair() {
    std::vector<Constraint> c;
    for (uint32_t i = 0; i < 25; ++i) c.push_back({0, 1, i, Vec3(0, (i % 5) * 0.25, (i / 5) * 0.25), 0.04});
    c.push_back({1, 2, 99, Vec3(1, 0, 0), 0.5});
    return c;
}

TEST(ConstraintReduction, KeepsAtMostNPerPairWithThePairsTotalArea) {
    const auto out = reduce_constraints(grid_pair(), 4);
    ASSERT_EQ(out.size(), 5u);  // 4 for the grid pair, the single one untouched
    double area = 0;
    for (size_t i = 0; i < 4; ++i) {
        EXPECT_EQ(out[i].piece_a, 0u);
        area += out[i].area;
    }
    EXPECT_NEAR(area, 1.0, 1e-12);
    EXPECT_EQ(out[4].vertex, 99u);
    EXPECT_DOUBLE_EQ(out[4].area, 0.5);
}

TEST(ConstraintReduction, FarthestPointsSpanTheInterface) {
    const auto out = reduce_constraints(grid_pair(), 4);
    // The four corners of the 1 x 1 square are the farthest-point choice.
    std::vector<uint32_t> v;
    for (size_t i = 0; i < 4; ++i) v.push_back(out[i].vertex);
    EXPECT_EQ(v, (std::vector<uint32_t>{0, 4, 20, 24}));
}

TEST(ConstraintReduction, ZeroOrALargeLimitKeepsEverything) {
    EXPECT_EQ(reduce_constraints(grid_pair(), 0).size(), 26u);
    EXPECT_EQ(reduce_constraints(grid_pair(), 100).size(), 26u);
}

}  // namespace
}  // namespace shatter
