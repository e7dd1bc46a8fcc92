#include "prescore/sharp_features.h"

#include <algorithm>
#include <cmath>
#include <map>

namespace shatter {

namespace {

using Edge = std::pair<uint32_t, uint32_t>;  // (low, high) vertex index

std::map<Edge, std::vector<uint32_t>> edge_triangles(const TriangleMesh& mesh) {
    std::map<Edge, std::vector<uint32_t>> edges;
    for (uint32_t t = 0; t < mesh.triangles.size(); ++t)
        for (int k = 0; k < 3; ++k) {
            uint32_t a = mesh.triangles[t][k], b = mesh.triangles[t][(k + 1) % 3];
            edges[std::minmax(a, b)].push_back(t);
        }
    return edges;
}

Vec3 normal(const TriangleMesh& mesh, uint32_t t) {
    const Tri& tri = mesh.triangles[t];
    const Vec3& a = mesh.vertices[tri[0]];
    return (mesh.vertices[tri[1]] - a).cross(mesh.vertices[tri[2]] - a).normalized();
}

}  // namespace

std::vector<Polyline> sharp_polylines(const TriangleMesh& mesh, double angle_degrees, double min_length) {
    const double cos_limit = std::cos(angle_degrees * M_PI / 180.0);
    // Sharp-edge graph: for each vertex, its sharp neighbours in ascending order.
    std::map<uint32_t, std::vector<uint32_t>> graph;
    for (const auto& [edge, tris] : edge_triangles(mesh)) {
        if (tris.size() != 2) continue;
        if (normal(mesh, tris[0]).dot(normal(mesh, tris[1])) >= cos_limit) continue;
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
