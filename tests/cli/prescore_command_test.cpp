// `shatter prescore` driven like a user drives it: the bunny end to end, determinism, flags over
// the shot file, and every class of bad input the issue lists.
#include <gtest/gtest.h>

#include <set>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "core/model_io.h"
#include "prescore/tet_topology.h"
#include "support/run_command.h"
#include "support/temp_dir.h"

namespace shatter {
namespace {

using testing_support::run_shatter;
using testing_support::slurp;
using testing_support::TempDir;

const char* kBunny = "/usr/share/glmark2/models/bunny.obj";

TEST(PrescoreCommand, BunnyGivesTenConnectedHollowPiecesJoinedOnlyWhereTheyTouch) {
    TempDir dir;
    auto r = run_shatter({"prescore", kBunny, "--scale", "0.1", "--hollow", "0.06", "-o", dir.file("b.model")});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    Model m = load_model(dir.file("b.model"));
    ASSERT_EQ(m.pieces.size(), 10u);

    // Hollow: fewer tets than the solid bunny at the same resolution, and cavity faces exist.
    TempDir solid_dir;
    ASSERT_EQ(run_shatter({"prescore", kBunny, "--scale", "0.1", "-o", solid_dir.file("s.model")}).exit_code, 0);
    Model solid = load_model(solid_dir.file("s.model"));
    EXPECT_LT(m.mesh.tets.size(), solid.mesh.tets.size());
    size_t cavity = 0;
    for (const Piece& p : m.pieces)
        for (FaceKind k : p.surface.kinds) cavity += k == FaceKind::Cavity;
    EXPECT_GT(cavity, 0u);

    // Every piece is one face-connected component (recomputed here, not read from the file).
    TetTopology topo = build_topology(m.mesh);
    for (uint32_t i = 0; i < m.pieces.size(); ++i) {
        std::vector<char> mask(m.mesh.tets.size(), 0);
        for (uint32_t t : m.pieces[i].tets) mask[t] = 1;
        int32_t components = 0;
        tet_components(topo, mask, &components);
        EXPECT_EQ(components, 1) << "piece " << i;
    }
    // Constraints only between pieces that share a face, and every such pair has constraints.
    std::set<std::pair<uint32_t, uint32_t>> touching, joined;
    for (uint32_t t = 0; t < m.mesh.tets.size(); ++t)
        for (int32_t n : topo.neighbour[t])
            if (n >= 0 && m.tet_piece[t] != m.tet_piece[n])
                touching.insert(std::minmax(m.tet_piece[t], m.tet_piece[static_cast<uint32_t>(n)]));
    for (const Constraint& c : m.constraints) joined.insert({c.piece_a, c.piece_b});
    EXPECT_EQ(joined, touching);
    EXPECT_NE(r.out.find("10 pieces"), std::string::npos) << r.out;
}

TEST(PrescoreCommand, SameInputsGiveIdenticalBytes) {
    TempDir dir;
    for (const char* name : {"a.model", "b.model"})
        ASSERT_EQ(run_shatter({"prescore", kBunny, "--scale", "0.1", "--hollow", "0.06", "--seed", "7", "-o",
                               dir.file(name)})
                      .exit_code,
                  0);
    EXPECT_EQ(slurp(dir.file("a.model")), slurp(dir.file("b.model")));
    EXPECT_EQ(slurp(dir.file("a.pieces.ply")), slurp(dir.file("b.pieces.ply")));
    ASSERT_EQ(run_shatter({"prescore", kBunny, "--scale", "0.1", "--seed", "8", "-o", dir.file("c.model")}).exit_code, 0);
    EXPECT_NE(slurp(dir.file("a.model")), slurp(dir.file("c.model")));
}

TEST(PrescoreCommand, FlagsOverrideTheShotFile) {
    TempDir dir;
    std::string shot = dir.write("s.toml", std::string("[mesh]\npath = \"") + kBunny +
                                               "\"\nscale = 0.1\n[prescore]\npieces = 4\n");
    auto r = run_shatter({"prescore", shot, "--pieces", "6", "-o", dir.file("m.model")});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(load_model(dir.file("m.model")).pieces.size(), 6u);
    r = run_shatter({"prescore", shot, "-o", dir.file("n.model")});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(load_model(dir.file("n.model")).pieces.size(), 4u);
}

TEST(PrescoreCommand, HelpListsEveryOptionWithItsDefault) {
    auto r = run_shatter({"prescore", "--help"});
    EXPECT_EQ(r.exit_code, 0);
    for (const char* opt : {"--pieces", "--seed", "--hollow", "--solid", "--resolution", "--density", "--scale",
                            "--repair", "--wrap-alpha", "--wrap-offset", "--collision-tolerance",
                            "--collision-max-parts", "--output"})
        EXPECT_NE(r.out.find(opt), std::string::npos) << opt;
    EXPECT_NE(r.out.find("kg/m^3, default: 2400"), std::string::npos);
}

TEST(PrescoreCommand, AFileInMetresThatMakesAnEngine743MetresLongIsWarnedWithTheScaleForMillimetres) {
    TempDir dir;
    auto r = run_shatter({"prescore", "/usr/share/assimp/models/glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb",
                          "--pieces", "2", "--resolution", "8", "-o", dir.file("e.model")});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const std::string log = r.out + r.err;
    EXPECT_NE(log.find("2CylinderEngine.glb: the mesh is 743.4 m long by its file's units"), std::string::npos) << log;
    EXPECT_NE(log.find("0.743 m long ([mesh] scale = 0.001)"), std::string::npos) << log;
}

// `shatter info MESH`: the mesh as shatter run takes it. The unitless unit cube is made 0.3 m long
// (0.3 m per unit, 0.027 m^3) and meshed as it is; with two faces gone it is wrapped first, and
// says why; the engine is 743.4 m long by its glTF units, with the warning that says so.
TEST(InfoCommand, AMeshIsDescribedAsShatterRunTakesIt) {
    TempDir dir;
    auto r = run_shatter({"info", SHATTER_SOURCE_DIR "/tests/fixtures/cube.obj", "--json"});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto j = nlohmann::json::parse(r.out);
    EXPECT_EQ(j["kind"], "mesh");
    EXPECT_EQ(j["triangles"], 12);
    EXPECT_TRUE(j["closed"].get<bool>());
    EXPECT_NEAR(j["scale_m_per_unit"].get<double>(), 0.3, 1e-12);
    EXPECT_TRUE(j["metres_per_unit_in_file"].is_null());
    EXPECT_NEAR(j["volume_m3"].get<double>(), 0.027, 1e-12);
    for (int a = 0; a < 3; ++a) EXPECT_NEAR(j["size_m"][a].get<double>(), 0.3, 1e-12);
    EXPECT_TRUE(j["meshed_as_it_is"].get<bool>());

    // The cube without its last two triangles (one face): open, so wrapped first.
    std::string open = slurp(SHATTER_SOURCE_DIR "/tests/fixtures/cube.obj");
    for (int k = 0; k < 2; ++k) open = open.substr(0, open.rfind("\nf ")) + "\n";
    r = run_shatter({"info", dir.write("open.obj", open)});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.out.find("meshing       alpha-wrapped first: the mesh is not closed (4 boundary edges)"), std::string::npos)
        << r.out;
    EXPECT_NE(r.out.find("next          shatter run "), std::string::npos) << r.out;

