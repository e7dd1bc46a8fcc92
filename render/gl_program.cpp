#include "render/gl_program.h"

#include <fmt/format.h>

#include "core/error.h"
#include "render/gl.h"

namespace shatter {

namespace {

GLuint compile(GLenum type, const char* source, const char* name) {
    GLuint s = glCreateShader(type);
    glShaderSource(s, 1, &source, nullptr);
    glCompileShader(s);
    GLint ok = 0;
    glGetShaderiv(s, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        char log[4096] = {};
        glGetShaderInfoLog(s, sizeof log, nullptr, log);
        glDeleteShader(s);
        throw Error(ExitCode::Internal, fmt::format("shader {} does not compile (a bug in shatter): {}", name, log));
    }
    return s;
}

}  // namespace

GlProgram::GlProgram(const char* vertex_source, const char* fragment_source, const char* name) {
    GLuint vs = compile(GL_VERTEX_SHADER, vertex_source, name);
    GLuint fs = compile(GL_FRAGMENT_SHADER, fragment_source, name);
    id_ = glCreateProgram();
    glAttachShader(id_, vs);
    glAttachShader(id_, fs);
    glLinkProgram(id_);
    glDeleteShader(vs);
    glDeleteShader(fs);
    GLint ok = 0;
    glGetProgramiv(id_, GL_LINK_STATUS, &ok);
    if (!ok) {
        char log[4096] = {};
        glGetProgramInfoLog(id_, sizeof log, nullptr, log);
        throw Error(ExitCode::Internal, fmt::format("program {} does not link (a bug in shatter): {}", name, log));
    }
}

GlProgram::~GlProgram() {
    if (id_) glDeleteProgram(id_);
}

GlProgram& GlProgram::operator=(GlProgram&& o) noexcept {
    if (this != &o) {
        if (id_) glDeleteProgram(id_);
        id_ = o.id_;
        o.id_ = 0;
    }
    return *this;
}

void GlProgram::use() const { glUseProgram(id_); }
void GlProgram::set(const char* name, int v) const { glUniform1i(glGetUniformLocation(id_, name), v); }
void GlProgram::set(const char* name, float v) const { glUniform1f(glGetUniformLocation(id_, name), v); }
void GlProgram::set(const char* name, const Eigen::Vector3f& v) const {
    glUniform3fv(glGetUniformLocation(id_, name), 1, v.data());
}
void GlProgram::set(const char* name, const Eigen::Matrix4f& m) const {
    glUniformMatrix4fv(glGetUniformLocation(id_, name), 1, GL_FALSE, m.data());  // Eigen is column-major too
}

}  // namespace shatter
