// The shot's [render] section: every key read with its unit and range, strict about unknown
// keys, colours and sample counts; and the pieces of geometry the look depends on.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "core/error.h"
#include "core/palette.h"
#include "core/shot.h"
#include "render/camera.h"
#include "render/mesh_builder.h"
#include "support/temp_dir.h"

namespace shatter {
namespace {

using testing_support::TempDir;

TEST(RenderSection, ReadsEveryKey) {
    TempDir dir;
    const std::string shot = dir.write("s.toml", R"([render]
width = 640
height = 360
camera_position = [1, 0.5, 2]
camera_target = [0, 0.1, 0]
fov = 50
shadows = false
shadow_map = 1024
msaa = 2
key_azimuth = 20
key_elevation = 60
colours = "material"
interior_colour = "#00ff00"
material_colour = "#ff0000"
fracture_tint = 0.3
cavity_shade = 0.2
background = "#000000"
)");
    const RenderSettings r = load_shot(shot).render;
    EXPECT_EQ(r.width, 640u);
    EXPECT_EQ(r.height, 360u);
    EXPECT_EQ(*r.camera_position, Vec3(1, 0.5, 2));
    EXPECT_EQ(*r.camera_target, Vec3(0, 0.1, 0));
    EXPECT_EQ(r.fov, 50);
    EXPECT_FALSE(r.shadows);
    EXPECT_EQ(r.shadow_map, 1024u);
    EXPECT_EQ(r.msaa, 2u);
    EXPECT_EQ(r.key_azimuth, 20);
    EXPECT_EQ(r.key_elevation, 60);
    EXPECT_EQ(r.colours, Colours::Material);
    ASSERT_TRUE(r.interior_colour);
    EXPECT_FLOAT_EQ((*r.interior_colour)[1], 1.0f);
    EXPECT_FLOAT_EQ(r.material_colour[0], 1.0f);
    EXPECT_FLOAT_EQ(r.material_colour[1], 0.0f);
    EXPECT_EQ(r.fracture_tint, 0.3);
    EXPECT_EQ(r.cavity_shade, 0.2);
    EXPECT_EQ(srgb_hex(r.background), "#000000");
    EXPECT_EQ(to_json(r)["material_colour"], "#ff0000");
}

TEST(RenderSection, RefusesBadValuesNamingTheLine) {
    TempDir dir;
    const std::pair<const char*, const char*> cases[] = {
        {"width = 0", "width"},           {"height = 20000", "height"},
        {"msaa = 3", "msaa"},             {"fov = 0", "fov"},
        {"colours = \"rainbow\"", "colours"}, {"interior_colour = \"white\"", "interior_colour"}, {"background = \"red\"", "background"},
        {"camera_target = [0, 0, 0]", "camera_position"}, {"fracture_tint = 2", "fracture_tint"},
        {"shadows = 1", "shadows"},       {"widht = 100", "width"},  // "did you mean"
    };
    for (const auto& [line, key] : cases) {
        const std::string shot = dir.write("bad.toml", std::string("[render]\n") + line + "\n");
        try {
            load_shot(shot);
            ADD_FAILURE() << line << " was accepted";
        } catch (const Error& e) {
            EXPECT_EQ(e.code(), ExitCode::BadInput) << line;
            EXPECT_NE(std::string(e.what()).find("bad.toml:2"), std::string::npos) << e.what();
            EXPECT_NE(std::string(e.what()).find(key), std::string::npos) << e.what();
        }
    }
}

TEST(RenderColours, HexIsSrgbAndRoundTrips) {
    EXPECT_NEAR((*parse_srgb_hex("#808080"))[0], 0.2158f, 1e-4);  // sRGB 128 is 21.6% linear light
    EXPECT_EQ(srgb_hex(*parse_srgb_hex("#dbd3c4")), "#dbd3c4");
    EXPECT_FALSE(parse_srgb_hex("#12345"));
    EXPECT_FALSE(parse_srgb_hex("#gg0000"));
}

TEST(RenderColours, FractureFacesAreLighterAndCavityFacesDarker) {
    RenderSettings s;
    s.colours = Colours::Palette;
    const Colour base = piece_base_colour(3, s);
    EXPECT_EQ(base, piece_colour(3));
    const Colour f = face_colour(base, FaceKind::Fracture, s), c = face_colour(base, FaceKind::Cavity, s);
    for (int i = 0; i < 3; ++i) {
        EXPECT_NEAR(f[size_t(i)], base[size_t(i)] + (1 - base[size_t(i)]) * 0.55f, 1e-6);
        EXPECT_NEAR(c[size_t(i)], base[size_t(i)] * 0.45f, 1e-6);
    }
    s.colours = Colours::Material;
    EXPECT_EQ(piece_base_colour(3, s), s.material_colour);
    s.interior_colour = Colour{0.1f, 0.2f, 0.3f};
    EXPECT_EQ(face_colour(base, FaceKind::Fracture, s), *s.interior_colour);
}

TEST(RenderCamera, AutomaticCameraKeepsEveryCornerOfTheBoundsInTheImage) {
    RenderSettings s;
    const Eigen::AlignedBox3d box(Vec3(-0.3, 0, -0.2), Vec3(0.4, 0.25, 0.3));
    const Camera c = make_camera(box, {}, s);
    const Eigen::Matrix4f vp = c.projection * c.view;
    float widest = 0;
    for (int i = 0; i < 8; ++i) {
        const Eigen::Vector3f p = box.corner(static_cast<Eigen::AlignedBox3d::CornerType>(i)).cast<float>();
        const Eigen::Vector4f q = vp * Eigen::Vector4f(p.x(), p.y(), p.z(), 1);
        const float x = q.x() / q.w(), y = q.y() / q.w(), z = q.z() / q.w();
        EXPECT_LE(std::abs(x), 0.9001f);
        EXPECT_LE(std::abs(y), 0.9001f);
        EXPECT_GT(z, -1.0f);
        EXPECT_LT(z, 1.0f);
        widest = std::max({widest, std::abs(x), std::abs(y)});
    }
    EXPECT_NEAR(widest, 0.9f, 1e-3);  // and as large as that allows
}

TEST(RenderMeshes, BoxAndPieceTrianglesFaceOutward) {
    const auto box = box_vertices(Vec3(1, 2, 3), {1, 1, 1});
    ASSERT_EQ(box.size(), 36u);
    for (const Vertex& v : box) {
        const Eigen::Vector3f p(v.position), n(v.normal);
        EXPECT_GT(p.dot(n), 0);  // a face's normal points away from the centre
    }
}

}  // namespace
}  // namespace shatter
