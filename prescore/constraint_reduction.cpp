#include "prescore/constraint_reduction.h"

#include <algorithm>
#include <limits>

namespace shatter {

namespace {

// Thins one pair's constraints [begin, end) into `out`.
void reduce_pair(const Constraint* begin, const Constraint* end, uint32_t max_per_pair, std::vector<Constraint>& out) {
    const size_t n = size_t(end - begin);
    if (max_per_pair == 0 || n <= max_per_pair) {
        out.insert(out.end(), begin, end);
        return;
    }
    std::vector<size_t> kept;
    size_t first = 0;
    for (size_t i = 1; i < n; ++i)
        if (begin[i].area > begin[first].area) first = i;
    kept.push_back(first);
    std::vector<double> dist(n, std::numeric_limits<double>::infinity());
    while (kept.size() < max_per_pair) {
        const Vec3& last = begin[kept.back()].pivot;
        size_t best = 0;
        double best_d = -1;
        for (size_t i = 0; i < n; ++i) {
            dist[i] = std::min(dist[i], (begin[i].pivot - last).squaredNorm());
            if (dist[i] > best_d) best_d = dist[i], best = i;
        }
        kept.push_back(best);
    }
    std::sort(kept.begin(), kept.end());
    std::vector<Constraint> result;
    for (size_t k : kept) {
        result.push_back(begin[k]);
        result.back().area = 0;
    }
    for (size_t i = 0; i < n; ++i) {
        size_t nearest = 0;
        double nearest_d = std::numeric_limits<double>::infinity();
        for (size_t k = 0; k < kept.size(); ++k) {
            const double d = (begin[i].pivot - begin[kept[k]].pivot).squaredNorm();
            if (d < nearest_d) nearest_d = d, nearest = k;
        }
        result[nearest].area += begin[i].area;
    }
    out.insert(out.end(), result.begin(), result.end());
}

}  // namespace

std::vector<Constraint> reduce_constraints(const std::vector<Constraint>& c, uint32_t max_per_pair) {
    std::vector<Constraint> out;
    size_t start = 0;
    for (size_t i = 1; i <= c.size(); ++i) {
        if (i < c.size() && c[i].piece_a == c[start].piece_a && c[i].piece_b == c[start].piece_b) continue;
        reduce_pair(c.data() + start, c.data() + i, max_per_pair, out);
        start = i;
    }
    return out;
}

}  // namespace shatter
