// shatter render MODEL TRAJECTORY -o FRAMES/ [--shot SHOT] [--size 1280x720] [--frames A:B] ...
#include <cstdio>
#include <filesystem>
#include <optional>

#include <fmt/format.h>

#include "cmd/command.h"
#include "core/error.h"
#include "core/model_io.h"
#include "core/shot.h"
#include "core/trajectory.h"
#include "render/render.h"

namespace shatter {

namespace {

struct RenderFlags {
    std::string model, trajectory, output, shot;
    std::optional<std::string> size, frames, camera, camera_position, camera_target, colour_mode, material_colour, background;
    std::optional<double> fov, key_azimuth, key_elevation, fracture_tint, cavity_shade;
    std::optional<uint32_t> msaa, shadow_map;
    bool no_shadows = false;
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

std::array<float, 3> parse_colour(const char* flag, const std::string& text) {
    auto c = parse_srgb_hex(text);
    if (!c) bad_flag(flag, text, "not a colour", "write an sRGB colour as #rrggbb, e.g. #dbd3c4");
    return *c;
}

RenderSettings settings_from(const RenderFlags& f) {
    RenderSettings s = f.shot.empty() ? RenderSettings{} : load_shot(f.shot).render;
    if (f.size) parse_size(*f.size, s);
    if (f.camera_position) s.camera_position = parse_point("--camera-position", *f.camera_position);
    if (f.camera_target) {
        if (!s.camera_position) bad_flag("--camera-target", *f.camera_target, "a target without a camera position",
                                         "also give --camera-position X,Y,Z");
        s.camera_target = parse_point("--camera-target", *f.camera_target);
    }
    override_checked(s.fov, f.fov, "--fov", kFovLimits);
    override_checked(s.key_azimuth, f.key_azimuth, "--key-azimuth", kAzimuthLimits);
    override_checked(s.key_elevation, f.key_elevation, "--key-elevation", kElevationLimits);
    override_checked(s.fracture_tint, f.fracture_tint, "--fracture-tint", kTintLimits);
    override_checked(s.cavity_shade, f.cavity_shade, "--cavity-shade", kTintLimits);
    override_checked(s.shadow_map, f.shadow_map, "--shadow-map", kShadowMapLimits);
    if (f.msaa) {
        check_msaa("--msaa", *f.msaa, true);
        s.msaa = *f.msaa;
    }
    if (f.no_shadows) s.shadows = false;
    if (f.colour_mode) s.colour_mode = *parse_colour_mode(*f.colour_mode);
    if (f.camera) s.camera = *parse_camera_mode(*f.camera);
    if (f.material_colour) s.material_colour = parse_colour("--material-colour", *f.material_colour);
    if (f.background) s.background = parse_colour("--background", *f.background);
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
    fmt::print("render: {} frames ({}..{}) of {}x{} in {:.2f}s, {:.1f} frames/s ({})\n", r.frames, range.first,
               range.end - 1, settings.width, settings.height, r.seconds, r.frames / std::max(r.seconds, 1e-9),
               r.renderer);
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
    c->add_option("--camera", f->camera,
                  option_help("without --camera-position: follow the pieces, or frame the whole animation", "",
                              to_string(d.camera)))
        ->check(CLI::IsMember({"follow", "whole"}));
    c->add_option("--camera-position", f->camera_position,
                  option_help("camera position X,Y,Z", "m", "--camera"));
    c->add_option("--camera-target", f->camera_target,
                  option_help("the point the camera looks at X,Y,Z", "m", "the centre of the animation"));
    c->add_option("--fov", f->fov, option_help("vertical field of view", "degrees", fmt::format("{:g}", d.fov)));
    c->add_flag("--no-shadows", f->no_shadows, "the key light casts no shadows (faster)");
    c->add_option("--shadow-map", f->shadow_map,
                  option_help("shadow map width and height", "texels", std::to_string(d.shadow_map)));
    c->add_option("--msaa", f->msaa, option_help("samples per pixel: 1 (off), 2 or 4", "", std::to_string(d.msaa)));
    c->add_option("--key-azimuth", f->key_azimuth,
                  option_help("key light direction from the camera's, positive to the right", "degrees",
                              fmt::format("{:g}", d.key_azimuth)));
    c->add_option("--key-elevation", f->key_elevation,
                  option_help("key light height above the horizon", "degrees", fmt::format("{:g}", d.key_elevation)));
    c->add_option("--colour-mode", f->colour_mode,
                  option_help("pieces: a palette colour per piece; material: --material-colour", "", "pieces"))
        ->check(CLI::IsMember({"pieces", "material"}));
    c->add_option("--material-colour", f->material_colour,
                  option_help("the colour of every piece in material mode (sRGB #rrggbb)", "", srgb_hex(d.material_colour)));
    c->add_option("--fracture-tint", f->fracture_tint,
                  option_help("fracture faces: this fraction of the way from the piece colour to white", "fraction",
                              fmt::format("{:g}", d.fracture_tint)));
    c->add_option("--cavity-shade", f->cavity_shade,
                  option_help("cavity faces: the piece colour times this", "fraction", fmt::format("{:g}", d.cavity_shade)));
    c->add_option("--background", f->background, option_help("background colour (sRGB #rrggbb)", "", srgb_hex(d.background)));
    return [f] { return run(*f); };
}

}  // namespace shatter
