// shatter simulate MODEL [--shot SHOT] [-o OUT.traj] [--alpha A] ...
#include <chrono>
#include <filesystem>
#include <optional>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "cmd/command.h"
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
    std::optional<double> alpha, stiffness, damping, strength, duration, fps, rate_limit;
    std::optional<uint32_t> substeps, iterations;
    std::optional<uint64_t> seed;
    std::optional<std::string> energy_split, directions, on_instability;
    bool rollback = false;
    bool exact_energy = false;
};

SimulationInput input_from(const SimulateFlags& f) {
    SimulationInput in;
    if (!f.shot.empty()) {
        Shot shot = load_shot(f.shot);
        in = {shot.scene, shot.object, shot.material, shot.simulate};
    }
    override_checked(in.material.alpha, f.alpha, "--alpha", kAlphaLimits);
    override_checked(in.material.stiffness, f.stiffness, "--stiffness", kStiffnessLimits);
    override_checked(in.material.damping, f.damping, "--damping", kDampingLimits);
    override_checked(in.material.strength, f.strength, "--strength", kStrengthLimits);
    override_checked(in.simulate.duration, f.duration, "--duration", kDurationLimits);
    if (f.duration) in.simulate.auto_duration = false;  // a flag's seconds replace the shot's "auto"
    override_checked(in.simulate.fps, f.fps, "--fps", kFpsLimits);
    override_checked(in.simulate.rate_limit, f.rate_limit, "--rate-limit", kRateLimitLimits);
    override_checked(in.simulate.substeps, f.substeps, "--substeps", kSubstepsLimits);
    override_checked(in.simulate.iterations, f.iterations, "--iterations", kIterationsLimits);
    if (f.seed) in.simulate.seed = *f.seed;
    if (f.rollback) in.simulate.rollback = true;
    if (f.exact_energy) in.simulate.exact_energy = true;
    if (f.energy_split)
        in.simulate.energy_split = *f.energy_split == "per_body" ? EnergySplitMode::PerBody : EnergySplitMode::Total;
    if (f.directions)
        in.simulate.directions = *f.directions == "opposed" ? KickDirectionMode::Opposed
                                 : *f.directions == "force" ? KickDirectionMode::Force
                                                            : KickDirectionMode::Paper;
    if (f.on_instability)
        in.simulate.on_instability = *f.on_instability == "clamp" ? InstabilityMode::Clamp : InstabilityMode::Stop;
    return in;
}

std::string sibling(const std::filesystem::path& out, const char* suffix) {
    return (out.parent_path() / (out.stem().string() + suffix)).string();
}

int run(const SimulateFlags& flags) {
    const std::string bytes = read_file(flags.model, "model file");
    const Model model = decode_model(bytes, flags.model);
    const SimulationInput in = input_from(flags);
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
    const double h = 1.0 / (in.simulate.fps * in.simulate.substeps);
    fmt::print("simulate: {} frames ({:g} s at {:g} fps), {} steps of {:.4g} s, {} pieces, {} of {} constraints broke\n",
               r.trajectory.frames(), in.simulate.duration, in.simulate.fps, r.steps, h, model.pieces.size(),
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
    const MaterialSettings m;
    const SimulateSettings s;
    CLI::App* c = root.add_subcommand(
        "simulate", "Simulate a model's pieces as rigid bodies joined by breakable compliant constraints, with "
                    "energized fracture. Writes OUT.traj, OUT.breaks.jsonl and OUT.energy.csv.");
    c->add_option("model", f->model, "the model file written by prescore")->required();
    c->add_option("--shot", f->shot, "a shot file (.toml) with [scene], [object], [material] and [simulate] sections");
    c->add_option("-o,--output", f->output, option_help("the trajectory file to write", "", "MODEL-STEM.traj"));
    c->add_option("--alpha", f->alpha,
                  option_help("fraction of a broken constraint's stored energy given back as kinetic energy (0: plain "
                              "breaking; > 1 for artistic effect)", "", fmt::format("{:g}", m.alpha)));
    c->add_option("--stiffness", f->stiffness,
                  option_help("constraint stiffness per m^2 of the area it stands for", "N/m^3",
                              fmt::format("{:g}", m.stiffness)));
    c->add_option("--damping", f->damping,
                  option_help("constraint damping per m^2", "N s/m^3", fmt::format("{:g}", m.damping)));
    c->add_option("--strength", f->strength,
                  option_help("tensile strength: a constraint breaks when its force exceeds strength x area", "Pa",
                              fmt::format("{:g}", m.strength)));
    c->add_option("--duration", f->duration, option_help("simulated time", "s", fmt::format("{:g}", s.duration)));
    c->add_option("--fps", f->fps, option_help("frames recorded per second", "1/s", fmt::format("{:g}", s.fps)));
    c->add_option("--substeps", f->substeps,
                  option_help("solver steps per frame (step h = 1 / (fps x substeps))", "", std::to_string(s.substeps)));
    c->add_option("--iterations", f->iterations,
                  option_help("solver iterations per step", "", std::to_string(s.iterations)));
    c->add_option("--rate-limit", f->rate_limit,
                  option_help("least time between two breaks (the paper's chain: 0.3); 0 = off", "s",
                              fmt::format("{:g}", s.rate_limit)));
    c->add_flag("--rollback", f->rollback,
                "re-run a step in which constraints broke, without them, before energizing (default: off)");
    c->add_flag("--exact-energy", f->exact_energy,
                "solve each break's impulse for the bodies' motion so that the kinetic energy gained is exactly alpha E "
                "(the paper's formula is exact only for bodies at rest) (default: off)");
    c->add_option("--energy-split", f->energy_split,
                  option_help("total: two bodies at rest gain alpha E in all; per_body: each gains alpha E (the "
                              "paper read literally)", "", to_string(s.energy_split)))
        ->check(CLI::IsMember({"total", "per_body"}));
    c->add_option("--directions", f->directions,
                  option_help("paper: each body kicked along -(torque x force); opposed: equal and opposite kicks that "
                              "conserve momentum; force: equal and opposite kicks along the joint's load, never into the "
                              "partner", "", to_string(s.directions)))
        ->check(CLI::IsMember({"paper", "opposed", "force"}));
    c->add_option("--on-instability", f->on_instability,
                  option_help("when the kinetic energy runs away (beyond what the scene supplies + 10%): stop (keep the "
                              "frames before, marked incomplete, exit 5) or clamp (scale the speeds down and go on; a NaN "
                              "still stops)", "", to_string(s.on_instability)))
        ->check(CLI::IsMember({"stop", "clamp"}));
    c->add_option("--seed", f->seed, option_help("seed of random kick directions", "", std::to_string(s.seed)));
    return [f] { return run(*f); };
}

}  // namespace shatter
