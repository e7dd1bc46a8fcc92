#include "simulate/bullet_collision.h"

#include <BulletCollision/CollisionDispatch/btConvexPlaneCollisionAlgorithm.h>
#include <BulletCollision/NarrowPhaseCollision/btGjkPairDetector.h>
#include <BulletCollision/NarrowPhaseCollision/btVoronoiSimplexSolver.h>

#include <typeinfo>

namespace shatter {

namespace {

// The farthest a hull's point (margin included) can be from its body's centre.
btScalar reach(const btConvexShape* s) {
    btVector3 lo, hi;
    s->getAabb(btTransform::getIdentity(), lo, hi);
    btVector3 corner = lo.absolute();
    corner.setMax(hi.absolute());
    return corner.length();
}

}  // namespace

bool PieceConvexAlgorithm::measure_gap(const btCollisionObjectWrapper* a, const btCollisionObjectWrapper* b) {
    has_gap_ = false;
    const auto* sa = static_cast<const btConvexShape*>(a->getCollisionShape());
    const auto* sb = static_cast<const btConvexShape*>(b->getCollisionShape());
    const btTransform& ta = a->getWorldTransform();
    const btTransform& tb = b->getWorldTransform();
    const btVector3 pa = ta(sa->localGetSupportVertexWithoutMarginNonVirtual((-axis_) * ta.getBasis()));
    const btVector3 pb = tb(sb->localGetSupportVertexWithoutMarginNonVirtual(axis_ * tb.getBasis()));
    gap_ = axis_.dot(pa - pb);
    if (!(gap_ > needed_)) return false;
    // The state for apart(), when the turns of both bodies are kept.
    const btBroadphaseProxy* proxy_a = a->getCollisionObject()->getBroadphaseHandle();
    const btBroadphaseProxy* proxy_b = b->getCollisionObject()->getBroadphaseHandle();
    const std::vector<btScalar>& turned = static_cast<PieceDispatcher*>(m_dispatcher)->turned;
    if (proxy_a && proxy_b && size_t(proxy_a->m_uniqueId) < turned.size() && size_t(proxy_b->m_uniqueId) < turned.size() &&
        &ta == &a->getCollisionObject()->getWorldTransform() && &tb == &b->getCollisionObject()->getWorldTransform()) {
        id_a_ = proxy_a->m_uniqueId, id_b_ = proxy_b->m_uniqueId;
        separation_ = axis_.dot(ta.getOrigin() - tb.getOrigin());
        turned_a_ = turned[size_t(id_a_)], turned_b_ = turned[size_t(id_b_)];
        has_gap_ = true;
    }
    return true;
}

void PieceConvexAlgorithm::processCollision(const btCollisionObjectWrapper* a, const btCollisionObjectWrapper* b,
                                            const btDispatcherInfo& info, btManifoldResult* out) {
    btPersistentManifold* manifold = const_cast<btPersistentManifold*>(getManifold());
    if (!own_ || !manifold || out->m_closestPointDistanceThreshold != 0) {
        // The first call makes the manifold; a compound's part shares its compound's.
        btConvexConvexAlgorithm::processCollision(a, b, info, out);
        return;
    }
    if (empty_ && has_axis_ && measure_gap(a, b)) return;
    // btConvexConvexAlgorithm::processCollision for two hulls without polyhedral features and
    // without perturbation, keeping GJK's separating axis.
    const auto* shape_a = static_cast<const btConvexShape*>(a->getCollisionShape());
    const auto* shape_b = static_cast<const btConvexShape*>(b->getCollisionShape());
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
    input.m_transformA = a->getWorldTransform();
    input.m_transformB = b->getWorldTransform();
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
    measure_gap(a, b);
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
    // Two bodies left out of the step (rigid flight, simulate/bullet_world.h) never collide.
    if (!static_cast<const btCollisionObject*>(a->m_clientObject)->isActive() &&
        !static_cast<const btCollisionObject*>(b->m_clientObject)->isActive())
        return;
    // A pair proven apart (processCollision would do nothing) and a linked pair (which never
    // collides) are answered without touching more than the bodies' centres.
    auto& pieces = static_cast<PieceDispatcher&>(dispatcher);
    if (pair.m_algorithm && typeid(*pair.m_algorithm) == typeid(PieceConvexAlgorithm) &&
        static_cast<const PieceConvexAlgorithm*>(pair.m_algorithm)->apart(*a, *b, pieces.turned.data()))
        return;
    if (pieces.linked.contains(a->m_uniqueId, b->m_uniqueId)) return;
    if (pieces.deferring && pair.m_algorithm && info.m_dispatchFunc == btDispatcherInfo::DISPATCH_DISCRETE &&
        ((typeid(*pair.m_algorithm) == typeid(PieceConvexAlgorithm) &&
          static_cast<PieceConvexAlgorithm*>(pair.m_algorithm)->independent()) ||
         typeid(*pair.m_algorithm) == typeid(btConvexPlaneCollisionAlgorithm))) {
        const auto* object_a = static_cast<const btCollisionObject*>(a->m_clientObject);
        const auto* object_b = static_cast<const btCollisionObject*>(b->m_clientObject);
        if (pieces.needsCollision(object_a, object_b)) pieces.deferred.push_back({pair.m_algorithm, object_a, object_b});
        return;
    }
    btCollisionDispatcher::defaultNearCallback(pair, dispatcher, info);
}

void PieceDispatcher::dispatchAllCollisionPairs(btOverlappingPairCache* pairs, const btDispatcherInfo& info,
                                                btDispatcher* dispatcher) {
    deferring = workers && workers->threads() > 1;
    deferred.clear();
    btCollisionDispatcher::dispatchAllCollisionPairs(pairs, info, dispatcher);
    deferring = false;
    if (deferred.empty()) return;
    parallel_tests += deferred.size();
    // (btCollisionDispatcher::defaultNearCallback's test, for one deferred pair.)
    workers->run(deferred.size(), 16, [this, &info](size_t i) {
        const Deferred& d = deferred[i];
        const btCollisionObjectWrapper a(nullptr, d.a->getCollisionShape(), d.a, d.a->getWorldTransform(), -1, -1);
        const btCollisionObjectWrapper b(nullptr, d.b->getCollisionShape(), d.b, d.b->getWorldTransform(), -1, -1);
        btManifoldResult result(&a, &b);
        d.algorithm->processCollision(&a, &b, info, &result);
    });
}

void PieceWorld::addConstraint(btTypedConstraint* c, bool disable_collisions_between_linked_bodies) {
    c->setUserConstraintId(m_constraints.size());
    btDiscreteDynamicsWorld::addConstraint(c, disable_collisions_between_linked_bodies);
    const btBroadphaseProxy* a = c->getRigidBodyA().getBroadphaseHandle();
    const btBroadphaseProxy* b = c->getRigidBodyB().getBroadphaseHandle();
    // (A body outside the broadphase is left to needsCollision.)
    if (!disable_collisions_between_linked_bodies || !a || !b) return;
    if (linking_.emplace(c, std::pair(a->m_uniqueId, b->m_uniqueId)).second) pieces_->linked.add(a->m_uniqueId, b->m_uniqueId, 1);
}

void PieceWorld::removeConstraint(btTypedConstraint* c) {
    const int i = c->getUserConstraintId();
    const int last = m_constraints.size() - 1;
    if (i >= 0 && i <= last && m_constraints[i] == c) {  // btDiscreteDynamicsWorld::removeConstraint, found at i
        m_constraints[last]->setUserConstraintId(i);
        m_constraints.swap(i, last);
        m_constraints.pop_back();
        c->setUserConstraintId(-1);
        c->getRigidBodyA().removeConstraintRef(c);
        c->getRigidBodyB().removeConstraintRef(c);
    } else {
        btDiscreteDynamicsWorld::removeConstraint(c);
    }
    const auto it = linking_.find(c);
    if (it == linking_.end()) return;
    pieces_->linked.add(it->second.first, it->second.second, -1);
    linking_.erase(it);
}

void PieceWorld::updateAabbs() {
    std::vector<btScalar>& turned = pieces_->turned;
    for (int i = 0; i < m_collisionObjects.size(); i++) {
        btCollisionObject* o = m_collisionObjects[i];
        if (const btBroadphaseProxy* proxy = o->getBroadphaseHandle()) {  // its turn since the last call
            const size_t id = size_t(proxy->m_uniqueId);
            const btMatrix3x3& r = o->getWorldTransform().getBasis();
            if (id >= turned.size()) turned.resize(id + 1, 0), rotation_.resize(id + 1, btMatrix3x3::getIdentity());
            btScalar f2 = 0;
            for (int row = 0; row < 3; ++row) f2 += (r[row] - rotation_[id][row]).length2();
            // Rounded up: the sum must not fall short of the turns.
            turned[id] += btSqrt(f2) * btScalar(1 + 1e-12);
            rotation_[id] = r;
        }
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
