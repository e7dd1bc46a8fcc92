// Counting intersecting triangle pairs with CGAL::Polygon_mesh_processing::self_intersections.
//
// CGAL 5.5 has no triangle-soup variant, so the triangles go into a Surface_mesh (Epick: exact
// predicates, so the count does not depend on rounding). Not counted: the pairs (f, f) CGAL
// reports for a degenerate face (check_mesh counts degenerate triangles itself), and triangles
// with a repeated index, which cannot enter a Surface_mesh.
//
// The faces are added to the Surface_mesh one by one, which succeeds for an oriented manifold
// (the usual case). A soup that is not one (non-manifold or non-orientable) is made one with
// orient_polygon_soup, which splits the vertices and edges where it is not manifold into
// copies at the same position. Triangles joined only
// through such a copy look disjoint to CGAL, which then reports their contact as an
// intersection; a reported pair that shares fewer vertices after the split than before is
// therefore dropped. The cost: a real crossing between two triangles that meet at a
// non-manifold vertex is missed. Such meshes cannot be tetrahedralized anyway.
//
// Measured on the bunny (69,666 triangles, 2 pairs), 2-core machine under load: ~0.2 s.
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Surface_mesh.h>

#include <iterator>

#include "prescore/mesh_check.h"

namespace shatter {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using Mesh = CGAL::Surface_mesh<Point>;
using Polygon = std::array<size_t, 3>;
namespace PMP = CGAL::Polygon_mesh_processing;

int shared_vertices(const Polygon& a, const Polygon& b) {
    int n = 0;
    for (size_t u : a)
        for (size_t v : b) n += (u == v);
    return n;
}

// Adds the polygons to an empty `surface` one by one (face i is polygon i); false when one
// cannot be added (the soup is not an oriented manifold). Much faster on the bunny than
// is_polygon_soup_a_polygon_mesh + polygon_soup_to_polygon_mesh (measured 0.16 s for those).
bool add_faces(const std::vector<Polygon>& polygons, Mesh& surface) {
    using V = Mesh::Vertex_index;
    for (const Polygon& p : polygons)
        if (surface.add_face(V(uint32_t(p[0])), V(uint32_t(p[1])), V(uint32_t(p[2]))) == Mesh::null_face())
            return false;
    return true;
}

}  // namespace

size_t count_self_intersections(const TriangleMesh& mesh) {
    std::vector<Point> points;
    points.reserve(mesh.vertices.size());
    for (const Vec3& v : mesh.vertices) points.emplace_back(v.x(), v.y(), v.z());
    std::vector<Polygon> original;  // the triangles without a repeated index
    original.reserve(mesh.triangles.size());
    for (const Tri& t : mesh.triangles) {
        if (t[0] != t[1] && t[1] != t[2] && t[0] != t[2]) original.push_back({t[0], t[1], t[2]});
    }

    Mesh surface;
    surface.reserve(points.size(), 3 * original.size() / 2, original.size());
    for (const Point& p : points) surface.add_vertex(p);
    std::vector<Polygon> polygons;  // the split soup, when the fast path fails
    const bool split = !add_faces(original, surface);
    if (split) {
        polygons = original;
        PMP::orient_polygon_soup(points, polygons);  // keeps the polygons' order
        surface.clear();
        PMP::polygon_soup_to_polygon_mesh(points, polygons, surface);  // face i is polygon i
    }
    std::vector<std::pair<Mesh::Face_index, Mesh::Face_index>> pairs;
    PMP::self_intersections(surface, std::back_inserter(pairs));

    size_t count = 0;
    for (const auto& [f, g] : pairs) {
        if (f == g) continue;  // a degenerate face
        const size_t a = size_t(f), b = size_t(g);
        if (split && shared_vertices(polygons[a], polygons[b]) < shared_vertices(original[a], original[b]))
            continue;  // they only touch where the soup was split
        ++count;
    }
    return count;
}

}  // namespace shatter
