#include "render/edge_filter.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <thread>
#include <vector>

namespace shatter {

namespace {

// A pixel is on an edge when the luma range of it and its four neighbours exceeds this fraction
// of their largest luma, and kMinRange in any case (dark regions).
constexpr float kRelativeRange = 0.125f;
constexpr float kMinRange = 0.0312f;
// How far the edge's ends are searched for, each way along it (unit: pixels).
constexpr int kSearch = 12;
// The largest sub-pixel blend (a pixel unlike all its neighbours, e.g. a thin line).
constexpr float kSubpixel = 0.75f;

struct Tables {
    std::array<float, 256> linear;     // sRGB byte -> linear light
    std::array<float, 255> threshold;  // linear values half-way between consecutive bytes
    Tables() {
        for (int i = 0; i < 256; ++i) {
            const double c = i / 255.0;
            linear[size_t(i)] = float(c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4));
        }
        for (int i = 0; i < 255; ++i) threshold[size_t(i)] = 0.5f * (linear[size_t(i)] + linear[size_t(i) + 1]);
    }
    uint8_t encode(float v) const {  // the byte whose linear value is nearest v
        return uint8_t(std::upper_bound(threshold.begin(), threshold.end(), v) - threshold.begin());
    }
};

const Tables& tables() {
    static const Tables t;
    return t;
}

class Filter {
public:
    Filter(const uint8_t* in, uint32_t width, uint32_t height)
        : in_(in), w_(int(width)), h_(int(height)), luma_(size_t(width) * height) {}

    // The luma of rows [y0, y1).
    void luma_rows(int y0, int y1) {
        for (size_t i = size_t(y0) * size_t(w_); i < size_t(y1) * size_t(w_); ++i) {
            const uint8_t* p = in_ + 4 * i;
            luma_[i] = (0.299f * p[0] + 0.587f * p[1] + 0.114f * p[2]) * (1.0f / 255.0f);
        }
    }

    // Rows [y0, y1) of the output, whose pixels hold the input's until filtered.
    void rows(uint8_t* out, int y0, int y1) const {
        for (int y = y0; y < y1; ++y) {
            const bool inside = y > 0 && y + 1 < h_;
            const float* row = luma_.data() + size_t(y) * size_t(w_);
            for (int x = 0; x < w_; ++x) {
                // Most pixels are flat: the range test first, without the clamps of luma().
                if (inside && x > 0 && x + 1 < w_) {
                    const float m = row[x], n = row[x + w_], s = row[x - w_], e = row[x + 1], w = row[x - 1];
                    const float hi = std::max(std::max(std::max(m, n), std::max(s, e)), w);
                    const float lo = std::min(std::min(std::min(m, n), std::min(s, e)), w);
                    if (hi - lo < std::max(kMinRange, hi * kRelativeRange)) continue;
                }
                pixel(out, x, y);
            }
        }
    }

private:
    float luma(int x, int y) const {
        x = std::clamp(x, 0, w_ - 1);
        y = std::clamp(y, 0, h_ - 1);
        return luma_[size_t(y) * size_t(w_) + size_t(x)];
    }

