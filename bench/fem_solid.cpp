// Corotational linear-elastic tets, lumped mass, implicit midpoint / backward Euler
// (bench/fem_solid.h gives the method and its sources).
#include "bench/fem_solid.h"

#include <Eigen/LU>
#include <Eigen/SVD>
#include <algorithm>
#include <cmath>

#include "core/error.h"

namespace shatter::fem {

namespace {

using Mat12 = Eigen::Matrix<double, 12, 12>;
using Vec12 = Eigen::Matrix<double, 12, 1>;

// The rotation of F's polar decomposition F = R S, from F = U Sigma V^T: R = U V^T, with the
// smallest singular direction flipped when that would be a reflection (an inverted tet).
Eigen::Matrix3d polar_rotation(const Eigen::Matrix3d& F) {
    Eigen::JacobiSVD<Eigen::Matrix3d> svd(F, Eigen::ComputeFullU | Eigen::ComputeFullV);
    Eigen::Matrix3d U = svd.matrixU();
    const Eigen::Matrix3d V = svd.matrixV();
    if ((U * V.transpose()).determinant() < 0) U.col(2) *= -1;
    return U * V.transpose();
}

// The same rotation found by iteration from a nearby one (Mueller, Bender, Chentanez & Macklin,
// "A Robust Method to Extract the Rotational Part of Deformations", MIG 2016): q turns towards
// the rotation that maximizes tr(R^T F), which is F's polar rotation when det F > 0. Started from
// the tet's rotation at the previous evaluation it takes a few iterations, against a full SVD.
void extract_rotation(const Eigen::Matrix3d& F, Eigen::Quaterniond& q) {
    for (int it = 0; it < 50; ++it) {
        const Eigen::Matrix3d R = q.toRotationMatrix();
        const Eigen::Vector3d omega =
            (R.col(0).cross(F.col(0)) + R.col(1).cross(F.col(1)) + R.col(2).cross(F.col(2))) /
            (std::abs(R.col(0).dot(F.col(0)) + R.col(1).dot(F.col(1)) + R.col(2).dot(F.col(2))) + 1e-300);
        const double w = omega.norm();
        if (w < 1e-14) break;
        q = Eigen::Quaterniond(Eigen::AngleAxisd(w, omega / w)) * q;
        q.normalize();
    }
}

Vec12 gather(const Eigen::VectorXd& x, const Tet& t) {
    Vec12 e;
    for (int a = 0; a < 4; ++a) e.segment<3>(3 * a) = x.segment<3>(3 * t[a]);
    return e;
}

}  // namespace

FemSolid::FemSolid(const TetMesh& mesh, const FemSettings& settings) : s_(settings), tets_(mesh.tets) {
    const size_t n = mesh.vertices.size();
    rest_.resize(3 * n);
    for (size_t v = 0; v < n; ++v) rest_.segment<3>(3 * v) = mesh.vertices[v];
    x_ = rest_;
    v_ = Eigen::VectorXd::Zero(3 * n);
    mass_ = Eigen::VectorXd::Zero(3 * n);
    loads_ = Eigen::VectorXd::Zero(3 * n);
    const double E = s_.material.young, nu = s_.material.poisson;
    const double mu = E / (2 * (1 + nu)), lambda = E * nu / ((1 + nu) * (1 - 2 * nu));
    volume_.resize(tets_.size());
    dm_inv_.resize(tets_.size());
    ke_.resize(tets_.size());
    rot_.assign(tets_.size(), Eigen::Matrix3d::Identity());
    quat_.assign(tets_.size(), Eigen::Quaterniond::Identity());
    for (size_t t = 0; t < tets_.size(); ++t) {
        const Tet& T = tets_[t];
        Eigen::Matrix3d Dm;
        for (int c = 0; c < 3; ++c) Dm.col(c) = mesh.vertices[T[c + 1]] - mesh.vertices[T[0]];
        const double V = Dm.determinant() / 6;
        if (!(V > 0)) throw Error(ExitCode::Internal, "fem: a tet has no positive volume");
        volume_[t] = V;
        dm_inv_[t] = Dm.inverse();
        // Shape function gradients: g_a = Dm^-T e_(a-1) for a = 1..3, g_0 = -(g_1 + g_2 + g_3).
        Eigen::Matrix<double, 3, 4> g;
        for (int a = 1; a < 4; ++a) g.col(a) = dm_inv_[t].row(a - 1).transpose();
        g.col(0) = -(g.col(1) + g.col(2) + g.col(3));
        // K_ab = V (lambda g_a g_b^T + mu g_b g_a^T + mu (g_a . g_b) I): the second derivative of
        // V (mu |sym grad u|^2 + lambda/2 (div u)^2).
        Mat12& K = ke_[t];
        for (int a = 0; a < 4; ++a)
            for (int b = 0; b < 4; ++b)
                K.block<3, 3>(3 * a, 3 * b) =
                    V * (lambda * g.col(a) * g.col(b).transpose() + mu * g.col(b) * g.col(a).transpose() +
                         mu * g.col(a).dot(g.col(b)) * Eigen::Matrix3d::Identity());
        for (int a = 0; a < 4; ++a) mass_.segment<3>(3 * T[a]).array() += s_.material.density * V / 4;
    }
    constrained_.assign(n, false);
    drive_velocity_.assign(n, Vec3::Zero());
    group_.resize(n);
    for (size_t v = 0; v < n; ++v) group_[v] = uint32_t(v);
    group_force_ = Eigen::VectorXd::Zero(3 * n);
}

void FemSolid::set_vertex_groups(const std::vector<uint32_t>& group) {
    group_ = group;
    pattern_ready_ = false;
}

FemSolid::~FemSolid() = default;

void FemSolid::clamp(const std::vector<uint32_t>& vertices) {
    for (uint32_t v : vertices) {
        constrained_[v] = true;
        drive_velocity_[v] = Vec3::Zero();
        v_.segment<3>(3 * v).setZero();
    }
    pattern_ready_ = false;
}

void FemSolid::drive(const std::vector<uint32_t>& vertices, const Vec3& velocity) {
    for (uint32_t v : vertices) {
        constrained_[v] = true;
        drive_velocity_[v] = velocity;
        v_.segment<3>(3 * v) = velocity;
    }
    pattern_ready_ = false;
}

void FemSolid::set_load(uint32_t vertex, const Vec3& force) { loads_.segment<3>(3 * vertex) = force; }

void FemSolid::prepare_pattern() {
    const size_t n = vertex_count();
    free_.assign(3 * n, -1);
    n_free_ = 0;
    // A group with a clamped or driven member moves with it, every member.
    std::vector<char> held(n, 0);
    std::vector<Vec3> held_velocity(n, Vec3::Zero());
    for (size_t v = 0; v < n; ++v)
        if (constrained_[v]) {
            held[group_[v]] = 1;
            held_velocity[group_[v]] = drive_velocity_[v];
        }
    for (size_t v = 0; v < n; ++v)
        if (group_[v] == v && !held[v])
            for (int c = 0; c < 3; ++c) free_[3 * v + c] = int(n_free_++);
    for (size_t v = 0; v < n; ++v) {
        if (group_[v] != v)
            for (int c = 0; c < 3; ++c) free_[3 * v + c] = free_[3 * group_[v] + c];
        if (held[group_[v]]) v_.segment<3>(3 * v) = held_velocity[group_[v]];
    }
    // The lower triangle of the tangent: every tet's vertex pairs plus the diagonal.
    std::vector<Eigen::Triplet<double>> trip;
    trip.reserve(tets_.size() * 78 + n_free_);
    for (size_t i = 0; i < n_free_; ++i) trip.emplace_back(int(i), int(i), 0.0);
    for (const Tet& T : tets_)
        for (int a = 0; a < 4; ++a)
            for (int b = 0; b < 4; ++b)
                for (int i = 0; i < 3; ++i)
                    for (int j = 0; j < 3; ++j) {
                        const int r = free_[3 * T[a] + i], c = free_[3 * T[b] + j];
                        if (r >= 0 && c >= 0 && r >= c) trip.emplace_back(r, c, 0.0);
                    }
    tangent_.resize(int(n_free_), int(n_free_));
    tangent_.setFromTriplets(trip.begin(), trip.end());
    tangent_.makeCompressed();
    const auto find = [&](int r, int c) {
        const int* inner = tangent_.innerIndexPtr();
        const int* lo = inner + tangent_.outerIndexPtr()[c];
        const int* hi = inner + tangent_.outerIndexPtr()[c + 1];
        return int(std::lower_bound(lo, hi, r) - inner);
    };
    slot_.assign(tets_.size() * 144, -1);
    for (size_t t = 0; t < tets_.size(); ++t)
        for (int a = 0; a < 4; ++a)
            for (int b = 0; b < 4; ++b)
                for (int i = 0; i < 3; ++i)
                    for (int j = 0; j < 3; ++j) {
                        const int r = free_[3 * tets_[t][a] + i], c = free_[3 * tets_[t][b] + j];
                        if (r >= 0 && c >= 0 && r >= c) slot_[t * 144 + (3 * a + i) * 12 + 3 * b + j] = find(r, c);
                    }
    diag_slot_.resize(n_free_);
    for (size_t i = 0; i < n_free_; ++i) diag_slot_[i] = find(int(i), int(i));
    vertex_slot_.assign(9 * n, -1);
    for (size_t v = 0; v < n; ++v)
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) {
                const int r = free_[3 * v + i], c = free_[3 * v + j];
                if (r >= 0 && c >= 0 && r >= c) vertex_slot_[9 * v + 3 * i + j] = find(r, c);
            }
    ldlt_ = std::make_unique<Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>>>();
    if (s_.solver == FemLinearSolver::LDLT) ldlt_->analyzePattern(tangent_);
    cg_ = std::make_unique<Eigen::ConjugateGradient<Eigen::SparseMatrix<double>, Eigen::Lower>>();
    cg_->setTolerance(s_.cg_tol);
    pattern_ready_ = true;
    constant_factored_ = false;
}

