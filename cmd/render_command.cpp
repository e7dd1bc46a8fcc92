// shatter render MODEL TRAJECTORY -o FRAMES/ [--shot SHOT] [--set render.KEY=VALUE]... [--size 1280x720] [--frames A:B] ...
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "cmd/command.h"
#include "cmd/setting_flags.h"
#include "core/error.h"
#include "core/model_io.h"
#include "core/shot.h"
#include "core/trajectory.h"
#include "render/render.h"

namespace shatter {

namespace {

struct RenderFlags {
    std::string model, trajectory, output, shot;
    std::optional<std::string> size, frames, camera_position, camera_target;
    std::unique_ptr<SettingFlags> settings;
};

[[noreturn]] void bad_flag(const std::string& flag, const std::string& value, const std::string& problem,
                           const std::string& fix) {
    throw Error(ExitCode::Usage, fmt::format("{} {}: {} (fix: {})", flag, value, problem, fix));
}

void parse_size(const std::string& text, RenderSettings& s) {
    unsigned w = 0, h = 0;
    char extra = 0;
    if (std::sscanf(text.c_str(), "%ux%u%c", &w, &h, &extra) != 2)
        bad_flag("--size", text, "not a size", "write WIDTHxHEIGHT in pixels, e.g. 1280x720");
    check_limits("--size " + text, "width", w, kImageSizeLimits, true);
    check_limits("--size " + text, "height", h, kImageSizeLimits, true);
    s.width = w;
    s.height = h;
}

FrameRange parse_frames(const std::optional<std::string>& text, uint32_t frames) {
    FrameRange r{0, frames};
    if (!text) return r;
    const size_t colon = text->find(':');
    auto number = [&](const std::string& part, uint32_t fallback) -> uint32_t {
        if (part.empty()) return fallback;
        char* end = nullptr;
        const unsigned long v = std::strtoul(part.c_str(), &end, 10);
        if (*end || part[0] == '-' || v > 0xffffffffu)
            bad_flag("--frames", *text, "not a frame range", "write A:B (frames A to B-1, counted from 0), A: or :B");
        return uint32_t(v);
    };
    if (colon == std::string::npos)
        bad_flag("--frames", *text, "not a frame range", "write A:B (frames A to B-1, counted from 0), A: or :B");
    r.first = number(text->substr(0, colon), 0);
    r.end = number(text->substr(colon + 1), frames);
    if (r.first >= r.end || r.end > frames)
        bad_flag("--frames", *text, fmt::format("outside the trajectory's {} frames, or empty", frames),
                 fmt::format("a range A:B with 0 <= A < B <= {}", frames));
    return r;
}

Vec3 parse_point(const char* flag, const std::string& text) {
    double x, y, z;
    char extra = 0;
    if (std::sscanf(text.c_str(), "%lf,%lf,%lf%c", &x, &y, &z, &extra) != 3 || !std::isfinite(x + y + z))
        bad_flag(flag, text, "not a point", "write X,Y,Z in metres, e.g. 0.5,0.4,1.2");
    return Vec3(x, y, z);
}

RenderSettings settings_from(const RenderFlags& f) {
    const std::vector<std::string>& sets = f.settings->overrides();
    Shot shot = f.shot.empty() ? shot_from_overrides(sets) : load_shot(f.shot, sets);
    f.settings->apply(shot);
    RenderSettings s = shot.render;
    if (f.size) parse_size(*f.size, s);
    if (f.camera_position) s.camera_position = parse_point("--camera-position", *f.camera_position);
    if (f.camera_target) {
        if (!s.camera_position) bad_flag("--camera-target", *f.camera_target, "a target without a camera position",
                                         "also give --camera-position X,Y,Z");
        s.camera_target = parse_point("--camera-target", *f.camera_target);
    }
    return s;
}

int run(const RenderFlags& f) {
    const RenderSettings settings = settings_from(f);
    const Model model = load_model(f.model);
    const Trajectory trajectory = load_trajectory(f.trajectory);
    const RenderScene scene = make_render_scene(model, f.model, trajectory, f.trajectory);
    const FrameRange range = parse_frames(f.frames, trajectory.frames());
    RenderOptions options;
    options.size_source = f.size ? "--size" : (f.shot.empty() ? "the default size" : f.shot + ": [render] width, height");
    const RenderReport r = render_frames(scene, settings, range, f.output, options);
    fmt::print("render: {} frames ({}..{}) of {}x{} in {:.2f}s, {:.1f} frames/s ({}){}\n", r.frames, range.first,
               range.end - 1, settings.width, settings.height, r.seconds, r.frames / std::max(r.seconds, 1e-9),
               r.renderer,
               r.repeated ? fmt::format("; {} the same picture as the frame before, written again undrawn", r.repeated) : "");
    fmt::print("time:   draw {:.3f}s, readback {:.3f}s (main thread); PNG encode {:.3f}s, write {:.3f}s (writer thread)\n",
               r.draw_seconds, r.readback_seconds, r.encode_seconds, r.write_seconds);
    fmt::print("wrote:  {}/{} .. {}\n", f.output, frame_file_name(range.first), frame_file_name(range.end - 1));
    return 0;
}

}  // namespace

RunCommand add_render_command(CLI::App& root) {
    auto f = std::make_shared<RenderFlags>();
    const RenderSettings d;
    CLI::App* c = root.add_subcommand(
        "render", "Draw every frame of a simulation to PNG (OpenGL 4.5 on OSMesa: no GPU or display needed). "
                  "Settings from the shot's [render] section (--shot); flags override.");
    c->add_option("model", f->model, "the model file the trajectory was simulated from (.model)")->required();
    c->add_option("trajectory", f->trajectory, "the trajectory written by shatter simulate")->required();
    c->add_option("-o,--output", f->output, "the directory to write frame_NNNNN.png into (created)")->required();
    c->add_option("--shot", f->shot, "a shot file whose [render] section gives the settings (docs/shot.md)");
    c->add_option("--size", f->size, option_help("image size WIDTHxHEIGHT", "pixels",
                                                 fmt::format("{}x{}", d.width, d.height)));
    c->add_option("--frames", f->frames, option_help("render frames A to B-1 only (A:B, A:, :B), e.g. to spread a "
                                                     "render over processes; a frame's bytes do not depend on it",
                                                     "frame numbers from 0", "all"));
    c->add_option("--camera-position", f->camera_position,
                  option_help("camera position X,Y,Z", "m", "--camera"));
    c->add_option("--camera-target", f->camera_target,
                  option_help("the point the camera looks at X,Y,Z", "m", "the centre of the animation"));
    f->settings = std::make_unique<SettingFlags>(*c, "render", std::vector<std::string>{"render"});
    return [f] { return run(*f); };
}

}  // namespace shatter
