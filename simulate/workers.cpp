#include "simulate/workers.h"

#include <algorithm>
#include <cstdlib>
#include <string>

namespace shatter {

Workers::Workers(unsigned threads) {
    for (unsigned i = 1; i < threads; ++i) pool_.emplace_back([this] { work(); });
}

Workers::~Workers() {
    {
        std::lock_guard<std::mutex> lock(mutex_);
        stop_ = true;
    }
    wake_.notify_all();
    for (std::thread& t : pool_) t.join();
}

void Workers::take() {
    for (;;) {
        const size_t start = next_.fetch_add(chunk_);
        if (start >= n_) return;
        const size_t end = std::min(n_, start + chunk_);
        for (size_t i = start; i < end; ++i) (*item_)(i);
    }
}

void Workers::work() {
    uint64_t seen = 0;
    for (;;) {
        {
            std::unique_lock<std::mutex> lock(mutex_);
            wake_.wait(lock, [&] { return stop_ || generation_ != seen; });
            if (stop_) return;
            seen = generation_;
            ++busy_;
        }
        take();
        {
            std::lock_guard<std::mutex> lock(mutex_);
            --busy_;
        }
        done_.notify_one();
    }
}

void Workers::run(size_t n, size_t chunk, const std::function<void(size_t)>& item) {
    if (pool_.empty() || n <= chunk) {
        for (size_t i = 0; i < n; ++i) item(i);
        return;
    }
    {
        std::lock_guard<std::mutex> lock(mutex_);
        item_ = &item;
        n_ = n;
        chunk_ = std::max<size_t>(chunk, 1);
        next_.store(0);
        ++generation_;
    }
    wake_.notify_all();
    take();
    std::unique_lock<std::mutex> lock(mutex_);
    // Every worker that woke for this loop has left it (one that has not woken yet finds no item
    // left when it does: next_ stays past n_ until the next run, which waits for busy_ again).
    done_.wait(lock, [&] { return busy_ == 0; });
}

unsigned default_threads() {
    if (const char* env = std::getenv("SHATTER_THREADS")) {
        char* end = nullptr;
        const long n = std::strtol(env, &end, 10);
        if (end != env && *end == 0 && n >= 1 && n <= 64) return unsigned(n);
    }
    return std::clamp(std::thread::hardware_concurrency(), 1u, 8u);
}

}  // namespace shatter
