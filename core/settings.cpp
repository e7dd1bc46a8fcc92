#include "core/settings.h"

#include <cmath>
#include <cstdlib>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "core/error.h"
#include "core/setting_table.h"

namespace shatter {

std::string Length::str() const {
    if (relative) return fmt::format("{:g}", value);
    return fmt::format("{:g}m", value);
}

std::optional<Length> Length::parse(const std::string& text) {
    if (text.empty()) return std::nullopt;
    const char* begin = text.c_str();
    char* end = nullptr;
    double v = std::strtod(begin, &end);
    if (end == begin || !std::isfinite(v)) return std::nullopt;
    std::string unit(end);
    if (unit.empty()) return Length{v, true};
    if (unit == "m") return Length{v, false};
    if (unit == "cm") return Length{v * 1e-2, false};
    if (unit == "mm") return Length{v * 1e-3, false};
    return std::nullopt;
}

const char* to_string(UpAxis up) {
    switch (up) {
        case UpAxis::Auto: return "auto";
        case UpAxis::Y: return "y";
        case UpAxis::Z: return "z";
    }
    return "?";
}

const char* to_string(RepairMode mode) {
    switch (mode) {
        case RepairMode::Auto: return "auto";
        case RepairMode::Always: return "always";
        case RepairMode::Never: return "never";
    }
    return "?";
}

void check_limits(const std::string& where, const std::string& key, double value, const Limits& limits,
                  bool from_flag) {
    if (std::isfinite(value) && value >= limits.min && value <= limits.max) return;
    const std::string prefix = where == key ? "" : where + ": ";
    std::string message = fmt::format("{}{} = {:g} is outside [{:g}, {:g}] {}", prefix, key, value, limits.min,
                                      limits.max, limits.unit);
    if (!std::isfinite(value)) message = fmt::format("{}{} = {} is not a finite number", prefix, key, value);
    message += fmt::format(" (fix: give a value from {:g} to {:g})", limits.min, limits.max);
    throw Error(from_flag ? ExitCode::Usage : ExitCode::BadInput, message);
}

void check_length(const std::string& where, const std::string& what, const Length& length, const Limits& relative,
                  const Limits& absolute, bool from_flag) {
    if (length.relative)
        check_limits(where, what + " (fraction of the diagonal)", length.value, relative, from_flag);
    else
        check_limits(where, what + " (absolute)", length.value, absolute, from_flag);
}

void check_hollow(const std::string& where, const Length& thickness, bool from_flag) {
    check_length(where, "hollow", thickness, kHollowRelativeLimits, kHollowAbsoluteLimits, from_flag);
}

void check_collision_tolerance(const std::string& where, const Length& tolerance, bool from_flag) {
    check_length(where, "collision_tolerance", tolerance, kCollisionToleranceRelativeLimits,
                 kCollisionToleranceAbsoluteLimits, from_flag);
}

// The keys come from the tables (core/setting_table_prescore.cpp), in the order files already
// written have them; "size" and "adapt" appear only when they differ from the defaults, so that
// a model made with a given scale keeps the bytes it had before they existed.
nlohmann::ordered_json to_json(const MeshSettings& s) {
    Shot shot;
    shot.mesh = s;
    return settings_json("mesh", shot);
}

nlohmann::ordered_json to_json(const PrescoreSettings& s) {
    Shot shot;
    shot.prescore = s;
    return settings_json("prescore", shot);
}

}  // namespace shatter
