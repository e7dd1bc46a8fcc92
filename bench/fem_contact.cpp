// Penalty contact with regularized Coulomb friction for the continuum reference
// (bench/fem_contact.h).
#include "bench/fem_contact.h"

#include <cmath>
#include <memory>

namespace shatter::fem {

namespace {

// What a vertex's contact with one obstacle was at the step's start.
struct Held {
    bool in = false;            // in contact at the step's start
    Vec3 n = Vec3::Zero();      // the outward normal there (a box: its face's)
    double fn = 0;              // the normal force there, k d - c v_n (>= 0): friction's
};

// The normal force on a vertex of mass m penetrating by d (may be < 0: outside) along n, with
// velocity v_rel relative to the obstacle, and its tangent. `damped`: the vertex was in contact at
// the step's start; then the force is max(0, k d - c v_n), else max(0, k d) (no damping in the
// step a contact begins). Either is continuous in the positions and velocities, so Newton's
// method does not meet a jump where a vertex crosses the surface.
void normal_force(const ContactSettings& s, double m, const Vec3& n, double d, const Vec3& v_rel, bool damped, Vec3& f,
                  Mat3& k_block, Mat3& c_block) {
    const double c = damped ? 2 * s.damping_ratio * std::sqrt(s.stiffness * m) : 0.0;
    const double fn = s.stiffness * d - c * v_rel.dot(n);
    if (fn <= 0) return;
    f += fn * n;
    const Mat3 nn = n * n.transpose();
    k_block += s.stiffness * nn;
    c_block += c * nn;
}

// Friction on a vertex in contact at the step's start: -mu fn v_t / max(|v_t|, v_eps) with the
// start's normal force and normal, whatever the vertex does within the step (so it has no jump
// either), and its damping for the tangent, exact: mu fn / |v_t| (P - t t^T) while slipping along
// t (P the projection onto the tangent plane; along the slip the force is constant),
// mu fn / v_eps P while sticking (|v_t| < v_eps).
void friction_force(const ContactSettings& s, const Held& h, const Vec3& v_rel, double mu, Vec3& f, Mat3& c_block) {
    if (h.fn <= 0 || mu <= 0) return;
    const Vec3 vt = v_rel - v_rel.dot(h.n) * h.n;
    const double slip = std::max(vt.norm(), s.slip_speed);
    f -= mu * h.fn * vt / slip;
    Mat3 across = Mat3::Identity() - h.n * h.n.transpose();
    if (vt.norm() > s.slip_speed) {
        const Vec3 t = vt / vt.norm();
        across -= t * t.transpose();
    }
    c_block += mu * h.fn / slip * across;
}

Vec3 box_velocity(const ContactBox& b, double t) {
    const double dt = 1e-6;
    return (b.center(t + dt) - b.center(t - dt)) / (2 * dt);
}

// Whether p is inside box b (centre c) and, if so, the nearest face's outward normal and depth.
bool inside_box(const ContactBox& b, const Vec3& c, const Vec3& p, Vec3& n, double& d) {
    const Vec3 q = p - c;
    const Vec3 depth = b.half - q.cwiseAbs();
    if ((depth.array() <= 0).any()) return false;
    int axis;
    d = depth.minCoeff(&axis);
    n = Vec3::Zero();
    n[axis] = q[axis] >= 0 ? 1 : -1;
    return true;
}

}  // namespace

void attach_contact(FemSolid& solid, const ContactSettings& s) {
    const Eigen::VectorXd& lumped_mass = solid.lumped_mass();
    const size_t slots = 1 + s.boxes.size() + s.spheres.size();
    // Per vertex and obstacle (slot 0 the ground, 1 + b box b, 1 + boxes + k sphere k): the
    // contact at the step's start.
    auto held = std::make_shared<std::vector<Held>>(solid.vertex_count() * slots);
    solid.set_step_begin([s, &lumped_mass, slots, held](double t, const Eigen::VectorXd& x, const Eigen::VectorXd& v) {
        const size_t n = size_t(x.size() / 3);
        held->assign(n * slots, Held{});
        std::vector<Vec3> centre(s.boxes.size()), velocity(s.boxes.size());
        for (size_t b = 0; b < s.boxes.size(); ++b) {
            centre[b] = s.boxes[b].center(t);
            velocity[b] = box_velocity(s.boxes[b], t);
        }
        for (size_t i = 0; i < n; ++i) {
            const Vec3 p = x.segment<3>(3 * i), vi = v.segment<3>(3 * i);
            const double c = 2 * s.damping_ratio * std::sqrt(s.stiffness * lumped_mass[3 * i]);
            Held* h = &(*held)[i * slots];
            const auto set = [&](Held& e, const Vec3& nrm, double d, const Vec3& v_rel) {
                e.in = true;
                e.n = nrm;
                e.fn = std::max(0.0, s.stiffness * d - c * v_rel.dot(nrm));
            };
            if (s.ground && p.y() < s.ground_height) set(h[0], Vec3(0, 1, 0), s.ground_height - p.y(), vi);
            for (size_t b = 0; b < s.boxes.size(); ++b) {
                Vec3 nrm;
                double d;
                if (inside_box(s.boxes[b], centre[b], p, nrm, d)) set(h[1 + b], nrm, d, vi - velocity[b]);
            }
            for (size_t k = 0; k < s.spheres.size(); ++k) {
                const Vec3 q = p - s.spheres[k].center;
                const double r = q.norm();
                if (r < s.spheres[k].radius && r > 0) set(h[1 + s.boxes.size() + k], q / r, s.spheres[k].radius - r, vi);
            }
        }
    });
    const FemSolid* solid_ptr = &solid;
    solid.set_extra_force([s, &lumped_mass, solid_ptr, slots, held](const Eigen::VectorXd& x, const Eigen::VectorXd& v,
                                                               Eigen::VectorXd& f, Eigen::VectorXd& block_k,
                                                               Eigen::VectorXd& block_c) {
        const double t = solid_ptr->eval_time();
        std::vector<Vec3> centre(s.boxes.size()), velocity(s.boxes.size());
        for (size_t b = 0; b < s.boxes.size(); ++b) {
            centre[b] = s.boxes[b].center(t);
            velocity[b] = box_velocity(s.boxes[b], t);
        }
        const size_t n = size_t(x.size() / 3);
        for (size_t i = 0; i < n; ++i) {
            const Vec3 p = x.segment<3>(3 * i), vi = v.segment<3>(3 * i);
            const double m = lumped_mass[3 * i];
            const Held* h = &(*held)[i * slots];
            Vec3 fi = Vec3::Zero();
            Mat3 ki = Mat3::Zero(), ci = Mat3::Zero();
            // The ground.
            if (s.ground) {
                const Vec3 nrm(0, 1, 0);
                normal_force(s, m, nrm, s.ground_height - p.y(), vi, h[0].in, fi, ki, ci);
                friction_force(s, h[0], vi, s.ground_friction, fi, ci);
            }
            // Boxes: a vertex in contact at the step's start keeps its face (the depth below it may
            // turn negative: outside); one that was not is pushed out of the nearest face.
            for (size_t b = 0; b < s.boxes.size(); ++b) {
                const Held& e = h[1 + b];
                const Vec3 v_rel = vi - velocity[b];
                if (e.in) {
                    int axis;
                    e.n.cwiseAbs().maxCoeff(&axis);
                    const double d = s.boxes[b].half[axis] - e.n[axis] * (p[axis] - centre[b][axis]);
                    normal_force(s, m, e.n, d, v_rel, true, fi, ki, ci);
                    friction_force(s, e, v_rel, s.boxes[b].friction, fi, ci);
                } else {
                    Vec3 nrm;
                    double d;
                    if (inside_box(s.boxes[b], centre[b], p, nrm, d)) normal_force(s, m, nrm, d, v_rel, false, fi, ki, ci);
                }
            }
            for (size_t k = 0; k < s.spheres.size(); ++k) {
                const Held& e = h[1 + s.boxes.size() + k];
                const Vec3 q = p - s.spheres[k].center;
                const double r = q.norm();
                if (r > 0) normal_force(s, m, q / r, s.spheres[k].radius - r, vi, e.in, fi, ki, ci);
                friction_force(s, e, vi, s.spheres[k].friction, fi, ci);
            }
            f.segment<3>(3 * i) += fi;
            for (int a = 0; a < 3; ++a)
                for (int b = 0; b < 3; ++b) {
                    block_k[9 * i + 3 * a + b] += ki(a, b);
                    block_c[9 * i + 3 * a + b] += ci(a, b);
                }
        }
    });
}

}  // namespace shatter::fem
