// The MP4 of a run, by ffmpeg (libx264), byte-identical across runs.
//
// Determinism: x264's output depends on its thread count (frame threads split the rate control
// and lookahead differently), so the count is fixed (kThreads) rather than left to the number of
// cores; x264 is deterministic for a given count unless asked not to be (--non-deterministic).
// The muxer and the codec are told +bitexact (no encoder version string, no creation time),
// metadata is not copied from the input, and the RGB -> YUV conversion is swscale's bit-exact
// path with the BT.709 matrix (HD players assume it; the stream is tagged the same way).
//
// Input: the frames' RGB bytes, in frame order, on ffmpeg's stdin (rawvideo, rgb24), written by us
// as each frame is ready: from render's memory when it left them (FramePixels), else decoded
// from the PNG; so the movie is encoded while render draws the frames (pipeline/run.cpp), and
// ffmpeg never parses a frame's file name. The pixels and the options being the same, the bytes
// are those of ffmpeg decoding frame_%05d.png itself (measured on the demo: the same MP4). The
// output is an absolute "file:" URL, so a ':' in it cannot be read as a protocol. Arguments go as an argv
// vector (pipeline/process.h): no shell ever sees a name.
#include "pipeline/encode.h"

#include <filesystem>

#include <fmt/format.h>

#include "core/atomic_file.h"
#include "core/error.h"
#include "pipeline/process.h"
#include "pipeline/tool_output.h"
#include "render/png_io.h"

