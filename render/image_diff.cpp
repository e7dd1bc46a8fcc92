#include "render/image_diff.h"

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <cstdlib>
#include <limits>

#include <fmt/format.h>

namespace shatter {

namespace {

std::vector<float> luma(const Image& img) {
    std::vector<float> y(size_t(img.width) * img.height);
    for (size_t i = 0; i < y.size(); ++i) {
        const uint8_t* p = &img.rgb[i * 3];
        y[i] = 0.299f * p[0] + 0.587f * p[1] + 0.114f * p[2];
    }
    return y;
}

// Separable 11-tap Gaussian (sigma 1.5) blur with replicated edges.
std::vector<float> blur(const std::vector<float>& in, uint32_t w, uint32_t h) {
    static const std::array<float, 11> kernel = [] {
        std::array<float, 11> k{};
        float sum = 0;
        for (int i = 0; i < 11; ++i) sum += k[size_t(i)] = std::exp(-float((i - 5) * (i - 5)) / (2 * 1.5f * 1.5f));
        for (float& v : k) v /= sum;
        return k;
    }();
    std::vector<float> tmp(in.size()), out(in.size());
    for (uint32_t y = 0; y < h; ++y)
        for (uint32_t x = 0; x < w; ++x) {
            float s = 0;
            for (int k = -5; k <= 5; ++k) {
                const int xx = std::clamp(int(x) + k, 0, int(w) - 1);
                s += kernel[size_t(k + 5)] * in[size_t(y) * w + size_t(xx)];
            }
            tmp[size_t(y) * w + x] = s;
        }
    for (uint32_t y = 0; y < h; ++y)
        for (uint32_t x = 0; x < w; ++x) {
            float s = 0;
            for (int k = -5; k <= 5; ++k) {
                const int yy = std::clamp(int(y) + k, 0, int(h) - 1);
                s += kernel[size_t(k + 5)] * tmp[size_t(yy) * w + x];
            }
            out[size_t(y) * w + x] = s;
        }
    return out;
}

double ssim(const Image& a, const Image& b) {
    const uint32_t w = a.width, h = a.height;
    const std::vector<float> x = luma(a), y = luma(b);
    std::vector<float> xx(x.size()), yy(x.size()), xy(x.size());
    for (size_t i = 0; i < x.size(); ++i) {
        xx[i] = x[i] * x[i];
        yy[i] = y[i] * y[i];
        xy[i] = x[i] * y[i];
    }
    const std::vector<float> mx = blur(x, w, h), my = blur(y, w, h);
    const std::vector<float> sxx = blur(xx, w, h), syy = blur(yy, w, h), sxy = blur(xy, w, h);
    const double c1 = std::pow(0.01 * 255, 2), c2 = std::pow(0.03 * 255, 2);
    double sum = 0;
    for (size_t i = 0; i < x.size(); ++i) {
        const double ux = mx[i], uy = my[i];
        const double vx = std::max(0.0, sxx[i] - ux * ux), vy = std::max(0.0, syy[i] - uy * uy);
        const double cxy = sxy[i] - ux * uy;
        sum += ((2 * ux * uy + c1) * (2 * cxy + c2)) / ((ux * ux + uy * uy + c1) * (vx + vy + c2));
    }
    return sum / double(x.size());
}

}  // namespace

DiffMetrics compare_images(const Image& a, const Image& b, double threshold) {
    assert(a.width == b.width && a.height == b.height);
    DiffMetrics m;
    double squares = 0;
    const size_t pixels = size_t(a.width) * a.height;
    for (size_t i = 0; i < pixels; ++i) {
        int pixel_max = 0;
        for (int c = 0; c < 3; ++c) {
            const int d = std::abs(int(a.rgb[i * 3 + c]) - int(b.rgb[i * 3 + c]));
            pixel_max = std::max(pixel_max, d);
            squares += double(d) * d;
        }
        m.max_channel_diff = std::max(m.max_channel_diff, pixel_max);
        m.pixels_over += pixel_max > threshold;
    }
    m.rmse = std::sqrt(squares / double(pixels * 3));
    m.psnr = m.rmse > 0 ? 20 * std::log10(255.0 / m.rmse) : std::numeric_limits<double>::infinity();
    m.fraction_over = double(m.pixels_over) / double(pixels);
    m.ssim = m.max_channel_diff == 0 ? 1.0 : ssim(a, b);
    return m;
}

std::vector<std::string> tolerance_failures(const DiffMetrics& m, const DiffTolerance& t) {
    std::vector<std::string> out;
    if (m.max_channel_diff > t.max_channel_diff)
        out.push_back(fmt::format("max channel difference {} > {:g}", m.max_channel_diff, t.max_channel_diff));
    if (m.rmse > t.max_rmse) out.push_back(fmt::format("rmse {:.4g} > {:g}", m.rmse, t.max_rmse));
    if (m.psnr < t.min_psnr) out.push_back(fmt::format("psnr {:.4g} dB < {:g}", m.psnr, t.min_psnr));
    if (m.ssim < t.min_ssim) out.push_back(fmt::format("ssim {:.6g} < {:g}", m.ssim, t.min_ssim));
    if (m.fraction_over > t.max_fraction)
        out.push_back(fmt::format("{:.4g}% of pixels differ by more than {:g} levels > {:g}%", 100 * m.fraction_over,
                                  t.threshold, 100 * t.max_fraction));
    return out;
}

Image heat_map(const Image& expected, const Image& actual) {
    assert(expected.width == actual.width && expected.height == actual.height);
    Image out(expected.width, expected.height);
    for (size_t i = 0; i < size_t(out.width) * out.height; ++i) {
        int d = 0;
        for (int c = 0; c < 3; ++c) d = std::max(d, std::abs(int(expected.rgb[i * 3 + c]) - int(actual.rgb[i * 3 + c])));
        const uint8_t* e = &expected.rgb[i * 3];
        const float grey = (0.299f * e[0] + 0.587f * e[1] + 0.114f * e[2]) * 0.3f;
        float r = grey, g = grey, b = grey;
        if (d > 0) {
            const float t = std::min(1.0f, std::log2(float(d)) / 6.0f);  // 1 level -> 0, 64 levels -> 1
            r = 96 + 159 * std::min(1.0f, t * 2);
            g = 255 * std::clamp(t * 2 - 0.6f, 0.0f, 1.0f);
            b = 255 * std::clamp(t * 3 - 2.0f, 0.0f, 1.0f);
        }
        out.rgb[i * 3 + 0] = uint8_t(std::lround(r));
        out.rgb[i * 3 + 1] = uint8_t(std::lround(g));
        out.rgb[i * 3 + 2] = uint8_t(std::lround(b));
    }
    return out;
}

}  // namespace shatter