    r = run_shatter({"info", "/usr/share/assimp/models/glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb"});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.out.find("size          743.4 m long, by the file's units (1 m per unit)"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("warning       "), std::string::npos) << r.out;
}

// A model site's download, zipped: `shatter info` names the mesh it reads in the archive (its glTF
// before the OBJ under source/), and describes that mesh.
TEST(InfoCommand, AnArchiveNamesTheMeshItReads) {
    const auto r = run_shatter({"info", SHATTER_SOURCE_DIR "/tests/fixtures/archive/textured_cube.zip", "--json"});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto j = nlohmann::json::parse(r.out);
    EXPECT_EQ(j["archive_mesh"], "scene.gltf");
    EXPECT_EQ(j["archive_other_meshes"], nlohmann::json::array({"source/textured_cube.obj"}));
    EXPECT_EQ(j["triangles"], 12);
    EXPECT_EQ(j["shows_only_its_shape"], false);
}

// An STL file is read z-up and stood up: a box 1 unit tall along the file's z is tall along y, and
// prescore says why; up = "y" keeps the file's axes. (A box of 0.2 x 0.4 x 1 units as 12 facets.)
TEST(PrescoreCommand, AnStlFileStandsUpAndUpYKeepsItsAxes) {
    TempDir dir;
    const double x = 0.2, y = 0.4, z = 1.0;
    const double c[8][3] = {{0, 0, 0}, {x, 0, 0}, {x, y, 0}, {0, y, 0}, {0, 0, z}, {x, 0, z}, {x, y, z}, {0, y, z}};
    const int f[12][3] = {{0, 2, 1}, {0, 3, 2}, {4, 5, 6}, {4, 6, 7}, {0, 1, 5}, {0, 5, 4},
                          {1, 2, 6}, {1, 6, 5}, {2, 3, 7}, {2, 7, 6}, {3, 0, 4}, {3, 4, 7}};
    std::string stl = "solid box\n";
    for (const auto& t : f) {
        stl += "facet normal 0 0 0\nouter loop\n";
        for (int k : t) stl += fmt::format("vertex {} {} {}\n", c[k][0], c[k][1], c[k][2]);
        stl += "endloop\nendfacet\n";
    }
    const std::string path = dir.write("box.stl", stl + "endsolid box\n");
    auto r = run_shatter({"info", path, "--json"});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    auto j = nlohmann::json::parse(r.out);
    EXPECT_EQ(j["up"], "z");
    // 0.3 m long (the default size) along y; the file's y (0.4 units) now along -z.
    // (assimp holds coordinates in single precision: 0.4 units to ~3e-8 of themselves)
    EXPECT_NEAR(j["size_m"][1].get<double>(), 0.3, 1e-7);
    EXPECT_NEAR(j["size_m"][2].get<double>(), 0.3 * 0.4, 1e-7);
    r = run_shatter({"prescore", path, "--pieces", "2", "--resolution", "6", "-o", dir.file("up.model")});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.err.find("auto: up: the file's +z turned to +y"), std::string::npos) << r.err;
    const auto extent = [](const Model& m) {
        Vec3 lo = Vec3::Constant(1e9), hi = -lo;
        for (const Vec3& v : m.mesh.vertices) lo = lo.cwiseMin(v), hi = hi.cwiseMax(v);
        return Vec3(hi - lo);
    };
    const Vec3 up = extent(load_model(dir.file("up.model")));
    EXPECT_NEAR(up.y(), 0.3, 1e-7) << up.transpose();
    EXPECT_NEAR(up.z(), 0.12, 1e-7) << up.transpose();
    r = run_shatter({"prescore", path, "--pieces", "2", "--resolution", "6", "--up", "y", "-o", dir.file("y.model")});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const Vec3 kept = extent(load_model(dir.file("y.model")));
    EXPECT_NEAR(kept.z(), 0.3, 1e-7) << kept.transpose();
    EXPECT_NEAR(kept.y(), 0.12, 1e-7) << kept.transpose();
}

