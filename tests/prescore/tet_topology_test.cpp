// Face adjacency and face-connected components on grids whose counts follow from the geometry.
#include "prescore/tet_topology.h"

#include <gtest/gtest.h>

#include "prescore/tet_test_meshes.h"

namespace shatter {
namespace {

size_t boundary_faces(const TetTopology& topology) {
    size_t n = 0;
    for (const auto& nb : topology.neighbour)
        for (int32_t u : nb) n += u < 0;
    return n;
}

TEST(TetTopology, SingleCubeHasTwelveBoundaryTrianglesAndSixInnerFaces) {
    const TetMesh mesh = test::cube_grid(1, 1, 1, 1.0);
    const TetTopology topology = build_topology(mesh);
    ASSERT_EQ(topology.neighbour.size(), 6u);
    EXPECT_EQ(boundary_faces(topology), 12u);       // 6 squares x 2 triangles
    EXPECT_EQ(6 * 4 - boundary_faces(topology), 12u);  // 6 inner faces, seen from both sides
}

TEST(TetTopology, GridBoundaryFaceCountIsTwoTrianglesPerBoundarySquare) {
    const TetMesh mesh = test::cube_grid(3, 4, 5, 0.1);
    const TetTopology topology = build_topology(mesh);
    EXPECT_EQ(boundary_faces(topology), size_t(2 * 2 * (3 * 4 + 4 * 5 + 3 * 5)));
}

TEST(TetTopology, NeighboursAreMutualAndShareTheFaceVertices) {
    const TetMesh mesh = test::cube_grid(3, 3, 2, 1.0);
    const TetTopology topology = build_topology(mesh);
    for (size_t t = 0; t < mesh.tets.size(); ++t) {
        for (int i = 0; i < 4; ++i) {
            const int32_t u = topology.neighbour[t][i];
            if (u < 0) continue;
            int back = 0;
            for (int j = 0; j < 4; ++j) back += topology.neighbour[u][j] == int32_t(t);
            EXPECT_EQ(back, 1);
            // The vertex opposite face i is the only one not in u.
            const auto& other = mesh.tets[u];
            EXPECT_EQ(std::count(other.begin(), other.end(), mesh.tets[t][i]), 0);
        }
    }
}

TEST(TetTopology, TwoSeparatedGridsAreTwoComponentsNumberedByLowestTet) {
    TetMesh mesh = test::cube_grid(2, 2, 2, 1.0);
    const size_t first = mesh.tets.size();
    test::append(mesh, test::cube_grid(3, 1, 1, 1.0, Vec3(5, 0, 0)));
    int32_t count = 0;
    const std::vector<int32_t> component = tet_components(build_topology(mesh), {}, &count);
    EXPECT_EQ(count, 2);
    for (size_t t = 0; t < mesh.tets.size(); ++t) EXPECT_EQ(component[t], t < first ? 0 : 1);
}

TEST(TetTopology, MaskingOutTheMiddleCellOfARowSplitsItInTwo) {
    const TetMesh mesh = test::cube_grid(3, 1, 1, 1.0);
    std::vector<char> mask(mesh.tets.size(), 1);
    for (size_t t = 6; t < 12; ++t) mask[t] = 0;  // cell 1 (tets are emitted cell by cell)
    int32_t count = 0;
    const std::vector<int32_t> component = tet_components(build_topology(mesh), mask, &count);
    EXPECT_EQ(count, 2);
    for (size_t t = 0; t < 18; ++t) EXPECT_EQ(component[t], t < 6 ? 0 : t < 12 ? -1 : 1);
}

}  // namespace
}  // namespace shatter
