// The frozen model fixture of every accepted version still reads, with the numbers it was made
// with (tests/fixtures/README.md).
#include <gtest/gtest.h>

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

}  // namespace
}  // namespace shatter
