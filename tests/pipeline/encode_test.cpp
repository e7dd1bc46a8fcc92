// MP4 encoding: an H.264 yuv420p file with every frame at the (even) frame size, the same bytes
// from two encodes, grey levels that survive the trip (limited range, no level shift), hostile directory names, and clean
// failures (no temporary file left) for missing frames, broken frames and a missing ffmpeg; and frames
// taken as they are written (as beside render) giving the bytes of frames that were all there.
#include <gtest/gtest.h>
#include <stdlib.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <map>

#include <fmt/format.h>

#include "core/error.h"
#include "pipeline/encode.h"
#include "pipeline/process.h"
#include "render/png_io.h"
#include "support/frames_appearing.h"
#include "support/temp_dir.h"

namespace shatter {
namespace {

namespace fs = std::filesystem;
using testing_support::FramesAppearing;
using testing_support::TempDir;

// The message of the error that encoding FRAMES frames of `dir` into `mp4` raises, its exit code
// `code` (a test failure when there is none).
std::string encode_error(const std::string& dir, uint32_t frames, const std::string& mp4, ExitCode code,
                         const FrameReady& ready = {}) {
    try {
        encode_mp4(dir, frames, 30.0, mp4, ready);
    } catch (const Error& e) {
        EXPECT_EQ(e.code(), code);
        return e.what();
    }
    ADD_FAILURE() << "no error";
    return "";
}

// Frame i: a grey level 40 + 10 i on the left half, a moving bright bar on the right.
void write_frames(const fs::path& dir, uint32_t count, uint32_t w, uint32_t h) {
    fs::create_directories(dir);
    for (uint32_t i = 0; i < count; ++i) {
        Image img(w, h);
        for (uint32_t y = 0; y < h; ++y)
            for (uint32_t x = 0; x < w; ++x) {
                uint8_t* p = img.pixel(x, y);
                const bool bar = x >= w / 2 && (x + i) % 16 < 4;
                const uint8_t v = x < w / 2 ? uint8_t(40 + 10 * i) : bar ? 230 : 20;
                p[0] = p[1] = p[2] = v;
            }
        save_png((dir / fmt::format("frame_{:05d}.png", i)).string(), img);
    }
}

std::string slurp(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
}

std::map<std::string, std::string> probe(const fs::path& mp4) {
    const ProcessResult r = run_process({"ffprobe", "-v", "error", "-select_streams", "v:0", "-count_frames",
                                         "-show_entries", "stream=codec_name,pix_fmt,width,height,nb_read_frames",
                                         "-of", "default=noprint_wrappers=1", mp4.string()});
    EXPECT_TRUE(r.ok()) << r.err;
    std::map<std::string, std::string> out;
    size_t begin = 0;
    while (begin < r.out.size()) {
        size_t end = r.out.find('\n', begin);
        if (end == std::string::npos) end = r.out.size();
        const std::string line = r.out.substr(begin, end - begin);
        if (auto eq = line.find('='); eq != std::string::npos) out[line.substr(0, eq)] = line.substr(eq + 1);
        begin = end + 1;
    }
    return out;
}

class ScopedPath {
public:
    explicit ScopedPath(const std::string& value) : old_(getenv("PATH") ? getenv("PATH") : "") { setenv("PATH", value.c_str(), 1); }
    ~ScopedPath() { setenv("PATH", old_.c_str(), 1); }

private:
    std::string old_;
};

TEST(Encode, Mp4IsH264Yuv420pWithEveryFrameAndOddSizesPaddedToEven) {
    TempDir tmp;
    write_frames(tmp.path() / "frames", 12, 63, 47);
    const fs::path mp4 = tmp.path() / "out.mp4";
    encode_mp4((tmp.path() / "frames").string(), 12, 24.0, mp4.string());
    auto info = probe(mp4);
    EXPECT_EQ(info["codec_name"], "h264");
    EXPECT_EQ(info["pix_fmt"], "yuv420p");
    EXPECT_EQ(info["width"], "64");
    EXPECT_EQ(info["height"], "48");
    EXPECT_EQ(info["nb_read_frames"], "12");
    EXPECT_EQ(tmp.entries(), (std::vector<std::string>{"frames", "out.mp4"}));  // no temporary left
}

TEST(Encode, TwoEncodesAreByteIdenticalAndGreyLevelsSurvive) {
    TempDir tmp;
    write_frames(tmp.path() / "frames", 6, 64, 48);
    encode_mp4((tmp.path() / "frames").string(), 6, 30.0, tmp.file("a.mp4"));
    encode_mp4((tmp.path() / "frames").string(), 6, 30.0, tmp.file("b.mp4"));
    const std::string a = slurp(tmp.file("a.mp4"));
    EXPECT_GT(a.size(), 1000u);
    EXPECT_EQ(a, slurp(tmp.file("b.mp4")));
    // Decode frame 5 back to 8-bit grey (raw bytes on stdout: a PNG would carry the stream's
    // transfer function as gAMA and be re-gamma'd by the reader); its flat left half was 40 + 10 * 5.
    const ProcessResult r = run_process({"ffmpeg", "-nostdin", "-loglevel", "error", "-i", tmp.file("a.mp4"), "-vf",
                                         "select=eq(n\\,5)", "-frames:v", "1", "-f", "rawvideo", "-pix_fmt", "gray", "-"});
    ASSERT_TRUE(r.ok()) << r.err;
    ASSERT_EQ(r.out.size(), 64u * 48u);
    for (uint32_t y : {4u, 24u, 44u})
        for (uint32_t x : {2u, 12u, 28u}) EXPECT_NEAR(int(uint8_t(r.out[y * 64 + x])), 90, 2) << x << "," << y;
}

// As `shatter run` encodes beside render: the frames appear one by one while ffmpeg already runs.
TEST(Encode, FramesTakenAsTheyAppearGiveTheBytesOfFramesThatWereAllThere) {
    TempDir tmp;
    write_frames(tmp.path() / "all", 8, 64, 48);
    encode_mp4((tmp.path() / "all").string(), 8, 30.0, tmp.file("all.mp4"));
    const fs::path later = tmp.path() / "later";
    FramesAppearing render(tmp.path() / "all", later, 8, std::chrono::milliseconds(20));
    uint32_t asked = 0;
    encode_mp4(later.string(), 8, 30.0, tmp.file("later.mp4"), [&](uint32_t f) {
        EXPECT_EQ(f, asked++);  // in order, each once
        return render.ready(f);
    });
    render.join();
    EXPECT_EQ(slurp(tmp.file("later.mp4")), slurp(tmp.file("all.mp4")));
}

// A frame that never comes (render failed): bad input naming it, ffmpeg stopped, no temporary left.
TEST(Encode, AFrameThatNeverComesEndsTheEncodingAndLeavesNoTemporary) {
    TempDir tmp;
    write_frames(tmp.path() / "frames", 3, 32, 32);
    const std::string what = encode_error((tmp.path() / "frames").string(), 5, tmp.file("out.mp4"), ExitCode::BadInput,
                                          [](uint32_t f) { return f < 3; });
    EXPECT_NE(what.find("frame_00003.png"), std::string::npos) << what;
    EXPECT_EQ(tmp.entries(), std::vector<std::string>{"frames"});
}

TEST(Encode, HostileDirectoryAndFileNamesWork) {
    TempDir tmp;
    const fs::path dir = tmp.path() / "frames 100% 'q' \"d\" $(touch x) `y`;\nz";
    write_frames(dir, 4, 32, 32);
    const fs::path mp4 = dir / "out put %d 'it' $(x):1.mp4";
    encode_mp4(dir.string(), 4, 30.0, mp4.string());
    EXPECT_EQ(probe(mp4)["nb_read_frames"], "4");
    EXPECT_FALSE(fs::exists(tmp.path() / "x"));
    EXPECT_FALSE(fs::exists(dir / "x"));
}

TEST(Encode, MissingFramesAreBadInputAndLeaveNoTemporary) {
    TempDir tmp;
    std::string what = encode_error(tmp.file("no-frames"), 10, tmp.file("out.mp4"), ExitCode::BadInput);
    EXPECT_NE(what.find("no-frames"), std::string::npos);
    write_frames(tmp.path() / "frames", 3, 16, 16);
    what = encode_error((tmp.path() / "frames").string(), 4, tmp.file("out.mp4"), ExitCode::BadInput);
    EXPECT_NE(what.find("frame_00003.png"), std::string::npos);
    EXPECT_EQ(tmp.entries(), std::vector<std::string>{"frames"});
}

TEST(Encode, FramesThatAreNoPngOrOfAnotherSizeAreBadInputNamingTheFrame) {
    TempDir tmp;
    fs::create_directories(tmp.path() / "frames");
    for (int i = 0; i < 3; ++i) tmp.write(fmt::format("frames/frame_{:05d}.png", i), "not a png\n");
    std::string what = encode_error((tmp.path() / "frames").string(), 3, tmp.file("out.mp4"), ExitCode::BadInput);
    EXPECT_NE(what.find("frame_00000.png"), std::string::npos) << what;
    write_frames(tmp.path() / "sizes", 3, 32, 32);
    save_png((tmp.path() / "sizes" / "frame_00002.png").string(), Image(32, 16));
    what = encode_error((tmp.path() / "sizes").string(), 3, tmp.file("out.mp4"), ExitCode::BadInput);
    EXPECT_NE(what.find("frame 2 is 32 x 16 pixels, frame 0 32 x 32"), std::string::npos) << what;
    EXPECT_EQ(tmp.entries(), (std::vector<std::string>{"frames", "sizes"}));
}

// An ffmpeg that fails (here a script in its place): a tool error with its last lines and the
// command that encodes the same frames, nothing left behind.
TEST(Encode, AFailingFfmpegIsAToolErrorWithItsOutput) {
    TempDir tmp;
    write_frames(tmp.path() / "frames", 2, 16, 16);
    fs::create_directories(tmp.path() / "bin");
    const std::string fake = tmp.write("bin/ffmpeg", "#!/bin/sh\ncat > /dev/null\necho 'no encoder here' >&2\nexit 3\n");
    fs::permissions(fake, fs::perms::owner_all);
    ScopedPath path((tmp.path() / "bin").string() + ":/usr/bin:/bin");
    const std::string what =
        encode_error((tmp.path() / "frames").string(), 2, tmp.file("out.mp4"), ExitCode::Tool);
    EXPECT_NE(what.find("ffmpeg failed (exit code 3)"), std::string::npos) << what;
    EXPECT_NE(what.find("no encoder here"), std::string::npos) << what;
    EXPECT_NE(what.find("frame_%05d.png"), std::string::npos) << what;
    EXPECT_EQ(tmp.entries(), (std::vector<std::string>{"bin", "frames"}));
}

// As `shatter run` gives them: frames' pixels held in memory are taken instead of their files
// (the same pixels give the same bytes; other pixels another movie), and frames not held are
// read from their files.
TEST(Encode, PixelsHeldInMemoryAreTakenInsteadOfTheFiles) {
    TempDir tmp;
    write_frames(tmp.path() / "frames", 6, 64, 48);
    encode_mp4((tmp.path() / "frames").string(), 6, 30.0, tmp.file("files.mp4"));
    FramePixels same;
    for (uint32_t f : {0u, 2u, 3u}) {
        const Image image = load_png((tmp.path() / "frames" / fmt::format("frame_{:05d}.png", f)).string());
        same.put(f, image.width, image.height, image.rgb);
    }
    encode_mp4((tmp.path() / "frames").string(), 6, 30.0, tmp.file("memory.mp4"), {}, &same);
    EXPECT_EQ(slurp(tmp.file("memory.mp4")), slurp(tmp.file("files.mp4")));
    EXPECT_FALSE(same.take(3)) << "taken once";
    FramePixels other;
    other.put(2, 64, 48, std::vector<uint8_t>(64 * 48 * 3, 200));
    encode_mp4((tmp.path() / "frames").string(), 6, 30.0, tmp.file("other.mp4"), {}, &other);
    EXPECT_NE(slurp(tmp.file("other.mp4")), slurp(tmp.file("files.mp4")));
}

TEST(Encode, FfmpegMissingFromPathIsAToolErrorNamingTheFix) {
    TempDir tmp;
    write_frames(tmp.path() / "frames", 2, 16, 16);
    ScopedPath path(tmp.path().string());  // a PATH without ffmpeg
    const std::string what = encode_error((tmp.path() / "frames").string(), 2, tmp.file("out.mp4"), ExitCode::Tool);
    EXPECT_NE(what.find("install ffmpeg"), std::string::npos) << what;
    EXPECT_EQ(tmp.entries(), std::vector<std::string>{"frames"});
}

TEST(Encode, UnwritableOutputIsAnIoError) {
    TempDir tmp;
    write_frames(tmp.path() / "frames", 2, 16, 16);
    encode_error((tmp.path() / "frames").string(), 2, tmp.file("no/such/dir/out.mp4"), ExitCode::Io);
}

}  // namespace
}  // namespace shatter
