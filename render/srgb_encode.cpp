#include "render/srgb_encode.h"

#include <cstddef>

namespace shatter {

void rgba_rows_to_rgb(const uint8_t* rgba, uint32_t width, uint32_t height, uint8_t* rgb) {
    for (uint32_t y = 0; y < height; ++y) {
        const uint8_t* in = rgba + size_t(height - 1 - y) * width * 4;
        uint8_t* out = rgb + size_t(y) * width * 3;
        for (uint32_t x = 0; x < width; ++x) {
            out[3 * x + 0] = in[4 * x + 0];
            out[3 * x + 1] = in[4 * x + 1];
            out[3 * x + 2] = in[4 * x + 2];
        }
    }
}

}  // namespace shatter
