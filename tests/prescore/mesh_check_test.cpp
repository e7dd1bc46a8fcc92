// check_mesh counts what the geometry of small hand-made meshes predicts; orient_outward and
// can_tetrahedralize act on those counts; alpha_wrap closes an open cube.
#include <gtest/gtest.h>

#include "prescore/mesh_check.h"
#include "prescore/repair.h"

namespace shatter {
namespace {

// The unit cube [0,1]^3 moved by `offset`, appended to `mesh` (12 outward triangles).
void add_cube(TriangleMesh& mesh, const Vec3& offset = Vec3::Zero()) {
    const uint32_t base = uint32_t(mesh.vertices.size());
    for (int i = 0; i < 8; ++i) {
        const Vec3 corner((i == 1 || i == 2 || i == 5 || i == 6), (i == 2 || i == 3 || i == 6 || i == 7), i >= 4);
        mesh.vertices.push_back(corner + offset);
    }
    const Tri faces[12] = {{0, 2, 1}, {0, 3, 2}, {4, 5, 6}, {4, 6, 7}, {0, 1, 5}, {0, 5, 4},
                           {3, 7, 6}, {3, 6, 2}, {0, 4, 7}, {0, 7, 3}, {1, 2, 6}, {1, 6, 5}};
    for (Tri t : faces) mesh.triangles.push_back({base + t[0], base + t[1], base + t[2]});
}

TriangleMesh unit_cube() {
    TriangleMesh mesh;
    add_cube(mesh);
    return mesh;
}

// Replaces every vertex by the first vertex at the same position (as load_mesh does).
void merge_equal_positions(TriangleMesh& mesh) {
    for (Tri& t : mesh.triangles)
        for (uint32_t& v : t)
            for (uint32_t first = 0; first < v; ++first)
                if (mesh.vertices[first] == mesh.vertices[v]) {
                    v = first;
                    break;
                }
}

TEST(CheckMesh, UnitCubeIsClosedManifoldOrientedWithVolumeOneAreaSix) {
    const MeshCheck c = check_mesh(unit_cube());
    EXPECT_EQ(c.vertices, 8u);
    EXPECT_EQ(c.triangles, 12u);
    EXPECT_TRUE(c.closed() && c.manifold() && c.oriented());
    EXPECT_EQ(c.components, 1u);
    EXPECT_EQ(c.degenerate_triangles, 0u);
    EXPECT_EQ(c.self_intersections, 0u);
    EXPECT_NEAR(c.volume, 1.0, 1e-12);
    EXPECT_NEAR(c.area, 6.0, 1e-12);
    EXPECT_NEAR(c.diagonal, std::sqrt(3.0), 1e-12);
    EXPECT_TRUE(can_tetrahedralize(c, nullptr));
}

TEST(CheckMesh, CubeWithoutOneFaceHasTheFourEdgesOfTheHoleAsBoundary) {
    TriangleMesh mesh = unit_cube();
    mesh.triangles.erase(mesh.triangles.begin() + 2, mesh.triangles.begin() + 4);  // the top
    const MeshCheck c = check_mesh(mesh);
    EXPECT_EQ(c.triangles, 10u);
    EXPECT_EQ(c.boundary_edges, 4u);  // the square's sides; its diagonal left with the face
    EXPECT_FALSE(c.closed());
    EXPECT_TRUE(c.manifold());
    std::string why;
    EXPECT_FALSE(can_tetrahedralize(c, &why));
    EXPECT_NE(why.find("not closed"), std::string::npos) << why;
}

TEST(CheckMesh, TwoDisjointCubesAreTwoComponentsOfTotalVolumeTwo) {
    TriangleMesh mesh = unit_cube();
    add_cube(mesh, Vec3(3, 0, 0));
    const MeshCheck c = check_mesh(mesh);
    EXPECT_EQ(c.components, 2u);
    EXPECT_NEAR(c.volume, 2.0, 1e-12);
    EXPECT_TRUE(c.closed() && c.manifold() && c.oriented());
    EXPECT_EQ(c.self_intersections, 0u);
}

TEST(CheckMesh, InsideOutCubeHasVolumeMinusOneAndOrientOutwardFixesIt) {
    TriangleMesh mesh = unit_cube();
    for (Tri& t : mesh.triangles) std::swap(t[1], t[2]);
    MeshCheck c = check_mesh(mesh);
    EXPECT_NEAR(c.volume, -1.0, 1e-12);
    EXPECT_TRUE(c.oriented());  // consistently oriented, just inward
    EXPECT_FALSE(can_tetrahedralize(c, nullptr));
    const MeshCheck inward = c;
    EXPECT_TRUE(orient_outward(mesh));
    c = check_mesh(mesh);
    EXPECT_NEAR(c.volume, 1.0, 1e-12);
    EXPECT_TRUE(can_tetrahedralize(c, nullptr));
    // The flip changes nothing else the check counts (prescore reads the flipped mesh's check
    // from the input's): the volume exactly negated, the rest equal.
    EXPECT_EQ(c.volume, -inward.volume);
    EXPECT_EQ(c.area, inward.area);
    EXPECT_EQ(c.boundary_edges, inward.boundary_edges);
    EXPECT_EQ(c.misoriented_edges, inward.misoriented_edges);
    EXPECT_EQ(c.nonmanifold_edges + c.nonmanifold_vertices, inward.nonmanifold_edges + inward.nonmanifold_vertices);
    EXPECT_EQ(c.degenerate_triangles, inward.degenerate_triangles);
    EXPECT_FALSE(orient_outward(mesh));  // already outward: left as it is
}

TEST(CheckMesh, OneFlippedTriangleMisorientsItsThreeEdges) {
    TriangleMesh mesh = unit_cube();
    std::swap(mesh.triangles[0][1], mesh.triangles[0][2]);
    const MeshCheck c = check_mesh(mesh);
    EXPECT_EQ(c.misoriented_edges, 3u);
    EXPECT_FALSE(c.oriented());
    EXPECT_TRUE(c.closed() && c.manifold());
}

TEST(CheckMesh, TwoCubesSharingOneEdgeHaveOneNonManifoldEdgeAndOneComponent) {
    TriangleMesh mesh = unit_cube();
    add_cube(mesh, Vec3(1, 1, 0));  // its edge x = y = 1, z in [0, 1] is the first cube's
    merge_equal_positions(mesh);
    const MeshCheck c = check_mesh(mesh);
    EXPECT_EQ(c.nonmanifold_edges, 1u);  // four triangles on the shared edge
    EXPECT_EQ(c.nonmanifold_vertices, 0u);  // the fans at its ends are joined by that edge
    EXPECT_FALSE(c.manifold());
    EXPECT_EQ(c.components, 1u);
    EXPECT_NEAR(c.volume, 2.0, 1e-12);
    EXPECT_EQ(c.self_intersections, 0u);  // they touch only along the shared edge
    EXPECT_FALSE(can_tetrahedralize(c, nullptr));
}

TEST(CheckMesh, TwoCubesSharingOneCornerHaveOneNonManifoldVertex) {
    TriangleMesh mesh = unit_cube();
    add_cube(mesh, Vec3(1, 1, 1));  // corner (1, 1, 1) is shared
    merge_equal_positions(mesh);
    const MeshCheck c = check_mesh(mesh);
    EXPECT_EQ(c.nonmanifold_edges, 0u);
    EXPECT_EQ(c.nonmanifold_vertices, 1u);  // two fans meet there
    EXPECT_EQ(c.components, 2u);
    EXPECT_EQ(c.self_intersections, 0u);  // touching at the shared corner is not crossing
}

TEST(CheckMesh, ZeroAreaTriangleAndRepeatedIndexAreDegenerate) {
    TriangleMesh mesh = unit_cube();
    mesh.vertices.push_back(Vec3(0.5, 0, 0));  // on the edge from corner 0 to corner 1
    mesh.triangles.push_back({0, 1, 8});       // collinear: zero area
    MeshCheck c = check_mesh(mesh);
    EXPECT_EQ(c.degenerate_triangles, 1u);
    EXPECT_FALSE(can_tetrahedralize(c, nullptr));
    mesh.triangles.back() = {0, 0, 1};  // repeated index
    c = check_mesh(mesh);
    EXPECT_EQ(c.degenerate_triangles, 1u);
    EXPECT_TRUE(c.closed());  // a repeated-index triangle is left out of the topology
}

TEST(CheckMesh, SpikeThroughTheTopFaceIsOneIntersectingPair) {
    // A thin triangle in the plane y = 0.25 from inside the cube out through the top face. At
    // z = 1 it spans x in [0.5, 0.525], y = 0.25, which lies in the top triangle (4, 5, 6)
    // (the half with y < x) only: one crossing pair.
    TriangleMesh mesh = unit_cube();
    mesh.vertices.push_back(Vec3(0.5, 0.25, 0.5));
    mesh.vertices.push_back(Vec3(0.5, 0.25, 1.5));
    mesh.vertices.push_back(Vec3(0.55, 0.25, 1.5));
    mesh.triangles.push_back({8, 9, 10});
    const MeshCheck c = check_mesh(mesh);
    EXPECT_EQ(c.self_intersections, 1u);
}

TEST(CheckMesh, DescribeNamesCountsAndState) {
    const std::string line = describe(check_mesh(unit_cube()));
    EXPECT_NE(line.find("8 vertices, 12 triangles, closed, manifold, oriented, 1 component"), std::string::npos)
        << line;
}

TEST(AlphaWrap, OpenCubeWithAlphaAboveTheHoleBecomesAClosedCubeWithinTheOffsetBound) {
    // Alpha 2 m is wider than the 1 m x 1 m hole, so the wrap passes over it and encloses the
    // whole cube. The wrap contains the input and stays within `offset` of it, so its volume
    // lies in [1, (1 + 2 offset)^3] = [1, 1.0301] for offset 0.005 m.
    TriangleMesh open = unit_cube();
    open.triangles.erase(open.triangles.begin() + 2, open.triangles.begin() + 4);
    const double offset = 0.005;
    const TriangleMesh wrap = alpha_wrap(open, 2.0, offset);
    const MeshCheck c = check_mesh(wrap);
    EXPECT_TRUE(c.closed() && c.manifold() && c.oriented()) << describe(c);
    EXPECT_EQ(c.components, 1u);
    EXPECT_EQ(c.degenerate_triangles, 0u);
    EXPECT_GE(c.volume, 1.0);
    EXPECT_LE(c.volume, std::pow(1 + 2 * offset, 3));
    EXPECT_TRUE(can_tetrahedralize(c, nullptr));
}

TEST(AlphaWrap, OpenCubeWithAlphaBelowTheHoleIsWrappedAsAThinShell) {
    // Alpha 0.1 m fits through the hole: the wrap enters and hugs both sides of the five walls.
    // Its volume is a shell about 2 * offset thick over 5 m^2 of wall: ~0.05 m^3, far below 1.
    TriangleMesh open = unit_cube();
    open.triangles.erase(open.triangles.begin() + 2, open.triangles.begin() + 4);
    const MeshCheck c = check_mesh(alpha_wrap(open, 0.1, 0.005));
    EXPECT_TRUE(c.closed() && c.manifold() && c.oriented()) << describe(c);
    EXPECT_GT(c.volume, 0.0);
    EXPECT_LT(c.volume, 0.2);
}

// The box alone (prescore's size check before the mesh is sized): two unit cubes 2 apart along x
// span 3 x 1 x 1, diagonal sqrt(11), and a vertex no triangle uses counts too, as in check_mesh.
TEST(CheckMesh, TheBoundingDiagonalAloneIsTheChecksDiagonal) {
    TriangleMesh mesh;
    add_cube(mesh);
    add_cube(mesh, Vec3(2, 0, 0));
    EXPECT_NEAR(bounding_diagonal(mesh), std::sqrt(11.0), 1e-12);
    mesh.vertices.push_back(Vec3(0, 0, -3));
    EXPECT_NEAR(bounding_diagonal(mesh), std::sqrt(9.0 + 1.0 + 16.0), 1e-12);
    EXPECT_EQ(bounding_diagonal(mesh), check_mesh(mesh, false).diagonal);
    EXPECT_EQ(bounding_diagonal(TriangleMesh{}), 0.0);
}

}  // namespace
}  // namespace shatter
