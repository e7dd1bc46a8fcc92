// Hollowing in three stages (see hollow.h): select the shell by centroid distance, restore
// bridges between shell parts that removal separated, then extract the kept tets.
#include "prescore/hollow.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <numeric>
#include <queue>
#include <string>
#include <tuple>
#include <utility>

#include "core/error.h"
#include "prescore/surface_distance.h"

namespace shatter {

namespace {

Vec3 centroid(const TetMesh& mesh, const Tet& t) {
    return 0.25 * (mesh.vertices[t[0]] + mesh.vertices[t[1]] + mesh.vertices[t[2]] + mesh.vertices[t[3]]);
}

// Upper bounds (m) on the distance from each tet centroid to the boundary surface: for boundary
// tets the distance to a boundary face's centroid, then shortest paths through the centroids of
// face neighbours (Dijkstra), explored only up to `limit`; infinity beyond. Every tet whose bound
// is <= limit is within `limit` of the surface and needs no exact query.
std::vector<double> distance_upper_bounds(const TetMesh& mesh, const TetTopology& topology,
                                          const std::vector<Vec3>& centroids, double limit) {
    std::vector<double> bound(mesh.tets.size(), INFINITY);
    using Entry = std::pair<double, uint32_t>;
    std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> heap;
    for (size_t t = 0; t < mesh.tets.size(); ++t) {
        const Tet& tet = mesh.tets[t];
        for (int i = 0; i < 4; ++i) {
            if (topology.neighbour[t][i] >= 0) continue;
            const Vec3 face = (mesh.vertices[tet[kTetFaces[i][0]]] + mesh.vertices[tet[kTetFaces[i][1]]] +
                               mesh.vertices[tet[kTetFaces[i][2]]]) / 3.0;
            bound[t] = std::min(bound[t], (centroids[t] - face).norm());
        }
        if (bound[t] <= limit) heap.emplace(bound[t], uint32_t(t));
    }
    while (!heap.empty()) {
        const auto [d, t] = heap.top();
        heap.pop();
        if (d > bound[t]) continue;  // stale entry
        for (int32_t u : topology.neighbour[t]) {
            if (u < 0) continue;
            const double via = d + (centroids[t] - centroids[u]).norm();
            if (via < bound[u] && via <= limit) {
                bound[u] = via;
                heap.emplace(via, uint32_t(u));
            }
        }
    }
    return bound;
}

// Tets to keep: a boundary face, or the centroid within `thickness` of the boundary surface.
// Cheap upper bounds settle most kept tets; an exact AABB-tree ball test settles the rest.
std::vector<char> select_shell(const TetMesh& mesh, const TetTopology& topology, double thickness) {
    std::vector<char> keep(mesh.tets.size(), 0);
    std::vector<Vec3> centroids(mesh.tets.size());
    TriangleMesh boundary{mesh.vertices, {}};
    for (size_t t = 0; t < mesh.tets.size(); ++t) {
        const Tet& tet = mesh.tets[t];
        centroids[t] = centroid(mesh, tet);
        for (int i = 0; i < 4; ++i) {
            if (topology.neighbour[t][i] >= 0) continue;
            boundary.triangles.push_back({tet[kTetFaces[i][0]], tet[kTetFaces[i][1]], tet[kTetFaces[i][2]]});
            keep[t] = 1;
        }
    }
    const std::vector<double> bound = distance_upper_bounds(mesh, topology, centroids, thickness);
    std::vector<uint32_t> unsure;
    std::vector<Vec3> points;
    for (size_t t = 0; t < mesh.tets.size(); ++t) {
        if (keep[t]) continue;
        if (bound[t] <= thickness) {
            keep[t] = 1;
        } else {
            unsure.push_back(uint32_t(t));
            points.push_back(centroids[t]);
        }
    }
    const std::vector<char> near = within_distance(boundary, points, thickness);
    for (size_t k = 0; k < unsure.size(); ++k) keep[unsure[k]] = near[k];
    return keep;
}

struct DisjointSets {
    std::vector<int32_t> parent;
    explicit DisjointSets(int32_t n) : parent(size_t(n)) { std::iota(parent.begin(), parent.end(), 0); }
    int32_t find(int32_t x) {
        while (parent[x] != x) x = parent[x] = parent[parent[x]];
        return x;
    }
    bool unite(int32_t a, int32_t b) {
        a = find(a);
        b = find(b);
        if (a == b) return false;
        parent[std::max(a, b)] = std::min(a, b);
        return true;
    }
};

struct Bridge {
    uint32_t cost;  // removed tets on the path
    uint32_t t, u;  // the face (t, u) where the two searches meet, t < u
    bool operator<(const Bridge& o) const { return std::tie(cost, t, u) < std::tie(o.cost, o.t, o.u); }
};

// Puts removed tets back until each input component holds one component of kept tets.
// Returns how many were put back.
size_t restore_connectivity(const TetTopology& topology, std::vector<char>& keep) {
    int32_t input_count = 0, kept_count = 0;
    tet_components(topology, {}, &input_count);
    std::vector<int32_t> label = tet_components(topology, keep, &kept_count);
    if (kept_count == input_count) return 0;  // every input component has boundary tets, all kept

    // Multi-source BFS from all kept tets through removed ones: nearest kept part and path back.
    const size_t n = keep.size();
    std::vector<uint32_t> dist(n, 0);
    std::vector<int32_t> parent(n, -1);
    std::vector<uint32_t> queue;
    for (size_t t = 0; t < n; ++t) {
        if (keep[t]) queue.push_back(uint32_t(t));
    }
    for (size_t head = 0; head < queue.size(); ++head) {
        const uint32_t t = queue[head];
        for (int32_t u : topology.neighbour[t]) {
            if (u < 0 || label[u] >= 0) continue;
            label[u] = label[t];
            dist[u] = dist[t] + 1;
            parent[u] = int32_t(t);
            queue.push_back(uint32_t(u));
        }
    }
    std::vector<Bridge> bridges;
    for (size_t t = 0; t < n; ++t) {
        for (int32_t u : topology.neighbour[t]) {
            if (u <= int32_t(t) || label[t] < 0 || label[u] < 0 || label[u] == label[t]) continue;
            bridges.push_back({dist[t] + dist[u], uint32_t(t), uint32_t(u)});
        }
    }
    std::sort(bridges.begin(), bridges.end());
    DisjointSets sets(kept_count);
    size_t restored = 0;
    for (const Bridge& b : bridges) {
        if (!sets.unite(label[b.t], label[b.u])) continue;
        for (int32_t x : {int32_t(b.t), int32_t(b.u)}) {
            for (; !keep[x]; x = parent[x]) {
                keep[x] = 1;
                ++restored;
            }
        }
    }
    return restored;
}

HollowResult extract(const TetMesh& mesh, const TetTopology& topology, const std::vector<char>& keep) {
    HollowResult result;
    constexpr uint32_t kUnused = UINT32_MAX;
    std::vector<uint32_t> remap(mesh.vertices.size(), kUnused);
    for (size_t t = 0; t < mesh.tets.size(); ++t) {
        if (!keep[t]) continue;
        for (uint32_t v : mesh.tets[t]) remap[v] = 0;
    }
    for (size_t v = 0; v < mesh.vertices.size(); ++v) {
        if (remap[v] == kUnused) continue;
        remap[v] = uint32_t(result.mesh.vertices.size());
        result.mesh.vertices.push_back(mesh.vertices[v]);
    }
    for (size_t t = 0; t < mesh.tets.size(); ++t) {
        if (!keep[t]) {
            ++result.removed;
            continue;
        }
        const Tet& tet = mesh.tets[t];
        result.mesh.tets.push_back({remap[tet[0]], remap[tet[1]], remap[tet[2]], remap[tet[3]]});
        result.source_tet.push_back(uint32_t(t));
        std::array<bool, 4> cavity{};
        for (int i = 0; i < 4; ++i) {
            const int32_t u = topology.neighbour[t][i];
            cavity[i] = u >= 0 && !keep[u];
        }
        result.cavity_face.push_back(cavity);
    }
    return result;
}

}  // namespace

HollowResult hollow(const TetMesh& mesh, const TetTopology& topology, double thickness) {
    assert(topology.neighbour.size() == mesh.tets.size());
    if (!std::isfinite(thickness) || thickness <= 0) {
        throw_input_error("hollow.thickness", "must be a finite length > 0 (m), got " + std::to_string(thickness),
                          "give the shell thickness in metres, or turn hollowing off");
    }
    std::vector<char> keep = select_shell(mesh, topology, thickness);
    const size_t restored = restore_connectivity(topology, keep);
    HollowResult result = extract(mesh, topology, keep);
    result.restored = restored;
    return result;
}

}  // namespace shatter
