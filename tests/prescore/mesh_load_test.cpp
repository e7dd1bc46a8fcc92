// load_mesh: every format gives the same unit cube, scale is applied, meshes are merged, the
// real bunny loads with the counts docs/physics.md section 8 gives, and bad files are BadInput
// errors that name the file.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdlib>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/error.h"
#include "meshio/mesh_load.h"
#include "prescore/mesh_check.h"
#include "support/unit_cube.h"

namespace shatter {
namespace {

using testing_support::kCorners;
using testing_support::kFaces;

std::string temp_path(const std::string& name) {
    std::filesystem::path dir = std::filesystem::path(testing::TempDir()) / "shatter_mesh_load_test";
    std::filesystem::create_directories(dir);
    return (dir / name).string();
}

std::string write_file(const std::string& name, const std::string& text) {
    const std::string path = temp_path(name);
    std::ofstream(path, std::ios::binary) << text;
    return path;
}

std::string cube_obj() {
    std::ostringstream s;
    for (const auto& c : kCorners) s << "v " << c[0] << " " << c[1] << " " << c[2] << "\n";
    for (const auto& f : kFaces) s << "f " << f[0] + 1 << " " << f[1] + 1 << " " << f[2] + 1 << "\n";
    return s.str();
}

std::string cube_ply() {
    std::ostringstream s;
    s << "ply\nformat ascii 1.0\nelement vertex 8\nproperty float x\nproperty float y\n"
         "property float z\nelement face 12\nproperty list uchar int vertex_indices\nend_header\n";
    for (const auto& c : kCorners) s << c[0] << " " << c[1] << " " << c[2] << "\n";
    for (const auto& f : kFaces) s << "3 " << f[0] << " " << f[1] << " " << f[2] << "\n";
    return s.str();
}

std::string cube_stl() {
    std::ostringstream s;
    s << "solid cube\n";
    for (const auto& f : kFaces) {
        s << "facet normal 0 0 0\nouter loop\n";
        for (int i : f) s << "vertex " << kCorners[i][0] << " " << kCorners[i][1] << " " << kCorners[i][2] << "\n";
        s << "endloop\nendfacet\n";
    }
    s << "endsolid cube\n";
    return s.str();
}

std::string cube_off() {
    std::ostringstream s;
    s << "OFF\n8 12 0\n";
    for (const auto& c : kCorners) s << c[0] << " " << c[1] << " " << c[2] << "\n";
    for (const auto& f : kFaces) s << "3 " << f[0] << " " << f[1] << " " << f[2] << "\n";
    return s.str();
}

void expect_unit_cube(const TriangleMesh& mesh, double scale) {
    EXPECT_EQ(mesh.vertices.size(), 8u);
    EXPECT_EQ(mesh.triangles.size(), 12u);
    const MeshCheck check = check_mesh(mesh);
    EXPECT_NEAR(check.volume, scale * scale * scale, 1e-12);
    EXPECT_TRUE(check.closed());
    EXPECT_TRUE(check.manifold());
    EXPECT_TRUE(check.oriented());
    EXPECT_EQ(check.components, 1u);
    EXPECT_EQ(check.self_intersections, 0u);
}

TEST(LoadMesh, UnitCubeObjGivesEightVerticesTwelveTrianglesVolumeOne) {
    expect_unit_cube(load_mesh(write_file("cube.obj", cube_obj()), 1.0), 1.0);
}

TEST(LoadMesh, UnitCubeAsciiPlyGivesEightVerticesTwelveTrianglesVolumeOne) {
    expect_unit_cube(load_mesh(write_file("cube.ply", cube_ply()), 1.0), 1.0);
}

TEST(LoadMesh, UnitCubeAsciiStlJoinsItsUnsharedCornersIntoEightVertices) {
    expect_unit_cube(load_mesh(write_file("cube.stl", cube_stl()), 1.0), 1.0);
}

TEST(LoadMesh, UnitCubeOffGivesEightVerticesTwelveTrianglesVolumeOne) {
    expect_unit_cube(load_mesh(write_file("cube.off", cube_off()), 1.0), 1.0);
}

TEST(LoadMesh, ScaleHalfGivesVolumeOneEighth) {
    expect_unit_cube(load_mesh(write_file("cube_half.obj", cube_obj()), 0.5), 0.5);
}

TEST(LoadMesh, TwoObjectsSharingVertexPositionsAreMergedIntoOneClosedCube) {
    // Object "box" is the cube without its top (10 triangles); object "lid" is the top, written
    // with its own copies of the four top corners. Merging by position closes the cube.
    std::ostringstream s;
    s << "o box\n";
    for (const auto& c : kCorners) s << "v " << c[0] << " " << c[1] << " " << c[2] << "\n";
    for (int f = 0; f < 12; ++f) {
        if (f == 2 || f == 3) continue;
        s << "f " << kFaces[f][0] + 1 << " " << kFaces[f][1] + 1 << " " << kFaces[f][2] + 1 << "\n";
    }
    s << "o lid\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\nf 9 10 11\nf 9 11 12\n";
    const TriangleMesh mesh = load_mesh(write_file("two_objects.obj", s.str()), 1.0);
    expect_unit_cube(mesh, 1.0);
}

std::string base64(const std::string& bytes) {
    const char* table = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    for (size_t i = 0; i < bytes.size(); i += 3) {
        uint32_t n = uint32_t(uint8_t(bytes[i])) << 16;
        if (i + 1 < bytes.size()) n |= uint32_t(uint8_t(bytes[i + 1])) << 8;
        if (i + 2 < bytes.size()) n |= uint32_t(uint8_t(bytes[i + 2]));
        out += table[(n >> 18) & 63];
        out += table[(n >> 12) & 63];
        out += i + 1 < bytes.size() ? table[(n >> 6) & 63] : '=';
        out += i + 2 < bytes.size() ? table[n & 63] : '=';
    }
    return out;
}

// A glTF 2.0 file whose one cube mesh is used by two nodes: one untransformed, one translated
// by (3, 0, 0) and scaled by 2.
std::string cube_gltf_two_instances() {
    std::string buffer;
    for (const auto& c : kCorners)
        for (double x : c) {
            const float f = float(x);
            buffer.append(reinterpret_cast<const char*>(&f), 4);
        }
    for (const auto& face : kFaces)
        for (int i : face) {
            const uint16_t index = uint16_t(i);
            buffer.append(reinterpret_cast<const char*>(&index), 2);
        }
    std::ostringstream s;
    s << R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0, 1]}],
  "nodes": [{"mesh": 0}, {"mesh": 0, "translation": [3, 0, 0], "scale": [2, 2, 2]}],
  "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
  "buffers": [{"byteLength": 168, "uri": "data:application/octet-stream;base64,)"
      << base64(buffer) << R"("}],
  "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 96, "target": 34962},
                  {"buffer": 0, "byteOffset": 96, "byteLength": 72, "target": 34963}],
  "accessors": [{"bufferView": 0, "componentType": 5126, "count": 8, "type": "VEC3",
                 "min": [0, 0, 0], "max": [1, 1, 1]},
                {"bufferView": 1, "componentType": 5123, "count": 36, "type": "SCALAR"}]}
)";
    return s.str();
}

