// The `shatter` command: global options, subcommand dispatch, and the mapping of errors to exit
// codes (README: "Exit codes").
#include <cstdio>
#include <filesystem>
#include <map>
#include <string>

#include <spdlog/spdlog.h>

#include "cmd/command.h"
#include "core/error.h"
#include "core/log.h"
#include "core/version.h"

namespace shatter {

std::string option_help(const std::string& description, const std::string& unit, const std::string& def) {
    std::string extra;
    if (!unit.empty()) extra = "unit: " + unit;
    if (!def.empty()) extra += (extra.empty() ? "" : ", ") + std::string("default: ") + def;
    return extra.empty() ? description : description + " (" + extra + ")";
}

}  // namespace shatter

int main(int argc, char** argv) {
    using namespace shatter;
    CLI::App app{"shatter: turns a mesh into a fractured animation (energized rigid-body fracture).\n"
                 "run: one shot from mesh to movie. Stages: prescore (mesh -> pieces and constraints), simulate\n"
                 "(pieces -> motion and breaks), render (frames), diff (compare renders), info (summarize any\n"
                 "stage file)."};
    app.footer("Environment: SHATTER_THREADS=N, the threads the simulation's contact tests run on (default: the\n"
               "cores the process may run on, its CPU affinity, at most 8; batch gives each parallel run its share).\n"
               "The output is the same for any number.");
    app.set_version_flag("--version", std::string("shatter ") + kVersion);
    std::string log_level = "info";
    app.add_option("--log-level", log_level, "diagnostics on stderr: trace, debug, info, warn, error, off (default: info)")
        ->check(CLI::IsMember({"trace", "debug", "info", "warn", "error", "off"}));
    app.require_subcommand(1);
    app.fallthrough();

    std::map<const CLI::App*, RunCommand> commands;
    auto add = [&](RunCommand (*adder)(CLI::App&)) {
        RunCommand run = adder(app);
        commands[app.get_subcommands({}).back()] = std::move(run);
    };
    add(add_prescore_command);
    add(add_simulate_command);
    add(add_info_command);
    add(add_render_command);
    add(add_diff_command);
    add(add_run_command);
    add(add_batch_command);
    add(add_submit_command);
    add(add_settings_doc_command);

    // `shatter MESH`: the first word that is not an option names no command; say which one runs it.
    for (int i = 1; i < argc; ++i) {
        const std::string word = argv[i];
        if (word == "--log-level") {
            ++i;
            continue;
        }
        if (word.empty() || word[0] == '-') continue;
        bool command = false;
        for (const CLI::App* sub : app.get_subcommands({})) command = command || sub->check_name(word);
        if (command) break;
        std::error_code ec;
        std::fprintf(stderr, "error: '%s' is not a command (fix: %s; 'shatter --help' lists the commands)\n", word.c_str(),
                     std::filesystem::is_regular_file(word, ec)
                         ? ("shatter run " + word + " runs the default shot on it, shatter batch FILE... several").c_str()
                         : "shatter run MESH or SHOT, batch, submit, prescore, simulate, render, diff, info");
        return static_cast<int>(ExitCode::Usage);
    }
    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForAllHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForVersion& e) {
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        app.exit(e);
        std::fprintf(stderr, "run 'shatter --help' or 'shatter <command> --help' for the options\n");
        return static_cast<int>(ExitCode::Usage);
    }
    setup_logging(log_level);
    try {
        for (const auto& [sub, run] : commands)
            if (sub->parsed()) return run();
        return static_cast<int>(ExitCode::Usage);
    } catch (const Error& e) {
        spdlog::error("{}", e.what());
        return static_cast<int>(e.code());
    } catch (const std::bad_alloc&) {
        spdlog::error("out of memory; try a coarser --resolution or fewer pieces");
        return static_cast<int>(ExitCode::BadInput);
    } catch (const std::exception& e) {
        spdlog::error("internal error (a bug in shatter, please report it): {}", e.what());
        return static_cast<int>(ExitCode::Internal);
    }
}
