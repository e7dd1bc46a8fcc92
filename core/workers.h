// A fixed set of worker threads that run a loop's items together with the calling thread. The
// items must be independent of each other: which thread runs an item never changes what it
// computes, so a run's bytes do not depend on the thread count.
#pragma once

#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace shatter {

class Workers {
public:
    // `threads` in all, the caller included (1: no worker thread). The worker threads start with
    // the first loop that has items for them.
    explicit Workers(unsigned threads) : threads_(std::max(threads, 1u)) {}
    ~Workers();
    Workers(const Workers&) = delete;
    Workers& operator=(const Workers&) = delete;
    unsigned threads() const { return threads_; }
    // item(i) for every i in [0, n), in chunks of `chunk` taken in turn by whichever thread is
    // free; returns when all are done.
    void run(size_t n, size_t chunk, const std::function<void(size_t)>& item);
    // a() and b() as the two items of one loop; what either throws is rethrown here once both
    // are done (a's first).
    void both(const std::function<void()>& a, const std::function<void()>& b);

private:
    void work();
    void take();  // runs chunks of the current loop until none is left
    const unsigned threads_;
    std::vector<std::thread> pool_;
    std::mutex mutex_;
    std::condition_variable wake_, done_;
    uint64_t generation_ = 0;  // one per run()
    bool stop_ = false;
    bool open_ = false;  // workers may join the current loop (until the caller has run out of items)
    unsigned busy_ = 0;  // worker threads inside the current loop
    const std::function<void(size_t)>* item_ = nullptr;
    size_t n_ = 0, chunk_ = 1;
    std::atomic<size_t> next_{0};
};

// The cores this process may run on: its CPU affinity (a Slurm job's or a container's cpuset),
// else the machine's; at least 1.
unsigned usable_cores();

// The number of threads a run uses: SHATTER_THREADS when set (1 to 64), else the cores the
// process may run on (its CPU affinity: a Slurm job's or a container's cpuset; at most 8). A
// value that is not a number from 1 to 64 is warned about and not used.
unsigned default_threads();

}  // namespace shatter
