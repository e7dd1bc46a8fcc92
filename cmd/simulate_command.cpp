// shatter simulate MODEL [--shot SHOT] [-o OUT.traj] [--set SECTION.KEY=VALUE]... [--alpha A] ...
#include <chrono>
#include <filesystem>
#include <memory>

#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <spdlog/spdlog.h>

#include "cmd/command.h"
#include "cmd/setting_flags.h"
#include "core/atomic_file.h"
#include "core/binary_io.h"
#include "core/error.h"
#include "core/model_io.h"
#include "core/shot.h"
#include "core/trajectory.h"
#include "simulate/recording.h"
#include "simulate/simulate.h"

namespace shatter {

namespace {

struct SimulateFlags {
    std::string model;
    std::string shot;
    std::string output;
    std::unique_ptr<SettingFlags> settings;
};

SimulationInput input_from(const SimulateFlags& f) {
    const std::vector<std::string>& sets = f.settings->overrides();
    Shot shot = f.shot.empty() ? shot_from_overrides(sets) : load_shot(f.shot, sets);
    f.settings->apply(shot);
    return {shot.scene, shot.object, shot.material, shot.simulate};
}

std::string sibling(const std::filesystem::path& out, const char* suffix) {
    return (out.parent_path() / (out.stem().string() + suffix)).string();
}

int run(const SimulateFlags& flags) {
    const SimulationInput in = input_from(flags);  // the flags' errors before the model's
    const std::string bytes = read_file(flags.model, "model file");
    const Model model = decode_model(bytes, flags.model);
    const std::filesystem::path out =
        flags.output.empty() ? std::filesystem::path(flags.model).stem().string() + ".traj" : flags.output;
    if (out.has_parent_path()) make_directories(out.parent_path().string());

    const auto start = std::chrono::steady_clock::now();
    const SimulationResult r = simulate(model, in, fmt::format("{:016x}", fnv1a64(bytes)));
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

    const std::string breaks = sibling(out, ".breaks.jsonl"), energy = sibling(out, ".energy.csv");
    save_trajectory(out.string(), r.trajectory);
    write_file_atomic(breaks, break_log_jsonl(r.breaks));
    write_file_atomic(energy, energy_csv(r.energy));

    double stored = 0, injected = 0;
    for (const BreakRecord& b : r.breaks) stored += b.kicks.stored_energy, injected += b.injected_energy;
    const std::string steps =
        in.simulate.auto_substeps
            ? fmt::format("{} steps chosen as it went (substeps = \"auto\"; {} probe steps re-run finer)", r.steps,
                          r.rejected_steps)
            : fmt::format("{} steps of {:.4g} s", r.steps, 1.0 / (in.simulate.fps * in.simulate.substeps));
    fmt::print("simulate: {} frames ({:g} s at {:g} fps), {}, {} pieces ({} asleep at the end), {} of {} constraints "
               "broke\n",
               r.trajectory.frames(), in.simulate.duration, in.simulate.fps, steps, model.pieces.size(), r.asleep,
               r.breaks.size(), model.constraints.size());
    fmt::print("energy:   {:.6g} J stored in the broken constraints, {:.6g} J injected (alpha {:g})\n", stored, injected,
               in.material.alpha);
    fmt::print("time:     {:.3f}s ({:.0f} steps/s)\n", seconds, seconds > 0 ? r.steps / seconds : 0.0);
    fmt::print("wrote:    {} (trajectory), {} (breaks), {} (energy)\n", out.string(), breaks, energy);
    if (!r.complete) {
        spdlog::error("the simulation stopped early: {}; the frames before are kept, marked incomplete", r.stop_reason);
        return static_cast<int>(ExitCode::Unstable);
    }
    return 0;
}

}  // namespace

RunCommand add_simulate_command(CLI::App& root) {
    auto f = std::make_shared<SimulateFlags>();
    CLI::App* c = root.add_subcommand(
        "simulate", "Simulate a model's pieces as rigid bodies joined by breakable compliant constraints, with "
                    "energized fracture. Writes OUT.traj, OUT.breaks.jsonl and OUT.energy.csv.");
    c->add_option("model", f->model, "the model file written by prescore")->required();
    c->add_option("--shot", f->shot, "a shot file (.toml) with [scene], [object], [material] and [simulate] sections");
    c->add_option("-o,--output", f->output, option_help("the trajectory file to write", "", "MODEL-STEM.traj"));
    f->settings = std::make_unique<SettingFlags>(*c, "simulate",
                                                 std::vector<std::string>{"scene", "object", "material", "simulate"});
    return [f] { return run(*f); };
}

}  // namespace shatter
