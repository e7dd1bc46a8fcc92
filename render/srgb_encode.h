// A frame as read back from GL (sRGB8_ALPHA8 bytes, bottom row first; GL encoded linear light
// to sRGB on write, see render/render_target.h) to the RGB rows, top first, that PNG stores.
#pragma once

#include <cstdint>

namespace shatter {

// `rgba`: width * height * 4 bytes, bottom row first. `rgb`: width * height * 3 bytes, top row first.
void rgba_rows_to_rgb(const uint8_t* rgba, uint32_t width, uint32_t height, uint8_t* rgb);

}  // namespace shatter