// An FBX file states its up axis, which assimp does not apply: a 0.2 x 0.4 x 1 m box that Blender
// exported z-up (its GlobalSettings UpAxis 2) stands along y; one that says y is up keeps its axes.
TEST(PrescoreCommand, AnFbxFileThatSaysZIsUpStandsUp) {
    auto r = run_shatter({"info", SHATTER_SOURCE_DIR "/tests/fixtures/axes/tall_box_z_up.fbx", "--json"});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    auto j = nlohmann::json::parse(r.out);
    EXPECT_EQ(j["up"], "z");
    EXPECT_NEAR(j["size_m"][1].get<double>(), 1.0, 1e-6) << j["size_m"];
    EXPECT_NEAR(j["size_m"][2].get<double>(), 0.4, 1e-6) << j["size_m"];
    r = run_shatter({"info", "/usr/share/assimp/models/FBX/spider.fbx", "--json"});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(nlohmann::json::parse(r.out)["up"], "y");
}

// Blender writes PLY z-up and says so in the header's comment; other PLY files (Stanford's scans)
// are y-up. The same 0.2 x 0.4 x 1 box, tall along the file's z, with and without that comment.
TEST(PrescoreCommand, APlyFileBlenderWroteStandsUp) {
    TempDir dir;
    const auto ply = [](const std::string& comment) {
        std::string s = "ply\nformat ascii 1.0\n" + comment +
                        "element vertex 8\nproperty float x\nproperty float y\nproperty float z\n"
                        "element face 12\nproperty list uchar uint vertex_indices\nend_header\n";
        for (int k = 0; k < 8; ++k) s += fmt::format("{} {} {}\n", 0.2 * (k & 1), 0.4 * ((k >> 1) & 1), 1.0 * (k >> 2));
        for (const char* f : {"0 2 1", "1 2 3", "4 5 6", "5 7 6", "0 1 4", "1 5 4", "2 6 3", "3 6 7", "0 4 2", "2 4 6",
                              "1 3 5", "3 7 5"})
            s += std::string("3 ") + f + "\n";
        return s;
    };
    auto r = run_shatter({"info", dir.write("blender.ply", ply("comment Created by Blender 3.4.1 - www.blender.org\n")), "--json"});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    auto j = nlohmann::json::parse(r.out);
    EXPECT_EQ(j["up"], "z");
    EXPECT_NEAR(j["size_m"][1].get<double>(), 0.3, 1e-6) << j["size_m"];
    r = run_shatter({"info", dir.write("scan.ply", ply("")), "--json"});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    j = nlohmann::json::parse(r.out);
    EXPECT_EQ(j["up"], "y");
    EXPECT_NEAR(j["size_m"][2].get<double>(), 0.3, 1e-6) << j["size_m"];
}

