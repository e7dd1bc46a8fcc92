// Text from input files (material and texture names, file names) as valid UTF-8, for the JSON and
// HTML it ends up in: a file from elsewhere may name things in Latin-1 ("Terraind\xe6k" in an
// OBJ's .mtl).
#pragma once

#include <string>
#include <string_view>

namespace shatter {

// `bytes` unchanged when it is valid UTF-8; otherwise every byte that does not start a valid,
// shortest-form sequence is read as Latin-1 (U+0080 to U+00FF, two bytes each) and control bytes
// below 0x20 become '?'.
std::string to_utf8(std::string_view bytes);
// `bytes` unchanged when it is valid UTF-8 (control characters and all), else to_utf8(bytes): for
// paths and names that must stay what they are whenever JSON can hold them.
std::string as_utf8(std::string_view bytes);

}  // namespace shatter
