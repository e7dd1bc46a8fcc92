// alpha_wrap: the soup goes to CGAL::alpha_wrap_3 (Epick) as points + triangles, and the
// wrap's Surface_mesh comes back as a TriangleMesh in the Surface_mesh's vertex order.
// Triangles with a repeated index or no area are left out (they add nothing to the wrapped shape).
// CGAL orients the wrap outward; if the volume ever came out negative we flip it
// (orient_outward), so callers may rely on "outward".
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/alpha_wrap_3.h>

#include <cmath>
#include <sstream>

#include "core/error.h"
#include "prescore/mesh_check.h"
#include "prescore/repair.h"

namespace shatter {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using Mesh = CGAL::Surface_mesh<Point>;

void check_length(const char* name, double value) {
    if (std::isfinite(value) && value > 0) return;
    std::ostringstream s;
    s << name << " = " << value << " m must be finite and > 0";
    throw_input_error("alpha wrap settings", s.str(),
                      "use a fraction of the mesh's bounding-box diagonal (alpha ~ diag/50, offset ~ diag/1000)");
}

TriangleMesh to_triangle_mesh(const Mesh& wrap) {
    TriangleMesh out;
    out.vertices.reserve(wrap.number_of_vertices());
    for (Mesh::Vertex_index v : wrap.vertices()) {
        const Point& p = wrap.point(v);
        out.vertices.emplace_back(p.x(), p.y(), p.z());
    }
    out.triangles.reserve(wrap.number_of_faces());
    for (Mesh::Face_index f : wrap.faces()) {
        Tri t{};
        int i = 0;
        for (Mesh::Vertex_index v : CGAL::vertices_around_face(wrap.halfedge(f), wrap)) t[i++] = uint32_t(v);
        out.triangles.push_back(t);
    }
    return out;
}

}  // namespace

TriangleMesh alpha_wrap(const TriangleMesh& soup, double alpha, double offset) {
    check_length("alpha", alpha);
    check_length("offset", offset);
    std::vector<Point> points;
    points.reserve(soup.vertices.size());
    for (const Vec3& v : soup.vertices) points.emplace_back(v.x(), v.y(), v.z());
    std::vector<std::array<size_t, 3>> faces;
    faces.reserve(soup.triangles.size());
    for (const Tri& t : soup.triangles) {
        // Triangles with a repeated index or no area add nothing to the wrapped shape, and a
        // soup of only collinear triangles crashed CGAL's wrapper (assimp's OBJ/number_formats.obj).
        const Vec3 &a = soup.vertices[t[0]], &b = soup.vertices[t[1]], &c = soup.vertices[t[2]];
        if (t[0] != t[1] && t[1] != t[2] && t[0] != t[2] && (b - a).cross(c - a).squaredNorm() > 0)
            faces.push_back({t[0], t[1], t[2]});
    }
    if (faces.empty()) {
        throw_input_error("alpha wrap input", "the mesh has no triangle with three distinct vertices and an area",
                          "give a mesh with triangles");
    }

    Mesh wrap;
    CGAL::alpha_wrap_3(points, faces, alpha, offset, wrap);
    // A fresh wrap has no removed elements; collect_garbage keeps vertex indices dense anyway.
    wrap.collect_garbage();
    TriangleMesh out = to_triangle_mesh(wrap);
    orient_outward(out);
    return out;
}

}  // namespace shatter
