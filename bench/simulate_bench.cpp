// simulate benchmark: steps per second, and the cost of energizing (alpha = 1 against alpha = 0
// on the same scene, and the time spent inside energizing itself), on the bunny and on plates of
// 100 to 10,000 box pieces dropped flat on the ground. Prints CSV; never fails on time.
// Goals (issue 3): energizing costs at most 2%; a 1,000-piece scene with >= 5,000 constraints
// runs at >= 60 steps per second.
#include <chrono>
#include <cstdio>
#include <string>

#include <spdlog/spdlog.h>

#include "prescore/prescore.h"
#include "scenes/box_model.h"
#include "simulate/simulate.h"

using namespace shatter;

namespace {

void run(const char* name, const Model& model, SimulationInput in, double alpha) {
    in.material.alpha = alpha;
    const auto t0 = std::chrono::steady_clock::now();
    const SimulationResult r = simulate(model, in, "bench");
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::printf("%s,%zu,%zu,%g,%llu,%zu,%.4f,%.1f,%.6f,%.3f\n", name, model.pieces.size(), model.constraints.size(),
                alpha, static_cast<unsigned long long>(r.steps), r.breaks.size(), s, double(r.steps) / s,
                r.energize_seconds, 100.0 * r.energize_seconds / s);
    std::fflush(stdout);
}

SimulationInput plate_drop(double duration) {
    SimulationInput in;
    in.object.pose.position = Vec3(0, 0.3, 0);
    in.material.stiffness = 1e11;  // N/m^3
    in.material.strength = 2e5;    // Pa: the 30 cm drop breaks part of the plate
    in.simulate.duration = duration;
    in.simulate.fps = 30;
    in.simulate.substeps = 8;
    in.simulate.iterations = 10;
    return in;
}

}  // namespace

int main() {
    spdlog::set_level(spdlog::level::warn);
    std::printf("scene,pieces,constraints,alpha,steps,breaks,wall_s,steps_per_s,energize_s,energize_percent\n");

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
    for (double alpha : {0.0, 1.0}) run("bunny", bunny, drop, alpha);

    // Plates of n x n cubes of 2 cm, joined by 4 constraints per shared face.
    for (uint32_t n : {10u, 32u, 100u}) {
        const Model plate = box_grid(n, 1, n, 0.02, Vec3(-0.01 * n, 0, -0.01 * n), 2400, 2);
        const double duration = n <= 32 ? 1.0 : 0.25;
        for (double alpha : {0.0, 1.0}) run(("plate" + std::to_string(n)).c_str(), plate, plate_drop(duration), alpha);
    }
    return 0;
}
