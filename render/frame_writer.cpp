#include "render/frame_writer.h"

#include <chrono>

#include "core/atomic_file.h"
#include "core/error.h"
#include "render/png_io.h"
#include "render/srgb_encode.h"

namespace shatter {

FrameWriter::FrameWriter(uint32_t width, uint32_t height, bool overlap, size_t depth, FramePixelsSink sink)
    : width_(width), height_(height), overlap_(overlap), depth_(depth), sink_(std::move(sink)) {
    if (overlap_) thread_ = std::thread([this] { run(); });
}

FrameWriter::~FrameWriter() {
    {
        std::lock_guard lock(mutex_);
        stop_ = true;
    }
    changed_.notify_all();
    if (thread_.joinable()) thread_.join();
}

std::vector<uint8_t> FrameWriter::buffer() {
    std::lock_guard lock(mutex_);
    if (free_.empty()) return std::vector<uint8_t>(size_t(width_) * height_ * 4);
    std::vector<uint8_t> b = std::move(free_.back());
    free_.pop_back();
    return b;
}

void FrameWriter::write(const Job& job) {
    const auto t0 = std::chrono::steady_clock::now();
    if (!job.rgba.empty()) {
        rgb_.resize(size_t(width_) * height_ * 3);
        rgba_rows_to_rgb(job.rgba.data(), width_, height_, rgb_.data());
        if (sink_) sink_(job.frame, width_, height_, rgb_);
        last_png_ = encode_png(rgb_.data(), width_, height_, 3, size_t(width_) * 3);
    } else if (sink_) {
        sink_(job.frame, width_, height_, rgb_);  // a repeat: the last frame's pixels
    }
    const auto t1 = std::chrono::steady_clock::now();
    write_file_atomic(job.path, last_png_);
    const auto t2 = std::chrono::steady_clock::now();
    encode_seconds_ += std::chrono::duration<double>(t1 - t0).count();
    write_seconds_ += std::chrono::duration<double>(t2 - t1).count();
}

void FrameWriter::rethrow() {
    if (error_) {
        std::exception_ptr e = error_;
        error_ = nullptr;
        std::rethrow_exception(e);
    }
}

void FrameWriter::push(std::vector<uint8_t> rgba, std::string path, uint32_t frame) {
    queue(Job{std::move(rgba), std::move(path), frame});
    pushed_ = true;
}

void FrameWriter::repeat(std::string path, uint32_t frame) {
    if (!pushed_) throw Error(ExitCode::Internal, "FrameWriter::repeat before any frame");
    queue(Job{{}, std::move(path), frame});
}

void FrameWriter::queue(Job job) {
    if (!overlap_) {
        write(job);
        if (!job.rgba.empty()) free_.push_back(std::move(job.rgba));
        return;
    }
    std::unique_lock lock(mutex_);
    changed_.wait(lock, [&] { return queue_.size() < depth_ || error_; });
    rethrow();
    queue_.push_back(std::move(job));
    changed_.notify_all();
}

void FrameWriter::finish() {
    if (overlap_) {
        std::unique_lock lock(mutex_);
        changed_.wait(lock, [&] { return (queue_.empty() && !busy_) || error_; });
    }
    rethrow();
}

void FrameWriter::run() {
    std::unique_lock lock(mutex_);
    for (;;) {
        changed_.wait(lock, [&] { return stop_ || !queue_.empty(); });
        if (queue_.empty()) return;  // stopping with nothing left
        if (error_) {                // after an error: drop the rest, write nothing more
            queue_.clear();
            changed_.notify_all();
            continue;
        }
        Job job = std::move(queue_.front());
        queue_.pop_front();
        busy_ = true;
        lock.unlock();
        std::exception_ptr failed;
        try {
            write(job);
        } catch (...) {
            failed = std::current_exception();
        }
        lock.lock();
        busy_ = false;
        if (failed && !error_) error_ = failed;
        if (!job.rgba.empty()) free_.push_back(std::move(job.rgba));
        changed_.notify_all();
    }
}

}  // namespace shatter
