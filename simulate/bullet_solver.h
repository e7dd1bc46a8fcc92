// Bullet's sequential-impulse solver, with two per-step costs removed that a structure of
// thousands of point constraints pays for nothing (measured on a 1,024-piece plate with 7,936
// constraints; docs/log.md):
// - Every iteration, btSequentialImpulseConstraintSolver::solveSingleIteration walks all
//   constraints to call solveConstraintObsolete, a no-op for every constraint type but the cone
//   twist, after looking up both solver bodies: ~10% of a step. We add only point constraints
//   (CompliantPointConstraint), so the walk is skipped.
// - writeBackJoints fills each constraint's btJointFeedback from its rows, reading both bodies'
//   linear and angular factors for every row: ~6% of a step, mostly cache misses. Our bodies keep
//   Bullet's unit factors (nothing here calls setLinearFactor or setAngularFactor), so the same
//   products come from the rows alone, bit for bit.
// - Setting up and writing back the joints' rows walks the constraints in island order, which is
//   not their order in memory: each constraint (704 bytes, ~7 cache lines touched) and its bodies
//   are a cache miss. convertJoints and the write-back prefetch a few constraints ahead: ~5% of a
//   step.
// - The iterations call Bullet's row update through a function pointer from a loop in another
//   library; ours inline it (the same arithmetic): ~2% of a step.
// - A joint row in Bullet's pool is 288 bytes, of which a pass over it reads 200 spread over five
//   cache lines; the 1,024-piece plate's 23,808 rows are 6.9 MB, more than a core's cache, so each
//   of a step's passes streamed them from memory. The passes read a copy of the rows instead
//   (JointRow: 128 bytes, the axis implied): the point constraint's rows run along the world axes,
//   so the linear half of each dot product and impulse is one component, exactly.
// The results are the same bytes as with Bullet's own solver (tested).
#pragma once

#include <memory>
#include <vector>

#include <btBulletDynamicsCommon.h>

