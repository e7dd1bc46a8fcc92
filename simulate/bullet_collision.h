// Collision filtering for pieces in Bullet, at the scale of centimetre pieces (docs/physics.md
// sections 5 and 6): which pairs the narrow phase sees, and how tight the broadphase boxes are.
#pragma once

#include <BulletCollision/CollisionDispatch/btConvexConvexAlgorithm.h>
#include <BulletCollision/NarrowPhaseCollision/btGjkEpaPenetrationDepthSolver.h>
#include <btBulletDynamicsCommon.h>

#include <algorithm>
#include <cstdint>
#include <limits>
#include <unordered_map>
#include <unordered_set>
#include <utility>
#include <vector>

#include "core/workers.h"

namespace shatter {

// Convex-convex contact between two pieces' hulls (btConvexHullShape), as
// btConvexConvexAlgorithm finds it, with the GJK skipped for a pair that is far apart: GJK's
// distance is that of a point of the hulls' Minkowski difference, never less than the true
// distance, and a point found farther apart than the manifold's breaking threshold is not kept.
// So when the pair's manifold holds no point and the hulls are provably apart by more than their
// margins plus that threshold, GJK could add nothing and is skipped: the same contacts to the bit.
// The proof: the gap between the hulls along the axis GJK last separated them by (their extents
// along it: two support vertices), less how far the bodies have moved since towards each other
// along it: their centres' approach along the axis, plus for each body r |R1 - R0|_F (a point r
// from a body's centre moves by at most that when its rotation goes from R0 to R1), |R1 - R0|_F
// bounded by the sum of the body's turns step by step (PieceDispatcher::turned). The extents are
// measured again when that bound runs out. The bound alone (apart()) needs only the pair's own
// state and the bodies' centres: exact_aabb_near_callback asks it before anything else.
class PieceConvexAlgorithm : public btConvexConvexAlgorithm {
public:
    PieceConvexAlgorithm(const btCollisionAlgorithmConstructionInfo& ci, const btCollisionObjectWrapper* a,
                         const btCollisionObjectWrapper* b, btConvexPenetrationDepthSolver* pd)
        : btConvexConvexAlgorithm(ci.m_manifold, ci, a, b, pd, 0, 3), pd_(pd), own_(ci.m_manifold == nullptr) {}
    void processCollision(const btCollisionObjectWrapper* a, const btCollisionObjectWrapper* b,
                          const btDispatcherInfo& info, btManifoldResult* out) override;
    // processCollision touches only this pair's own state and manifold (made by an earlier call):
    // it may run beside other pairs' (PieceDispatcher::workers).
    bool independent() { return own_ && getManifold() != nullptr; }
    // The pair of these proxies (in this order) is proven apart by the bound: processCollision
    // would do nothing.
    bool apart(const btBroadphaseProxy& a, const btBroadphaseProxy& b, const btScalar* turned) const {
        if (!has_gap_ || a.m_uniqueId != id_a_ || b.m_uniqueId != id_b_) return false;
        const btVector3& ca = static_cast<const btCollisionObject*>(a.m_clientObject)->getWorldTransform().getOrigin();
        const btVector3& cb = static_cast<const btCollisionObject*>(b.m_clientObject)->getWorldTransform().getOrigin();
        return gap_ + (axis_.dot(ca - cb) - separation_) - radius_a_ * (turned[id_a_] - turned_a_) -
                   radius_b_ * (turned[id_b_] - turned_b_) >
               needed_;
    }

