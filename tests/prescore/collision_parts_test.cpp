// Collision parts: as few convex parts as keep a piece's shape.
#include "prescore/collision_parts.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/error.h"
#include "prescore/convex_hull.h"
#include "prescore/tet_test_meshes.h"

namespace shatter {
namespace {

double sum_volume(const std::vector<ConvexPart>& parts) {
    double v = 0;
    for (const ConvexPart& p : parts) v += p.volume;
    return v;
}

double sum_hull_volume(const std::vector<ConvexPart>& parts) {
    double v = 0;
    for (const ConvexPart& p : parts) v += p.hull_volume;
    return v;
}

TEST(ConvexHull, BoxGridHullIsItsEightCornersAndVolume) {
    const TetMesh mesh = test::cube_grid(3, 2, 2, 0.5);
    double volume = 0;
    const std::vector<Vec3> hull = convex_hull_points(mesh.vertices, &volume);
    EXPECT_EQ(hull.size(), 8u);
    EXPECT_NEAR(volume, 1.5 * 1.0 * 1.0, 1e-12);
    EXPECT_EQ(hull.front(), Vec3(0, 0, 0));  // sorted lexicographically
    EXPECT_EQ(hull.back(), Vec3(1.5, 1, 1));
}

TEST(ConvexHull, CoplanarPointsHaveNoVolume) {
    double volume = -1;
    const std::vector<Vec3> flat = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}, {2, 3, 0}};
    EXPECT_EQ(convex_hull_points(flat, &volume).size(), 5u);
    EXPECT_EQ(volume, 0.0);
}

TEST(CollisionParts, ConvexBlockIsOnePart) {
    const TetMesh mesh = test::cube_grid(3, 2, 2, 0.5);
    const std::vector<ConvexPart> parts = collision_parts(mesh, test::all_tets(mesh), {});
    ASSERT_EQ(parts.size(), 1u);
    EXPECT_NEAR(parts[0].volume, 1.5, 1e-12);
    EXPECT_NEAR(parts[0].hull_volume, 1.5, 1e-12);
    EXPECT_EQ(parts[0].points.size(), 8u);
}

TEST(CollisionParts, LShapedBlockSplitsIntoTwoOrThreeTightParts) {
    // 6 x 6 square minus a 4 x 4 corner, 1 cell thick: area 20, filled hull 28 (40% excess).
    const TetMesh mesh = test::cube_grid(6, 6, 1, 1.0, Vec3::Zero(), [](int i, int j, int) { return i < 2 || j < 2; });
    const CollisionSettings settings;
    const std::vector<ConvexPart> parts = collision_parts(mesh, test::all_tets(mesh), settings);
    EXPECT_GE(parts.size(), 2u);
    EXPECT_LE(parts.size(), 3u);
    for (const ConvexPart& p : parts) EXPECT_NEAR(p.hull_volume, p.volume, 1e-9);  // max_gap 0: exactly convex
    EXPECT_NEAR(sum_volume(parts), 20.0, 1e-9);
}

TEST(CollisionParts, MaxPartsOneGivesTheFilledHull) {
    const TetMesh mesh = test::cube_grid(6, 6, 1, 1.0, Vec3::Zero(), [](int i, int j, int) { return i < 2 || j < 2; });
    CollisionSettings settings;
    settings.max_parts = 1;
    const std::vector<ConvexPart> parts = collision_parts(mesh, test::all_tets(mesh), settings);
    ASSERT_EQ(parts.size(), 1u);
    EXPECT_NEAR(parts[0].hull_volume, 28.0, 1e-9);
}

