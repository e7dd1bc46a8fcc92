// shatter prescore MESH|SHOT [-o OUT.model] [--pieces N] [--seed S] [--hollow T | --solid] ...
#include <algorithm>
#include <filesystem>
#include <optional>
#include <utility>
#include <vector>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <spdlog/spdlog.h>

#include "cmd/command.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "core/model_io.h"
#include "core/shot.h"
#include "prescore/pieces_ply.h"
#include "prescore/prescore.h"

namespace shatter {

namespace {

struct PrescoreFlags {
    std::string input;
    std::string output;
    std::optional<uint32_t> pieces;
    std::optional<uint64_t> seed;
    std::optional<std::string> hollow;
    bool solid = false;
    std::optional<double> resolution, density, scale, size, wrap_alpha, wrap_offset;
    bool no_adapt = false;
    std::optional<std::string> collision_tolerance;
    std::optional<uint32_t> collision_parts, constraints_per_pair;
    std::optional<std::string> repair;
};

Length parse_length_flag(const char* flag, const std::string& text) {
    auto len = Length::parse(text);
    if (!len)
        throw Error(ExitCode::Usage, fmt::format("{} {}: not a length (fix: write a fraction of the bounding-box "
                                                 "diagonal such as 0.05, or a length such as 12mm)", flag, text));
    return *len;
}

// A generated object ([generate]) is built from boxes: the mesh and tet flags do not apply.
void refuse_mesh_flags(const PrescoreFlags& f) {
    const std::vector<std::pair<const char*, bool>> given = {
        {"--pieces", bool(f.pieces)}, {"--seed", bool(f.seed)}, {"--hollow", bool(f.hollow)}, {"--solid", f.solid},
        {"--resolution", bool(f.resolution)}, {"--density", bool(f.density)}, {"--scale", bool(f.scale)},
        {"--size", bool(f.size)}, {"--no-adapt", f.no_adapt},
        {"--wrap-alpha", bool(f.wrap_alpha)}, {"--wrap-offset", bool(f.wrap_offset)},
        {"--collision-tolerance", bool(f.collision_tolerance)}, {"--collision-max-parts", bool(f.collision_parts)},
        {"--constraints-per-pair", bool(f.constraints_per_pair)}, {"--repair", bool(f.repair)}};
    for (const auto& [flag, set] : given)
        if (set)
            throw Error(ExitCode::Usage,
                        fmt::format("{}: {} has [generate]: its object is built from boxes, not from a mesh (fix: "
                                    "remove {}, or change the [generate] section)", flag, f.input, flag));
}

Shot shot_from(const PrescoreFlags& f) {
    Shot shot;
    if (is_shot_path(f.input)) {
        shot = load_shot(f.input);
        if (shot.generate) {
            refuse_mesh_flags(f);
            return shot;
        }
        if (shot.mesh.path.empty())
            throw_input_error(f.input, "the shot has no [mesh] path",
                              "add path = \"your.obj\" under [mesh], or [generate] (docs/shot.md)");
    } else {
        shot.mesh.path = f.input;
    }
    MeshSettings& m = shot.mesh;
    PrescoreSettings& p = shot.prescore;
    if (f.scale) {
        double scale = 0;
        override_checked(scale, f.scale, "--scale", kScaleLimits);
        m.scale = scale;
    }
    if (f.size) {
        double size = 0;
        override_checked(size, f.size, "--size", kSizeLimits);
        m.size = size;
    }
    if (f.no_adapt) m.adapt = false;
    override_checked(m.wrap_alpha, f.wrap_alpha, "--wrap-alpha", kWrapAlphaLimits);
    override_checked(m.wrap_offset, f.wrap_offset, "--wrap-offset", kWrapOffsetLimits);
    if (f.repair) m.repair = *parse_repair_mode(*f.repair);
    override_checked(p.pieces, f.pieces, "--pieces", kPiecesLimits);
    if (f.seed) p.seed = *f.seed;
    override_checked(p.resolution, f.resolution, "--resolution", kResolutionLimits);
    override_checked(p.density, f.density, "--density", kDensityLimits);
    if (f.collision_tolerance) {
        p.collision_tolerance = parse_length_flag("--collision-tolerance", *f.collision_tolerance);
        check_collision_tolerance("--collision-tolerance", p.collision_tolerance, true);
    }
    override_checked(p.collision_max_parts, f.collision_parts, "--collision-max-parts", kCollisionPartsLimits);
    override_checked(p.constraints_per_pair, f.constraints_per_pair, "--constraints-per-pair", kConstraintsPerPairLimits);
    if (f.solid) p.hollow.reset();
    if (f.hollow) {
        p.hollow = parse_length_flag("--hollow", *f.hollow);
        check_hollow("--hollow", *p.hollow, true);
    }
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
    const std::string ply = (out_path.parent_path() / (out_path.stem().string() + ".pieces.ply")).string();

    PrescoreReport report;
    Model model = prescore_shot(shot, &report);
    save_model(out, model);
    write_file_atomic(ply, pieces_ply(model));

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
    fmt::print("wrote:    {} (model), {} (pieces, one colour each)\n", out, ply);
    return 0;
}

}  // namespace

RunCommand add_prescore_command(CLI::App& root) {
    auto flags = std::make_shared<PrescoreFlags>();
    const PrescoreSettings p;
    const MeshSettings m;
    CLI::App* c = root.add_subcommand(
        "prescore", "Tetrahedralize a mesh, optionally hollow it, split it into pieces and place the constraints "
                    "that join them. Writes OUT.model and OUT.pieces.ply.");
    c->add_option("input", flags->input, "a mesh file (OBJ, PLY, STL, OFF, glTF/GLB, 3DS, FBX, ...) or a shot file (.toml) with "
                                     "[mesh] or [generate] (a beam, plate or chain built from boxes)")
        ->required();
    c->add_option("-o,--output", flags->output, option_help("the model file to write", "", "INPUT-STEM.model"));
    c->add_option("--pieces", flags->pieces, option_help("number of pieces", "count", std::to_string(p.pieces)));
    c->add_option("--seed", flags->seed, option_help("seed of the random choice of seed tets", "", std::to_string(p.seed)));
    auto* hollow = c->add_option("--hollow", flags->hollow,
                                 option_help("hollow the object, keeping a shell this thick: a fraction of the "
                                             "bounding-box diagonal (0.05) or a length (12mm, 1.5cm, 0.02m)",
                                             "fraction or m", "solid"));
    c->add_flag("--solid", flags->solid, "keep every tet (overrides a hollow shell in the shot)")->excludes(hollow);
    c->add_option("--resolution", flags->resolution,
                  option_help("tet size = bounding-box diagonal / resolution", "", fmt::format("{:g}", p.resolution)));
    c->add_option("--density", flags->density, option_help("material density", "kg/m^3", fmt::format("{:g}", p.density)));
    c->add_option("--scale", flags->scale,
                  option_help("metres per mesh unit", "m", "the file's units (glTF: 1; FBX, Collada: theirs), else --size"));
    c->add_option("--size", flags->size,
                  option_help("make the longest side of the mesh's bounding box this long (wins over --scale)", "m",
                              fmt::format("{:g} for a file without units", kDefaultSize)));
    c->add_flag("--no-adapt", flags->no_adapt,
                "refuse a mesh whose tets lose parts instead of raising the resolution, thickening thin walls and "
                "merging slivers (the default adapts, and logs and records each choice)");
    c->add_option("--repair", flags->repair,
                  option_help("alpha-wrap the mesh: auto (only when it cannot be tetrahedralized as it is), always, "
                              "never (refuse such meshes)", "", to_string(m.repair)))
        ->check(CLI::IsMember({"auto", "always", "never"}));
    c->add_option("--wrap-alpha", flags->wrap_alpha,
                  option_help("alpha-wrap ball radius, fraction of the diagonal", "", fmt::format("{:g}", m.wrap_alpha)));
    c->add_option("--wrap-offset", flags->wrap_offset,
                  option_help("alpha-wrap offset, fraction of the diagonal", "", fmt::format("{:g}", m.wrap_offset)));
    c->add_option("--collision-tolerance", flags->collision_tolerance,
                  option_help("split a piece's collision shape into convex parts until the mean gap between each "
                              "part's hull and the piece's real shape is at most this: a fraction of the diagonal "
                              "(0.01) or a length (2mm)", "fraction or m", p.collision_tolerance.str()));
    c->add_option("--collision-max-parts", flags->collision_parts,
                  option_help("most convex collision parts per piece", "count", std::to_string(p.collision_max_parts)));
    c->add_option("--constraints-per-pair", flags->constraints_per_pair,
                  option_help("most constraints joining two pieces, spread over their interface by farthest-point "
                              "sampling with the pair's whole area; 0 = one per shared vertex", "count",
                              std::to_string(p.constraints_per_pair)));
    return [flags] { return run(*flags); };
}

}  // namespace shatter
