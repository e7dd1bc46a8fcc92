// A vertex array on the GL side: the vertices of render/mesh_builder.h in one buffer, drawn as a
// triangle list, either unindexed (three vertices per triangle) or with an index buffer.
#pragma once

#include <vector>

#include <Eigen/Geometry>

#include "render/mesh_builder.h"

namespace shatter {

class GpuMesh {
public:
    explicit GpuMesh(const std::vector<Vertex>& vertices);
    explicit GpuMesh(const IndexedVertices& mesh);
    ~GpuMesh();
    GpuMesh(const GpuMesh&) = delete;
    GpuMesh& operator=(const GpuMesh&) = delete;
    void draw() const;
    const Eigen::AlignedBox3f& bounds() const { return bounds_; }  // of the vertices, in the mesh's frame

private:
    Eigen::AlignedBox3f bounds_;
    unsigned vao_ = 0;
    unsigned vbo_ = 0;
    unsigned ebo_ = 0;   // 0: unindexed
    int count_ = 0;      // vertices (unindexed) or indices drawn
};

}  // namespace shatter
