// Collision filtering for pieces in Bullet, at the scale of centimetre pieces (docs/physics.md
// sections 5 and 6): which pairs the narrow phase sees, and how tight the broadphase boxes are.
#pragma once

#include <BulletCollision/CollisionDispatch/btConvexConvexAlgorithm.h>
#include <BulletCollision/NarrowPhaseCollision/btGjkEpaPenetrationDepthSolver.h>
#include <btBulletDynamicsCommon.h>

#include <algorithm>
#include <cstdint>
#include <limits>
#include <unordered_set>
#include <utility>
#include <vector>

namespace shatter {

// Skips the narrow phase for pairs of pieces that overlapped where they started without being
// joined (pieces touching along an edge, or whose convex parts reach into a neighbour): their
// contact would push them apart, load their constraints and break them in free fall. A pair is
// released once its bounding boxes part.
// Convex-convex contact between two pieces' hulls (btConvexHullShape), as
// btConvexConvexAlgorithm finds it, with the GJK skipped for a pair that is far apart: GJK's
// distance is that of a point of the hulls' Minkowski difference, never less than the true
// distance, and a point found farther apart than the manifold's breaking threshold is not kept.
// So when the pair's manifold holds no point and the hulls are provably apart by more than their
// margins plus that threshold, GJK could add nothing and is skipped: the same contacts to the bit.
// The proof: the gap between the hulls along the axis GJK last separated them by (their extents
// along it: two support vertices), less how far the bodies have moved since towards each other
// along it (a point r from a body's centre moves by at most |dc| + |R1 - R0|_F r when the body
// goes from (R0, c0) to (R1, c1)); the extents are measured again when that bound runs out.
class PieceConvexAlgorithm : public btConvexConvexAlgorithm {
public:
    PieceConvexAlgorithm(const btCollisionAlgorithmConstructionInfo& ci, const btCollisionObjectWrapper* a,
                         const btCollisionObjectWrapper* b, btConvexPenetrationDepthSolver* pd)
        : btConvexConvexAlgorithm(ci.m_manifold, ci, a, b, pd, 0, 3), pd_(pd), own_(ci.m_manifold == nullptr) {}
    void processCollision(const btCollisionObjectWrapper* a, const btCollisionObjectWrapper* b,
                          const btDispatcherInfo& info, btManifoldResult* out) override;

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
    // The gap along axis_ measured again at the bodies' transforms; false when it is too small.
    bool measure_gap(const btConvexShape* sa, const btConvexShape* sb, const btTransform& ta, const btTransform& tb);
    btConvexPenetrationDepthSolver* pd_;
    bool own_;               // the manifold is this pair's own (not a compound's, shared)
    bool empty_ = false;     // the manifold held no point after this algorithm's last GJK
    bool has_axis_ = false;  // axis_ holds the last GJK's separating direction
    bool has_gap_ = false;   // gap_ was measured at ta_, tb_
    btScalar needed_ = 0;    // the gap that proves no contact (unit: m)
    btScalar radius_a_ = 0, radius_b_ = 0;  // the hulls' farthest points from their bodies' centres
    btVector3 axis_{0, 0, 0};  // world, unit, from B towards A
    btScalar gap_ = 0;       // min over A of axis.a - max over B of axis.b (unit: m)
    btTransform ta_, tb_;
};

class PieceDispatcher : public btCollisionDispatcher {
public:
    // Pairs of convex hulls (the pieces' parts) collide with PieceConvexAlgorithm.
    explicit PieceDispatcher(btCollisionConfiguration* config) : btCollisionDispatcher(config) {
        registerCollisionCreateFunc(CONVEX_HULL_SHAPE_PROXYTYPE, CONVEX_HULL_SHAPE_PROXYTYPE, &hulls_);
    }
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
    bool needsCollision(const btCollisionObject* a, const btCollisionObject* b) override {
        if (a->getUserIndex() >= 0 && b->getUserIndex() >= 0 && ignored.contains(a->getUserIndex(), b->getUserIndex()))
            return false;
        return btCollisionDispatcher::needsCollision(a, b);
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
    using btDiscreteDynamicsWorld::btDiscreteDynamicsWorld;
    // btCollisionWorld::updateSingleAabb with the shape's own padding.
    void updateAabbs() override;
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
