// libFuzzer target: the shot file reader (load_shot: TOML syntax, every section, every key's
// type and range). Seeds: tests/fuzz/corpus/shot/ (the built-in shots and variants).
#include <string_view>

#include "core/shot.h"
#include "tests/fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string_view bytes(reinterpret_cast<const char*>(data), size);
    const std::string path = shatter::fuzz::scratch_file(bytes, "toml");
    shatter::fuzz::expect_value_or_error([&] { shatter::load_shot(path); });
    return 0;
}
