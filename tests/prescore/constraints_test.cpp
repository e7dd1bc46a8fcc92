// Constraint placement on meshes whose shared faces are known by hand.
#include "prescore/constraints.h"

#include <gtest/gtest.h>

#include <tuple>

#include "prescore/tet_test_meshes.h"

namespace shatter {
namespace {

// Pieces by cell: tets are emitted 6 per cell in x-fastest cell order.
std::vector<uint32_t> piece_per_cell(const TetMesh& mesh, const std::vector<uint32_t>& cell_piece) {
    std::vector<uint32_t> tet_piece(mesh.tets.size());
    for (size_t t = 0; t < tet_piece.size(); ++t) tet_piece[t] = cell_piece[t / 6];
    return tet_piece;
}

double total_area(const std::vector<Constraint>& cs, uint32_t a, uint32_t b) {
    double sum = 0;
    for (const Constraint& c : cs)
        if (c.piece_a == a && c.piece_b == b) sum += c.area;
    return sum;
}

TEST(Constraints, TwoTetsSharingOneFaceGiveThreeConstraintsOfAThirdOfItsArea) {
    TetMesh mesh;
    mesh.vertices = {{0, 0, 0}, {2, 0, 0}, {0, 3, 0}, {0, 0, 1}, {0, 0, -1}};
    mesh.tets = {{0, 1, 2, 3}, {0, 1, 2, 4}};  // share the triangle (0, 1, 2) of area 3
    for (Tet& t : mesh.tets) test::orient(mesh, t);
    const TetTopology topology = build_topology(mesh);
    const std::vector<Constraint> cs = place_constraints(mesh, topology, {1, 0});
    ASSERT_EQ(cs.size(), 3u);
    for (uint32_t v = 0; v < 3; ++v) {
        EXPECT_EQ(cs[v].piece_a, 0u);
        EXPECT_EQ(cs[v].piece_b, 1u);
        EXPECT_EQ(cs[v].vertex, v);
        EXPECT_EQ(cs[v].pivot, mesh.vertices[v]);
        EXPECT_DOUBLE_EQ(cs[v].area, 1.0);
    }
    EXPECT_TRUE(place_constraints(mesh, topology, {0, 0}).empty());  // same piece: none
}

TEST(Constraints, TwoCubesSplitAtTheMiddlePlaneJoinAtTheFourSquareCorners) {
    const TetMesh mesh = test::cube_grid(2, 1, 1, 1.0);
    const std::vector<Constraint> cs = place_constraints(mesh, build_topology(mesh), piece_per_cell(mesh, {0, 1}));
    ASSERT_EQ(cs.size(), 4u);  // the distinct vertices of the shared unit square at x = 1
    double sum = 0;
    for (const Constraint& c : cs) {
        EXPECT_EQ(c.pivot.x(), 1.0);
        sum += c.area;
        // Corners on the square's diagonal touch both of its triangles: 2 * (1/2) / 3.
        const bool diagonal = c.pivot.y() == c.pivot.z();
        EXPECT_DOUBLE_EQ(c.area, diagonal ? 1.0 / 3.0 : 1.0 / 6.0);
    }
    EXPECT_DOUBLE_EQ(sum, 1.0);
}

TEST(Constraints, FourQuadrantsJoinOnlyAcrossSharedFacesAndComeSorted) {
    const TetMesh mesh = test::cube_grid(2, 2, 1, 0.5);  // cells (0,0) (1,0) (0,1) (1,1)
    const std::vector<uint32_t> tet_piece = piece_per_cell(mesh, {0, 1, 2, 3});
    const std::vector<Constraint> cs = place_constraints(mesh, build_topology(mesh), tet_piece);
    for (size_t i = 1; i < cs.size(); ++i) {
        EXPECT_LT(std::tie(cs[i - 1].piece_a, cs[i - 1].piece_b, cs[i - 1].vertex),
                  std::tie(cs[i].piece_a, cs[i].piece_b, cs[i].vertex));
    }
    for (const Constraint& c : cs) EXPECT_LT(c.piece_a, c.piece_b);
    // Face neighbours share a 0.5 x 0.5 square; diagonal cells touch along an edge only.
    EXPECT_DOUBLE_EQ(total_area(cs, 0, 1), 0.25);
    EXPECT_DOUBLE_EQ(total_area(cs, 0, 2), 0.25);
    EXPECT_DOUBLE_EQ(total_area(cs, 1, 3), 0.25);
    EXPECT_DOUBLE_EQ(total_area(cs, 2, 3), 0.25);
    EXPECT_EQ(total_area(cs, 0, 3), 0.0);
    EXPECT_EQ(total_area(cs, 1, 2), 0.0);
    EXPECT_EQ(cs.size(), 16u);  // 4 pairs x 4 square corners
}

TEST(Constraints, PairAreasSumToTheSharedArea) {
    const TetMesh mesh = test::cube_grid(4, 3, 2, 0.25);
    std::vector<uint32_t> tet_piece(mesh.tets.size());
    for (size_t t = 0; t < tet_piece.size(); ++t) tet_piece[t] = (t / 6) % 4 < 2 ? 0 : 1;  // split at x = 0.5
    const std::vector<Constraint> cs = place_constraints(mesh, build_topology(mesh), tet_piece);
    EXPECT_NEAR(total_area(cs, 0, 1), 0.75 * 0.5, 1e-14);
    EXPECT_EQ(cs.size(), size_t(4 * 3));  // vertices of the 3 x 2 cell interface
}

}  // namespace
}  // namespace shatter
