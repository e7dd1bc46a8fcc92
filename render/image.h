// An 8-bit RGB image, rows top to bottom: what render writes and diff compares.
#pragma once

#include <cstdint>
#include <vector>

namespace shatter {

struct Image {
    uint32_t width = 0;   // (unit: pixels)
    uint32_t height = 0;  // (unit: pixels)
    std::vector<uint8_t> rgb;  // width * height * 3 bytes, sRGB-encoded, row-major from the top

    Image() = default;
    Image(uint32_t w, uint32_t h) : width(w), height(h), rgb(size_t(w) * h * 3, 0) {}
    uint8_t* pixel(uint32_t x, uint32_t y) { return &rgb[(size_t(y) * width + x) * 3]; }
    const uint8_t* pixel(uint32_t x, uint32_t y) const { return &rgb[(size_t(y) * width + x) * 3]; }
};

}  // namespace shatter