    void pixel(uint8_t* out, int x, int y) const {
        const size_t at = 4 * (size_t(y) * size_t(w_) + size_t(x));
        const float m = luma(x, y), n = luma(x, y + 1), s = luma(x, y - 1), e = luma(x + 1, y), w = luma(x - 1, y);
        const float hi = std::max({m, n, s, e, w}), lo = std::min({m, n, s, e, w});
        const float range = hi - lo;
        if (range < std::max(kMinRange, hi * kRelativeRange)) return;
        const float ne = luma(x + 1, y + 1), nw = luma(x - 1, y + 1), se = luma(x + 1, y - 1), sw = luma(x - 1, y - 1);
        // Sub-pixel: how much the pixel stands out from its neighbourhood's mean.
        const float mean = (2 * (n + s + e + w) + ne + nw + se + sw) / 12;
        float sub = std::clamp(std::abs(mean - m) / range, 0.0f, 1.0f);
        sub = (3 - 2 * sub) * sub * sub;
        sub = sub * sub * kSubpixel;
        // The edge runs along x (horizontal: luma changes with y) or along y.
        const float across_y = std::abs(nw - 2 * w + sw) + 2 * std::abs(n - 2 * m + s) + std::abs(ne - 2 * e + se);
        const float across_x = std::abs(nw - 2 * n + ne) + 2 * std::abs(w - 2 * m + e) + std::abs(sw - 2 * s + se);
        const bool horizontal = across_y >= across_x;
        // The side across the edge with the larger step.
        const float before = horizontal ? s : w, after = horizontal ? n : e;
        const bool back = std::abs(before - m) >= std::abs(after - m);
        const int side = back ? -1 : 1;
        const float other = back ? before : after;
        const float gradient = 0.25f * std::max(std::abs(before - m), std::abs(after - m));
        const float edge_luma = 0.5f * (m + other);
        // Walk along the edge both ways until the pair of pixels straddling it no longer averages
        // to the edge's luma: the edge's ends.
        const int dx = horizontal ? 1 : 0, dy = horizontal ? 0 : 1;
        const int ox = horizontal ? 0 : side, oy = horizontal ? side : 0;
        auto end = [&](int dir, float* delta) {
            for (int i = 1; i <= kSearch; ++i) {
                const int px = x + dir * i * dx, py = y + dir * i * dy;
                *delta = 0.5f * (luma(px, py) + luma(px + ox, py + oy)) - edge_luma;
                if (std::abs(*delta) >= gradient) return i;
            }
            return kSearch;
        };
        float delta_neg = 0, delta_pos = 0;
        const int d_neg = end(-1, &delta_neg), d_pos = end(1, &delta_pos);
        const bool neg_closer = d_neg < d_pos;
        const float span = float(d_neg + d_pos - 1);
        float offset = 0.5f - float(std::min(d_neg, d_pos) - 0.5f) / std::max(span, 1.0f);
        // Only when the nearer end steps the way the pixel does (else the pixel is on the edge's
        // far side of the staircase).
        const bool centre_below = m < edge_luma;
        if (((neg_closer ? delta_neg : delta_pos) < 0) == centre_below) offset = 0;
        const float t = std::max(offset, sub);
        if (!(t > 0)) return;
        const Tables& lut = tables();
        const uint8_t* a = in_ + at;
        const uint8_t* b = in_ + 4 * (size_t(std::clamp(y + oy, 0, h_ - 1)) * size_t(w_) +
                                      size_t(std::clamp(x + ox, 0, w_ - 1)));
        for (int c = 0; c < 3; ++c) {
            const float la = lut.linear[a[c]], lb = lut.linear[b[c]];
            out[at + size_t(c)] = lut.encode(la + t * (lb - la));
        }
    }

    const uint8_t* in_;
    int w_, h_;
    std::vector<float> luma_;
};

}  // namespace

void filter_edges(uint8_t* rgba, uint32_t width, uint32_t height, unsigned threads) {
    if (width == 0 || height == 0) return;
    const std::vector<uint8_t> in(rgba, rgba + size_t(width) * height * 4);
    Filter filter(in.data(), width, height);
    const int h = int(height);
    const int n = int(std::clamp(threads, 1u, 16u));
    // Each thread its band of rows: first the luma (all of it before any filtering), then the
    // pixels, each written from the input alone.
    auto in_parallel = [&](const auto& work) {
        std::vector<std::thread> workers;
        for (int i = 1; i < n; ++i) workers.emplace_back([&, i] { work(h * i / n, h * (i + 1) / n); });
        work(0, h / n);
        for (std::thread& t : workers) t.join();
    };
    in_parallel([&](int y0, int y1) { filter.luma_rows(y0, y1); });
    in_parallel([&](int y0, int y1) { filter.rows(rgba, y0, y1); });
}

}  // namespace shatter