TEST(LoadMesh, GltfMeshUsedByTwoNodesGivesTwoCubesWithNodeTransformsApplied) {
    const TriangleMesh mesh = load_mesh(write_file("two_cubes.gltf", cube_gltf_two_instances()), 1.0);
    EXPECT_EQ(mesh.vertices.size(), 16u);
    EXPECT_EQ(mesh.triangles.size(), 24u);
    const MeshCheck check = check_mesh(mesh);
    EXPECT_NEAR(check.volume, 1.0 + 8.0, 1e-12);  // the unit cube and the cube of side 2
    EXPECT_EQ(check.components, 2u);
    EXPECT_TRUE(check.closed() && check.manifold() && check.oriented());
    EXPECT_EQ(check.bbox_max, Vec3(5, 2, 2));
}

// The unit cube moved by `offset` along every axis, as OBJ text (written exactly).
std::string cube_obj_at(double offset) {
    std::ostringstream s;
    s.precision(17);
    for (const auto& c : kCorners) s << "v " << c[0] + offset << " " << c[1] + offset << " " << c[2] + offset << "\n";
    for (const auto& f : kFaces) s << "f " << f[0] + 1 << " " << f[1] + 1 << " " << f[2] + 1 << "\n";
    return s.str();
}

// Single precision spaces numbers in [2^k, 2^(k+1)) by 2^(k-23): the unit cube (diagonal sqrt 3)
// read at 2.5 million units from the origin is rounded to steps of 2^-2, at 20,000 to 2^-9 (1.1e-3
// of its size: warned), at 4,000 to 2^-12 (1.4e-4: not); at the origin, to 2^-23.
TEST(LoadMesh, AMeshFarFromItsOriginIsToldHowCoarselySinglePrecisionRoundsIt) {
    const struct { double offset, step; bool warned; } cases[] = {
        {2.5e6, 0x1p-2, true}, {2e4, 0x1p-9, true}, {4e3, 0x1p-12, false}, {0, 0x1p-23, false}};
    for (const auto& c : cases) {
        const LoadedMesh loaded = load_mesh_file(write_file("cube_far.obj", cube_obj_at(c.offset)));
        EXPECT_EQ(loaded.rounding.step, c.step) << c.offset;
        EXPECT_EQ(loaded.rounding.coordinate, c.offset + 1) << c.offset;
        EXPECT_NEAR(loaded.rounding.size, std::sqrt(3.0), 1e-9 * (c.offset + 1)) << c.offset;
        const std::string hint = rounding_hint(loaded.rounding);
        EXPECT_EQ(!hint.empty(), c.warned) << c.offset << ": " << hint;
    }
    const std::string hint = rounding_hint(load_mesh_file(write_file("cube_far.obj", cube_obj_at(2.5e6))).rounding);
    for (const char* part : {"2.5e+06 units", "1.44e+06 times", "1.73 units across", "steps of 0.25 units", "14%",
                             "Move the object to the origin"})
        EXPECT_NE(hint.find(part), std::string::npos) << part << " in: " << hint;
    // Node transforms are applied in double precision: a mesh is measured by the coordinates its
    // file holds (the second cube, moved by 3 and scaled by 2, reaches 5 only after its transform).
    const LoadedMesh moved = load_mesh_file(write_file("two_cubes.gltf", cube_gltf_two_instances()));
    EXPECT_EQ(moved.rounding.coordinate, 1.0);
    EXPECT_EQ(rounding_hint(moved.rounding), "");
}

