// seeds = "points": each point's tet seeds one piece, and a point outside the object is refused
// with a message that names the point.
#include "prescore/seed_points.h"

#include <gtest/gtest.h>

#include <string>

#include "core/error.h"
#include "core/shot.h"
#include "prescore/partition.h"
#include "prescore/prescore.h"
#include "prescore/tet_test_meshes.h"
#include "support/temp_dir.h"

namespace shatter {
namespace {

// A 0.3 x 0.15 x 0.15 m brick of 6 x 3 x 3 cubes of 5 cm (324 tets).
TetMesh brick() { return test::cube_grid(6, 3, 3, 0.05); }

bool holds(const TetMesh& m, uint32_t t, const Vec3& p) {
    const Tet& k = m.tets[t];
    Vec3 lo = m.vertices[k[0]], hi = lo;
    for (uint32_t v : k) lo = lo.cwiseMin(m.vertices[v]), hi = hi.cwiseMax(m.vertices[v]);
    return (p.array() >= lo.array() - 1e-12).all() && (p.array() <= hi.array() + 1e-12).all();
}

TEST(SeedPoints, ABrickWithTwoPointsGivesTwoPiecesEachHoldingItsPoint) {
    const TetMesh m = brick();
    const std::vector<std::array<double, 3>> points = {{0.26, 0.07, 0.08}, {0.03, 0.11, 0.02}};
    const std::vector<uint32_t> seeds = seed_tets_of_points(m, points, 0.05, "shot.toml:3");
    ASSERT_EQ(seeds.size(), 2u);
    for (size_t i = 0; i < 2; ++i) EXPECT_TRUE(holds(m, seeds[i], Vec3(points[i][0], points[i][1], points[i][2])));
    const Partition part = partition_from_seeds(m, build_topology(m), seeds);
    ASSERT_EQ(part.piece_tets.size(), 2u);
    EXPECT_EQ(part.piece_tets[0] + part.piece_tets[1], m.tets.size());
    EXPECT_EQ(part.joined_components, 0u);
    // Pieces are numbered by ascending seed tet; each seed's tet is in its own piece, and the two
    // points are in different pieces.
    EXPECT_NE(part.tet_piece[seeds[0]], part.tet_piece[seeds[1]]);
    for (uint32_t p = 0; p < 2; ++p) EXPECT_EQ(part.tet_piece[part.seeds[p]], p);
    // Grown at equal rates from points 0.23 m apart along x: each takes about half the brick.
    EXPECT_NEAR(double(part.piece_tets[0]) / m.tets.size(), 0.5, 0.15);
}

TEST(SeedPoints, APointOutsideTheObjectIsRefusedNamingItsIndexValueAndWhere) {
    const TetMesh m = brick();
    try {
        seed_tets_of_points(m, {{0.1, 0.05, 0.05}, {0.5, 0.05, 0.05}}, 0.05, "shot.toml:7");
        FAIL() << "no error";
    } catch (const Error& e) {
        EXPECT_EQ(e.code(), ExitCode::BadInput);
        const std::string what = e.what();
        EXPECT_NE(what.find("shot.toml:7: prescore.seed_points[1] = [0.5, 0.05, 0.05] m is outside the object"),
                  std::string::npos)
            << what;
        EXPECT_NE(what.find("fix: give points inside the object"), std::string::npos) << what;
    }
    // On the surface or a little outside (within a tet's size): the nearest tet.
    EXPECT_EQ(seed_tets_of_points(m, {{0.3, 0.15, 0.15}}, 0.05, "x").size(), 1u);
}

TEST(SeedPoints, TwoPointsInOneTetAreRefused) {
    const TetMesh m = brick();
    EXPECT_THROW(seed_tets_of_points(m, {{0.1, 0.05, 0.05}, {0.1, 0.05, 0.05}}, 0.05, "x"), Error);
}

// The whole prescore from a shot: a 0.3 x 0.15 x 0.15 m brick with two seed points at either end
// gives two pieces (pieces = 10 in the file is overridden, and noted), each holding its point.
// A point outside the brick is refused naming the shot's line, the point and the fix.
TEST(SeedPoints, AShotsBrickWithTwoPointsIsSplitIntoTwoPiecesEachHoldingItsPoint) {
    testing_support::TempDir dir;
    TriangleMesh box;
    for (int i = 0; i < 8; ++i) box.vertices.push_back(Vec3(i & 1 ? 0.3 : 0, i & 2 ? 0.15 : 0, i & 4 ? 0.15 : 0));
    box.triangles = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
                     {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
    dir.write("brick.obj", test::obj_text(box));
    const std::string head = "[mesh]\npath = \"brick.obj\"\nscale = 1\n\n[prescore]\npieces = 10\nresolution = 10\n"
                             "render_surface = false\nseeds = \"points\"\n";
    const Shot shot = load_shot(dir.write("a.toml", head + "seed_points = [[0.04, 0.07, 0.07], [0.26, 0.08, 0.07]]\n"));
    PrescoreReport report;
    const Model m = prescore_shot(shot, &report);
    ASSERT_EQ(m.pieces.size(), 2u);
    const Vec3 points[2] = {Vec3(0.04, 0.07, 0.07), Vec3(0.26, 0.08, 0.07)};
    for (const Vec3& p : points) {
        const std::vector<uint32_t> t = seed_tets_of_points(m.mesh, {{p.x(), p.y(), p.z()}}, 1e-9, "x");
        EXPECT_TRUE(holds(m.mesh, t[0], p));
        // The piece whose centre is nearer the point holds it: the brick is split across x.
        const uint32_t piece = m.tet_piece[t[0]];
        EXPECT_LT((m.pieces[piece].mass.center - p).norm(), (m.pieces[1 - piece].mass.center - p).norm());
    }
    EXPECT_NE(m.tet_piece[seed_tets_of_points(m.mesh, {{0.04, 0.07, 0.07}}, 1e-9, "x")[0]],
              m.tet_piece[seed_tets_of_points(m.mesh, {{0.26, 0.08, 0.07}}, 1e-9, "x")[0]]);
    bool noted = false;
    for (const auto& c : report.choices.list) noted = noted || c.what == "pieces 10 -> 2";
    EXPECT_TRUE(noted);

    const std::string bad = dir.write("b.toml", head + "seed_points = [[0.04, 0.07, 0.07],\n  [0.26, 0.5, 0.07]]\n");
    try {
        prescore_shot(load_shot(bad), nullptr);
        FAIL() << "no error";
    } catch (const Error& e) {
        EXPECT_EQ(e.code(), ExitCode::BadInput);
        const std::string what = e.what();
        EXPECT_NE(what.find(bad + ":10"), std::string::npos) << what;
        EXPECT_NE(what.find("prescore.seed_points[1] = [0.26, 0.5, 0.07] m is outside the object"), std::string::npos)
            << what;
    }
}

}  // namespace
}  // namespace shatter
