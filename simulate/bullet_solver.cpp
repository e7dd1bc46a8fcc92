#include "simulate/bullet_solver.h"

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
    Eigen::VectorXd residual, correction, body_rhs;
    std::vector<double> inv_cfm;      // 1 / C per row
    std::vector<int> body_index;      // per solver body, its first unknown in G, or -1 (not moving)
    bool ok = false;
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
    a.internalApplyImpulse(c.m_contactNormal1 * a.internalGetInvMass(), c.m_angularComponentA, delta);
    b.internalApplyImpulse(c.m_contactNormal2 * b.internalGetInvMass(), c.m_angularComponentB, delta);
    return delta * (1. / c.m_jacDiagABInv);
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
        add(solve_joints_directly());
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
    } else {
        for (int j = 0; j < m_tmpSolverNonContactConstraintPool.size(); ++j) {
            btSolverConstraint& row = m_tmpSolverNonContactConstraintPool[m_orderNonContactConstraintPool[j]];
            if (iteration < row.m_overrideNumSolverIterations) add(solve_row(row, true));
        }
    }
    if (iteration >= info.m_numIterations && !extra_) return residual;
    for (int j = 0; j < m_tmpSolverContactConstraintPool.size(); ++j)
        add(solve_row(m_tmpSolverContactConstraintPool[m_orderTmpConstraintPool[j]], false));
    for (int j = 0; j < m_tmpSolverContactFrictionConstraintPool.size(); ++j) {
        btSolverConstraint& row = m_tmpSolverContactFrictionConstraintPool[m_orderFrictionConstraintPool[j]];
        const btScalar normal = m_tmpSolverContactConstraintPool[row.m_frictionIndex].m_appliedImpulse;
        if (normal > btScalar(0)) {
            row.m_lowerLimit = -(row.m_friction * normal);
            row.m_upperLimit = row.m_friction * normal;
            add(solve_row(row, true));
        }
    }
    for (int j = 0; j < m_tmpSolverContactRollingFrictionConstraintPool.size(); ++j) {
        btSolverConstraint& row = m_tmpSolverContactRollingFrictionConstraintPool[j];
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
    d.residual.resize(n);
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
    std::vector<Eigen::Triplet<double>> entries;
    for (int id = 0; id < m_tmpSolverBodyPool.size(); ++id) {
        const int k = d.body_index[size_t(id)];
        if (k < 0) continue;
        const btSolverBody& body = m_tmpSolverBodyPool[id];
        for (int i = 0; i < 3; ++i) entries.emplace_back(k + i, k + i, 1.0 / double(body.internalGetInvMass()[i]));
        const btMatrix3x3 inertia = body.m_originalBody->getInvInertiaTensorWorld().inverse();
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) entries.emplace_back(k + 3 + i, k + 3 + j, double(inertia[i][j]));
    }
    for (int r = 0; r < n; ++r) {
        const btSolverConstraint& row = m_tmpSolverNonContactConstraintPool[r];
        const double w = d.inv_cfm[size_t(r)];
        const int at[2] = {d.body_index[size_t(row.m_solverBodyIdA)], d.body_index[size_t(row.m_solverBodyIdB)]};
        const Vec6 jac[2] = {row_jacobian(row, true), row_jacobian(row, false)};
        for (int x = 0; x < 2; ++x)
            for (int y = 0; y < 2; ++y) {
                if (at[x] < 0 || at[y] < 0) continue;
                for (int i = 0; i < 6; ++i)
                    for (int j = 0; j < 6; ++j)
                        if (jac[x][i] != 0 && jac[y][j] != 0)
                            entries.emplace_back(at[x] + i, at[y] + j, w * jac[x][i] * jac[y][j]);
            }
    }
    Eigen::SparseMatrix<double> G(unknowns, unknowns);
    G.setFromTriplets(entries.begin(), entries.end());
    d.ldlt.compute(G);
    d.ok = d.ldlt.info() == Eigen::Success;
    d.body_rhs.resize(unknowns);
}

