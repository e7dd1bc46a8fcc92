// Where a frame is drawn: a linear-light RGBA16F colour buffer with `samples` samples per pixel
// and a 24-bit depth buffer; with MSAA, a single-sample RGBA16F buffer the samples are averaged
// into (glBlitFramebuffer) and read back from. Half floats keep the dark tones of linear light
// free of banding until the one sRGB quantization on the CPU (render/srgb_encode.h).
#pragma once

#include <cstdint>

namespace shatter {

class RenderTarget {
public:
    RenderTarget(uint32_t width, uint32_t height, uint32_t samples);  // throws Error(Io) when out of memory
    ~RenderTarget();
    RenderTarget(const RenderTarget&) = delete;
    RenderTarget& operator=(const RenderTarget&) = delete;

    void bind_scene() const;  // the framebuffer the scene is drawn into
    // Averages the samples (when multisampled) and reads the linear RGBA16F pixels back:
    // width * height * 4 half floats, GL's bottom row first.
    void resolve_and_read(uint16_t* rgba_half) const;
    uint32_t width() const { return width_; }
    uint32_t height() const { return height_; }
    uint32_t samples() const { return samples_; }

private:
    uint32_t width_, height_, samples_;
    unsigned scene_fbo_ = 0, colour_ = 0, depth_ = 0;
    unsigned resolve_fbo_ = 0, resolve_colour_ = 0;  // only with samples > 1
};

}  // namespace shatter