void FemSolid::update_rotations(const Eigen::VectorXd& x) {
    if (!s_.corotational) return;
    for (size_t t = 0; t < tets_.size(); ++t) {
        const Tet& T = tets_[t];
        Eigen::Matrix3d Ds;
        for (int c = 0; c < 3; ++c) Ds.col(c) = x.segment<3>(3 * T[c + 1]) - x.segment<3>(3 * T[0]);
        const Eigen::Matrix3d F = Ds * dm_inv_[t];
        if (F.determinant() > 0) {
            extract_rotation(F, quat_[t]);
            rot_[t] = quat_[t].toRotationMatrix();
        } else {  // inverted: the SVD's rotation, reflection removed
            rot_[t] = polar_rotation(F);
            quat_[t] = Eigen::Quaterniond(rot_[t]);
        }
    }
}

void FemSolid::elastic_forces(const Eigen::VectorXd& x, Eigen::VectorXd& f) {
    update_rotations(x);
    for (size_t t = 0; t < tets_.size(); ++t) {
        const Tet& T = tets_[t];
        const Eigen::Matrix3d& R = rot_[t];
        Vec12 e = gather(x, T);
        for (int a = 0; a < 4; ++a) e.segment<3>(3 * a) = R.transpose() * e.segment<3>(3 * a) - rest_.segment<3>(3 * T[a]);
        const Vec12 fl = -(ke_[t] * e);
        for (int a = 0; a < 4; ++a) f.segment<3>(3 * T[a]) += R * fl.segment<3>(3 * a);
    }
}

