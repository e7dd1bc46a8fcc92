#include "simulate/bullet_solver.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <unordered_map>
#include <vector>

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>

#include "simulate/compliant_constraint.h"

namespace shatter {

// The joint rows' system of one solve, K = J M^-1 J^T + C (C: the rows' CFM, diagonal, > 0),
// solved in the bodies' space by the Woodbury identity
//   K^-1 r = C^-1 (r - J G^-1 J^T C^-1 r),   G = M + J^T C^-1 J,
// G being the bodies' mass plus the joints' stiffness, 6 unknowns per body (the size of the
// pieces, not of the rows: a pair of pieces shares dozens of rows).
struct PieceSolver::Direct {
    Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt;
    Eigen::VectorXd u, rhs, z;  // scratch of solve_joints_directly
    std::vector<double> inv_cfm;      // 1 / C per row
    std::vector<int> body_index;      // per solver body, its first unknown in G, or -1 (not moving)
    bool ok = false;
    // G's 6 x 6 blocks: one per moving body (its diagonal) and one per pair of moving bodies that
    // a joint row joins (first unknown lower), in the order first met; reused from step to step.
    struct Block {
        int row, col;
        Eigen::Matrix<double, 6, 6> value;
    };
    std::vector<Block> blocks;
    std::unordered_map<uint64_t, size_t> block_of;  // (row, col) -> index in blocks
    std::vector<Eigen::Triplet<double>> entries;
    Eigen::SparseMatrix<double> G;
    // Per moving body (unknowns 6 k to 6 k + 5): its solver body and its mass block M_k.
    std::vector<int> bodies;
    std::vector<Eigen::Matrix<double, 6, 6>> mass;
    // In the bodies' space: J^T C^-1 b (b_r = rhs_r / jacDiagABInv_r, constant within the step),
    // and the joints' impulses J^T l and J^T l_push as they stand.
    Eigen::VectorXd rhs_body, impulse, push_impulse;
    // u + z of the last solve on the velocities, which the rows' impulses stand for (valid when
    // have_last): a row's correction in the next solve is -C^-1 J (u' - last_u).
    Eigen::VectorXd last_u;
    bool have_last = false;
    // G's sparsity pattern at the last analysis: a step with the same pattern (no joint broke or
    // woke) only refactors.
    std::vector<int> outer, inner;
    // The contact rows (and their sliding friction rows) that hold light joined bodies against
    // bodies that do not move, solved through the joints (anchor_contacts, solve_anchored_contacts):
    // the rows; for each its contact's place among them (-1 for a contact row), its joined body's
    // first unknown and its Jacobian there; per row of the contact and friction pools whether it is
    // one of them; W = J G^-1 J^T over them.
    std::vector<btSolverConstraint*> anchored;
    std::vector<int> anchored_normal;
    std::vector<int> anchored_at;  // the row's joined body's first unknown
    std::vector<Eigen::Matrix<double, 6, 1>> anchored_jacobian;  // the row's Jacobian on it
    std::vector<char> anchored_contact, anchored_friction;
    Eigen::MatrixXd W, columns, response;
    Eigen::VectorXd velocity, start;
    std::vector<int> parent, slot;
    std::vector<double> island_mass;
    // True when G's pattern (outer, inner) is the one analysed last; records it otherwise.
    bool ok_pattern(const int* o, int no, const int* i, int ni) {
        if (int(outer.size()) == no && int(inner.size()) == ni && std::equal(o, o + no, outer.begin()) &&
            std::equal(i, i + ni, inner.begin()))
            return true;
        outer.assign(o, o + no);
        inner.assign(i, i + ni);
        return false;
    }
};

PieceSolver::PieceSolver() : direct_system_(std::make_unique<Direct>()) {}
PieceSolver::~PieceSolver() = default;

namespace {

// How far ahead (in constraints) the set-up and write-back loops ask for memory.
constexpr int kPrefetchConstraints = 4;

// The cache lines of a point constraint that set-up and write-back read or write: the typed
// constraint's header (applied impulse, feedback pointer, bodies, enabled flag), the pivots and
// settings at the end of btPoint2PointConstraint, and the derived class's own members (the
// spring and the feedback).
void prefetch_constraint(const btTypedConstraint* c) {
    const char* p = reinterpret_cast<const char*>(c);
    for (int line = 0; line < 2; ++line) __builtin_prefetch(p + 64 * line, 1);
    for (int line = 9; line < 14; ++line) __builtin_prefetch(p + 64 * line, 1);
}

void prefetch_body(const btRigidBody& b) {
    const char* p = reinterpret_cast<const char*>(&b);
    for (int line = 0; line < 21; line += 2) __builtin_prefetch(p + 64 * line, 0);
}

// btSolverBody::internalApplyImpulse, the same arithmetic, inlined.
__attribute__((always_inline)) inline void apply_impulse(btSolverBody& body, const btVector3& linear,
                                                         const btVector3& angular, btScalar impulse) {
    if (body.m_originalBody) {
        body.m_deltaLinearVelocity += linear * impulse * body.m_linearFactor;
        body.m_deltaAngularVelocity += angular * (impulse * body.m_angularFactor);
    }
}

}  // namespace

// A row's impulse update, clamped to [lower, upper] (or only below, for contacts), applied to both
// bodies' velocity changes; returns the change over the row's effective mass (the residual).
__attribute__((always_inline)) inline btScalar PieceSolver::solve_row(btSolverConstraint& c, bool upper_limit) {
    btSolverBody& a = m_tmpSolverBodyPool[c.m_solverBodyIdA];
    btSolverBody& b = m_tmpSolverBodyPool[c.m_solverBodyIdB];
    btScalar delta = c.m_rhs - btScalar(c.m_appliedImpulse) * c.m_cfm;
    const btScalar va = c.m_contactNormal1.dot(a.internalGetDeltaLinearVelocity()) +
                        c.m_relpos1CrossNormal.dot(a.internalGetDeltaAngularVelocity());
    const btScalar vb = c.m_contactNormal2.dot(b.internalGetDeltaLinearVelocity()) +
                        c.m_relpos2CrossNormal.dot(b.internalGetDeltaAngularVelocity());
    delta -= va * c.m_jacDiagABInv;
    delta -= vb * c.m_jacDiagABInv;
    const btScalar sum = btScalar(c.m_appliedImpulse) + delta;
    if (sum < c.m_lowerLimit) {
        delta = c.m_lowerLimit - c.m_appliedImpulse;
        c.m_appliedImpulse = c.m_lowerLimit;
    } else if (upper_limit && sum > c.m_upperLimit) {
        delta = c.m_upperLimit - c.m_appliedImpulse;
        c.m_appliedImpulse = c.m_upperLimit;
    } else {
        c.m_appliedImpulse = sum;
    }
    apply_impulse(a, c.m_contactNormal1 * a.internalGetInvMass(), c.m_angularComponentA, delta);
    apply_impulse(b, c.m_contactNormal2 * b.internalGetInvMass(), c.m_angularComponentB, delta);
    return delta * (1. / c.m_jacDiagABInv);
}

// solve_row for a joint row of joint_rows_: the same arithmetic, with the row's linear direction
// +-e_k: n . v is +-v_k and the impulse's linear part changes component k alone, exactly (the
// other components gain +-0, and a velocity change that starts at +0 is never -0).
__attribute__((always_inline)) inline btScalar PieceSolver::solve_joint_row(JointRow& c, const JointRowBodies& ids) {
    btSolverBody& a = m_tmpSolverBodyPool[ids.a];
    btSolverBody& b = m_tmpSolverBodyPool[ids.b];
    const int k = ids.axis;
    btVector3& linear_a = a.internalGetDeltaLinearVelocity();
    btVector3& linear_b = b.internalGetDeltaLinearVelocity();
    btVector3& angular_a = a.internalGetDeltaAngularVelocity();
    btVector3& angular_b = b.internalGetDeltaAngularVelocity();
    btScalar delta = c.rhs - c.applied * c.cfm;
    const btScalar va = linear_a[k] + (c.relpos_a[0] * angular_a[0] + c.relpos_a[1] * angular_a[1] +
                                       c.relpos_a[2] * angular_a[2]);
    const btScalar vb = -linear_b[k] + (c.relpos_b[0] * angular_b[0] + c.relpos_b[1] * angular_b[1] +
                                        c.relpos_b[2] * angular_b[2]);
    delta -= va * c.jac_diag_inv;
    delta -= vb * c.jac_diag_inv;
    const btScalar sum = c.applied + delta;
    if (sum < -SIMD_INFINITY) {
        delta = -SIMD_INFINITY - c.applied;
        c.applied = -SIMD_INFINITY;
    } else if (sum > SIMD_INFINITY) {
        delta = SIMD_INFINITY - c.applied;
        c.applied = SIMD_INFINITY;
    } else {
        c.applied = sum;
    }
    if (a.m_originalBody) {
        linear_a[k] += a.internalGetInvMass()[k] * delta;
        for (int i = 0; i < 3; ++i) angular_a[i] += c.angular_a[i] * delta;
    }
    if (b.m_originalBody) {
        linear_b[k] += -b.internalGetInvMass()[k] * delta;
        for (int i = 0; i < 3; ++i) angular_b[i] += c.angular_b[i] * delta;
    }
    return delta * (1. / c.jac_diag_inv);
}

// One projected Gauss-Seidel pass, as btSequentialImpulseConstraintSolver::solveSingleIteration
// does it without SOLVER_RANDMIZE_ORDER and SOLVER_INTERLEAVE_CONTACT_AND_FRICTION_CONSTRAINTS
// (Bullet's defaults, and ours): the joint rows, then (within the contact iterations) the
// contact rows, their friction rows bounded by the contact's impulse, and rolling friction. The
// row updates are Bullet's scalar ones, written here so that they inline into the loops; the
// other modes go to Bullet's own pass.
btScalar PieceSolver::solveSingleIteration(int iteration, btCollisionObject** bodies, int numBodies,
                                           btPersistentManifold** manifolds, int numManifolds,
                                           btTypedConstraint**, int, const btContactSolverInfo& info,
                                           btIDebugDraw* debugDrawer) {
    if (info.m_solverMode & (SOLVER_RANDMIZE_ORDER | SOLVER_INTERLEAVE_CONTACT_AND_FRICTION_CONSTRAINTS))
        return btSequentialImpulseConstraintSolver::solveSingleIteration(iteration, bodies, numBodies, manifolds,
                                                                         numManifolds, nullptr, 0, info, debugDrawer);
    btScalar residual = 0;
    const auto add = [&residual](btScalar r) { residual = btMax(residual, r * r); };
    if (direct_ && direct_system_->ok) {
        // The convergence is checked from the step's last own iteration on, up to the first row
        // past the tolerance (the rows' impulses are set by the solve after the last iteration);
        // without a tolerance the rows are set wherever the iterations may stop.
        add(solve_joints_directly(false, extra_ || !(tolerance_ > 0) || iteration + 1 >= own_iterations_, true));
    } else if (tolerance_ > 0 && compact_) {
        btScalar most = 0;
        for (int j = 0; j < m_tmpSolverNonContactConstraintPool.size(); ++j) {
            const int r = m_orderNonContactConstraintPool[j];
            JointRow& row = joint_rows_[size_t(r)];
            const btScalar correction = solve_joint_row(row, joint_row_bodies_[size_t(r)]);  // dl w
            add(correction);
            most = btMax(most, btFabs(correction * row.jac_diag_inv) * row_scale_[r]);
        }
        joint_residual_ = most;
    } else if (tolerance_ > 0) {
        btScalar most = 0;
        for (int j = 0; j < m_tmpSolverNonContactConstraintPool.size(); ++j) {
            const int r = m_orderNonContactConstraintPool[j];
            btSolverConstraint& row = m_tmpSolverNonContactConstraintPool[r];
            if (!extra_ && iteration >= row.m_overrideNumSolverIterations) continue;
            const btScalar correction = solve_row(row, true);  // dl w
            add(correction);
            most = btMax(most, btFabs(correction * row.m_jacDiagABInv) * row_scale_[r]);
        }
        joint_residual_ = most;
    } else if (compact_) {
        for (int j = 0; j < m_tmpSolverNonContactConstraintPool.size(); ++j) {
            const int r = m_orderNonContactConstraintPool[j];
            add(solve_joint_row(joint_rows_[size_t(r)], joint_row_bodies_[size_t(r)]));
        }
    } else {
        for (int j = 0; j < m_tmpSolverNonContactConstraintPool.size(); ++j) {
            btSolverConstraint& row = m_tmpSolverNonContactConstraintPool[m_orderNonContactConstraintPool[j]];
            if (iteration < row.m_overrideNumSolverIterations) add(solve_row(row, true));
        }
    }
    if (iteration >= info.m_numIterations && !extra_) return residual;
    // Past the step's own iterations, with direct joints, only the contacts of jointed pieces are
    // iterated further: the iterations that follow are there to converge the joints, and the
    // contacts of fragments without joints (most of a pile after the impact) have had the step's
    // own iterations, as with iterative joints.
    const std::vector<int>* joined = extra_ && direct_ && direct_system_->ok ? &direct_system_->body_index : nullptr;
    const auto skip = [joined](const btSolverConstraint& row) {
        return joined && (*joined)[size_t(row.m_solverBodyIdA)] < 0 && (*joined)[size_t(row.m_solverBodyIdB)] < 0;
    };
    // The contacts that hold joined pieces against the ground first, through the joints; the
    // others one row at a time.
    const bool anchored = direct_ && direct_system_->ok && !direct_system_->anchored.empty();
    if (anchored) add(solve_anchored_contacts());
    const std::vector<char>& contact_done = direct_system_->anchored_contact;
    const std::vector<char>& friction_done = direct_system_->anchored_friction;
    for (int j = 0; j < m_tmpSolverContactConstraintPool.size(); ++j) {
        const int r = m_orderTmpConstraintPool[j];
        btSolverConstraint& row = m_tmpSolverContactConstraintPool[r];
        if (!skip(row) && !(anchored && contact_done[size_t(r)])) add(solve_row(row, false));
    }
    for (int j = 0; j < m_tmpSolverContactFrictionConstraintPool.size(); ++j) {
        const int r = m_orderFrictionConstraintPool[j];
        btSolverConstraint& row = m_tmpSolverContactFrictionConstraintPool[r];
        if (skip(row) || (anchored && friction_done[size_t(r)])) continue;
        const btScalar normal = m_tmpSolverContactConstraintPool[row.m_frictionIndex].m_appliedImpulse;
        if (normal > btScalar(0)) {
            row.m_lowerLimit = -(row.m_friction * normal);
            row.m_upperLimit = row.m_friction * normal;
            add(solve_row(row, true));
        }
    }
    for (int j = 0; j < m_tmpSolverContactRollingFrictionConstraintPool.size(); ++j) {
        btSolverConstraint& row = m_tmpSolverContactRollingFrictionConstraintPool[j];
        if (skip(row)) continue;
        const btScalar normal = m_tmpSolverContactConstraintPool[row.m_frictionIndex].m_appliedImpulse;
        if (normal > btScalar(0)) {
            btScalar bound = row.m_friction * normal;
            if (bound > row.m_friction) bound = row.m_friction;
            row.m_lowerLimit = -bound;
            row.m_upperLimit = bound;
            add(solve_row(row, true));
        }
    }
    return residual;
}

namespace {

using Vec6 = Eigen::Matrix<double, 6, 1>;

// A row's Jacobian on one of its two bodies: (contactNormal1, relpos1CrossNormal) on A,
// (contactNormal2, relpos2CrossNormal) on B.
Vec6 row_jacobian(const btSolverConstraint& c, bool on_a) {
    const btVector3& lin = on_a ? c.m_contactNormal1 : c.m_contactNormal2;
    const btVector3& ang = on_a ? c.m_relpos1CrossNormal : c.m_relpos2CrossNormal;
    Vec6 j;
    j << lin[0], lin[1], lin[2], ang[0], ang[1], ang[2];
    return j;
}

}  // namespace

// A joint row's equation, as Bullet's row update reads it (solve_row): the row is satisfied when
//   rhs - cfm l - (J dv) jacDiagABInv = 0,
// rhs and cfm being pre-multiplied by jacDiagABInv = 1 / (J M^-1 J^T) of the row alone. Divided by
// jacDiagABInv, over all joint rows with dv = M^-1 J^T l + (the contacts' part):
//   (J M^-1 J^T + C) l = rhs / jacDiagABInv - J dv_contacts,   C = diag(cfm / jacDiagABInv).
// Every compliant joint has C > 0, so it is solved in the bodies' space (Direct).
void PieceSolver::factor_joints() {
    const int n = m_tmpSolverNonContactConstraintPool.size();
    Direct& d = *direct_system_;
    d.inv_cfm.assign(size_t(n), 0.0);
    for (int r = 0; r < n; ++r) {
        const btSolverConstraint& row = m_tmpSolverNonContactConstraintPool[r];
        const double cfm = row.m_jacDiagABInv != 0 ? double(row.m_cfm) / double(row.m_jacDiagABInv) : 0.0;
        if (!(cfm > 0)) return;  // a rigid row: left to the iterations (d.ok stays false)
        d.inv_cfm[size_t(r)] = 1.0 / cfm;
    }
    factor_body_space();
}

// G = M + J^T C^-1 J over the dynamic bodies the joints touch (6 unknowns each: linear, then
// angular velocity change).
void PieceSolver::factor_body_space() {
    const int n = m_tmpSolverNonContactConstraintPool.size();
    Direct& d = *direct_system_;
    d.body_index.assign(size_t(m_tmpSolverBodyPool.size()), -1);
    int unknowns = 0;
    auto moving = [&](int id) {
        const btSolverBody& body = m_tmpSolverBodyPool[id];
        return body.m_originalBody && !body.internalGetInvMass().isZero();
    };
    for (int r = 0; r < n; ++r) {
        const btSolverConstraint& row = m_tmpSolverNonContactConstraintPool[r];
        for (int id : {row.m_solverBodyIdA, row.m_solverBodyIdB})
            if (d.body_index[size_t(id)] < 0 && moving(id)) d.body_index[size_t(id)] = unknowns, unknowns += 6;
    }
    // G = M + sum over rows of w J_r^T J_r, summed in 6 x 6 blocks (a pair of pieces shares
    // dozens of rows) and handed to Eigen as one triplet per non-zero entry of a block.
    d.blocks.clear();
    d.block_of.clear();
    d.bodies.assign(size_t(unknowns / 6), -1);
    d.mass.resize(size_t(unknowns / 6));
    for (int id = 0; id < m_tmpSolverBodyPool.size(); ++id) {
        const int k = d.body_index[size_t(id)];
        if (k < 0) continue;
        const btSolverBody& body = m_tmpSolverBodyPool[id];
        Eigen::Matrix<double, 6, 6> m = Eigen::Matrix<double, 6, 6>::Zero();
        for (int i = 0; i < 3; ++i) m(i, i) = 1.0 / double(body.internalGetInvMass()[i]);
        const btMatrix3x3 inertia = body.m_originalBody->getInvInertiaTensorWorld().inverse();
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) m(3 + i, 3 + j) = double(inertia[i][j]);
        d.block_of.emplace((uint64_t(uint32_t(k)) << 32) | uint32_t(k), d.blocks.size());
        d.blocks.push_back({k, k, m});
        d.bodies[size_t(k / 6)] = id;
        d.mass[size_t(k / 6)] = m;
    }
    const auto block = [&d](int row, int col) -> Eigen::Matrix<double, 6, 6>& {
        const uint64_t key = (uint64_t(uint32_t(row)) << 32) | uint32_t(col);
        auto [it, added] = d.block_of.emplace(key, d.blocks.size());
        if (added) d.blocks.push_back({row, col, Eigen::Matrix<double, 6, 6>::Zero()});
        return d.blocks[it->second].value;
    };
    for (int r = 0; r < n; ++r) {
        const btSolverConstraint& row = m_tmpSolverNonContactConstraintPool[r];
        const double w = d.inv_cfm[size_t(r)];
        int at[2] = {d.body_index[size_t(row.m_solverBodyIdA)], d.body_index[size_t(row.m_solverBodyIdB)]};
        Vec6 jac[2] = {row_jacobian(row, true), row_jacobian(row, false)};
        if (at[1] >= 0 && (at[0] < 0 || at[1] < at[0])) {
            std::swap(at[0], at[1]);
            std::swap(jac[0], jac[1]);
        }
        if (at[0] < 0) continue;
        block(at[0], at[0]).noalias() += w * jac[0] * jac[0].transpose();
        if (at[1] < 0) continue;
        if (at[1] == at[0]) {  // a row with both ends on one body
            block(at[0], at[0]).noalias() += w * (jac[0] * jac[1].transpose() + jac[1] * jac[0].transpose() +
                                                  jac[1] * jac[1].transpose());
            continue;
        }
        block(at[1], at[1]).noalias() += w * jac[1] * jac[1].transpose();
        block(at[0], at[1]).noalias() += w * jac[0] * jac[1].transpose();
    }
    d.entries.clear();
    for (const Direct::Block& b : d.blocks)
        for (int i = 0; i < 6; ++i)
            for (int j = 0; j < 6; ++j) {
                const double v = b.value(i, j);
                if (v == 0) continue;
                d.entries.emplace_back(b.row + i, b.col + j, v);
                if (b.row != b.col) d.entries.emplace_back(b.col + j, b.row + i, v);
            }
    Eigen::SparseMatrix<double>& G = d.G;
    G.resize(unknowns, unknowns);
    G.setFromTriplets(d.entries.begin(), d.entries.end());
    const bool same_pattern =
        d.ok_pattern(G.outerIndexPtr(), G.outerSize() + 1, G.innerIndexPtr(), int(G.nonZeros()));
    if (!same_pattern) d.ldlt.analyzePattern(G);
    d.ldlt.factorize(G);
    d.ok = d.ldlt.info() == Eigen::Success;
    // The right-hand side's constant part and the joints' impulses, in the bodies' space.
    d.rhs_body.setZero(unknowns);
    d.impulse.setZero(unknowns);
    d.push_impulse.setZero(unknowns);
    d.have_last = false;
    for (int r = 0; r < n; ++r) {
        const btSolverConstraint& c = m_tmpSolverNonContactConstraintPool[r];
        const double b = d.inv_cfm[size_t(r)] * double(c.m_rhs / c.m_jacDiagABInv);
        const double l = double(c.m_appliedImpulse);
        for (bool on_a : {true, false})
            if (const int k = d.body_index[size_t(on_a ? c.m_solverBodyIdA : c.m_solverBodyIdB)]; k >= 0) {
                const Vec6 j = row_jacobian(c, on_a);
                d.rhs_body.segment<6>(k) += b * j;
                d.impulse.segment<6>(k) += l * j;
            }
    }
}

