// FrameRenderer on the small test scene: what lands on the image is where geometry says it is.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>

#include "render/frame_renderer.h"
#include "render/gl_context.h"
#include "render/png_io.h"
#include "render/srgb_encode.h"
#include "render_test_scene.h"
#include "support/temp_dir.h"

namespace shatter {
namespace {

using namespace testing_support;

Image render_one(const TestScene& t, const RenderSettings& s, uint32_t frame) {
    GlContext context;
    RenderScene scene = t.scene();
    FrameRenderer r(scene, s);
    std::vector<uint8_t> rgba(size_t(s.width) * s.height * 4);
    r.render(frame, rgba.data());
    Image img(s.width, s.height);
    rgba_rows_to_rgb(rgba.data(), s.width, s.height, img.rgb.data());
    return img;
}

TEST(FrameRenderer, DumpsAFrameForLooking) {
    const char* dir = std::getenv("SHATTER_RENDER_DUMP");
    if (!dir) GTEST_SKIP() << "set SHATTER_RENDER_DUMP=DIR to write frames to look at";
    TestScene t;
    RenderSettings s = small_render_settings();
    s.width = 960;
    s.height = 540;
    for (uint32_t f : {0u, 12u, 23u}) save_png(std::string(dir) + "/look_" + std::to_string(f) + ".png", render_one(t, s, f));
}

}  // namespace
}  // namespace shatter
