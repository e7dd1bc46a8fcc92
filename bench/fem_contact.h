// Contact for the continuum reference (bench/fem_solid.h), kept simple: penalty forces on the
// solid's vertices against the ground plane, axis-aligned boxes (static, or moving by a function
// of time: the study's kinematic block) and spheres. A vertex inside an obstacle is pushed out
// along the nearest face's normal (a sphere: radially) with force k d + c (-v_n), c = 2 zeta
// sqrt(k m) for the vertex's lumped mass m, never pulling; friction is Coulomb's, regularized
// below a sliding speed v_eps: f_t = -mu f_n v_t / max(|v_t|, v_eps), with f_n held at its value
// at the step's first evaluation (a vertex entering contact within a step has no friction until
// the next). Only vertices are tested:
// an obstacle's edge or corner can enter the solid's faces unseen. The normal stiffness goes to
// the step's tangent (FemSolid's ExtraForce); friction and damping do not. The penalty method
// of e.g. Wriggers, "Computational Contact Mechanics", ch. 2, in its most basic form.
#pragma once

#include <functional>
#include <vector>

#include "bench/fem_solid.h"

namespace shatter::fem {

struct ContactBox {
    Vec3 half = Vec3::Ones();                       // half extents (unit: m)
    std::function<Vec3(double)> center;             // its centre at time t (unit: m)
    double friction = 0.5;
};

struct ContactSphere {
    Vec3 center = Vec3::Zero();
    double radius = 0.5;
    double friction = 0.5;
};

struct ContactSettings {
    double stiffness = 1e8;     // per vertex (unit: N/m)
    double damping_ratio = 0.5; // zeta
    double slip_speed = 1e-3;   // v_eps (unit: m/s)
    bool ground = true;
    double ground_height = 0;
    double ground_friction = 0.5;
    std::vector<ContactBox> boxes;
    std::vector<ContactSphere> spheres;
};

// The contact force as FemSolid's extra force. `time` is read at every evaluation: set it to the
// time the step evaluates its forces at (midpoint: t + h / 2; backward Euler: t + h).
ExtraForce contact_force(const ContactSettings& s, const Eigen::VectorXd& lumped_mass, const double* time);

}  // namespace shatter::fem
