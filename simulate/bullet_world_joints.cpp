// The joints of BulletWorld (simulate/bullet_world.h): their state, forces, stretch, residuals
// and loads, as simulate and the automatic step read them.
#include <btBulletDynamicsCommon.h>

#include <algorithm>
#include <cmath>

#include "simulate/bullet_world.h"
#include "simulate/bullet_world_impl.h"

namespace shatter {

double BulletWorld::joint_tolerance() const {
    return setup_.direct_joints && !(setup_.converge_tolerance > 0) ? kDirectTolerance : setup_.converge_tolerance;
}

double BulletWorld::max_load() const {
    double load = 0;
    for (size_t c = 0; c < impl_->joints.size(); ++c) {
        if (!active(c) || !awake(c)) continue;
        const double f = force_on_a(c).norm(), s = strength(c);
        load = std::max(load, s > 0 ? f / s : (f > 0 ? INFINITY : 0.0));
    }
    return load;
}

double BulletWorld::approach_load() {
    Impl& m = *impl_;
    std::vector<double> scale(m.pieces.size(), 0.0);  // per piece: the largest sqrt(k / w) / strength
    bool any = false;
    for (size_t c = 0; c < m.joints.size(); ++c) {
        const auto& j = m.joints[c];
        if (!j.active || !j.constraint || !(j.strength > 0) || !Impl::awake(j)) continue;
        const double w = j.constraint->row_inverse_masses().maxCoeff();
        if (!(w > 0)) continue;
        const double s = std::sqrt(j.constraint->stiffness() / w) / j.strength;
        scale[j.piece_a] = std::max(scale[j.piece_a], s);
        scale[j.piece_b] = std::max(scale[j.piece_b], s);
        any = true;
    }
    if (!any) return 0;
    m.world.performDiscreteCollisionDetection();
    double load = 0;
    btDispatcher& d = m.dispatcher;
    for (int i = 0; i < d.getNumManifolds(); ++i) {
        const btPersistentManifold* manifold = d.getManifoldByIndexInternal(i);
        const btRigidBody* a = btRigidBody::upcast(manifold->getBody0());
        const btRigidBody* b = btRigidBody::upcast(manifold->getBody1());
        if (!a || !b) continue;
        auto scale_of = [&](const btRigidBody* body) {
            const int piece = body->getUserIndex();
            return piece >= 0 && size_t(piece) < scale.size() ? scale[size_t(piece)] : 0.0;
        };
        const double s = std::max(scale_of(a), scale_of(b));
        if (!(s > 0)) continue;
        for (int p = 0; p < manifold->getNumContacts(); ++p) {
            const btManifoldPoint& point = manifold->getContactPoint(p);
            if (!(point.getDistance() < 0)) continue;
            const btVector3 va = a->getVelocityInLocalPoint(point.getPositionWorldOnA() - a->getCenterOfMassPosition());
            const btVector3 vb = b->getVelocityInLocalPoint(point.getPositionWorldOnB() - b->getCenterOfMassPosition());
            const double approach = -double((va - vb).dot(point.m_normalWorldOnB));  // the normal points from B to A
            load = std::max(load, approach * s);
        }
    }
    return load;
}

double BulletWorld::joint_frequency(size_t c) const {
    if (!active(c) || !impl_->joints[c].constraint) return 0;
    const auto& j = *impl_->joints[c].constraint;
    return std::sqrt(j.stiffness() * j.row_inverse_masses().maxCoeff());
}

void BulletWorld::joint_frequencies(double* highest, double* lowest) const {
    *highest = 0, *lowest = 0;
    for (size_t c = 0; c < impl_->joints.size(); ++c) {
        if (!active(c) || !impl_->joints[c].constraint || !awake(c)) continue;
        const auto& j = *impl_->joints[c].constraint;
        const Vec3 w = j.row_inverse_masses();
        const double high = std::sqrt(j.stiffness() * w.maxCoeff()), low = std::sqrt(j.stiffness() * w.minCoeff());
        *highest = std::max(*highest, high);
        *lowest = *lowest == 0 ? low : std::min(*lowest, low);
    }
}

int BulletWorld::last_step_iterations() const { return impl_->solver.most_iterations(); }

size_t BulletWorld::constraint_count() const { return impl_->joints.size(); }

bool BulletWorld::active(size_t c) const { return impl_->joints[c].active; }

double BulletWorld::strength(size_t c) const { return impl_->joints[c].strength; }

double BulletWorld::stiffness(size_t c) const {
    const auto& j = impl_->joints[c];
    return j.constraint ? j.constraint->stiffness() : 0.0;
}

Vec3 BulletWorld::force_on_a(size_t c) const {
    const auto& j = impl_->joints[c];
    return j.constraint ? to_eigen(j.constraint->feedback().m_appliedForceBodyA) : Vec3::Zero();
}

Vec3 BulletWorld::load_on_a(size_t c) const {
    const auto& j = impl_->joints[c];
    return j.constraint ? to_eigen(j.constraint->load().m_appliedForceBodyA) : Vec3::Zero();
}

bool BulletWorld::bullet_disabled(size_t c) const {
    const auto& j = impl_->joints[c];
    return j.active && j.constraint && !j.constraint->isEnabled();
}

void BulletWorld::enable(size_t c) {
    impl_->residual_known = false;
    const auto& j = impl_->joints[c];
    if (j.constraint) j.constraint->setEnabled(true);
}

double BulletWorld::max_cfm(size_t c) const {
    const auto& j = impl_->joints[c];
    return j.constraint ? j.constraint->last_max_cfm() : 0.0;
}

double BulletWorld::current_max_cfm(size_t c, double* min_w) const {
    const auto& j = impl_->joints[c];
    *min_w = 0;
    if (!j.constraint) return 0;
    const Vec3 w = j.constraint->row_inverse_masses();
    *min_w = w.minCoeff();
    return j.constraint->row_cfm(*min_w);  // CFM falls as w grows: the lightest row has the largest
}

uint32_t BulletWorld::piece_a(size_t c) const { return impl_->joints[c].piece_a; }

uint32_t BulletWorld::piece_b(size_t c) const { return impl_->joints[c].piece_b; }

BulletWorld::JointStretch BulletWorld::joint_stretch(size_t c) const {
    const auto& j = impl_->joints[c];
    JointStretch out;
    if (!j.constraint) return out;
    const CompliantPointConstraint& k = *j.constraint;
    const btRigidBody& a = k.getRigidBodyA();
    const btRigidBody& b = k.getRigidBodyB();
    const btVector3 pa = a.getWorldTransform() * k.getPivotInA();
    const btVector3 pb = b.getWorldTransform() * k.getPivotInB();
    out.stretch = to_eigen(pb - pa);
    out.rate = to_eigen(b.getVelocityInLocalPoint(pb - b.getCenterOfMassPosition()) -
                        a.getVelocityInLocalPoint(pa - a.getCenterOfMassPosition()));
    out.force_on_a = to_eigen(k.load().m_appliedForceBodyA);
    return out;
}

double BulletWorld::joint_residual(size_t c) const {
    const auto& j = impl_->joints[c];
    if (!j.active || !j.constraint || !(j.strength > 0)) return 0;
    const JointStretch s = joint_stretch(c);
    return Impl::spring_residual(j, s.stretch, s.rate, s.force_on_a);
}

double BulletWorld::max_joint_residual(int64_t* worst) const {
    if (impl_->residual_known) {
        *worst = impl_->residual_worst;
        return impl_->residual_max;
    }
    double most = 0;
    *worst = -1;
    for (size_t c = 0; c < impl_->joints.size(); ++c) {
        if (!awake(c)) continue;
        const double r = joint_residual(c);
        if (r > most) most = r, *worst = int64_t(c);
    }
    return most;
}

}  // namespace shatter