// Blender's own files are z-up and assimp reads them as they are: assimp's HUMAN.blend (a figure
// 10.7 units tall along the file's z, 1.6 deep along its y) stands along y.
TEST(PrescoreCommand, ABlenderFileStandsUp) {
    const auto r = run_shatter({"info", "/usr/share/assimp/models/BLEND/HUMAN.blend", "--json"});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto j = nlohmann::json::parse(r.out);
    EXPECT_EQ(j["up"], "z");
    EXPECT_NEAR(j["size_m"][1].get<double>(), 0.3, 1e-6) << j["size_m"];
    EXPECT_LT(j["size_m"][2].get<double>(), 0.1) << j["size_m"];
}

// One bad input: the exit code, a message naming `expect`, and no file left in the output folder.
struct BadCase {
    const char* name;
    std::string mesh_text;  // written to the input file ("" = no file)
    const char* mesh_name;
    std::vector<std::string> flags;
    int exit_code;
    const char* expect;
};

class PrescoreBadInput : public ::testing::TestWithParam<BadCase> {};

// Three faces of a tetrahedron: alpha wrapping turns the open soup into a sheet far thinner than
// a tet, which only thickening can fill.
const char* kOpenSoup = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 2 3 4\n";

// The open soup with the defaults: its walls are given a thickness, and the model says so.
TEST(PrescoreCommand, AnOpenSoupIsGivenAThicknessAndTheModelRecordsWhy) {
    TempDir dir;
    auto r = run_shatter({"prescore", dir.write("sheet.obj", kOpenSoup), "-o", dir.file("m.model")});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.err.find("auto: thicken: alpha wrap with offset"), std::string::npos) << r.err;
    auto info = run_shatter({"info", dir.file("m.model"), "--json"});
    ASSERT_EQ(info.exit_code, 0) << info.err;
    EXPECT_NE(info.out.find("thicken"), std::string::npos) << info.out;
    EXPECT_NE(info.out.find("the tets fall apart"), std::string::npos) << info.out;
}

