// libFuzzer target: the batch file reader of `shatter batch` and `submit` (load_batch: TOML
// syntax, [batch], [[job]] with set and sweep tables). Seeds: tests/fuzz/corpus/batch/.
#include <string_view>

#include "pipeline/batch_file.h"
#include "tests/fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string_view bytes(reinterpret_cast<const char*>(data), size);
    const std::string path = shatter::fuzz::scratch_file(bytes, "batch.toml");
    shatter::fuzz::expect_value_or_error([&] { shatter::load_batch(path, "/nonexistent/fuzz-out"); });
    return 0;
}
