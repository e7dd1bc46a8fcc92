// The paper's scenes (assets/beam, plate, chain, bunny_sphere) over their alpha sweeps: prints
// one CSV row per scene and alpha with the breaks, the energy books and the fragments' energy
// after the first break (docs/results/scenes.md holds the sweeps' results; docs/scenes.md says how
// to read them).
//
//   scenes_bench [SCENE ...] [--set SECTION.KEY=VALUE ...] [--alpha A,B,...]
#include <chrono>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <string>
#include <vector>

#include "core/fragments.h"
#include "core/shot.h"
#include "prescore/prescore.h"
#include "simulate/simulate.h"

namespace shatter {
namespace {

std::vector<double> default_alphas(const std::string& scene) {
    if (scene == "beam" || scene == "plate") return {0, 0.5, 1, 1.5};
    return {0, 0.5, 1, 2};
}

// The first recorded frame at or after t (the last if none).
const EnergySample& sample_at(const std::vector<EnergySample>& e, double t) {
    for (const EnergySample& s : e)
        if (s.time >= t - 1e-9) return s;
    return e.back();
}

size_t fragments(const Model& model, const SimulationResult& r) { return count_fragments(model, r.breaks); }

void run(const std::string& scene, const std::vector<std::string>& sets, std::vector<double> alphas) {
    const bool file = scene.size() > 5 && scene.substr(scene.size() - 5) == ".toml";  // a shot file, not a name
    const Shot shot = load_shot(file ? scene : SHATTER_SOURCE_DIR "/assets/" + scene + ".toml", sets);
    const Model model = prescore_shot(shot, nullptr);
    if (alphas.empty()) alphas = default_alphas(scene);
    for (double alpha : alphas) {
        SimulationInput in{shot.scene, shot.object, shot.material, shot.simulate};
        in.material.alpha = alpha;
        const auto start = std::chrono::steady_clock::now();
        const SimulationResult r = simulate(model, in, "bench");
        const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        double stored = 0, injected = 0;
        for (const BreakRecord& b : r.breaks) {
            stored += b.kicks.stored_energy;
            injected += b.injected_energy;
        }
        const double t0 = r.breaks.empty() ? -1 : r.breaks.front().time;
        double before = 0, at_break = 0, later = 0, mech = 0;
        if (!r.breaks.empty()) {
            const EnergySample* pre = &r.energy.front();
            for (const EnergySample& e : r.energy)
                if (e.time < t0 - 1e-9) pre = &e;
            const EnergySample& first = sample_at(r.energy, t0);
            const EnergySample& post = sample_at(r.energy, t0 + 0.1);
            before = pre->kinetic;
            at_break = first.kinetic;
            later = post.kinetic;
            mech = post.kinetic + post.potential - pre->kinetic - pre->potential;
        }
        // The spread (kinetic energy about the common centre of mass) 10, 50 and 100 ms after the
        // first break, from the recorded frames (record at a higher fps for a finer look).
        double spread[3] = {0, 0, 0};
        const double after[3] = {0.01, 0.05, 0.1};
        for (int i = 0; i < 3 && t0 >= 0; ++i)
            spread[i] = spread_energy(model, r.trajectory, uint32_t(std::lround((t0 + after[i]) * r.trajectory.fps)));
        std::printf("%s,%g,%zu,%.4f,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%zu,%d,%.2f\n", scene.c_str(), alpha,
                    r.breaks.size(), t0, stored, injected, before, at_break, later, mech, spread[0], spread[1], spread[2],
                    fragments(model, r), r.complete ? 1 : 0, seconds);
        std::fflush(stdout);
    }
}

}  // namespace
}  // namespace shatter

int main(int argc, char** argv) {
    std::vector<std::string> scenes, sets;
    std::vector<double> alphas;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        if (a == "--set" && i + 1 < argc) {
            sets.push_back(argv[++i]);
        } else if (a == "--alpha" && i + 1 < argc) {
            std::stringstream list(argv[++i]);
            for (std::string x; std::getline(list, x, ',');) alphas.push_back(std::stod(x));
        } else {
            scenes.push_back(a);
        }
    }
    if (scenes.empty()) scenes = {"beam", "plate", "chain", "bunny_sphere"};
    std::printf("scene,alpha,breaks,first_break_s,stored_J,injected_J,kinetic_before_J,kinetic_at_break_frame_J,"
                "kinetic_0.1s_after_J,mechanical_gain_0.1s_after_J,spread_10ms_J,spread_50ms_J,spread_100ms_J,fragments,"
                "complete,seconds\n");
    try {
        for (const std::string& s : scenes) shatter::run(s, sets, alphas);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "%s\n", e.what());
        return 1;
    }
    return 0;
}