TEST_P(PrescoreBadInput, ClearMessageNonZeroExitNoOutputLeft) {
    const BadCase& c = GetParam();
    TempDir in, out;
    std::string mesh = in.file(c.mesh_name);
    if (!c.mesh_text.empty()) in.write(c.mesh_name, c.mesh_text);
    std::vector<std::string> args = {"prescore", mesh, "-o", out.file("m.model")};
    args.insert(args.end(), c.flags.begin(), c.flags.end());
    auto r = run_shatter(args);
    EXPECT_EQ(r.exit_code, c.exit_code) << r.err;
    EXPECT_NE(r.err.find(c.expect), std::string::npos) << r.err;
    EXPECT_TRUE(out.entries().empty()) << "left behind: " << out.entries().front();
}

const char* kCube =
    "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
    "f 1 3 2\nf 1 4 3\nf 5 6 7\nf 5 7 8\nf 1 2 6\nf 1 6 5\nf 2 3 7\nf 2 7 6\nf 3 4 8\nf 3 8 7\nf 4 1 5\nf 4 5 8\n";

std::string open_cube() {  // the cube without its top (two triangles)
    std::string s = kCube;
    return s.substr(0, s.find("f 5 6 7")) + s.substr(s.find("f 1 2 6"));
}

INSTANTIATE_TEST_SUITE_P(
    Cases, PrescoreBadInput,
    ::testing::Values(
        BadCase{"MissingFile", "", "nothere.obj", {}, 3, "nothere.obj"},
        BadCase{"TextFileNamedObj", "this is not a mesh\njust words\n", "words.obj", {}, 3, "words.obj"},
        BadCase{"EmptyMesh", "# nothing\n", "empty.obj", {}, 3, "empty.obj"},
        BadCase{"NanCoordinates", std::string("v nan 0 0\n") + kCube, "nan.obj", {}, 3, "nan.obj"},
        BadCase{"MeshWithoutArea", "v 0 0 0\nv 1 0 0\nv 2 0 0\nv 3 0 0\nf 1 2 3\nf 2 3 4\n", "line.obj", {}, 3,
                "line.obj: the mesh has no area"},
        BadCase{"OpenMeshWithRepairOff", open_cube(), "open.obj", {"--repair", "never"}, 3, "--repair auto"},
        BadCase{"OpenSoupWrappedIntoASheetWithoutAdapt", kOpenSoup, "sheet.obj", {"--no-adapt"}, 3, "adapt"},
        BadCase{"MorePiecesThanTets", kCube, "cube.obj", {"--pieces", "100000"}, 3, "pieces"},
        BadCase{"ZeroThickness", kCube, "cube.obj", {"--hollow", "0"}, 2, "--hollow"},
        BadCase{"NegativeThickness", kCube, "cube.obj", {"--hollow=-0.1"}, 2, "--hollow"},
        BadCase{"NanDensity", kCube, "cube.obj", {"--density", "nan"}, 2, "--density"},
        BadCase{"UnknownFlag", kCube, "cube.obj", {"--peices", "3"}, 2, "peices"}),
    [](const auto& info) { return info.param.name; });

}  // namespace
}  // namespace shatter
