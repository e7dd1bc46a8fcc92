// Face adjacency by sorting: every tet face becomes a record (sorted vertex triple, tet, face);
// after sorting, the records of a shared face are adjacent. Components by breadth-first search
// started from tets in ascending index order, so component numbers follow the lowest tet index.
#include "prescore/tet_topology.h"

#include <algorithm>
#include <cassert>
#include <string>

#include "core/error.h"

namespace shatter {

namespace {

struct FaceRecord {
    std::array<uint32_t, 3> key;  // sorted vertex indices
    uint32_t tet;
    uint32_t face;

    bool operator<(const FaceRecord& o) const {
        if (key != o.key) return key < o.key;
        if (tet != o.tet) return tet < o.tet;
        return face < o.face;
    }
};

std::vector<FaceRecord> face_records(const TetMesh& mesh) {
    std::vector<FaceRecord> records;
    records.reserve(mesh.tets.size() * 4);
    for (size_t t = 0; t < mesh.tets.size(); ++t) {
        const Tet& tet = mesh.tets[t];
        for (uint32_t i = 0; i < 4; ++i) {
            std::array<uint32_t, 3> key = {tet[kTetFaces[i][0]], tet[kTetFaces[i][1]], tet[kTetFaces[i][2]]};
            std::sort(key.begin(), key.end());
            records.push_back({key, uint32_t(t), i});
        }
    }
    std::sort(records.begin(), records.end());
    return records;
}

}  // namespace

TetTopology build_topology(const TetMesh& mesh) {
    TetTopology topology;
    topology.neighbour.assign(mesh.tets.size(), {-1, -1, -1, -1});
    const std::vector<FaceRecord> records = face_records(mesh);
    size_t i = 0;
    while (i < records.size()) {
        size_t j = i + 1;
        while (j < records.size() && records[j].key == records[i].key) ++j;
        if (j - i > 2) {
            const auto& k = records[i].key;
            assert(false && "a tet face is shared by more than two tets");
            throw Error(ExitCode::Internal,
                        "tet mesh is not manifold: face (" + std::to_string(k[0]) + ", " + std::to_string(k[1]) +
                            ", " + std::to_string(k[2]) + ") is shared by " + std::to_string(j - i) + " tets");
        }
        if (j - i == 2) {
            const FaceRecord& a = records[i];
            const FaceRecord& b = records[i + 1];
            topology.neighbour[a.tet][a.face] = int32_t(b.tet);
            topology.neighbour[b.tet][b.face] = int32_t(a.tet);
        }
        i = j;
    }
    return topology;
}

std::vector<int32_t> tet_components(const TetTopology& topology, const std::vector<char>& mask, int32_t* count) {
    const size_t n = topology.neighbour.size();
    assert(mask.empty() || mask.size() == n);
    auto in_mask = [&](size_t t) { return mask.empty() || mask[t] != 0; };
    std::vector<int32_t> component(n, -1);
    std::vector<uint32_t> queue;
    queue.reserve(n);
    int32_t next = 0;
    for (size_t start = 0; start < n; ++start) {
        if (!in_mask(start) || component[start] >= 0) continue;
        queue.clear();
        queue.push_back(uint32_t(start));
        component[start] = next;
        for (size_t head = 0; head < queue.size(); ++head) {
            for (int32_t u : topology.neighbour[queue[head]]) {
                if (u < 0 || component[u] >= 0 || !in_mask(size_t(u))) continue;
                component[u] = next;
                queue.push_back(uint32_t(u));
            }
        }
        ++next;
    }
    if (count) *count = next;
    return component;
}

}  // namespace shatter
