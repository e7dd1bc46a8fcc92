// The edge filter (render/edge_filter.h) against the exact answer: a half-plane edge drawn with
// one sample per pixel (each pixel white or black by its centre) and the same edge with each
// pixel's exact coverage, the image an ideal anti-aliasing would give.
#include <cmath>
#include <cstdint>
#include <vector>

#include <gtest/gtest.h>

#include "render/edge_filter.h"

namespace shatter {
namespace {

constexpr uint32_t kSize = 96;

double linear(uint8_t v) {
    const double c = v / 255.0;
    return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

// White where y < slope (x - centre) + centre (pixel units, pixel centres at +0.5): one sample per
// pixel, and the exact coverage of each pixel (linear light), estimated on a 32 x 32 grid.
struct Edge {
    std::vector<uint8_t> rgba;
    std::vector<double> coverage;
};

Edge half_plane(double slope) {
    Edge e;
    e.rgba.assign(kSize * kSize * 4, 255);
    e.coverage.assign(kSize * kSize, 0);
    const double c = kSize / 2.0 + 0.3;
    auto inside = [&](double x, double y) { return y < slope * (x - c) + c; };
    for (uint32_t y = 0; y < kSize; ++y)
        for (uint32_t x = 0; x < kSize; ++x) {
            const size_t i = size_t(y) * kSize + x;
            const uint8_t v = inside(x + 0.5, y + 0.5) ? 255 : 0;
            for (int k = 0; k < 3; ++k) e.rgba[4 * i + size_t(k)] = v;
            int n = 0;
            for (int sy = 0; sy < 32; ++sy)
                for (int sx = 0; sx < 32; ++sx) n += inside(x + (sx + 0.5) / 32, y + (sy + 0.5) / 32);
            e.coverage[i] = n / 1024.0;
        }
    return e;
}

// The mean distance from the exact coverage, in linear light, over the pixels the edge crosses.
double error(const std::vector<uint8_t>& rgba, const std::vector<double>& coverage) {
    double sum = 0;
    int n = 0;
    for (size_t i = 0; i < coverage.size(); ++i) {
        if (coverage[i] == 0 || coverage[i] == 1) continue;
        sum += std::abs(linear(rgba[4 * i + 1]) - coverage[i]);
        ++n;
    }
    return sum / n;
}

TEST(EdgeFilter, LeavesAFlatImageAlone) {
    std::vector<uint8_t> rgba(64 * 48 * 4);
    for (size_t i = 0; i < rgba.size(); ++i) rgba[i] = uint8_t(40 + (i % 4) * 50);
    const std::vector<uint8_t> before = rgba;
    filter_edges(rgba.data(), 64, 48);
    EXPECT_EQ(rgba, before);
}

// A staircase edge becomes a ramp: the filtered pixels are closer to each pixel's exact
// coverage than the one-sample image, on shallow and steep edges alike.
TEST(EdgeFilter, BringsAStaircaseEdgeTowardsItsExactCoverage) {
    for (double slope : {1.0 / 8, 1.0 / 3, 3.0, 8.0}) {
        Edge e = half_plane(slope);
        const double aliased = error(e.rgba, e.coverage);
        filter_edges(e.rgba.data(), kSize, kSize);
        const double filtered = error(e.rgba, e.coverage);
        // One sample per pixel is off by up to a quarter on average (along a shallow edge a
        // pixel's coverage is uniform in [0, 1], and rounds to 0 or 1; measured 0.19 to 0.25).
        EXPECT_GT(aliased, 0.15) << "slope " << slope;
        // Measured: 0.017 (slope 1/8), 0.033 (1/3), 0.030 (3), 0.019 (8): 7% to 17% of the aliased
        // error.
        EXPECT_LT(filtered, 0.25 * aliased) << "slope " << slope << ": aliased " << aliased;
    }
}

TEST(EdgeFilter, GivesTheSameBytesWithAnyNumberOfThreads) {
    Edge e = half_plane(1.0 / 5);
    std::vector<uint8_t> one = e.rgba, three = e.rgba;
    filter_edges(one.data(), kSize, kSize, 1);
    filter_edges(three.data(), kSize, kSize, 3);
    EXPECT_EQ(one, three);
    EXPECT_NE(one, e.rgba);
}

}  // namespace
}  // namespace shatter
