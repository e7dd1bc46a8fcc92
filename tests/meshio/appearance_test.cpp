// The input's appearance (meshio/appearance.h) on assimp-testmodels' textured files: the glTF
// box's embedded PNG and its texture coordinates, the Collada duck's TGA beside it, a missing
// texture as a warning, and positions that are load_mesh's.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <filesystem>
#include <fstream>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "meshio/appearance.h"
#include "meshio/mesh_load.h"
#include "support/temp_dir.h"

namespace shatter {
namespace {

const std::string kModels = "/usr/share/assimp/models";
const std::string kBox = kModels + "/glTF2/BoxTextured-glTF-Binary/BoxTextured.glb";
const std::string kDuck = kModels + "/Collada/duck.dae";

bool have(const std::string& path) { return std::filesystem::exists(path); }

// The box: 6 faces of 2 triangles, each face its own 4 vertices (24, the UV seams kept), one
// material whose base colour texture is the embedded PNG (CesiumLogoFlat.png, 2,433 bytes in the
// glTF version of the same file), every UV within [0, 6] (the texture repeats).
TEST(Appearance, GltfBoxKeepsItsEmbeddedPngAndTextureCoordinates) {
    if (!have(kBox)) GTEST_SKIP() << kBox << " is missing (fix: scripts/install-deps.sh installs assimp-testmodels)";
    const Appearance a = load_appearance(kBox);
    EXPECT_EQ(a.mesh.triangles.size(), 12u);
    EXPECT_EQ(a.mesh.vertices.size(), 24u);
    ASSERT_EQ(a.uv.size(), 24u);
    EXPECT_TRUE(a.colour.empty());
    ASSERT_EQ(a.material.size(), 12u);
    const Material& m = a.materials.at(a.material[0]);
    EXPECT_EQ(m.texture_mime, "image/png");
    EXPECT_EQ(m.texture.size(), 2433u);
    EXPECT_EQ(m.texture_name, "*0");
    EXPECT_TRUE(a.warnings.empty());
    EXPECT_FALSE(a.plain());
    for (const auto& uv : a.uv) {
        EXPECT_GE(std::min(uv[0], uv[1]), 0.0f);
        EXPECT_LE(std::max(uv[0], uv[1]), 6.0f);
    }
    // The same positions as load_mesh's (which joins them): every vertex is one of its 8 corners.
    const TriangleMesh joined = load_mesh_file(kBox).mesh;
    EXPECT_EQ(joined.vertices.size(), 8u);
    for (const Vec3& v : a.mesh.vertices)
        EXPECT_NE(std::find(joined.vertices.begin(), joined.vertices.end(), v), joined.vertices.end());
}

// The duck: its material names ./duckCM.tga, found beside the file and kept as the file's bytes.
TEST(Appearance, ColladaDuckFindsItsTgaBesideTheFile) {
    if (!have(kDuck)) GTEST_SKIP() << kDuck << " is missing";
    const Appearance a = load_appearance(kDuck);
    EXPECT_EQ(a.mesh.triangles.size(), 4212u);
    EXPECT_EQ(a.uv.size(), a.mesh.vertices.size());
    std::set<uint32_t> used(a.material.begin(), a.material.end());
    ASSERT_EQ(used.size(), 1u);
    const Material& m = a.materials.at(*used.begin());
    EXPECT_EQ(m.texture_mime, "image/x-tga");
    EXPECT_EQ(m.texture.size(), std::filesystem::file_size(kModels + "/Collada/duckCM.tga"));
    EXPECT_EQ(m.texture_name, "duckCM.tga");
    EXPECT_TRUE(a.warnings.empty());
    // Its positions are load_mesh's (which joins them), each as read: the duck has no symmetry
    // that would hide two axes swapped (as the isolated import's read once did).
    const TriangleMesh joined = load_mesh_file(kDuck).mesh;
    std::set<std::array<double, 3>> places;
    for (const Vec3& v : joined.vertices) places.insert({v.x(), v.y(), v.z()});
    size_t found = 0;
    for (const Vec3& v : a.mesh.vertices) found += places.count({v.x(), v.y(), v.z()});
    EXPECT_EQ(found, a.mesh.vertices.size());
}

// A texture mapped by a projection instead of UVs (LightWave's spherical mapping): assimp turns
// it into texture coordinates, around the sphere in u and from pole to pole in v.
TEST(Appearance, SphericalMappingBecomesTextureCoordinates) {
    const std::string earth = kModels + "/LWO/LWO2/MappingModes/earth_spherical_y.lwo";
    if (!have(earth)) GTEST_SKIP() << earth << " is missing";
    const Appearance a = load_appearance(earth);
    ASSERT_EQ(a.uv.size(), a.mesh.vertices.size());
    float lo[2] = {1e9f, 1e9f}, hi[2] = {-1e9f, -1e9f};
    for (const auto& uv : a.uv)
        for (int i = 0; i < 2; ++i) lo[i] = std::min(lo[i], uv[size_t(i)]), hi[i] = std::max(hi[i], uv[size_t(i)]);
    for (int i = 0; i < 2; ++i) {
        EXPECT_LT(lo[i], 0.05f) << i;
        EXPECT_GT(hi[i], 0.95f) << i;
    }
    EXPECT_FALSE(a.plain());
}

// The duck copied without its texture: a warning naming the texture, the material untextured.
TEST(Appearance, AMissingTextureIsAWarningNotAnError) {
    if (!have(kDuck)) GTEST_SKIP() << kDuck << " is missing";
    testing_support::TempDir dir;
    std::filesystem::copy_file(kDuck, dir.file("duck.dae"));
    const Appearance a = load_appearance(dir.file("duck.dae"));
    ASSERT_EQ(a.warnings.size(), 1u);
    EXPECT_NE(a.warnings[0].find("duckCM.tga"), std::string::npos) << a.warnings[0];
    for (const Material& m : a.materials) EXPECT_TRUE(m.texture.empty());
    EXPECT_EQ(a.mesh.triangles.size(), 4212u);
}

// The duck copied with its texture named in other letters (as files made on Windows name them),
// beside it and in a folder beside it: found by its name in any case, beside it first.
TEST(Appearance, ATextureIsFoundByItsNameInAnyLetterCaseBesideTheFileOrInAFolderBesideIt) {
    if (!have(kDuck)) GTEST_SKIP() << kDuck << " is missing";
    const std::string tga = kModels + "/Collada/duckCM.tga";
    const auto texture_of = [](const Appearance& a) {
        std::set<uint32_t> used(a.material.begin(), a.material.end());
        EXPECT_EQ(used.size(), 1u);
        return a.materials.at(*used.begin());
    };
    testing_support::TempDir dir;
    std::filesystem::copy_file(kDuck, dir.file("duck.dae"));
    std::filesystem::create_directory(dir.file("textures"));
    std::filesystem::copy_file(tga, dir.file("textures/DuckCM.tga"));
    Appearance a = load_appearance(dir.file("duck.dae"));
    EXPECT_TRUE(a.warnings.empty());
    EXPECT_EQ(texture_of(a).texture.size(), std::filesystem::file_size(tga));
    EXPECT_EQ(texture_of(a).texture_name, "DuckCM.tga");
    std::filesystem::copy_file(tga, dir.file("DUCKcm.TGA"));
    a = load_appearance(dir.file("duck.dae"));
    EXPECT_TRUE(a.warnings.empty());
    EXPECT_EQ(texture_of(a).texture_name, "DUCKcm.TGA");
}

// Game mods and asset packs keep models/ and textures/ side by side (Minetest's carts: models/
// carts_cart.b3d naming carts_cart.png in textures/): the duck in models/, its texture in textures/.
TEST(Appearance, ATextureIsFoundInAFolderBesideTheMeshFilesFolder) {
    if (!have(kDuck)) GTEST_SKIP() << kDuck << " is missing";
    const std::string tga = kModels + "/Collada/duckCM.tga";
    testing_support::TempDir dir;
    std::filesystem::create_directories(dir.file("models"));
    std::filesystem::create_directories(dir.file("textures"));
    std::filesystem::copy_file(kDuck, dir.file("models/duck.dae"));
    Appearance a = load_appearance(dir.file("models/duck.dae"));
    EXPECT_EQ(a.warnings.size(), 1u) << "not found yet";
    std::filesystem::copy_file(tga, dir.file("textures/duckCM.tga"));
    a = load_appearance(dir.file("models/duck.dae"));
    EXPECT_TRUE(a.warnings.empty());
    bool found = false;
    for (const Material& m : a.materials) found = found || m.texture.size() == std::filesystem::file_size(tga);
    EXPECT_TRUE(found);
}

// assimp's FBX spider names its textures where it was made (D:\projects\...\models\OBJ\drkwood2.jpg,
// ...); copied to models/FBX/ with the images in models/OBJ/, each is found by the
// written path's last folder and name under the folder above the file's.
TEST(Appearance, ATextureIsFoundByTheEndOfItsWrittenPathAboveTheFile) {
    const std::string spider = kModels + "/FBX/spider.fbx";
    if (!have(spider)) GTEST_SKIP() << spider << " is missing";
    testing_support::TempDir dir;
    std::filesystem::create_directories(dir.file("models/FBX"));
    std::filesystem::create_directories(dir.file("models/OBJ"));
    std::filesystem::copy_file(spider, dir.file("models/FBX/spider.fbx"));
    for (const char* image : {"drkwood2.jpg", "wal67ar_small.jpg", "wal69ar_small.jpg", "engineflare1.jpg", "SpiderTex.jpg"})
        std::filesystem::copy_file(kModels + "/OBJ/" + image, dir.file(std::string("models/OBJ/") + image));
    const Appearance a = load_appearance(dir.file("models/FBX/spider.fbx"));
    EXPECT_TRUE(a.warnings.empty()) << a.warnings.front();
    size_t textured = 0;
    for (const Material& m : a.materials) textured += !m.texture.empty();
    EXPECT_EQ(textured, 4u);
}

TEST(Appearance, ImageTypesByTheirFirstBytesElseTheirName) {
    EXPECT_EQ(image_mime("\x89PNG\r\n\x1a\nrest", "x.tga"), "image/png");
    EXPECT_EQ(image_mime("\xff\xd8\xff\xe0", "x"), "image/jpeg");
    EXPECT_EQ(image_mime(std::string("RIFF\x40\0\0\0WEBPVP8L", 16), "x.png"), "image/webp");
    EXPECT_EQ(image_mime("whatever", "a/b/C.TGA"), "image/x-tga");
    EXPECT_EQ(image_mime("whatever", "c.xyz"), "");
}

// prescore reads a file's appearance a second time only when load_mesh_file did not find it plain
// (LoadedMesh::plain: no vertex colours, no texture, materials white or assimp's default). That
// must never skip anything: every file it calls plain has a plain appearance and no warnings, and
// the files that show something (a texture, vertex colours, a grey or named material, a texture
// not found) are not plain.
TEST(Appearance, AFileTheReaderCallsPlainShowsNothingBeyondItsShape) {
    const std::vector<std::pair<std::string, bool>> files = {
        {"/usr/share/glmark2/models/bunny.obj", true},         // no material library
        {kModels + "/STL/Wuson.stl", true},
        {kModels + "/PLY/Wuson.ply", true},
        {kModels + "/OBJ/box.obj", false},                    // a material 'Default', grey
        {kModels + "/OBJ/cube_with_vertexcolors.obj", false},  // vertex colours
        {kModels + "/OBJ/cube_usemtl.obj", false},             // named materials
        {kModels + "/OBJ/spider.obj", false},                  // textures, some not beside it
        {kBox, false},
        {kDuck, false},
    };
    size_t checked = 0;
    for (const auto& [path, expected] : files) {
        if (!have(path)) continue;
        ++checked;
        const bool plain = load_mesh_file(path).plain;
        EXPECT_EQ(plain, expected) << path;
        const Appearance a = load_appearance(path);
        if (plain) {
            EXPECT_TRUE(a.plain()) << path;
            EXPECT_TRUE(a.warnings.empty()) << path;
        }
    }
    if (checked == 0) GTEST_SKIP() << "none of the files is installed (fix: scripts/install-deps.sh)";
}

}  // namespace
}  // namespace shatter