    struct CreateFunc : btCollisionAlgorithmCreateFunc {
        btGjkEpaPenetrationDepthSolver pd;
        btCollisionAlgorithm* CreateCollisionAlgorithm(btCollisionAlgorithmConstructionInfo& ci,
                                                       const btCollisionObjectWrapper* a,
                                                       const btCollisionObjectWrapper* b) override {
            // Not from the dispatcher's pool, whose elements may be smaller (freeing tells them apart).
            void* mem = btAlignedAlloc(sizeof(PieceConvexAlgorithm), 16);
            return new (mem) PieceConvexAlgorithm(ci, a, b, &pd);
        }
    };

private:
    // Measures the gap along axis_ at the bodies' transforms; whether it proves them apart.
    bool measure_gap(const btCollisionObjectWrapper* a, const btCollisionObjectWrapper* b);
    btConvexPenetrationDepthSolver* pd_;
    bool own_;               // the manifold is this pair's own (not a compound's, shared)
    bool empty_ = false;     // the manifold held no point after this algorithm's last GJK
    bool has_axis_ = false;  // axis_ holds the last GJK's separating direction
    bool has_gap_ = false;   // the last measured gap proves the pair apart; the state below holds
    int id_a_ = -1, id_b_ = -1;  // the bodies' proxy ids
    btScalar needed_ = 0;    // the gap that proves no contact (unit: m)
    btScalar radius_a_ = 0, radius_b_ = 0;  // the hulls' farthest points from their bodies' centres
    btVector3 axis_{0, 0, 0};  // world, unit, from B towards A
    btScalar gap_ = 0;       // min over A of axis.a - max over B of axis.b when measured (unit: m)
    btScalar separation_ = 0;  // axis.(centre A - centre B) when measured (unit: m)
    btScalar turned_a_ = 0, turned_b_ = 0;  // PieceDispatcher::turned of A and B when measured
};

// Skips the narrow phase for pairs of pieces that overlapped where they started without being
// joined (pieces touching along an edge, or whose convex parts reach into a neighbour): their
// contact would push them apart, load their constraints and break them in free fall. A pair is
// released once its bounding boxes part.
class PieceDispatcher : public btCollisionDispatcher {
public:
    // Pairs of convex hulls (the pieces' parts) collide with PieceConvexAlgorithm; with
    // skip_apart false, with Bullet's btConvexConvexAlgorithm (for comparison).
    explicit PieceDispatcher(btCollisionConfiguration* config, bool skip_apart = true)
        : btCollisionDispatcher(config), skip_apart(skip_apart) {
        if (skip_apart) registerCollisionCreateFunc(CONVEX_HULL_SHAPE_PROXYTYPE, CONVEX_HULL_SHAPE_PROXYTYPE, &hulls_);
    }
    const bool skip_apart;
    // Per proxy id: the sum over the steps so far of |R1 - R0|_F, R0 and R1 a body's rotation
    // before and after the step (PieceWorld::updateAabbs), bounding how far it has turned since
    // any earlier step: |R(t1) - R(t0)|_F <= turned(t1) - turned(t0).
    std::vector<btScalar> turned;
    // The ignored pairs of pieces, looked up for every pair of every step: a hash set, and per
    // piece how many ignored pairs it is in, so that most pairs are passed without a lookup.
    class Ignored {
    public:
        void insert(int a, int b) {
            if (!pairs_.insert(key(a, b)).second) return;
            for (int p : {a, b}) {
                if (size_t(p) >= count_.size()) count_.resize(size_t(p) + 1, 0);
                ++count_[size_t(p)];
            }
        }
        bool contains(int a, int b) const {
            return !pairs_.empty() && size_t(a) < count_.size() && size_t(b) < count_.size() &&
                   count_[size_t(a)] && count_[size_t(b)] && pairs_.count(key(a, b));
        }
        // Drops the pairs for which `parted(a, b)` holds (a < b).
        template <class Parted>
        void release(Parted parted) {
            for (auto it = pairs_.begin(); it != pairs_.end();) {
                const int a = int(*it >> 32), b = int(*it & 0xffffffffu);
                if (!parted(a, b)) {
                    ++it;
                    continue;
                }
                --count_[size_t(a)];
                --count_[size_t(b)];
                it = pairs_.erase(it);
            }
        }

    private:
        static uint64_t key(int a, int b) {
            const auto [lo, hi] = std::minmax(a, b);
            return uint64_t(uint32_t(lo)) << 32 | uint32_t(hi);
        }
        std::unordered_set<uint64_t> pairs_;  // (smaller piece, larger piece)
        std::vector<uint32_t> count_;         // per piece
    };
    Ignored ignored;

    // The pairs of bodies joined by constraints added with "disable collisions between linked
    // bodies", by their broadphase proxies' ids: btCollisionDispatcher::needsCollision finds them
    // by walking both bodies' lists of linked bodies (one entry per constraint, ~60 for a piece
    // of the 1,000-piece bunny), touching memory of both bodies for every pair of every step;
    // the near callback asks here first, from the proxies it has read already.
    class Linked {
    public:
        void add(int a, int b, int delta) {
            for (const auto& [p, q] : {std::pair(a, b), std::pair(b, a)}) {
                if (size_t(p) >= others_.size()) others_.resize(size_t(p) + 1);
                auto& list = others_[size_t(p)];
                auto it = std::find_if(list.begin(), list.end(), [q = q](const auto& e) { return e.first == q; });
                if (it == list.end()) it = list.insert(list.end(), {q, 0});
                it->second += delta;
                if (it->second == 0) list.erase(it);
            }
        }
        bool contains(int a, int b) const {
            if (size_t(a) >= others_.size()) return false;
            for (const auto& e : others_[size_t(a)])
                if (e.first == b) return true;
            return false;
        }

    private:
        std::vector<std::vector<std::pair<int, int>>> others_;  // per proxy id: (other id, constraints)
    };
    Linked linked;