void FemSolid::total_forces(const Eigen::VectorXd& x, const Eigen::VectorXd& v, Eigen::VectorXd& f,
                            Eigen::VectorXd& block_k, Eigen::VectorXd& block_c) {
    f = loads_;
    for (size_t i = 0; i < vertex_count(); ++i) f.segment<3>(3 * i) += mass_.segment<3>(3 * i).cwiseProduct(s_.gravity);
    block_k.setZero(3 * f.size());
    block_c.setZero(3 * f.size());
    elastic_forces(x, f);
    if (extra_) extra_(x, v, f, block_k, block_c);
}

void FemSolid::assemble_tangent(double c_k) {
    double* val = tangent_.valuePtr();
    std::fill(val, val + tangent_.nonZeros(), 0.0);
    for (size_t t = 0; t < tets_.size(); ++t) {
        const Eigen::Matrix3d& R = rot_[t];
        const int* slot = &slot_[t * 144];
        for (int a = 0; a < 4; ++a)
            for (int b = 0; b < 4; ++b) {
                const Eigen::Matrix3d B = c_k * R * ke_[t].block<3, 3>(3 * a, 3 * b) * R.transpose();
                for (int i = 0; i < 3; ++i)
                    for (int j = 0; j < 3; ++j) {
                        const int k = slot[(3 * a + i) * 12 + 3 * b + j];
                        if (k >= 0) val[k] += B(i, j);
                    }
            }
    }
}

void FemSolid::add_blocks(double c_k, const Eigen::VectorXd& block_k, double c_c, const Eigen::VectorXd& block_c) {
    double* val = tangent_.valuePtr();
    for (size_t e = 0; e < vertex_slot_.size(); ++e)
        if (vertex_slot_[e] >= 0 && (block_k[e] != 0 || block_c[e] != 0))
            val[vertex_slot_[e]] += c_k * block_k[e] + c_c * block_c[e];
}

int FemSolid::step(double h) { return step_within(h, 0); }

