// How prescore adapts to a mesh (prescore/adapt.h): the size it chooses, the tets it fits to a
// wall thinner than a tet, and the slivers it joins to their nearest pieces.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include <fmt/format.h>

#include "core/error.h"
#include "prescore/adapt.h"
#include "prescore/mesh_check.h"
#include "prescore/prescore.h"
#include "prescore/tet_topology.h"
#include "support/temp_dir.h"

namespace shatter {
namespace {

// An axis-aligned box as 12 outward triangles.
TriangleMesh box(const Vec3& lo, const Vec3& hi) {
    TriangleMesh m;
    for (int i = 0; i < 8; ++i)
        m.vertices.emplace_back(i & 1 ? hi.x() : lo.x(), i & 2 ? hi.y() : lo.y(), i & 4 ? hi.z() : lo.z());
    m.triangles = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
                   {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
    return m;
}

// An n x n x n grid of unit-ish cubes from `lo` with edge `h`, each cube split into 6 tets; a
// block of its own (it shares no vertex with what `m` held before).
void add_tet_block(TetMesh& m, const Vec3& lo, double h, int n) {
    const uint32_t start = uint32_t(m.vertices.size());
    const auto at = [&](int i, int j, int k) {
        m.vertices.push_back(lo + h * Vec3(i, j, k));
        return uint32_t(m.vertices.size() - 1);
    };
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j)
            for (int k = 0; k < n; ++k) {
                uint32_t c[8];
                for (int b = 0; b < 8; ++b) c[b] = at(i + (b & 1), j + (b >> 1 & 1), k + (b >> 2 & 1));
                // Six tets around the diagonal c0-c7 (Kuhn's subdivision); orientation fixed below.
                const int paths[6][2] = {{1, 3}, {1, 5}, {2, 3}, {2, 6}, {4, 5}, {4, 6}};
                for (const auto& p : paths) {
                    Tet t{c[0], c[p[0]], c[p[0] | p[1]], c[7]};
                    const auto& v = m.vertices;
                    if (tet_volume(v[t[0]], v[t[1]], v[t[2]], v[t[3]]) < 0) std::swap(t[2], t[3]);
                    m.tets.push_back(t);
                }
            }
    // Join the duplicated corner vertices so that neighbouring cubes share faces.
    std::vector<uint32_t> first(m.vertices.size());
    for (uint32_t a = 0; a < m.vertices.size(); ++a) {
        first[a] = a;
        for (uint32_t b = start; b < a; ++b)
            if ((m.vertices[a] - m.vertices[b]).norm() < 1e-12) {
                first[a] = first[b];
                break;
            }
    }
    for (Tet& t : m.tets)
        for (uint32_t& v : t) v = first[v];
}

double tets_volume(const TetMesh& m) {
    double volume = 0;
    for (const Tet& t : m.tets)
        volume += tet_volume(m.vertices[t[0]], m.vertices[t[1]], m.vertices[t[2]], m.vertices[t[3]]);
    return volume;
}

// prescore with the defaults on a mesh file written from `text`.
Model prescore_text(const std::string& name, const std::string& text, PrescoreReport* report,
                    RepairMode repair = RepairMode::Auto) {
    testing_support::TempDir dir;
    MeshSettings mesh;
    mesh.path = dir.write(name, text);
    mesh.repair = repair;
    return prescore(mesh, PrescoreSettings{}, report);
}

TEST(Adapt, SizeWinsOverScaleWhichWinsOverTheFileUnitsAndAUnitlessFileIsMadeThreeTenthsOfAMetreLong) {
    const TriangleMesh m = box(Vec3(0, 0, 0), Vec3(4, 2, 1));  // longest side 4 units
    MeshSettings s;
    AutoChoices choices;
    s.size = 2.0;
    s.scale = 0.1;
    EXPECT_DOUBLE_EQ(choose_scale(m, 0.01, s, choices), 0.5);  // 2 m / 4 units
    s.size.reset();
    EXPECT_DOUBLE_EQ(choose_scale(m, 0.01, s, choices), 0.1);
    s.scale.reset();
    EXPECT_DOUBLE_EQ(choose_scale(m, 0.01, s, choices), 0.01);  // an FBX file in centimetres
    EXPECT_TRUE(choices.list.empty());
    EXPECT_DOUBLE_EQ(choose_scale(m, 0, s, choices), kDefaultSize / 4);
    ASSERT_EQ(choices.list.size(), 1u);
    EXPECT_NE(choices.list[0].what.find("size 0.3 m"), std::string::npos) << choices.list[0].what;
    EXPECT_NE(choices.list[0].why.find("4 units"), std::string::npos) << choices.list[0].why;
    EXPECT_EQ(choices.to_json()[0]["what"], choices.list[0].what);
}

TEST(Adapt, AFileWhoseUnitsMakeItHugeOrTinyIsToldTheSizesOtherUnitsWouldGive) {
    EXPECT_EQ(units_hint(0.3), "");
    EXPECT_EQ(units_hint(kPlausibleLongest[1]), "");
    EXPECT_EQ(units_hint(kPlausibleLongest[0]), "");
    // glTF's 2CylinderEngine: 743.4 m by its file (metres), 0.743 m had it meant millimetres.
    const std::string large = units_hint(743.4);
    for (const char* part : {"743.4 m long", "0.743 m long ([mesh] scale = 0.001)", "7.43 m (scale = 0.01)",
                             "18.9 m (scale = 0.0254)", "--set mesh.scale=0.001"})
        EXPECT_NE(large.find(part), std::string::npos) << part << " in: " << large;
    const std::string tiny = units_hint(5e-4);
    EXPECT_NE(tiny.find("0.0005 m long"), std::string::npos) << tiny;
    EXPECT_NE(tiny.find("--size"), std::string::npos) << tiny;
}

// A warning prescore gives is kept in the model's settings, naming the file without its folder:
// the same mesh gives the same model bytes from two folders. A unit cube 20,000 units from its
// file's origin is read in steps of 2^-9 (rounding_hint's warning); at the origin, no warning.
TEST(Adapt, AModelKeepsItsWarningsWithTheFileNamedWithoutItsFolder) {
    const auto cube_at = [](double offset) {
        std::string text;
        for (int i = 0; i < 8; ++i)
            text += fmt::format("v {} {} {}\n", offset + (i & 1), offset + ((i >> 1) & 1), offset + ((i >> 2) & 1));
        for (const char* f : {"1 3 2", "2 3 4", "5 6 8", "5 8 7", "1 2 6", "1 6 5", "3 7 8", "3 8 4", "1 5 7", "1 7 3",
                              "2 4 8", "2 8 6"})
            text += fmt::format("f {}\n", f);
        return text;
    };
    testing_support::TempDir a, b;
    std::filesystem::create_directories(b.file("deeper"));
    MeshSettings mesh;
    mesh.path = a.write("far_cube.obj", cube_at(2e4));
    const Model from_a = prescore(mesh, PrescoreSettings{}, nullptr);
    mesh.path = b.write("deeper/far_cube.obj", cube_at(2e4));
    const Model from_b = prescore(mesh, PrescoreSettings{}, nullptr);
    const auto settings = nlohmann::ordered_json::parse(from_a.settings_json);
    ASSERT_EQ(settings.value("warnings", nlohmann::ordered_json::array()).size(), 1u) << settings.dump(2);
    const std::string warning = settings["warnings"][0];
    EXPECT_EQ(warning.rfind("far_cube.obj: its coordinates reach 2e+04 units", 0), 0u) << warning;
    EXPECT_NE(warning.find("steps of 0.002 units"), std::string::npos) << warning;
    EXPECT_EQ(from_a.settings_json, from_b.settings_json);
    mesh.path = a.write("near_cube.obj", cube_at(0));
    EXPECT_FALSE(nlohmann::ordered_json::parse(prescore(mesh, PrescoreSettings{}, nullptr).settings_json).contains("warnings"));
}

// A plate 1 m wide and 1 cm thick: at resolution 20 a tet is 7 cm, seven times the plate's
// thickness, so Mesh_3 loses it. Adapting ends in one connected body that fills at least the
// plate and at most the plate grown on every side by the thickening offset.
TEST(Adapt, APlateThinnerThanATetIsFittedAsOneBodyAndRefusedWithoutAdapt) {
    const TriangleMesh plate = box(Vec3(0, 0, 0), Vec3(1, 0.01, 1));
    const MeshCheck check = check_mesh(plate, false);
    PrescoreSettings ps;
    MeshSettings ms;
    AutoChoices choices;
    const FittedTets fit = fit_tets(plate, plate, check, false, check.diagonal, ms, ps, "plate", choices);
    ASSERT_FALSE(fit.tets.tets.empty());
    int32_t clusters = 0;
    tet_components(build_topology(fit.tets), {}, &clusters);
    EXPECT_EQ(clusters, 1);
    const double volume = tets_volume(fit.tets);
    const double offset = fit.wrapped ? kThickenOffset * check.diagonal / fit.resolution : 0;
    EXPECT_GE(volume, 0.9 * 0.01);
    EXPECT_LE(volume, (1 + 2 * offset) * (0.01 + 2 * offset) * (1 + 2 * offset) * 1.05);
    ASSERT_FALSE(choices.list.empty());
    EXPECT_GT(fit.resolution, ps.resolution - 1e-12);

    ms.adapt = false;
    AutoChoices none;
    try {
        fit_tets(plate, plate, check, false, check.diagonal, ms, ps, "plate", none);
        ADD_FAILURE() << "a plate thinner than a tet was accepted without adapt";
    } catch (const Error& e) {
        EXPECT_EQ(e.code(), ExitCode::BadInput);
        EXPECT_NE(std::string(e.what()).find("plate"), std::string::npos) << e.what();
    }
}

// A flat square of two triangles (no thickness: a sheet, as a plane or a pane is modelled) is
// given a thickness: prescore wraps it and thickens the wrap, and its tets fill the square grown
// by the thickening offset d, whose volume Steiner's formula gives for a flat convex set:
// 2 d A + P pi d^2 / 2 + 4 pi d^3 / 3 (A the area, P the perimeter; measured 3.1% under it, the tets
// inside the wrap). Without repair it is refused.
TEST(Adapt, AFlatSheetIsGivenAThicknessAndRefusedWithoutRepair) {
    const std::string square = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3\nf 1 3 4\n";
    PrescoreReport report;
    const Model model = prescore_text("square.obj", square, &report);
    EXPECT_EQ(model.pieces.size(), PrescoreSettings{}.pieces);
    EXPECT_FALSE(model.constraints.empty());
    int32_t clusters = 0;
    tet_components(build_topology(model.mesh), {}, &clusters);
    EXPECT_EQ(clusters, 1);
    const double side = kDefaultSize, d = kThickenOffset * std::sqrt(2.0) * side / report.resolution;
    const double grown = 2 * d * side * side + 4 * side * M_PI * d * d / 2 + 4 * M_PI * d * d * d / 3;
    EXPECT_NEAR(tets_volume(model.mesh), grown, 0.05 * grown)
        << "offset " << d << " m at resolution " << report.resolution;

    try {
        prescore_text("square.obj", square, nullptr, RepairMode::Never);
        ADD_FAILURE() << "a sheet was accepted without repair";
    } catch (const Error& e) {
        EXPECT_EQ(e.code(), ExitCode::BadInput);
        EXPECT_NE(std::string(e.what()).find("sheet"), std::string::npos) << e.what();
    }
}

// A flat triangular frame around a triangular hole (CGAL's triangular_hole.off), given a
// thickness: the centre of its bounding box lies in the hole, and Mesh_3's first points, on rays
// from there, missed the thickened wall so that it made no tets (it took a thicker wall at a
// coarser resolution); started from points on the wall it meshes at the first thickening, and its
// tets fill the frame grown by the offset (2 d A + P pi d^2 / 2 for a region with one hole; the
// rims at the hole's corners overlap, so within 10%).
TEST(Adapt, AFlatFrameAroundAHoleIsMeshedAtItsFirstThickening) {
    PrescoreReport report;
    const Model model = prescore_text("frame.off",
                                      "OFF\n6 6 0\n1 1 0\n3 1 0\n2 2 0\n2 3 0\n0 0 0\n4 0 0\n"
                                      "3 0 2 3\n3 1 3 2\n3 0 4 1\n3 1 4 5\n3 1 5 3\n3 0 3 4\n",
                                      &report);
    EXPECT_DOUBLE_EQ(report.resolution, 2 * PrescoreSettings{}.resolution);
    const double unit = kDefaultSize / 4;  // the frame is 4 units wide
    const double area = unit * unit * (0.5 * 4 * 3 - 0.5 * 2 * 1);
    const double perimeter = unit * (4 + 2 * std::sqrt(13.0) + 2 + 2 * std::sqrt(2.0));
    const double d = kThickenOffset * report.input.diagonal / report.resolution;
    const double grown = 2 * d * area + perimeter * M_PI * d * d / 2;
    EXPECT_NEAR(tets_volume(model.mesh), grown, 0.1 * grown) << "offset " << d << " m";
}

// A block of 4 x 4 x 4 cubes and, 1 m away, one small cube (6 of 390 tets, 1/512 of the
// volume): the small cluster is no piece of its own; it joins the piece of the nearest tet.
TEST(Adapt, ASliverClusterJoinsThePieceNearestToIt) {
    TetMesh m;
    add_tet_block(m, Vec3(0, 0, 0), 0.25, 4);
    add_tet_block(m, Vec3(2, 0.5, 0.5), 0.125, 1);
    const TetTopology topo = build_topology(m);
    AutoChoices choices;
    const Partition p = partition_adapted(m, topo, 3, 1, true, choices);
    ASSERT_EQ(p.piece_tets.size(), 3u);
    ASSERT_EQ(p.tet_piece.size(), 390u);
    // The nearest large tet to the sliver's centroid (2.0625, 0.5625, 0.5625) is in the block's
    // cube at x in [0.75, 1], y in [0.5, 0.75], z in [0.5, 0.75].
    uint32_t nearest = 0;
    double best = HUGE_VAL;
    for (uint32_t t = 0; t < 384; ++t) {
        Vec3 c = Vec3::Zero();
        for (uint32_t v : m.tets[t]) c += m.vertices[v] / 4;
        const double d = (c - Vec3(2.0625, 0.5625, 0.5625)).squaredNorm();
        if (d < best) best = d, nearest = t;
    }
    for (uint32_t t = 384; t < 390; ++t) EXPECT_EQ(p.tet_piece[t], p.tet_piece[nearest]);
    ASSERT_EQ(choices.list.size(), 1u);
    EXPECT_NE(choices.list[0].what.find("1 small tet clusters (6 tets"), std::string::npos) << choices.list[0].what;

    // Without adapt the sliver is a body of its own and needs its own piece.
    AutoChoices none;
    const Partition q = partition_adapted(m, topo, 3, 1, false, none);
    for (uint32_t t = 385; t < 390; ++t) EXPECT_EQ(q.tet_piece[t], q.tet_piece[384]);
    for (uint32_t t = 0; t < 384; ++t) EXPECT_NE(q.tet_piece[t], q.tet_piece[384]);
    EXPECT_TRUE(none.list.empty());
}

// A heap of 120 equal cubes apart from each other, each 0.83% of the volume: under the sliver
// share of the volume, but as large as the largest body, so each is a body and gets a piece.
TEST(Adapt, AHeapOfSimilarSmallBodiesKeepsEveryBodyAsAPiece) {
    TetMesh m;
    for (int i = 0; i < 120; ++i) add_tet_block(m, Vec3(0.5 * (i % 10), 0.5 * (i / 10), 0), 0.25, 1);
    AutoChoices choices;
    const Partition p = partition_adapted(m, build_topology(m), 10, 1, true, choices);
    ASSERT_EQ(p.piece_tets.size(), 120u);
    for (int i = 0; i < 120; ++i)
        for (int t = 1; t < 6; ++t) EXPECT_EQ(p.tet_piece[6 * i + t], p.tet_piece[6 * i]) << i;
    std::vector<uint32_t> piece_of_block;
    for (int i = 0; i < 120; ++i) piece_of_block.push_back(p.tet_piece[6 * i]);
    std::sort(piece_of_block.begin(), piece_of_block.end());
    EXPECT_EQ(std::unique(piece_of_block.begin(), piece_of_block.end()), piece_of_block.end());
    ASSERT_EQ(choices.list.size(), 1u);
    EXPECT_NE(choices.list[0].what.find("pieces 10 -> 120"), std::string::npos) << choices.list[0].what;
}

// Past kMaxBodies separate bodies the largest are pieces and the smaller join their nearest.
TEST(Adapt, PastTheMostBodiesTheSmallerOnesJoinTheirNearestPieces) {
    TetMesh m;
    const int big = int(kMaxBodies);
    for (int i = 0; i < big; ++i) add_tet_block(m, Vec3(0.5 * (i % 40), 0.5 * (i / 40), 0), 0.25, 1);
    for (int i = 0; i < 5; ++i) add_tet_block(m, Vec3(0.5 * i, -0.5, 0), 0.15, 1);  // 22% of a big one's volume
    AutoChoices choices;
    const Partition p = partition_adapted(m, build_topology(m), 10, 1, true, choices);
    ASSERT_EQ(p.piece_tets.size(), kMaxBodies);
    // Small block i lies 0.25 m below big block i (the nearest): it moves with that block's piece.
    for (int i = 0; i < 5; ++i)
        for (int t = 0; t < 6; ++t) EXPECT_EQ(p.tet_piece[6 * (big + i) + t], p.tet_piece[6 * i]) << i;
    ASSERT_EQ(choices.list.size(), 2u);
    EXPECT_NE(choices.list[1].what.find("5 of 1005 separate bodies"), std::string::npos) << choices.list[1].what;
}

}  // namespace
}  // namespace shatter