// One exact solve of the joint rows with the contacts' impulses held, carried out in the bodies'
// space. With u the moving bodies' velocity changes (or push velocities), a row's equation
// b - C l - J u = 0 (C = cfm / jacDiagABInv, b = rhs / jacDiagABInv; no b for the pushes) has,
// for the rows together, the correction dl = C^-1 (r - J z), r = b - C l - J u, z = G^-1 J^T C^-1 r
// (Woodbury, G = M + J^T C^-1 J). After it the rows hold l' = C^-1 (b - J (u + z)), and
//   J^T C^-1 r = J^T C^-1 b - J^T l - A u  (A = G - M),    J^T l' = J^T l + M z:
// the bodies' velocities change by z. The iteration needs one sparse product and one solve in
// the bodies' space; one pass over the rows sets each row's l' (for the write-back and the books)
// and finds the largest correction.
btScalar PieceSolver::solve_joints_directly(bool push, bool rows, bool decide) {
    Direct& d = *direct_system_;
    const int n = m_tmpSolverNonContactConstraintPool.size();
    const int unknowns = int(d.bodies.size()) * 6;
    Eigen::VectorXd& held = push ? d.push_impulse : d.impulse;
    // u, the moving bodies' velocity changes (or push velocities)
    Eigen::VectorXd& u = d.u;
    u.resize(unknowns);
    for (size_t i = 0; i < d.bodies.size(); ++i) {
        const btSolverBody& body = m_tmpSolverBodyPool[d.bodies[i]];
        const btVector3& lin = push ? body.m_pushVelocity : body.m_deltaLinearVelocity;
        const btVector3& ang = push ? body.m_turnVelocity : body.m_deltaAngularVelocity;
        u.segment<6>(Eigen::Index(6 * i)) << lin[0], lin[1], lin[2], ang[0], ang[1], ang[2];
    }
    // A u = G u - M u
    Eigen::VectorXd& rhs = d.rhs;
    rhs.noalias() = d.G * u;
    for (size_t i = 0; i < d.bodies.size(); ++i)
        rhs.segment<6>(Eigen::Index(6 * i)).noalias() -= d.mass[i] * u.segment<6>(Eigen::Index(6 * i));
    if (push)
        rhs = -rhs - held;
    else
        rhs = d.rhs_body - held - rhs;
    Eigen::VectorXd& z = d.z;
    z = d.ldlt.solve(rhs);
    // Since G z = J^T C^-1 r, the new impulses J^T l' = held + M z: the bodies' velocities change
    // by z.
    for (size_t i = 0; i < d.bodies.size(); ++i) {
        btSolverBody& body = m_tmpSolverBodyPool[d.bodies[i]];
        const Eigen::Index k = Eigen::Index(6 * i);
        const btVector3 lin(z[k], z[k + 1], z[k + 2]), ang(z[k + 3], z[k + 4], z[k + 5]);
        if (push) {
            body.m_pushVelocity += lin;
            body.m_turnVelocity += ang;
        } else {
            body.internalGetDeltaLinearVelocity() += lin;
            body.internalGetDeltaAngularVelocity() += ang;
        }
        held.segment<6>(k).noalias() += d.mass[i] * z.segment<6>(k);
    }
    u += z;  // the velocities the rows' new impulses leave
    if (push) return 0;  // the rows' push impulses are not read: J^T l_push is kept
    if (!rows) {
        d.last_u = u;
        d.have_last = true;
        return 0;
    }
    // Where the correction only decides whether the iterations go on, it is measured up to the
    // first row past the tolerance, and the rows' impulses are left to the solve after the last
    // iteration, which sets them all (from the velocities alone: the same impulses).
    // J v of a row, v in the moving bodies' space.
    const auto along = [&d](const btSolverConstraint& c, const Eigen::VectorXd& v) {
        double jv = 0;
        if (const int k = d.body_index[size_t(c.m_solverBodyIdA)]; k >= 0) jv += row_jacobian(c, true).dot(v.segment<6>(k));
        if (const int k = d.body_index[size_t(c.m_solverBodyIdB)]; k >= 0) jv += row_jacobian(c, false).dot(v.segment<6>(k));
        return jv;
    };
    if (decide && d.have_last && tolerance_ > 0) {
        d.last_u = u - d.last_u;  // the change since the last solve
        btScalar most = 0;
        for (int r = 0; r < n && most <= tolerance_; ++r) {
            const btScalar delta = btScalar(-d.inv_cfm[size_t(r)] * along(m_tmpSolverNonContactConstraintPool[r], d.last_u));
            if (r < row_scale_.size()) most = btMax(most, btFabs(delta) * row_scale_[r]);
        }
        d.last_u = u;
        joint_residual_ = most;
        return 0;
    }
    // Each row's own impulse l' = C^-1 (b - J (u + z)), and the largest correction.
    if (d.have_last)
        d.last_u = u - d.last_u;  // now the change since the last solve
    else
        d.last_u.setZero(u.size());
    btScalar largest = 0, most = 0;
    for (int r = 0; r < n; ++r) {
        btSolverConstraint& c = m_tmpSolverNonContactConstraintPool[r];
        const double ju = along(c, u), jdu = along(c, d.last_u);
        const double w = d.inv_cfm[size_t(r)];
        const btScalar l = btScalar(w * (double(c.m_rhs / c.m_jacDiagABInv) - ju));
        const btScalar delta = d.have_last ? btScalar(-w * jdu) : l - c.m_appliedImpulse;
        c.m_appliedImpulse = l;
        largest = btMax(largest, btFabs(delta / c.m_jacDiagABInv));
        if (tolerance_ > 0 && r < row_scale_.size()) most = btMax(most, btFabs(delta) * row_scale_[r]);
    }
    d.last_u = u;
    d.have_last = true;
    joint_residual_ = most;
    return largest;
}

