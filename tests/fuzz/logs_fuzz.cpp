// libFuzzer target: the simulate logs that `shatter run` reads back for summary.json
// (simulation_facts: OUT.breaks.jsonl and OUT.energy.csv), against the frozen model and
// trajectory fixtures. Input: the break log, a NUL byte, the energy CSV.
// Seeds: tests/fuzz/corpus/logs/.
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

#include "core/atomic_file.h"
#include "core/model_io.h"
#include "core/trajectory.h"
#include "pipeline/run_metrics.h"
#include "tests/fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    static const shatter::Model model =
        shatter::load_model(std::string(SHATTER_SOURCE_DIR) + "/tests/fixtures/model-v1.model");
    static const shatter::Trajectory traj = [] {
        shatter::Trajectory t =
            shatter::load_trajectory(std::string(SHATTER_SOURCE_DIR) + "/tests/fixtures/trajectory-v1.traj");
        t.props = 0;  // the fixture's two pieces against the model's two, as a run pairs them
        t.poses.clear();
        for (uint32_t f = 0; f < 3; ++f)
            for (uint32_t b = 0; b < 2; ++b) t.poses.push_back({});
        return t;
    }();
    const std::string_view bytes(reinterpret_cast<const char*>(data), size);
    const size_t nul = bytes.find('\0');
    const std::string breaks(bytes.substr(0, nul));
    const std::string energy(nul == std::string_view::npos ? std::string_view() : bytes.substr(nul + 1));
    shatter::fuzz::expect_value_or_error([&] { shatter::simulation_facts(model, traj, breaks, energy); });
    return 0;
}
