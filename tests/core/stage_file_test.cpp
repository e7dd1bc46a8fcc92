#include <gtest/gtest.h>

#include "core/error.h"
#include "core/model_io.h"
#include "core/stage_file.h"

namespace shatter {
namespace {

Model small_model() {
    Model m;
    m.producer = producer_string();
    m.settings_json = R"({"pieces":2})";
    m.density = 1000;
    m.mesh.vertices = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1), Vec3(1, 1, 1)};
    m.mesh.tets = {{0, 1, 2, 3}, {1, 2, 3, 4}};
    m.tet_piece = {0, 1};
    m.pieces.resize(2);
    for (uint32_t i = 0; i < 2; ++i) {
        Piece& p = m.pieces[i];
        p.tets = {i};
        p.surface.vertices = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)};
        p.surface.triangles = {{0, 1, 2}};
        p.surface.kinds = {i ? FaceKind::Fracture : FaceKind::Outer};
        p.mass.volume = 1.0 / 6;
        p.mass.mass = 1000.0 / 6;
        p.mass.center = Vec3(0.25, 0.25, 0.25 + i);
        p.mass.inertia = Mat3::Identity() * 3;
        p.collision.push_back({{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)}, 1.0 / 6, 1.0 / 6});
    }
    // Piece 1 has a render surface (version 2), piece 0 none.
    RenderSurface rs;
    rs.vertices = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)};
    rs.normals = {Vec3(0, 0, -1), Vec3(0.6, 0, -0.8), Vec3(0, 0.6, -0.8), Vec3(0, 1, 0)};
    rs.triangles = {{0, 2, 1}, {0, 1, 3}};
    rs.kinds = {FaceKind::Outer, FaceKind::Fracture};
    m.pieces[1].render = rs;
    m.constraints = {{0, 1, 1, Vec3(1, 0, 0), 0.1}, {0, 1, 2, Vec3(0, 1, 0), 0.2}};
    return m;
}

ExitCode decode_error(const std::string& bytes, std::string* message) {
    try {
        decode_model(bytes, "m.model");
    } catch (const Error& e) {
        *message = e.what();
        return e.code();
    }
    return ExitCode::Ok;
}

TEST(ModelFile, RoundTripKeepsEveryFieldAndEncodesToTheSameBytes) {
    Model m = small_model();
    std::string bytes = encode_model(m);
    Model back = decode_model(bytes, "m.model");
    EXPECT_EQ(back.producer, m.producer);
    EXPECT_EQ(back.settings_json, m.settings_json);
    EXPECT_EQ(back.mesh.tets, m.mesh.tets);
    EXPECT_EQ(back.pieces[1].mass.center, m.pieces[1].mass.center);
    EXPECT_EQ(back.pieces[1].surface.kinds[0], FaceKind::Fracture);
    EXPECT_EQ(back.constraints[1].area, 0.2);
    EXPECT_FALSE(back.pieces[0].render);
    ASSERT_TRUE(back.pieces[1].render);
    EXPECT_EQ(back.pieces[1].render->vertices, m.pieces[1].render->vertices);
    EXPECT_EQ(back.pieces[1].render->normals, m.pieces[1].render->normals);
    EXPECT_EQ(back.pieces[1].render->triangles, m.pieces[1].render->triangles);
    EXPECT_EQ(back.pieces[1].render->kinds, m.pieces[1].render->kinds);
    EXPECT_FALSE(back.pieces[1].render->fell_back);
    EXPECT_EQ(encode_model(back), bytes);
}

TEST(ModelFile, RenderSurfaceWithANormalNotOfUnitLengthIsRefused) {
    Model m = small_model();
    m.pieces[1].render->normals[2] = Vec3(0, 0.5, 0);
    std::string message;
    EXPECT_EQ(decode_error(encode_model(m), &message), ExitCode::BadInput);
    EXPECT_NE(message.find("render surface normal is not of unit length"), std::string::npos) << message;
}

TEST(ModelFile, EveryTruncationIsRefusedWithAClearError) {
    std::string bytes = encode_model(small_model());
    for (size_t n = 0; n < bytes.size(); ++n) {
        std::string message;
        ASSERT_EQ(decode_error(bytes.substr(0, n), &message), ExitCode::BadInput) << "length " << n;
        EXPECT_NE(message.find("m.model"), std::string::npos);
    }
}

TEST(ModelFile, EveryFlippedBitIsRefused) {
    std::string bytes = encode_model(small_model());
    for (size_t i = 0; i < bytes.size(); ++i) {
        for (int bit = 0; bit < 8; bit += 3) {
            std::string damaged = bytes;
            damaged[i] = static_cast<char>(damaged[i] ^ (1 << bit));
            std::string message;
            // A flip in the producer or settings text is not detectable by the payload checksum
            // and decodes; anything else must be refused.
            ExitCode code = decode_error(damaged, &message);
            if (code == ExitCode::Ok) {
                Model back = decode_model(damaged, "m.model");
                EXPECT_TRUE(back.producer != small_model().producer || back.settings_json != small_model().settings_json)
                    << "byte " << i;
            } else {
                EXPECT_EQ(code, ExitCode::BadInput);
            }
        }
    }
}

TEST(ModelFile, NewerVersionIsRefusedAndSaysToUpdate) {
    std::string bytes = encode_model(small_model());
    bytes[8] = 99;  // version field
    std::string message;
    EXPECT_EQ(decode_error(bytes, &message), ExitCode::BadInput);
    EXPECT_NE(message.find("version 99 is newer"), std::string::npos) << message;
}

TEST(ModelFile, AnotherKindOfFileIsNamed) {
    std::string bytes = encode_model(small_model());
    bytes.replace(0, 8, "SHTTRAJE");
    std::string message;
    EXPECT_EQ(decode_error(bytes, &message), ExitCode::BadInput);
    EXPECT_NE(message.find("is a SHTTRAJE file, not a model"), std::string::npos) << message;
    EXPECT_EQ(decode_error("v 1 2 3\n", &message), ExitCode::BadInput);
    EXPECT_NE(message.find("not a shatter model file"), std::string::npos) << message;
}

}  // namespace
}  // namespace shatter