// The contacts that hold a light joined piece against what does not move (the ground, a kinematic
// prop), for solve_anchored_contacts. A resting contact row (its bodies' speed along its normal at
// most kAnchoredRestSpeed before the solve) between a joined body and a body that does not
// move qualifies when the body weighs under 1 / kAnchoredGain of its joined island (the pieces
// its joints connect it to, through others) and the row's effective mass through the joints,
// 1 / (J G^-1 J^T), is over kAnchoredGain times its own, 1 / (J M^-1 J^T): the ratio at which
// one row at a time stops converging in the stability map's rig (docs/accuracy.md section 6).
// Its sliding friction rows go with it. G^-1 is needed on those bodies' unknowns only: six
// back-substitutions per body (at most kMaxAnchoredBodies, first met first), from which
// W = J G^-1 J^T over the rows.
void PieceSolver::anchor_contacts() {
    Direct& d = *direct_system_;
    d.anchored.clear();
    d.anchored_normal.clear();
    d.anchored_at.clear();
    d.anchored_jacobian.clear();
    d.anchored_contact.assign(size_t(m_tmpSolverContactConstraintPool.size()), 0);
    d.anchored_friction.assign(size_t(m_tmpSolverContactFrictionConstraintPool.size()), 0);
    const int count = int(d.bodies.size());
    // The joined islands' masses (union-find over G's off-diagonal blocks).
    std::vector<int>& parent = d.parent;
    parent.resize(size_t(count));
    for (int i = 0; i < count; ++i) parent[size_t(i)] = i;
    const auto find = [&parent](int i) {
        while (parent[size_t(i)] != i) i = parent[size_t(i)] = parent[size_t(parent[size_t(i)])];
        return i;
    };
    for (const Direct::Block& b : d.blocks)
        if (b.row != b.col) parent[size_t(find(b.row / 6))] = find(b.col / 6);
    std::vector<double>& island = d.island_mass;
    island.assign(size_t(count), 0.0);
    for (int i = 0; i < count; ++i) island[size_t(find(i))] += d.mass[size_t(i)](0, 0);
    const auto still = [this](int id) {
        const btSolverBody& body = m_tmpSolverBodyPool[id];
        return !body.m_originalBody || body.internalGetInvMass().isZero();
    };
    // Candidate contacts and their bodies.
    std::vector<int>& slot = d.slot;  // per joined body: its place among the candidates' bodies, or -1
    slot.assign(size_t(count), -1);
    std::vector<int> bodies, candidates;
    for (int r = 0; r < m_tmpSolverContactConstraintPool.size(); ++r) {
        const btSolverConstraint& row = m_tmpSolverContactConstraintPool[r];
        const int a = d.body_index[size_t(row.m_solverBodyIdA)], b = d.body_index[size_t(row.m_solverBodyIdB)];
        int k = -1;
        if (a >= 0 && b < 0 && still(row.m_solverBodyIdB)) k = a;
        if (b >= 0 && a < 0 && still(row.m_solverBodyIdA)) k = b;
        if (k < 0) continue;
        // A resting contact only: at an impact the row's own mass is what the first instant
        // sees (and the joints are for the fracture to load), at rest the joints carry the load.
        const btSolverBody& sa = m_tmpSolverBodyPool[row.m_solverBodyIdA];
        const btSolverBody& sb = m_tmpSolverBodyPool[row.m_solverBodyIdB];
        const btScalar approach =
            row.m_contactNormal1.dot(sa.m_linearVelocity + sa.m_externalForceImpulse) +
            row.m_relpos1CrossNormal.dot(sa.m_angularVelocity + sa.m_externalTorqueImpulse) +
            row.m_contactNormal2.dot(sb.m_linearVelocity + sb.m_externalForceImpulse) +
            row.m_relpos2CrossNormal.dot(sb.m_angularVelocity + sb.m_externalTorqueImpulse);
        if (!(btFabs(approach) <= btScalar(kAnchoredRestSpeed))) continue;
        const int body = k / 6;
        if (!(island[size_t(find(body))] > kAnchoredGain * d.mass[size_t(body)](0, 0))) continue;
        if (slot[size_t(body)] < 0) {
            if (int(bodies.size()) == kMaxAnchoredBodies) continue;
            slot[size_t(body)] = int(bodies.size());
            bodies.push_back(body);
        }
        candidates.push_back(r);
    }
    if (candidates.empty()) return;
    // G^-1's columns for the candidate bodies' unknowns.
    const int unknowns = count * 6;
    d.columns.setZero(unknowns, 6 * Eigen::Index(bodies.size()));
    for (size_t c = 0; c < bodies.size(); ++c)
        d.columns.block<6, 6>(6 * bodies[c], 6 * Eigen::Index(c)).setIdentity();
    d.response = d.ldlt.solve(d.columns);
    std::vector<int> place(size_t(m_tmpSolverContactConstraintPool.size()), -1);
    const auto add = [&d](btSolverConstraint& row, int normal) {
        const bool on_a = d.body_index[size_t(row.m_solverBodyIdA)] >= 0;
        d.anchored.push_back(&row);
        d.anchored_normal.push_back(normal);
        d.anchored_at.push_back(d.body_index[size_t(on_a ? row.m_solverBodyIdA : row.m_solverBodyIdB)]);
        d.anchored_jacobian.push_back(row_jacobian(row, on_a));
    };
    for (int r : candidates) {
        btSolverConstraint& row = m_tmpSolverContactConstraintPool[r];
        const bool on_a = d.body_index[size_t(row.m_solverBodyIdA)] >= 0;
        const int k = d.body_index[size_t(on_a ? row.m_solverBodyIdA : row.m_solverBodyIdB)];
        const Vec6 j = row_jacobian(row, on_a);
        const double through = j.dot(d.response.block<6, 6>(k, 6 * slot[size_t(k / 6)]) * j);
        if (!(through * double(row.m_jacDiagABInv) * kAnchoredGain < 1)) continue;
        place[size_t(r)] = int(d.anchored.size());
        add(row, -1);
    }
    if (d.anchored.empty()) return;
    for (int r = 0; r < m_tmpSolverContactFrictionConstraintPool.size(); ++r) {
        btSolverConstraint& row = m_tmpSolverContactFrictionConstraintPool[r];
        const int normal = place[size_t(row.m_frictionIndex)];
        if (normal < 0) continue;
        d.anchored_friction[size_t(r)] = 1;
        add(row, normal);
    }
    for (size_t r = 0; r < place.size(); ++r) d.anchored_contact[r] = place[r] >= 0;
    // W_ij = J_i (G^-1)_(body i, body j) J_j^T.
    const int m = int(d.anchored.size());
    d.W.resize(m, m);
    for (int i = 0; i < m; ++i)
        for (int j = 0; j < m; ++j)
            d.W(i, j) = d.anchored_jacobian[size_t(i)].dot(
                d.response.block<6, 6>(d.anchored_at[size_t(i)], 6 * slot[size_t(d.anchored_at[size_t(j)] / 6)]) *
                d.anchored_jacobian[size_t(j)]);
}

