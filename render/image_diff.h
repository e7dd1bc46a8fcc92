// Metrics between two images of the same size, as `shatter diff` and the golden tests use them.
// All on 8-bit sRGB values (what a viewer sees), channel differences in levels (0 to 255):
//   max_channel_diff  the largest |a - b| over every channel of every pixel;
//   rmse              root mean square of |a - b| over every channel of every pixel;
//   psnr              20 log10(255 / rmse) in dB (infinite for identical images);
//   ssim              mean structural similarity (Wang, Bovik, Sheikh, Simoncelli 2004, "Image
//                     quality assessment: from error visibility to structural similarity") of
//                     the luma Y' = 0.299 R + 0.587 G + 0.114 B, 11x11 Gaussian window of sigma
//                     1.5, C1 = (0.01 * 255)^2, C2 = (0.03 * 255)^2, edges replicated;
//   fraction_over     the fraction of pixels whose largest channel difference exceeds the
//                     threshold (levels).
// A pair is within tolerance when every bound of DiffTolerance holds.
#pragma once

#include <string>
#include <vector>

#include "render/image.h"

namespace shatter {

struct DiffTolerance {
    double max_channel_diff = 255;  // (unit: levels) 255: not checked
    double max_rmse = 1.0;          // (unit: levels)
    double min_psnr = 0;            // (unit: dB) 0: not checked
    double min_ssim = 0.99;         // (unit: 1)
    double threshold = 8;           // a pixel differs when a channel differs by more than this (unit: levels)
    double max_fraction = 0.001;    // most pixels that may differ (unit: fraction of the pixels)
};

struct DiffMetrics {
    int max_channel_diff = 0;
    double rmse = 0;
    double psnr = 0;  // +inf when identical
    double ssim = 1;
    double fraction_over = 0;
    size_t pixels_over = 0;
};

// `a` and `b` must have the same size (the caller checks and reports a mismatch).
DiffMetrics compare_images(const Image& a, const Image& b, double threshold);

// The bounds `m` breaks, as text ("rmse 3.2 > 1"); empty when within tolerance.
std::vector<std::string> tolerance_failures(const DiffMetrics& m, const DiffTolerance& t);

// A heat map of the difference: the expected image in dim grey, and each pixel's largest
// channel difference over it from dark red (1 level) through red and yellow to white (>= 64).
Image heat_map(const Image& expected, const Image& actual);

}  // namespace shatter
