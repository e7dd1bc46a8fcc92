// FrameRenderer on the small test scene: what lands on the image is where geometry says it is.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>

#include "core/error.h"
#include "core/model_io.h"
#include "render/frame_renderer.h"
#include "render/gl_context.h"
#include "render/image_diff.h"
#include "render/mesh_builder.h"
#include "render/png_io.h"
#include "render/srgb_encode.h"
#include "scenes/render_test_scene.h"
#include "support/temp_dir.h"

namespace shatter {
namespace {

using namespace testing_support;

Image render_one(const TestScene& t, const RenderSettings& s, uint32_t frame,
                 MsaaRegion region = MsaaRegion::Edges) {
    GlContext context;
    RenderScene scene = t.scene();
    FrameRenderer r(scene, s, region);
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

// MSAA only around the pieces', props' and colliders' rectangle gives the frame that MSAA over
// the whole frame gives: the rest is ground and background, where a pixel's four samples are
// equal. At most a level apart along the ground's own triangle edges; a frame where the
// pieces fly far apart and one where they sit together.
TEST(FrameRenderer, MsaaAroundTheEdgesGivesTheAllMsaaFrameWithinALevel) {
    TestScene t;
    RenderSettings s = small_render_settings();
    s.width = 640;
    s.height = 360;
    s.msaa = 4;
    s.edge_filter = false;
    for (uint32_t f : {0u, 23u}) {
        const Image edges = render_one(t, s, f), everywhere = render_one(t, s, f, MsaaRegion::Everywhere);
        const DiffMetrics d = compare_images(edges, everywhere, 1);
        EXPECT_LE(d.max_channel_diff, 1) << "frame " << f;  // measured: 1
        EXPECT_LT(d.fraction_over, 0.001) << "frame " << f << ": " << d.pixels_over << " pixels over one level";
        // ...and is not the one-sample frame: the edges are smoothed.
        s.msaa = 1;
        const DiffMetrics one = compare_images(edges, render_one(t, s, f), 1);
        s.msaa = 4;
        EXPECT_GT(one.pixels_over, 200u) << "frame " << f;  // measured: 959 and 1,164
    }
}

// A piece with a render surface is drawn from it, indexed: three indices per triangle, a vertex
// per surface vertex and kind that uses it, the surface's normals. On the v2 fixture (a cube: its
// render surfaces are the cube's faces cut per piece, so they cover what the tet surfaces
// cover), frames drawn from the render surfaces and from the tet surfaces agree but for the
// triangulation's edge pixels.
TEST(FrameRenderer, RenderSurfacesAreDrawnIndexedAndCoverWhatTheTetSurfacesCover) {
    TestScene with;
    with.model = load_model(SHATTER_SOURCE_DIR "/tests/fixtures/model-v2.model");
    with.trajectory = test_trajectory(with.model, with.settings);
    const RenderSettings s = small_render_settings();
    for (uint32_t i = 0; i < with.model.pieces.size(); ++i) {
        const Piece& p = with.model.pieces[i];
        ASSERT_TRUE(p.render);
        const IndexedVertices m = piece_mesh(p, i, s);
        EXPECT_EQ(m.indices.size(), 3 * p.render->triangles.size());
        EXPECT_LE(m.vertices.size(), 3 * p.render->vertices.size());
        EXPECT_LT(m.vertices.size(), m.indices.size());
        const RenderSurface& rs = *p.render;
        for (size_t t = 0; t < rs.triangles.size(); ++t)
            for (int k = 0; k < 3; ++k) {
                const Vertex& v = m.vertices[m.indices[3 * t + size_t(k)]];
                const Vec3& n = rs.normals[rs.triangles[t][size_t(k)]];
                EXPECT_FLOAT_EQ(v.normal[0], float(n.x()));
                EXPECT_FLOAT_EQ(v.normal[1], float(n.y()));
                EXPECT_FLOAT_EQ(v.normal[2], float(n.z()));
            }
    }
    TestScene without = with;
    for (Piece& p : without.model.pieces) p.render.reset();
    for (uint32_t f : {0u, 23u}) {
        const DiffMetrics d = compare_images(render_one(with, s, f), render_one(without, s, f), 24);
        EXPECT_LT(d.fraction_over, 0.01) << "frame " << f << ": " << d.pixels_over << " pixels over 24 levels";
        ::testing::Test::RecordProperty("rmse_frame_" + std::to_string(f), std::to_string(d.rmse));
    }
}

// [render] interior_texture lands on the fracture faces and nowhere else: the pixels it changes
// are the pixels an interior colour changes, and a red image makes them red. Frames as the two
// cube pieces fly apart and turn (checked where their fracture faces are in view); the edge
// filter off, so that no pixel changes for a neighbour's sake.
TEST(FrameRenderer, AnInteriorTextureLandsOnTheFractureFacesAlone) {
    TestScene t;
    TempDir tmp;
    Image red(4, 4);
    for (size_t i = 0; i < red.rgb.size(); i += 3) red.rgb[i] = 255;
    save_png(tmp.file("red.png"), red);
    RenderSettings s = small_render_settings();
    s.edge_filter = false;
    RenderSettings green = s, textured = s;
    green.interior_colour = Colour{0, 1, 0};
    textured.interior_texture = tmp.file("red.png");
    size_t total = 0;
    for (uint32_t f : {8u, 12u, 16u, 20u, 23u}) {
        const Image base = render_one(t, s, f), g = render_one(t, green, f), r = render_one(t, textured, f);
        size_t fracture = 0, only_one = 0;
        double red_sum = 0, green_sum = 0;
        for (size_t i = 0; i < base.rgb.size(); i += 3) {
            const auto moved = [&](const Image& a) {
                return std::abs(a.rgb[i] - base.rgb[i]) + std::abs(a.rgb[i + 1] - base.rgb[i + 1]) +
                           std::abs(a.rgb[i + 2] - base.rgb[i + 2]) > 6;
            };
            const bool in_g = moved(g), in_r = moved(r);
            fracture += in_g;
            only_one += in_g != in_r;
            if (in_r) red_sum += r.rgb[i], green_sum += r.rgb[i + 1];
        }
        total += fracture;
        ::testing::Test::RecordProperty("fracture_pixels_" + std::to_string(f), std::to_string(fracture));
        if (fracture < 50) continue;  // the faces turned away in this frame
        EXPECT_LT(double(only_one), 0.05 * double(fracture)) << "frame " << f << ": " << only_one << " of " << fracture;
        EXPECT_GT(red_sum, 3 * green_sum) << "frame " << f;  // lit red: the red channel alone
    }
    EXPECT_GT(total, 500u) << "the fracture faces should be in view";
}

TEST(FrameRenderer, AnInteriorTextureThatIsNoImageIsBadInputNamingTheFile) {
    TestScene t;
    TempDir tmp;
    RenderSettings s = small_render_settings();
    s.interior_texture = tmp.write("stone.png", "not an image");
    GlContext context;
    RenderScene scene = t.scene();
    try {
        FrameRenderer r(scene, s, MsaaRegion::Edges);
        FAIL() << "no error";
    } catch (const Error& e) {
        EXPECT_EQ(e.code(), ExitCode::BadInput);
        EXPECT_NE(std::string(e.what()).find("stone.png"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("interior_texture"), std::string::npos) << e.what();
    }
}

}  // namespace
}  // namespace shatter