// Projected Gauss-Seidel over the anchored contact rows with the joints' response included: a
// row's impulse moves every joined body by G^-1 J^T dl (what the direct joint solve that follows
// makes of it), so a light piece pressed by the heavy pieces joined to it is held as their whole
// weight is, where one row at a time it is held only as its own mass is (a heavy stack standing on
// a light piece slides and creeps). Each row: dl = (b - c l - J v) / (W_ii + c), clamped to the
// row's limits (a friction row's from its contact's impulse, as Bullet bounds them), J v of every
// row updated by W's column. kAnchoredSweeps sweeps, then the impulses go on the bodies (M^-1 J^T
// dl, as Bullet applies them); the next joint solve spreads them as W assumed. Returns the
// largest change over the row's own effective mass, as solve_row does.
btScalar PieceSolver::solve_anchored_contacts() {
    Direct& d = *direct_system_;
    const int m = int(d.anchored.size());
    d.velocity.resize(m);
    d.start.resize(m);
    for (int i = 0; i < m; ++i) {
        const btSolverConstraint& row = *d.anchored[size_t(i)];
        const btSolverBody& a = m_tmpSolverBodyPool[row.m_solverBodyIdA];
        const btSolverBody& b = m_tmpSolverBodyPool[row.m_solverBodyIdB];
        d.velocity[i] = double(row.m_contactNormal1.dot(a.m_deltaLinearVelocity) +
                               row.m_relpos1CrossNormal.dot(a.m_deltaAngularVelocity) +
                               row.m_contactNormal2.dot(b.m_deltaLinearVelocity) +
                               row.m_relpos2CrossNormal.dot(b.m_deltaAngularVelocity));
        d.start[i] = double(row.m_appliedImpulse);
    }
    for (int sweep = 0; sweep < kAnchoredSweeps; ++sweep)
        for (int i = 0; i < m; ++i) {
            btSolverConstraint& row = *d.anchored[size_t(i)];
            const int normal = d.anchored_normal[size_t(i)];
            if (normal >= 0) {
                const btScalar held = d.anchored[size_t(normal)]->m_appliedImpulse;
                if (!(held > btScalar(0))) continue;  // as Bullet: no friction without a push
                row.m_lowerLimit = -(row.m_friction * held);
                row.m_upperLimit = row.m_friction * held;
            }
            const double inv = 1.0 / double(row.m_jacDiagABInv);
            const double c = double(row.m_cfm) * inv;
            const double l = double(row.m_appliedImpulse);
            const double next = std::clamp(l + (double(row.m_rhs) * inv - c * l - d.velocity[i]) / (d.W(i, i) + c),
                                           double(row.m_lowerLimit), normal >= 0 ? double(row.m_upperLimit) : HUGE_VAL);
            if (next == l) continue;
            row.m_appliedImpulse = btScalar(next);
            d.velocity.noalias() += d.W.col(i) * (next - l);
        }
    btScalar largest = 0;
    for (int i = 0; i < m; ++i) {
        const btSolverConstraint& row = *d.anchored[size_t(i)];
        const btScalar delta = btScalar(double(row.m_appliedImpulse) - d.start[i]);
        if (delta == btScalar(0)) continue;
        btSolverBody& a = m_tmpSolverBodyPool[row.m_solverBodyIdA];
        btSolverBody& b = m_tmpSolverBodyPool[row.m_solverBodyIdB];
        a.internalApplyImpulse(row.m_contactNormal1 * a.internalGetInvMass(), row.m_angularComponentA, delta);
        b.internalApplyImpulse(row.m_contactNormal2 * b.internalGetInvMass(), row.m_angularComponentB, delta);
        largest = btMax(largest, btFabs(delta * (btScalar(1) / row.m_jacDiagABInv)));
    }
    return largest;
}

