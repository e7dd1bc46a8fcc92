#include "core/log.h"

#include <algorithm>

#include <spdlog/sinks/stdout_color_sinks.h>

namespace shatter {

bool setup_logging(const std::string& level) {
    auto lvl = spdlog::level::from_str(level);
    if (lvl == spdlog::level::off && level != "off") return false;
    auto logger = spdlog::stderr_color_mt("shatter");  // (mt: `shatter run` logs from the stages beside render)
    logger->set_pattern("%^%l%$: %v");
    logger->set_level(lvl);
    spdlog::set_default_logger(logger);
    return true;
}

void warn_and_keep(std::vector<std::string>& kept, std::string text) {
    spdlog::warn("{}", text);
    if (std::find(kept.begin(), kept.end(), text) == kept.end()) kept.push_back(std::move(text));
}

}  // namespace shatter