TEST(LoadMesh, GlmarkBunnyHasPhysicsMdCountsClosedManifoldOneComponentTwoCrossings) {
    const std::string bunny = "/usr/share/glmark2/models/bunny.obj";
    if (!std::filesystem::exists(bunny)) GTEST_SKIP() << bunny << " is not installed (glmark2-data)";
    auto start = std::chrono::steady_clock::now();
    const TriangleMesh mesh = load_mesh(bunny, 1.0);
    auto loaded = std::chrono::steady_clock::now();
    const MeshCheck check = check_mesh(mesh);
    auto checked = std::chrono::steady_clock::now();
    using ms = std::chrono::duration<double, std::milli>;
    std::printf("bunny: load %.0f ms, check %.0f ms: %s\n", ms(loaded - start).count(),
                ms(checked - loaded).count(), describe(check).c_str());
    EXPECT_EQ(mesh.vertices.size(), 34835u);
    EXPECT_EQ(mesh.triangles.size(), 69666u);
    EXPECT_TRUE(check.closed());
    EXPECT_TRUE(check.manifold());
    EXPECT_TRUE(check.oriented());
    EXPECT_GT(check.volume, 0);
    EXPECT_EQ(check.components, 1u);
    EXPECT_EQ(check.self_intersections, 2u);
    std::string why;
    EXPECT_TRUE(can_tetrahedralize(check, &why)) << why;
}

// Runs load_mesh and returns the BadInput error's message (fails the test otherwise).
std::string bad_input_message(const std::string& path, double scale = 1.0) {
    try {
        load_mesh(path, scale);
    } catch (const Error& e) {
        EXPECT_EQ(e.code(), ExitCode::BadInput) << e.what();
        return e.what();
    }
    ADD_FAILURE() << "load_mesh(" << path << ") did not throw";
    return "";
}

TEST(LoadMeshErrors, MissingFileIsBadInputNamingTheFile) {
    const std::string path = temp_path("no_such_mesh.obj");
    const std::string message = bad_input_message(path);
    EXPECT_NE(message.find(path), std::string::npos) << message;
    EXPECT_NE(message.find("does not exist"), std::string::npos) << message;
}