// Bullet's set-up of the joint rows, in the same order and with the same calls (so the same
// bytes), with prefetching: first every constraint's row count (and its feedback cleared, its
// impulse reset), then each constraint's rows from getInfo2.
void PieceSolver::convertJoints(btTypedConstraint** constraints, int count, const btContactSolverInfo& info) {
    m_tmpConstraintSizesPool.resizeNoInitialize(count);
    int rows = 0;
    for (int i = 0; i < count; ++i) {
        if (i + kPrefetchConstraints < count) prefetch_constraint(constraints[i + kPrefetchConstraints]);
        btTypedConstraint* c = constraints[i];
        c->buildJacobian();
        c->internalSetAppliedImpulse(0);
        if (btJointFeedback* fb = c->getJointFeedback()) {
            fb->m_appliedForceBodyA.setZero();
            fb->m_appliedTorqueBodyA.setZero();
            fb->m_appliedForceBodyB.setZero();
            fb->m_appliedTorqueBodyB.setZero();
        }
        btTypedConstraint::btConstraintInfo1& size = m_tmpConstraintSizesPool[i];
        if (c->isEnabled()) {
            c->getInfo1(&size);
        } else {
            size.m_numConstraintRows = 0;
            size.nub = 0;
        }
        rows += size.m_numConstraintRows;
    }
    m_tmpSolverNonContactConstraintPool.resizeNoInitialize(rows);
    // The passes' copy of the rows (JointRow), made as each constraint's rows are set up.
    compact_ = !direct_ && !(info.m_solverMode & (SOLVER_RANDMIZE_ORDER | SOLVER_INTERLEAVE_CONTACT_AND_FRICTION_CONSTRAINTS));
    if (compact_) {
        joint_rows_.resize(size_t(rows));
        joint_row_bodies_.resize(size_t(rows));
    }
    int fewest_iterations = std::numeric_limits<int>::max();
    int row = 0;
    for (int i = 0; i < count; ++i) {
        if (i + kPrefetchConstraints < count) {
            const btTypedConstraint* ahead = constraints[i + kPrefetchConstraints];
            prefetch_constraint(ahead);
            prefetch_body(ahead->getRigidBodyA());
            prefetch_body(ahead->getRigidBodyB());
        }
        const btTypedConstraint::btConstraintInfo1& size = m_tmpConstraintSizesPool[i];
        if (size.m_numConstraintRows) {
            btTypedConstraint* c = constraints[i];
            const int a = getOrInitSolverBody(c->getRigidBodyA(), info.m_timeStep);
            const int b = getOrInitSolverBody(c->getRigidBodyB(), info.m_timeStep);
            convertJoint(&m_tmpSolverNonContactConstraintPool[row], c, size, a, b, info);
            for (int r = row; compact_ && r < row + size.m_numConstraintRows; ++r) {
                const btSolverConstraint& from = m_tmpSolverNonContactConstraintPool[r];
                fewest_iterations = std::min(fewest_iterations, from.m_overrideNumSolverIterations);
                compact_ = copy_joint_row(from, a, b, &joint_rows_[size_t(r)], &joint_row_bodies_[size_t(r)]);
            }
        }
        row += size.m_numConstraintRows;
    }
    // A row that takes fewer passes than the solve's (a constraint's own iteration count) is
    // skipped in the passes past its count: Bullet's rows then.
    if (fewest_iterations < btMax(m_maxOverrideNumSolverIterations, info.m_numIterations)) compact_ = false;
}

