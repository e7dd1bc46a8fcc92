// Encodes frames to PNG and writes them on a second thread while the next frame renders: PNG encoding costs about
// as much as drawing at 1280x720, and llvmpipe leaves gaps (setup, readback) that the encoder
// fills. A bounded queue of `depth` frames: push() blocks when the writer falls behind, so
// memory stays at depth + 1 frame buffers.
//
// Determinism: each frame is encoded from its own pixels into its own file, so the order in
// which the thread gets to them cannot change any byte. With overlap off, push() writes inline.
#pragma once

#include <condition_variable>
#include <cstdint>
#include <deque>
#include <exception>
#include <functional>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

namespace shatter {

// Given a frame's number, size and sRGB RGB bytes (top row first).
using FramePixelsSink =
    std::function<void(uint32_t frame, uint32_t width, uint32_t height, const std::vector<uint8_t>& rgb)>;

class FrameWriter {
public:
    // `sink`, when set, gets each frame's pixels on the writer's thread before its file is written.
    FrameWriter(uint32_t width, uint32_t height, bool overlap, size_t depth = 2, FramePixelsSink sink = {});
    ~FrameWriter();  // waits for the queue to drain (errors are dropped; call finish() to see them)

    // A buffer of width * height * 4 bytes to read a frame into (recycled).
    std::vector<uint8_t> buffer();
    // Queues the sRGB RGBA bytes of frame `frame` (GL's bottom row first) to be encoded to PNG and
    // written to `path`; rethrows an error of an earlier write.
    void push(std::vector<uint8_t> rgba, std::string path, uint32_t frame = 0);
    // Queues the PNG of the frame pushed last written again to `path` as frame `frame` (a frame
    // whose pixels are that frame's: the same bytes, not encoded again). Needs an earlier push.
    void repeat(std::string path, uint32_t frame = 0);
    // Waits until every queued frame is written; rethrows the first error.
    void finish();

    double encode_seconds() const { return encode_seconds_; }
    double write_seconds() const { return write_seconds_; }

private:
    struct Job {
        std::vector<uint8_t> rgba;  // empty: the last PNG again
        std::string path;
        uint32_t frame = 0;
    };
    void queue(Job job);
    void run();
    void write(const Job& job);
    void rethrow();

    uint32_t width_, height_;
    bool overlap_;
    size_t depth_;
    FramePixelsSink sink_;
    std::mutex mutex_;
    std::condition_variable changed_;
    std::deque<Job> queue_;
    std::vector<std::vector<uint8_t>> free_;
    std::vector<uint8_t> rgb_;  // the writer's sRGB bytes
    std::string last_png_;      // the last frame encoded
    bool stop_ = false;
    bool pushed_ = false;  // (the render thread's)
    bool busy_ = false;
    std::exception_ptr error_;
    double encode_seconds_ = 0, write_seconds_ = 0;
    std::thread thread_;
};

}  // namespace shatter
