// BulletWorld's state (the pimpl), shared by the files that implement it: bullet_world.cpp (the
// adapter: building the world, stepping it, saving and restoring it, breaking and kicking),
// bullet_world_books.cpp (the energy books: the work each step does, the energies) and
// bullet_world_joints.cpp (the joints: their forces, stretch, residuals and loads). Included only
// by those three.
#pragma once

#include <btBulletDynamicsCommon.h>

#include <memory>
#include <vector>

#include "simulate/bullet_collision.h"
#include "simulate/bullet_convert.h"
#include "simulate/bullet_solver.h"
#include "simulate/bullet_world.h"
#include "simulate/compliant_constraint.h"
#include "core/workers.h"

namespace shatter {

struct BulletWorld::Impl {
    std::unique_ptr<Workers> workers;  // (first: the dispatcher holds it until the world is gone)
    btDefaultCollisionConfiguration config;
    PieceDispatcher dispatcher{&config};
    // Sweep and prune keeps exactly the pairs whose boxes overlap; btDbvtBroadphase keeps every
    // pair within its fixed 5 cm fattening (~110,000 for a 1,024-piece plate of 2 cm pieces),
    // which the near callback then walks every step. Boxes beyond the world bounds are clamped
    // to them (still correct, only less culled); 32-bit quantization over 2 km is ~1e-6 m,
    // rounded outwards.
    explicit Impl(uint32_t objects)
        : broadphase(btVector3(-kWorldHalfSize, -kWorldHalfSize, -kWorldHalfSize),
                     btVector3(kWorldHalfSize, kWorldHalfSize, kWorldHalfSize), objects + 1) {
        // Convex against a plane, Bullet finds the hull's one deepest point a step: a small piece
        // landing fast pivots on that corner while its others go through, and sinks (a 1 cm cube
        // from 1 m in steps of 1/120 s: 40 mm under the ground where the step took it 11.7 mm).
        // While a manifold holds fewer than three points, three more come from the hull turned
        // slightly: it is stopped whole.
        config.setPlaneConvexMultipointIterations(3, 3);
    }
    static constexpr btScalar kWorldHalfSize = 1000;  // (unit: m)
    bt32BitAxisSweep3 broadphase;
    PieceSolver solver;
    PieceWorld world{&dispatcher, &broadphase, &solver, &config};