bool PieceSolver::copy_joint_row(const btSolverConstraint& from, int a, int b, JointRow* to, JointRowBodies* bodies) const {
    int axis = -1;
    for (int k = 0; k < 3; ++k)
        if (from.m_contactNormal1[k] == btScalar(1) && from.m_contactNormal2[k] == btScalar(-1)) axis = k;
    if (axis < 0) return false;
    for (int k = 0; k < 3; ++k)
        if (k != axis && (from.m_contactNormal1[k] != btScalar(0) || from.m_contactNormal2[k] != btScalar(0)))
            return false;
    if (from.m_lowerLimit != -SIMD_INFINITY || from.m_upperLimit != SIMD_INFINITY) return false;
    const btVector3 one(1, 1, 1);
    for (const int i : {a, b}) {
        const btSolverBody& body = m_tmpSolverBodyPool[i];
        if (!(body.m_linearFactor == one) || !(body.m_angularFactor == one)) return false;
    }
    for (int k = 0; k < 3; ++k) {
        to->relpos_a[k] = from.m_relpos1CrossNormal[k];
        to->relpos_b[k] = from.m_relpos2CrossNormal[k];
        to->angular_a[k] = from.m_angularComponentA[k];
        to->angular_b[k] = from.m_angularComponentB[k];
    }
    to->rhs = from.m_rhs;
    to->cfm = from.m_cfm;
    to->jac_diag_inv = from.m_jacDiagABInv;
    to->applied = from.m_appliedImpulse;
    *bodies = {from.m_solverBodyIdA, from.m_solverBodyIdB, axis};
    return true;
}

