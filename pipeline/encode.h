// The MP4 of a run: ffmpeg (H.264, yuv420p) from the frames' pixels, byte-identical across runs.
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

namespace shatter {

// Frames' pixels handed from render to encode in memory, so that ffmpeg gets them without a PNG
// to decode (about half of its CPU time on the demo). At most kHeld frames at once: a frame that
// does not fit (encode behind) is read from its file, as is one render did not draw (a resumed
// run's). Thread-safe.
class FramePixels {
public:
    struct Frame {
        uint32_t width = 0, height = 0;  // (unit: pixels)
        std::vector<uint8_t> rgb;        // sRGB, top row first
    };
    static constexpr size_t kHeld = 8;
    void put(uint32_t frame, uint32_t width, uint32_t height, const std::vector<uint8_t>& rgb);
    // Frame `frame`'s pixels when held (and every earlier frame forgotten).
    std::optional<Frame> take(uint32_t frame);

private:
    std::mutex mutex_;
    std::map<uint32_t, Frame> held_;
};

// Encodes FRAMES_DIR/frame_NNNNN.png, frames [0, frames), at `fps` into `mp4_path` (written to a
// temporary name beside it and renamed into place). Odd sizes are padded to even. Throws
// Error(BadInput) when the directory or a frame is missing or fps is outside (0, 1000],
// Error(Tool) naming the fix when ffmpeg is missing ("install ffmpeg: make deps, or apt-get
// install ffmpeg") or fails (with its last lines of output and the command to rerun), Error(Io)
// when the output cannot be written. Takes ~2-3 s for 120 frames at 1280x720 on 2 cores.
//
// The frames' pixels go to ffmpeg through a pipe (raw RGB: the bytes of ffmpeg decoding the
// PNGs itself), one after the other, so the movie can be encoded while they are drawn: given
// `ready`, the frames need not be there yet; each is read once ready(i) returns true (it waits
// until frame i is written), and ready(i) returning false (the frame will never come: its
// render failed) ends the encoding with Error(BadInput). `pixels`, when given, holds frames'
// pixels render left there (taken instead of decoding their files). The bytes are the same
// either way. A frame that is no PNG, or of another size than frame 0, is Error(BadInput).
using FrameReady = std::function<bool(uint32_t frame)>;
void encode_mp4(const std::string& frames_dir, uint32_t frames, double fps, const std::string& mp4_path,
                const FrameReady& ready = {}, FramePixels* pixels = nullptr);

}  // namespace shatter
