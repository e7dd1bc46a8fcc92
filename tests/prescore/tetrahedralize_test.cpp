// tetrahedralize: the unit cube's tets sum to its volume, all positive; two runs give the same
// bytes; the bunny at the default resolution gives a few thousand tets.
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>

#include "core/error.h"
#include "meshio/mesh_load.h"
#include "prescore/mesh_check.h"
#include "prescore/tetrahedralize.h"

namespace shatter {
namespace {

TriangleMesh unit_cube() {
    TriangleMesh mesh;
    for (int i = 0; i < 8; ++i)
        mesh.vertices.emplace_back((i == 1 || i == 2 || i == 5 || i == 6), (i == 2 || i == 3 || i == 6 || i == 7), i >= 4);
    mesh.triangles = {{0, 2, 1}, {0, 3, 2}, {4, 5, 6}, {4, 6, 7}, {0, 1, 5}, {0, 5, 4},
                      {3, 7, 6}, {3, 6, 2}, {0, 4, 7}, {0, 7, 3}, {1, 2, 6}, {1, 6, 5}};
    return mesh;
}

double total_volume(const TetMesh& m, double* min_volume) {
    double sum = 0;
    *min_volume = HUGE_VAL;
    for (const Tet& t : m.tets) {
        const double v = tet_volume(m.vertices[t[0]], m.vertices[t[1]], m.vertices[t[2]], m.vertices[t[3]]);
        sum += v;
        *min_volume = std::min(*min_volume, v);
    }
    return sum;
}

TEST(Tetrahedralize, UnitCubeTetsArePositiveAndSumToExactlyVolumeOne) {
    const TetMesh tets = tetrahedralize(unit_cube(), tetrahedralize_settings_for(std::sqrt(3.0), kDefaultTetResolution));
    ASSERT_GT(tets.tets.size(), 0u);
    double min_volume = 0;
    const double volume = total_volume(tets, &min_volume);
    EXPECT_GT(min_volume, 0.0);
    // The cube's edges are protected features, so its corners and edges are kept exactly.
    EXPECT_NEAR(volume, 1.0, 1e-9);
    // Every vertex is used (compacted) and lies in the cube (up to rounding).
    std::vector<bool> used(tets.vertices.size(), false);
    for (const Tet& t : tets.tets)
        for (uint32_t v : t) used[v] = true;
    EXPECT_EQ(std::count(used.begin(), used.end(), false), 0);
    for (const Vec3& v : tets.vertices) {
        EXPECT_GE(v.minCoeff(), -1e-9);
        EXPECT_LE(v.maxCoeff(), 1 + 1e-9);
    }
}

TEST(Tetrahedralize, TwoRunsGiveIdenticalVerticesAndTets) {
    const auto settings = tetrahedralize_settings_for(std::sqrt(3.0), 15);
    const TetMesh a = tetrahedralize(unit_cube(), settings);
    const TetMesh b = tetrahedralize(unit_cube(), settings);
    ASSERT_EQ(a.vertices.size(), b.vertices.size());
    ASSERT_EQ(a.tets.size(), b.tets.size());
    for (size_t i = 0; i < a.vertices.size(); ++i) ASSERT_EQ(a.vertices[i], b.vertices[i]) << i;  // bitwise
    EXPECT_TRUE(a.tets == b.tets);
}

TEST(Tetrahedralize, SettingsForResolutionDivideTheDiagonal) {
    const TetrahedralizeSettings s = tetrahedralize_settings_for(2.0, 20);
    EXPECT_DOUBLE_EQ(s.cell_size, 0.1);
    EXPECT_DOUBLE_EQ(s.facet_size, 0.1);
    EXPECT_DOUBLE_EQ(s.facet_distance, 0.01);
    EXPECT_EQ(s.facet_angle, 25);
    EXPECT_EQ(s.cell_radius_edge_ratio, 3);
}

TEST(Tetrahedralize, NonPositiveResolutionOrSizeIsBadInput) {
    EXPECT_THROW(tetrahedralize_settings_for(1.0, 0.0), Error);
    EXPECT_THROW(tetrahedralize_settings_for(0.0, 20), Error);
    TetrahedralizeSettings s = tetrahedralize_settings_for(1.0, 20);
    s.cell_size = -1;
    try {
        tetrahedralize(unit_cube(), s);
        ADD_FAILURE() << "no error";
    } catch (const Error& e) {
        EXPECT_EQ(e.code(), ExitCode::BadInput);
        EXPECT_NE(std::string(e.what()).find("cell_size"), std::string::npos) << e.what();
    }
}

TEST(Tetrahedralize, OpenMeshIsBadInput) {
    TriangleMesh open = unit_cube();
    open.triangles.pop_back();
    EXPECT_THROW(tetrahedralize(open, tetrahedralize_settings_for(std::sqrt(3.0), 10)), Error);
}

TEST(Tetrahedralize, BunnyAtDefaultResolutionGivesAFewThousandTets) {
    const std::string bunny = "/usr/share/glmark2/models/bunny.obj";
    if (!std::filesystem::exists(bunny)) GTEST_SKIP() << bunny << " is not installed (glmark2-data)";
    const TriangleMesh mesh = load_mesh(bunny, 1.0);
    const MeshCheck check = check_mesh(mesh, false);
    const auto start = std::chrono::steady_clock::now();
    const TetMesh tets = tetrahedralize(mesh, tetrahedralize_settings_for(check.diagonal, kDefaultTetResolution));
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    double min_volume = 0;
    const double volume = total_volume(tets, &min_volume);
    std::printf("bunny R=%g: %zu tets, %zu vertices, %.3f s, volume %.5g of %.5g m^3\n", kDefaultTetResolution,
                tets.tets.size(), tets.vertices.size(), seconds, volume, check.volume);
    EXPECT_GE(tets.tets.size(), 1000u);
    EXPECT_LE(tets.tets.size(), 10000u);
    EXPECT_GT(min_volume, 0.0);
    EXPECT_NEAR(volume, check.volume, 0.05 * check.volume);
}

}  // namespace
}  // namespace shatter
