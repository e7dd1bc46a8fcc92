#include "render/render_target.h"

#include <fmt/format.h>

#include "core/error.h"
#include "render/gl.h"
#include "render/gl_context.h"

namespace shatter {

namespace {

void check_complete(const char* what, uint32_t w, uint32_t h) {
    const GLenum status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
    check_gl(what);
    if (status != GL_FRAMEBUFFER_COMPLETE)
        throw Error(ExitCode::Io, fmt::format("OpenGL cannot make a {}x{} {} (status 0x{:04x}; fix: a smaller --size "
                                              "or --msaa 1)", w, h, what, status));
}

}  // namespace

RenderTarget::RenderTarget(uint32_t width, uint32_t height, uint32_t samples)
    : width_(width), height_(height), samples_(samples) {
    const GLsizei w = GLsizei(width), h = GLsizei(height);
    glGenFramebuffers(1, &scene_fbo_);
    glBindFramebuffer(GL_FRAMEBUFFER, scene_fbo_);
    glGenRenderbuffers(1, &colour_);
    glBindRenderbuffer(GL_RENDERBUFFER, colour_);
    glRenderbufferStorageMultisample(GL_RENDERBUFFER, samples > 1 ? GLsizei(samples) : 0, GL_SRGB8_ALPHA8, w, h);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, colour_);
    glGenRenderbuffers(1, &depth_);
    glBindRenderbuffer(GL_RENDERBUFFER, depth_);
    glRenderbufferStorageMultisample(GL_RENDERBUFFER, samples > 1 ? GLsizei(samples) : 0, GL_DEPTH_COMPONENT24, w, h);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth_);
    check_complete("scene framebuffer", width, height);
    if (samples > 1) {
        glGenFramebuffers(1, &resolve_fbo_);
        glBindFramebuffer(GL_FRAMEBUFFER, resolve_fbo_);
        glGenRenderbuffers(1, &resolve_colour_);
        glBindRenderbuffer(GL_RENDERBUFFER, resolve_colour_);
        glRenderbufferStorage(GL_RENDERBUFFER, GL_SRGB8_ALPHA8, w, h);
        glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, resolve_colour_);
        glGenRenderbuffers(1, &resolve_depth_);
        glBindRenderbuffer(GL_RENDERBUFFER, resolve_depth_);
        glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT24, w, h);
        glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, resolve_depth_);
        check_complete("resolve framebuffer", width, height);
    }
}

RenderTarget::~RenderTarget() {
    if (resolve_fbo_) glDeleteFramebuffers(1, &resolve_fbo_);
    if (resolve_colour_) glDeleteRenderbuffers(1, &resolve_colour_);
    if (resolve_depth_) glDeleteRenderbuffers(1, &resolve_depth_);
    glDeleteFramebuffers(1, &scene_fbo_);
    glDeleteRenderbuffers(1, &depth_);
    glDeleteRenderbuffers(1, &colour_);
}

void RenderTarget::bind_scene() const {
    glBindFramebuffer(GL_FRAMEBUFFER, scene_fbo_);
    glViewport(0, 0, GLsizei(width_), GLsizei(height_));
}

void RenderTarget::bind_resolved() const {
    glBindFramebuffer(GL_FRAMEBUFFER, resolve_fbo_ ? resolve_fbo_ : scene_fbo_);
    glViewport(0, 0, GLsizei(width_), GLsizei(height_));
}

void RenderTarget::resolve(const PixelRect& r) const {
    if (samples_ <= 1 || r.empty()) return;
    glEnable(GL_FRAMEBUFFER_SRGB);  // the resolve decodes the samples, averages in linear light, encodes
    glDisable(GL_SCISSOR_TEST);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, scene_fbo_);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, resolve_fbo_);
    glBlitFramebuffer(r.x0, r.y0, r.x1, r.y1, r.x0, r.y0, r.x1, r.y1, GL_COLOR_BUFFER_BIT, GL_NEAREST);
}

void RenderTarget::read(uint8_t* rgba) const {
    glBindFramebuffer(GL_READ_FRAMEBUFFER, resolve_fbo_ ? resolve_fbo_ : scene_fbo_);
    glReadBuffer(GL_COLOR_ATTACHMENT0);
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    glReadPixels(0, 0, GLint(width_), GLint(height_), GL_RGBA, GL_UNSIGNED_BYTE, rgba);
    check_gl("reading a frame back");
}

}  // namespace shatter
