// Contact for the continuum reference (bench/fem_solid.h), kept simple: penalty forces on the
// solid's vertices against the ground plane, axis-aligned boxes (static, or moving by a function
// of time: the study's kinematic block) and spheres. A vertex inside an obstacle is pushed out
// along the nearest face's normal (a sphere: radially) with force k d + c (-v_n), c = 2 zeta
// sqrt(k m) for the vertex's lumped mass m, never pulling; friction is Coulomb's, regularized
// below a sliding speed v_eps: f_t = -mu f_n v_t / max(|v_t|, v_eps).
//
// What a step holds fixed, so that the force has no jump for Newton's method to cycle on: which
// vertices touch which obstacle (and a box's face) is decided at the step's start; friction takes
// its normal force f_n = k d - c v_n and its normal from there ("lagged" friction, as e.g. Li et
// al.'s IPC, SIGGRAPH 2020, lags it) and applies whatever the vertex does within the step; the
// damping acts only on the vertices in contact at the start, so a vertex that enters within the
// step meets k d alone (continuous at d = 0) and one that leaves sees max(0, k d - c v_n) fall to
// zero continuously. A vertex that enters within a step has no friction until the next. Only
// vertices are tested: an obstacle's edge or corner can enter the solid's faces unseen. The
// stiffness and damping of every part (friction's exact: mu f_n / |v_t| across the slip, mu f_n /
// v_eps in every tangential direction while sticking) go to the step's tangent as per-vertex 3 x 3
// blocks. The penalty method of e.g. Wriggers, "Computational Contact Mechanics", ch. 2, in its
// most basic form.
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

// Sets the contact force as `solid`'s extra force and its step-begin hook (the contacts at the
// step's start). Moving obstacles are placed at the solid's evaluation time. The forces keep a
// reference to the solid.
void attach_contact(FemSolid& solid, const ContactSettings& s);

}  // namespace shatter::fem
