#include <numeric>

#include "core/model.h"

namespace shatter {

size_t count_fragments(const Model& model, const std::vector<bool>& broken) {
    std::vector<uint32_t> parent(model.pieces.size());
    std::iota(parent.begin(), parent.end(), 0u);
    auto find = [&](uint32_t x) {
        while (parent[x] != x) x = parent[x] = parent[parent[x]];
        return x;
    };
    for (size_t c = 0; c < model.constraints.size(); ++c)
        if (c >= broken.size() || !broken[c]) parent[find(model.constraints[c].piece_a)] = find(model.constraints[c].piece_b);
    size_t groups = 0;
    for (uint32_t p = 0; p < parent.size(); ++p) groups += find(p) == p;
    return groups;
}

}  // namespace shatter
