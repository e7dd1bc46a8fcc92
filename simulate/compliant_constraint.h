// A btPoint2PointConstraint that is a spring-damper of stiffness k and damping c in physical
// units: ERP from k, c and h; each of its three rows gets its own CFM from its own inverse
// effective mass, recomputed every step as the bodies turn (simulate/spring.h). It also carries
// the joint feedback that breaking and energizing read.
#pragma once

#include <btBulletDynamicsCommon.h>

#include "core/geometry.h"

namespace shatter {

class CompliantPointConstraint : public btPoint2PointConstraint {
public:
    CompliantPointConstraint(btRigidBody& a, btRigidBody& b, const btVector3& pivot_in_a, const btVector3& pivot_in_b,
                             double stiffness, double damping, double h);

    void getInfo2(btConstraintInfo2* info) override;
    // btPoint2PointConstraint builds Jacobian entries here for Bullet's obsolete solver path,
    // which the sequential-impulse solver never reads (it uses getInfo2): measured 5% of a
    // 1,000-piece step, skipped.
    void buildJacobian() override {}

    // The three rows' inverse effective masses w (world x, y, z) with the bodies as they are now.
    Vec3 row_inverse_masses() const;
    // The CFM of a row with inverse effective mass w at this constraint's k, c and h.
    double row_cfm(double w) const;

    // A new solver step h (the automatic step): ERP and the rows' CFM follow it.
    void set_step(double h);
    double step() const { return h_; }  // (unit: s)
    double stiffness() const { return k_; }
    double damping() const { return c_; }
    // The force at which it breaks (unit: N): the scale of its convergence residual.
    double strength() const { return strength_; }
    void set_strength(double strength) { strength_ = strength; }
    // The largest row CFM of the last step (1 / (w h (h k + c)) over the three rows).
    double last_max_cfm() const { return last_max_cfm_; }
    const btJointFeedback& feedback() const { return feedback_; }
    // The load of the split-impulse push on the joint (PieceSolver::push_joints): the force its
    // stretch by the step's push adds to the spring, as feedback() has the solve's. The step's
    // solve made the pieces' velocities from feedback() alone (the books' work), but the joint's
    // stretch at the step's end is both, and so is what it holds and stores.
    btJointFeedback& push_feedback() { return push_feedback_; }
    const btJointFeedback& push_feedback() const { return push_feedback_; }
    // What its stretch holds at the step's end: feedback() and push_feedback() together, the load
    // that breaks it and that it stores.
    btJointFeedback load() const;

private:
    double k_, c_, h_;
    double strength_ = 0;
    double last_max_cfm_ = 0;
    btJointFeedback feedback_;
    btJointFeedback push_feedback_;
};

}  // namespace shatter
