// Round-robin flood fill (see partition.h). Each piece keeps a FIFO of its claimed tets and a
// cursor into the faces of the tet at the front; a turn advances the cursor to the next
// unclaimed neighbour and claims it. Work is O(tets + pieces * rounds).
#include "prescore/partition.h"

#include <algorithm>
#include <cassert>
#include <limits>
#include <string>

#include "core/error.h"
#include "core/rng.h"

namespace shatter {

namespace {

constexpr uint32_t kUnclaimed = UINT32_MAX;

void validate(size_t tets, uint32_t pieces, int32_t components) {
    const std::string where = "partition";
    if (pieces == 0) {
        throw_input_error(where, "pieces is 0", "ask for at least 1 piece");
    }
    if (pieces > tets) {
        throw_input_error(where,
                          "pieces is " + std::to_string(pieces) + " but the tet mesh has only " +
                              std::to_string(tets) + " tets",
                          "ask for at most " + std::to_string(tets) + " pieces, or use a finer tet mesh");
    }
    if (pieces < uint32_t(components)) {
        throw_input_error(where,
                          "pieces is " + std::to_string(pieces) + " but the tet mesh has " +
                              std::to_string(components) + " separate components, each needs its own piece",
                          "ask for at least " + std::to_string(components) + " pieces");
    }
}

// Seeds per component: one each, the rest by highest averages on the tet counts.
std::vector<uint32_t> seeds_per_component(const std::vector<uint32_t>& sizes, uint32_t pieces) {
    std::vector<uint32_t> alloc(sizes.size(), 1);
    for (uint32_t given = uint32_t(sizes.size()); given < pieces; ++given) {
        size_t best = SIZE_MAX;
        for (size_t c = 0; c < sizes.size(); ++c) {
            if (alloc[c] >= sizes[c]) continue;
            // sizes[c] / (alloc[c] + 1) > sizes[best] / (alloc[best] + 1), exactly.
            if (best == SIZE_MAX ||
                uint64_t(sizes[c]) * (alloc[best] + 1) > uint64_t(sizes[best]) * (alloc[c] + 1)) {
                best = c;
            }
        }
        assert(best != SIZE_MAX);
        ++alloc[best];
    }
    return alloc;
}

// `count` distinct tets of `members`, each draw in proportion to `weight` among those left.
void draw_weighted(const std::vector<uint32_t>& members, uint32_t count, const std::vector<double>& weight, Rng& rng,
                   std::vector<uint32_t>& seeds) {
    std::vector<double> w;
    w.reserve(members.size());
    for (uint32_t t : members) w.push_back(weight[t]);
    for (uint32_t k = 0; k < count; ++k) {
        double total = 0;
        for (double x : w) total += x;
        const double u = rng.uniform() * total;
        size_t pick = SIZE_MAX;
        double sum = 0;
        for (size_t i = 0; i < w.size(); ++i) {
            if (w[i] <= 0) continue;
            pick = i;  // the last one left, should round-off carry u past the end
            sum += w[i];
            if (u < sum) break;
        }
        assert(pick != SIZE_MAX);
        seeds.push_back(members[pick]);
        w[pick] = 0;
    }
}

// `weight` empty: uniform (partial Fisher-Yates); else without replacement in proportion to it.
std::vector<uint32_t> draw_seeds(const std::vector<int32_t>& component, int32_t count, uint32_t pieces,
                                 uint64_t seed, const std::vector<double>& weight) {
    std::vector<std::vector<uint32_t>> members(static_cast<size_t>(count));
    for (size_t t = 0; t < component.size(); ++t) members[size_t(component[t])].push_back(uint32_t(t));
    std::vector<uint32_t> sizes;
    for (const auto& m : members) sizes.push_back(uint32_t(m.size()));
    const std::vector<uint32_t> alloc = seeds_per_component(sizes, pieces);

    Rng rng(seed);
    std::vector<uint32_t> seeds;
    for (size_t c = 0; c < members.size(); ++c) {
        std::vector<uint32_t>& m = members[c];
        if (!weight.empty()) {
            draw_weighted(m, alloc[c], weight, rng, seeds);
            continue;
        }
        for (uint32_t k = 0; k < alloc[c]; ++k) {  // partial Fisher-Yates: k distinct tets
            const uint32_t j = k + rng.below(uint32_t(m.size()) - k);
            std::swap(m[k], m[j]);
            seeds.push_back(m[k]);
        }
    }
    std::sort(seeds.begin(), seeds.end());
    return seeds;
}

struct Grower {
    std::vector<uint32_t> queue;  // claimed tets in claim order
    size_t head = 0;              // the tet whose neighbours are being claimed
    int face = 0;                 // next face of queue[head] to look across
};

// One turn of piece p: claim the next unclaimed neighbour in BFS order. False when the
// piece's frontier is empty.
bool grow_one(Grower& g, uint32_t p, const TetTopology& topology, std::vector<uint32_t>& tet_piece) {
    while (g.head < g.queue.size()) {
        const auto& nb = topology.neighbour[g.queue[g.head]];
        while (g.face < 4) {
            const int32_t u = nb[g.face++];
            if (u >= 0 && tet_piece[u] == kUnclaimed) {
                tet_piece[u] = p;
                g.queue.push_back(uint32_t(u));
                return true;
            }
        }
        ++g.head;
        g.face = 0;
    }
    return false;
}

// The tet piece p would claim on its next turn (grow_one's), without claiming it; -1 when its
// frontier is empty.
int32_t peek_next(Grower& g, const TetTopology& topology, const std::vector<uint32_t>& tet_piece) {
    while (g.head < g.queue.size()) {
        const auto& nb = topology.neighbour[g.queue[g.head]];
        while (g.face < 4) {
            const int32_t u = nb[g.face];
            if (u >= 0 && tet_piece[u] == kUnclaimed) return u;
            ++g.face;
        }
        ++g.head;
        g.face = 0;
    }
    return -1;
}

void grow_round_robin(std::vector<Grower>& growers, std::vector<uint32_t>& active, const TetTopology& topology,
                      std::vector<uint32_t>& tet_piece) {
    while (!active.empty()) {
        size_t kept = 0;
        for (uint32_t p : active) {
            if (grow_one(growers[p], p, topology, tet_piece)) active[kept++] = p;
        }
        active.resize(kept);
    }
}

}  // namespace

Partition partition_from_seeds(const TetMesh& mesh, const TetTopology& topology, std::vector<uint32_t> seeds) {
    assert(!seeds.empty());
    std::sort(seeds.begin(), seeds.end());
    assert(std::adjacent_find(seeds.begin(), seeds.end()) == seeds.end());
    const uint32_t pieces = uint32_t(seeds.size());
    Partition result;
    result.seeds = seeds;
    result.tet_piece.assign(mesh.tets.size(), kUnclaimed);
    std::vector<Grower> growers(pieces);
    std::vector<uint32_t> active;
    for (uint32_t p = 0; p < pieces; ++p) {
        result.tet_piece[seeds[p]] = p;
        growers[p].queue.push_back(seeds[p]);
        active.push_back(p);
    }
    grow_round_robin(growers, active, topology, result.tet_piece);
    int32_t count = 0;
    const std::vector<int32_t> component = tet_components(topology, {}, &count);
    std::vector<uint32_t> component_piece(size_t(count), kUnclaimed);
    for (uint32_t t = 0; t < mesh.tets.size(); ++t) {
        if (result.tet_piece[t] != kUnclaimed || component_piece[size_t(component[t])] != kUnclaimed) continue;
        const Vec3 at = tet_centroid(mesh, t);
        double best = std::numeric_limits<double>::infinity();
        for (uint32_t p = 0; p < pieces; ++p)
            if (const double d = (tet_centroid(mesh, seeds[p]) - at).squaredNorm(); d < best)
                best = d, component_piece[size_t(component[t])] = p;
        ++result.joined_components;
    }
    for (uint32_t t = 0; t < mesh.tets.size(); ++t)
        if (result.tet_piece[t] == kUnclaimed) result.tet_piece[t] = component_piece[size_t(component[t])];
    result.piece_tets.assign(pieces, 0);
    for (uint32_t p : result.tet_piece) ++result.piece_tets[p];
    return result;
}

Partition partition(const TetMesh& mesh, const TetTopology& topology, uint32_t pieces, uint64_t seed,
                    const std::vector<double>& density) {
    assert(topology.neighbour.size() == mesh.tets.size());
    assert(density.empty() || density.size() == mesh.tets.size());
    int32_t components = 0;
    const std::vector<int32_t> component = tet_components(topology, {}, &components);
    validate(mesh.tets.size(), pieces, components);

    std::vector<double> weight;  // density x volume
    for (size_t t = 0; t < density.size(); ++t) {
        const Tet& k = mesh.tets[t];
        weight.push_back(density[t] * tet_volume(mesh.vertices[k[0]], mesh.vertices[k[1]], mesh.vertices[k[2]],
                                                 mesh.vertices[k[3]]));
    }
    Partition result;
    result.seeds = draw_seeds(component, components, pieces, seed, weight);
    result.tet_piece.assign(mesh.tets.size(), kUnclaimed);
    std::vector<Grower> growers(pieces);
    std::vector<uint32_t> active;
    for (uint32_t p = 0; p < pieces; ++p) {
        result.tet_piece[result.seeds[p]] = p;
        growers[p].queue.push_back(result.seeds[p]);
        active.push_back(p);
    }
    if (density.empty()) {
        grow_round_robin(growers, active, topology, result.tet_piece);
    } else {
        // Each turn gives a piece one credit; a tet costs its density over the lowest.
        double lowest = std::numeric_limits<double>::infinity();
        for (double w : density) lowest = std::min(lowest, w);
        std::vector<double> credit(pieces, 0.0);
        while (!active.empty()) {
            size_t kept = 0;
            for (uint32_t p : active) {
                const int32_t next = peek_next(growers[p], topology, result.tet_piece);
                if (next < 0) continue;  // enclosed
                credit[p] += 1;
                const double cost = density[size_t(next)] / lowest;
                if (credit[p] >= cost) {
                    credit[p] -= cost;
                    result.tet_piece[size_t(next)] = p;
                    growers[p].queue.push_back(uint32_t(next));
                }
                active[kept++] = p;
            }
            active.resize(kept);
        }
    }
    result.piece_tets.assign(pieces, 0);
    for (uint32_t p : result.tet_piece) {
        assert(p != kUnclaimed);
        ++result.piece_tets[p];
    }
    return result;
}

}  // namespace shatter
