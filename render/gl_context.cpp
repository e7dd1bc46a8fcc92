#include "render/gl_context.h"

#include <algorithm>

#include <fmt/format.h>

#include "core/error.h"
#include "render/gl.h"

namespace shatter {

int GlLimits::max_image_size() const {
    return std::min({max_renderbuffer_size, max_viewport[0], max_viewport[1], max_texture_size});
}

GlContext::GlContext() {
    const int attribs[] = {OSMESA_FORMAT,        OSMESA_RGBA, OSMESA_DEPTH_BITS,    0,
                           OSMESA_STENCIL_BITS,  0,           OSMESA_ACCUM_BITS,    0,
                           OSMESA_PROFILE,       OSMESA_CORE_PROFILE,
                           OSMESA_CONTEXT_MAJOR_VERSION, 4, OSMESA_CONTEXT_MINOR_VERSION, 5, 0};
    OSMesaContext ctx = OSMesaCreateContextAttribs(attribs, nullptr);
    if (!ctx)
        throw Error(ExitCode::Tool, "OSMesa: cannot create an OpenGL 4.5 core context (fix: install Mesa's "
                                    "libosmesa6 >= 20, whose llvmpipe provides GL 4.5; scripts/install-deps.sh)");
    context_ = ctx;
    if (!OSMesaMakeCurrent(ctx, dummy_, GL_UNSIGNED_BYTE, 4, 4)) {
        OSMesaDestroyContext(ctx);
        context_ = nullptr;
        throw Error(ExitCode::Tool, "OSMesa: cannot make the context current (fix: check the Mesa installation)");
    }
    glGetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &limits_.max_renderbuffer_size);
    glGetIntegerv(GL_MAX_VIEWPORT_DIMS, limits_.max_viewport);
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &limits_.max_texture_size);
    glGetIntegerv(GL_MAX_SAMPLES, &limits_.max_samples);
    renderer_ = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
    version_ = reinterpret_cast<const char*>(glGetString(GL_VERSION));
    // Output is stored as written: no implicit sRGB conversion, no dithering.
    glDisable(GL_DITHER);
    check_gl("context setup");
}

GlContext::~GlContext() {
    if (context_) {
        OSMesaMakeCurrent(nullptr, nullptr, GL_UNSIGNED_BYTE, 0, 0);
        OSMesaDestroyContext(static_cast<OSMesaContext>(context_));
    }
}

void check_gl(const char* what) {
    const GLenum e = glGetError();
    if (e == GL_NO_ERROR) return;
    if (e == GL_OUT_OF_MEMORY)
        throw Error(ExitCode::Io, fmt::format("OpenGL ran out of memory during {} (fix: a smaller --size, "
                                              "--msaa 1 or a smaller shadow map)", what));
    throw Error(ExitCode::Internal, fmt::format("OpenGL error 0x{:04x} during {} (a bug in shatter)", e, what));
}

}  // namespace shatter
