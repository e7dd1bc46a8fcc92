#include "meshio/image_decode.h"

#include <cmath>

#include <stb/stb_image.h>
#include <webp/decode.h>

namespace shatter {

namespace {

float srgb_to_linear(float c) { return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f); }

constexpr int kMaxImageSide = 16384;  // WebP's own limit is 16383

// A WebP image, which stb_image does not read, by libwebp.
std::optional<DecodedImage> decode_webp(const std::string& bytes, std::string* why) {
    const auto* data = reinterpret_cast<const uint8_t*>(bytes.data());
    int w = 0, h = 0;
    if (!WebPGetInfo(data, bytes.size(), &w, &h) || w <= 0 || h <= 0) {
        if (why) *why = "not a WebP image libwebp reads";
        return std::nullopt;
    }
    if (w > kMaxImageSide || h > kMaxImageSide) {
        if (why) *why = "a WebP image larger than 16384 pixels on a side";
        return std::nullopt;
    }
    DecodedImage image;
    image.width = uint32_t(w);
    image.height = uint32_t(h);
    image.rgba.resize(size_t(w) * size_t(h) * 4);
    if (!WebPDecodeRGBAInto(data, bytes.size(), image.rgba.data(), image.rgba.size(), w * 4)) {
        if (why) *why = "a WebP image that does not decode";
        return std::nullopt;
    }
    return image;
}

}  // namespace

bool is_webp(const std::string& bytes) {
    return bytes.size() >= 12 && bytes.compare(0, 4, "RIFF") == 0 && bytes.compare(8, 4, "WEBP") == 0;
}

const uint8_t* DecodedImage::at(float u, float v) const {
    auto wrap = [](float x, uint32_t n) {
        const double f = double(x) - std::floor(double(x));  // [0, 1)
        const double i = std::isfinite(f) ? std::floor(f * n) : 0;
        return std::min(uint32_t(i), n - 1);
    };
    const uint32_t x = wrap(u, width), y = height - 1 - wrap(v, height);  // row 0 is the top
    return &rgba[(size_t(y) * width + x) * 4];
}

std::optional<DecodedImage> decode_image(const std::string& bytes, std::string* why) {
    if (is_webp(bytes)) return decode_webp(bytes, why);
    int w = 0, h = 0, channels = 0;
    stbi_uc* data = stbi_load_from_memory(reinterpret_cast<const stbi_uc*>(bytes.data()), int(bytes.size()), &w, &h,
                                          &channels, 4);
    if (data == nullptr || w <= 0 || h <= 0) {
        if (why) *why = stbi_failure_reason() ? stbi_failure_reason() : "not an image";
        if (data) stbi_image_free(data);
        return std::nullopt;
    }
    DecodedImage image;
    image.width = uint32_t(w);
    image.height = uint32_t(h);
    image.rgba.assign(data, data + size_t(w) * size_t(h) * 4);
    stbi_image_free(data);
    return image;
}

std::array<float, 3> mean_linear_colour(const DecodedImage& image) {
    float table[256];
    for (int i = 0; i < 256; ++i) table[i] = srgb_to_linear(float(i) / 255.0f);
    double sum[3] = {0, 0, 0};
    const size_t n = size_t(image.width) * image.height;
    for (size_t i = 0; i < n; ++i)
        for (int k = 0; k < 3; ++k) sum[k] += table[image.rgba[4 * i + size_t(k)]];
    if (n == 0) return {1, 1, 1};
    return {float(sum[0] / double(n)), float(sum[1] / double(n)), float(sum[2] / double(n))};
}

}  // namespace shatter
