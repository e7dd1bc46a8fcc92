// Geometry types every stage shares. Coordinates are in metres once a mesh is loaded (the
// shot's mesh.scale is applied at load time), in the model frame (the frame of the input mesh).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <cstdint>
#include <vector>

namespace shatter {

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;
using Tri = std::array<uint32_t, 3>;  // vertex indices, counter-clockwise seen from outside
using Tet = std::array<uint32_t, 4>;  // vertex indices, positive orientation (see tet_volume)

// An indexed triangle mesh (a surface, or a soup when it is not closed).
struct TriangleMesh {
    std::vector<Vec3> vertices;  // (unit: m)
    std::vector<Tri> triangles;
};

// A tetrahedral mesh. Every tet has positive signed volume.
struct TetMesh {
    std::vector<Vec3> vertices;  // (unit: m)
    std::vector<Tet> tets;
};

// Signed volume of tet (a, b, c, d): det[b-a, c-a, d-a] / 6, positive when d lies on the side
// that the normal (b-a)x(c-a) of triangle (a, b, c) points to.
inline double tet_volume(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
    return (b - a).cross(c - a).dot(d - a) / 6.0;
}

// The centroid of tet t of `mesh`: the mean of its four vertices.
inline Vec3 tet_centroid(const TetMesh& mesh, uint32_t t) {
    const Tet& k = mesh.tets[t];
    return (mesh.vertices[k[0]] + mesh.vertices[k[1]] + mesh.vertices[k[2]] + mesh.vertices[k[3]]) / 4;
}

// The four faces of a positively oriented tet; face i is opposite vertex i and is ordered so
// that its normal points out of the tet.
constexpr std::array<std::array<int, 3>, 4> kTetFaces = {{{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}}};

}  // namespace shatter
