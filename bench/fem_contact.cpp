// Penalty contact with regularized Coulomb friction for the continuum reference
// (bench/fem_contact.h).
#include "bench/fem_contact.h"

#include <cmath>
#include <memory>

namespace shatter::fem {

namespace {

// The force on a vertex of mass m at x with velocity v (relative to the obstacle) penetrating by
// d along the outward normal n.
// fn_friction: the normal force friction scales with, taken at the step's first evaluation and
// held through the step (its dependence on the positions is not in the tangent: with it, Newton's
// method diverged on a sliding block); negative: use this evaluation's.
void push(const ContactSettings& s, double m, const Vec3& n, double d, const Vec3& v_rel, double mu, Vec3& f,
          Vec3& k_diag, Vec3& c_diag, double& fn_friction) {
    const double c = 2 * s.damping_ratio * std::sqrt(s.stiffness * m);
    const double vn = v_rel.dot(n);
    const double fn_now = std::max(0.0, s.stiffness * d - c * vn);
    if (fn_friction < 0) fn_friction = fn_now;
    const double fn = fn_friction;
    const Vec3 vt = v_rel - vn * n;
    const double slip = std::max(vt.norm(), s.slip_speed);
    f += fn_now * n - mu * fn * vt / slip;
    const Vec3 nn = n.cwiseProduct(n);
    k_diag += s.stiffness * nn;
    // d(friction)/dv: mu fn / |v_t| across the slip only (along it the force is constant), all
    // tangential directions while sticking (|v_t| < v_eps).
    Vec3 across = Vec3::Ones() - nn;
    if (vt.norm() > s.slip_speed) {
        const Vec3 t = vt / vt.norm();
        across -= t.cwiseProduct(t);
    }
    c_diag += c * nn + mu * fn / slip * across.cwiseMax(0.0);
}

}  // namespace

ExtraForce contact_force(const ContactSettings& s, const Eigen::VectorXd& lumped_mass, const double* time) {
    // Per vertex and obstacle (ground, boxes, spheres): the friction's normal force this step.
    auto held = std::make_shared<std::vector<double>>();
    auto held_time = std::make_shared<double>(-1e300);
    return [s, &lumped_mass, time, held, held_time](const Eigen::VectorXd& x, const Eigen::VectorXd& v,
                                                    Eigen::VectorXd& f, Eigen::VectorXd& diag_k,
                                                    Eigen::VectorXd& diag_c) {
        const double t = *time, dt = 1e-6;
        const size_t slots = 1 + s.boxes.size() + s.spheres.size();
        const bool first = t != *held_time;
        if (first) {  // a new step: take the normal forces afresh
            held->assign(size_t(x.size() / 3) * slots, -1.0);
            *held_time = t;
        }
        std::vector<Vec3> centre(s.boxes.size()), velocity(s.boxes.size());
        for (size_t b = 0; b < s.boxes.size(); ++b) {
            centre[b] = s.boxes[b].center(t);
            velocity[b] = (s.boxes[b].center(t + dt) - s.boxes[b].center(t - dt)) / (2 * dt);
        }
        const size_t n = size_t(x.size() / 3);
        for (size_t i = 0; i < n; ++i) {
            const Vec3 p = x.segment<3>(3 * i), vi = v.segment<3>(3 * i);
            const double m = lumped_mass[3 * i];
            Vec3 fi = Vec3::Zero(), ki = Vec3::Zero(), ci = Vec3::Zero();
            double* fh = &(*held)[i * slots];
            if (s.ground && p.y() < s.ground_height)
                push(s, m, Vec3(0, 1, 0), s.ground_height - p.y(), vi, s.ground_friction, fi, ki, ci, fh[0]);
            for (size_t b = 0; b < s.boxes.size(); ++b) {
                const Vec3 q = p - centre[b];
                const Vec3 depth = s.boxes[b].half - q.cwiseAbs();
                if ((depth.array() <= 0).any()) continue;
                int axis;
                const double d = depth.minCoeff(&axis);
                Vec3 nrm = Vec3::Zero();
                nrm[axis] = q[axis] >= 0 ? 1 : -1;
                push(s, m, nrm, d, vi - velocity[b], s.boxes[b].friction, fi, ki, ci, fh[1 + b]);
            }
            for (size_t k = 0; k < s.spheres.size(); ++k) {
                const ContactSphere& sp = s.spheres[k];
                const Vec3 q = p - sp.center;
                const double r = q.norm();
                if (r >= sp.radius || r == 0) continue;
                push(s, m, q / r, sp.radius - r, vi, sp.friction, fi, ki, ci, fh[1 + s.boxes.size() + k]);
            }
            if (first)  // not in contact at the step's first evaluation: no friction this step
                for (size_t k = 0; k < slots; ++k) fh[k] = std::max(fh[k], 0.0);
            f.segment<3>(3 * i) += fi;
            diag_k.segment<3>(3 * i) += ki;
            diag_c.segment<3>(3 * i) += ci;
        }
    };
}

}  // namespace shatter::fem
