#include "prescore/sharp_features.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <map>

namespace shatter {

namespace {

using Edge = std::pair<uint32_t, uint32_t>;  // (low, high) vertex index

// Each edge (low, high) that exactly two triangles share, with those two, in ascending order of
// the edge: one sort of the triangles' sides.
std::vector<std::pair<Edge, std::array<uint32_t, 2>>> edges_of_two(const TriangleMesh& mesh) {
    std::vector<std::pair<uint64_t, uint32_t>> sides;  // (low << 32 | high, triangle)
    sides.reserve(3 * mesh.triangles.size());
    for (uint32_t t = 0; t < mesh.triangles.size(); ++t)
        for (int k = 0; k < 3; ++k) {
            const auto [a, b] = std::minmax(mesh.triangles[t][k], mesh.triangles[t][(k + 1) % 3]);
            sides.emplace_back(uint64_t(a) << 32 | b, t);
        }
    std::sort(sides.begin(), sides.end());
    std::vector<std::pair<Edge, std::array<uint32_t, 2>>> out;
    for (size_t i = 0; i < sides.size();) {
        size_t j = i + 1;
        while (j < sides.size() && sides[j].first == sides[i].first) ++j;
        if (j - i == 2) {
            const Edge edge{uint32_t(sides[i].first >> 32), uint32_t(sides[i].first)};
            out.push_back({edge, {sides[i].second, sides[i + 1].second}});
        }
        i = j;
    }
    return out;
}

Vec3 normal(const TriangleMesh& mesh, uint32_t t) {
    const Tri& tri = mesh.triangles[t];
    const Vec3& a = mesh.vertices[tri[0]];
    return (mesh.vertices[tri[1]] - a).cross(mesh.vertices[tri[2]] - a).normalized();
}

}  // namespace

// (A map of edges to vectors of triangles and the normals per edge took 75 to 82 ms on glmark2's
// bunny, in the tets' critical path; sorted sides and the normals once, 22 to 24 ms.)
std::vector<Polyline> sharp_polylines(const TriangleMesh& mesh, double angle_degrees, double min_length) {
    const double cos_limit = std::cos(angle_degrees * M_PI / 180.0);
    // Sharp-edge graph: for each vertex, its sharp neighbours in ascending order.
    std::map<uint32_t, std::vector<uint32_t>> graph;
    std::vector<Vec3> normals(mesh.triangles.size());
    for (uint32_t t = 0; t < mesh.triangles.size(); ++t) normals[t] = normal(mesh, t);
    for (const auto& [edge, tris] : edges_of_two(mesh)) {
        if (normals[tris[0]].dot(normals[tris[1]]) >= cos_limit) continue;
        graph[edge.first].push_back(edge.second);
        graph[edge.second].push_back(edge.first);
    }
    std::map<Edge, bool> used;
    std::vector<Polyline> out;
    auto walk = [&](uint32_t start, uint32_t next) {
        std::vector<uint32_t> chain = {start};
        uint32_t prev = start, cur = next;
        used[std::minmax(prev, cur)] = true;
        chain.push_back(cur);
        while (graph[cur].size() == 2 && cur != start) {
            const uint32_t n = graph[cur][0] == prev ? graph[cur][1] : graph[cur][0];
            if (used[std::minmax(cur, n)]) break;
            used[std::minmax(cur, n)] = true;
            prev = cur;
            cur = n;
            chain.push_back(cur);
        }
        Polyline line;
        double length = 0;
        for (uint32_t v : chain) {
            if (!line.empty()) length += (mesh.vertices[v] - line.back()).norm();
            line.push_back(mesh.vertices[v]);
        }
        if (length >= min_length) out.push_back(std::move(line));
    };
    // Open chains start at vertices where the graph does not simply pass through (degree != 2);
    // what is left afterwards are closed loops.
    for (const auto& [v, nbrs] : graph)
        if (nbrs.size() != 2)
            for (uint32_t n : nbrs)
                if (!used[std::minmax(v, n)]) walk(v, n);
    for (const auto& [v, nbrs] : graph)
        for (uint32_t n : nbrs)
            if (!used[std::minmax(v, n)]) walk(v, n);
    return out;
}

}  // namespace shatter
