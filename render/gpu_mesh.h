// A vertex array on the GL side: the flat-shaded vertices of render/mesh_builder.h in one buffer,
// drawn as a triangle list.
#pragma once

#include <vector>

#include "render/mesh_builder.h"

namespace shatter {

class GpuMesh {
public:
    explicit GpuMesh(const std::vector<Vertex>& vertices);
    ~GpuMesh();
    GpuMesh(const GpuMesh&) = delete;
    GpuMesh& operator=(const GpuMesh&) = delete;
    void draw() const;

private:
    unsigned vao_ = 0;
    unsigned vbo_ = 0;
    int count_ = 0;
};

}  // namespace shatter
