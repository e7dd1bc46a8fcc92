#include "simulate/compliant_constraint.h"

#include <algorithm>

#include "simulate/bullet_convert.h"
#include "simulate/spring.h"

namespace shatter {
namespace {

void clear(btJointFeedback& f) {
    for (btVector3* v : {&f.m_appliedForceBodyA, &f.m_appliedTorqueBodyA, &f.m_appliedForceBodyB, &f.m_appliedTorqueBodyB})
        v->setZero();
}

}  // namespace

CompliantPointConstraint::CompliantPointConstraint(btRigidBody& a, btRigidBody& b, const btVector3& pivot_in_a,
                                                   const btVector3& pivot_in_b, double stiffness, double damping,
                                                   double h)
    : btPoint2PointConstraint(a, b, pivot_in_a, pivot_in_b), k_(stiffness), c_(damping), h_(h) {
    setParam(BT_CONSTRAINT_ERP, btScalar(spring_erp(k_, c_, h_)), -1);  // only axis -1 is honoured
    setJointFeedback(&feedback_);
    clear(push_feedback_);
}

Vec3 CompliantPointConstraint::row_inverse_masses() const {
    const btRigidBody& a = getRigidBodyA();
    const btRigidBody& b = getRigidBodyB();
    const Vec3 ra = to_eigen(a.getWorldTransform().getBasis() * getPivotInA());
    const Vec3 rb = to_eigen(b.getWorldTransform().getBasis() * getPivotInB());
    const Mat3 ia = to_eigen(a.getInvInertiaTensorWorld());
    const Mat3 ib = to_eigen(b.getInvInertiaTensorWorld());
    Vec3 w;
    for (int j = 0; j < 3; ++j) w[j] = row_inverse_mass(a.getInvMass(), ia, ra, b.getInvMass(), ib, rb, Vec3::Unit(j));
    return w;
}

btJointFeedback CompliantPointConstraint::load() const {
    btJointFeedback sum;
    sum.m_appliedForceBodyA = feedback_.m_appliedForceBodyA + push_feedback_.m_appliedForceBodyA;
    sum.m_appliedTorqueBodyA = feedback_.m_appliedTorqueBodyA + push_feedback_.m_appliedTorqueBodyA;
    sum.m_appliedForceBodyB = feedback_.m_appliedForceBodyB + push_feedback_.m_appliedForceBodyB;
    sum.m_appliedTorqueBodyB = feedback_.m_appliedTorqueBodyB + push_feedback_.m_appliedTorqueBodyB;
    return sum;
}

double CompliantPointConstraint::row_cfm(double w) const { return spring_cfm(k_, c_, h_, w); }

void CompliantPointConstraint::set_step(double h) {
    h_ = h;
    setParam(BT_CONSTRAINT_ERP, btScalar(spring_erp(k_, c_, h_)), -1);
}

void CompliantPointConstraint::getInfo2(btConstraintInfo2* info) {
    btPoint2PointConstraint::getInfo2(info);
    clear(push_feedback_);  // solved again: the solver's write-back sets it when the step pushes
    // A driven (kinematic) body is already where its script has it at the step's end when the
    // joints are solved, and its motion within the step comes in again through its velocity: the
    // error is counted from where its pivot was at the step's start, so that the drive moves the
    // joint once. (Counted twice, a link pulled at 1.1 cm/s in steps of 1/480 s ran ahead of the
    // end cube by a step's motion, 23 um, past its own breaking stretch of 17 um.)
    const btRigidBody& a = getRigidBodyA();
    const btRigidBody& b = getRigidBodyB();
    if (a.isKinematicObject() || b.isKinematicObject()) {
        btVector3 drive(0, 0, 0);
        if (a.isKinematicObject()) drive += a.getVelocityInLocalPoint(a.getWorldTransform().getBasis() * getPivotInA());
        if (b.isKinematicObject()) drive -= b.getVelocityInLocalPoint(b.getWorldTransform().getBasis() * getPivotInB());
        const btScalar erp = getParam(BT_CONSTRAINT_ERP, -1);
        for (int j = 0; j < 3; ++j) info->m_constraintError[j * info->rowskip] += erp * drive[j];
    }
    const Vec3 w = row_inverse_masses();
    last_max_cfm_ = 0;
    for (int j = 0; j < 3; ++j) {
        const double cfm = row_cfm(w[j]);
        info->cfm[j * info->rowskip] = btScalar(cfm);
        last_max_cfm_ = std::max(last_max_cfm_, cfm);
    }
}

}  // namespace shatter
