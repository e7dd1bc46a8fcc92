// shatter prescore MESH|SHOT [-o OUT.model] [--set SECTION.KEY=VALUE]... [--pieces N] [--hollow T | --solid] ...
#include <algorithm>
#include <filesystem>
#include <memory>
#include <utility>
#include <vector>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <nlohmann/json.hpp>
#include <spdlog/spdlog.h>

#include "cmd/command.h"
#include "cmd/setting_flags.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "core/model_io.h"
#include "core/shot.h"
#include "prescore/prescore.h"

namespace shatter {

namespace {

struct PrescoreFlags {
    std::string input;
    std::string output;
    std::unique_ptr<SettingFlags> settings;
};

// A generated object ([generate]) is built from boxes: the mesh and tet flags do not apply.
void refuse_mesh_flags(const PrescoreFlags& f) {
    for (const char* section : {"mesh", "prescore"}) {
        const std::string flag = f.settings->first_given(section);
        if (!flag.empty())
            throw Error(ExitCode::Usage,
                        fmt::format("{}: {} has [generate]: its object is built from boxes, not from a mesh (fix: "
                                    "remove {}, or change the [generate] section)", flag, f.input, flag));
    }
}

Shot shot_from(const PrescoreFlags& f) {
    const std::vector<std::string>& sets = f.settings->overrides();
    Shot shot;
    if (is_shot_path(f.input)) {
        shot = load_shot(f.input, sets);
        if (shot.generate) {
            refuse_mesh_flags(f);
            return shot;
        }
        if (shot.mesh.path.empty())
            throw_input_error(f.input, "the shot has no [mesh] path",
                              "add path = \"your.obj\" under [mesh], or [generate] (docs/shot.md)");
    } else {
        shot = shot_from_overrides(sets);
        if (shot.mesh.path.empty()) shot.mesh.path = f.input;
    }
    f.settings->apply(shot);
    return shot;
}

std::string default_output(const std::string& input) {
    return std::filesystem::path(input).stem().string() + ".model";
}

int run(const PrescoreFlags& flags) {
    Shot shot = shot_from(flags);
    const std::string out = flags.output.empty() ? default_output(flags.input) : flags.output;
    const std::filesystem::path out_path(out);
    if (out_path.has_parent_path()) make_directories(out_path.parent_path().string());

    PrescoreReport report;
    Model model = prescore_shot(shot, &report);
    const std::string ply = save_prescore_outputs(model, out);

    size_t pairs = 0, parts = 0;
    for (size_t i = 0; i < model.constraints.size(); ++i)
        pairs += i == 0 || model.constraints[i].piece_a != model.constraints[i - 1].piece_a ||
                 model.constraints[i].piece_b != model.constraints[i - 1].piece_b;
    double mass = 0, seconds = 0;
    std::vector<size_t> tets;
    for (const Piece& p : model.pieces) {
        mass += p.mass.mass;
        parts += p.collision.size();
        tets.push_back(p.tets.size());
    }
    std::string sizes = fmt::format("{}", fmt::join(tets, " "));
    if (tets.size() > 16) {
        std::sort(tets.begin(), tets.end());
        sizes = fmt::format("min {}, median {}, max {}", tets.front(), tets[tets.size() / 2], tets.back());
    }
    std::string phases;
    for (const auto& [name, s] : report.phase_seconds) {
        phases += fmt::format("{}{} {:.3f}s", phases.empty() ? "" : ", ", name, s);
        seconds += s;
    }
    if (shot.generate)
        fmt::print("generate: a {} of {} boxes, {} constraints between {} piece pairs, mass {:.4g} kg\n",
                   to_string(shot.generate->kind), model.pieces.size(), model.constraints.size(), pairs, mass);
    else
        fmt::print("prescore: {} pieces, {} tets (per piece: {}), {} constraints between {} piece pairs, "
               "{} collision parts, mass {:.4g} kg\n",
               model.pieces.size(), model.mesh.tets.size(), sizes, model.constraints.size(), pairs, parts, mass);
    if (report.repaired) {
        const double before = report.input.volume, after = report.tetrahedralized_from.volume;
        fmt::print("repair:   alpha-wrapped ({}), volume {:.4g} -> {:.4g} m^3 ({:+.1f}%)\n", describe(report.input),
                   before, after, before > 0 ? 100 * (after / before - 1) : 0.0);
    }
    fmt::print("time:     {:.3f}s ({})\n", seconds, phases);
    fmt::print("wrote:    {} (model), {} (pieces, {})\n", out, ply, model.materials.empty() ? "one colour each" : "in the input's colours");
    return 0;
}

}  // namespace

RunCommand add_prescore_command(CLI::App& root) {
    auto flags = std::make_shared<PrescoreFlags>();
    CLI::App* c = root.add_subcommand(
        "prescore", "Tetrahedralize a mesh, optionally hollow it, split it into pieces and place the constraints "
                    "that join them. Writes OUT.model and OUT.pieces.ply.");
    c->add_option("input", flags->input, "a mesh file (OBJ, PLY, STL, OFF, glTF/GLB, 3DS, FBX, ...) or a shot file (.toml) with "
                                     "[mesh] or [generate] (a beam, plate or chain built from boxes)")
        ->required();
    c->add_option("-o,--output", flags->output, option_help("the model file to write", "", "INPUT-STEM.model"));
    flags->settings =
        std::make_unique<SettingFlags>(*c, "prescore", std::vector<std::string>{"mesh", "generate", "prescore"});
    return [flags] { return run(*flags); };
}

}  // namespace shatter
