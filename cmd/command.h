// Each `shatter` subcommand lives in its own cmd/<name>_command.cpp: it declares its options on a
// CLI11 subcommand and returns the function that runs it. Commands only parse options, call the
// stage libraries and print; all logic is in the libraries.
#pragma once

#include <functional>
#include <optional>
#include <string>

#include <CLI/CLI.hpp>

#include "core/settings.h"

namespace shatter {

using RunCommand = std::function<int()>;

RunCommand add_prescore_command(CLI::App& root);
RunCommand add_info_command(CLI::App& root);
RunCommand add_render_command(CLI::App& root);
RunCommand add_diff_command(CLI::App& root);
RunCommand add_simulate_command(CLI::App& root);
RunCommand add_run_command(CLI::App& root);
RunCommand add_batch_command(CLI::App& root);
RunCommand add_submit_command(CLI::App& root);
RunCommand add_settings_doc_command(CLI::App& root);

// "DESCRIPTION (unit: UNIT, default: DEFAULT)" for --help texts.
std::string option_help(const std::string& description, const std::string& unit, const std::string& def);

}  // namespace shatter