// A step of h, or when Newton's method does not converge in it, two of h / 2 (down to
// h / 2^max_halvings, where the last iterate is taken as it is and counted).
int FemSolid::step_within(double h, int depth) {
    const Eigen::VectorXd x0 = x_, v0 = v_;
    const double t0 = time_;
    bool converged = false;
    const int it = newton_step(h, converged);
    if (converged || depth >= s_.max_halvings) {
        if (!converged) ++unconverged_steps_;
        return it;
    }
    x_ = x0;
    v_ = v0;
    time_ = t0;
    ++halved_steps_;
    const int a = step_within(h / 2, depth + 1);
    const int b = step_within(h / 2, depth + 1);
    return it + a + b;
}

int FemSolid::newton_step(double h, bool& converged) {
    if (!pattern_ready_) prepare_pattern();
    const bool midpoint = s_.integrator == FemIntegrator::Midpoint;
    const double c_k = midpoint ? h * h / 4 : h * h;
    const Eigen::VectorXd x0 = x_, v0 = v_;
    eval_time_ = time_ + (midpoint ? 0.5 : 1.0) * h;
    if (step_begin_) step_begin_(time_, x0, v0);
    Eigen::VectorXd v1 = v0, x1(x0.size()), xe(x0.size()), ve(x0.size()), f, block_k, block_c;
    const double c_c = midpoint ? h / 2 : h;
    Eigen::VectorXd r(n_free_), dv(n_free_);
    // The residual m (v1 - v0) - h f(x(v1), v1) over the free coordinates, at v.
    const auto residual = [&](const Eigen::VectorXd& v, Eigen::VectorXd& res) {
        x1 = x0 + (midpoint ? 0.5 * h : h) * (midpoint ? Eigen::VectorXd(v0 + v) : v);
        xe = midpoint ? Eigen::VectorXd(0.5 * (x0 + x1)) : x1;
        ve = midpoint ? Eigen::VectorXd(0.5 * (v0 + v)) : v;
        total_forces(xe, ve, f, block_k, block_c);
        res.setZero();
        for (size_t c = 0; c < free_.size(); ++c)
            if (free_[c] >= 0) res[free_[c]] += mass_[c] * (v[c] - v0[c]) - h * f[c];
    };
    residual(v1, r);
    converged = false;
    int it = 0;
    double last_update = 0, previous_update = 0;  // max |dv| of the last two updates
    Eigen::VectorXd v_try(v1.size()), r_try(n_free_);
    for (; it < s_.max_newton; ++it) {
        const bool reuse = constant_factored_ && factored_c_ == c_k && !s_.corotational && block_k.isZero(0);
        // Modified Newton: the tangent of the first iterate, refreshed when the extra force's
        // stiffness changed (a contact began or ended), else Newton diverges on a stiff contact, and
        // when the last update shrank by less than 4 (friction's damping, which depends on the
        // sliding velocity, or the rotations moved on).
        const bool contacts_changed = it > 0 && block_k != factored_block_k_;
        const bool slow = it > 1 && last_update > 0.25 * previous_update;
        if ((it == 0 && !reuse) || contacts_changed || slow) {
            if (it > 0) update_rotations(xe);
            factored_block_k_ = block_k;
            assemble_tangent(c_k);
            double* val = tangent_.valuePtr();
            for (size_t c = 0; c < free_.size(); ++c)
                if (free_[c] >= 0) val[diag_slot_[free_[c]]] += mass_[c];
            add_blocks(c_k, block_k, c_c, block_c);
            if (s_.solver == FemLinearSolver::LDLT) {
                ldlt_->factorize(tangent_);
                if (ldlt_->info() != Eigen::Success)
                    throw Error(ExitCode::Internal, "fem: the step's tangent is not positive definite");
            } else {
                cg_->compute(tangent_);
            }
            constant_factored_ = !s_.corotational && block_k.isZero(0);
            factored_c_ = c_k;
        }
        if (s_.solver == FemLinearSolver::LDLT) {
            dv = ldlt_->solve(-r);
        } else {
            dv = cg_->solve(-r);
            cg_iterations_ += cg_->iterations();
        }
        // Backtracking on the residual's norm: a contact that turns on and off between iterates
        // (the penalty force's kink) otherwise sends Newton round a cycle of two.
        const double r0 = r.norm();
        double step = 1;
        for (int ls = 0;; ++ls) {
            v_try = v1;
            for (size_t c = 0; c < free_.size(); ++c)
                if (free_[c] >= 0) v_try[c] += step * dv[free_[c]];
            residual(v_try, r_try);
            if (r_try.norm() <= (1 - 1e-4 * step) * r0 || ls >= s_.max_backtracks) break;
            step *= 0.5;
        }
        v1 = v_try;
        r = r_try;
        double dmax = 0, vmax = 0;
        for (size_t c = 0; c < free_.size(); ++c)
            if (free_[c] >= 0) {
                dmax = std::max(dmax, std::abs(step * dv[free_[c]]));
                vmax = std::max(vmax, std::abs(v1[c]));
            }
        previous_update = last_update;
        last_update = dmax;
        if (dmax <= s_.newton_tol * (vmax + 1e-3) + s_.newton_floor) {
            ++it;
            converged = true;
            break;
        }
    }
    x_ = x0 + (midpoint ? 0.5 * h : h) * (midpoint ? Eigen::VectorXd(v0 + v1) : v1);
    v_ = v1;
    time_ += h;
    group_force_ = mass_.cwiseProduct(v1 - v0) / h - f;
    return it;
}

