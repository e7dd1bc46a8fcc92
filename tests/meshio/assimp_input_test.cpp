// Files assimp 5.2 misreads, made readable (meshio/assimp_input.h): the same unit cube from a
// UTF-16 OBJ (either byte order, with its UTF-16 material library), an OFF file with comments
// after its numbers, a zipped AMF and glmark2's .jobj; AMF without colours; the jellyfish itself;
// and the decoders' edges.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/error.h"
#include "meshio/appearance.h"
#include "meshio/assimp_input.h"
#include "meshio/mesh_load.h"
#include "support/unit_cube.h"

namespace shatter {
namespace {

using testing_support::kCorners;
using testing_support::kFaces;

std::string write_file(const std::string& name, const std::string& bytes) {
    const std::filesystem::path dir = std::filesystem::path(testing::TempDir()) / "shatter_assimp_input_test";
    std::filesystem::create_directories(dir);
    const std::string path = (dir / name).string();
    std::ofstream(path, std::ios::binary) << bytes;
    return path;
}

// ASCII `text` as UTF-16 with its byte-order mark, in either byte order, lines ending in CR LF
// as Windows writes them.
std::string utf16(const std::string& text, bool little) {
    std::string out = little ? std::string("\xFF\xFE") : std::string("\xFE\xFF");
    for (char c : text) {
        for (char u : c == '\n' ? std::string("\r\n") : std::string(1, c)) {
            out += little ? std::string{u, '\0'} : std::string{'\0', u};
        }
    }
    return out;
}

std::string cube_obj(const std::string& header) {
    std::ostringstream s;
    s << header;
    for (const auto& c : kCorners) s << "v " << c[0] << " " << c[1] << " " << c[2] << "\n";
    for (const auto& f : kFaces) s << "f " << f[0] + 1 << " " << f[1] + 1 << " " << f[2] + 1 << "\n";
    return s.str();
}

void expect_unit_cube(const TriangleMesh& mesh) {
    EXPECT_EQ(mesh.vertices.size(), 8u);
    EXPECT_EQ(mesh.triangles.size(), 12u);
    double volume = 0;  // the divergence theorem over the outward triangles
    for (const auto& t : mesh.triangles)
        volume += mesh.vertices[t[0]].dot(mesh.vertices[t[1]].cross(mesh.vertices[t[2]])) / 6;
    EXPECT_NEAR(volume, 1.0, 1e-12);
}

TEST(AssimpInput, AUtf16ObjInEitherByteOrderIsTheUnitCubeWithItsUtf16MaterialsColour) {
    for (bool little : {true, false}) {
        const std::string name = little ? "le" : "be";
        write_file(name + ".mtl", utf16("newmtl red\nKd 1 0 0\n", little));
        const std::string obj =
            write_file(name + ".obj", utf16(cube_obj("mtllib " + name + ".mtl\nusemtl red\n"), little));
        SCOPED_TRACE(name);
        expect_unit_cube(load_mesh(obj, 1.0));
        const Appearance a = load_appearance(obj);
        bool red = false;
        for (const Material& m : a.materials) red = red || (m.base_colour[0] == 1 && m.base_colour[1] == 0);
        EXPECT_TRUE(red) << "the material library, in UTF-16 too, is read";
    }
}

TEST(AssimpInput, AnOffFileWithCommentsAfterItsNumbersIsTheUnitCubeWithItsColours) {
    std::ostringstream s;
    s << "# a comment first\nCOFF\n8 12 0 # counts\n";
    for (const auto& c : kCorners) s << c[0] << " " << c[1] << " " << c[2] << " 0.9 0 0 #red\n";
    for (const auto& f : kFaces) s << "3 " << f[0] << " " << f[1] << " " << f[2] << "#a face\n";
    const std::string off = write_file("commented.off", s.str());
    expect_unit_cube(load_mesh(off, 1.0));
    const Appearance a = load_appearance(off);
    ASSERT_EQ(a.colour.size(), a.mesh.vertices.size());
    EXPECT_NEAR(a.colour.front()[1], 0.0, 1e-6);
    EXPECT_GT(a.colour.front()[0], 0.5);
}

// CGAL's OFF writer puts comment lines between the counts, the vertices and the faces; assimp
// 5.2 read each such line in place of a face (CGAL's cube_poly.off: 10 of its 12 triangles).
TEST(AssimpInput, AnOffFileWithCommentLinesAsCgalWritesThemKeepsEveryFace) {
    std::ostringstream s;
    s << "OFF\n8 12 0\n# vertices\n";
    for (const auto& c : kCorners) s << c[0] << " " << c[1] << " " << c[2] << "\n";
    s << "# facets\n";
    for (const auto& f : kFaces) s << "3 " << f[0] << " " << f[1] << " " << f[2] << "\n";
    s << "\n# End of OFF #\n";
    expect_unit_cube(load_mesh(write_file("cgal.off", s.str()), 1.0));
}

TEST(AssimpInput, AJobjIsTheUnitCubeAndItsIndicesAreChecked) {
    std::ostringstream s;
    for (const auto& c : kCorners) s << "v " << c[0] << " " << c[1] << " " << c[2] << "\nvn 0 0 1\nvt 0 0 0\n";
    for (const auto& f : kFaces) s << "i " << f[0] << "\ni " << f[1] << "\ni " << f[2] << "\n";
    expect_unit_cube(load_mesh(write_file("cube.jobj", s.str()), 1.0));

    const auto problem = [](const std::string& text) {
        try {
            jobj_as_obj(text, "x.jobj");
        } catch (const Error& e) {
            EXPECT_EQ(e.code(), ExitCode::BadInput);
            return std::string(e.what());
        }
        return std::string("accepted");
    };
    EXPECT_NE(problem("v 0 0 0\nv 1 0 0\nv 0 1 0\ni 0\ni 1\ni 3\n").find("x.jobj:6"), std::string::npos);
    EXPECT_NE(problem("v 0 0 0\ni 0\ni 0\n").find("left over"), std::string::npos);
    EXPECT_NE(problem("v 0 0 zero\n").find("x.jobj:1"), std::string::npos);
    EXPECT_NE(problem("i -1\n").find("whole number"), std::string::npos);
    EXPECT_EQ(jobj_as_obj("v 0 0 0\nv 1 0 0\nv 0 1 0\ni 2\ni 1\ni 0\n", "x.jobj"),
              "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 3 2 1\n");
}

TEST(AssimpInput, AZippedAmfIsTheUnitCube) {
    expect_unit_cube(load_mesh(SHATTER_SOURCE_DIR "/tests/fixtures/amf/cube_zipped.amf", 1.0));
}

// assimp's AMF reader gives every vertex a colour, (0, 0, 0, 0) where the file has none: an AMF
// without colours is plain (drawn in its material's colour, not black), one with them keeps them.
TEST(AssimpInput, AnAmfWithoutColoursIsPlainAndOneWithThemKeepsThem) {
    const std::string amf = SHATTER_SOURCE_DIR "/tests/fixtures/amf/cube_zipped.amf";
    EXPECT_TRUE(load_mesh_file(amf).plain);
    EXPECT_TRUE(load_appearance(amf).colour.empty());
    const std::string green = "/usr/share/assimp/models/AMF/test2.amf";  // a green tetrahedron
    if (!std::filesystem::exists(green)) GTEST_SKIP() << green << " is missing (fix: scripts/install-deps.sh)";
    EXPECT_FALSE(load_mesh_file(green).plain);
    const Appearance a = load_appearance(green);
    ASSERT_FALSE(a.colour.empty());
    EXPECT_GT(a.colour.front()[1], a.colour.front()[0]);
}

// glmark2's jellyfish (the one model of glmark2-data assimp reads as points): 13,200 indices,
// 4,400 triangles over 2,808 vertices, 9.9 units tall.
TEST(AssimpInput, GlmarkJellyfishHas4400Triangles) {
    const std::string path = "/usr/share/glmark2/models/jellyfish.jobj";
    if (!std::filesystem::exists(path)) GTEST_SKIP() << path << " is missing (fix: scripts/install-deps.sh)";
    const LoadedMesh loaded = load_mesh_file(path);
    EXPECT_EQ(loaded.mesh.triangles.size(), 4400u);
    double lo = 1e9, hi = -1e9;
    for (const auto& v : loaded.mesh.vertices) lo = std::min(lo, v.y()), hi = std::max(hi, v.y());
    EXPECT_NEAR(hi - lo, 1.56851112843 + 9.26005458832, 1e-5);
}

TEST(AssimpInput, Utf16DecodesSurrogatePairsAndRefusesWhatIsNotText) {
    // U+00E6 (2 bytes), U+20AC (3) and U+1F600 (a surrogate pair; 4) after the mark.
    EXPECT_EQ(utf16_as_utf8(std::string("\xFF\xFE\xE6\x00\xAC\x20\x3D\xD8\x00\xDE", 10)),
              "\xC3\xA6\xE2\x82\xAC\xF0\x9F\x98\x80");
    EXPECT_EQ(utf16_as_utf8(std::string("\xFE\xFF\x00\x61", 4)), "a");
    EXPECT_FALSE(utf16_as_utf8(std::string("\xFF\xFE\x61\x00\x00\x00", 6)));  // a NUL: binary
    EXPECT_FALSE(utf16_as_utf8(std::string("\xFF\xFE\x61", 3)));              // an odd length
    EXPECT_FALSE(utf16_as_utf8(std::string("\xFF\xFE\x00\xDC", 4)));          // a lone low surrogate
    EXPECT_FALSE(utf16_as_utf8("solid cube"));                                // no mark
}

TEST(AssimpInput, OffCommentsGoAndColoursOfThreeGetAnAlpha) {
    EXPECT_EQ(off_for_assimp("#c\nOFF\n1 0 0 # n\n\n0 0 0#x\n"), "OFF\n1 0 0 \n0 0 0\n");
    EXPECT_FALSE(off_for_assimp("OFF\n1 0 0\n0 0 0\n"));
    EXPECT_EQ(off_for_assimp("COFF 2 0 0\n1 2 3 0.5 0.5 0.5\n4 5 6 1 0 0 1\n"),
              "COFF 2 0 0\n1 2 3 0.5 0.5 0.5 1\n4 5 6 1 0 0 1\n");
    EXPECT_EQ(off_for_assimp("CNOFF\n1 0 0\n1 2 3 0 0 1 0.5 0.5 0.5\n3 0 0 0\n"),
              "CNOFF\n1 0 0\n1 2 3 0 0 1 0.5 0.5 0.5 1\n3 0 0 0\n");
}

}  // namespace
}  // namespace shatter
