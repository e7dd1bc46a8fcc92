// Where a frame is drawn: an SRGB8_ALPHA8 colour buffer with `samples` samples per pixel and a
// 24-bit depth buffer; with MSAA, a single-sample SRGB8_ALPHA8 buffer the samples are averaged
// into (glBlitFramebuffer) and read back from. Shaders write linear light and, with
// GL_FRAMEBUFFER_SRGB on, GL encodes it to sRGB bytes (fine steps in the darks, no banding);
// the resolve decodes the samples, averages them in linear light and encodes again. A quarter
// of the bytes of RGBA16F to clear, resolve and read back, and no conversion on the CPU.
// With MSAA the single-sample buffer has its own depth buffer too, so that the parts of a frame
// without edges can be drawn into it directly (render/frame_renderer.h).
#pragma once

#include <cstdint>

namespace shatter {

// Pixels [x0, x1) x [y0, y1), GL's bottom row first.
struct PixelRect {
    int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
    bool empty() const { return x1 <= x0 || y1 <= y0; }
};

class RenderTarget {
public:
    RenderTarget(uint32_t width, uint32_t height, uint32_t samples);  // throws Error(Io) when out of memory
    ~RenderTarget();
    RenderTarget(const RenderTarget&) = delete;
    RenderTarget& operator=(const RenderTarget&) = delete;

    void bind_scene() const;     // the framebuffer the scene is drawn into (multisampled with MSAA)
    void bind_resolved() const;  // the single-sample framebuffer that is read back
    // Averages the samples of a rectangle of the multisampled framebuffer into the single-sample one.
    void resolve(const PixelRect& rect) const;
    // Reads the sRGB RGBA8 pixels back: width * height * 4 bytes, GL's bottom row first.
    void read(uint8_t* rgba) const;
    uint32_t width() const { return width_; }
    uint32_t height() const { return height_; }
    uint32_t samples() const { return samples_; }

private:
    uint32_t width_, height_, samples_;
    unsigned scene_fbo_ = 0, colour_ = 0, depth_ = 0;
    unsigned resolve_fbo_ = 0, resolve_colour_ = 0, resolve_depth_ = 0;  // only with samples > 1
};

}  // namespace shatter