int FemSolid::solve_static() {
    if (!pattern_ready_) prepare_pattern();
    Eigen::VectorXd f, block_k, block_c, rhs(n_free_);
    int it = 0;
    for (; it < s_.max_newton; ++it) {
        total_forces(x_, v_, f, block_k, block_c);
        assemble_tangent(1.0);
        add_blocks(1.0, block_k, 0.0, block_c);
        rhs.setZero();
        for (size_t c = 0; c < free_.size(); ++c)
            if (free_[c] >= 0) rhs[free_[c]] += f[c];
        if (s_.solver != FemLinearSolver::LDLT) ldlt_->analyzePattern(tangent_);
        ldlt_->factorize(tangent_);
        constant_factored_ = false;
        if (ldlt_->info() != Eigen::Success) throw Error(ExitCode::Internal, "fem: the stiffness is singular (clamp the solid)");
        const Eigen::VectorXd dx = ldlt_->solve(rhs);
        for (size_t c = 0; c < free_.size(); ++c)
            if (free_[c] >= 0) x_[c] += dx[free_[c]];
        const double scale = (x_ - rest_).cwiseAbs().maxCoeff();
        if (!s_.corotational || dx.cwiseAbs().maxCoeff() <= s_.newton_tol * scale + 1e-300) {
            ++it;
            break;
        }
    }
    v_.setZero();
    for (size_t v = 0; v < vertex_count(); ++v) v_.segment<3>(3 * v) = drive_velocity_[v];
    total_forces(x_, v_, f, block_k, block_c);
    group_force_ = -f;
    return it;
}

double FemSolid::kinetic_energy() const { return 0.5 * v_.cwiseProduct(mass_).dot(v_); }

double FemSolid::tet_elastic_energy(size_t t) const {
    const Tet& T = tets_[t];
    Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
    if (s_.corotational) {
        Eigen::Matrix3d Ds;
        for (int c = 0; c < 3; ++c) Ds.col(c) = x_.segment<3>(3 * T[c + 1]) - x_.segment<3>(3 * T[0]);
        R = polar_rotation(Ds * dm_inv_[t]);
    }
    Vec12 e = gather(x_, T);
    for (int a = 0; a < 4; ++a) e.segment<3>(3 * a) = R.transpose() * e.segment<3>(3 * a) - rest_.segment<3>(3 * T[a]);
    return 0.5 * e.dot(ke_[t] * e);
}

double FemSolid::elastic_energy() const {
    double e = 0;
    for (size_t t = 0; t < tets_.size(); ++t) e += tet_elastic_energy(t);
    return e;
}

double FemSolid::gravity_energy() const {
    double e = 0;
    for (size_t v = 0; v < vertex_count(); ++v) e -= mass_[3 * v] * s_.gravity.dot(x_.segment<3>(3 * v));
    return e;
}

double FemSolid::load_energy() const { return -loads_.dot(x_ - rest_); }

Eigen::SparseMatrix<double> FemSolid::free_stiffness() {
    if (!pattern_ready_) prepare_pattern();
    update_rotations(x_);
    assemble_tangent(1.0);
    constant_factored_ = false;
    Eigen::SparseMatrix<double> full = tangent_.selfadjointView<Eigen::Lower>();
    return full;
}

Eigen::VectorXd FemSolid::free_mass() const {
    Eigen::VectorXd m = Eigen::VectorXd::Zero(n_free_);
    for (size_t c = 0; c < free_.size(); ++c)
        if (free_[c] >= 0) m[free_[c]] += mass_[c];
    return m;
}

}  // namespace shatter::fem