btScalar PieceSolver::solveGroupCacheFriendlyIterations(btCollisionObject** bodies, int numBodies,
                                                        btPersistentManifold** manifolds, int numManifolds,
                                                        btTypedConstraint** constraints, int numConstraints,
                                                        const btContactSolverInfo& info, btIDebugDraw* debugDrawer) {
    const int own = btMax(m_maxOverrideNumSolverIterations, info.m_numIterations);
    own_iterations_ = own;
    most_iterations_ = btMax(most_iterations_, own);
    direct_system_->ok = false;
    if (direct_ && m_tmpSolverNonContactConstraintPool.size() > 0) factor_joints();
    if (direct_ && direct_system_->ok) anchor_contacts();
    if (!(tolerance_ > 0) || m_tmpSolverNonContactConstraintPool.size() == 0) {
        const btScalar r = btSequentialImpulseConstraintSolver::solveGroupCacheFriendlyIterations(
            bodies, numBodies, manifolds, numManifolds, constraints, numConstraints, info, debugDrawer);
        if (direct_ && direct_system_->ok) solve_joints_directly();  // the joints last
        return r;
    }
    // Bullet's loop (split-impulse pass, then `own` iterations, here without Bullet's early stop
    // at its residual threshold), then more until the joints converge.
    solveGroupCacheFriendlySplitImpulseIterations(bodies, numBodies, manifolds, numManifolds, constraints, numConstraints,
                                                  info, debugDrawer);
    const btScalar inv_h = btScalar(1) / info.m_timeStep;
    row_scale_.resizeNoInitialize(m_tmpSolverNonContactConstraintPool.size());
    for (int r = 0; r < m_tmpSolverNonContactConstraintPool.size(); ++r) {
        const btSolverConstraint& row = m_tmpSolverNonContactConstraintPool[r];
        const auto* c = static_cast<const CompliantPointConstraint*>(row.m_originalContactPoint);
        row_scale_[r] = c->strength() > 0 && row.m_cfm > 0 ? inv_h / (row.m_cfm * btScalar(c->strength())) : 0;
    }
    int iteration = 0;
    extra_ = false;
    for (; iteration < own; ++iteration)
        solveSingleIteration(iteration, bodies, numBodies, manifolds, numManifolds, constraints, numConstraints, info,
                             debugDrawer);
    extra_ = true;
    for (; joint_residual_ > tolerance_ && iteration < max_iterations_; ++iteration)
        solveSingleIteration(iteration, bodies, numBodies, manifolds, numManifolds, constraints, numConstraints, info,
                             debugDrawer);
    extra_ = false;
    if (direct_ && direct_system_->ok) solve_joints_directly();  // the joints last
    most_iterations_ = btMax(most_iterations_, iteration);
    return 0;
}

