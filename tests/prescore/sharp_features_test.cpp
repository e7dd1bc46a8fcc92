#include <gtest/gtest.h>

#include <cmath>

#include "meshio/mesh_load.h"
#include "prescore/sharp_features.h"
#include "tet_test_meshes.h"

namespace shatter {
namespace {

TriangleMesh box(double x, double y, double z) {
    TriangleMesh m;
    for (int i = 0; i < 8; ++i)
        m.vertices.emplace_back(x * (i == 1 || i == 2 || i == 5 || i == 6), y * (i == 2 || i == 3 || i == 6 || i == 7),
                                z * (i >= 4));
    m.triangles = {{0, 2, 1}, {0, 3, 2}, {4, 5, 6}, {4, 6, 7}, {0, 1, 5}, {0, 5, 4},
                   {3, 7, 6}, {3, 6, 2}, {0, 4, 7}, {0, 7, 3}, {1, 2, 6}, {1, 6, 5}};
    return m;
}

TEST(SharpFeatures, ABoxHasTwelveEdgesEndingAtItsCorners) {
    const auto lines = sharp_polylines(box(2, 1, 0.5), 60, 0.1);
    ASSERT_EQ(lines.size(), 12u);
    double length = 0;
    for (const Polyline& l : lines) {
        ASSERT_EQ(l.size(), 2u);  // corner to corner: each box edge is one mesh edge
        length += (l[1] - l[0]).norm();
    }
    EXPECT_NEAR(length, 4 * (2 + 1 + 0.5), 1e-12);
}

TEST(SharpFeatures, CreasesShorterThanTheMinimumLengthAreDropped) {
    EXPECT_EQ(sharp_polylines(box(2, 1, 0.5), 60, 0.75).size(), 8u);  // the four 0.5 edges go
}

TEST(SharpFeatures, ASmoothSphereHasNone) {
    EXPECT_TRUE(sharp_polylines(test::icosphere(3), 60, 0.0).empty());
}

TEST(SharpFeatures, TheBunnysCreasesAreAllShorterThanATenthOfItsDiagonal) {
    const std::string bunny = "/usr/share/glmark2/models/bunny.obj";
    const TriangleMesh mesh = load_mesh(bunny, 1.0);
    const double diagonal = std::sqrt(2.0 * 2.0 + 1.982 * 1.982 + 1.55 * 1.55);
    EXPECT_TRUE(sharp_polylines(mesh, 60, 0.1 * diagonal).empty());
    EXPECT_FALSE(sharp_polylines(mesh, 60, 0.015 * diagonal).empty());  // short scan creases exist
}

}  // namespace
}  // namespace shatter
