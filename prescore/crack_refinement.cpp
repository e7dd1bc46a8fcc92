// The crack tets split 1:8 (crack_refinement.h).
#include "prescore/crack_refinement.h"

#include <algorithm>

namespace shatter {

uint32_t CrackRefinement::midpoint(uint32_t a, uint32_t b) const {
    const std::array<uint32_t, 2> e = {std::min(a, b), std::max(a, b)};
    const auto it = std::lower_bound(edges.begin(), edges.end(), e, [](const auto& x, const auto& key) { return x.first < key; });
    return it != edges.end() && it->first == e ? it->second : UINT32_MAX;
}

CrackRefinement refine_tets(const TetMesh& mesh, const TetTopology& topology,
                            const std::vector<std::array<FaceKind, 4>>& face_kind, const std::vector<char>& split) {
    CrackRefinement r;
    r.mesh.vertices = mesh.vertices;
    // The split edges, numbered in ascending order after the original vertices.
    std::vector<std::array<uint32_t, 2>> edges;
    for (size_t t = 0; t < mesh.tets.size(); ++t) {
        if (!split[t]) continue;
        const Tet& k = mesh.tets[t];
        for (int a = 0; a < 4; ++a)
            for (int b = a + 1; b < 4; ++b) edges.push_back({std::min(k[a], k[b]), std::max(k[a], k[b])});
    }
    std::sort(edges.begin(), edges.end());
    edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
    for (const auto& e : edges) {
        r.edges.emplace_back(e, uint32_t(r.mesh.vertices.size()));
        r.ends.push_back(e);
        r.mesh.vertices.push_back((mesh.vertices[e[0]] + mesh.vertices[e[1]]) / 2);
    }
    for (uint32_t t = 0; t < mesh.tets.size(); ++t) {
        const Tet& k = mesh.tets[t];
        std::array<int32_t, 4> outer;  // per face of the original tet
        for (int i = 0; i < 4; ++i) outer[i] = topology.neighbour[t][i] < 0 ? int32_t(face_kind[t][i]) : -1;
        if (!split[t]) {
            r.mesh.tets.push_back(k);
            r.parent.push_back(t);
            r.whole.push_back(1);
            r.boundary.push_back(outer);
            continue;
        }
        // Local vertices: 0-3 the corners, then the midpoints; `mask` says which corners each
        // lies between (a face of a sub-tet lies on original face i when no vertex has bit i).
        std::array<uint32_t, 10> id;
        std::array<uint32_t, 10> mask;
        for (int a = 0; a < 4; ++a) id[a] = k[a], mask[a] = 1u << a;
        std::array<std::array<int, 4>, 4> mid{};
        int n = 4;
        for (int a = 0; a < 4; ++a)
            for (int b = a + 1; b < 4; ++b) {
                id[n] = r.midpoint(k[a], k[b]);
                mask[n] = (1u << a) | (1u << b);
                mid[a][b] = mid[b][a] = n++;
            }
        std::vector<std::array<int, 4>> sub = {{0, mid[0][1], mid[0][2], mid[0][3]},
                                               {mid[0][1], 1, mid[1][2], mid[1][3]},
                                               {mid[0][2], mid[1][2], 2, mid[2][3]},
                                               {mid[0][3], mid[1][3], mid[2][3], 3}};
        // The octahedron: its shortest diagonal and the four tets around it.
        const std::array<std::array<int, 2>, 3> diagonal = {{{mid[0][1], mid[2][3]}, {mid[0][2], mid[1][3]}, {mid[0][3], mid[1][2]}}};
        int best = 0;
        for (int d = 1; d < 3; ++d)
            if ((r.mesh.vertices[id[diagonal[d][0]]] - r.mesh.vertices[id[diagonal[d][1]]]).norm() <
                (r.mesh.vertices[id[diagonal[best][0]]] - r.mesh.vertices[id[diagonal[best][1]]]).norm())
                best = d;
        std::vector<int> ring;  // the other four midpoints, around the diagonal
        {
            std::vector<int> rest;
            for (int m = 4; m < 10; ++m)
                if (m != diagonal[best][0] && m != diagonal[best][1]) rest.push_back(m);
            ring.push_back(rest[0]);
            std::vector<char> used(10, 0);
            used[size_t(rest[0])] = 1;
            while (ring.size() < 4)
                for (int m : rest)
                    if (!used[size_t(m)] && (mask[size_t(m)] & mask[size_t(ring.back())])) {
                        ring.push_back(m), used[size_t(m)] = 1;
                        break;
                    }
        }
        for (int i = 0; i < 4; ++i) sub.push_back({diagonal[best][0], diagonal[best][1], ring[size_t(i)], ring[size_t(i + 1) % 4]});
        for (std::array<int, 4> s : sub) {
            const auto at = [&](int j) { return r.mesh.vertices[id[size_t(s[size_t(j)])]]; };
            if (tet_volume(at(0), at(1), at(2), at(3)) < 0) std::swap(s[2], s[3]);
            Tet tet;
            std::array<int32_t, 4> faces;
            for (int j = 0; j < 4; ++j) {
                tet[size_t(j)] = id[size_t(s[size_t(j)])];
                uint32_t on = 0;  // the corners any vertex of face j touches
                for (int v : kTetFaces[size_t(j)]) on |= mask[size_t(s[size_t(v)])];
                faces[size_t(j)] = -1;
                for (int i = 0; i < 4; ++i)
                    if (!(on & (1u << i))) faces[size_t(j)] = outer[size_t(i)];
            }
            r.mesh.tets.push_back(tet);
            r.parent.push_back(t);
            r.whole.push_back(0);
            r.boundary.push_back(faces);
        }
    }
    return r;
}

}  // namespace shatter
