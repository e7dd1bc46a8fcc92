// render_frames (render/render.h): the loop over a frame range. The main thread owns the GL
// context and renders; a FrameWriter thread encodes and writes the PNGs of earlier frames.
#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <optional>

#include <fmt/format.h>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/progress.h"
#include "render/frame_renderer.h"
#include "render/frame_writer.h"
#include "render/gl_context.h"
#include "render/render.h"

namespace shatter {

namespace {

// Fails early, before any rendering, when nothing can be written into `dir`.
void check_writable(const std::string& dir) {
    make_directories(dir);
    const std::string probe = (std::filesystem::path(dir) / fmt::format(".shatter-probe.{}", ::getpid())).string();
    const int fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_EXCL, 0644);
    if (fd < 0) throw_io_error(dir, std::strerror(errno));
    ::close(fd);
    ::unlink(probe.c_str());
}

}  // namespace

std::string frame_file_name(uint32_t frame) { return fmt::format("frame_{:05d}.png", frame); }

RenderReport render_frames(const RenderScene& scene, const RenderSettings& settings, FrameRange range,
                           const std::string& out_dir, const RenderOptions& options) {
    const uint32_t frames = scene.trajectory->frames();
    if (range.first >= range.end || range.end > frames)
        throw Error(ExitCode::Usage, fmt::format("--frames {}:{} is outside the trajectory's frames 0:{} (fix: a "
                                                 "range A:B with 0 <= A < B <= {})", range.first, range.end, frames,
                                                 frames));
    check_writable(out_dir);
    GlContext context;
    check_render_limits(settings, context.limits().max_image_size(), context.limits().max_samples,
                        options.size_source);
    RenderReport report;
    report.renderer = context.renderer();
    const auto start = std::chrono::steady_clock::now();
    FrameRenderer renderer(scene, settings, options.msaa_region);
    FrameWriter writer(settings.width, settings.height, options.overlap, 2, options.on_pixels);
    std::optional<Progress> progress;
    if (options.progress) progress.emplace("render", range.end - range.first);
    bool drew_before = false;  // frame f - 1 went through the writer in this loop
    for (uint32_t f = range.first; f < range.end; ++f) {
        const std::string path = (std::filesystem::path(out_dir) / frame_file_name(f)).string();
        std::error_code ec;
        if (options.skip_existing && std::filesystem::exists(path, ec)) {
            if (progress) progress->advance();
            drew_before = false;
            continue;
        }
        // A frame that draws what the one before drew (pieces at rest, the camera still): that
        // frame's PNG again, the same bytes without drawing or encoding.
        if (drew_before && renderer.same_picture(f, f - 1)) {
            writer.repeat(path, f);
            if (progress) progress->advance();
            ++report.frames;
            ++report.repeated;
            continue;
        }
        drew_before = true;
        std::vector<uint8_t> rgba = writer.buffer();
        renderer.render(f, rgba.data());
        report.draw_seconds += renderer.last_times().draw;
        report.readback_seconds += renderer.last_times().readback;
        report.filter_seconds += renderer.last_times().filter;
        writer.push(std::move(rgba), path, f);
        if (progress) progress->advance();
        ++report.frames;
    }
    writer.finish();
    if (progress) progress->done();
    report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    report.encode_seconds = writer.encode_seconds();
    report.write_seconds = writer.write_seconds();
    return report;
}

}  // namespace shatter
