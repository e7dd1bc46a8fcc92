#include "core/progress.h"

#include <unistd.h>

#include <cstdio>

#include <spdlog/spdlog.h>

namespace shatter {

Progress::Progress(std::string label, size_t total)
    : label_(std::move(label)), total_(total), start_(std::chrono::steady_clock::now()) {
    tty_ = ::isatty(2) == 1;
    enabled_ = spdlog::default_logger_raw()->level() <= spdlog::level::info;
}

Progress::~Progress() { done(); }

void Progress::advance(size_t n) {
    count_ += n;
    if (enabled_) draw(false);
}

void Progress::done() {
    if (finished_) return;
    finished_ = true;
    count_ = total_;
    if (enabled_) draw(true);
}

void Progress::draw(bool final) {
    const double fraction = total_ ? static_cast<double>(count_) / static_cast<double>(total_) : 1.0;
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    // Fast loops stay quiet: a bar appears after half a second, lines on a pipe after two.
    if (seconds < (tty_ ? 0.5 : 2.0) && !(final && (last_width_ >= 0 || last_tenth_ >= 0))) return;
    if (tty_) {
        const int width = 30;
        const int filled = static_cast<int>(fraction * width);
        if (filled == last_width_ && !final) return;
        last_width_ = filled;
        std::fprintf(stderr, "\r%-10s [%.*s%*s] %3d%% %zu/%zu %.1fs%s", label_.c_str(), filled,
                     "##############################", width - filled, "", static_cast<int>(fraction * 100), count_,
                     total_, seconds, final ? "\n" : "");
    } else {
        const int tenth = static_cast<int>(fraction * 10);
        if (tenth == last_tenth_ || (tenth < 10 && !final && tenth == 0)) return;
        last_tenth_ = tenth;
        std::fprintf(stderr, "%s: %d%% (%zu/%zu) %.1fs\n", label_.c_str(), static_cast<int>(fraction * 100), count_,
                     total_, seconds);
    }
    std::fflush(stderr);
}

}  // namespace shatter
