// Piece surfaces: closed (every edge twice, opposite directions), outward (enclosed signed volume
// equals the tet volume), face kinds as the geometry says.
#include "prescore/piece_surface.h"

#include <gtest/gtest.h>

#include <map>

#include "prescore/hollow.h"
#include "prescore/tet_test_meshes.h"

namespace shatter {
namespace {

void expect_closed(const PieceSurface& s) {
    std::map<std::pair<uint32_t, uint32_t>, int> directed;
    for (const Tri& t : s.triangles)
        for (int k = 0; k < 3; ++k) ++directed[{t[k], t[(k + 1) % 3]}];
    for (const auto& [edge, n] : directed) {
        EXPECT_EQ(n, 1);
        const auto back = directed.find({edge.second, edge.first});
        EXPECT_TRUE(back != directed.end() && back->second == 1);
    }
}

double enclosed_volume(const PieceSurface& s) {
    double v = 0;
    for (const Tri& t : s.triangles)
        v += s.vertices[t[0]].dot(s.vertices[t[1]].cross(s.vertices[t[2]])) / 6;
    return v;
}

std::map<FaceKind, double> area_by_kind(const PieceSurface& s) {
    std::map<FaceKind, double> area;
    for (size_t i = 0; i < s.triangles.size(); ++i) {
        const Tri& t = s.triangles[i];
        const Vec3& a = s.vertices[t[0]];
        area[s.kinds[i]] += 0.5 * (s.vertices[t[1]] - a).cross(s.vertices[t[2]] - a).norm();
    }
    return area;
}

TEST(PieceSurface, TwoPieceCubeHalvesAreClosedOutwardAndKindedByGeometry) {
    const TetMesh mesh = test::cube_grid(4, 4, 4, 0.25);  // unit cube
    std::vector<uint32_t> tet_piece(mesh.tets.size());
    for (size_t t = 0; t < tet_piece.size(); ++t) tet_piece[t] = (t / 6) % 4 < 2 ? 0 : 1;  // x < 0.5
    const TetTopology topology = build_topology(mesh);
    for (uint32_t piece : {0u, 1u}) {
        const PieceSurface s = piece_surface(mesh, topology, tet_piece, piece, nullptr);
        ASSERT_EQ(s.kinds.size(), s.triangles.size());
        expect_closed(s);
        EXPECT_NEAR(enclosed_volume(s), 0.5, 1e-12);
        auto area = area_by_kind(s);
        EXPECT_NEAR(area[FaceKind::Fracture], 1.0, 1e-12);  // the plane x = 0.5
        EXPECT_NEAR(area[FaceKind::Outer], 1.0 + 4 * 0.5, 1e-12);
        EXPECT_EQ(area.count(FaceKind::Cavity), 0u);
        for (size_t i = 0; i < s.triangles.size(); ++i) {
            if (s.kinds[i] != FaceKind::Fracture) continue;
            for (uint32_t v : s.triangles[i]) EXPECT_EQ(s.vertices[v].x(), 0.5);
        }
    }
}

TEST(PieceSurface, VerticesAreCompactedInFirstUseOrder) {
    const TetMesh mesh = test::cube_grid(3, 2, 2, 1.0);
    const std::vector<uint32_t> tet_piece(mesh.tets.size(), 0);
    const PieceSurface s = piece_surface(mesh, build_topology(mesh), tet_piece, 0, nullptr);
    EXPECT_EQ(s.vertices.size(), size_t(4 * 3 * 3 - 2));  // grid vertices minus the 2 inner ones
    uint32_t next = 0;
    for (const Tri& t : s.triangles)
        for (uint32_t v : t) {
            EXPECT_LE(v, next);
            if (v == next) ++next;
        }
    EXPECT_EQ(next, s.vertices.size());
}

TEST(PieceSurface, HollowedCubeHasOuterAndCavityWalls) {
    const TetMesh solid = test::cube_grid(6, 6, 6, 1.0);
    const HollowResult hollowed = hollow(solid, build_topology(solid), 1.0);
    const TetMesh& mesh = hollowed.mesh;
    const std::vector<uint32_t> tet_piece(mesh.tets.size(), 0);
    const PieceSurface s = piece_surface(mesh, build_topology(mesh), tet_piece, 0, &hollowed.cavity_face);
    expect_closed(s);
    EXPECT_NEAR(enclosed_volume(s), 6 * 6 * 6 - 4 * 4 * 4, 1e-9);  // the cavity wall faces inwards
    auto area = area_by_kind(s);
    EXPECT_NEAR(area[FaceKind::Outer], 6 * 36, 1e-9);
    EXPECT_NEAR(area[FaceKind::Cavity], 6 * 16, 1e-9);
    EXPECT_EQ(area.count(FaceKind::Fracture), 0u);
}

}  // namespace
}  // namespace shatter
