// The energy books of BulletWorld (simulate/bullet_world.h): what each step's joints, contacts,
// driven pieces and integration did (account_step, step_work), and the energies the books count.
#include <btBulletDynamicsCommon.h>

#include <cmath>

#include "simulate/bullet_world.h"
#include "simulate/bullet_world_impl.h"

namespace shatter {

namespace {

// The mean of a body's velocity at the point p before and after the step: `linear` and
// `angular` its velocities at the start, `centre` its centre of mass then, where the solver took
// the lever arm p - centre of the impulses it applied at p. (The lever arm after the step is off
// by the step's turn: 1.4% of the work on a link spinning at 170 rad/s, at 1/30,000 s.)
btVector3 mean_velocity(const btRigidBody& b, const btVector3& linear, const btVector3& angular, const btVector3& centre,
                        const btVector3& p) {
    const btVector3 r = p - centre;
    return 0.5 * (b.getLinearVelocity() + b.getAngularVelocity().cross(r) + linear + angular.cross(r));
}

}  // namespace

BulletWorld::StepWork BulletWorld::step_work() const { return impl_->work; }

void BulletWorld::Impl::account_step(double h_step) {
    residual_max = 0;
    residual_worst = -1;
    deepest = {};
    // Work w done on body b, added to a dynamic piece's sum or a driven one's (a driven piece or
    // prop, whose motion is scripted); static bodies do not move.
    auto add_work = [](const btRigidBody& b, double w, double* on_pieces, double* on_drivers) {
        // (A body of zero mass is flagged static even when it is kinematic.)
        if (b.isStaticObject() && !b.isKinematicObject()) return;
        *(b.isKinematicObject() ? on_drivers : on_pieces) += w;
    };
    // The work of the impulse P on body b at point p.
    auto work_of = [&](const btRigidBody& b, const btVector3& p, const btVector3& impulse, double* on_pieces,
                       double* on_drivers) {
        const Before& start = before[size_t(b.getUserIndex2())];
        add_work(b, double(impulse.dot(mean_velocity(b, start.linear, start.angular, start.pose.getOrigin(), p))),
                 on_pieces, on_drivers);
    };
    // In rigid flight the joints were not solved (no impulse) and their pieces moved alike.
    // A sleeping island was neither solved nor moved: its joints' feedback is their last solve's.
    for (size_t c = 0; c < (flying ? 0 : joints.size()); ++c) {
        Joint& j = joints[c];
        if (!j.active || !j.constraint || !awake(j)) continue;
        const CompliantPointConstraint& k = *j.constraint;
        const btRigidBody& a = k.getRigidBodyA();
        const btRigidBody& b = k.getRigidBodyB();
        const btVector3 force = k.feedback().m_appliedForceBodyA;
        const btVector3 impulse = force * btScalar(k.step());
        const btVector3 pa = a.getWorldTransform() * k.getPivotInA(), pb = b.getWorldTransform() * k.getPivotInB();
        double pieces = 0, drivers = 0;
        work_of(a, before[size_t(a.getUserIndex2())].pose * k.getPivotInA(), impulse, &pieces, &drivers);
        work_of(b, before[size_t(b.getUserIndex2())].pose * k.getPivotInB(), -impulse, &pieces, &drivers);
        const Vec3 stretch = to_eigen(pb - pa);
        const double e = 0.5 * k.stiffness() * stretch.squaredNorm();
        // The joint's residual (BulletWorld::joint_residual, the same arithmetic), for the step's largest.
        if (j.strength > 0) {
            const Vec3 rate = to_eigen(b.getVelocityInLocalPoint(pb - b.getCenterOfMassPosition()) -
                                       a.getVelocityInLocalPoint(pa - a.getCenterOfMassPosition()));
            const double r = spring_residual(j, stretch, rate, to_eigen(k.load().m_appliedForceBodyA));
            if (r > residual_max) residual_max = r, residual_worst = int64_t(c);
        }
        // The joint gave the pieces `pieces`, the drivers `drivers`, and stored e - elastic[c]:
        // what is left of nothing it took away.
        work.joints += -(pieces + drivers) - (e - elastic[c]);
        work.driven -= drivers;
        elastic[c] = e;
    }
    for (int i = 0; i < dispatcher.getNumManifolds(); ++i) {
        btPersistentManifold* manifold = dispatcher.getManifoldByIndexInternal(i);
        const auto* a = btRigidBody::upcast(manifold->getBody0());
        const auto* b = btRigidBody::upcast(manifold->getBody1());
        if (!a || !b || !(moving(*a) || moving(*b))) continue;  // kept from before a sleep
        for (int p = 0; p < manifold->getNumContacts(); ++p) {
            const btManifoldPoint& point = manifold->getContactPoint(p);
            if (point.getDistance() < 0)
                for (const btRigidBody* body : {a, b}) {
                    const int piece = body->getUserIndex();  // -1: not a piece
                    if (piece < 0) continue;
                    const PieceBody& pb = pieces[size_t(piece)];
                    const double depth = -double(point.getDistance());
                    if (pb.dynamic && pb.radius > 0 && depth > deepest.depth_per_radius * pb.radius)
                        deepest = {depth / pb.radius, depth, uint32_t(piece)};
                }
            const btVector3 impulse = point.m_normalWorldOnB * point.m_appliedImpulse +
                                      point.m_lateralFrictionDir1 * point.m_appliedImpulseLateral1 +
                                      point.m_lateralFrictionDir2 * point.m_appliedImpulseLateral2;
            double pieces = 0, drivers = 0;
            work_of(*a, point.getPositionWorldOnA(), impulse, &pieces, &drivers);
            work_of(*b, point.getPositionWorldOnB(), -impulse, &pieces, &drivers);
            work.contacts += -(pieces + drivers);
            work.driven -= drivers;
        }
    }
    // The step's integration (StepWork::integration): gravity's, and the turn's.
    for (size_t i = 0; i < bodies.size(); ++i) {
        const btRigidBody& b = *bodies[i];
        if (b.isStaticOrKinematicObject() || !(b.getInvMass() > 0)) continue;
        const Before& start = before[i];
        if (asleep(b)) {
            // Asleep: unmoved, and its velocity set to zero as its island fell asleep (what is
            // left at rest, below the sleeping thresholds, is taken as friction would take it);
            // nothing to book in the steps it sleeps through.
            if (start.linear.isZero() && start.angular.isZero()) continue;
            const btVector3 l = start.angular * start.inv_inertia.inverse();
            work.contacts += 0.5 * (double(start.linear.length2()) / double(b.getInvMass()) + double(l.dot(start.angular)));
            continue;
        }
        // (Rigid flight moves the pieces on the parabola exactly: nothing to book.)
        if (flying && b.getUserIndex() >= 0) continue;
        const btVector3 dv = b.getLinearVelocity() - start.linear;
        work.integration += 0.5 * h_step / double(b.getInvMass()) * double(b.getGravity().dot(dv));
        const btVector3& w1 = b.getAngularVelocity();
        const btVector3 mean = 0.5 * (w1 + start.angular);
        const btMatrix3x3 inertia0 = start.inv_inertia.inverse(), inertia1 = b.getInvInertiaTensorWorld().inverse();
        work.integration -= 0.5 * double(w1.dot((inertia1 - inertia0) * w1)) + double(mean.dot(inertia0 * start.gyroscopic));
    }
    // The contacts' pushes out of penetration (split impulse): a body moved by dx gains potential
    // energy -m g . dx that no impulse gave (its joints' stretch goes to their column above).
    for (const PieceSolver::Push& p : solver.pushes()) {
        if (p.body->isStaticOrKinematicObject() || !(p.body->getInvMass() > 0)) continue;
        work.contacts += double(p.body->getGravity().dot(p.velocity)) * h_step / double(p.body->getInvMass());
    }
    // The contacts' rolling and spinning friction: angular impulses T, each doing T . (mean
    // angular velocity) on its body.
    for (const PieceSolver::AngularImpulse& t : solver.rolling_friction()) {
        const Before& start = before[size_t(t.body->getUserIndex2())];
        double pieces = 0, drivers = 0;
        add_work(*t.body, double(t.impulse.dot(0.5 * (t.body->getAngularVelocity() + start.angular))), &pieces, &drivers);
        work.contacts += -(pieces + drivers);
        work.driven -= drivers;
    }
    residual_known = true;
}

namespace {

// In a frame moving at `frame`, `inertia` the body's inertia tensor in the world frame.
double body_kinetic_energy(const btRigidBody& b, const Mat3& inertia, const Vec3& frame = Vec3::Zero()) {
    const Vec3 v = to_eigen(b.getLinearVelocity()) - frame, w = to_eigen(b.getAngularVelocity());
    return 0.5 * v.squaredNorm() / b.getInvMass() + 0.5 * w.dot(inertia * w);
}

Mat3 inertia_tensor(const btRigidBody& b) { return to_eigen(b.getInvInertiaTensorWorld()).inverse(); }

double body_kinetic_energy(const btRigidBody& b) { return body_kinetic_energy(b, inertia_tensor(b)); }

}  // namespace

double BulletWorld::kinetic_energy() const {
    double e = 0;
    for (const auto& p : impl_->pieces)
        if (p.dynamic) e += body_kinetic_energy(*p.body);
    for (const btRigidBody* b : impl_->projectiles) e += body_kinetic_energy(*b);
    return e;
}

void BulletWorld::kinetic_energies_of(const std::vector<uint32_t>& pieces, const Vec3& frame, double* in_frame,
                                      double* in_world, std::vector<Mat3>* inertia) const {
    const bool known = !inertia->empty();
    double e = 0, e_world = 0;
    size_t k = 0;
    for (uint32_t p : pieces) {
        if (!impl_->pieces[p].dynamic) continue;
        const btRigidBody& b = *impl_->pieces[p].body;
        if (!known) inertia->push_back(inertia_tensor(b));
        const Mat3& tensor = (*inertia)[k++];
        e += body_kinetic_energy(b, tensor, frame);
        e_world += body_kinetic_energy(b, tensor);
    }
    *in_frame = e;
    *in_world = e_world;
}

double BulletWorld::potential_energy() const {
    double e = 0;
    for (const auto& p : impl_->pieces)
        if (p.dynamic) e -= impl_->gravity.dot(to_eigen(p.body->getCenterOfMassPosition())) / p.body->getInvMass();
    for (const btRigidBody* b : impl_->projectiles)
        e -= impl_->gravity.dot(to_eigen(b->getCenterOfMassPosition())) / b->getInvMass();
    return e;
}

double BulletWorld::Impl::joint_elastic(const Joint& j) {
    const CompliantPointConstraint& k = *j.constraint;
    const btVector3 d = k.getRigidBodyB().getWorldTransform() * k.getPivotInB() -
                        k.getRigidBodyA().getWorldTransform() * k.getPivotInA();
    return 0.5 * k.stiffness() * double(d.length2());
}

double BulletWorld::Impl::stored_energy_of(const Joint& j) {
    return shatter::stored_energy(to_eigen(j.constraint->load().m_appliedForceBodyA), j.constraint->stiffness());
}

double BulletWorld::stored_energy() const {
    double e = 0;
    for (const auto& j : impl_->joints)
        if (j.active) e += Impl::stored_energy_of(j);
    return e;
}

double BulletWorld::elastic_energy() const {
    double e = 0;
    for (const auto& j : impl_->joints)
        if (j.active && j.constraint) e += Impl::joint_elastic(j);
    return e;
}

Vec3 BulletWorld::linear_momentum() const {
    Vec3 p = Vec3::Zero();
    for (const auto& pb : impl_->pieces)
        if (pb.dynamic) p += to_eigen(pb.body->getLinearVelocity()) / pb.body->getInvMass();
    return p;
}

Vec3 BulletWorld::angular_momentum() const {
    Vec3 l = Vec3::Zero();
    for (const auto& pb : impl_->pieces) {
        if (!pb.dynamic) continue;
        const btRigidBody& b = *pb.body;
        const Vec3 x = to_eigen(b.getCenterOfMassPosition());
        const Vec3 v = to_eigen(b.getLinearVelocity());
        const Mat3 inv_i = to_eigen(b.getInvInertiaTensorWorld());
        l += x.cross(v / b.getInvMass()) + inv_i.inverse() * to_eigen(b.getAngularVelocity());
    }
    return l;
}

}  // namespace shatter