    // The narrow phase of the pairs whose algorithm holds its own manifold already (pieces'
    // hulls after their first contact test, pieces on the ground) runs on `workers`' threads after
    // the walk over the pairs; the walk itself, which makes and frees algorithms and manifolds in
    // the pairs' order (the solver's order), stays on the calling thread. Each such pair's test
    // reads the bodies' poses and writes its own algorithm and manifold only: the same contacts
    // for any number of threads.
    Workers* workers = nullptr;
    struct Deferred {
        btCollisionAlgorithm* algorithm;
        const btCollisionObject* a;
        const btCollisionObject* b;
    };
    std::vector<Deferred> deferred;  // filled by exact_aabb_near_callback during the walk
    bool deferring = false;
    uint64_t parallel_tests = 0;  // deferred pairs tested so far
    void dispatchAllCollisionPairs(btOverlappingPairCache* pairs, const btDispatcherInfo& info,
                                   btDispatcher* dispatcher) override;

    // btCollisionDispatcher::needsCollision, with the linked pairs (the only bodies
    // checkCollideWith refuses: nothing else marks bodies to ignore) from `linked`.
    bool needsCollision(const btCollisionObject* a, const btCollisionObject* b) override {
        if (a->getUserIndex() >= 0 && b->getUserIndex() >= 0 && ignored.contains(a->getUserIndex(), b->getUserIndex()))
            return false;
        const btBroadphaseProxy* pa = a->getBroadphaseHandle();
        const btBroadphaseProxy* pb = b->getBroadphaseHandle();
        if (!pa || !pb) return btCollisionDispatcher::needsCollision(a, b);
        return (a->isActive() || b->isActive()) && !linked.contains(pa->m_uniqueId, pb->m_uniqueId);
    }

private:
    PieceConvexAlgorithm::CreateFunc hulls_;
};

// The proxies' boxes decide here before the narrow phase (a broadphase may keep a pair whose
// boxes no longer overlap until it next sweeps).
// btCollisionWorld pads every proxy's box by gContactBreakingThreshold, a fixed 2 cm made for
// metre-sized bodies: with 2 cm pieces every piece then overlaps ~24 neighbours and each pair runs
// the narrow phase. PieceWorld pads by the shape's own contact breaking threshold instead (the
// distance within which its manifolds keep points), so every pair that can have a contact still
// overlaps. A pair whose exact boxes part loses its algorithm and manifold, as it would on
// leaving the broadphase: a manifold not refreshed any more would feed stale contacts (even
// penetrating ones) to the solver.
void exact_aabb_near_callback(btBroadphasePair& pair, btCollisionDispatcher& dispatcher,
                              const btDispatcherInfo& info);

class PieceWorld : public btDiscreteDynamicsWorld {
public:
    PieceWorld(PieceDispatcher* dispatcher, btBroadphaseInterface* broadphase, btConstraintSolver* solver,
               btCollisionConfiguration* config)
        : btDiscreteDynamicsWorld(dispatcher, broadphase, solver, config), pieces_(dispatcher) {}
    // btCollisionWorld::updateSingleAabb with the shape's own padding.
    void updateAabbs() override;
    // Bullet's, keeping the dispatcher's linked pairs (PieceDispatcher::Linked) in step. Each
    // constraint's user id holds its place in the world's list, so that removing it does not
    // search the list (Bullet's linear search: 31,000 joints, hundreds of breaks a step); the
    // list ends in the same order as Bullet's (the last moved into the gap).
    void addConstraint(btTypedConstraint* c, bool disable_collisions_between_linked_bodies) override;
    void removeConstraint(btTypedConstraint* c) override;
    // Takes every constraint out of the world's list, and puts them back in the same order:
    // rigid flight (simulate/bullet_world.h), where the islands and the solve need not walk them.
    void park_constraints() {
        parked_ = m_constraints;
        m_constraints.resize(0);
    }
    void unpark_constraints() {
        m_constraints = parked_;
        parked_.resize(0);
    }

private:
    PieceDispatcher* pieces_;
    std::vector<btMatrix3x3> rotation_;  // per proxy id: the body's rotation at the last updateAabbs
    // The constraints added with collisions disabled, and their bodies' proxy ids.
    std::unordered_map<const btTypedConstraint*, std::pair<int, int>> linking_;
    btAlignedObjectArray<btTypedConstraint*> parked_;
};

// The deepest point contactPairTest found between two bodies (the most negative distance: the
// overlap; unit: m), among points closer than a threshold (m); whether there was one.
struct ContactFound : btCollisionWorld::ContactResultCallback {
    double threshold;
    double deepest = std::numeric_limits<double>::infinity();
    explicit ContactFound(double t) : threshold(t) { m_closestDistanceThreshold = btScalar(t); }
    bool found() const { return deepest < threshold; }
    btScalar addSingleResult(btManifoldPoint& p, const btCollisionObjectWrapper*, int, int,
                             const btCollisionObjectWrapper*, int, int) override {
        deepest = std::min(deepest, double(p.getDistance()));
        return 0;
    }
};

}  // namespace shatter
