// glTF files as web tools write them (meshio/gltf_extensions.h): gltfpack's quantized positions and
// texture coordinates (KHR_mesh_quantization, with a KHR_texture_transform scaling them back), the
// same meshopt-compressed (EXT_meshopt_compression), a texture transform in a plain file, and a
// WebP texture (EXT_texture_webp). Each reads as the OBJ it was made from: the same surface, and
// every triangle reads the same part of the texture; Khronos's texture transform test asset reads
// as it marks correct. A mesh instanced by a node (EXT_mesh_gpu_instancing) is drawn at every
// instance. A damaged compressed file is refused naming the file and the fix.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <fstream>
#include <iterator>
#include <optional>
#include <string>

#include "core/error.h"
#include "meshio/appearance.h"
#include "meshio/gltf_extensions.h"
#include "meshio/image_decode.h"
#include "meshio/mesh_load.h"
#include "support/temp_dir.h"

namespace shatter {
namespace {

const std::string kDir = SHATTER_SOURCE_DIR "/tests/fixtures/gltfpack/";

TEST(GltfExtensions, FindsTheExtensionsTheReaderCannotTake) {
    EXPECT_EQ(unreadable_gltf_extension(kDir + "textured_cube.quantized.glb"), "KHR_mesh_quantization");
    EXPECT_EQ(unreadable_gltf_extension(kDir + "textured_cube.meshopt.glb"), "EXT_meshopt_compression");
    EXPECT_EQ(unreadable_gltf_extension(kDir + "textured_cube.obj"), "");
    EXPECT_FALSE(plain_glb(kDir + "textured_cube.obj").has_value());
    EXPECT_EQ(unreadable_gltf_extension("/usr/share/assimp/models/glTF2/BoxTextured-glTF-Binary/BoxTextured.glb"), "");
}

// The unit cube: 8 corners, 12 triangles, the OBJ's volume and 1 m on a side (glTF is in metres),
// within gltfpack's 14-bit position grid.
TEST(GltfExtensions, QuantizedAndCompressedCubesReadAsTheCube) {
    // The signed volume (the divergence theorem): the same size and the same winding as the OBJ's
    // (whose faces the script wound inwards).
    const auto volume = [](const TriangleMesh& m) {
        double v = 0;
        for (const Tri& t : m.triangles) v += m.vertices[t[0]].dot(m.vertices[t[1]].cross(m.vertices[t[2]])) / 6;
        return v;
    };
    const double obj = volume(load_mesh_file(kDir + "textured_cube.obj").mesh);
    EXPECT_NEAR(std::abs(obj), 1.0, 1e-9);
    for (const char* name : {"textured_cube.quantized.glb", "textured_cube.meshopt.glb"}) {
        const LoadedMesh loaded = load_mesh_file(kDir + name);
        const TriangleMesh& m = loaded.mesh;
        EXPECT_EQ(m.vertices.size(), 8u) << name;
        EXPECT_EQ(m.triangles.size(), 12u) << name;
        EXPECT_NEAR(volume(m), obj, 1e-3) << name;
        Vec3 lo = Vec3::Constant(1e9), hi = -lo;
        for (const Vec3& v : m.vertices) lo = lo.cwiseMin(v), hi = hi.cwiseMax(v);
        EXPECT_NEAR((hi - lo - Vec3::Ones()).cwiseAbs().maxCoeff(), 0, 1e-3) << name;
        EXPECT_EQ(loaded.metres_per_unit, 1.0) << name;
    }
}

// Per triangle, its centre and the texture coordinate there: each packed triangle has one of the
// OBJ's at the same place reading the same point of the texture (within the 12-bit grid gltfpack
// quantizes coordinates to).
TEST(GltfExtensions, EveryTriangleReadsTheTextureWhereTheObjDoes) {
    const Appearance obj = load_appearance(kDir + "textured_cube.obj");
    ASSERT_EQ(obj.mesh.triangles.size(), 12u);
    ASSERT_EQ(obj.uv.size(), obj.mesh.vertices.size());
    const auto centre = [](const Appearance& a, size_t t) {
        Vec3 p = Vec3::Zero();
        std::array<double, 2> uv{0, 0};
        for (uint32_t v : a.mesh.triangles[t]) {
            p += a.mesh.vertices[v] / 3;
            uv[0] += a.uv[v][0] / 3, uv[1] += a.uv[v][1] / 3;
        }
        return std::make_pair(p, uv);
    };
    for (const char* name : {"textured_cube.quantized.glb", "textured_cube.meshopt.glb", "textured_cube.transformed.gltf",
                             "textured_cube.webp.glb"}) {
        const Appearance packed = load_appearance(kDir + name);
        ASSERT_EQ(packed.mesh.triangles.size(), 12u) << name;
        ASSERT_EQ(packed.uv.size(), packed.mesh.vertices.size()) << name;
        EXPECT_FALSE(packed.plain()) << name;
        int textured = 0;
        for (const Material& m : packed.materials) textured += !m.texture.empty();
        EXPECT_EQ(textured, 1) << name << ": the PNG comes embedded";
        for (size_t t = 0; t < packed.mesh.triangles.size(); ++t) {
            const auto [p, uv] = centre(packed, t);
            double best = 1e9, uv_error = 1e9;
            for (size_t o = 0; o < obj.mesh.triangles.size(); ++o) {
                const auto [q, uv_obj] = centre(obj, o);
                const double d = (p - q).norm();
                if (d < best) best = d, uv_error = std::max(std::abs(uv[0] - uv_obj[0]), std::abs(uv[1] - uv_obj[1]));
            }
            EXPECT_LT(best, 1e-3) << name << " triangle " << t;
            EXPECT_LT(uv_error, 2e-3) << name << " triangle " << t << " reads another part of the texture";
        }
    }
}

// The unit cube drawn three times by one node (EXT_mesh_gpu_instancing, rotations as normalized
// shorts): at the origin; 3 m along x turned 90 degrees about y (x from 3 to 4, z from -1 to 0);
// 3 m along z scaled 2. Three cubes of 1 + 1 + 8 m^3 within (0, 0, -1) to (4, 2, 5).
TEST(GltfExtensions, InstancedMeshesAreDrawnAtEveryInstance) {
    const TriangleMesh m = load_mesh_file(kDir + "instanced_cubes.glb").mesh;
    ASSERT_EQ(m.triangles.size(), 36u) << "an instance is missing";
    double volume = 0;
    for (const Tri& t : m.triangles) volume += m.vertices[t[0]].dot(m.vertices[t[1]].cross(m.vertices[t[2]])) / 6;
    EXPECT_NEAR(volume, 10, 1e-3);
    Vec3 lo = Vec3::Constant(1e9), hi = -lo;
    for (const Vec3& v : m.vertices) lo = lo.cwiseMin(v), hi = hi.cwiseMax(v);
    EXPECT_NEAR((lo - Vec3(0, 0, -1)).cwiseAbs().maxCoeff(), 0, 1e-3);
    EXPECT_NEAR((hi - Vec3(4, 2, 5)).cwiseAbs().maxCoeff(), 0, 1e-3);
}

// The cube whose texture is a lossless WebP of quadrants.png named only by EXT_texture_webp (as
// glTF-Transform writes it): its material carries the WebP, which decodes to the PNG's pixels.
TEST(GltfExtensions, AWebpTextureIsTheMaterialsImage) {
    const Appearance a = load_appearance(kDir + "textured_cube.webp.glb");
    const Material* textured = nullptr;
    for (const Material& m : a.materials)
        if (!m.texture.empty()) textured = &m;
    ASSERT_NE(textured, nullptr) << "the texture was dropped";
    EXPECT_EQ(textured->texture_mime, "image/webp");
    std::string png;
    {
        std::ifstream in(kDir + "quadrants.png", std::ios::binary);
        png.assign(std::istreambuf_iterator<char>(in), {});
    }
    std::string why;
    const std::optional<DecodedImage> webp = decode_image(textured->texture, &why), expected = decode_image(png, &why);
    ASSERT_TRUE(webp.has_value()) << why;
    ASSERT_TRUE(expected.has_value()) << why;
    EXPECT_EQ(webp->width, expected->width);
    EXPECT_EQ(webp->height, expected->height);
    EXPECT_EQ(webp->rgba, expected->rgba);
}

// A texture with only a KTX2 image (KHR_texture_basisu), which nothing on Debian decodes: a warning
// that names it and the fix, the material drawn in its base colour (assimp alone dropped it unsaid).
TEST(GltfExtensions, AKtx2TextureIsAWarningNamingIt) {
    const Appearance a = load_appearance(kDir + "textured_cube.ktx2.glb");
    for (const Material& m : a.materials) EXPECT_TRUE(m.texture.empty()) << m.name;
    ASSERT_EQ(a.warnings.size(), 1u);
    EXPECT_NE(a.warnings[0].find("KTX2"), std::string::npos) << a.warnings[0];
    EXPECT_NE(a.warnings[0].find("fix: export the model with PNG, JPEG or WebP textures"), std::string::npos) << a.warnings[0];
}

// Khronos's TextureTransformTest (assimp-testmodels): its "Rotation" quad (1 m, centred at
// (-1.1, -0.55), texture coordinates (0, 0) at its top-left corner to (1, 1)) reads Arrow.png, an
// arrow along the texture's diagonal, through a rotation of 22.5 degrees, with three markers
// around it. Seen from the quad's top-left corner the arrow points at the green one (at -67.5
// degrees) when the rotation is applied as glTF defines it, at the yellow one (-45) when it is
// not, and at the red one (-22.5) when it is applied the other way round.
TEST(GltfExtensions, TheKhronosTextureTransformArrowPointsAtItsGreenMarker) {
    const std::string path = "/usr/share/assimp/models/glTF2/textureTransform/TextureTransformTest.gltf";
    const Appearance a = load_appearance(path);
    ASSERT_EQ(a.uv.size(), a.mesh.vertices.size());
    // The quad's corners, each with its texture coordinate (v turned back to glTF's, downwards).
    const Vec3 centre(-1.1, -0.55, 0);
    std::vector<std::pair<Vec3, std::array<double, 2>>> corners;
    for (size_t v = 0; v < a.mesh.vertices.size(); ++v) {
        const Vec3 d = a.mesh.vertices[v] - centre;
        if (std::abs(d.z()) < 1e-6 && std::abs(std::abs(d.x()) - 0.5) < 1e-6 && std::abs(std::abs(d.y()) - 0.5) < 1e-6)
            corners.push_back({d, {a.uv[v][0], 1.0 - a.uv[v][1]}});
    }
    ASSERT_GE(corners.size(), 3u);
    // The affine map from the quad's (x, y) to its texture coordinates, from three corners.
    Eigen::Matrix3d xy1, uv1;
    for (int k = 0; k < 3; ++k) {
        xy1.col(k) << corners[size_t(k)].first.x(), corners[size_t(k)].first.y(), 1;
        uv1.col(k) << corners[size_t(k)].second[0], corners[size_t(k)].second[1], 1;
    }
    const Eigen::Matrix2d to_uv = (uv1 * xy1.inverse()).topLeftCorner<2, 2>();
    // The quad's direction along which the texture's diagonal (1, 1) runs.
    const Eigen::Vector2d along = to_uv.inverse() * Eigen::Vector2d(1, 1);
    const double degrees = std::atan2(along.y(), along.x()) * 180 / M_PI;
    EXPECT_NEAR(degrees, -67.5, 1.0) << "-45: the rotation was not applied; -22.5: it was applied the other way";
}

// A compressed buffer view cut short: refused with the file's name and gltfpack's fix.
TEST(GltfExtensions, ADamagedCompressedFileIsRefusedWithTheFix) {
    testing_support::TempDir dir;
    std::string bytes;
    {
        std::ifstream in(kDir + "textured_cube.meshopt.glb", std::ios::binary);
        bytes.assign(std::istreambuf_iterator<char>(in), {});
    }
    // The binary chunk's compressed bytes after the JSON, overwritten with zeros.
    const size_t json_length = size_t(uint8_t(bytes[12])) | size_t(uint8_t(bytes[13])) << 8;
    for (size_t i = 20 + json_length + 8; i < bytes.size(); ++i) bytes[i] = 0;
    const std::string path = dir.write("damaged.glb", bytes);
    try {
        (void)plain_glb(path);
        ADD_FAILURE() << "a damaged file decoded";
    } catch (const Error& e) {
        EXPECT_EQ(e.code(), ExitCode::BadInput);
        const std::string what = e.what();
        EXPECT_NE(what.find("damaged.glb"), std::string::npos) << what;
        EXPECT_NE(what.find("gltfpack -i FILE -o plain.glb -noq"), std::string::npos) << what;
    }
}

}  // namespace
}  // namespace shatter
