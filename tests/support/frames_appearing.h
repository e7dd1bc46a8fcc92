// Frames that appear one by one, as render writes them while encode and the contact sheet already
// wait for them (pipeline/run.cpp: the stages beside render): frame_00000.png, ... of `from` are
// copied into `to`, `every` apart, on a thread of its own; ready(f) waits until frame f is there.
#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <thread>

#include <fmt/format.h>

namespace shatter::testing_support {

class FramesAppearing {
public:
    FramesAppearing(const std::filesystem::path& from, const std::filesystem::path& to, uint32_t count,
                    std::chrono::milliseconds every) {
        std::filesystem::create_directories(to);
        thread_ = std::thread([this, from, to, count, every] {
            for (uint32_t i = 0; i < count; ++i) {
                std::this_thread::sleep_for(every);
                const std::string name = fmt::format("frame_{:05d}.png", i);
                std::filesystem::copy_file(from / name, to / name);
                written_ = i + 1;
            }
        });
    }
    ~FramesAppearing() { join(); }
    FramesAppearing(const FramesAppearing&) = delete;
    FramesAppearing& operator=(const FramesAppearing&) = delete;

    // Waits until frame f is written; true (the frame comes).
    bool ready(uint32_t f) const {
        while (written_ <= f) std::this_thread::sleep_for(std::chrono::milliseconds(1));
        return true;
    }
    void join() {
        if (thread_.joinable()) thread_.join();
    }

private:
    std::atomic<uint32_t> written_{0};
    std::thread thread_;
};

}  // namespace shatter::testing_support
