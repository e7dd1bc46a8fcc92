// Determinism as a contract: every built-in scene, run briefly at a small size, must give the
// same model, trajectory and frame bytes as pinned in tests/pins/scenes.txt (FNV-1a 64), the way
// physics engines pin their determinism. Any change of those bytes, intended or not, fails here.
//
// After an intended change (a new default, a physics fix), re-pin with
//   SHATTER_UPDATE_PINS=1 build/tests/cli_tests --gtest_filter='DeterminismPins.*'
// and say in the commit message why the bytes changed.
//
// A frame's bytes are also the renderer's: a point release of Mesa's software rasterizer
// (Debian's libosmesa6) moves pixels by a level here and there, and so does the processor it
// compiles its shaders for (llvmpipe's JIT uses what the processor has: on a machine with
// AVX-512, code that draws the same and the same package gave other frame bytes for every
// scene, and the same model and trajectory bytes; so did two AVX-512 machines). The pins record the
// renderer's package version and the processor's vector instruction sets; where either differs
// the frames are not compared (the test says so), the model and trajectory bytes still are.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <vector>

#include <fmt/format.h>

#include "core/binary_io.h"
#include "support/run_command.h"
#include "support/temp_dir.h"

namespace shatter {
namespace {

namespace fs = std::filesystem;
using testing_support::run_shatter;
using testing_support::slurp;
using testing_support::TempDir;

const std::string kPins = SHATTER_SOURCE_DIR "/tests/pins/scenes.txt";
const char* kScenes[] = {"bunny", "bunny_sphere", "beam", "plate", "chain"};
constexpr uint32_t kFrame = 4;  // the pinned frame (of 7: 0.2 s at 30 fps)

std::map<std::string, std::string> read_pins() {
    std::map<std::string, std::string> pins;
    std::istringstream in(slurp(kPins));
    for (std::string line; std::getline(in, line);) {
        if (line.empty() || line[0] == '#') continue;
        const size_t space = line.find(' ');
        pins[line.substr(0, space)] = line.substr(space + 1);
    }
    return pins;
}

// The installed renderer's package version, or "unknown" where dpkg does not say.
std::string renderer_version() {
    const auto r = testing_support::run_command({"/usr/bin/dpkg-query", "-W", "--showformat=${Version}", "libosmesa6"});
    return r.exit_code == 0 && !r.out.empty() ? r.out : "unknown";
}

// The processor's instruction sets that llvmpipe's code generator may use, by /proc/cpuinfo's
// flags: the widest vector instructions ("avx512f", "avx2", "avx" or "sse") and a hash of every
// SIMD-related flag (sse*, ssse3, avx*, fma, f16c, bmi*, amx*, vaes, vpclmulqdq, gfni, popcnt): two
// AVX-512 machines with the same Mesa package gave other frame bytes, so the widest set alone
// does not say which code draws.
std::string vector_instructions() {
    std::istringstream in(slurp("/proc/cpuinfo"));
    for (std::string line; std::getline(in, line);) {
        if (line.rfind("flags", 0) != 0) continue;
        std::istringstream words(line.substr(line.find(':') + 1));
        std::vector<std::string> simd;
        for (std::string w; words >> w;)
            for (const char* prefix : {"sse", "ssse", "avx", "fma", "f16c", "bmi", "amx", "vaes", "vpclmul", "gfni", "popcnt"})
                if (w.rfind(prefix, 0) == 0) {
                    simd.push_back(w);
                    break;
                }
        std::sort(simd.begin(), simd.end());
        std::string all;
        for (const std::string& w : simd) all += w + ' ';
        const auto has = [&](const char* isa) { return std::find(simd.begin(), simd.end(), isa) != simd.end(); };
        const char* widest = has("avx512f") ? "avx512f" : has("avx2") ? "avx2" : has("avx") ? "avx" : "sse";
        return fmt::format("{} (simd flags {:08x})", widest, uint32_t(fnv1a64(all)));
    }
    return "sse";
}

// What draws the frames: "libosmesa6 VERSION on ISA (simd flags HASH)".
std::string renderer() { return "libosmesa6 " + renderer_version() + " on " + vector_instructions(); }

std::string hash_of(const std::string& path) { return fmt::format("{:016x}", fnv1a64(slurp(path))); }

TEST(DeterminismPins, EveryBuiltInSceneGivesItsPinnedBytes) {
    TempDir dir;
    std::map<std::string, std::string> got;
    for (const char* scene : kScenes) {
        const std::string out = dir.file(scene);
        auto r = run_shatter({"run", std::string(SHATTER_SOURCE_DIR "/assets/") + scene + ".toml", "-o", out,
                              "--no-progress", "--stages", "prescore,simulate,render", "--set", "simulate.duration=0.2",
                              "--set", "render.width=160", "--set", "render.height=90", "--set", "render.shadow_map=512"});
        ASSERT_EQ(r.exit_code, 0) << scene << ": " << r.err;
        got[std::string(scene) + ".model"] = hash_of(fmt::format("{}/{}.model", out, scene));
        got[std::string(scene) + ".traj"] = hash_of(fmt::format("{}/{}.traj", out, scene));
        got[std::string(scene) + ".frame"] = hash_of(fmt::format("{}/frames/frame_{:05d}.png", out, kFrame));
    }
    if (std::getenv("SHATTER_UPDATE_PINS")) {
        fs::create_directories(fs::path(kPins).parent_path());
        std::ofstream pins(kPins);
        pins << "# FNV-1a 64 of each built-in scene's model, trajectory and frame " << kFrame
             << " (0.2 s, 160x90): tests/cli/determinism_pins_test.cpp\n";
        pins << "renderer " << renderer() << '\n';
        for (const auto& [name, hash] : got) pins << name << ' ' << hash << '\n';
        GTEST_SKIP() << "pins rewritten: " << kPins;
    }
    auto pins = read_pins();
    const std::string pinned_renderer = pins["renderer"];
    pins.erase("renderer");
    const std::string renderer_now = renderer();
    const bool same_renderer = pinned_renderer == renderer_now;
    ASSERT_EQ(pins.size(), got.size()) << "re-pin with SHATTER_UPDATE_PINS=1 (see the file's comment)";
    for (const auto& [name, hash] : got) {
        const auto it = pins.find(name);
        ASSERT_NE(it, pins.end()) << name << " is not pinned";
        if (name.ends_with(".frame") && !same_renderer) continue;
        EXPECT_EQ(it->second, hash) << name << ": the bytes changed. If intended, re-pin with SHATTER_UPDATE_PINS=1";
    }
    if (!same_renderer)
        std::printf("frames not compared: pinned with %s, rendered with %s (re-pin with SHATTER_UPDATE_PINS=1)\n",
                    pinned_renderer.c_str(), renderer_now.c_str());
}

}  // namespace
}  // namespace shatter
