// The frozen model fixture of every accepted version still reads, with the numbers it was made
// with (tests/fixtures/README.md).
#include <gtest/gtest.h>

#include "core/error.h"
#include "core/model_io.h"

namespace shatter {
namespace {

TEST(ModelFixture, Version1FixtureReadsWithItsKnownContents) {
    Model m = load_model(SHATTER_SOURCE_DIR "/tests/fixtures/model-v1.model");
    EXPECT_EQ(m.producer, "shatter 0.1.0");
    ASSERT_EQ(m.pieces.size(), 2u);
    EXPECT_EQ(m.mesh.tets.size(), 56u);
    EXPECT_EQ(m.constraints.size(), 8u);
    double mass = 0, volume = 0;
    Vec3 moment = Vec3::Zero();
    for (const Piece& p : m.pieces) {
        mass += p.mass.mass;
        volume += p.mass.volume;
        moment += p.mass.mass * p.mass.center;
    }
    EXPECT_NEAR(volume, 1e-3, 1e-15);  // a 10 cm cube, meshed with its edges protected
    EXPECT_NEAR(mass, 1.0, 1e-12);     // at 1000 kg/m^3
    EXPECT_LT((moment / mass - Vec3(0.05, 0.05, 0.05)).norm(), 1e-12);
    double area = 0;
    for (const Constraint& c : m.constraints) area += c.area;
    EXPECT_GT(area, 0.0);
    EXPECT_LE(area, 0.1 * 0.1 * std::sqrt(3.0));  // no interface in a cube is larger than its diagonal section
    for (const Piece& p : m.pieces) EXPECT_FALSE(p.render);  // version 1: drawn with the tet surfaces
}

// Version 2: the same cube with render surfaces, the cube's own faces cut per piece.
TEST(ModelFixture, Version2FixtureReadsWithItsRenderSurfaces) {
    Model m = load_model(SHATTER_SOURCE_DIR "/tests/fixtures/model-v2.model");
    ASSERT_EQ(m.pieces.size(), 2u);
    EXPECT_EQ(m.mesh.tets.size(), 56u);
    EXPECT_EQ(m.constraints.size(), 8u);
    double mass = 0;
    for (const Piece& p : m.pieces) mass += p.mass.mass;
    EXPECT_NEAR(mass, 1.0, 1e-12);
    for (const Piece& p : m.pieces) {
        ASSERT_TRUE(p.render);
        const RenderSurface& rs = *p.render;
        EXPECT_FALSE(rs.fell_back);
        ASSERT_EQ(rs.normals.size(), rs.vertices.size());
        ASSERT_EQ(rs.kinds.size(), rs.triangles.size());
        size_t outer = 0, fracture = 0;
        for (FaceKind k : rs.kinds) outer += k == FaceKind::Outer, fracture += k == FaceKind::Fracture;
        EXPECT_GT(outer, 0u);
        EXPECT_GT(fracture, 0u);
        // The cube's faces: every outer vertex's normal is an axis (its faces are flat, creases sharp).
        for (size_t t = 0; t < rs.triangles.size(); ++t) {
            if (rs.kinds[t] != FaceKind::Outer) continue;
            for (uint32_t v : rs.triangles[t]) EXPECT_NEAR(rs.normals[v].cwiseAbs().maxCoeff(), 1.0, 1e-9);
            for (uint32_t v : rs.triangles[t]) {
                const Vec3& x = rs.vertices[v];
                EXPECT_GE(x.minCoeff(), -1e-9);
                EXPECT_LE(x.maxCoeff(), 0.1 + 1e-9);
            }
        }
    }
}

// Version 3: the textured glTF box (assimp-testmodels' BoxTextured.glb) at 10 cm in 2 pieces,
// each render surface with texture coordinates and materials, the model with the file's two
// materials (assimp's default and the textured one, its embedded 2,433-byte PNG).
TEST(ModelFixture, Version3FixtureReadsWithItsMaterialsAndTextureCoordinates) {
    Model m = load_model(SHATTER_SOURCE_DIR "/tests/fixtures/model-v3.model");
    ASSERT_EQ(m.pieces.size(), 2u);
    EXPECT_EQ(m.mesh.tets.size(), 56u);
    ASSERT_EQ(m.materials.size(), 2u);
    const uint32_t t = m.materials[0].texture.empty() ? 1 : 0;  // the textured one
    const Material& textured = m.materials[t];
    EXPECT_EQ(textured.texture_mime, "image/png");
    ASSERT_EQ(textured.texture.size(), 2433u);
    EXPECT_EQ(textured.texture.compare(1, 3, "PNG"), 0);
    EXPECT_TRUE(m.materials[1 - t].texture.empty());
    for (const Piece& p : m.pieces) {
        ASSERT_TRUE(p.render);
        const RenderSurface& rs = *p.render;
        EXPECT_EQ(rs.uv.size(), rs.vertices.size());
        EXPECT_TRUE(rs.colour.empty());
        ASSERT_EQ(rs.material.size(), rs.triangles.size());
        for (uint32_t i : rs.material) EXPECT_EQ(i, t);
    }
}

// The version 3 fields come back as written, and the bytes are the same when written again.
TEST(ModelFixture, AppearanceRoundTripsAndABadMaterialIndexIsRefused) {
    Model m = load_model(SHATTER_SOURCE_DIR "/tests/fixtures/model-v2.model");
    m.materials = {Material{"plain", {0.25f, 0.5f, 0.75f, 1}, "", "", ""},
                   Material{"tex", {1, 1, 1, 0.5f}, std::string("\x89PNG\0bytes", 10), "image/png", "a.png"}};
    RenderSurface& rs = *m.pieces[0].render;
    for (size_t v = 0; v < rs.vertices.size(); ++v) {
        rs.uv.push_back({float(v) * 0.5f, -float(v)});
        rs.colour.push_back({0.1f, 0.2f, 0.3f, float(v % 2)});
    }
    for (size_t t = 0; t < rs.triangles.size(); ++t) rs.material.push_back(uint32_t(t % 2));
    const std::string bytes = encode_model(m);
    const Model back = decode_model(bytes, "m.model");
    ASSERT_EQ(back.materials.size(), 2u);
    EXPECT_EQ(back.materials[1].texture, m.materials[1].texture);
    EXPECT_EQ(back.materials[1].texture_mime, "image/png");
    EXPECT_EQ(back.materials[1].texture_name, "a.png");
    EXPECT_EQ(back.materials[0].base_colour, m.materials[0].base_colour);
    EXPECT_EQ(back.pieces[0].render->uv, rs.uv);
    EXPECT_EQ(back.pieces[0].render->colour, rs.colour);
    EXPECT_EQ(back.pieces[0].render->material, rs.material);
    EXPECT_TRUE(back.pieces[1].render->uv.empty());  // piece 1 has none
    EXPECT_EQ(encode_model(back), bytes);

    rs.material[0] = 2;  // of 2 materials
    EXPECT_THROW(decode_model(encode_model(m), "m.model"), Error);
}

}  // namespace
}  // namespace shatter
