#include "simulate/bullet_world.h"
#include "simulate/bullet_world_impl.h"

#include <BulletCollision/CollisionShapes/btShapeHull.h>
#include <LinearMath/btConvexHullComputer.h>
#include <btBulletDynamicsCommon.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <set>
#include <functional>

#include "core/error.h"
#include "core/material_presets.h"
#include "meshio/mesh_load.h"
#include "simulate/bullet_collision.h"
#include "simulate/bullet_convert.h"
#include "simulate/bullet_shapes.h"
#include "simulate/bullet_solver.h"
#include "simulate/compliant_constraint.h"
#include "simulate/spring.h"
#include "simulate/surface_pair.h"

namespace shatter {

namespace {

// A scripted body: its transform at the world's current clock.
class ScriptedMotion : public btMotionState {
public:
    ScriptedMotion(const double* clock, btTransform start, std::function<Vec3(double)> offset)
        : clock_(clock), start_(start), offset_(std::move(offset)) {}
    void getWorldTransform(btTransform& t) const override {
        t = start_;
        t.setOrigin(start_.getOrigin() + to_bullet(offset_(*clock_)));
    }
    void setWorldTransform(const btTransform&) override {}

private:
    const double* clock_;
    btTransform start_;
    std::function<Vec3(double)> offset_;
};

// A pair's friction and restitution from its two bodies': simulate/surface_pair.h.
btScalar combined_friction(const btCollisionObject* a, const btCollisionObject* b) {
    return btScalar(pair_friction(a->getFriction(), b->getFriction()));
}
btScalar combined_restitution(const btCollisionObject* a, const btCollisionObject* b) {
    return btScalar(pair_restitution(a->getRestitution(), b->getRestitution()));
}

}  // namespace


BulletWorld::BulletWorld(const Model& model, const WorldSetup& setup)
    : impl_(std::make_unique<Impl>(
          uint32_t(1 + setup.scene.colliders.size() + setup.scene.kinematic.size() + setup.scene.projectiles.size() +
                   model.pieces.size()))),
      setup_(setup) {
    Impl& m = *impl_;
    m.dispatcher.setNearCallback(exact_aabb_near_callback);
    // Bullet's rules are process-wide: set once, for every world.
    static const bool combine_rules_set = [] {
        gCalculateCombinedFrictionCallback = combined_friction;
        gCalculateCombinedRestitutionCallback = combined_restitution;
        return true;
    }();
    (void)combine_rules_set;
    m.workers = std::make_unique<Workers>(setup.threads ? setup.threads : default_threads());
    m.dispatcher.workers = m.workers.get();
    // Only active bodies' boxes follow them (every body is kept active but in rigid flight).
    m.world.setForceUpdateAllAabbs(false);
    m.gravity = setup.scene.gravity;
    m.world.setGravity(to_bullet(setup.scene.gravity));
    btContactSolverInfo& info = m.world.getSolverInfo();
    info.m_numIterations = int(setup.iterations);
    const bool direct_default = setup.direct_joints && !(setup.converge_tolerance > 0);
    m.solver.converge(joint_tolerance(), direct_default ? int(kDirectIterationCap * setup.iterations)
                                                        : int(std::max(setup.max_iterations, setup.iterations)));
    m.solver.direct_joints(setup.direct_joints);
    m.solver.push_joints(setup.direct_joints);
    // A joined push turns the pieces as the joints ask (Bullet's default applies a tenth of the turn).
    if (setup.direct_joints) info.m_splitImpulseTurnErp = 1;
    info.m_splitImpulse = 1;  // penetration is resolved without adding kinetic energy
    info.m_splitImpulsePenetrationThreshold = 0;
    // A step's iterations end early once no row's update changes a relative velocity by more
    // than kSettledSpeed (Bullet's residual is the largest squared change): a falling or resting
    // structure settles in a few passes (docs/physics.md section 6).
    info.m_leastSquaresResidualThreshold = btScalar(kSettledSpeed * kSettledSpeed);

    // Static scene.
    if (setup.scene.ground) {
        m.shapes.emplace_back(new btStaticPlaneShape(btVector3(0, 1, 0), btScalar(setup.scene.ground_height)));
        m.add_body(0, btVector3(0, 0, 0), m.shapes.back().get(), btTransform::getIdentity(), nullptr,
                   setup.scene.ground_surface);
    }
    for (const ColliderSettings& c : setup.scene.colliders) {
        btCollisionShape* shape = nullptr;
        const ShapeSettings& s = c.shape;
        switch (s.kind) {
            case ShapeKind::Box: shape = new btBoxShape(to_bullet(0.5 * s.size)); break;
            case ShapeKind::Sphere: shape = new btSphereShape(btScalar(s.radius)); break;
            case ShapeKind::Plane: shape = new btStaticPlaneShape(btVector3(0, 1, 0), 0); break;
            case ShapeKind::Mesh: {
                m.collider_meshes.push_back(load_mesh(s.mesh, s.mesh_scale));
                TriangleMesh& tm = m.collider_meshes.back();
                auto arr = std::make_unique<btTriangleIndexVertexArray>(
                    int(tm.triangles.size()), reinterpret_cast<int*>(tm.triangles.data()), int(3 * sizeof(uint32_t)),
                    int(tm.vertices.size()), reinterpret_cast<btScalar*>(tm.vertices.data()), int(3 * sizeof(double)));
                shape = new btBvhTriangleMeshShape(arr.get(), true);
                m.triangle_arrays.push_back(std::move(arr));
                break;
            }
        }
        m.shapes.emplace_back(shape);
        m.add_body(0, btVector3(0, 0, 0), shape, make_transform(rotation_matrix(c.pose.rotation_deg), c.pose.position),
                   nullptr, c.surface);
    }
    // Props: scripted boxes and spheres.
    for (const KinematicSettings& k : setup.scene.kinematic) {
        btCollisionShape* shape = m.prop_shape(k.shape);
        const btTransform start = make_transform(rotation_matrix(k.pose.rotation_deg), Vec3::Zero());
        const KinematicSettings prop = k;
        m.motions.emplace_back(new ScriptedMotion(&time_, start, [prop](double t) { return kinematic_position(prop, t); }));
        btRigidBody* body = m.add_body(0, btVector3(0, 0, 0), shape, start, m.motions.back().get(), k.surface);
        body->setCollisionFlags(body->getCollisionFlags() | btCollisionObject::CF_KINEMATIC_OBJECT);
        m.props.push_back(body);
    }
    // Projectiles: boxes and spheres of their own mass, launched at t = 0.
    for (const ProjectileSettings& p : setup.scene.projectiles) {
        btCollisionShape* shape = m.prop_shape(p.shape);
        const double mass = projectile_mass(p);
        btVector3 inertia;
        shape->calculateLocalInertia(btScalar(mass), inertia);
        btRigidBody* body = m.add_body(mass, inertia, shape,
                                       make_transform(rotation_matrix(p.pose.rotation_deg), p.pose.position), nullptr,
                                       p.surface);
        body->setLinearVelocity(to_bullet(p.velocity));
        m.props.push_back(body);
        m.projectiles.push_back(body);
    }
    build_pieces(model);
    build_joints(model);
    ignore_initial_overlaps();
    if (setup.sleep_speed > 0) allow_sleep(model);
    // Rigid flight, when every piece is dynamic and moves alike (the object's spin would load the
    // joints) and nothing is within reach at the start.
    bool alike = setup.rigid_flight && m.pieces.size() >= 2 && setup.object.angular_velocity.isZero();
    for (const Impl::PieceBody& p : m.pieces) alike = alike && p.dynamic;
    if (alike && !near_anything()) {
        for (const Impl::PieceBody& p : m.pieces) p.body->forceActivationState(DISABLE_SIMULATION);
        m.world.park_constraints();
        m.flying = true;
    }
}

void BulletWorld::allow_sleep(const Model& model) {
    Impl& m = *impl_;
    gDeactivationTime = btScalar(kSleepTime);  // Bullet's global; every body that must not sleep opts out
    // Everything joined, through joints, to a driven piece stays awake.
    std::vector<char> kept(m.pieces.size(), 0);
    std::vector<uint32_t> queue;
    for (size_t i = 0; i < m.pieces.size(); ++i)
        if (!m.pieces[i].dynamic) kept[i] = 1, queue.push_back(uint32_t(i));
    for (size_t next = 0; next < queue.size(); ++next)
        for (const Impl::Link& l : m.links[queue[next]])
            if (!kept[l.other]) kept[l.other] = 1, queue.push_back(l.other);
    const btScalar v = btScalar(setup_.sleep_speed);
    for (size_t i = 0; i < m.pieces.size(); ++i) {
        Impl::PieceBody& p = m.pieces[i];
        if (kept[i]) continue;
        p.may_sleep = true;
        p.body->forceActivationState(ACTIVE_TAG);
        p.body->setSleepingThresholds(v, v / btScalar(std::max(piece_radius(model.pieces[i]), 1e-6)));
    }
    for (btRigidBody* b : m.projectiles) {
        btVector3 centre;
        btScalar radius;
        b->getCollisionShape()->getBoundingSphere(centre, radius);
        b->forceActivationState(ACTIVE_TAG);
        b->setSleepingThresholds(v, v / std::max(radius, btScalar(1e-6)));
    }
}

bool BulletWorld::awake(size_t c) const {
    const Impl::Joint& j = impl_->joints[c];
    return j.constraint && Impl::awake(j);
}

uint32_t BulletWorld::sleeping_pieces() const {
    uint32_t n = 0;
    for (const Impl::PieceBody& p : impl_->pieces) n += Impl::asleep(*p.body);
    return n;
}

uint64_t BulletWorld::parallel_contact_tests() const { return impl_->dispatcher.parallel_tests; }

bool BulletWorld::flying() const { return impl_->flying; }
double BulletWorld::flight_end() const { return impl_->flying ? time_ : impl_->flight_end; }

bool BulletWorld::near_anything() const {
    const Impl& m = *impl_;
    // The pieces' contact boxes as the broadphase pads them (PieceWorld::updateAabbs), grown once
    // more by the largest padding: a pair the near phase could see is found with room to spare.
    btVector3 lo(BT_LARGE_FLOAT, BT_LARGE_FLOAT, BT_LARGE_FLOAT), hi = -lo;
    btScalar pad = 0;
    for (const Impl::PieceBody& p : m.pieces) {
        const btCollisionShape* shape = p.body->getCollisionShape();
        const btScalar t = shape->getContactBreakingThreshold(gContactBreakingThreshold);
        btVector3 l, u;
        shape->getAabb(p.body->getWorldTransform(), l, u);
        lo.setMin(l - btVector3(t, t, t));
        hi.setMax(u + btVector3(t, t, t));
        pad = std::max(pad, t);
    }
    lo -= btVector3(pad, pad, pad);
    hi += btVector3(pad, pad, pad);
    // Swept over the step (fly()): a flight never ends a step within reach of anything, so what
    // looks for contacts after a step (approach_load) finds none that a solved step would have.
    const btScalar h = btScalar(setup_.h);
    const auto sweep = [h](const btRigidBody& b, btVector3* l, btVector3* u) {
        const btVector3 d = (b.getLinearVelocity() + b.getGravity() * (h / 2)) * h;  // fly()'s move
        l->setMin(*l + d);
        u->setMax(*u + d);
    };
    sweep(*m.pieces.front().body, &lo, &hi);
    for (const auto& body : m.bodies) {
        const btRigidBody& b = *body;
        if (b.getUserIndex() >= 0) continue;  // a piece
        const btCollisionShape* shape = b.getCollisionShape();
        // Where this step's collision detection will see it: a kinematic body where its script
        // has it at the step's clock.
        btTransform t = b.getWorldTransform();
        if (b.isKinematicObject() && b.getMotionState()) b.getMotionState()->getWorldTransform(t);
        if (shape->getShapeType() == STATIC_PLANE_PROXYTYPE) {
            const auto* plane = static_cast<const btStaticPlaneShape*>(shape);
            const btVector3 n = t.getBasis() * plane->getPlaneNormal();
            const btVector3 on = t(plane->getPlaneNormal() * plane->getPlaneConstant());
            btScalar lowest = 0;  // the box's least height above the plane
            for (int i = 0; i < 3; ++i) lowest += n[i] * (n[i] > 0 ? lo[i] : hi[i]);
            if (lowest - n.dot(on) <= 0) return true;
            continue;
        }
        const btScalar r = shape->getContactBreakingThreshold(gContactBreakingThreshold);
        btVector3 l, u;
        shape->getAabb(t, l, u);
        if (!b.isStaticOrKinematicObject()) sweep(b, &l, &u);  // a projectile
        if (TestAabbAgainstAabb2(l - btVector3(r, r, r), u + btVector3(r, r, r), lo, hi)) return true;
    }
    return false;
}

void BulletWorld::end_flight() {
    Impl& m = *impl_;
    if (!m.flying) return;
    for (const Impl::PieceBody& p : m.pieces) p.body->forceActivationState(p.may_sleep ? ACTIVE_TAG : DISABLE_DEACTIVATION);
    m.world.unpark_constraints();
    m.flying = false;
    m.flight_end = time_;
}

// Bullet steps the rest of the scene, leaving out the pieces (DISABLE_SIMULATION); they fall as
// free bodies do, exactly (no spin, so no turn).
void BulletWorld::fly() {
    Impl& m = *impl_;
    m.world.stepSimulation(btScalar(setup_.h), 0, btScalar(setup_.h));
    const btScalar h = btScalar(setup_.h);
    // The fall is a parabola, followed exactly at any step: x += (v0 + v1) h / 2. (Bullet's update,
    // v += g h then x += v h, runs ahead by g h t / 2: at the automatic step's 1/480 s, a plate
    // dropped 0.48 m met the sphere a millisecond early.)
    for (const Impl::PieceBody& p : m.pieces) {
        btRigidBody& b = *p.body;
        const btVector3 v0 = b.getLinearVelocity();
        const btVector3 v = v0 + b.getGravity() * h;
        btTransform t = b.getWorldTransform();
        t.setOrigin(t.getOrigin() + (v0 + v) * (h / 2));
        b.setLinearVelocity(v);
        b.setWorldTransform(t);
        b.setInterpolationWorldTransform(t);
        b.setInterpolationLinearVelocity(v);
    }
}

void BulletWorld::ignore_initial_overlaps() {
    Impl& m = *impl_;
    std::vector<btVector3> lo(m.pieces.size()), hi(m.pieces.size());
    for (size_t i = 0; i < m.pieces.size(); ++i) m.pieces[i].body->getAabb(lo[i], hi[i]);
    for (size_t i = 0; i < m.pieces.size(); ++i)
        for (size_t j = i + 1; j < m.pieces.size(); ++j) {
            if (!TestAabbAgainstAabb2(lo[i], hi[i], lo[j], hi[j])) continue;
            btRigidBody* a = m.pieces[i].body;
            btRigidBody* b = m.pieces[j].body;
            if (!a->checkCollideWith(b)) continue;  // joined: never collide while joined
            ContactFound contact(1e-4);
            m.world.contactPairTest(a, b, contact);
            if (contact.found()) m.dispatcher.ignored.insert(int(i), int(j));
        }
}

// An overlap deeper than this fraction of the smaller piece's least box extent is not pushed out
// when a pair's last joint breaks (remove_constraint). Touching faces and the joints' own
// compression (micrometres) stay far below it.
constexpr double kDeepOverlap = 0.01;

namespace {

// The least extent of the smaller of two boxes (unit: m): the scale of a pair's overlap and
// parting thresholds.
btScalar least_extent(const btVector3& lo_a, const btVector3& hi_a, const btVector3& lo_b, const btVector3& hi_b) {
    const btVector3 ea = hi_a - lo_a, eb = hi_b - lo_b;
    return std::min(ea[ea.minAxis()], eb[eb.minAxis()]);
}

}  // namespace

// A pair is released when its bounding boxes are apart by more than 5% of the smaller box's
// least extent: neighbours that only touch along an edge jitter by a hair while joined to the
// rest, and releasing them at the first hair would make them collide at that edge every step.
void BulletWorld::release_parted_pairs() {
    Impl& m = *impl_;
    m.dispatcher.ignored.release([&m](int a, int b) {
        btVector3 lo_a, hi_a, lo_b, hi_b;
        m.pieces[size_t(a)].body->getAabb(lo_a, hi_a);
        m.pieces[size_t(b)].body->getAabb(lo_b, hi_b);
        const btScalar gap = btScalar(0.05) * least_extent(lo_a, hi_a, lo_b, hi_b);
        const btVector3 pad(gap, gap, gap);
        return !TestAabbAgainstAabb2(lo_a - pad, hi_a + pad, lo_b, hi_b);
    });
}

BulletWorld::~BulletWorld() {
    end_flight();
    Impl& m = *impl_;
    for (auto& j : m.joints)
        if (j.active && j.constraint) m.world.removeConstraint(j.constraint.get());
    // Taking a body out of the world one at a time walks every overlapping pair and moves its six
    // edges through sweep and prune's sorted lists: quadratic in the bodies (a ninth of a
    // 10,000-piece run). The pairs (and their collision algorithms) go in one pass instead, last
    // first, and the bodies leave without their broadphase entries, which go with the broadphase.
    btOverlappingPairCache* pairs = m.broadphase.getOverlappingPairCache();
    btBroadphasePairArray& overlapping = pairs->getOverlappingPairArray();
    while (overlapping.size() > 0) {
        const btBroadphasePair& last = overlapping[overlapping.size() - 1];
        pairs->removeOverlappingPair(last.m_pProxy0, last.m_pProxy1, &m.dispatcher);
    }
    for (auto& b : m.bodies) {
        b->setBroadphaseHandle(nullptr);
        m.world.removeRigidBody(b.get());
    }
}

}  // namespace shatter

