// Which overloaded constraints break in this step.
//
// A constraint is overloaded when the norm of its force (from the step's joint feedback, f =
// lambda / h) exceeds its strength: the norm, not Bullet's per-row impulse threshold, so the
// result depends neither on the load's direction nor on the step size.
// Without a rate limit every overloaded constraint breaks. With one (the paper's chain: one break
// per ~0.3 s), at most one breaks per `rate_limit` seconds: the most overloaded (largest
// |f| / strength; ties to the lower index); the others wait and are checked again next step.
#pragma once

#include <cstddef>
#include <limits>
#include <vector>

namespace shatter {

struct Overload {
    size_t constraint = 0;
    double ratio = 0;  // |f| / strength (> 1)
};

class BreakPolicy {
public:
    explicit BreakPolicy(double rate_limit) : rate_limit_(rate_limit) {}
    // The constraints to break at time t (ascending), given this step's overloads (ascending).
    std::vector<size_t> select(const std::vector<Overload>& overloads, double t);

private:
    double rate_limit_;
    double last_break_ = -std::numeric_limits<double>::infinity();
};

}  // namespace shatter
