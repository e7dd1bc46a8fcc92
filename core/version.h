#pragma once

namespace shatter {
inline constexpr const char* kVersion = "0.1.0";
}  // namespace shatter
