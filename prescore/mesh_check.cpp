// Topology and measures of a triangle mesh. Definitions: mesh_check.h.
//
// Edges are found by sorting the 3T directed half-edges by their undirected key, so the cost is
// O(T log T) and the result does not depend on hash order. Fans around vertices and components
// use union-find: over triangle corners (3 per triangle) for fans, over triangles for components.
#include "prescore/mesh_check.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <sstream>

#include <fmt/format.h>

namespace shatter {
namespace {

class UnionFind {
public:
    explicit UnionFind(size_t n) : parent_(n) { std::iota(parent_.begin(), parent_.end(), size_t(0)); }
    size_t find(size_t x) {
        while (parent_[x] != x) x = parent_[x] = parent_[parent_[x]];
        return x;
    }
    void unite(size_t a, size_t b) {
        a = find(a), b = find(b);
        if (a != b) parent_[std::max(a, b)] = std::min(a, b);
    }

private:
    std::vector<size_t> parent_;
};

struct HalfEdge {
    uint64_t key;     // min(u, v) << 32 | max(u, v)
    uint32_t tri;
    uint8_t corner;   // the edge goes from corner to corner + 1 of `tri`
    bool forward;     // u < v
};

bool has_repeated_index(const Tri& t) { return t[0] == t[1] || t[1] == t[2] || t[0] == t[2]; }

bool is_zero_area(const Vec3& a, const Vec3& b, const Vec3& c) {
    double longest = std::max({(b - a).squaredNorm(), (c - b).squaredNorm(), (a - c).squaredNorm()});
    return (b - a).cross(c - a).norm() <= 1e-12 * longest;
}

std::vector<HalfEdge> sorted_half_edges(const TriangleMesh& mesh) {
    std::vector<HalfEdge> edges;
    edges.reserve(3 * mesh.triangles.size());
    for (uint32_t t = 0; t < mesh.triangles.size(); ++t) {
        const Tri& tri = mesh.triangles[t];
        if (has_repeated_index(tri)) continue;
        for (uint8_t i = 0; i < 3; ++i) {
            uint32_t u = tri[i], v = tri[(i + 1) % 3];
            uint64_t key = (uint64_t(std::min(u, v)) << 32) | std::max(u, v);
            edges.push_back({key, t, i, u < v});
        }
    }
    std::sort(edges.begin(), edges.end(), [](const HalfEdge& a, const HalfEdge& b) {
        return a.key != b.key ? a.key < b.key : a.tri < b.tri;
    });
    return edges;
}

// Edge counts, fans around vertices and components, from the sorted half-edges.
void check_topology(const TriangleMesh& mesh, MeshCheck& check) {
    const std::vector<HalfEdge> edges = sorted_half_edges(mesh);
    UnionFind corners(3 * mesh.triangles.size());  // corner id: 3 * triangle + corner
    UnionFind triangles(mesh.triangles.size());
    for (size_t begin = 0; begin < edges.size();) {
        size_t end = begin;
        while (end < edges.size() && edges[end].key == edges[begin].key) ++end;
        const size_t count = end - begin;
        if (count == 1) ++check.boundary_edges;
        if (count > 2) ++check.nonmanifold_edges;
        if (count == 2 && edges[begin].forward == edges[begin + 1].forward) ++check.misoriented_edges;
        for (size_t i = begin + 1; i < end; ++i) {
            const HalfEdge& a = edges[begin];
            const HalfEdge& b = edges[i];
            triangles.unite(a.tri, b.tri);
            // Join the corners of both triangles at each end of the edge: u is the lower index.
            auto corner_at = [&](const HalfEdge& h, bool lower) {
                bool start = (h.forward == lower);  // the edge's start vertex is the one wanted
                return 3 * size_t(h.tri) + (start ? h.corner : (h.corner + 1) % 3);
            };
            corners.unite(corner_at(a, true), corner_at(b, true));
            corners.unite(corner_at(a, false), corner_at(b, false));
        }
        begin = end;
    }
    std::vector<uint32_t> fans(mesh.vertices.size(), 0);
    for (uint32_t t = 0; t < mesh.triangles.size(); ++t) {
        if (has_repeated_index(mesh.triangles[t])) continue;
        if (triangles.find(t) == t) ++check.components;
        for (int i = 0; i < 3; ++i)
            if (corners.find(3 * size_t(t) + i) == 3 * size_t(t) + i) ++fans[mesh.triangles[t][i]];
    }
    check.nonmanifold_vertices = size_t(std::count_if(fans.begin(), fans.end(), [](uint32_t f) { return f > 1; }));
}

void bounding_box(const TriangleMesh& mesh, Vec3& lo, Vec3& hi) {
    lo = hi = mesh.vertices[0];
    for (const Vec3& v : mesh.vertices) {
        lo = lo.cwiseMin(v);
        hi = hi.cwiseMax(v);
    }
}

void check_measures(const TriangleMesh& mesh, MeshCheck& check) {
    if (!mesh.vertices.empty()) {
        bounding_box(mesh, check.bbox_min, check.bbox_max);
        check.diagonal = (check.bbox_max - check.bbox_min).norm();
    }
    for (const Tri& t : mesh.triangles) {
        const Vec3 &a = mesh.vertices[t[0]], &b = mesh.vertices[t[1]], &c = mesh.vertices[t[2]];
        check.volume += a.dot(b.cross(c)) / 6.0;
        check.area += 0.5 * (b - a).cross(c - a).norm();
        if (has_repeated_index(t) || is_zero_area(a, b, c)) ++check.degenerate_triangles;
    }
}

}  // namespace

double bounding_diagonal(const TriangleMesh& mesh) {
    if (mesh.vertices.empty()) return 0;
    Vec3 lo, hi;
    bounding_box(mesh, lo, hi);
    return (hi - lo).norm();
}

MeshCheck check_mesh(const TriangleMesh& mesh, bool find_self_intersections) {
    MeshCheck check;
    check.vertices = mesh.vertices.size();
    check.triangles = mesh.triangles.size();
    check_measures(mesh, check);
    check_topology(mesh, check);
    if (find_self_intersections) check.self_intersections = count_self_intersections(mesh);
    return check;
}

std::string describe(const MeshCheck& c) {
    std::ostringstream s;
    s.precision(4);
    s << c.vertices << " vertices, " << c.triangles << " triangles, ";
    s << (c.closed() ? "closed" : std::to_string(c.boundary_edges) + " boundary edges") << ", ";
    if (c.manifold()) {
        s << "manifold, ";
    } else {
        s << c.nonmanifold_edges << " non-manifold edges, " << c.nonmanifold_vertices
          << " non-manifold vertices, ";
    }
    s << (c.oriented() ? "oriented" : std::to_string(c.misoriented_edges) + " misoriented edges") << ", ";
    s << c.components << (c.components == 1 ? " component, " : " components, ");
    if (c.degenerate_triangles > 0) s << c.degenerate_triangles << " degenerate triangles, ";
    s << c.self_intersections << " self-intersecting pairs, ";
    const Vec3 size = c.bbox_max - c.bbox_min;
    s << "volume " << c.volume << " m^3, area " << c.area << " m^2, bbox " << size.x() << " x "
      << size.y() << " x " << size.z() << " m";
    return s.str();
}

bool orient_outward(TriangleMesh& mesh) {
    double volume = 0;
    for (const Tri& t : mesh.triangles)
        volume += mesh.vertices[t[0]].dot(mesh.vertices[t[1]].cross(mesh.vertices[t[2]]));
    if (volume >= 0) return false;
    for (Tri& t : mesh.triangles) std::swap(t[1], t[2]);
    return true;
}

bool can_tetrahedralize(const MeshCheck& c, std::string* why) {
    std::string problem;
    if (c.triangles == 0) {
        problem = "the mesh has no triangles";
    } else if (!c.closed()) {
        problem = "the mesh is not closed (" + std::to_string(c.boundary_edges) + " boundary edges)";
    } else if (!c.manifold()) {
        problem = "the mesh is not manifold (" + std::to_string(c.nonmanifold_edges) + " edges, " +
                  std::to_string(c.nonmanifold_vertices) + " vertices)";
    } else if (!c.oriented()) {
        problem = "the triangles are not consistently oriented (" + std::to_string(c.misoriented_edges) +
                  " misoriented edges)";
    } else if (!(c.volume > 0)) {
        std::ostringstream s;
        s << "the enclosed volume " << c.volume << " m^3 is not positive (an inside-out mesh: orient_outward)";
        problem = s.str();
    } else if (c.degenerate_triangles > 0) {
        problem = "the mesh has " + std::to_string(c.degenerate_triangles) + " degenerate triangles";
    }
    if (problem.empty()) return true;
    if (why != nullptr) *why = problem + "; repair it with alpha wrapping (closes, cleans and orients any mesh)";
    return false;
}

bool is_sheet(const MeshCheck& c, std::string* why) {
    const Vec3 extent = c.bbox_max - c.bbox_min;
    const double d = c.diagonal;
    const bool flat = extent.minCoeff() <= 1e-6 * d;
    const bool empty_inside = c.closed() && std::abs(c.volume) <= 1e-9 * d * d * d;
    if (!flat && !empty_inside) return false;
    *why = fmt::format("the mesh is a sheet: {} (bounding box {:.4g} x {:.4g} x {:.4g} m, volume {:.4g} m^3); repair it "
                       "with alpha wrapping, which gives it a thickness",
                       flat ? "flat" : "it encloses no volume", extent.x(), extent.y(), extent.z(), c.volume);
    return true;
}

size_t max_self_intersections(const MeshCheck& c) { return std::max<size_t>(8, c.triangles / 100); }

void stand_up(std::vector<Vec3>& points) {
    for (Vec3& v : points) v = Vec3(v.x(), v.z(), -v.y());
}

bool meshes_as_it_is(const MeshCheck& input, const MeshCheck& oriented, bool count_crossings, std::string* why) {
    std::string reason;
    bool usable = !is_sheet(input, &reason) && can_tetrahedralize(oriented, &reason);
    if (usable && count_crossings && input.self_intersections > max_self_intersections(input)) {
        usable = false;
        reason = fmt::format("{} self-intersecting triangle pairs (more than {})", input.self_intersections,
                             max_self_intersections(input));
    }
    if (why != nullptr) *why = reason;
    return usable;
}


}  // namespace shatter