    struct PieceBody {
        btRigidBody* body = nullptr;
        Mat3 principal = Mat3::Identity();  // body axes in the model frame
        Vec3 model_center = Vec3::Zero();
        bool dynamic = true;
        bool may_sleep = false;  // WorldSetup::sleep_speed
        double radius = 0;       // piece_radius (unit: m)
    };
    struct Joint {
        std::unique_ptr<CompliantPointConstraint> constraint;  // null when both ends are scripted
        uint32_t piece_a = 0, piece_b = 0;
        double strength = 0;
        bool active = false;
    };
    std::vector<PieceBody> pieces;
    std::vector<btRigidBody*> props;        // the kinematic bodies, then the projectiles
    std::vector<btRigidBody*> projectiles;  // dynamic: in the books beside the pieces
    std::vector<Joint> joints;
    // Each piece's active joints, in the order they were added (a break takes its joint out of
    // both lists, keeping the order): joined_pieces walks these, never the broken joints.
    struct Link {
        uint32_t joint;
        uint32_t other;  // the piece at the joint's other end
        bool is_a;       // the piece holding the list is the joint's piece_a
    };
    std::vector<std::vector<Link>> links;
    mutable std::vector<uint32_t> joined_index;  // joined_bodies' scratch: per piece, UINT32_MAX between calls
    mutable std::vector<int8_t> joined_side;     // joined_pieces' scratch: per piece, -1 between calls
    // Each joint's pivot (the mean of where its two pieces place it) as of pose count pivot_at[j]:
    // the breaks of one step read the pivots of the same joined pieces again and again (a
    // 1,000-piece bunny's impact breaks hundreds of joints in a step, each kick solved through up
    // to kJoinedPiecesLimit pieces). `poses` counts the changes of the bodies' poses.
    mutable std::vector<Vec3> pivot;
    mutable std::vector<uint64_t> pivot_at;
    uint64_t poses = 1;
    const Vec3& joint_pivot(uint32_t j) const {
        if (pivot_at[j] != poses) {
            const CompliantPointConstraint& k = *joints[j].constraint;
            pivot[j] = 0.5 * (to_eigen(k.getRigidBodyA().getWorldTransform() * k.getPivotInA()) +
                              to_eigen(k.getRigidBodyB().getWorldTransform() * k.getPivotInB()));
            pivot_at[j] = poses;
        }
        return pivot[j];
    }
    // The books of the steps (BulletWorld::StepWork), each joint's elastic energy after the last
    // step (elastic_known: still the poses'), and every body's velocities and pose before the
    // step (where the solver took the impulses' lever arms).
    StepWork work;
    std::vector<double> elastic;
    bool elastic_known = false;
    struct Before {
        btVector3 linear, angular;
        btTransform pose;
        btMatrix3x3 inv_inertia;  // world frame
        btVector3 gyroscopic;     // the step's change of angular velocity by Bullet's implicit gyroscopic term
    };
    std::vector<Before> before;
    bool flying = false;      // rigid flight (BulletWorld::flying)
    double flight_end = 0;    // (unit: s)
    // The largest joint residual after the last step and where, while nothing has changed since.
    double residual_max = 0;
    int64_t residual_worst = -1;
    bool residual_known = false;
    // The last step's deepest contact for its piece's size (BulletWorld::last_step_deepest_contact).
    DeepContact deepest;
    void account_step(double h);  // after a step of h (unit: s)
    static double joint_elastic(const Joint& j);  // k |d|^2 / 2 from the poses (unit: J)
    static bool asleep(const btCollisionObject& b) { return b.getActivationState() == ISLAND_SLEEPING; }
    // Not in a sleeping island (joined pieces share their island).
    static bool awake(const Joint& j) {
        return !asleep(j.constraint->getRigidBodyA()) || !asleep(j.constraint->getRigidBodyB());
    }
    // Moved by the step, or in rigid flight: dynamic and not asleep.
    static bool moving(const btRigidBody& b) { return !b.isStaticOrKinematicObject() && !asleep(b); }
    // |f - (k d + c d')| / strength: the joint's force on A against its spring's (joint_residual).
    static double spring_residual(const Joint& j, const Vec3& stretch, const Vec3& rate, const Vec3& force) {
        const Vec3 spring = j.constraint->stiffness() * stretch + j.constraint->damping() * rate;
        return (force - spring).norm() / j.strength;
    }
    std::vector<std::unique_ptr<btCollisionShape>> shapes;
    std::vector<std::unique_ptr<btMotionState>> motions;
    std::vector<std::unique_ptr<btRigidBody>> bodies;
    std::vector<std::unique_ptr<btTriangleIndexVertexArray>> triangle_arrays;
    std::vector<TriangleMesh> collider_meshes;
    Vec3 gravity = Vec3::Zero();

    static double stored_energy_of(const Joint& j);

    // A kinematic body's or projectile's shape: a sphere or a box, owned by `shapes`.
    btCollisionShape* prop_shape(const ShapeSettings& s) {
        shapes.emplace_back(s.kind == ShapeKind::Sphere ? static_cast<btCollisionShape*>(new btSphereShape(btScalar(s.radius)))
                                                        : new btBoxShape(to_bullet(0.5 * s.size)));
        return shapes.back().get();
    }

    btRigidBody* add_body(double mass, const btVector3& inertia, btCollisionShape* shape, const btTransform& t,
                          btMotionState* motion, const SurfaceSettings& surface) {
        btRigidBody::btRigidBodyConstructionInfo info(btScalar(mass), motion, shape, inertia);
        info.m_startWorldTransform = t;
        info.m_friction = btScalar(surface.friction);
        info.m_restitution = btScalar(surface.restitution);
        auto body = std::make_unique<btRigidBody>(info);
        if (!motion) body->setWorldTransform(t);
        body->setActivationState(DISABLE_DEACTIVATION);
        world.addRigidBody(body.get());
        body->setUserIndex2(int(bodies.size()));  // its place in `bodies` (account_step)
        bodies.push_back(std::move(body));
        return bodies.back().get();
    }
};

}  // namespace shatter
