// A tiny seeded random number generator whose output is the same on every platform and standard
// library. std::uniform_int_distribution and friends are implementation-defined (libstdc++ and
// libc++ give different numbers for the same engine state), so shatter draws its random numbers
// here instead (prescore's seeds and crack relief, simulate's kick directions).
//
// Engine: SplitMix64 (Steele, Lea, Flood, "Fast splittable pseudorandom number generators",
// OOPSLA 2014); bounded integers by Lemire's multiply-shift with rejection ("Fast random integer
// generation in an interval", ACM TOMACS 2019), which is exactly uniform.
#pragma once

#include <cassert>
#include <cstdint>

namespace shatter {

// SplitMix64's output function: 64 bits mixed so that nearby inputs give unrelated outputs (also
// a hash of integers, as the faired cracks' relief uses it).
inline uint64_t mix64(uint64_t z) {
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

class Rng {
public:
    explicit Rng(uint64_t seed) : state_(seed) {}

    // The next 64 random bits.
    uint64_t next_u64() { return mix64(state_ += 0x9E3779B97F4A7C15ull); }

    // A uniform integer in [0, bound); bound must be > 0.
    uint32_t below(uint32_t bound) {
        assert(bound > 0);
        uint64_t m = uint64_t(uint32_t(next_u64() >> 32)) * bound;
        auto low = uint32_t(m);
        if (low < bound) {
            const uint32_t threshold = uint32_t(-bound) % bound;
            while (low < threshold) {
                m = uint64_t(uint32_t(next_u64() >> 32)) * bound;
                low = uint32_t(m);
            }
        }
        return uint32_t(m >> 32);
    }

    // A uniform double in [0, 1) with 53 random bits.
    double uniform() { return double(next_u64() >> 11) * 0x1.0p-53; }

private:
    uint64_t state_;
};

}  // namespace shatter
