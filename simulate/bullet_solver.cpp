#include "simulate/bullet_solver.h"

#include <vector>

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>

#include "simulate/compliant_constraint.h"

namespace shatter {

// The joint rows' system of one solve: K = J M^-1 J^T + diag(CFM), factored.
struct PieceSolver::Direct {
    Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt;
    Eigen::VectorXd residual, correction;
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

// A joint row's equation, as Bullet's row update reads it (solve_row): the row is satisfied when
//   rhs - cfm l - (J dv) jacDiagABInv = 0,
// rhs and cfm being pre-multiplied by jacDiagABInv = 1 / (J M^-1 J^T) of the row alone. Divided by
// jacDiagABInv, over all joint rows with dv = M^-1 J^T l + (the contacts' part):
//   (J M^-1 J^T + diag(cfm / jacDiagABInv)) l = rhs / jacDiagABInv - J dv_contacts.
// K's entry for rows i and j is the sum over the bodies they share of J_i,b . M_b^-1 J_j,b^T: the
// row's direction for that body (contactNormal, relposCrossNormal) against what an impulse on
// row j does to it (contactNormal x inverse mass, angularComponent = I^-1 relposCrossNormal).
void PieceSolver::factor_joints() {
    const int n = m_tmpSolverNonContactConstraintPool.size();
    // The rows at each dynamic solver body, with the side (A or B) they act on it from.
    std::vector<std::vector<std::pair<int, bool>>> at_body(size_t(m_tmpSolverBodyPool.size()));
    for (int r = 0; r < n; ++r) {
        const btSolverConstraint& row = m_tmpSolverNonContactConstraintPool[r];
        at_body[size_t(row.m_solverBodyIdA)].push_back({r, true});
        at_body[size_t(row.m_solverBodyIdB)].push_back({r, false});
    }
    std::vector<Eigen::Triplet<double>> entries;
    for (int r = 0; r < n; ++r) {
        const btSolverConstraint& row = m_tmpSolverNonContactConstraintPool[r];
        // The row alone: 1 / jacDiagABInv, as Bullet computed it, plus its CFM.
        const double diag = row.m_jacDiagABInv != 0 ? (1.0 + double(row.m_cfm)) / double(row.m_jacDiagABInv) : 1.0;
        entries.emplace_back(r, r, diag);
    }
    for (size_t b = 0; b < at_body.size(); ++b) {
        const btSolverBody& body = m_tmpSolverBodyPool[int(b)];
        const auto& rows = at_body[b];
        if (rows.size() < 2 || body.internalGetInvMass().isZero()) continue;
        for (size_t x = 0; x < rows.size(); ++x) {
            const btSolverConstraint& ri = m_tmpSolverNonContactConstraintPool[rows[x].first];
            const btVector3& lin_i = rows[x].second ? ri.m_contactNormal1 : ri.m_contactNormal2;
            const btVector3& ang_i = rows[x].second ? ri.m_relpos1CrossNormal : ri.m_relpos2CrossNormal;
            for (size_t y = 0; y < rows.size(); ++y) {
                if (rows[x].first == rows[y].first) continue;  // the diagonal is the row's own
                const btSolverConstraint& rj = m_tmpSolverNonContactConstraintPool[rows[y].first];
                const btVector3& lin_j = rows[y].second ? rj.m_contactNormal1 : rj.m_contactNormal2;
                const btVector3& dw_j = rows[y].second ? rj.m_angularComponentA : rj.m_angularComponentB;
                const double k = double(lin_i.dot(lin_j * body.internalGetInvMass()) + ang_i.dot(dw_j));
                if (k != 0) entries.emplace_back(rows[x].first, rows[y].first, k);
            }
        }
    }
    Eigen::SparseMatrix<double> K(n, n);
    K.setFromTriplets(entries.begin(), entries.end());  // duplicates (rows sharing both bodies) are summed
    Direct& d = *direct_system_;
    d.ldlt.compute(K);
    d.ok = d.ldlt.info() == Eigen::Success;
    d.residual.resize(n);
}

btScalar PieceSolver::solve_joints_directly() {
    Direct& d = *direct_system_;
    const int n = m_tmpSolverNonContactConstraintPool.size();
    for (int r = 0; r < n; ++r) {
        const btSolverConstraint& c = m_tmpSolverNonContactConstraintPool[r];
        btSolverBody& a = m_tmpSolverBodyPool[c.m_solverBodyIdA];
        btSolverBody& b = m_tmpSolverBodyPool[c.m_solverBodyIdB];
        const btScalar jv = c.m_contactNormal1.dot(a.internalGetDeltaLinearVelocity()) +
                            c.m_relpos1CrossNormal.dot(a.internalGetDeltaAngularVelocity()) +
                            c.m_contactNormal2.dot(b.internalGetDeltaLinearVelocity()) +
                            c.m_relpos2CrossNormal.dot(b.internalGetDeltaAngularVelocity());
        d.residual[r] = c.m_jacDiagABInv != 0
                            ? double((c.m_rhs - btScalar(c.m_appliedImpulse) * c.m_cfm) / c.m_jacDiagABInv - jv)
                            : 0.0;
    }
    d.correction = d.ldlt.solve(d.residual);
    btScalar largest = 0, most = 0;
    for (int r = 0; r < n; ++r) {
        btSolverConstraint& c = m_tmpSolverNonContactConstraintPool[r];
        const btScalar delta = btScalar(d.correction[r]);
        c.m_appliedImpulse = btScalar(c.m_appliedImpulse) + delta;
        m_tmpSolverBodyPool[c.m_solverBodyIdA].internalApplyImpulse(
            c.m_contactNormal1 * m_tmpSolverBodyPool[c.m_solverBodyIdA].internalGetInvMass(), c.m_angularComponentA, delta);
        m_tmpSolverBodyPool[c.m_solverBodyIdB].internalApplyImpulse(
            c.m_contactNormal2 * m_tmpSolverBodyPool[c.m_solverBodyIdB].internalGetInvMass(), c.m_angularComponentB, delta);
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
    if (!(tolerance_ > 0) || m_tmpSolverNonContactConstraintPool.size() == 0)
        return btSequentialImpulseConstraintSolver::solveGroupCacheFriendlyIterations(
            bodies, numBodies, manifolds, numManifolds, constraints, numConstraints, info, debugDrawer);
    // Bullet's loop (split-impulse pass, then `own` iterations: Bullet's residual threshold is 0,
    // so it never stops early), then more until the joints converge.
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
    most_iterations_ = btMax(most_iterations_, iteration);
    return 0;
}

btScalar PieceSolver::solveGroupCacheFriendlyFinish(btCollisionObject** bodies, int numBodies,
                                                    const btContactSolverInfo& info) {
    write_back_joints(info);
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