namespace shatter {

// Convergence (converge(), off by default): after the step's iterations, the joint rows (and the
// contacts with them) are iterated again until every joint's force matches its spring law within
// `tolerance` of its strength, or `max_iterations` is reached. A joint row's correction dl at its
// update is the impulse that would zero its equation; its force mismatch is dl / (h CFM)
// (docs/physics.md, "Joint convergence"). Only CompliantPointConstraints may be added.
//
// Direct joints (direct_joints(true), off by default): each iteration solves all joint rows of the
// batch at once instead of one row at a time: the linear system (J M^-1 J^T + CFM) dl = r of the
// rows' residuals r with the contacts' impulses held, factored once per step (a sparse LDL^T).
// Its solution is the fixed point Gauss-Seidel would reach after infinitely many passes, so a
// chain of a heavy and a light piece is as stiff as its springs say whatever their mass ratio;
// the contacts are still iterated around it (block Gauss-Seidel), and the joints are solved once
// more after the last iteration, so that their forces are exact for the contacts' final impulses.
// A contact that holds a light joined piece against the ground (or anything that does not move)
// is solved through the joints instead: its row weighs what the joints make it weigh, so a heavy
// stack standing on a light piece is held by its whole weight (anchor_contacts).
// The spring law, the CFM and the damping keep their meaning (docs/physics.md, "Direct joints").
class PieceSolver : public btSequentialImpulseConstraintSolver {
public:
    PieceSolver();
    ~PieceSolver() override;
    void direct_joints(bool on) { direct_ = on; }
    // Joined pushes (push_joints(true), off by default): the split-impulse pass that moves
    // penetrating pieces out by position also solves the joint rows on the push velocities (with
    // the direct solve when direct joints are on), so that a push moves joined pieces together
    // instead of stretching their joints.
    void push_joints(bool on) { push_joints_ = on; }
    void converge(double tolerance, int max_iterations) {
        tolerance_ = tolerance;
        max_iterations_ = max_iterations;
    }
    // Over the solves since reset_counts() (Bullet solves islands in batches, each its own call):
    // the most iterations one took, and the angular impulses of the contacts' rolling and
    // spinning friction rows, which Bullet keeps nowhere after the solve (a manifold point holds
    // only its normal and sliding friction impulses).
    // And the split impulse's pushes: each body's push velocity, by which the step moves it out of
    // penetration (position only).
    void reset_counts() {
        most_iterations_ = 0;
        rolling_.clear();
        pushes_.clear();
    }
    int most_iterations() const { return most_iterations_; }
    struct AngularImpulse {
        const btRigidBody* body;  // a dynamic or kinematic body
        btVector3 impulse;        // (unit: N m s)
    };
    const std::vector<AngularImpulse>& rolling_friction() const { return rolling_; }
    struct Push {
        const btRigidBody* body;  // a dynamic body
        btVector3 velocity;       // moves its centre of mass by velocity h (unit: m/s)
    };
    const std::vector<Push>& pushes() const { return pushes_; }

protected:
    btScalar solveGroupCacheFriendlyIterations(btCollisionObject** bodies, int numBodies,
                                               btPersistentManifold** manifolds, int numManifolds,
                                               btTypedConstraint** constraints, int numConstraints,
                                               const btContactSolverInfo& info, btIDebugDraw* debugDrawer) override;
    btScalar solveSingleIteration(int iteration, btCollisionObject** bodies, int numBodies,
                                  btPersistentManifold** manifolds, int numManifolds, btTypedConstraint** constraints,
                                  int numConstraints, const btContactSolverInfo& info,
                                  btIDebugDraw* debugDrawer) override;
    void convertJoints(btTypedConstraint** constraints, int numConstraints, const btContactSolverInfo& info) override;
    void solveGroupCacheFriendlySplitImpulseIterations(btCollisionObject** bodies, int numBodies,
                                                       btPersistentManifold** manifolds, int numManifolds,
                                                       btTypedConstraint** constraints, int numConstraints,
                                                       const btContactSolverInfo& info,
                                                       btIDebugDraw* debugDrawer) override;
    btScalar solveGroupCacheFriendlyFinish(btCollisionObject** bodies, int numBodies,
                                           const btContactSolverInfo& info) override;

private:
    btScalar solve_row(btSolverConstraint& row, bool upper_limit);
    // A point constraint's row as the passes read it (built by convertJoints from Bullet's row,
    // which gets the impulse back in write_back_joints): the row's axis is world axis `axis` on
    // body A and its opposite on body B, with Bullet's bounds (none: +-SIMD_INFINITY) and unit
    // linear and angular factors; used when every joint row of the solve is so, and the rows are
    // iterated (not solved directly) in Bullet's order.
    struct JointRow {
        btScalar relpos_a[3], relpos_b[3];  // m_relpos1CrossNormal, m_relpos2CrossNormal
        btScalar angular_a[3], angular_b[3];  // m_angularComponentA, m_angularComponentB
        btScalar rhs, cfm, jac_diag_inv, applied;
    };
    struct JointRowBodies {
        int a, b, axis;
    };
    // Copies Bullet's row (of solver bodies a and b); false when it is not a row JointRow holds.
    bool copy_joint_row(const btSolverConstraint& from, int a, int b, JointRow* to, JointRowBodies* bodies) const;
    btScalar solve_joint_row(JointRow& row, const JointRowBodies& bodies);
    std::vector<JointRow> joint_rows_;
    std::vector<JointRowBodies> joint_row_bodies_;
    bool compact_ = false;  // the passes read joint_rows_
    void factor_joints();
    void factor_body_space();
    // One direct solve of every joint row, on the velocities (or on the push velocities); the
    // largest correction (residual). `rows`: set each row's impulse and measure the correction
    // (else 0 is returned and the rows catch up at the next solve that sets them). `decide`: the
    // correction only decides whether the iterations go on (joint_residual_ is then measured up to
    // the first row past the tolerance, 0 is returned, and the rows catch up as above).
    btScalar solve_joints_directly(bool push = false, bool rows = true, bool decide = false);
    // Contacts that hold light joined pieces against what does not move, solved through the
    // joints: at most this many bodies' contacts, this many sweeps per iteration.
    static constexpr int kMaxAnchoredBodies = 32, kAnchoredSweeps = 8;
    static constexpr double kAnchoredGain = 10;
    static constexpr double kAnchoredRestSpeed = 0.1;  // (unit: m/s) along the contact's normal
    void anchor_contacts();
    btScalar solve_anchored_contacts();
    struct Direct;
    std::unique_ptr<Direct> direct_system_;
    bool direct_ = false;
    bool push_joints_ = false;
    bool pushed_ = false;  // this solve's push pass moved bodies with the joint rows solved
    void write_back_joints(const btContactSolverInfo& info);

    double tolerance_ = 0;
    int max_iterations_ = 0;
    bool extra_ = false;                 // in the iterations past the step's own count
    int own_iterations_ = 0;             // the step's own count
    btAlignedObjectArray<btScalar> row_scale_;  // per joint row: 1 / (h CFM strength)
    btScalar joint_residual_ = 0;        // of the current iteration
    int most_iterations_ = 0;
    std::vector<AngularImpulse> rolling_;
    std::vector<Push> pushes_;
};

}  // namespace shatter
