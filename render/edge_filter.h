// Anti-aliasing as a filter over the finished image, one sample per pixel: where a pixel's luma
// differs from its neighbours' by more than a threshold, the edge's orientation and its extent
// along the image are found, and the pixel is blended with its neighbour across the edge by how
// far it lies from the edge's ends (a staircase step becomes a ramp) or by how much it stands out
// from its 3 x 3 neighbourhood (sub-pixel features). The idea of Timothy Lottes' FXAA (NVIDIA,
// 2009-2011), written for the CPU: exact integer steps along the edge, colours blended in linear
// light as a multisample resolve averages them.
//
// It costs a fraction of what multisampling costs llvmpipe (docs/render.md, "Anti-aliasing"):
// flat regions (sky, ground, the inside of faces) are passed over at the threshold test.
// Deterministic: every output pixel is a function of the input image alone, whatever the
// threads.
#pragma once

#include <cstdint>

namespace shatter {

// Filters the sRGB RGBA image `rgba` (width x height, 4 bytes a pixel, rows packed) in place;
// alpha is left as it is. Uses up to `threads` threads (>= 1).
void filter_edges(uint8_t* rgba, uint32_t width, uint32_t height, unsigned threads = 2);

}  // namespace shatter
