// One logger for every stage: spdlog to stderr (data goes to files and stdout, diagnostics to
// stderr). setup_logging() is called once by the command line; libraries just log.
#pragma once

#include <string>
#include <vector>

#include <spdlog/spdlog.h>

namespace shatter {

// Levels: trace, debug, info, warn, error, off. Returns false for an unknown level name.
bool setup_logging(const std::string& level);

// Logs `text` as a warning and keeps it in `kept` unless it is there already: a stage keeps its
// warnings in its file whatever the log level (core/stage_file.h stage_warnings).
void warn_and_keep(std::vector<std::string>& kept, std::string text);

}  // namespace shatter
