// simulate benchmark: steps per second, and the cost of energizing (alpha = 1 against alpha = 0
// on the same scene, and the time spent inside energizing itself; steps per CPU second too, since
// the machine is shared), on the bunny and on plates of
// 100 to 10,000 box pieces dropped flat on the ground. Prints CSV; never fails on time.
// Arguments (optional): a scene name to run only that scene (bunny, bunny1000, plate10, plate32,
// plate100),
// then the solver iterations for the plates (default 20, as shipped), then the alphas to run (default "01"),
// then the joint solve ("auto", as shipped, "iterative" or "direct"; [simulate] joints; when not
// given, bunny1000, plate32 and plate100 run with iterative joints too, beside), then what the kicks
// move ("pieces" or "joined"; [simulate] kick_bodies; default as shipped), then the fall ("rigid": rigid
// flight, as shipped, or "solved": every joint solved in every step of it; [simulate] rigid_flight), then
// whether pieces at rest sleep ("sleep", as shipped, or "awake"; [simulate] sleep).
// SHATTER_BENCH_LOG set: the simulation's info lines too (the joint solve "auto" chose, where rigid
// flight ended). Goals (docs/benchmarks.md): energizing costs at most 2%; a 1,000-piece scene with >= 5,000
// constraints runs at >= 60 steps per second. Each row also has the breaking joints' books: the
// energy their forces stored, what their stretch held, and the ratio of the two.
#include <chrono>
#include <ctime>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "core/log.h"
#include "prescore/prescore.h"
#include "scenes/box_model.h"
#include "simulate/simulate.h"

using namespace shatter;

namespace {

uint32_t g_iterations = 20;                    // the shipped default ([simulate] iterations)
JointSolve g_joints = JointSolve::Auto;  // the shipped default ([simulate] joints)
// No joint solve named: the goal scenes (bunny1000, plate32, plate100) run with the shipped
// joints and, after each, with iterative ones, side by side in one run.
bool g_beside_iterative = true;
KickBodiesMode g_kick_bodies = SimulateSettings{}.kick_bodies;  // the shipped default ([simulate] kick_bodies)
bool g_rigid_flight = SimulateSettings{}.rigid_flight;           // the shipped default ([simulate] rigid_flight)
bool g_sleep = SimulateSettings{}.sleep;                         // the shipped default ([simulate] sleep)

void run(const char* name, const Model& model, SimulationInput in, double alpha,
         JointSolve joints = g_joints) {
    in.material.alpha = alpha;
    in.simulate.joints = joints;
    in.simulate.kick_bodies = g_kick_bodies;
    in.simulate.rigid_flight = g_rigid_flight;
    in.simulate.sleep = g_sleep;
    const auto t0 = std::chrono::steady_clock::now();
    const std::clock_t c0 = std::clock();
    const SimulationResult r = simulate(model, in, "bench");
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const double cpu = double(std::clock() - c0) / CLOCKS_PER_SEC;
    // The recorded poses' bytes, hashed (FNV-1a): two builds that agree here made the same film.
    uint64_t hash = 1469598103934665603ull;
    for (const BodyPose& p : r.trajectory.poses) {
        const float f[7] = {p.position.x(), p.position.y(), p.position.z(), p.rotation.w(),
                            p.rotation.x(),  p.rotation.y(),  p.rotation.z()};
        const auto* bytes = reinterpret_cast<const unsigned char*>(f);
        for (size_t i = 0; i < sizeof(f); ++i) hash = (hash ^ bytes[i]) * 1099511628211ull;
    }
    // The books of the breaks: what the broken joints' forces stored, and what they held by their
    // stretch (equal when the joints' forces match their stretch; docs/physics.md section 5b).
    double stored = 0;
    for (const BreakRecord& b : r.breaks) stored += b.kicks.stored_energy;
    const double stretch = r.energy.empty() ? 0.0 : r.energy.back().removed;
    const char* solve = solves_joints_directly(model, in.simulate) ? "+direct"
                        : in.simulate.joints == JointSolve::Iterative ? "+iterative"
                                                                       : "";
    std::printf("%s%s,%zu,%zu,%u,%g,%llu,%zu,%zu,%016llx,%.4f,%.1f,%.1f,%.6f,%.3f,%u,%.1f,%.4g,%.4g,%.3g\n", name, solve,
                model.pieces.size(),
                model.constraints.size(), in.simulate.iterations, alpha, static_cast<unsigned long long>(r.steps),
                r.breaks.size(), count_fragments(model, r.breaks), static_cast<unsigned long long>(hash), s,
                double(r.steps) / s, double(r.steps) / cpu, r.energize_seconds,
                100.0 * r.energize_seconds / s, r.asleep, r.steps ? double(r.solver_iterations) / double(r.steps) : 0.0,
                stored, stretch, stored > 0 ? stretch / stored : 0.0);
    std::fflush(stdout);
}

// The paper's plate scene at scale: the plate falls flat onto a sphere and breaks over it.

SimulationInput plate_drop(double duration, uint32_t n) {
    SimulationInput in;
    ColliderSettings sphere;
    sphere.shape.kind = ShapeKind::Sphere;
    sphere.shape.radius = 0.005 * n;
    sphere.pose.position = Vec3(0, sphere.shape.radius, 0);
    in.scene.colliders.push_back(sphere);
    in.object.pose.position = Vec3(0, 2 * sphere.shape.radius + 0.2, 0);
    in.material.stiffness = 1e11;  // N/m^3
    in.material.strength = 2e5;    // Pa
    in.simulate.duration = duration;
    in.simulate.fps = 30;
    in.simulate.substeps = 8;
    in.simulate.iterations = g_iterations;
    return in;
}

}  // namespace