namespace shatter {

// The radius of a piece's contact patch with what it rests on, as a fraction of its own radius.
constexpr double kContactPatch = 0.25;
// Rolling resistance (the lever arm of the normal force against rolling), as a fraction of a
// piece's radius.
constexpr double kRollingResistance = 0.01;

void BulletWorld::build_pieces(const Model& model) {
    Impl& m = *impl_;
    const Mat3 r_obj = rotation_matrix(setup_.object.pose.rotation_deg);
    const Vec3 t_obj = object_translation(model, setup_.object);
    const double scale = setup_.material.density ? *setup_.material.density / model.density : 1.0;
    std::vector<const PieceDriveSettings*> drive(model.pieces.size(), nullptr);
    for (const PieceDriveSettings& d : setup_.object.driven) {
        if (d.piece >= model.pieces.size())
            throw_input_error("[[object.driven]] piece", "piece " + std::to_string(d.piece) + " does not exist (the model has " +
                                                              std::to_string(model.pieces.size()) + " pieces)",
                              "use a piece index from `shatter info MODEL`");
        drive[d.piece] = &d;
    }
    // The object's centre of mass, about which its initial angular velocity turns it.
    Vec3 com = Vec3::Zero();
    double total = 0;
    for (const Piece& p : model.pieces) com += p.mass.mass * p.mass.center, total += p.mass.mass;
    com = r_obj * (total > 0 ? com / total : com) + t_obj;

    m.pieces.resize(model.pieces.size());
    for (uint32_t i = 0; i < model.pieces.size(); ++i) {
        const Piece& piece = model.pieces[i];
        Impl::PieceBody& pb = m.pieces[i];
        Vec3 moments;
        principal_frame(piece.mass.inertia, &pb.principal, &moments);
        pb.model_center = piece.mass.center;
        pb.radius = piece_radius(piece);
        const double mass = piece.mass.mass * scale;
        moments = (moments * scale).cwiseMax(1e-12 * mass * std::pow(std::cbrt(piece.mass.volume), 2));
        // One convex part collides as itself: convex-convex contact is far cheaper than
        // compound-compound (measured 17% of a 1,000-piece step).
        const double margin = collision_margin(piece.mass.volume);
        btCollisionShape* compound = nullptr;
        if (piece.collision.size() == 1) {
            compound = make_part(piece.collision[0], pb.principal, piece.mass.center, margin);
            m.shapes.emplace_back(compound);
        } else {
            auto* parts = new btCompoundShape();
            m.shapes.emplace_back(parts);
            for (const ConvexPart& part : piece.collision) {
                btConvexHullShape* child = make_part(part, pb.principal, piece.mass.center, margin);
                m.shapes.emplace_back(child);
                parts->addChildShape(btTransform::getIdentity(), child);
            }
            compound = parts;
        }
        const Vec3 position = r_obj * piece.mass.center + t_obj;
        const btTransform start = make_transform(r_obj * pb.principal, position);
        const PieceDriveSettings* d = drive[i];
        pb.dynamic = d == nullptr;
        btRigidBody* body = nullptr;
        if (pb.dynamic) {
            body = m.add_body(mass, to_bullet(moments), compound, start, nullptr, setup_.material.surface);
            const Vec3 w = setup_.object.angular_velocity;
            body->setLinearVelocity(to_bullet(setup_.object.velocity + w.cross(position - com)));
            body->setAngularVelocity(to_bullet(w));
        } else if (d->fixed) {
            body = m.add_body(0, btVector3(0, 0, 0), compound, start, nullptr, setup_.material.surface);
        } else {
            const PieceDriveSettings drive_copy = *d;
            m.motions.emplace_back(
                new ScriptedMotion(&time_, start, [drive_copy](double t) { return drive_offset(drive_copy, t); }));
            body = m.add_body(0, btVector3(0, 0, 0), compound, start, m.motions.back().get(), setup_.material.surface);
            body->setCollisionFlags(body->getCollisionFlags() | btCollisionObject::CF_KINEMATIC_OBJECT);
        }
        // A piece lying on a face spins about the contact normal with nothing to stop it: Bullet's
        // friction acts at the contact points, in the plane. Torsional friction of a contact patch
        // of radius a under pressure N is (2/3) mu N a; Bullet combines a pair's as
        // spinning_A mu_B + spinning_B mu_A, so each piece's spinning friction is (2/3) a, with a
        // a quarter of its radius. Bullet adds the torsional row only with rolling friction, which
        // gets a rolling resistance of 1% of the radius (docs/physics.md section 6).
        const double radius = piece_radius(piece);
        body->setSpinningFriction(btScalar(2.0 / 3.0 * kContactPatch * radius));
        body->setRollingFriction(btScalar(kRollingResistance * radius));
        body->setUserIndex(int(i));
        pb.body = body;
    }
}

void BulletWorld::build_joints(const Model& model) {
    Impl& m = *impl_;
    const Mat3 r_obj = rotation_matrix(setup_.object.pose.rotation_deg);
    const Vec3 t_obj = object_translation(model, setup_.object);
    m.joints.resize(model.constraints.size());
    m.pivot.assign(model.constraints.size(), Vec3::Zero());
    m.pivot_at.assign(model.constraints.size(), 0);
    m.links.assign(m.pieces.size(), {});
    for (size_t i = 0; i < model.constraints.size(); ++i) {
        const Constraint& c = model.constraints[i];
        Impl::Joint& j = m.joints[i];
        j.piece_a = c.piece_a;
        j.piece_b = c.piece_b;
        // k, damping and strength from the material and the constraint's area (and, with Young's
        // modulus, its length between the piece centres): core/material_presets.h.
        const ConstraintMaterial cm = constraint_material(setup_.material, model, c);
        j.strength = cm.strength;
        const Impl::PieceBody& a = m.pieces[c.piece_a];
        const Impl::PieceBody& b = m.pieces[c.piece_b];
        if ((!a.dynamic && !b.dynamic) || !(c.area > 0)) continue;  // nothing to solve
        const btVector3 pivot = to_bullet(r_obj * c.pivot + t_obj);
        j.constraint = std::make_unique<CompliantPointConstraint>(
            *a.body, *b.body, a.body->getWorldTransform().inverse() * pivot, b.body->getWorldTransform().inverse() * pivot,
            cm.stiffness, cm.damping, setup_.h);
        j.constraint->set_strength(j.strength);
        if (setup_.bullet_breaking) j.constraint->setBreakingImpulseThreshold(btScalar(j.strength * setup_.h));
        m.world.addConstraint(j.constraint.get(), true);
        j.active = true;
        m.links[c.piece_a].push_back({uint32_t(i), c.piece_b, true});
        m.links[c.piece_b].push_back({uint32_t(i), c.piece_a, false});
    }
}

void BulletWorld::step() {
    time_ += setup_.h;
    impl_->solver.reset_counts();
    Impl& m = *impl_;
    if (!m.elastic_known) {
        m.elastic.assign(m.joints.size(), 0.0);
        for (size_t c = 0; c < m.joints.size(); ++c)
            if (m.joints[c].active && m.joints[c].constraint) m.elastic[c] = Impl::joint_elastic(m.joints[c]);
        m.elastic_known = true;
    }
    m.before.resize(m.bodies.size());
    for (size_t i = 0; i < m.bodies.size(); ++i) {
        const btRigidBody& b = *m.bodies[i];
        const bool gyroscopic = !b.isStaticOrKinematicObject() && (b.getFlags() & BT_ENABLE_GYROSCOPIC_FORCE_IMPLICIT_BODY);
        m.before[i] = {b.getLinearVelocity(), b.getAngularVelocity(), b.getWorldTransform(), b.getInvInertiaTensorWorld(),
                       gyroscopic ? b.computeGyroscopicImpulseImplicit_Body(btScalar(setup_.h)) : btVector3(0, 0, 0)};
    }
    if (m.flying && near_anything()) end_flight();
    if (m.flying) fly();
    else m.world.stepSimulation(btScalar(setup_.h), 0, btScalar(setup_.h));
    ++m.poses;
    m.account_step(setup_.h);
    release_parted_pairs();
}


void BulletWorld::set_step(double h) {
    impl_->residual_known = false;
    setup_.h = h;
    for (auto& j : impl_->joints) {
        if (!j.constraint) continue;
        j.constraint->set_step(h);
        if (setup_.bullet_breaking) j.constraint->setBreakingImpulseThreshold(btScalar(j.strength * h));
    }
}


bool BulletWorld::touches_scene() const {
    const Impl& m = *impl_;
    const auto dynamic_piece = [&](const btCollisionObject* o) {
        const int i = o->getUserIndex();
        return i >= 0 && size_t(i) < m.pieces.size() && m.pieces[size_t(i)].dynamic;
    };
    for (int i = 0; i < m.dispatcher.getNumManifolds(); ++i) {
        const btPersistentManifold* manifold = m.dispatcher.getManifoldByIndexInternal(i);
        const bool a = dynamic_piece(manifold->getBody0()), b = dynamic_piece(manifold->getBody1());
        if (a == b) continue;  // two pieces, or none
        for (int p = 0; p < manifold->getNumContacts(); ++p)
            if (manifold->getContactPoint(p).getDistance() <= 0) return true;
    }
    return false;
}


struct BulletWorld::Snapshot {
    struct Body {
        btTransform transform, interpolation;
        btVector3 linear, angular, interpolation_linear, interpolation_angular;
        int activation;
        btScalar deactivation_time;
    };
    std::vector<Body> bodies;
    double time = 0;
    StepWork work;
};

void BulletWorld::forget_contact_impulses() {
    btDispatcher& d = impl_->dispatcher;
    for (int i = 0; i < d.getNumManifolds(); ++i) {
        btPersistentManifold* m = d.getManifoldByIndexInternal(i);
        for (int p = 0; p < m->getNumContacts(); ++p) {
            btManifoldPoint& point = m->getContactPoint(p);
            point.m_appliedImpulse = 0;
            point.m_appliedImpulseLateral1 = 0;
            point.m_appliedImpulseLateral2 = 0;
        }
    }
}

std::shared_ptr<BulletWorld::Snapshot> BulletWorld::save() const {
    auto s = std::make_shared<Snapshot>();
    s->time = time_;
    s->work = impl_->work;
    for (const auto& b : impl_->bodies)
        s->bodies.push_back({b->getWorldTransform(), b->getInterpolationWorldTransform(), b->getLinearVelocity(),
                             b->getAngularVelocity(), b->getInterpolationLinearVelocity(),
                             b->getInterpolationAngularVelocity(), b->getActivationState(), b->getDeactivationTime()});
    return s;
}

void BulletWorld::restore(const Snapshot& s) {
    time_ = s.time;
    ++impl_->poses;
    impl_->work = s.work;
    impl_->residual_known = false;
    impl_->elastic_known = false;
    for (size_t i = 0; i < s.bodies.size(); ++i) {
        btRigidBody& b = *impl_->bodies[i];
        const Snapshot::Body& v = s.bodies[i];
        b.setWorldTransform(v.transform);
        b.setInterpolationWorldTransform(v.interpolation);
        b.setLinearVelocity(v.linear);
        b.setAngularVelocity(v.angular);
        b.setInterpolationLinearVelocity(v.interpolation_linear);
        b.setInterpolationAngularVelocity(v.interpolation_angular);
        // Rigid flight that ended in the undone step stays ended (its pieces' state is the flight's).
        if (v.activation != DISABLE_SIMULATION && b.getActivationState() != DISABLE_SIMULATION) {
            b.forceActivationState(v.activation);
            b.setDeactivationTime(v.deactivation_time);
        }
        if (b.getMotionState()) b.getMotionState()->setWorldTransform(v.transform);
        b.updateInertiaTensor();
    }
}

double BulletWorld::velocity_jump_force(size_t c, const Snapshot& before) const {
    const auto& j = impl_->joints[c];
    if (!j.active || !j.constraint) return 0;
    const CompliantPointConstraint& k = *j.constraint;
    double jump = 0;
    for (const btRigidBody* b : {&k.getRigidBodyA(), &k.getRigidBodyB()}) {
        const Snapshot::Body& then = before.bodies[size_t(b->getUserIndex2())];
        const btVector3 r = b->getWorldTransform().getBasis() * (b == &k.getRigidBodyA() ? k.getPivotInA() : k.getPivotInB());
        const btVector3 dv = (b->getLinearVelocity() - then.linear) + (b->getAngularVelocity() - then.angular).cross(r);
        jump = std::max(jump, double(dv.length()));
    }
    const double w = k.row_inverse_masses().minCoeff();
    return w > 0 ? jump * std::sqrt(k.stiffness() / w) : HUGE_VAL;
}


void BulletWorld::remove_constraint(size_t c) {
    Impl& m = *impl_;
    auto& j = m.joints[c];
    if (!j.active) return;
    m.residual_known = false;
    m.world.removeConstraint(j.constraint.get());
    j.active = false;
    for (const uint32_t p : {j.piece_a, j.piece_b}) {
        std::vector<Impl::Link>& l = m.links[p];
        l.erase(std::find_if(l.begin(), l.end(), [c](const Impl::Link& x) { return x.joint == c; }));
    }
    // Joined pieces never collide, so a pair whose last joint breaks may overlap by then: partly
    // broken, its remaining joints a hinge, it can turn into itself (up to simulate.h
    // kOverlapBreak of the smaller piece's radius, where the joints left break; before that rule,
    // two of the plate's cubes 18 mm into each other). Their new contact would push that overlap
    // out while the pieces are still joined to others: each step's split-impulse push stretches a
    // stiff joint, whose ERP turns it into speed (4 J in one step: the plate's runaways). Such a
    // pair ignores itself, like a pair that starts overlapping, until it has parted
    // (release_parted_pairs).
    btRigidBody* a = m.pieces[j.piece_a].body;
    btRigidBody* b = m.pieces[j.piece_b].body;
    if (!a->checkCollideWith(b)) return;  // still joined by another constraint
    ContactFound contact(1e-4);
    m.world.contactPairTest(a, b, contact);
    btVector3 lo_a, hi_a, lo_b, hi_b;
    a->getAabb(lo_a, hi_a);
    b->getAabb(lo_b, hi_b);
    if (contact.deepest < -kDeepOverlap * double(least_extent(lo_a, hi_a, lo_b, hi_b)))
        m.dispatcher.ignored.insert(int(j.piece_a), int(j.piece_b));
}

std::array<BodyAtPivot, 2> BulletWorld::bodies_at_pivot(size_t c, Vec3* pivot) const {
    const auto& j = impl_->joints[c];
    const CompliantPointConstraint& k = *j.constraint;
    const btRigidBody& a = k.getRigidBodyA();
    const btRigidBody& b = k.getRigidBodyB();
    *pivot = 0.5 * (to_eigen(a.getWorldTransform() * k.getPivotInA()) + to_eigen(b.getWorldTransform() * k.getPivotInB()));
    const btJointFeedback load = k.load();
    std::array<BodyAtPivot, 2> out;
    const btRigidBody* body[2] = {&a, &b};
    const uint32_t piece[2] = {j.piece_a, j.piece_b};
    const btVector3 force[2] = {load.m_appliedForceBodyA, load.m_appliedForceBodyB};
    const btVector3 torque[2] = {load.m_appliedTorqueBodyA, load.m_appliedTorqueBodyB};
    for (int s = 0; s < 2; ++s) {
        BodyAtPivot& p = out[s];
        p.dynamic = impl_->pieces[piece[s]].dynamic;
        p.inv_mass = body[s]->getInvMass();
        p.inv_inertia = to_eigen(body[s]->getInvInertiaTensorWorld());
        p.r = *pivot - to_eigen(body[s]->getCenterOfMassPosition());
        p.force = to_eigen(force[s]);
        p.torque = to_eigen(torque[s]);
        p.velocity = to_eigen(body[s]->getVelocityInLocalPoint(to_bullet(p.r)));
        p.centre_velocity = to_eigen(body[s]->getLinearVelocity());
    }
    return out;
}

void BulletWorld::apply_kicks(size_t c, const Vec3& pivot, const BreakKicks& kicks) {
    end_flight();
    impl_->residual_known = false;
    const auto& j = impl_->joints[c];
    const uint32_t piece[2] = {j.piece_a, j.piece_b};
    for (int s = 0; s < 2; ++s) {
        if (!impl_->pieces[piece[s]].dynamic || kicks.kick[s].magnitude == 0) continue;
        btRigidBody* body = impl_->pieces[piece[s]].body;
        body->activate();
        body->applyImpulse(to_bullet(kicks.kick[s].impulse), to_bullet(pivot) - body->getCenterOfMassPosition());
    }
}

void BulletWorld::fragments(Fragments* out) const {
    const Impl& m = *impl_;
    out->of.assign(m.pieces.size(), UINT32_MAX);
    out->first.clear();
    out->pieces.clear();
    for (uint32_t p = 0; p < m.pieces.size(); ++p) {
        if (out->of[p] != UINT32_MAX) continue;
        const uint32_t f = uint32_t(out->first.size()), start = uint32_t(out->pieces.size());
        out->first.push_back(start);
        out->of[p] = f;
        out->pieces.push_back(p);
        for (size_t next = start; next < out->pieces.size(); ++next)
            for (const Impl::Link& l : m.links[out->pieces[next]]) {
                if (out->of[l.other] != UINT32_MAX) continue;
                out->of[l.other] = f;
                out->pieces.push_back(l.other);
            }
        std::sort(out->pieces.begin() + start, out->pieces.end());
    }
    out->first.push_back(uint32_t(out->pieces.size()));
}

void BulletWorld::joined_pieces(size_t c, size_t limit, const Fragments& fragments, JoinedPieces* out) const {
    const Impl& m = *impl_;
    const uint32_t start[2] = {m.joints[c].piece_a, m.joints[c].piece_b};
    const uint32_t fragment[2] = {fragments.of[start[0]], fragments.of[start[1]]};
    *out = JoinedPieces{};
    out->parted = fragment[0] != fragment[1];
    if (!out->parted && fragments.size(fragment[0]) > limit) {
        out->held = true;
        return;
    }
    std::vector<int8_t>& side = m.joined_side;
    side.resize(m.pieces.size(), -1);
    for (int s = 0; s < (out->parted ? 2 : 1); ++s) {
        if (s == 1) out->side_b = out->pieces.size();
        const uint32_t f = fragment[s];
        if (fragments.size(f) > limit) {
            // Past the limit: the side moves as one rigid body, its joints are not wanted.
            out->pieces.insert(out->pieces.end(), fragments.pieces.begin() + fragments.first[f],
                               fragments.pieces.begin() + fragments.first[f + 1]);
            continue;
        }
        // Every joint is met from both its pieces: kept from its piece_a.
        const size_t begin = out->pieces.size();
        side[start[s]] = int8_t(s);
        out->pieces.push_back(start[s]);
        for (size_t next = begin; next < out->pieces.size(); ++next)
            for (const Impl::Link& l : m.links[out->pieces[next]]) {
                if (l.is_a) out->joints.push_back(l.joint);
                if (side[l.other] >= 0) continue;
                side[l.other] = int8_t(s);
                out->pieces.push_back(l.other);
            }
        for (size_t i = begin; i < out->pieces.size(); ++i) side[out->pieces[i]] = -1;
    }
    if (!out->parted) out->side_b = out->pieces.size();
    std::sort(out->joints.begin(), out->joints.end());
}

void BulletWorld::joined_bodies(const JoinedPieces& joined, std::vector<JoinedBody>* bodies,
                                std::vector<JoinedJoint>* joints, std::vector<VelocityChange>* velocities) const {
    const Impl& m = *impl_;
    bodies->resize(joined.pieces.size());
    velocities->resize(joined.pieces.size());
    std::vector<uint32_t>& index = m.joined_index;
    index.resize(m.pieces.size(), UINT32_MAX);
    for (size_t i = 0; i < joined.pieces.size(); ++i) {
        const Impl::PieceBody& piece = m.pieces[joined.pieces[i]];
        const btRigidBody& b = *piece.body;
        index[joined.pieces[i]] = uint32_t(i);
        JoinedBody& body = (*bodies)[i];
        body.dynamic = piece.dynamic;
        body.inv_mass = piece.dynamic ? double(b.getInvMass()) : 0.0;
        body.inv_inertia = piece.dynamic ? to_eigen(b.getInvInertiaTensorWorld()) : Mat3::Zero();
        body.centre = to_eigen(b.getCenterOfMassPosition());
        (*velocities)[i] = {to_eigen(b.getLinearVelocity()), to_eigen(b.getAngularVelocity())};
    }
    joints->clear();
    for (uint32_t j : joined.joints)
        joints->push_back({index[m.joints[j].piece_a], index[m.joints[j].piece_b], m.joint_pivot(j)});
    for (uint32_t p : joined.pieces) index[p] = UINT32_MAX;
}

void BulletWorld::add_velocities(const std::vector<uint32_t>& pieces, const std::vector<VelocityChange>& dv) {
    end_flight();
    impl_->residual_known = false;
    for (size_t i = 0; i < pieces.size(); ++i) {
        if (!impl_->pieces[pieces[i]].dynamic) continue;
        btRigidBody* b = impl_->pieces[pieces[i]].body;
        b->activate();
        b->setLinearVelocity(b->getLinearVelocity() + to_bullet(dv[i].linear));
        b->setAngularVelocity(b->getAngularVelocity() + to_bullet(dv[i].angular));
    }
}

Vec3 BulletWorld::frame_velocity(const std::vector<uint32_t>& pieces) const {
    double mass = 0;
    Vec3 momentum = Vec3::Zero();
    for (uint32_t p : pieces) {
        if (!impl_->pieces[p].dynamic) return Vec3::Zero();
        const btRigidBody& b = *impl_->pieces[p].body;
        mass += 1.0 / b.getInvMass();
        momentum += to_eigen(b.getLinearVelocity()) / b.getInvMass();
    }
    return mass > 0 ? Vec3(momentum / mass) : Vec3::Zero();
}


DeepContact BulletWorld::last_step_deepest_contact() const { return impl_->deepest; }


bool BulletWorld::finite() const {
    const auto ok = [](const btRigidBody& b) {
        return to_eigen(b.getCenterOfMassPosition()).allFinite() && to_eigen(b.getLinearVelocity()).allFinite() &&
               to_eigen(b.getAngularVelocity()).allFinite();
    };
    for (const auto& pb : impl_->pieces)
        if (!ok(*pb.body)) return false;
    for (const btRigidBody* b : impl_->projectiles)
        if (!ok(*b)) return false;
    return true;
}

void BulletWorld::scale_piece_velocities(double factor) {
    impl_->residual_known = false;
    for (auto& p : impl_->pieces) {
        if (!p.dynamic) continue;
        p.body->setLinearVelocity(p.body->getLinearVelocity() * factor);
        p.body->setAngularVelocity(p.body->getAngularVelocity() * factor);
    }
}

BodyPose BulletWorld::piece_pose(uint32_t i) const {
    const auto& pb = impl_->pieces[i];
    const btTransform& t = pb.body->getWorldTransform();
    const Mat3 r = to_eigen(t.getBasis()) * pb.principal.transpose();
    BodyPose pose;
    pose.position = to_eigen(t.getOrigin()).cast<float>();
    pose.rotation = Eigen::Quaterniond(r).normalized().cast<float>();
    return pose;
}

BodyPose BulletWorld::prop_pose(uint32_t i) const {
    const btTransform& t = impl_->props[i]->getWorldTransform();
    BodyPose pose;
    pose.position = to_eigen(t.getOrigin()).cast<float>();
    pose.rotation = Eigen::Quaterniond(to_eigen(t.getBasis())).normalized().cast<float>();
    return pose;
}

Vec3 BulletWorld::piece_velocity(uint32_t i) const { return to_eigen(impl_->pieces[i].body->getLinearVelocity()); }
Vec3 BulletWorld::piece_angular_velocity(uint32_t i) const {
    return to_eigen(impl_->pieces[i].body->getAngularVelocity());
}
Vec3 BulletWorld::piece_position(uint32_t i) const {
    return to_eigen(impl_->pieces[i].body->getCenterOfMassPosition());
}
uint32_t BulletWorld::pieces() const { return uint32_t(impl_->pieces.size()); }
uint32_t BulletWorld::props() const { return uint32_t(impl_->props.size()); }
bool BulletWorld::piece_dynamic(uint32_t i) const { return impl_->pieces[i].dynamic; }

}  // namespace shatter