namespace shatter {

namespace {

namespace fs = std::filesystem;

constexpr int kThreads = 4;                  // fixed: x264's bytes depend on it (see above)
constexpr const char* kPreset = "veryfast";  // 120 frames at 1280x720: ~1.8 s of CPU
constexpr const char* kQuality = "18";       // x264 CRF: visually lossless for rendered frames

std::string frame_name(uint32_t i) { return fmt::format("frame_{:05d}.png", i); }

void check_rate(const std::string& frames_dir, uint32_t frames, double fps) {
    if (frames == 0) throw_input_error(frames_dir, "no frames to encode (0 frames)", "render the frames first");
    if (!(fps > 0.0 && fps <= 1000.0))
        throw_input_error(frames_dir, fmt::format("frame rate {} is outside (0, 1000] fps", fps),
                          "give a frame rate in (0, 1000]");
}

void check_frames(const std::string& frames_dir, uint32_t frames, double fps) {
    check_rate(frames_dir, frames, fps);
    std::error_code ec;
    if (!fs::is_directory(frames_dir, ec))
        throw_input_error(frames_dir, "frames directory not found", "render the frames first (shatter render)");
    for (uint32_t i = 0; i < frames; ++i)
        if (!fs::is_regular_file(fs::path(frames_dir) / frame_name(i), ec))
            throw_input_error((fs::path(frames_dir) / frame_name(i)).string(),
                              fmt::format("frame {} of {} is missing", i, frames),
                              "render all frames first (shatter render)");
}

// Pad to even sizes (yuv420p halves both), then RGB -> BT.709 limited-range YUV, bit-exact.
constexpr const char* kFilters =
    "pad=ceil(iw/2)*2:ceil(ih/2)*2,"
    "scale=out_color_matrix=bt709:out_range=tv:flags=accurate_rnd+bitexact,format=yuv420p";

// ffmpeg's argv: `input` (its options and -i), then the encoding into `output` (absolute).
std::vector<std::string> ffmpeg_arguments(const std::string& ffmpeg, const std::vector<std::string>& input,
                                          uint32_t frames, const std::string& output) {
    std::vector<std::string> args{ffmpeg, "-hide_banner", "-loglevel", "error", "-y"};
    args.insert(args.end(), input.begin(), input.end());
    const std::vector<std::string> encode{
            "-frames:v", std::to_string(frames), "-vf", kFilters,
            "-c:v", "libx264", "-preset", kPreset, "-crf", kQuality, "-threads", std::to_string(kThreads),
            "-pix_fmt", "yuv420p", "-colorspace", "bt709", "-color_primaries", "bt709", "-color_trc", "bt709",
            "-color_range", "tv", "-fflags", "+bitexact", "-flags:v", "+bitexact", "-map_metadata", "-1",
            "-movflags", "+faststart", "-f", "mp4", "file:" + output};
    args.insert(args.end(), encode.begin(), encode.end());
    return args;
}

// The frames' RGB bytes (width x height) on ffmpeg's stdin.
std::vector<std::string> raw_input(double fps, uint32_t width, uint32_t height) {
    return {"-f", "rawvideo", "-pix_fmt", "rgb24", "-s", fmt::format("{}x{}", width, height),
            "-framerate", fmt::format("{}", fps), "-i", "pipe:0"};
}

// The error for a failed ffmpeg run: its last lines, and the command to see more.
[[noreturn]] void throw_ffmpeg_failure(const std::string& ffmpeg, const std::string& frames_dir, uint32_t frames,
                                       double fps, const std::string& mp4_path, const ProcessResult& result) {
    const std::string output = last_lines(result.err + result.out, 8);
    // The same encoding with ffmpeg reading the PNGs itself (the same bytes).
    const std::string rerun =
        command_line({frames_dir}) + " && " +
        command_line(ffmpeg_arguments(ffmpeg, {"-framerate", fmt::format("{}", fps), "-i", "frame_%05d.png"}, frames,
                                      fs::absolute(mp4_path).string()));
    throw Error(ExitCode::Tool, fmt::format("{}: ffmpeg failed ({}) encoding {} frames of {}:\n{}\n(fix: check that the "
                                            "frames are readable PNGs of one size and that ffmpeg has libx264; to see "
                                            "more, run: cd {})",
                                            mp4_path, result.describe(), frames, frames_dir,
                                            output.empty() ? "(no output)" : output, rerun));
}

}  // namespace

void FramePixels::put(uint32_t frame, uint32_t width, uint32_t height, const std::vector<uint8_t>& rgb) {
    std::lock_guard lock(mutex_);
    if (held_.size() >= kHeld) return;  // encode is behind: it reads this one from its file
    held_[frame] = Frame{width, height, rgb};
}

std::optional<FramePixels::Frame> FramePixels::take(uint32_t frame) {
    std::lock_guard lock(mutex_);
    held_.erase(held_.begin(), held_.lower_bound(frame));
    const auto it = held_.find(frame);
    if (it == held_.end()) return std::nullopt;
    Frame out = std::move(it->second);
    held_.erase(it);
    return out;
}

void encode_mp4(const std::string& frames_dir, uint32_t frames, double fps, const std::string& mp4_path,
                const FrameReady& ready, FramePixels* pixels) {
    const std::optional<std::string> ffmpeg = find_program("ffmpeg");
    if (!ffmpeg)
        throw Error(ExitCode::Tool, mp4_path + ": ffmpeg not found on PATH, cannot encode the MP4 "
                                    "(fix: install ffmpeg: make deps, or apt-get install ffmpeg)");
    if (ready)
        check_rate(frames_dir, frames, fps);
    else
        check_frames(frames_dir, frames, fps);
    ToolOutput output(mp4_path, ".mp4");  // removed again unless committed
    ProcessOptions options;
    options.stdin_stream = true;
    // Started with frame 0, whose size is the movie's; killed unless waited for.
    std::optional<ChildProcess> child;
    uint32_t width = 0, height = 0;
    for (uint32_t i = 0; i < frames; ++i) {
        const std::string frame = (fs::path(frames_dir) / frame_name(i)).string();
        if (ready && !ready(i))
            throw_input_error(frame, fmt::format("frame {} of {} was not drawn", i, frames),
                              "render all frames first (shatter render)");
        std::optional<FramePixels::Frame> f = pixels ? pixels->take(i) : std::nullopt;
        if (!f) {
            Image image = decode_png(read_file(frame, "frame"), frame);
            f = FramePixels::Frame{image.width, image.height, std::move(image.rgb)};
        }
        if (i == 0) {
            width = f->width, height = f->height;
            child.emplace(ffmpeg_arguments(*ffmpeg, raw_input(fps, width, height), frames, output.path()), options);
        } else if (f->width != width || f->height != height) {
            throw_input_error(frame, fmt::format("frame {} is {} x {} pixels, frame 0 {} x {}", i, f->width, f->height,
                                                 width, height),
                              "render all frames at one size");
        }
        const std::string_view bytes(reinterpret_cast<const char*>(f->rgb.data()), f->rgb.size());
        if (!child->write_stdin(bytes)) break;  // ffmpeg stopped: its result says why
    }
    const ProcessResult result = child->wait();
    if (!result.ok()) throw_ffmpeg_failure(*ffmpeg, frames_dir, frames, fps, mp4_path, result);
    output.commit();
}

}  // namespace shatter
