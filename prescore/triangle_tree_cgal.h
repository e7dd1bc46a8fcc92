// The triangle lookup shared by the translation units that ask a surface for its nearest point
// (render_surface_cgal.cpp: normals; appearance_transfer_cgal.cpp: UVs, colours, materials;
// surface_agreement_cgal.cpp: distances) or whether a ball meets it (surface_distance_cgal.cpp):
// a CGAL AABB tree over triangles in Simple_cartesian<double> (no predicate that needs
// exactness), and the barycentric weights the attribute transfers interpolate with. Include from
// CGAL translation units only.
#pragma once

#include <algorithm>
#include <vector>

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Simple_cartesian.h>

#include "core/geometry.h"

namespace shatter {

using TreeKernel = CGAL::Simple_cartesian<double>;
using TreeTriangle = TreeKernel::Triangle_3;
using TriangleTree = CGAL::AABB_tree<CGAL::AABB_traits<
    TreeKernel, CGAL::AABB_triangle_primitive<TreeKernel, std::vector<TreeTriangle>::const_iterator>>>;

inline TreeKernel::Point_3 tree_point(const Vec3& v) { return {v.x(), v.y(), v.z()}; }

// Barycentric weights (sum 1) of p's projection on the plane of triangle abc: negative outside
// the triangle. A degenerate triangle gives its centre.
inline Vec3 barycentric(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
    const Vec3 n = (b - a).cross(c - a);
    const double nn = n.squaredNorm();
    if (!(nn > 0)) return Vec3(1.0 / 3, 1.0 / 3, 1.0 / 3);
    Vec3 w((c - b).cross(p - b).dot(n) / nn, (a - c).cross(p - c).dot(n) / nn, 0);
    w.z() = 1 - w.x() - w.y();
    return w;
}

// Weights clamped to the triangle (non-negative, sum 1).
inline Vec3 clamped(Vec3 w) {
    w = w.cwiseMax(0.0);
    return w / std::max(w.sum(), 1e-300);
}

}  // namespace shatter