// Bullet's split-impulse pass (the contacts' push rows, Bullet's row update, as many passes as the
// step's iterations), with the joint rows solved on the push velocities after the contacts in
// each pass: J push + C l_push = 0, the joints' own compliance, no right-hand side.
void PieceSolver::solveGroupCacheFriendlySplitImpulseIterations(btCollisionObject** bodies, int numBodies,
                                                                btPersistentManifold** manifolds, int numManifolds,
                                                                btTypedConstraint** constraints, int numConstraints,
                                                                const btContactSolverInfo& info,
                                                                btIDebugDraw* debugDrawer) {
    const int joints = m_tmpSolverNonContactConstraintPool.size();
    if (!push_joints_ || !info.m_splitImpulse || joints == 0) {
        btSequentialImpulseConstraintSolver::solveGroupCacheFriendlySplitImpulseIterations(
            bodies, numBodies, manifolds, numManifolds, constraints, numConstraints, info, debugDrawer);
        return;
    }
    bool pushing = false;  // nothing penetrates: no push to share
    for (int j = 0; j < m_tmpSolverContactConstraintPool.size() && !pushing; ++j)
        pushing = m_tmpSolverContactConstraintPool[j].m_rhsPenetration != 0;
    if (!pushing) return;
    pushed_ = true;
    for (int r = 0; r < joints; ++r) m_tmpSolverNonContactConstraintPool[r].m_appliedPushImpulse = 0;
    const bool direct = direct_ && direct_system_->ok;
    if (direct) direct_system_->push_impulse.setZero();
    for (int iteration = 0; iteration < info.m_numIterations; ++iteration) {
        for (int j = 0; j < m_tmpSolverContactConstraintPool.size(); ++j) {
            const btSolverConstraint& c = m_tmpSolverContactConstraintPool[m_orderTmpConstraintPool[j]];
            resolveSplitPenetrationImpulse(m_tmpSolverBodyPool[c.m_solverBodyIdA], m_tmpSolverBodyPool[c.m_solverBodyIdB], c);
        }
        if (direct) {
            solve_joints_directly(true);
            continue;
        }
        for (int j = 0; j < joints; ++j) {
            btSolverConstraint& c = m_tmpSolverNonContactConstraintPool[m_orderNonContactConstraintPool[j]];
            btSolverBody& a = m_tmpSolverBodyPool[c.m_solverBodyIdA];
            btSolverBody& b = m_tmpSolverBodyPool[c.m_solverBodyIdB];
            const btScalar jv = c.m_contactNormal1.dot(a.m_pushVelocity) + c.m_relpos1CrossNormal.dot(a.m_turnVelocity) +
                                c.m_contactNormal2.dot(b.m_pushVelocity) + c.m_relpos2CrossNormal.dot(b.m_turnVelocity);
            const btScalar delta = -btScalar(c.m_appliedPushImpulse) * c.m_cfm - jv * c.m_jacDiagABInv;
            c.m_appliedPushImpulse = btScalar(c.m_appliedPushImpulse) + delta;
            a.internalApplyPushImpulse(c.m_contactNormal1 * a.internalGetInvMass(), c.m_angularComponentA, delta);
            b.internalApplyPushImpulse(c.m_contactNormal2 * b.internalGetInvMass(), c.m_angularComponentB, delta);
        }
    }
}

btScalar PieceSolver::solveGroupCacheFriendlyFinish(btCollisionObject** bodies, int numBodies,
                                                    const btContactSolverInfo& info) {
    write_back_joints(info);
    // A rolling or spinning friction row turns its two bodies about its axis: the angular impulse
    // axis x impulse on A, the opposite on B (Bullet's setupTorsionalFrictionConstraint).
    for (int j = 0; j < m_tmpSolverContactRollingFrictionConstraintPool.size(); ++j) {
        const btSolverConstraint& row = m_tmpSolverContactRollingFrictionConstraintPool[j];
        if (row.m_appliedImpulse == btScalar(0)) continue;
        const btRigidBody* a = m_tmpSolverBodyPool[row.m_solverBodyIdA].m_originalBody;
        const btRigidBody* b = m_tmpSolverBodyPool[row.m_solverBodyIdB].m_originalBody;
        if (a) rolling_.push_back({a, row.m_relpos1CrossNormal * row.m_appliedImpulse});
        if (b) rolling_.push_back({b, row.m_relpos2CrossNormal * row.m_appliedImpulse});
    }
    if (info.m_splitImpulse)
        for (int i = 0; i < m_tmpSolverBodyPool.size(); ++i) {
            const btSolverBody& body = m_tmpSolverBodyPool[i];
            if (body.m_originalBody && !body.m_pushVelocity.isZero())
                pushes_.push_back({body.m_originalBody, body.m_pushVelocity});
        }
    // Bullet's own write-back then has no joint rows left to visit; contacts and bodies as usual.
    m_tmpSolverNonContactConstraintPool.resizeNoInitialize(0);
    compact_ = false;
    return btSequentialImpulseConstraintSolver::solveGroupCacheFriendlyFinish(bodies, numBodies, info);
}

// What btSequentialImpulseConstraintSolver::writeBackJoints computes, with the bodies' linear and
// angular factors equal to one: feedback (force and torque on each body) = row direction x
// impulse / h, summed over the constraint's rows in order; the applied impulse; the breaking
// threshold.
void PieceSolver::write_back_joints(const btContactSolverInfo& info) {
    constexpr int kPrefetchRows = 12;
    const btScalar inv_h = btScalar(1) / info.m_timeStep;
    const int rows = m_tmpSolverNonContactConstraintPool.size();
    for (int j = 0; j < rows; ++j) {
        if (j + kPrefetchRows < rows) {
            const auto* ahead = static_cast<const btTypedConstraint*>(
                m_tmpSolverNonContactConstraintPool[j + kPrefetchRows].m_originalContactPoint);
            __builtin_prefetch(ahead, 1);
            __builtin_prefetch(ahead->getJointFeedback(), 1);
        }
        btSolverConstraint& row = m_tmpSolverNonContactConstraintPool[j];
        auto* constraint = static_cast<btTypedConstraint*>(row.m_originalContactPoint);
        if (compact_) row.m_appliedImpulse = joint_rows_[size_t(j)].applied;
        const btScalar impulse = row.m_appliedImpulse;
        if (btJointFeedback* fb = constraint->getJointFeedback()) {
            fb->m_appliedForceBodyA += row.m_contactNormal1 * impulse * inv_h;
            fb->m_appliedTorqueBodyA += row.m_relpos1CrossNormal * impulse * inv_h;
            fb->m_appliedForceBodyB += row.m_contactNormal2 * impulse * inv_h;
            fb->m_appliedTorqueBodyB += row.m_relpos2CrossNormal * impulse * inv_h;
        }
        constraint->internalSetAppliedImpulse(impulse);
        if (btFabs(impulse) >= constraint->getBreakingImpulseThreshold()) constraint->setEnabled(false);
        if (!pushed_) continue;
        // The push's load: the spring's force k h J push for the stretch h J push that the push
        // velocities give the row (the turn by its ERP, as the step moves the bodies). Not the
        // push rows' impulse, which holds the damper's c J push as well: a push has no speed.
        const btSolverBody& a = m_tmpSolverBodyPool[row.m_solverBodyIdA];
        const btSolverBody& b = m_tmpSolverBodyPool[row.m_solverBodyIdB];
        const btScalar jv = row.m_contactNormal1.dot(a.m_pushVelocity) +
                            row.m_relpos1CrossNormal.dot(a.m_turnVelocity) * info.m_splitImpulseTurnErp +
                            row.m_contactNormal2.dot(b.m_pushVelocity) +
                            row.m_relpos2CrossNormal.dot(b.m_turnVelocity) * info.m_splitImpulseTurnErp;
        auto* joint = static_cast<CompliantPointConstraint*>(constraint);
        const btScalar force = -btScalar(joint->stiffness()) * info.m_timeStep * jv;
        btJointFeedback& fb = joint->push_feedback();
        fb.m_appliedForceBodyA += row.m_contactNormal1 * force;
        fb.m_appliedTorqueBodyA += row.m_relpos1CrossNormal * force;
        fb.m_appliedForceBodyB += row.m_contactNormal2 * force;
        fb.m_appliedTorqueBodyB += row.m_relpos2CrossNormal * force;
    }
    pushed_ = false;
}

}  // namespace shatter
