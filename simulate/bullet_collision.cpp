#include "simulate/bullet_collision.h"

namespace shatter {

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
