// libFuzzer target: the PNG reader behind `shatter diff` (decode_png, libpng's simplified API).
// Seeds: tests/fuzz/corpus/png/ (small frames in every colour type).
#include <string_view>

#include "render/png_io.h"
#include "tests/fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string_view bytes(reinterpret_cast<const char*>(data), size);
    shatter::fuzz::expect_value_or_error([&] { shatter::decode_png(bytes, "fuzz.png"); });
    return 0;
}
