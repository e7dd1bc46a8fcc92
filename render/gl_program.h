// A linked GLSL program and uniform setters by name. Compile and link failures are our bugs
// (the sources are built in) and throw Error(Internal) with the driver's log.
#pragma once

#include <string>

#include <Eigen/Core>

namespace shatter {

class GlProgram {
public:
    GlProgram() = default;
    GlProgram(const char* vertex_source, const char* fragment_source, const char* name);
    ~GlProgram();
    GlProgram(GlProgram&& o) noexcept : id_(o.id_) { o.id_ = 0; }
    GlProgram& operator=(GlProgram&& o) noexcept;
    GlProgram(const GlProgram&) = delete;
    GlProgram& operator=(const GlProgram&) = delete;

    void use() const;
    unsigned id() const { return id_; }
    // Setters of the program in use; a name the linker optimized away is ignored.
    void set(const char* name, int v) const;
    void set(const char* name, float v) const;
    void set(const char* name, const Eigen::Vector3f& v) const;
    void set(const char* name, const Eigen::Matrix4f& m) const;

private:
    unsigned id_ = 0;
};

}  // namespace shatter
