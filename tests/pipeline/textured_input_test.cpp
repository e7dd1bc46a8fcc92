// A textured input keeps its texture in the frames: assimp-testmodels' duck (Collada, its TGA
// texture beside it) through prescore and render. The texture's mean colour is yellow (hue
// ~50 degrees); with colours = "input" most of the duck's pixels have the texture's hue, with
// colours = "material" (one beige colour) none does, and with the texture file missing the duck
// is drawn in its material's base colour (a warning, not an error). A PLY's vertex colours show
// too.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "core/model_io.h"
#include "core/palette.h"
#include "prescore/prescore.h"
#include "render/frame_renderer.h"
#include "render/gl_context.h"
#include "render/image.h"
#include "render/srgb_encode.h"
#include "render/texture.h"
#include "scenes/render_test_scene.h"
#include "support/duck.h"
#include "support/temp_dir.h"

namespace shatter {
namespace {

using testing_support::kDuck;
using testing_support::prescore_duck;

// Hue (degrees) and saturation of an sRGB pixel.
std::pair<double, double> hue_saturation(const uint8_t* p) {
    const double r = p[0] / 255.0, g = p[1] / 255.0, b = p[2] / 255.0;
    const double hi = std::max({r, g, b}), lo = std::min({r, g, b}), d = hi - lo;
    if (d <= 0) return {0, 0};
    double h = hi == r ? std::fmod((g - b) / d, 6.0) : hi == g ? (b - r) / d + 2 : (r - g) / d + 4;
    h *= 60;
    if (h < 0) h += 360;
    return {h, d / hi};
}

Image render(const Model& model, RenderSettings s) {
    const SceneSettings scene;
    const Trajectory t = testing_support::test_trajectory(model, scene, 2);
    GlContext context;
    RenderScene rs;
    rs.model = &model;
    rs.trajectory = &t;
    rs.scene = scene;
    FrameRenderer r(rs, s);
    std::vector<uint8_t> rgba(size_t(s.width) * s.height * 4);
    r.render(0, rgba.data());
    Image img(s.width, s.height);
    rgba_rows_to_rgb(rgba.data(), s.width, s.height, img.rgb.data());
    return img;
}

// Pixels saturated (> 0.4) and within 15 degrees of `hue`.
size_t pixels_of_hue(const Image& img, double hue) {
    size_t n = 0;
    for (size_t i = 0; i < img.rgb.size(); i += 3) {
        const auto [h, sat] = hue_saturation(&img.rgb[i]);
        const double dh = std::min(std::abs(h - hue), 360 - std::abs(h - hue));
        n += sat > 0.4 && dh < 15;
    }
    return n;
}

TEST(TexturedInput, TheDucksFramesShowItsTextureNotTheMaterialColour) {
    if (!std::filesystem::exists(kDuck)) GTEST_SKIP() << kDuck << " is missing (fix: scripts/install-deps.sh)";
    const Model model = prescore_duck(kDuck);
    std::vector<DecodedImage> images;
    const std::vector<MaterialLook> looks = material_looks(model, &images);
    ASSERT_EQ(images.size(), 1u);
    EXPECT_EQ(images[0].width, 512u);
    // The texture's mean colour, as sRGB bytes, and its hue: what the duck's pixels should show.
    int32_t textured = -1;
    for (size_t m = 0; m < looks.size(); ++m)
        if (looks[m].texture >= 0) textured = int32_t(m);
    ASSERT_GE(textured, 0);
    const Colour mean = looks[size_t(textured)].mean;
    const uint8_t mean8[3] = {linear_to_srgb8(mean[0]), linear_to_srgb8(mean[1]), linear_to_srgb8(mean[2])};
    const double hue = hue_saturation(mean8).first;
    EXPECT_GT(hue, 40);  // yellow
    EXPECT_LT(hue, 65);

    RenderSettings s = testing_support::small_render_settings();
    s.colours = Colours::Input;
    const Image input = render(model, s);
    s.colours = Colours::Material;
    const Image material = render(model, s);
    // The duck covers roughly 80 x 80 of the 320 x 180 pixels.
    const size_t with_texture = pixels_of_hue(input, hue), without = pixels_of_hue(material, hue);
    EXPECT_GT(with_texture, 2000u);
    EXPECT_LT(without, 20u);
    ::testing::Test::RecordProperty("texture_hue", std::to_string(hue));
    ::testing::Test::RecordProperty("pixels_of_the_texture_hue", std::to_string(with_texture));
    ::testing::Test::RecordProperty("pixels_of_the_texture_hue_material", std::to_string(without));
}

TEST(TexturedInput, WithoutItsTextureFileTheDuckIsDrawnInItsBaseColour) {
    if (!std::filesystem::exists(kDuck)) GTEST_SKIP() << kDuck << " is missing";
    testing_support::TempDir dir;
    std::filesystem::copy_file(kDuck, dir.file("duck.dae"));
    const Model model = prescore_duck(dir.file("duck.dae"));
    for (const Material& m : model.materials) EXPECT_TRUE(m.texture.empty());
    RenderSettings s = testing_support::small_render_settings();
    s.colours = Colours::Input;
    const Image img = render(model, s);
    EXPECT_LT(pixels_of_hue(img, 52), 20u);
}

// Vertex colours: a PLY cube whose bottom corners are red and top corners blue is drawn with
// both, where colours = "material" shows neither.
TEST(TexturedInput, VertexColoursReachTheFrames) {
    std::string ply = "ply\nformat ascii 1.0\nelement vertex 8\nproperty float x\nproperty float y\nproperty float z\n"
                      "property uchar red\nproperty uchar green\nproperty uchar blue\nelement face 12\n"
                      "property list uchar int vertex_indices\nend_header\n";
    for (int i = 0; i < 8; ++i)
        ply += std::string(i & 1 ? "0.1 " : "0 ") + (i & 2 ? "0.1 " : "0 ") + (i & 4 ? "0.1 " : "0 ") +
               (i & 2 ? "0 0 255\n" : "255 0 0\n");
    for (const char* f : {"0 2 3", "0 3 1", "4 5 7", "4 7 6", "0 1 5", "0 5 4", "2 6 7", "2 7 3", "0 4 6", "0 6 2",
                          "1 3 7", "1 7 5"})
        ply += std::string("3 ") + f + "\n";
    testing_support::TempDir dir;
    MeshSettings mesh;
    mesh.path = dir.write("cube.ply", ply);
    PrescoreSettings settings;
    settings.pieces = 2;
    settings.resolution = 4;
    const Model model = prescore(mesh, settings, nullptr);
    RenderSettings s = testing_support::small_render_settings();
    s.colours = Colours::Input;
    const Image input = render(model, s);
    s.colours = Colours::Material;
    const Image material = render(model, s);
    EXPECT_GT(pixels_of_hue(input, 0), 100u);    // red (measured 209: the camera looks down on the blue top)
    EXPECT_GT(pixels_of_hue(input, 240), 700u);  // blue (measured 1,460)
    EXPECT_EQ(pixels_of_hue(material, 0) + pixels_of_hue(material, 240), 0u);
    ::testing::Test::RecordProperty("red_pixels", std::to_string(pixels_of_hue(input, 0)));
    ::testing::Test::RecordProperty("blue_pixels", std::to_string(pixels_of_hue(input, 240)));
}

// A texture that does not decode is a warning: the material keeps its base colour.
TEST(TexturedInput, AnUndecodableTextureFallsBackToTheBaseColour) {
    Model model = load_model(SHATTER_SOURCE_DIR "/tests/fixtures/model-v3.model");
    for (Material& m : model.materials)
        if (!m.texture.empty()) m.texture = "\x89PNG\r\n\x1a\n not really";
    std::vector<DecodedImage> images;
    const std::vector<MaterialLook> looks = material_looks(model, &images);
    EXPECT_TRUE(images.empty());
    for (const MaterialLook& l : looks) EXPECT_EQ(l.texture, -1);
    RenderSettings s = testing_support::small_render_settings();
    s.colours = Colours::Input;
    EXPECT_NO_THROW(render(model, s));
}

}  // namespace
}  // namespace shatter
