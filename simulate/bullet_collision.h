// Collision filtering for pieces in Bullet, at the scale of centimetre pieces (docs/physics.md
// sections 5 and 6): which pairs the narrow phase sees, and how tight the broadphase boxes are.
#pragma once

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
class PieceDispatcher : public btCollisionDispatcher {
public:
    using btCollisionDispatcher::btCollisionDispatcher;
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
