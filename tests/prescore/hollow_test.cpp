// Hollowing: the shell predicted by the distance rule, cavity walls, connectivity repair.
#include "prescore/hollow.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/error.h"
#include "prescore/tet_test_meshes.h"

namespace shatter {
namespace {

int32_t components(const TetMesh& mesh) {
    int32_t count = 0;
    tet_components(build_topology(mesh), {}, &count);
    return count;
}

Vec3 centroid(const TetMesh& mesh, const Tet& t) {
    return 0.25 * (mesh.vertices[t[0]] + mesh.vertices[t[1]] + mesh.vertices[t[2]] + mesh.vertices[t[3]]);
}

TEST(Hollow, CubeKeepsExactlyTheTwoCellShell) {
    // 12^3 cells of h; thickness 2h. Centroids of cells in layers 0-1 lie within 1.75h of the
    // outside, those of deeper cells at least 2.25h away: the inner 8^3 cells go, exactly.
    const double h = 0.05;
    const TetMesh mesh = test::cube_grid(12, 12, 12, h);
    const HollowResult r = hollow(mesh, build_topology(mesh), 2 * h);
    EXPECT_EQ(r.removed, size_t(8 * 8 * 8 * 6));
    EXPECT_EQ(r.restored, 0u);
    ASSERT_EQ(r.mesh.tets.size(), mesh.tets.size() - r.removed);
    EXPECT_NEAR(test::total_volume(r.mesh), (12 * 12 * 12 - 8 * 8 * 8) * h * h * h, 1e-12);
    EXPECT_EQ(components(r.mesh), 1);
    for (size_t t = 0; t < r.mesh.tets.size(); ++t) {
        const Vec3 c = centroid(mesh, mesh.tets[r.source_tet[t]]);
        EXPECT_LE(std::min(c.minCoeff(), 12 * h - c.maxCoeff()), 2 * h);
        EXPECT_EQ(centroid(r.mesh, r.mesh.tets[t]), c);  // the kept tet is the source tet
    }
    // The cavity wall is the surface of the removed 8^3 cube: area 6 (8h)^2.
    double cavity_area = 0;
    for (size_t t = 0; t < r.mesh.tets.size(); ++t) {
        for (int i = 0; i < 4; ++i) {
            if (!r.cavity_face[t][i]) continue;
            const Tet& tet = r.mesh.tets[t];
            const Vec3& a = r.mesh.vertices[tet[kTetFaces[i][0]]];
            const Vec3& b = r.mesh.vertices[tet[kTetFaces[i][1]]];
            const Vec3& c = r.mesh.vertices[tet[kTetFaces[i][2]]];
            cavity_area += 0.5 * (b - a).cross(c - a).norm();
        }
    }
    EXPECT_NEAR(cavity_area, 6 * 64 * h * h, 1e-12);
}

TEST(Hollow, CavityFacesAreExactlyTheNewBoundaryFaces) {
    const TetMesh mesh = test::spherical_shell(1.0, 0.2, 2, 6);
    const TetTopology before = build_topology(mesh);
    const HollowResult r = hollow(mesh, before, 0.3);
    EXPECT_GT(r.removed, 0u);
    const TetTopology after = build_topology(r.mesh);
    size_t cavity = 0;
    for (size_t t = 0; t < r.mesh.tets.size(); ++t) {
        for (int i = 0; i < 4; ++i) {
            const bool was_interior = before.neighbour[r.source_tet[t]][i] >= 0;
            const bool now_boundary = after.neighbour[t][i] < 0;
            EXPECT_EQ(r.cavity_face[t][i], was_interior && now_boundary);
            cavity += r.cavity_face[t][i];
        }
    }
    EXPECT_GT(cavity, 0u);
}

TEST(Hollow, InternalVoidKeepsTwoShellsJoinedByARestoredBridge) {
    // A 14^3 block with a 2^3 void in the middle: the outer shell and the shell around the void
    // are separated by removed tets, so hollowing must restore a short path between them.
    const TetMesh mesh = test::cube_grid(14, 14, 14, 1.0, Vec3::Zero(), [](int i, int j, int k) {
        return !(i >= 6 && i < 8 && j >= 6 && j < 8 && k >= 6 && k < 8);
    });
    const HollowResult r = hollow(mesh, build_topology(mesh), 1.5);
    EXPECT_EQ(components(r.mesh), 1);
    EXPECT_GT(r.restored, 0u);
    EXPECT_LT(r.restored, 20u);  // a path across ~2 cells, not a slab
    EXPECT_EQ(r.removed + r.mesh.tets.size(), mesh.tets.size());
}

TEST(Hollow, DumbbellWithThinNeckStaysOneComponent) {
    // Two 6^3 blocks joined by a 1 x 1 neck, 4 cells long: the neck lies wholly in the shell.
    const TetMesh mesh = test::cube_grid(16, 6, 6, 1.0, Vec3::Zero(), [](int i, int j, int k) {
        return i < 6 || i >= 10 || (j == 2 && k == 2);
    });
    const HollowResult r = hollow(mesh, build_topology(mesh), 1.0);
    EXPECT_GT(r.removed, 0u);
    EXPECT_EQ(components(r.mesh), 1);
}

TEST(Hollow, SeparateObjectsStaySeparate) {
    TetMesh mesh = test::cube_grid(6, 6, 6, 1.0);
    test::append(mesh, test::cube_grid(6, 6, 6, 1.0, Vec3(10, 0, 0)));
    const HollowResult r = hollow(mesh, build_topology(mesh), 1.0);
    EXPECT_EQ(r.removed, size_t(2 * 4 * 4 * 4 * 6));
    EXPECT_EQ(components(r.mesh), 2);
}

TEST(Hollow, ThinShellStaysClosedAndConnected) {
    // Thickness far below a tet: only tets touching the outside remain, and they are joined.
    const TetMesh mesh = test::cube_grid(8, 8, 8, 1.0);
    const HollowResult r = hollow(mesh, build_topology(mesh), 0.01);
    EXPECT_EQ(components(r.mesh), 1);
    const TetTopology topology = build_topology(r.mesh);
    size_t outer = 0;
    for (size_t t = 0; t < r.mesh.tets.size(); ++t)
        for (int i = 0; i < 4; ++i) outer += topology.neighbour[t][i] < 0 && !r.cavity_face[t][i];
    EXPECT_EQ(outer, size_t(2 * 6 * 64));  // the outside surface is intact
}

TEST(Hollow, SameInputSameShell) {
    const TetMesh mesh = test::spherical_shell(1.0, 0.1, 2, 8);
    const TetTopology topology = build_topology(mesh);
    const HollowResult a = hollow(mesh, topology, 0.25);
    const HollowResult b = hollow(mesh, topology, 0.25);
    EXPECT_EQ(a.source_tet, b.source_tet);
    EXPECT_EQ(a.cavity_face, b.cavity_face);
    EXPECT_EQ(a.restored, b.restored);
}

TEST(Hollow, NonPositiveOrNonFiniteThicknessIsAnInputError) {
    const TetMesh mesh = test::cube_grid(2, 2, 2, 1.0);
    const TetTopology topology = build_topology(mesh);
    for (double t : {0.0, -1.0, double(NAN), double(INFINITY)}) EXPECT_THROW(hollow(mesh, topology, t), Error) << t;
}

}  // namespace
}  // namespace shatter
