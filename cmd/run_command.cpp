// shatter run SHOT|MESH [-o DIR] [--set SECTION.KEY=VALUE]... [--stages LIST] [--chunk I/N] [--cache DIR]
#include <cstdio>

#include <fmt/format.h>

#include "cmd/command.h"
#include "core/error.h"
#include "pipeline/run.h"

namespace shatter {

namespace {

struct RunFlags {
    RunOptions options;
    std::vector<std::string> stages;
    std::string chunk;
};

int run(RunFlags& f) {
    for (const std::string& list : f.stages) {
        size_t start = 0;
        while (start <= list.size()) {
            const size_t comma = std::min(list.find(',', start), list.size());
            const std::string name = list.substr(start, comma - start);
            const auto stage = parse_stage(name);
            if (!stage)
                throw Error(ExitCode::Usage, fmt::format("--stages {}: '{}' is not a stage (fix: a comma-separated list "
                                                         "of prescore, simulate, render, encode, sheet, plot, export)",
                                                         list, name));
            f.options.stages.push_back(*stage);
            start = comma + 1;
        }
    }
    if (!f.chunk.empty()) {
        unsigned i = 0, n = 0;
        char extra = 0;
        if (std::sscanf(f.chunk.c_str(), "%u/%u%c", &i, &n, &extra) != 2 || n == 0 || i >= n)
            throw Error(ExitCode::Usage, fmt::format("--chunk {}: not a chunk (fix: I/N with 0 <= I < N, e.g. 0/4 for "
                                                     "the first quarter of the frames)", f.chunk));
        f.options.chunk = i;
        f.options.chunks = n;
    }
    const RunResult r = run_shot(f.options);
    std::fputs(("\n" + format_run_summary(r)).c_str(), stdout);
    return r.exit_code;
}

}  // namespace

RunCommand add_run_command(CLI::App& root) {
    auto f = std::make_shared<RunFlags>();
    CLI::App* c = root.add_subcommand(
        "run", "Run a shot from mesh to movie: prescore, simulate, render, encode (MP4), contact sheet, energy plot, "
               ".glb and report.html, into one output folder. Stages that are up to date are skipped; a killed run resumes.");
    c->add_option("shot", f->options.shot,
                  "the shot file (.toml; docs/shot.md), or a mesh file in any format assimp reads (OBJ, PLY, STL, OFF, "
                  "glTF/GLB, 3DS, FBX, ...), or an archive holding one (.zip, .7z, .rar, .tar.gz: a model site's download), to run the "
                  "default shot on it (a 1.5 m drop, docs/shot.md)")
        ->required();
    c->add_option("-o,--output", f->options.output_dir, option_help("the output folder", "", "out/SHOT-NAME"));
    c->add_option("--set", f->options.overrides,
                  "override a shot setting, SECTION.KEY=VALUE, written as in the shot file (repeatable), e.g. "
                  "--set material.alpha=0.5 --set render.width=640")
        ->allow_extra_args(false);
    c->add_option("--stages", f->stages,
                  option_help("only these stages, comma-separated: prescore, simulate, render, encode, sheet, plot, export, "
                              "report; what they read must be up to date (the model and the trajectory; the frames for encode and sheet)", "", "all"));
    c->add_option("--chunk", f->chunk,
                  option_help("render only chunk I of N equal frame ranges, I/N counted from 0 (for cluster job "
                              "arrays); later stages wait until every frame is there", "", "0/1"));
    c->add_option("--cache", f->options.cache_dir,
                  option_help("a stage cache shared between runs (prescore and simulate outputs by input hash)", "",
                              "none"));
    c->add_flag("--force", f->options.force, "run every asked stage even when it is up to date");
    c->add_flag("--no-progress", [f](int64_t) { f->options.progress = false; }, "no progress bars on stderr");
    return [f] { return run(*f); };
}

}  // namespace shatter