btScalar PieceSolver::solve_joints_directly(bool push) {
    Direct& d = *direct_system_;
    const int n = m_tmpSolverNonContactConstraintPool.size();
    for (int r = 0; r < n; ++r) {
        const btSolverConstraint& c = m_tmpSolverNonContactConstraintPool[r];
        btSolverBody& a = m_tmpSolverBodyPool[c.m_solverBodyIdA];
        btSolverBody& b = m_tmpSolverBodyPool[c.m_solverBodyIdB];
        if (push) {  // the same rows with no right-hand side: joined pieces move together
            const btScalar jv = c.m_contactNormal1.dot(a.m_pushVelocity) + c.m_relpos1CrossNormal.dot(a.m_turnVelocity) +
                                c.m_contactNormal2.dot(b.m_pushVelocity) + c.m_relpos2CrossNormal.dot(b.m_turnVelocity);
            d.residual[r] = c.m_jacDiagABInv != 0
                                ? double(-btScalar(c.m_appliedPushImpulse) * c.m_cfm / c.m_jacDiagABInv - jv)
                                : 0.0;
            continue;
        }
        const btScalar jv = c.m_contactNormal1.dot(a.internalGetDeltaLinearVelocity()) +
                            c.m_relpos1CrossNormal.dot(a.internalGetDeltaAngularVelocity()) +
                            c.m_contactNormal2.dot(b.internalGetDeltaLinearVelocity()) +
                            c.m_relpos2CrossNormal.dot(b.internalGetDeltaAngularVelocity());
        d.residual[r] = c.m_jacDiagABInv != 0
                            ? double((c.m_rhs - btScalar(c.m_appliedImpulse) * c.m_cfm) / c.m_jacDiagABInv - jv)
                            : 0.0;
    }
    // K^-1 r = C^-1 (r - J G^-1 J^T C^-1 r)
    d.body_rhs.setZero();
    for (int r = 0; r < n; ++r) {
        const btSolverConstraint& c = m_tmpSolverNonContactConstraintPool[r];
        const double wr = d.inv_cfm[size_t(r)] * d.residual[r];
        if (const int k = d.body_index[size_t(c.m_solverBodyIdA)]; k >= 0)
            d.body_rhs.segment<6>(k) += wr * row_jacobian(c, true);
        if (const int k = d.body_index[size_t(c.m_solverBodyIdB)]; k >= 0)
            d.body_rhs.segment<6>(k) += wr * row_jacobian(c, false);
    }
    const Eigen::VectorXd z = d.ldlt.solve(d.body_rhs);
    d.correction.resize(n);
    for (int r = 0; r < n; ++r) {
        const btSolverConstraint& c = m_tmpSolverNonContactConstraintPool[r];
        double jz = 0;
        if (const int k = d.body_index[size_t(c.m_solverBodyIdA)]; k >= 0)
            jz += row_jacobian(c, true).dot(z.segment<6>(k));
        if (const int k = d.body_index[size_t(c.m_solverBodyIdB)]; k >= 0)
            jz += row_jacobian(c, false).dot(z.segment<6>(k));
        d.correction[r] = d.inv_cfm[size_t(r)] * (d.residual[r] - jz);
    }
    btScalar largest = 0, most = 0;
    if (push) {
        for (int r = 0; r < n; ++r) {
            btSolverConstraint& c = m_tmpSolverNonContactConstraintPool[r];
            const btScalar delta = btScalar(d.correction[r]);
            c.m_appliedPushImpulse = btScalar(c.m_appliedPushImpulse) + delta;
            m_tmpSolverBodyPool[c.m_solverBodyIdA].internalApplyPushImpulse(
                c.m_contactNormal1 * m_tmpSolverBodyPool[c.m_solverBodyIdA].internalGetInvMass(), c.m_angularComponentA, delta);
            m_tmpSolverBodyPool[c.m_solverBodyIdB].internalApplyPushImpulse(
                c.m_contactNormal2 * m_tmpSolverBodyPool[c.m_solverBodyIdB].internalGetInvMass(), c.m_angularComponentB, delta);
            if (c.m_jacDiagABInv != 0) largest = btMax(largest, btFabs(delta / c.m_jacDiagABInv));
        }
        return largest;
    }
    for (int r = 0; r < n; ++r) {
        btSolverConstraint& c = m_tmpSolverNonContactConstraintPool[r];
        const btScalar delta = btScalar(d.correction[r]);
        c.m_appliedImpulse = btScalar(c.m_appliedImpulse) + delta;
        btSolverBody& a = m_tmpSolverBodyPool[c.m_solverBodyIdA];
        btSolverBody& b = m_tmpSolverBodyPool[c.m_solverBodyIdB];
        a.internalApplyImpulse(c.m_contactNormal1 * a.internalGetInvMass(), c.m_angularComponentA, delta);
        b.internalApplyImpulse(c.m_contactNormal2 * b.internalGetInvMass(), c.m_angularComponentB, delta);
        if (c.m_jacDiagABInv != 0) largest = btMax(largest, btFabs(delta / c.m_jacDiagABInv));
        if (tolerance_ > 0 && r < row_scale_.size()) most = btMax(most, btFabs(delta) * row_scale_[r]);
    }
    joint_residual_ = most;
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
        }
        row += size.m_numConstraintRows;
    }
}

btScalar PieceSolver::solveGroupCacheFriendlyIterations(btCollisionObject** bodies, int numBodies,
                                                        btPersistentManifold** manifolds, int numManifolds,
                                                        btTypedConstraint** constraints, int numConstraints,
                                                        const btContactSolverInfo& info, btIDebugDraw* debugDrawer) {
    const int own = btMax(m_maxOverrideNumSolverIterations, info.m_numIterations);
    most_iterations_ = btMax(most_iterations_, own);
    direct_system_->ok = false;
    if (direct_ && m_tmpSolverNonContactConstraintPool.size() > 0) factor_joints();
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
    for (int r = 0; r < joints; ++r) m_tmpSolverNonContactConstraintPool[r].m_appliedPushImpulse = 0;
    const bool direct = direct_ && direct_system_->ok;
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
        const btSolverConstraint& row = m_tmpSolverNonContactConstraintPool[j];
        auto* constraint = static_cast<btTypedConstraint*>(row.m_originalContactPoint);
        const btScalar impulse = row.m_appliedImpulse;
        if (btJointFeedback* fb = constraint->getJointFeedback()) {
            fb->m_appliedForceBodyA += row.m_contactNormal1 * impulse * inv_h;
            fb->m_appliedTorqueBodyA += row.m_relpos1CrossNormal * impulse * inv_h;
            fb->m_appliedForceBodyB += row.m_contactNormal2 * impulse * inv_h;
            fb->m_appliedTorqueBodyB += row.m_relpos2CrossNormal * impulse * inv_h;
        }
        constraint->internalSetAppliedImpulse(impulse);
        if (btFabs(impulse) >= constraint->getBreakingImpulseThreshold()) constraint->setEnabled(false);
    }
}

}  // namespace shatter