TEST(CollisionParts, HollowShellPieceCollidesFarTighterThanItsFilledHull) {
    // The upper half of a thin spherical shell (R = 1, r = 0.9): as one hull it would fill the
    // half ball; split into caps it follows the shell.
    const TetMesh mesh = test::spherical_shell(1.0, 0.9, 3, 2);
    std::vector<uint32_t> piece;
    for (uint32_t t = 0; t < mesh.tets.size(); ++t) {
        const Tet& tet = mesh.tets[t];
        if ((mesh.vertices[tet[0]] + mesh.vertices[tet[1]] + mesh.vertices[tet[2]] + mesh.vertices[tet[3]]).z() > 0) {
            piece.push_back(t);
        }
    }
    CollisionSettings one;
    one.max_parts = 1;
    const double filled = collision_parts(mesh, piece, one)[0].hull_volume;
    const std::vector<ConvexPart> parts = collision_parts(mesh, piece, {});
    EXPECT_GT(parts.size(), 4u);
    EXPECT_LE(parts.size(), 16u);
    const double volume = sum_volume(parts);
    EXPECT_NEAR(volume, 4.0 / 3.0 * M_PI * (1 - 0.9 * 0.9 * 0.9) / 2, 0.02 * volume);
    EXPECT_GT(filled, 3.5 * volume);                   // the filled hull is mostly air
    EXPECT_LT(sum_hull_volume(parts), 0.55 * filled);  // measured 0.49
}

TEST(CollisionParts, WholeShellStaysBelowTheFilledBallAtTheDefaultPartLimit) {
    const TetMesh mesh = test::spherical_shell(1.0, 0.85, 3, 2);
    const std::vector<ConvexPart> parts = collision_parts(mesh, test::all_tets(mesh), {});
    EXPECT_EQ(parts.size(), 16u);  // a closed shell cannot be tight with 16 convex parts
    EXPECT_NEAR(sum_volume(parts), test::total_volume(mesh), 1e-9);
    EXPECT_LT(sum_hull_volume(parts), 0.85 * 4.0 / 3.0 * M_PI);  // measured 0.81 of the ball
}

TEST(CollisionParts, EachPartsMeanGapStaysWithinTheToleranceWithFewerParts) {
    // Half of a shell 0.1 thick: a gap tolerance of 0.02 needs fewer parts than exact convexity,
    // and every part's mean gap (hull volume - volume) / hull area is within it.
    const TetMesh mesh = test::spherical_shell(1.0, 0.9, 3, 2);
    std::vector<uint32_t> piece;
    for (uint32_t t = 0; t < mesh.tets.size(); ++t) {
        const Tet& tet = mesh.tets[t];
        if ((mesh.vertices[tet[0]] + mesh.vertices[tet[1]] + mesh.vertices[tet[2]] + mesh.vertices[tet[3]]).z() > 0)
            piece.push_back(t);
    }
    CollisionSettings loose;
    loose.max_gap = 0.02;
    loose.max_parts = 64;
    CollisionSettings exact;
    exact.max_parts = 64;
    const auto parts = collision_parts(mesh, piece, loose);
    EXPECT_LT(parts.size(), collision_parts(mesh, piece, exact).size());
    for (const ConvexPart& p : parts) {
        double volume = 0, area = 0;
        convex_hull_points(p.points, &volume, &area);
        EXPECT_LE((p.hull_volume - p.volume) / area, 0.02 + 1e-12);
    }
}

TEST(CollisionParts, SameInputSameParts) {
    const TetMesh mesh = test::spherical_shell(1.0, 0.8, 2, 2);
    const auto a = collision_parts(mesh, test::all_tets(mesh), {});
    const auto b = collision_parts(mesh, test::all_tets(mesh), {});
    ASSERT_EQ(a.size(), b.size());
    for (size_t i = 0; i < a.size(); ++i) {
        EXPECT_EQ(a[i].points, b[i].points);
        EXPECT_EQ(a[i].volume, b[i].volume);
        EXPECT_EQ(a[i].hull_volume, b[i].hull_volume);
    }
}

TEST(CollisionParts, OutOfRangeSettingsAreInputErrors) {
    const TetMesh mesh = test::cube_grid(1, 1, 1, 1.0);
    CollisionSettings zero_parts;
    zero_parts.max_parts = 0;
    EXPECT_THROW(collision_parts(mesh, {0}, zero_parts), Error);
    CollisionSettings negative;
    negative.max_gap = -0.1;
    EXPECT_THROW(collision_parts(mesh, {0}, negative), Error);
}

}  // namespace
}  // namespace shatter
