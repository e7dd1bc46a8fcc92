#include "simulate/spring.h"

#include <algorithm>

namespace shatter {

double row_inverse_mass(double inv_mass_a, const Mat3& inv_inertia_a, const Vec3& r_a, double inv_mass_b,
                        const Mat3& inv_inertia_b, const Vec3& r_b, const Vec3& axis) {
    const Vec3 ra = r_a.cross(axis), rb = r_b.cross(axis);
    return inv_mass_a + inv_mass_b + ra.dot(inv_inertia_a * ra) + rb.dot(inv_inertia_b * rb);
}

double spring_erp(double k, double c, double h) { return h * k / (h * k + c); }

double spring_cfm(double k, double c, double h, double w) { return 1.0 / (w * h * (h * k + c)); }

double min_stiffness_for_cfm(double c, double h, double w, double max_cfm) {
    // 1 / (w h (h k + c)) = max_cfm  <=>  k = (1 / (max_cfm w h) - c) / h
    return std::max(0.0, (1.0 / (max_cfm * w * h) - c) / h);
}

}  // namespace shatter
