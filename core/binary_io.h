// Little-endian byte writer and a bounds-checked reader for the stage files. The reader never
// trusts a count: every read checks the bytes left, and a corrupt file becomes a BadInput Error
// naming the file and the byte offset, never a crash or a huge allocation.
#pragma once

#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>
#include <vector>

#include "core/geometry.h"

namespace shatter {

static_assert(sizeof(double) == 8 && sizeof(float) == 4, "IEEE-754 doubles and floats expected");

class ByteWriter {
public:
    void u8(uint8_t v) { bytes_.push_back(static_cast<char>(v)); }
    void u32(uint32_t v) { raw(&v, 4); }
    void u64(uint64_t v) { raw(&v, 8); }
    void f32(float v) { raw(&v, 4); }
    void f64(double v) { raw(&v, 8); }
    void vec3(const Vec3& v) {
        f64(v.x());
        f64(v.y());
        f64(v.z());
    }
    void mat3(const Mat3& m);
    void str(std::string_view s);
    void bytes(std::string_view s) { bytes_.append(s); }
    const std::string& data() const { return bytes_; }
    std::string& data() { return bytes_; }

private:
    void raw(const void* p, size_t n);  // little-endian hosts only (checked in binary_io.cpp)
    std::string bytes_;
};

class ByteReader {
public:
    // `source` names the file in error messages; `base` is the offset of `data` in that file.
    ByteReader(std::string_view data, std::string source, size_t base = 0)
        : data_(data), source_(std::move(source)), base_(base) {}

    uint8_t u8();
    uint32_t u32();
    uint64_t u64();
    float f32();
    double f64();           // any value, NaN included
    double finite_f64(const char* what);  // rejects NaN and Inf
    Vec3 finite_vec3(const char* what);
    Mat3 finite_mat3(const char* what);
    std::string str(size_t max_length = 1 << 24);
    std::string_view bytes(size_t n);
    // A count of items that each take at least `min_item_bytes`; rejects counts that cannot fit
    // in the bytes left, so a corrupt count never triggers a huge allocation.
    uint32_t count(size_t min_item_bytes, const char* what);
    // An index that must be < limit.
    uint32_t index(uint32_t limit, const char* what);

    size_t offset() const { return base_ + pos_; }
    size_t remaining() const { return data_.size() - pos_; }
    [[noreturn]] void fail(const std::string& problem) const;

private:
    void raw(void* p, size_t n);
    std::string_view data_;
    std::string source_;
    size_t base_ = 0;
    size_t pos_ = 0;
};

// FNV-1a, 64 bit: the checksum of stage-file payloads and the hash of cache keys. Not for
// security; it detects truncation and bit flips.
uint64_t fnv1a64(std::string_view bytes, uint64_t seed = 0xcbf29ce484222325ull);

}  // namespace shatter
