// shatter info FILE [--json]: summarizes any stage file.
#include <cstdio>

#include <fmt/format.h>

#include "cmd/command.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "core/model_io.h"
#include "core/stage_file.h"
#include "core/trajectory.h"
#include "core/trajectory_summary.h"
#include "prescore/model_summary.h"

namespace shatter {

namespace {

int run(const std::string& path, bool json) {
    const std::string bytes = read_file(path, "stage file");
    const std::string magic = stage_file_magic(bytes);
    nlohmann::ordered_json summary;
    std::string text;
    if (magic == kModelMagic) {
        summary = model_summary(decode_model(bytes, path));
        text = model_summary_text(summary);
    } else if (magic == kTrajectoryMagic) {
        summary = trajectory_summary(decode_trajectory(bytes, path));
        text = trajectory_summary_text(summary);
    } else {
        throw_input_error(path, magic.empty() ? "not a shatter stage file" : "unknown stage file kind " + magic,
                          "pass a file written by shatter (a .model from prescore, a trajectory from simulate)");
    }
    summary["file"] = path;
    if (json)
        fmt::print("{}\n", summary.dump(2));
    else
        fmt::print("file          {}\n{}", path, text);
    return 0;
}

}  // namespace

RunCommand add_info_command(CLI::App& root) {
    auto path = std::make_shared<std::string>();
    auto json = std::make_shared<bool>(false);
    CLI::App* c = root.add_subcommand("info", "Summarize a stage file (model: pieces, tets, constraints, piece pairs, "
                                              "mass, volume, collision parts, connectivity; trajectory: frames, "
                                              "fps, duration, pieces, props, complete, settings, per-piece path "
                                              "length, top speed and final position).");
    c->add_option("file", *path, "the stage file")->required();
    c->add_flag("--json", *json, "print JSON instead of text");
    return [path, json] { return run(*path, *json); };
}

}  // namespace shatter
