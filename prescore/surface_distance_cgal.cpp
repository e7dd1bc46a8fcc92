// Ball-versus-surface tests with CGAL's AABB tree (CGAL 5.5, Simple_cartesian<double>):
// do_intersect of a Sphere_3 (a solid ball for CGAL's Sphere_3/Triangle_3 and Sphere_3/Bbox_3
// predicates) with the triangles. Each answer is independent of query order, so results are
// deterministic.
#include "prescore/surface_distance.h"

#include "prescore/triangle_tree_cgal.h"

namespace shatter {

// The tree is plain doubles, no exact fallback: the filtered Epick predicates for ball/triangle
// tests fail their filter so often near the surface that exact arithmetic cost 10x the time; a
// centroid's distance rule does not need exactness, and IEEE doubles give the same answers on
// every run.

std::vector<char> within_distance(const TriangleMesh& surface, const std::vector<Vec3>& points, double radius) {
    std::vector<char> within(points.size(), 0);
    if (surface.triangles.empty()) return within;
    std::vector<TreeTriangle> triangles;
    triangles.reserve(surface.triangles.size());
    for (const Tri& t : surface.triangles) {
        triangles.emplace_back(tree_point(surface.vertices[t[0]]), tree_point(surface.vertices[t[1]]),
                               tree_point(surface.vertices[t[2]]));
    }
    const TriangleTree tree(triangles.cbegin(), triangles.cend());
    const double r2 = radius * radius;
    for (size_t i = 0; i < points.size(); ++i) {
        within[i] = tree.do_intersect(TreeKernel::Sphere_3(tree_point(points[i]), r2)) ? 1 : 0;
    }
    return within;
}

}  // namespace shatter
