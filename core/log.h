// One logger for every stage: spdlog to stderr (data goes to files and stdout, diagnostics to
// stderr). setup_logging() is called once by the command line; libraries just log.
#pragma once

#include <string>

#include <spdlog/spdlog.h>

namespace shatter {

// Levels: trace, debug, info, warn, error, off. Returns false for an unknown level name.
bool setup_logging(const std::string& level);

}  // namespace shatter
