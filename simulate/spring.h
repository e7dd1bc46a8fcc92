// A compliant point constraint as a spring-damper, in physical units, and the ERP/CFM that make
// Bullet's sequential-impulse solver integrate exactly that spring (implicitly) at step h.
//
// Bullet's joint CFM is dimensionless, relative to the row's effective mass: the solver's row
// update is  dl = rhs - cfm * l - (J dv) / w,  so the regularisation a row sees is  w * cfm,
// w = 1/m_A + 1/m_B + (r_A x n)^T I_A^-1 (r_A x n) + (r_B x n)^T I_B^-1 (r_B x n)  being the
// row's inverse effective mass. A spring k (N/m) with damper c (N s/m), integrated implicitly
// over a step h, needs a regularisation of 1 / (h (h k + c)) and an error reduction
// h k / (h k + c) (docs/physics.md derives both). Hence, per row,
//
//     ERP = h k / (h k + c)            CFM_row = 1 / (w_row h (h k + c))
//
// (the paper's K = ERP / (h CFM) is ODE's convention, where CFM is not scaled by w).
// A btPoint2PointConstraint has three rows along the world axes with three different w; one
// CFM for all three would make the spring stiffer along some axes than others, so
// CompliantPointConstraint sets each row's CFM from its own w, every step.
//
// The solver converges only for CFM < 1 (docs/physics.md sections 1 and 8: stiffness ratio 0.997
// at CFM 0.5, 0.79 at 0.8, NaN above 1): a spring too soft for its bodies at that step is refused.
#pragma once

#include "core/geometry.h"

namespace shatter {

struct SpringRows {
    double erp = 0;
    Vec3 cfm = Vec3::Zero();  // per world axis
};

// Inverse effective mass of the point constraint along unit `axis`. A static or kinematic body
// has inv_mass 0 and inv_inertia 0.
double row_inverse_mass(double inv_mass_a, const Mat3& inv_inertia_a, const Vec3& r_a, double inv_mass_b,
                        const Mat3& inv_inertia_b, const Vec3& r_b, const Vec3& axis);

double spring_erp(double stiffness, double damping, double h);
double spring_cfm(double stiffness, double damping, double h, double row_inverse_mass);

// The stiffness below which a row with inverse effective mass w needs CFM > max_cfm at step h:
// solves 1 / (w h (h k + c)) = max_cfm for k.
double min_stiffness_for_cfm(double damping, double h, double row_inverse_mass, double max_cfm);

}  // namespace shatter
