// libFuzzer target: the model file reader (decode_model) and what `shatter info` does with the
// result. Seeds: tests/fuzz/corpus/model/ (the frozen fixture and small variants).
#include <string_view>

#include <nlohmann/json.hpp>

#include "core/model_io.h"
#include "prescore/model_summary.h"
#include "tests/fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string_view bytes(reinterpret_cast<const char*>(data), size);
    shatter::fuzz::expect_value_or_error([&] {
        const shatter::Model model = shatter::decode_model(bytes, "fuzz.model");
        shatter::model_summary_text(shatter::model_summary(model));
    });
    return 0;
}