// A reader that runs past its deadline is killed and the file refused (assimp's PLY reader once
// spun for ever: tests/fuzz/regressions/mesh/ply-nul-after-magic-hang.seed). The deadline is
// minutes; SHATTER_MESH_IMPORT_TIMEOUT shortens it here to 1 ms, less than the bunny's ~0.1 s.
TEST(LoadMeshErrors, AReaderPastItsDeadlineIsKilledAndTheFileRefused) {
    const std::string bunny = "/usr/share/glmark2/models/bunny.obj";
    ASSERT_EQ(::setenv("SHATTER_MESH_IMPORT_TIMEOUT", "0.001", 1), 0);
    const std::string message = bad_input_message(bunny);
    ::unsetenv("SHATTER_MESH_IMPORT_TIMEOUT");
    EXPECT_NE(message.find(bunny + ": the mesh reader (assimp) did not finish within 0.001 s"), std::string::npos)
        << message;
    EXPECT_EQ(load_mesh(bunny, 1.0).triangles.size(), 69666u);  // and without the override it loads
}

TEST(LoadMeshErrors, TextFileNamedObjIsBadInputNamingTheFile) {
    const std::string path = write_file("letter.obj", "Dear reader,\nthis is not a mesh.\n");
    const std::string message = bad_input_message(path);
    EXPECT_NE(message.find(path), std::string::npos) << message;
    EXPECT_NE(message.find("no triangles"), std::string::npos) << message;
}

TEST(LoadMeshErrors, EmptyObjIsBadInputNamingTheFile) {
    const std::string path = write_file("empty.obj", "");
    const std::string message = bad_input_message(path);
    EXPECT_NE(message.find(path), std::string::npos) << message;
    EXPECT_NE(message.find("empty"), std::string::npos) << message;
}

// OpenSCAD's test data holds a .3mf that is the model's XML alone, not the ZIP package a 3MF is.
TEST(LoadMeshErrors, A3mfThatIsNotAZipIsBadInputSayingSo) {
    const std::string path = write_file("model.3mf", "<?xml version=\"1.0\"?>\n<model unit=\"millimeter\"></model>\n");
    try {
        load_mesh(path, 1.0);
        FAIL() << "accepted";
    } catch (const Error& e) {
        EXPECT_EQ(e.code(), ExitCode::BadInput);
        EXPECT_NE(std::string(e.what()).find("this one is not a ZIP (it is XML"), std::string::npos) << e.what();
    }
}

TEST(LoadMeshErrors, ObjWithOnlyVerticesIsBadInputWithNoTriangles) {
    const std::string path = write_file("vertices.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n");
    const std::string message = bad_input_message(path);
    EXPECT_NE(message.find(path), std::string::npos) << message;
    EXPECT_NE(message.find("no triangles"), std::string::npos) << message;
}

TEST(LoadMeshErrors, ObjIndexOutOfRangeIsBadInputWithAssimpsReason) {
    const std::string path = write_file("bad_index.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n");
    const std::string message = bad_input_message(path);
    EXPECT_NE(message.find(path), std::string::npos) << message;
    EXPECT_NE(message.find("out of range"), std::string::npos) << message;
}

TEST(LoadMeshErrors, ObjWithOnlyPointsAndLinesHasNoTriangles) {
    const std::string path = write_file("lines.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nl 1 2\nl 2 3\np 1\n");
    const std::string message = bad_input_message(path);
    EXPECT_NE(message.find(path), std::string::npos) << message;
    EXPECT_NE(message.find("no triangles"), std::string::npos) << message;
}

TEST(LoadMeshErrors, NanCoordinateIsBadInputNamingTheFileAndPosition) {
    std::string text = cube_obj();
    text.replace(text.find("v 1 1 1"), 7, "v 1 nan 1");
    const std::string path = write_file("nan.obj", text);
    const std::string message = bad_input_message(path);
    EXPECT_NE(message.find(path), std::string::npos) << message;
    // assimp renumbers vertices, so the message gives the bad position itself.
    EXPECT_NE(message.find("non-finite"), std::string::npos) << message;
    EXPECT_NE(message.find("(1, nan, 1)"), std::string::npos) << message;
}

TEST(LoadMeshErrors, ZeroNegativeAndInfiniteScaleAreBadInput) {
    const std::string path = write_file("cube_scale.obj", cube_obj());
    for (double scale : {0.0, -1.0, HUGE_VAL, std::nan("")}) {
        const std::string message = bad_input_message(path, scale);
        EXPECT_NE(message.find("scale"), std::string::npos) << message;
    }
}

}  // namespace
}  // namespace shatter
