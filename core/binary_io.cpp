#include "core/binary_io.h"

#include <bit>
#include <cmath>

#include "core/error.h"

namespace shatter {

static_assert(std::endian::native == std::endian::little,
              "stage files are little-endian; a big-endian port needs byte swapping here");

void ByteWriter::raw(const void* p, size_t n) { bytes_.append(static_cast<const char*>(p), n); }

void ByteWriter::mat3(const Mat3& m) {
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) f64(m(r, c));
}

void ByteWriter::str(std::string_view s) {
    u32(static_cast<uint32_t>(s.size()));
    bytes_.append(s);
}

void ByteReader::fail(const std::string& problem) const {
    throw_input_error(source_ + " (byte " + std::to_string(offset()) + ")", problem,
                      "the file is damaged or not a shatter file; write it again with the stage that made it");
}

void ByteReader::raw(void* p, size_t n) {
    if (remaining() < n) fail("the file ends early (truncated)");
    std::memcpy(p, data_.data() + pos_, n);
    pos_ += n;
}

uint8_t ByteReader::u8() { uint8_t v; raw(&v, 1); return v; }
uint32_t ByteReader::u32() { uint32_t v; raw(&v, 4); return v; }
uint64_t ByteReader::u64() { uint64_t v; raw(&v, 8); return v; }
float ByteReader::f32() { float v; raw(&v, 4); return v; }
double ByteReader::f64() { double v; raw(&v, 8); return v; }

double ByteReader::finite_f64(const char* what) {
    double v = f64();
    if (!std::isfinite(v)) fail(std::string(what) + " is not a finite number");
    return v;
}

Vec3 ByteReader::finite_vec3(const char* what) {
    Vec3 v;
    for (int i = 0; i < 3; ++i) v[i] = finite_f64(what);
    return v;
}

Mat3 ByteReader::finite_mat3(const char* what) {
    Mat3 m;
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) m(r, c) = finite_f64(what);
    return m;
}

std::string ByteReader::str(size_t max_length) {
    uint32_t n = u32();
    if (n > max_length || n > remaining()) fail("a text field claims " + std::to_string(n) + " bytes");
    std::string s(data_.substr(pos_, n));
    pos_ += n;
    return s;
}

std::string_view ByteReader::bytes(size_t n) {
    if (remaining() < n) fail("the file ends early (truncated)");
    std::string_view s = data_.substr(pos_, n);
    pos_ += n;
    return s;
}

uint32_t ByteReader::count(size_t min_item_bytes, const char* what) {
    uint32_t n = u32();
    if (min_item_bytes > 0 && n > remaining() / min_item_bytes)
        fail(std::string("the count of ") + what + " (" + std::to_string(n) + ") does not fit in the file");
    return n;
}

uint32_t ByteReader::index(uint32_t limit, const char* what) {
    uint32_t v = u32();
    if (v >= limit)
        fail(std::string(what) + " " + std::to_string(v) + " is out of range (must be < " + std::to_string(limit) + ")");
    return v;
}

uint64_t fnv1a64(std::string_view bytes, uint64_t seed) {
    uint64_t h = seed;
    for (unsigned char c : bytes) {
        h ^= c;
        h *= 0x100000001b3ull;
    }
    return h;
}

}  // namespace shatter
