// The diff metrics on synthetic pairs whose answers are known in closed form: identical, one
// pixel changed, Gaussian noise of known sigma, a one-pixel shift of stripes.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "render/image_diff.h"

namespace shatter {
namespace {

Image flat(uint32_t w, uint32_t h, uint8_t v) {
    Image img(w, h);
    std::fill(img.rgb.begin(), img.rgb.end(), v);
    return img;
}

// Vertical stripes, 4 pixels black then 4 white; shifted right by `shift` (the first columns
// repeat column 0).
Image stripes(uint32_t w, uint32_t h, uint32_t shift) {
    Image img(w, h);
    for (uint32_t y = 0; y < h; ++y)
        for (uint32_t x = 0; x < w; ++x) {
            const uint32_t src = x >= shift ? x - shift : 0;
            std::fill_n(img.pixel(x, y), 3, uint8_t((src / 4) % 2 ? 255 : 0));
        }
    return img;
}

// Mid-grey plus independent Gaussian noise of `sigma` levels per channel (Box-Muller on our own
// uniform draws, so the pair is the same on every standard library).
Image noisy(const Image& base, double sigma, uint32_t seed) {
    std::mt19937 rng(seed);
    auto uniform = [&] { return (double(rng()) + 0.5) / 4294967296.0; };
    Image out = base;
    for (uint8_t& v : out.rgb) {
        const double n = sigma * std::sqrt(-2 * std::log(uniform())) * std::cos(2 * M_PI * uniform());
        v = uint8_t(std::clamp(std::lround(v + n), 0L, 255L));
    }
    return out;
}

TEST(ImageDiff, IdenticalImagesHaveZeroErrorInfinitePsnrAndSsimOne) {
    const Image a = stripes(64, 48, 0);
    const DiffMetrics m = compare_images(a, a, 8);
    EXPECT_EQ(m.max_channel_diff, 0);
    EXPECT_EQ(m.rmse, 0);
    EXPECT_TRUE(std::isinf(m.psnr));
    EXPECT_EQ(m.ssim, 1);
    EXPECT_EQ(m.fraction_over, 0);
    EXPECT_TRUE(tolerance_failures(m, DiffTolerance{}).empty());
}

TEST(ImageDiff, OnePixelChangedGivesItsDifferenceAndOnePixelsFraction) {
    const Image a = flat(100, 50, 100);
    Image b = a;
    b.pixel(10, 20)[1] = 160;  // one channel of one pixel, by 60 levels
    const DiffMetrics m = compare_images(a, b, 8);
    EXPECT_EQ(m.max_channel_diff, 60);
    EXPECT_NEAR(m.rmse, std::sqrt(60.0 * 60.0 / (100 * 50 * 3)), 1e-12);
    EXPECT_NEAR(m.psnr, 20 * std::log10(255 / m.rmse), 1e-9);
    EXPECT_EQ(m.pixels_over, 1u);
    EXPECT_DOUBLE_EQ(m.fraction_over, 1.0 / 5000);
    EXPECT_LT(m.ssim, 1.0);
    EXPECT_GT(m.ssim, 0.99);  // one pixel barely moves the mean structural similarity
    // Below the threshold, the pixel does not count.
    EXPECT_EQ(compare_images(a, b, 60).pixels_over, 0u);
}

TEST(ImageDiff, GaussianNoiseOfKnownSigmaGivesThatRmse) {
    const Image a = flat(256, 256, 128);
    const double sigma = 5;
    const DiffMetrics m = compare_images(a, noisy(a, sigma, 7), 255);
    // Rounding to whole levels adds a uniform error of variance 1/12.
    const double expected = std::sqrt(sigma * sigma + 1.0 / 12);
    EXPECT_NEAR(m.rmse, expected, 0.03);  // 196,608 samples: the estimate is within ~0.3%
    EXPECT_NEAR(m.psnr, 20 * std::log10(255 / expected), 0.06);
    // SSIM of a flat image against flat + noise: C2 / (var_Y + C2) with the luma's noise variance
    // var_Y = sigma^2 (0.299^2 + 0.587^2 + 0.114^2) (+ rounding), means equal.
    const double var_y = (sigma * sigma + 1.0 / 12) * (0.299 * 0.299 + 0.587 * 0.587 + 0.114 * 0.114);
    const double c2 = std::pow(0.03 * 255, 2);
    // The Gaussian window's weighted sample variance is var_Y (1 - sum w^2), sum w^2 ~ 1 / (4 pi 1.5^2).
    const double windowed = var_y * (1 - 1 / (4 * M_PI * 1.5 * 1.5));
    EXPECT_NEAR(m.ssim, c2 / (windowed + c2), 0.01);
}

TEST(ImageDiff, OnePixelShiftOfStripesChangesTheEdgeColumns) {
    const Image a = stripes(64, 32, 0), b = stripes(64, 32, 1);
    const DiffMetrics m = compare_images(a, b, 8);
    // Stripes of period 8 in 64 columns have 15 edges inside the image; a shift by one flips the
    // column right of each edge from black to white or back.
    EXPECT_EQ(m.max_channel_diff, 255);
    EXPECT_EQ(m.pixels_over, 15u * 32);
    EXPECT_NEAR(m.fraction_over, 15.0 / 64, 1e-12);
    EXPECT_NEAR(m.rmse, 255 * std::sqrt(15.0 / 64), 1e-9);
    EXPECT_LT(m.ssim, 0.9);
}

TEST(ImageDiff, EveryToleranceBoundIsChecked) {
    DiffMetrics m;
    m.max_channel_diff = 10;
    m.rmse = 2;
    m.psnr = 40;
    m.ssim = 0.95;
    m.fraction_over = 0.01;
    DiffTolerance loose{255, 255, 0, -1, 8, 1};
    EXPECT_TRUE(tolerance_failures(m, loose).empty());
    auto fails = [&](auto tighten) {
        DiffTolerance t = loose;
        tighten(t);
        return tolerance_failures(m, t).size();
    };
    EXPECT_EQ(fails([](DiffTolerance& t) { t.max_channel_diff = 9; }), 1u);
    EXPECT_EQ(fails([](DiffTolerance& t) { t.max_rmse = 1.9; }), 1u);
    EXPECT_EQ(fails([](DiffTolerance& t) { t.min_psnr = 41; }), 1u);
    EXPECT_EQ(fails([](DiffTolerance& t) { t.min_ssim = 0.96; }), 1u);
    EXPECT_EQ(fails([](DiffTolerance& t) { t.max_fraction = 0.009; }), 1u);
    EXPECT_EQ(fails([](DiffTolerance& t) { t.max_channel_diff = 10; t.max_rmse = 2; t.min_ssim = 0.95; }), 0u);
}

TEST(ImageDiff, HeatMapMarksOnlyTheChangedPixel) {
    const Image a = flat(8, 8, 200);
    Image b = a;
    b.pixel(3, 4)[0] = 0;
    const Image h = heat_map(a, b);
    EXPECT_EQ(h.pixel(3, 4)[0], 255);  // a 200-level difference is white-hot
    EXPECT_EQ(h.pixel(3, 4)[2], 255);
    EXPECT_EQ(h.pixel(0, 0)[0], h.pixel(0, 0)[2]);  // unchanged pixels stay grey
    EXPECT_LT(h.pixel(0, 0)[0], 80);
}

}  // namespace
}  // namespace shatter
