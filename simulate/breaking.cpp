#include "simulate/breaking.h"

#include <algorithm>
#include <cmath>

namespace shatter {

std::vector<Overload> find_overloads(BulletWorld& world, BreakCriterion criterion) {
    std::vector<Overload> over;
    if (world.flying()) return over;  // no joint is solved, none loaded
    for (size_t c = 0; c < world.constraint_count(); ++c) {
        if (!world.active(c)) continue;
        const double f = world.load_on_a(c).norm();
        const double ratio = world.strength(c) > 0 ? f / world.strength(c) : INFINITY;
        if (criterion == BreakCriterion::BulletImpulse) {
            if (!world.bullet_disabled(c)) continue;
            world.enable(c);
        } else if (!(f > world.strength(c))) {
            continue;
        }
        over.push_back({c, ratio});
    }
    return over;
}

uint64_t break_key(uint64_t seed, size_t constraint) {
    uint64_t z = seed + 0x9e3779b97f4a7c15ull * (constraint + 1);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    return z ^ (z >> 27);
}

namespace {

// The kicks of a break as the pieces' joints pass them on (joined_response.h), adding kinetic
// energy `released` in `frame`: their magnitudes into `kicks` (which holds their directions), the
// change of velocity of every piece of `joined` into `dv`, and the dynamic ones' inertia tensors
// (world frame) into `inertia`. False when the joints hold the pair.
bool joined_kicks(const BulletWorld& world, size_t c, const BulletWorld::JoinedPieces& joined, const Vec3& pivot,
                  const std::array<BodyAtPivot, 2>& free, const EnergizeSettings& settings, const Vec3& frame,
                  double released, BreakKicks* kicks, std::vector<VelocityChange>* dv, std::vector<Mat3>* inertia) {
    if (joined.held) return false;
    std::vector<JoinedBody> bodies;
    std::vector<JoinedJoint> joints;
    std::vector<VelocityChange> v;
    world.joined_bodies(joined, &bodies, &joints, &v);
    // The two pieces' places in `joined.pieces`: piece_a's is the first.
    const auto b_at = std::find(joined.pieces.begin(), joined.pieces.end(), world.piece_b(c));
    const uint32_t at[2] = {0, uint32_t(b_at - joined.pieces.begin())};
    std::vector<BodyImpulse> impulses;
    double free_a = 0;  // the same term for the two pieces alone
    for (int s = 0; s < 2; ++s) {
        if (!free[s].dynamic) continue;
        impulses.push_back({at[s], pivot, kicks->kick[s].direction});
        free_a += 0.5 / effective_mass(free[s].inv_mass, free[s].inv_inertia, free[s].r, kicks->kick[s].direction);
    }
    const size_t n = bodies.size();
    std::vector<VelocityChange>& u = *dv;
    u.clear();
    if (n <= kJoinedPiecesLimit) {
        u = joined_response(bodies, joints, impulses);
    } else {
        // Two fragments, apart: each side on its own, a large one as one rigid body.
        for (int s = 0; s < 2; ++s) {
            const size_t first = s == 0 ? 0 : joined.side_b, end = s == 0 ? joined.side_b : n;
            const std::vector<JoinedBody> side(bodies.begin() + first, bodies.begin() + end);
            std::vector<BodyImpulse> on;
            for (const BodyImpulse& i : impulses)
                if (i.body >= first && i.body < end) on.push_back({uint32_t(i.body - first), i.point, i.impulse});
            std::vector<VelocityChange> part;
            if (side.size() > kJoinedPiecesLimit) {
                part = rigid_response(side, on);
            } else {
                std::vector<JoinedJoint> within;
                for (const JoinedJoint& j : joints)
                    if (j.a >= first && j.a < end) within.push_back({uint32_t(j.a - first), uint32_t(j.b - first), j.pivot});
                part = joined_response(side, within, on);
            }
            u.insert(u.end(), part.begin(), part.end());
        }
    }
    // Per unit magnitude: the energy terms mu b + mu^2 a of each body, summed per side.
    double a[2] = {0, 0}, b[2] = {0, 0};
    inertia->clear();
    for (size_t i = 0; i < bodies.size(); ++i) {
        if (!bodies[i].dynamic) continue;
        const int s = joined.parted && i >= joined.side_b ? 1 : 0;
        inertia->push_back(bodies[i].inv_inertia.inverse());
        const Mat3& turn = inertia->back();
        const double m = 1.0 / bodies[i].inv_mass;
        a[s] += 0.5 * (m * u[i].linear.squaredNorm() + u[i].angular.dot(turn * u[i].angular));
        if (settings.exact_energy) b[s] += m * (v[i].linear - frame).dot(u[i].linear) + v[i].angular.dot(turn * u[i].angular);
    }
    if (!(a[0] + a[1] > kHeldResponse * free_a)) return false;
    const double mu = kick_magnitude(a[0] + a[1], b[0] + b[1], released);
    for (int s = 0; s < 2; ++s) {
        Kick& kick = kicks->kick[s];
        if (!free[s].dynamic) continue;
        kick.magnitude = mu;
        kick.impulse = mu * kick.direction;
        // Of a side, when the break parted them; else half of the whole.
        kick.energy = joined.parted ? mu * b[s] + mu * mu * a[s] : 0.5 * (mu * (b[0] + b[1]) + mu * mu * (a[0] + a[1]));
        const double response = joined.parted ? 2 * a[s] : a[0] + a[1];
        kick.effective_mass = response > 0 ? 1.0 / response : 0.0;
    }
    for (VelocityChange& d : u) d.linear *= mu, d.angular *= mu;
    return true;
}

}  // namespace

BreakRecord energize_broken(BulletWorld& world, size_t c, const std::array<BodyAtPivot, 2>& load,
                            const EnergizeSettings& settings, uint64_t key, std::optional<Vec3> frame_velocity,
                            const BulletWorld::JoinedPieces* joined, double release) {
    Vec3 pivot;
    std::array<BodyAtPivot, 2> now = world.bodies_at_pivot(c, &pivot);
    for (int s = 0; s < 2; ++s) {
        now[s].force = load[s].force;
        now[s].torque = load[s].torque;
    }
    BreakRecord r;
    r.time = world.time();
    r.constraint = uint32_t(c);
    r.piece_a = world.piece_a(c);
    r.piece_b = world.piece_b(c);
    r.pivot = pivot;
    r.force = load[0].force;
    r.strength = world.strength(c);
    r.stiffness = world.stiffness(c);
    r.alpha = settings.alpha;
    const Vec3 frame = frame_velocity ? *frame_velocity : pair_frame_velocity(load[0], load[1]);
    // The kinetic energy of the bodies the kicks move, in the pair's frame and in the world's.
    const std::vector<uint32_t> pair = {r.piece_a, r.piece_b};
    const std::vector<uint32_t>& moved = joined ? joined->pieces : pair;
    std::vector<Mat3> inertia;  // of the moved pieces, for both books
    std::vector<VelocityChange> dv;
    if (joined) {
        r.kicks = kick_directions(now[0], now[1], r.stiffness, settings, key);
        const double own = settings.alpha * r.kicks.stored_energy;
        if (!joined_kicks(world, c, *joined, pivot, now, settings, frame, own + release, &r.kicks, &dv, &inertia)) {
            r.held_energy = own;
            return r;
        }
        r.released_energy = release;
    } else {
        r.kicks = energize(now[0], now[1], r.stiffness, settings, key, frame);
    }
    double before = 0, before_world = 0, after = 0, after_world = 0;
    world.kinetic_energies_of(moved, frame, &before, &before_world, &inertia);
    if (joined) world.add_velocities(joined->pieces, dv);
    else world.apply_kicks(c, pivot, r.kicks);
    world.kinetic_energies_of(moved, frame, &after, &after_world, &inertia);
    r.injected_energy = after - before;
    r.momentum_work = after_world - before_world - r.injected_energy;
    return r;
}

}  // namespace shatter
