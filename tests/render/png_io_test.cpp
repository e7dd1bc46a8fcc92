// PNG writing and reading: exact round trip, RGBA written as RGB, bytes that depend only on the
// pixels, and refusal of files that are not PNGs.
#include <gtest/gtest.h>

#include "core/error.h"
#include "render/png_io.h"

namespace shatter {
namespace {

Image gradient(uint32_t w, uint32_t h) {
    Image img(w, h);
    for (uint32_t y = 0; y < h; ++y)
        for (uint32_t x = 0; x < w; ++x) {
            uint8_t* p = img.pixel(x, y);
            p[0] = uint8_t(x * 7);
            p[1] = uint8_t(y * 13);
            p[2] = uint8_t((x ^ y) * 3);
        }
    return img;
}

TEST(PngIo, RoundTripIsExact) {
    const Image a = gradient(37, 21);
    const Image b = decode_png(encode_png(a), "memory");
    EXPECT_EQ(b.width, 37u);
    EXPECT_EQ(b.height, 21u);
    EXPECT_EQ(a.rgb, b.rgb);
}

TEST(PngIo, RgbaIsWrittenAsRgbWithTheSameBytesAsRgb) {
    const Image a = gradient(16, 9);
    std::vector<uint8_t> rgba;
    for (size_t i = 0; i < a.rgb.size(); i += 3) rgba.insert(rgba.end(), {a.rgb[i], a.rgb[i + 1], a.rgb[i + 2], 77});
    EXPECT_EQ(encode_png(rgba.data(), 16, 9, 4, 16 * 4), encode_png(a));
}

TEST(PngIo, SamePixelsGiveSameBytes) { EXPECT_EQ(encode_png(gradient(64, 64)), encode_png(gradient(64, 64))); }

TEST(PngIo, RefusesBytesThatAreNotAPng) {
    EXPECT_THROW(decode_png("not a png at all", "x.png"), Error);
    std::string truncated = encode_png(gradient(32, 32));
    truncated.resize(truncated.size() / 2);
    try {
        decode_png(truncated, "half.png");
        FAIL() << "a truncated PNG was accepted";
    } catch (const Error& e) {
        EXPECT_EQ(e.code(), ExitCode::BadInput);
        EXPECT_NE(std::string(e.what()).find("half.png"), std::string::npos) << e.what();
    }
}

}  // namespace
}  // namespace shatter
