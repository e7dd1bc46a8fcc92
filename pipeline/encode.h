// The MP4 of a run: ffmpeg (H.264, yuv420p) from the PNG frames, byte-identical across runs.
#pragma once

#include <cstdint>
#include <functional>
#include <string>

namespace shatter {

// Encodes FRAMES_DIR/frame_NNNNN.png, frames [0, frames), at `fps` into `mp4_path` (written to a
// temporary name beside it and renamed into place). Odd sizes are padded to even. Throws
// Error(BadInput) when the directory or a frame is missing or fps is outside (0, 1000],
// Error(Tool) naming the fix when ffmpeg is missing ("install ffmpeg: make deps, or apt-get
// install ffmpeg") or fails (with its last lines of output and the command to rerun), Error(Io)
// when the output cannot be written. Takes ~2-3 s for 120 frames at 1280x720 on 2 cores.
//
// The frames go to ffmpeg through a pipe, one after the other, so the movie can be encoded while
// they are drawn: given `ready`, the frames need not be there yet; each is read once ready(i)
// returns true (it waits until frame i is written), and ready(i) returning false (the frame will
// never come: its render failed) ends the encoding with Error(BadInput). The bytes are the same
// either way.
using FrameReady = std::function<bool(uint32_t frame)>;
void encode_mp4(const std::string& frames_dir, uint32_t frames, double fps, const std::string& mp4_path,
                const FrameReady& ready = {});

}  // namespace shatter
