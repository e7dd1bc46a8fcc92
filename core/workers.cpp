#include "core/workers.h"

#include <sched.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <array>
#include <exception>
#include <cstdlib>

namespace shatter {

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
            if (!open_) continue;  // woke too late: the loop is over
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
    if (threads_ == 1 || n <= chunk) {
        for (size_t i = 0; i < n; ++i) item(i);
        return;
    }
    while (pool_.size() + 1 < threads_) pool_.emplace_back([this] { work(); });
    {
        std::lock_guard<std::mutex> lock(mutex_);
        item_ = &item;
        n_ = n;
        chunk_ = std::max<size_t>(chunk, 1);
        next_.store(0);
        ++generation_;
        open_ = true;
    }
    wake_.notify_all();
    take();
    std::unique_lock<std::mutex> lock(mutex_);
    // No worker joins from here on (one that wakes now goes back to sleep), and those that joined
    // finish their chunks: then none is left inside the loop when the next one is set up.
    open_ = false;
    done_.wait(lock, [&] { return busy_ == 0; });
}

void Workers::both(const std::function<void()>& a, const std::function<void()>& b) {
    std::array<std::exception_ptr, 2> failed;
    run(2, 1, [&](size_t i) {
        try {
            (i == 0 ? a : b)();
        } catch (...) {
            failed[i] = std::current_exception();
        }
    });
    for (const std::exception_ptr& e : failed)
        if (e) std::rethrow_exception(e);
}

unsigned usable_cores() {
    cpu_set_t allowed;
    CPU_ZERO(&allowed);
    const unsigned n = sched_getaffinity(0, sizeof(allowed), &allowed) == 0 ? unsigned(CPU_COUNT(&allowed))
                                                                            : std::thread::hardware_concurrency();
    return std::max(n, 1u);
}

unsigned default_threads() {
    const unsigned cores = std::min(usable_cores(), 8u);
    if (const char* env = std::getenv("SHATTER_THREADS")) {
        char* end = nullptr;
        const long n = std::strtol(env, &end, 10);
        if (end != env && *end == 0 && n >= 1 && n <= 64) return unsigned(n);
        static bool warned = false;
        if (!warned)
            spdlog::warn("SHATTER_THREADS=\"{}\" is not a number of threads from 1 to 64; using {} (the cores; fix: "
                         "unset it or give e.g. SHATTER_THREADS=2)", env, cores);
        warned = true;
    }
    return cores;
}

}  // namespace shatter
