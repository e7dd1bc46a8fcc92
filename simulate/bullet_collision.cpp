#include "simulate/bullet_collision.h"

#include <BulletCollision/NarrowPhaseCollision/btGjkPairDetector.h>
#include <BulletCollision/NarrowPhaseCollision/btVoronoiSimplexSolver.h>

namespace shatter {


namespace {

// Over-estimates of how far any point r from a body's centre can have moved towards -axis (for
// the body on side A) between two transforms: -axis.(c1 - c0) + |R1 - R0|_F r.
btScalar approach(const btTransform& t0, const btTransform& t1, const btVector3& axis, btScalar radius) {
    btScalar f2 = 0;
    for (int r = 0; r < 3; ++r) f2 += (t1.getBasis()[r] - t0.getBasis()[r]).length2();
    return -axis.dot(t1.getOrigin() - t0.getOrigin()) + btSqrt(f2) * radius;
}

// The farthest a hull's point (margin included) can be from its body's centre.
btScalar reach(const btConvexShape* s) {
    btVector3 lo, hi;
    s->getAabb(btTransform::getIdentity(), lo, hi);
    btVector3 corner = lo.absolute();
    corner.setMax(hi.absolute());
    return corner.length();
}

}  // namespace

bool PieceConvexAlgorithm::measure_gap(const btConvexShape* sa, const btConvexShape* sb, const btTransform& ta,
                                       const btTransform& tb) {
    const btVector3 pa = ta(sa->localGetSupportVertexWithoutMarginNonVirtual((-axis_) * ta.getBasis()));
    const btVector3 pb = tb(sb->localGetSupportVertexWithoutMarginNonVirtual(axis_ * tb.getBasis()));
    gap_ = axis_.dot(pa - pb);
    ta_ = ta, tb_ = tb;
    has_gap_ = gap_ > needed_;
    return has_gap_;
}

void PieceConvexAlgorithm::processCollision(const btCollisionObjectWrapper* a, const btCollisionObjectWrapper* b,
                                            const btDispatcherInfo& info, btManifoldResult* out) {
    btPersistentManifold* manifold = const_cast<btPersistentManifold*>(getManifold());
    if (!own_ || !manifold || out->m_closestPointDistanceThreshold != 0) {
        // The first call makes the manifold; a compound's part shares its compound's.
        btConvexConvexAlgorithm::processCollision(a, b, info, out);
        return;
    }
    const auto* shape_a = static_cast<const btConvexShape*>(a->getCollisionShape());
    const auto* shape_b = static_cast<const btConvexShape*>(b->getCollisionShape());
    const btTransform& ta = a->getWorldTransform();
    const btTransform& tb = b->getWorldTransform();
    if (empty_ && has_axis_) {
        if (has_gap_ && gap_ - approach(ta_, ta, axis_, radius_a_) - approach(tb_, tb, -axis_, radius_b_) > needed_) {
            return;
        }
        if (measure_gap(shape_a, shape_b, ta, tb)) {
            return;
        }
    }
    // btConvexConvexAlgorithm::processCollision for two hulls without polyhedral features and
    // without perturbation, keeping GJK's separating axis.
    const btScalar margins = shape_a->getMarginNonVirtual() + shape_b->getMarginNonVirtual();
    const btScalar threshold = manifold->getContactBreakingThreshold();
    out->setPersistentManifold(manifold);
    btGjkPairDetector::ClosestPointInput input;
    btVoronoiSimplexSolver simplex;
    btGjkPairDetector gjk(shape_a, shape_b, &simplex, pd_);
    gjk.setMinkowskiA(shape_a);
    gjk.setMinkowskiB(shape_b);
    input.m_maximumDistanceSquared = margins + threshold + out->m_closestPointDistanceThreshold;
    input.m_maximumDistanceSquared *= input.m_maximumDistanceSquared;
    input.m_transformA = ta;
    input.m_transformB = tb;
    gjk.getClosestPoints(input, *out, info.m_debugDraw);
    out->refreshContactPoints();
    empty_ = manifold->getNumContacts() == 0;
    has_gap_ = false;
    const btVector3 axis = gjk.getCachedSeparatingAxis();
    const btScalar length2 = axis.length2();
    has_axis_ = empty_ && length2 > SIMD_EPSILON;
    if (!has_axis_) return;
    axis_ = axis / btSqrt(length2);
    // The factor and the nanometre: room for rounding in GJK's distance, in the axis' length and
    // in the motion bound.
    needed_ = btScalar(1.001) * (margins + threshold) + btScalar(1e-9);
    radius_a_ = reach(shape_a) * btScalar(1.001);
    radius_b_ = reach(shape_b) * btScalar(1.001);
    measure_gap(shape_a, shape_b, ta, tb);
}

void exact_aabb_near_callback(btBroadphasePair& pair, btCollisionDispatcher& dispatcher,
                              const btDispatcherInfo& info) {
    const btBroadphaseProxy* a = pair.m_pProxy0;
    const btBroadphaseProxy* b = pair.m_pProxy1;
    if (!TestAabbAgainstAabb2(a->m_aabbMin, a->m_aabbMax, b->m_aabbMin, b->m_aabbMax)) {
        if (pair.m_algorithm) {
            pair.m_algorithm->~btCollisionAlgorithm();
            dispatcher.freeCollisionAlgorithm(pair.m_algorithm);
            pair.m_algorithm = nullptr;
        }
        return;
    }
    btCollisionDispatcher::defaultNearCallback(pair, dispatcher, info);
}

void PieceWorld::updateAabbs() {
    for (int i = 0; i < m_collisionObjects.size(); i++) {
        btCollisionObject* o = m_collisionObjects[i];
        if (!(m_forceUpdateAllAabbs || o->isActive())) continue;
        const btCollisionShape* shape = o->getCollisionShape();
        const btScalar t = shape->getContactBreakingThreshold(gContactBreakingThreshold);
        const btVector3 pad(t, t, t);
        btVector3 lo, hi;
        shape->getAabb(o->getWorldTransform(), lo, hi);
        lo -= pad, hi += pad;
        if (getDispatchInfo().m_useContinuous && o->getInternalType() == btCollisionObject::CO_RIGID_BODY &&
            !o->isStaticOrKinematicObject()) {
            btVector3 lo2, hi2;
            shape->getAabb(o->getInterpolationWorldTransform(), lo2, hi2);
            lo.setMin(lo2 - pad);
            hi.setMax(hi2 + pad);
        }
        m_broadphasePairCache->setAabb(o->getBroadphaseHandle(), lo, hi, m_dispatcher1);
    }
}

}  // namespace shatter
