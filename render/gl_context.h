// An off-screen OpenGL 4.5 core context from OSMesa (Mesa's llvmpipe rasterizer on the CPU): no
// GPU, no display. llvmpipe runs LP_NUM_THREADS rasterizer threads (default: the core count);
// its output does not depend on that count. One context per thread that draws; it is made
// current on creation and released on destruction.
#pragma once

#include <cstdint>
#include <string>

namespace shatter {

struct GlLimits {
    int max_renderbuffer_size = 0;  // GL_MAX_RENDERBUFFER_SIZE (unit: pixels)
    int max_viewport[2] = {0, 0};   // GL_MAX_VIEWPORT_DIMS (unit: pixels)
    int max_texture_size = 0;       // GL_MAX_TEXTURE_SIZE (unit: pixels)
    int max_samples = 0;            // GL_MAX_SAMPLES
    // The largest width and height an image may have: the smallest of the limits above.
    int max_image_size() const;
};

class GlContext {
public:
    GlContext();  // throws Error(Tool) when OSMesa cannot give a 4.5 core context
    ~GlContext();
    GlContext(const GlContext&) = delete;
    GlContext& operator=(const GlContext&) = delete;

    const GlLimits& limits() const { return limits_; }
    const std::string& renderer() const { return renderer_; }  // e.g. "llvmpipe (LLVM 15.0.6, 256 bits)"
    const std::string& version() const { return version_; }

private:
    void* context_ = nullptr;  // OSMesaContext
    unsigned char dummy_[4 * 4 * 4] = {};  // the 4x4 default framebuffer; we draw into our own FBOs
    GlLimits limits_;
    std::string renderer_;
    std::string version_;
};

// Throws Error(Internal) naming `what` when GL reports an error (our bug), or Error(Io) for
// GL_OUT_OF_MEMORY (an image too large for the memory at hand).
void check_gl(const char* what);

}  // namespace shatter