int main(int argc, char** argv) {
    // The log goes to standard error: standard output is the CSV (make bench keeps it).
    setup_logging(getenv("SHATTER_BENCH_LOG") ? "info" : "warn");
    const std::string only = argc > 1 ? argv[1] : "";
    if (argc > 2) g_iterations = uint32_t(std::stoul(argv[2]));
    const std::string alphas = argc > 3 ? argv[3] : "01";
    if (argc > 4) g_beside_iterative = false;
    if (argc > 4)
        g_joints = std::string(argv[4]) == "direct"      ? JointSolve::Direct
                   : std::string(argv[4]) == "iterative" ? JointSolve::Iterative
                                                         : JointSolve::Auto;
    if (argc > 5) g_kick_bodies = std::string(argv[5]) == "joined" ? KickBodiesMode::Joined : KickBodiesMode::Pieces;
    if (argc > 6) g_rigid_flight = std::string(argv[6]) != "solved";
    if (argc > 7) g_sleep = std::string(argv[7]) != "awake";
    const auto wanted = [&](const std::string& name) { return only.empty() || only == name; };
    std::printf("scene,pieces,constraints,iterations,alpha,steps,breaks,fragments,poses_hash,wall_s,steps_per_s,steps_per_cpu_s,energize_s,"
                "energize_percent,asleep,iterations_per_step,stored_J,stretch_J,stretch_over_stored\n");

    if (wanted("bunny")) {
    MeshSettings mesh;
    mesh.path = "/usr/share/glmark2/models/bunny.obj";
    mesh.scale = 0.1;
    PrescoreSettings ps;
    ps.hollow = Length{0.06, true};
    const Model bunny = prescore(mesh, ps, nullptr);
    SimulationInput drop;
    drop.object.pose.position = Vec3(0, 1.0, 0);
    drop.material.stiffness = 4e10;
    drop.material.strength = 1e6;
    drop.simulate.duration = 2.0;
    for (char a : alphas) run("bunny", bunny, drop, a - '0');
    }

    // The demo's bunny (assets/bunny.toml: hollow, 1.5 m drop, h = 1/480 s) cut finer, at resolution
    // 60 into 1,000 pieces with every shared vertex joined (~38,000 tets, ~31,000 constraints),
    // for 1.5 s (720 steps): a real mesh at 1,000 pieces, which breaks into hundreds of fragments.
    if (wanted("bunny1000")) {
    MeshSettings mesh;
    mesh.path = "/usr/share/glmark2/models/bunny.obj";
    mesh.scale = 0.1;
    PrescoreSettings ps;
    ps.hollow = Length{0.06, true};
    ps.resolution = 60;
    ps.pieces = 1000;
    ps.density = 1100;
    ps.render_surface = false;
    const Model bunny = prescore(mesh, ps, nullptr);
    SimulationInput drop;
    drop.object.pose.position = Vec3(0, 1.5, 0);
    drop.material.stiffness = 3e9;
    drop.material.strength = 2e4;
    drop.material.surface = SurfaceSettings{0.6, 0.1};
    drop.simulate.duration = 1.5;
    drop.simulate.substeps = 16;
    for (char a : alphas) {
        run("bunny1000", bunny, drop, a - '0');
        if (g_beside_iterative) run("bunny1000", bunny, drop, a - '0', JointSolve::Iterative);
    }
    }

    // Plates of n x n cubes of 2 cm, joined by 4 constraints per shared face.
    for (uint32_t n : {10u, 32u, 100u}) {
        const std::string name = "plate" + std::to_string(n);
        if (!wanted(name)) continue;
        const Model plate = box_grid(n, 1, n, 0.02, Vec3(-0.01 * n, 0, -0.01 * n), 2400, 2);
        const double duration = n <= 32 ? 1.0 : 0.25;
        for (char a : alphas) {
            run(name.c_str(), plate, plate_drop(duration, n), a - '0');
            if (g_beside_iterative && n >= 32) run(name.c_str(), plate, plate_drop(duration, n), a - '0', JointSolve::Iterative);
        }
    }
    return 0;
}
