#include "simulate/break_policy.h"

namespace shatter {

std::vector<size_t> BreakPolicy::select(const std::vector<Overload>& overloads, double t) {
    std::vector<size_t> out;
    if (overloads.empty()) return out;
    if (rate_limit_ <= 0) {
        for (const Overload& o : overloads) out.push_back(o.constraint);
    } else {
        // 1e-9 s of slack: "every 0.3 s" must not miss a step to rounding.
        if (t - last_break_ < rate_limit_ - 1e-9) return out;
        const Overload* worst = &overloads.front();
        for (const Overload& o : overloads)
            if (o.ratio > worst->ratio) worst = &o;
        out.push_back(worst->constraint);
    }
    last_break_ = t;
    return out;
}

}  // namespace shatter
